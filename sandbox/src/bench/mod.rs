//! `sandbox bench`: times the parallax material's phases (depth prepass + opaque) with GPU
//! timestamps over standard scenes (every method × shadow mode, a sample-count sweep, an
//! LOD-threshold sweep, a far-field scene, the frame phase by phase, stacked planes for
//! overdraw) and the CPU side of 10,000 parallax entities; prints a table and writes JSON, CSV
//! and a PNG chart. See sandbox/BENCHMARKS.md.

mod chart;
mod cpu_side;
mod report;
mod sample_count;
mod scene;
mod scene_shadows;
mod stats;
mod texel_rate;
mod versus_mesh;

use std::path::PathBuf;
use std::time::{Duration, SystemTime, UNIX_EPOCH};

use anyhow::{Context, Result};
use clap::Args;
use pom::material::Choice;
use pom::preview::PreviewView;
use pom::{ParallaxMethod, ParallaxOcclusionMaterial, RenderPath, ShadowMode};

use crate::cli_types::{PathArgs, parse_size};
use crate::material_args::MaterialArgs;
use crate::preview_textures::PreviewTextures;
use crate::render_command::{TextureArgs, ViewArgs};
use report::{AdapterReport, BenchReport, CaseResult, Ratio};
use sample_count::{ProbeResult, SampleRate};
use scene::{BenchScene, SceneOptions, Warmup};

/// Exit message when the adapter cannot time passes (exit status 0).
pub const NO_TIMESTAMPS: &str = "GPU timestamps are not available";

/// Least warm-up time per case outside `--quick` (see [`Warmup::least`]).
const FULL_MIN_WARMUP: Duration = Duration::from_millis(300);
const FULL_SIZES: [(u32, u32); 2] = [(1920, 1080), (3840, 2160)];
const QUICK_SIZES: [(u32, u32); 2] = [(64, 36), (96, 54)];
/// Samples per pixel of the fragment-stage texel-rate probe.
const PROBE_TAPS: u32 = 64;
const SAMPLE_SWEEP: [u32; 5] = [8, 16, 32, 64, 128];
const LOD_SWEEP: [f32; 6] = [0.0, 1.0, 2.0, 4.0, 6.0, 8.0];
const METHODS: [ParallaxMethod; 5] = [
    ParallaxMethod::NormalMapping,
    ParallaxMethod::ParallaxOffset,
    ParallaxMethod::Steep,
    ParallaxMethod::Occlusion,
    ParallaxMethod::Relief,
];
const SHADOWS: [ShadowMode; 3] = [ShadowMode::Off, ShadowMode::Hard, ShadowMode::Soft];
// Far field: so many repeats that every pixel covers 2^(lod_threshold + 3) texels or more.
const FAR_FIELD_MIP_MARGIN: f32 = 3.0;

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
    /// Extract, prepare and render times of many entities on the CPU.
    CpuSide,
    /// The base material's frame phase by phase: prepass, opaque, post-processing.
    Phases,
    /// Four planes stacked along the view (drawn back to front) against one.
    Overdraw,
    /// The street corner with and without scene shadows, per light type.
    SceneShadows,
    /// Tatarchuk's listing 2 transliterated to WGSL on the same plane, beside our POM.
    SeedPort,
}

/// Planes stacked by the overdraw measurement, and how far apart (in plane sizes: several
/// times any relief's depth, so each plane hides the next).
const OVERDRAW_PLANES: usize = 4;
const OVERDRAW_SPACING: f32 = 0.1 * pom::preview::PLANE_SIZE;

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
    pub path: PathArgs,
}

struct Runner<'a> {
    warmup: Warmup,
    frames: usize,
    path: RenderPath,
    textures: &'a PreviewTextures,
    base: ParallaxOcclusionMaterial,
    view: PreviewView,
    cases: Vec<CaseResult>,
    ratios: Vec<Ratio>,
}

impl Runner<'_> {
    fn case(
        &mut self,
        scene: &mut BenchScene,
        group: &'static str,
        size: (u32, u32),
        tiling: f32,
        material: ParallaxOcclusionMaterial,
    ) -> Result<f64> {
        self.case_variant(scene, group, (size, tiling), material, String::new())
    }

    /// Puts `material`'s settings (keeping the textures) on every parallax entity of `scene`.
    fn configure(scene: &mut BenchScene, material: &ParallaxOcclusionMaterial) {
        let settings = material.clone();
        scene.configure(move |m| {
            *m = ParallaxOcclusionMaterial {
                base_color_texture: m.base_color_texture.clone(),
                normal_map: m.normal_map.clone(),
                height_map: m.height_map.clone(),
                ..settings.clone()
            }
        });
    }

    fn record(
        &mut self,
        group: &'static str,
        (size, tiling): ((u32, u32), f32),
        material: &ParallaxOcclusionMaterial,
        (pass, variant): (&'static str, String),
        times: &[f64],
    ) -> Result<f64> {
        let spread = stats::Spread::of(times).context("no valid timings")?;
        self.cases.push(CaseResult {
            group,
            method: material.method.name().to_owned(),
            shadows: material.shadows.name().to_owned(),
            width: size.0,
            height: size.1,
            min_samples: material.min_samples,
            max_samples: material.max_samples,
            lod_threshold: material.lod_threshold,
            tiling,
            pass,
            variant,
            spread,
        });
        Ok(spread.median_ms)
    }

    fn case_variant(
        &mut self,
        scene: &mut BenchScene,
        group: &'static str,
        place: ((u32, u32), f32),
        material: ParallaxOcclusionMaterial,
        variant: String,
    ) -> Result<f64> {
        Self::configure(scene, &material);
        let (pass, times) = scene.time(self.warmup, self.frames)?;
        self.record(group, place, &material, (pass, variant), &times)
    }

    /// The base material's frame phase by phase.
    fn phases(&mut self, scene: &mut BenchScene, size: (u32, u32)) -> Result<()> {
        let material = self.base.clone();
        Self::configure(scene, &material);
        let phases = ["prepass", "opaque", "post"];
        let times = scene.time_phases(self.warmup, self.frames, &phases)?;
        for (phase, times) in &times {
            let place = (size, self.view.tiling);
            self.record("phases", place, &material, (phase, String::new()), times)?;
        }
        Ok(())
    }

    /// One plane against [`OVERDRAW_PLANES`] stacked along the view, POM with and without
    /// depth offset: drawn back to front (each plane its own mesh) and as copies of one mesh
    /// (which the renderer draws nearest first).
    fn overdraw(&mut self, size: (u32, u32)) -> Result<()> {
        for depth_offset in [false, true] {
            let material = ParallaxOcclusionMaterial {
                method: ParallaxMethod::Occlusion,
                depth_offset,
                ..self.base.clone()
            };
            let offset = if depth_offset { ", depth offset" } else { "" };
            let place = (size, self.view.tiling);
            let view = self.view;
            let mut one = self.scene(size, &view)?;
            let variant = format!("1 plane{offset}");
            let one_ms =
                self.case_variant(&mut one, "overdraw", place, material.clone(), variant)?;
            drop(one);
            for (own_meshes, order) in [(true, "back to front"), (false, "one mesh")] {
                let mut stacked = self.scene(size, &view)?;
                stacked.stack_planes(OVERDRAW_PLANES, OVERDRAW_SPACING, own_meshes)?;
                let variant = format!("{OVERDRAW_PLANES} planes, {order}{offset}");
                let stacked_ms =
                    self.case_variant(&mut stacked, "overdraw", place, material.clone(), variant)?;
                self.ratios.push(Ratio {
                    what: format!("overdraw: {OVERDRAW_PLANES} planes {order} / 1{offset}"),
                    width: size.0,
                    height: size.1,
                    ratio: stacked_ms / one_ms,
                });
            }
        }
        Ok(())
    }

    /// The street corner per light type with scene shadows and without: each phase, and the
    /// frame (their sum).
    fn scene_shadows(&mut self, size: (u32, u32)) -> Result<()> {
        let place = (size, 1.0);
        let material = self.base.clone();
        let mut frame_without = None;
        for case in scene_shadows::ShadowCase::ALL {
            let times = scene_shadows::time(size, case, self.path, self.warmup, self.frames)?;
            let frames: Vec<f64> = (0..self.frames)
                .map(|frame| times.iter().map(|(_, phase)| phase[frame]).sum())
                .collect();
            for (phase, times) in &times {
                let variant = case.name().to_owned();
                self.record("scene_shadows", place, &material, (phase, variant), times)?;
            }
            let variant = case.name().to_owned();
            let frame_ms = self.record(
                "scene_shadows",
                place,
                &material,
                ("frame", variant),
                &frames,
            )?;
            match frame_without {
                None => frame_without = Some(frame_ms),
                Some(without) => self.ratios.push(Ratio {
                    what: format!("street corner frame: {} / no shadows", case.name()),
                    width: size.0,
                    height: size.1,
                    ratio: frame_ms / without,
                }),
            }
        }
        Ok(())
    }

    /// The base material and the seed's own shader (listing 2 ported) on the same plane: our
    /// POM, then the port, and their ratio; then the same far away (every pixel past the LOD
    /// threshold), where both only normal-map: the per-pixel base cost. Each in its own scene:
    /// the port has no deferred shader, and a registered material without one sends every
    /// frame forward, so ours runs on the path asked for and the port forward.
    fn seed_port(&mut self, size: (u32, u32)) -> Result<()> {
        let texture_width = self.textures.height.size().0;
        let far_tiling = far_field_tiling(size, texture_width, self.base.lod_threshold);
        for (tiling, far) in [(self.view.tiling, false), (far_tiling, true)] {
            let place = (size, tiling);
            let material = self.base.clone();
            let view = PreviewView {
                tiling,
                ..self.view
            };
            let mut scene = self.scene(size, &view)?;
            let (ours, port) = if far {
                ("ours, far field", "seed port, far field")
            } else {
                ("ours", "seed port")
            };
            let ours_ms = self.case_variant(
                &mut scene,
                "seed_port",
                place,
                material.clone(),
                ours.into(),
            )?;
            drop(scene);
            let mut scene = BenchScene::new(
                SceneOptions {
                    seed_port: true,
                    ..SceneOptions::timed_plane(size, self.path)
                },
                self.textures,
                material.clone(),
                &view,
            )?;
            scene.use_seed_port()?;
            let (pass, times) = scene.time(self.warmup, self.frames)?;
            let port_ms =
                self.record("seed_port", place, &material, (pass, port.into()), &times)?;
            self.ratios.push(Ratio {
                what: format!("{ours} / the seed's listing 2"),
                width: size.0,
                height: size.1,
                ratio: ours_ms / port_ms,
            });
        }
        Ok(())
    }

    fn scene(&self, size: (u32, u32), view: &PreviewView) -> Result<BenchScene> {
        BenchScene::new(
            SceneOptions::timed_plane(size, self.path),
            self.textures,
            self.base.clone(),
            view,
        )
    }

    /// The base material with `method` and `shadows`.
    fn with_modes(&self, method: ParallaxMethod, shadows: ShadowMode) -> ParallaxOcclusionMaterial {
        ParallaxOcclusionMaterial {
            method,
            shadows,
            ..self.base.clone()
        }
    }

    /// Every method × shadow mode, and the cost of POM's shadows.
    fn methods(&mut self, scene: &mut BenchScene, size: (u32, u32)) -> Result<()> {
        let mut pom = [0.0; 3];
        for method in METHODS {
            for (index, shadows) in SHADOWS.into_iter().enumerate() {
                let material = self.with_modes(method, shadows);
                let ms = self.case(scene, "methods", size, self.view.tiling, material)?;
                if method == ParallaxMethod::Occlusion {
                    pom[index] = ms;
                }
            }
        }
        for (shadows, on) in [("hard", pom[1]), ("soft", pom[2])] {
            self.ratios.push(Ratio {
                what: format!("POM {shadows} shadows / no shadows"),
                width: size.0,
                height: size.1,
                ratio: on / pom[0],
            });
        }
        Ok(())
    }

    /// POM with `max_samples` from 8 to 128.
    fn sample_sweep(&mut self, scene: &mut BenchScene, size: (u32, u32)) -> Result<()> {
        for max_samples in SAMPLE_SWEEP {
            let material = ParallaxOcclusionMaterial {
                method: ParallaxMethod::Occlusion,
                min_samples: self.base.min_samples.min(max_samples),
                max_samples,
                ..self.base.clone()
            };
            self.case(scene, "samples", size, self.view.tiling, material)?;
        }
        Ok(())
    }

    /// POM with every LOD threshold of [`LOD_SWEEP`].
    fn lod_sweep(&mut self, scene: &mut BenchScene, size: (u32, u32)) -> Result<()> {
        for lod_threshold in LOD_SWEEP {
            let material = ParallaxOcclusionMaterial {
                method: ParallaxMethod::Occlusion,
                lod_threshold,
                ..self.base.clone()
            };
            self.case(scene, "lod_sweep", size, self.view.tiling, material)?;
        }
        Ok(())
    }

    /// POM's height samples per second (shadows off) against the fragment-path probe and the
    /// chip's limit `chip` (G texels/s).
    fn sample_rate(
        &mut self,
        scene: &mut BenchScene,
        size: (u32, u32),
        chip: Option<f64>,
    ) -> Result<SampleRate> {
        let pom = self.with_modes(ParallaxMethod::Occlusion, ShadowMode::Off);
        let pom_ms = self.case(scene, "texel_rate", size, self.view.tiling, pom.clone())?;
        let (warmup, frames) = (self.warmup, self.frames);
        let mut probe_ms = |taps| -> Result<f64> {
            let times = scene.time_texel_rate_probe(taps, warmup, frames)?;
            let spread = stats::Spread::of(&times).context("no valid probe timings")?;
            Ok(spread.median_ms)
        };
        let probe = ProbeResult {
            taps: PROBE_TAPS,
            median_ms: probe_ms(PROBE_TAPS)?,
            one_tap_ms: probe_ms(1)?,
        };
        let count =
            sample_count::count_view_samples(size, self.textures, &pom, &self.view, self.path)?;
        Ok(SampleRate::new(size, count, pom_ms, probe, chip))
    }

    /// Normal mapping and POM where every pixel is past the LOD threshold.
    fn far_field(&mut self, size: (u32, u32)) -> Result<()> {
        let texture_width = self.textures.height.size().0;
        let far_tiling = far_field_tiling(size, texture_width, self.base.lod_threshold);
        let far_view = PreviewView {
            tiling: far_tiling,
            ..self.view
        };
        let mut far = self.scene(size, &far_view)?;
        let base_shadows = self.base.shadows;
        let normal = self.with_modes(ParallaxMethod::NormalMapping, base_shadows);
        let normal_ms = self.case(&mut far, "far_field", size, far_tiling, normal)?;
        let pom = self.with_modes(ParallaxMethod::Occlusion, base_shadows);
        let pom_ms = self.case(&mut far, "far_field", size, far_tiling, pom)?;
        self.ratios.push(Ratio {
            what: "far field POM / normal mapping".to_owned(),
            width: size.0,
            height: size.1,
            ratio: pom_ms / normal_ms,
        });
        Ok(())
    }
}

/// Runs the benchmark.
pub fn run(args: &BenchArgs) -> Result<()> {
    let base = args.material.settings();
    base.validate().context("invalid material")?;
    let depth_map = base.height_convention == pom::HeightConvention::Depth;
    let textures = PreviewTextures::load(&args.textures.files(depth_map), base.height_scale)?;
    let view = args.view.preview_view();
    let path = args.path.path;
    let sizes: Vec<(u32, u32)> = match (args.sizes.is_empty(), args.quick) {
        (false, _) => args.sizes.clone(),
        (true, true) => QUICK_SIZES.to_vec(),
        (true, false) => FULL_SIZES.to_vec(),
    };
    let (warmup, frames) = if args.quick {
        (
            Warmup {
                frames: 2,
                least: Duration::ZERO,
            },
            5,
        )
    } else {
        (
            Warmup {
                frames: args.warmup as usize,
                least: FULL_MIN_WARMUP,
            },
            args.frames as usize,
        )
    };
    let started = SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .map(|d| d.as_secs())
        .unwrap_or(0);

    let probe = BenchScene::new(
        SceneOptions {
            timestamps: !args.no_timestamps,
            ..SceneOptions::timed_plane(sizes[0], path)
        },
        &textures,
        base.clone(),
        &view,
    )?;
    let adapter: AdapterReport = probe.adapter().context("no adapter")?.into();
    if !probe.timing_supported() {
        println!(
            "{NO_TIMESTAMPS} on {} ({}): nothing to measure.",
            adapter.name, adapter.backend
        );
        return Ok(());
    }
    drop(probe);
    if adapter.software_driver {
        println!(
            "note: {} is a software driver: timings are not performance",
            adapter.name
        );
    }

    let mut runner = Runner {
        warmup,
        frames,
        path,
        textures: &textures,
        base: base.clone(),
        view,
        cases: Vec::new(),
        ratios: Vec::new(),
    };
    let wanted =
        |measurement: Measurement| args.only.is_empty() || args.only.contains(&measurement);
    let texel_rate = texel_rate::texel_rate(&adapter.name, args.texel_rate.map(f64::from));
    let mut sample_rates = Vec::new();
    for &size in &sizes {
        eprintln!("timing {}x{} ...", size.0, size.1);
        let mut scene = runner.scene(size, &view)?;
        if wanted(Measurement::Methods) {
            runner.methods(&mut scene, size)?;
        }
        if wanted(Measurement::Samples) {
            runner.sample_sweep(&mut scene, size)?;
        }
        if wanted(Measurement::LodSweep) {
            runner.lod_sweep(&mut scene, size)?;
        }
        if wanted(Measurement::TexelRate) {
            let chip = texel_rate.as_ref().map(|rate| rate.gtexels_per_s);
            sample_rates.push(runner.sample_rate(&mut scene, size, chip)?);
        }
        if wanted(Measurement::Phases) {
            runner.phases(&mut scene, size)?;
        }
        drop(scene);
        if wanted(Measurement::FarField) {
            runner.far_field(size)?;
        }
        if wanted(Measurement::Overdraw) {
            runner.overdraw(size)?;
        }
        if wanted(Measurement::SceneShadows) {
            runner.scene_shadows(size)?;
        }
        if wanted(Measurement::SeedPort) {
            runner.seed_port(size)?;
        }
    }

    let versus_mesh = if wanted(Measurement::VersusMesh) {
        eprintln!(
            "POM against displaced grids at {}x{} ...",
            sizes[0].0, sizes[0].1
        );
        Some(versus_mesh::compare(&versus_mesh::Setup {
            size: sizes[0],
            textures: &textures,
            base: &ParallaxOcclusionMaterial {
                method: ParallaxMethod::Occlusion,
                ..base.clone()
            },
            view: &view,
            path,
            quick: args.quick,
            frames: (warmup, frames),
        })?)
    } else {
        None
    };

    let cpu_side = if wanted(Measurement::CpuSide) {
        eprintln!("timing the CPU side with {} entities ...", args.entities);
        Some(cpu_side::measure(
            args.entities,
            &textures,
            path,
            warmup.frames,
            frames,
        )?)
    } else {
        None
    };
    let report = BenchReport {
        texel_rate,
        adapter,
        path: path.name(),
        unix_time: started,
        quick: args.quick,
        warmup_frames: warmup.frames,
        timed_frames: frames,
        cases: runner.cases,
        ratios: runner.ratios,
        sample_rates,
        versus_mesh,
        cpu_side,
    };
    print!("{}", report.table());
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("creating {}", args.out.display()))?;
    report.write_files(&args.out)?;
    let images = report.versus_mesh.iter().flat_map(|v| &v.images);
    for (file, image) in images {
        let path = args.out.join(file);
        image
            .save(&path)
            .with_context(|| format!("writing {}", path.display()))?;
    }
    let chart_path = args.out.join("bench.png");
    chart::write_chart(&chart_path, &report.adapter.name, &report.cases)?;
    chart::check_written(&chart_path)?;
    let versus = if report.versus_mesh.is_some() {
        " and the versus_*.png images"
    } else {
        ""
    };
    println!(
        "wrote bench.json, bench.csv, bench.png{versus} to {}",
        args.out.display()
    );
    Ok(())
}

/// Repeats across the plane so that one pixel covers 2^(lod_threshold + margin) texels: every
/// pixel is past the LOD threshold and its transition band.
fn far_field_tiling(size: (u32, u32), texture_width: u32, lod_threshold: f32) -> f32 {
    let texels_per_pixel = (lod_threshold + FAR_FIELD_MIP_MARGIN).exp2();
    texels_per_pixel * size.0.max(size.1) as f32 / texture_width.max(1) as f32
}

#[cfg(test)]
mod tests {
    use super::far_field_tiling;

    #[test]
    fn far_field_puts_every_pixel_past_the_threshold() {
        // 1920 px across, 1024 texels per repeat, threshold 4: 128 texels per pixel.
        let tiling = far_field_tiling((1920, 1080), 1024, 4.0);
        assert!((tiling * 1024.0 / 1920.0 - 128.0).abs() < 1e-3);
    }
}
