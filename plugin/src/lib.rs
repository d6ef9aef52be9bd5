//! Parallax occlusion mapping for a small Bevy-style ECS on hecs, rendered with wgpu.
//!
//! An [`App`] holds a `hecs::World`, a type-keyed [`Resources`] map and a [`Schedule`] of
//! systems in named [`Stage`]s; [`Plugin`]s add systems and resources. [`DefaultPlugins`] draws
//! every entity with a `Handle<Mesh>` and a [`Transform`] into an offscreen target that
//! [`capture`] reads back.
//!
//! ```no_run
//! use pom::*;
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! let mut app = App::new();
//! app.add_plugin(DefaultPlugins::headless(256, 256));
//! let cube = app.resources.get_mut::<Assets<Mesh>>().unwrap().add(Mesh::cube(1.0));
//! app.world.spawn((Camera::perspective(45.0), Transform::from_xyz(2.0, 2.0, 3.0).looking_at(glam::Vec3::ZERO, glam::Vec3::Y)));
//! app.world.spawn((DirectionalLight::default(), Transform::IDENTITY.looking_at(glam::Vec3::new(-1.0, -2.0, -1.0), glam::Vec3::Y)));
//! app.world.spawn((cube, LitMaterial::default(), Transform::IDENTITY));
//! app.update()?;
//! capture(&app)?.save("cube.png")?;
//! # Ok(()) }
//! ```
#![warn(missing_docs)]

// The crate's macros name `pom::…` paths; this makes them resolve inside the crate too.
extern crate self as pom;

// The Rust blocks of the README and of plugin/docs/ compile as doctests, so they stay true
// (those marked `ignore` are kept true by tests: tests/tests/custom_material.rs and
// window_examples.rs compare them with the files they show).
#[cfg(doctest)]
mod doc_tests {
    #[doc = include_str!("../../README.md")]
    struct Readme;
    #[doc = include_str!("../docs/sandbox.md")]
    struct Sandbox;
    #[doc = include_str!("../docs/renderer.md")]
    struct Renderer;
    #[doc = include_str!("../docs/authoring-materials.md")]
    struct AuthoringMaterials;
    #[doc = include_str!("../docs/custom-material.md")]
    struct CustomMaterial;
    #[doc = include_str!("../docs/scene-tests.md")]
    struct SceneTests;
    #[cfg(feature = "window")]
    #[doc = include_str!("../docs/window.md")]
    struct Window;
}

// Fixed pseudo-random inputs for unit tests that sample many cases.
#[cfg(test)]
mod test_numbers {
    /// Numbers in [0, 1) from a fixed seed (a linear congruential generator).
    pub(crate) fn seeded(mut state: u64) -> impl FnMut() -> f32 {
        move || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (state >> 40) as f32 / (1u64 << 24) as f32
        }
    }
}

mod app;
mod assets;
mod camera;
mod capture;
mod color;
mod default_plugins;
mod dynamic_height;
mod exposure;
pub mod files;
mod gltf_loader;
pub mod gpu;
mod height_field;
mod image;
#[cfg(feature = "scene-tests")]
mod image_compare;
mod light;
mod lighting;
pub mod lit;
pub mod material;
pub mod mesh;
mod name;
mod normal_map;
pub mod parallax;
pub mod parameters;
pub mod picking;
pub mod prelude;
pub mod preview;
#[cfg(feature = "scene-tests")]
pub mod reference;
pub mod render;
#[cfg(feature = "scene-tests")]
pub mod script;
#[cfg(feature = "dev-tools")]
pub mod seed_port;
pub mod shader;
#[cfg(feature = "dev-tools")]
mod shader_reload;
mod shadows;
#[cfg(feature = "dev-tools")]
mod split_view;
mod stderr_log;
#[cfg(feature = "dev-tools")]
pub mod texel_rate_probe;
mod time;
mod transform;
#[cfg(feature = "window")]
pub mod window;

pub use app::{App, AppError, BoxedError, IntoSystem, Plugin, Resources, Schedule, Stage, System};

/// The markers that tell [`IntoSystem`]'s two kinds of function apart (returning nothing, or a
/// `Result`); only code generic over systems names them. Not at the root, where `Infallible`
/// would shadow `std::convert::Infallible` for a `use pom::*`.
pub mod system_kinds {
    pub use crate::app::{Fallible, Infallible};
}
pub use assets::{AssetId, AssetRef, Assets, Handle, free_unused_assets};
pub use camera::{Camera, Projection, active_camera, active_cameras};
pub use capture::{capture, capture_f32, capture_scene};
pub use color::{Color, linear_to_srgb, srgb_to_linear};
pub use default_plugins::DefaultPlugins;
pub use dynamic_height::{
    DynamicHeightError, DynamicHeightField, SobelPass, derive_dynamic_normals,
};
pub use exposure::Exposure;
pub use gltf_loader::{
    GltfError, GltfOptions, GltfScene, LayerExtras, MAX_GLTF_VERTICES, PomExtras, load_gltf,
    load_gltf_bytes, load_gltf_with,
};
pub use gpu::{GpuContext, GpuTimings, TimingMode};
pub use height_field::{HeightConvention, HeightField, patterns};
pub use image::{
    Channel, FilterMode, IMAGE_MEMORY_BUDGET, Image, ImageError, ImageSampler, MAX_IMAGE_PIXELS,
    MAX_IMAGE_SIDE, Pixels, TextureKind, WrapMode,
};
#[cfg(feature = "scene-tests")]
pub use image_compare::{FlipComparison, FlipTolerance, flip_compare};
pub use light::{AmbientLight, DirectionalLight, MAX_LIGHT_OUTPUT, PointLight, SpotLight};
pub use lighting::LightingModel;
pub use lit::{AlphaMode, LitMaterial, LitParams, LitPatch, LitPlugin, LitPreset};
pub use material::{Material, MaterialPlugin, ShadedMaterial};
pub use mesh::{MAX_GRID_CELLS, Mesh, MeshError};
pub use name::Name;
pub use normal_map::normal_map_from_heights;
pub use parallax::{
    CurvedSilhouetteWarnings, DebugView, HeightSource, HeightUnits, LayerWeights, ParallaxLayer,
    ParallaxLayers, ParallaxMethod, ParallaxOcclusionMaterial, PomMaterialError, PomPatch,
    PomPlugin, PomPreset, PresetError, ShadowMode, Silhouette, TRIPLANAR_SCALE_LIMITS,
    TextureMapping, TriplanarMeshWarnings,
};
pub use picking::{PickHit, Ray, pick_at, pick_entity};
pub use render::environment::{EnvironmentChoice, EnvironmentError, EquirectImage, Sky};
pub use render::{
    AntiAliasing, FastApproximateAntiAliasing, TemporalAntiAliasing, TemporalHistory,
    set_camera_anti_aliasing, set_camera_fxaa,
};
pub use render::{EnvironmentLight, EnvironmentSettings, EnvironmentSource};
pub use render::{
    PostProcessPath, RenderError, RenderPath, RenderPhase, RenderPlugin, TargetFormat,
};
pub use render::{Tonemapping, set_camera_display_mapping};
#[cfg(feature = "scene-tests")]
pub use script::{Report, RunOptions, ScriptError, run_script, run_script_with};
#[cfg(feature = "dev-tools")]
pub use shader_reload::{
    ShaderHotReload, ShaderReloadError, ShaderReloadStatus, compose_checked, reload_changed_shaders,
};
pub use shadows::{DIRECTIONAL_CASCADES, LightShadows, NotShadowCaster, NotShadowReceiver};
#[cfg(feature = "dev-tools")]
pub use split_view::{SplitView, SplitViewError, render_split_view};
pub use stderr_log::{DEFAULT_LOG_LEVEL, log_to_stderr};
pub use time::{Time, TimeStep};
pub use transform::{
    GlobalTransform, Parent, Transform, TransformPlugin, despawn_recursive, propagate_transforms,
};

/// Every entry shader the crate compiles (with the features it was built with), for
/// validation tests.
pub const SHADERS: &[render::shaders::ComposedShader] = &[
    lit::LIT_SHADER,
    lit::LIT_DEFERRED_SHADER,
    parallax::PARALLAX_SHADER,
    parallax::PARALLAX_DEFERRED_SHADER,
    render::shaders::SOBEL,
    parallax::MAX_PYRAMID_SHADER,
    render::DEFERRED_BACKGROUND,
    render::environment::PREFILTER,
    render::environment::BACKGROUND,
    render::VISIBILITY_CLEAR_SHADER,
    render::SETTLED_DEPTH_SHADER,
    render::POLYGON_PASS_SHADER,
    gpu::SCATTER_SHADER,
    material::DEFERRED_CLASSIFY_SHADER,
    render::POST_SHADERS[0],
    render::POST_SHADERS[1],
    render::POST_SHADERS[2],
    render::TAA_SHADER,
    render::FXAA_SHADERS[0],
    render::FXAA_SHADERS[1],
    render::FXAA_SHADERS[2],
    render::FXAA_SHADERS[3],
    #[cfg(feature = "window")]
    window::PRESENT_SHADER,
    #[cfg(feature = "dev-tools")]
    texel_rate_probe::TEXEL_RATE_PROBE,
    #[cfg(feature = "dev-tools")]
    seed_port::SEED_PORT_SHADER,
    #[cfg(feature = "dev-tools")]
    seed_port::SEED_PORT_COMPUTE_SHADER,
];

/// Re-exported so users name the same versions the plugin was built with.
pub use {bytemuck, glam, hecs, wgpu};

/// Re-exported for the code `material_parameters!` and `choice_enum!` generate.
#[doc(hidden)]
pub use serde;
