//! The GPU layer under the renderer: the device ([`GpuContext`]), bind group layout helpers,
//! pipelines compiled in the background, timestamp timing, texture readback, the pipeline of a
//! full-screen pass, and the GPU copies of meshes and images with the textures derived from
//! them. It knows nothing of frames, phases, cameras or materials: `render` builds the frame on
//! it.

mod assets;
mod context;
mod derived_textures;
mod fragment_counter;
mod full_screen_pipeline;
pub(crate) mod layout;
pub(crate) mod object_buffer;
mod pipeline_compilation;
mod readback;
mod scatter_upload;
mod texture_bind_groups;
mod timing;
mod vertex;

pub(crate) use assets::GpuAssets;
pub use assets::{DefaultTexture, DefaultTextures, GpuMesh, TextureFacts, UploadStats};
pub use context::{DEFERRED_FEATURES, GpuContext, GpuError, MAX_KEPT_ERRORS};
pub use derived_textures::{
    ComputeDispatch, ComputeDispatches, DERIVED_TEXTURES_PASS, DerivedStorage, DerivedTexture,
    DerivedTextureBuilder, DerivedTextures, MAX_DERIVED_TEXTURES, TextureDerivation,
    TextureDeriver,
};
pub use fragment_counter::FragmentInvocationCounter;
#[cfg(test)]
pub(crate) use full_screen_pipeline::FULL_SCREEN_GROUP;
pub(crate) use full_screen_pipeline::{BindGroupCache, FullScreenPipeline};
pub use layout::{ShaderEntry, clearing_attachment};
pub use object_buffer::ObjectBuffer;
pub use pipeline_compilation::{PipelineCompilation, wait_for_pipelines};
pub use readback::{CaptureError, read_rgba8, read_rgba32f, read_texture, read_texture_level};
pub use scatter_upload::SCATTER_SHADER;
pub(crate) use scatter_upload::ScatterQueue;
pub(crate) use texture_bind_groups::{BoundTextures, TextureBindGroups};
pub use texture_bind_groups::{MAX_MATERIAL_TEXTURES, MaterialTextures};
pub use timing::{
    GpuTimer, GpuTimings, MAX_TIMED_PASSES, PassTimestamps, TimingMode, pass_milliseconds,
    resolve_gpu_timings, set_gpu_timing, time_pass,
};
pub use vertex::Vertex;
