//! The renderer: GPU context, offscreen target, extract / prepare / render systems.
//! A frame runs the [`RenderPhase`]s in their documented order (see `phases.rs`).
//!
//! Where things are: [`RenderPlugin`] (plugin.rs) adds the renderer and makes its GPU state,
//! the [`Renderer`] (renderer.rs); each frame, `extract.rs` copies what the world says,
//! [`prepare_frame`] and [`render_frame`] (frame.rs) upload it and run the phases, one function
//! each (frame_passes.rs); `crate::capture` reads images back, `present.rs` shows them in a window.

pub mod anti_aliasing;
mod display_referred;
pub mod environment;
mod environment_maps;
mod error;
mod extract;
mod frame;
pub mod frame_group;
mod frame_nodes;
mod frame_passes;
mod frame_uniform;
mod full_screen_pass;
pub(crate) mod gpu_types;
mod light_buffers;
pub mod lights;
pub(crate) mod phases;
mod plugin;
mod post_chain;
mod render_path;
mod renderer;
pub mod shaders;
mod shadow_maps;
pub mod shadows;
mod sorted_draws;
mod standard_features;
mod target;
pub mod tonemapping;
mod visibility;

pub use anti_aliasing::{
    AntiAliasing, AntiAliasingFrame, AntiAliasingPlugin, FXAA_SHADERS, FastApproximateAntiAliasing,
    HISTORY_FORMAT, OBJECT_MOTION_PASS, ObjectMotion, POST_FILTER_MIP_BIAS, POST_FILTER_PASS,
    TAA_PASS, TAA_SHADER, TaaUniform, TemporalAntiAliasing, TemporalFrame, TemporalHistory,
    TemporalView, jitter_offset, set_camera_anti_aliasing, set_camera_fxaa,
};
pub(crate) use display_referred::display_referred_alpha;
pub use display_referred::display_referred_wgsl;
pub use environment::{
    EnvironmentLight, EnvironmentPlugin, EnvironmentSettings, EnvironmentSource,
};
pub use environment_maps::{
    ENVIRONMENT_FORMAT, EnvironmentMaps, EnvironmentTextures, IRRADIANCE_BYTES,
};
pub use error::RenderError;
pub(crate) use extract::{ExtractedFrame, extract_frame};
pub use frame::{prepare_frame, render_frame};
pub use frame_nodes::{FrameNode, FrameNodes, FrameView, NodeOrderError, NodePlace};
pub(crate) use frame_passes::clear_value;
pub(crate) use frame_uniform::FrameUniformBuffer;
pub use full_screen_pass::{EFFECT_FILES, FullScreenPass};
pub use gpu_types::MeshTransform;
pub(crate) use gpu_types::{FrameUniform, ShadowViewGpu};
pub use light_buffers::LightBuffers;
pub use lights::LightsPlugin;
pub use phases::{
    DrawPhase, HasDraws, MOTION_ID_FORMAT, PhaseDraw, PhaseWork, RenderPhase, RenderPhases,
    ResolveDispatch, ShadowDraw, SortedDraw,
};
pub use plugin::{PostProcessPath, RenderPlugin};
pub use post_chain::{
    FullScreenStage, HdrInput, PostChainError, PostEffect, PostImage, PostIo, PostStage,
};
pub use render_path::{DeferredUnavailable, RenderPath, UnknownRenderPath};
pub use renderer::Renderer;
pub(crate) use renderer::{BoundResources, PhaseBindings, phase_bindings};
pub use shadow_maps::SHADOW_MAP_FORMAT;
pub(crate) use shadow_maps::ShadowMaps;
pub use shadow_maps::{MAX_SHADOW_VIEWS, ShadowViewPlan};
pub use shadows::ShadowsPlugin;
pub(crate) use sorted_draws::SortedDraws;
pub use standard_features::{RenderFeature, RenderFeatures};
pub(crate) use target::plain_texture;
pub use target::{DEPTH_FORMAT, RenderTarget, TargetFormat, fit_render_target};
pub(crate) use tonemapping::POST_SHADERS;
pub use tonemapping::{
    CameraTonemapping, PostSettings, Tonemapping, TonemappingPlugin, set_camera_display_mapping,
};
pub use visibility::VISIBILITY_BYTES_PER_PIXEL;
pub use visibility::{
    DEFERRED_BACKGROUND, POLYGON_PASS_SHADER, SETTLED_DEPTH_SHADER, SettledDepth,
    VISIBILITY_CLEAR_SHADER,
};
pub(crate) use visibility::{
    DeferredBackground, MAX_LISTED_TRIANGLES, MAX_POLYGON_TRIANGLES, MIN_POLYGON_PIXELS,
    VisibilityBuffer, VisibilityIds, VisiblePolygon, VisiblePolygons,
};
