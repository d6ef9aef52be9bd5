//! The options of `sandbox bench` and the measurements `--only` picks.

use std::path::PathBuf;

use clap::Args;

use crate::cli_types::{BenchPathArgs, parse_size};
use crate::material_args::MaterialArgs;
use crate::render_command::{TextureArgs, ViewArgs};

/// One measurement of the bench, for `--only`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Measurement {
    /// Every method × shadow mode.
    Methods,
    /// POM's `max_samples` sweep.
    Samples,
    /// POM's `lod_threshold` sweep.
    LodSweep,
    /// Normal mapping and POM where every pixel is past the LOD threshold.
    FarField,
    /// POM's height samples per second against the texel-rate limits.
    TexelRate,
    /// POM against displaced grids at equal FLIP error.
    VersusMesh,
    /// Extract, prepare and render times of many entities on the CPU, with a material each or
    /// one shared.
    CpuSide,
    /// The base material's frame phase by phase: prepass, opaque, post-processing.
    Phases,
    /// Four planes stacked along the view (drawn back to front) against one.
    Overdraw,
    /// The street corner with and without scene shadows, per light type.
    SceneShadows,
    /// The street corner under the sky against without it, the relief's occlusion of the
    /// environment on the cobblestones against without it, and a 2K `.hdr`'s prefiltering.
    Environment,
    /// The street corner at night lit by 1, 256 and 1,024 point lights: the frame phase by
    /// phase, and the CPU's culling and upload of the lights.
    Lights,
    /// Each silhouette mode against `off` on the preview cube and sphere.
    Silhouette,
    /// TAA and the post filter: each pass's time, and the jittered march at 16 samples
    /// under TAA against 50 samples.
    Antialiasing,
    /// The bench material against its height map as one, four alike and four differently
    /// tiled layers of a layered material.
    Layers,
    /// Triplanar mapping against texture coordinates on the preview sphere.
    Triplanar,
    /// Tatarchuk's listing 2 transliterated to WGSL on the same plane, beside our POM.
    SeedPort,
    /// Steep, POM and relief at 8–64 samples and MaxMip: error, fetches per pixel and time.
    MethodTable,
    /// MaxMip's pyramid rebuilt every frame (a dynamic height field): the build's GPU time.
    PyramidBuild,
    /// The wall time of the frame that first uses MaxMip with hard shadows (its pipelines are
    /// compiled then) against the frames around it.
    FirstUse,
}

/// Options of `sandbox bench`.
#[derive(Debug, Args)]
pub struct BenchArgs {
    /// Tiny images and few frames: checks the harness, measures nothing useful.
    #[arg(long)]
    pub quick: bool,
    /// Folder for bench.json, bench.csv and bench.png (created).
    #[arg(long, value_name = "DIR", default_value = "bench-results")]
    pub out: PathBuf,
    /// Image size WIDTHxHEIGHT to time, repeatable [default: 1920x1080 and 3840x2160].
    #[arg(long = "size", value_name = "WxH", value_parser = parse_size)]
    pub sizes: Vec<(u32, u32)>,
    /// Timed frames per case, at least 20 (--quick uses 5).
    #[arg(long, value_name = "N", default_value_t = 30, value_parser = clap::value_parser!(u32).range(20..=10_000))]
    pub frames: u32,
    /// Untimed frames before each case (rendering for at least 0.3 s without --quick).
    #[arg(long, value_name = "N", default_value_t = 5)]
    pub warmup: u32,
    /// Bilinear texel rate of the GPU in G texels/s, for an adapter not in the built-in table.
    #[arg(long, value_name = "GTEXELS", value_parser = crate::cli_types::parse_positive)]
    pub texel_rate: Option<f32>,
    /// Entities in the CPU-side measurement.
    #[arg(long, value_name = "N", default_value_t = 10_000)]
    pub entities: usize,
    /// Make only this measurement, repeatable [default: all of them].
    #[arg(long = "only", value_enum, value_name = "MEASUREMENT")]
    pub only: Vec<Measurement>,
    /// Behave as on an adapter without timestamp queries (tests the message and exit path).
    #[arg(long)]
    pub no_timestamps: bool,
    #[command(flatten)]
    pub textures: TextureArgs,
    #[command(flatten)]
    pub material: MaterialArgs,
    #[command(flatten)]
    pub view: ViewArgs,
    #[command(flatten)]
    pub path: BenchPathArgs,
}
