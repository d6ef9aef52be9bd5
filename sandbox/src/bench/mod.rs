//! `sandbox bench`: times the parallax material's phases (depth prepass + opaque) with GPU
//! timestamps over standard scenes (every method × shadow mode, a sample-count sweep, an
//! LOD-threshold sweep, a far-field scene, the frame phase by phase, stacked planes for
//! overdraw) and the CPU side of 10,000 parallax entities, once per render path asked for
//! (`--path`, repeatable); prints a table and writes JSON, CSV and a PNG chart. See
//! sandbox/BENCHMARKS.md.

mod antialiasing;
mod args;
mod chart;
mod cpu_side;
mod environment;
mod first_use;
mod layers_and_triplanar;
mod lights;
mod method_table;
mod pyramid_build;
mod report;
mod sample_count;
mod scene;
mod scene_shadows;
mod seed_port;
mod stats;
mod texel_rate;
mod versus_mesh;

use std::time::{Duration, SystemTime, UNIX_EPOCH};

use anyhow::{Context, Result};
use pom::material::Choice;
use pom::preview::{PreviewShape, PreviewView};
use pom::{ParallaxMethod, ParallaxOcclusionMaterial, RenderPath, ShadowMode, Silhouette};

use crate::preview_textures::PreviewTextures;
use report::{AdapterReport, BenchReport, CaseResult, Ratio};
use sample_count::{ProbeResult, SampleRate};
use scene::{BenchScene, SceneOptions, Warmup};

pub use args::{BenchArgs, Measurement};

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
const METHODS: [ParallaxMethod; 6] = [
    ParallaxMethod::NormalMapping,
    ParallaxMethod::ParallaxOffset,
    ParallaxMethod::Steep,
    ParallaxMethod::Occlusion,
    ParallaxMethod::Relief,
    ParallaxMethod::MaxMip,
];
const SHADOWS: [ShadowMode; 3] = [ShadowMode::Off, ShadowMode::Hard, ShadowMode::Soft];
// Far field: so many repeats that every pixel covers 2^(lod_threshold + 3) texels or more.
const FAR_FIELD_MIP_MARGIN: f32 = 3.0;

/// Planes stacked by the overdraw measurement, and how far apart (in plane sizes: several
/// times any relief's depth, so each plane hides the next).
const OVERDRAW_PLANES: usize = 4;
const OVERDRAW_SPACING: f32 = 0.1 * pom::preview::PLANE_SIZE;

/// A case's median milliseconds, and the path its frames ran.
#[derive(Clone, Copy, Debug)]
struct Median {
    ms: f64,
    path: &'static str,
}

/// Makes the measurements on one path at a time ([`Runner::path`]), collecting what every
/// path measured.
struct Runner<'a> {
    warmup: Warmup,
    frames: usize,
    /// The path asked for in the measurements now running.
    path: RenderPath,
    textures: &'a PreviewTextures,
    base: ParallaxOcclusionMaterial,
    view: PreviewView,
    cases: Vec<CaseResult>,
    ratios: Vec<Ratio>,
    sample_rates: Vec<SampleRate>,
    versus_mesh: Vec<versus_mesh::VersusMesh>,
    cpu_side: Vec<cpu_side::CpuSide>,
    method_rows: Vec<method_table::MethodRow>,
    /// The method table's (mean, p99) errors per row, computed once for the run.
    method_errors: Vec<(f32, f32)>,
    /// The bench's height map repeated to the pyramid build's large size, made once for the run.
    large_height_map: Option<pom::Image>,
}

impl Runner<'_> {
    /// Every measurement `args` asks for, at every size of `sizes`, on [`Runner::path`].
    fn measure(
        &mut self,
        args: &BenchArgs,
        sizes: &[(u32, u32)],
        texel_rate: Option<f64>,
    ) -> Result<()> {
        let wanted =
            |measurement: Measurement| args.only.is_empty() || args.only.contains(&measurement);
        let asked = self.path;
        let on_path = if args.path.paths().len() > 1 {
            format!(", path {asked}")
        } else {
            String::new()
        };
        for &size in sizes {
            eprintln!("timing {}x{}{on_path} ...", size.0, size.1);
            let view = self.view;
            let mut scene = self.scene(size, &view)?;
            if wanted(Measurement::Methods) {
                self.methods(&mut scene, size)?;
            }
            if wanted(Measurement::Samples) {
                self.sample_sweep(&mut scene, size)?;
            }
            if wanted(Measurement::LodSweep) {
                self.lod_sweep(&mut scene, size)?;
            }
            if wanted(Measurement::TexelRate) {
                let rate = self.sample_rate(&mut scene, size, texel_rate)?;
                self.sample_rates.push(rate);
            }
            if wanted(Measurement::Phases) {
                self.phases(&mut scene, size)?;
            }
            if wanted(Measurement::MethodTable) {
                self.method_table(&mut scene, size)?;
            }
            drop(scene);
            if wanted(Measurement::FarField) {
                self.far_field(size)?;
            }
            if wanted(Measurement::Overdraw) {
                self.overdraw(size)?;
            }
            if wanted(Measurement::SceneShadows) {
                self.scene_shadows(size)?;
            }
            if wanted(Measurement::Environment) {
                self.environment(size)?;
            }
            if wanted(Measurement::Lights) {
                self.lights(size)?;
            }
            if wanted(Measurement::Silhouette) {
                self.silhouette(size)?;
            }
            if wanted(Measurement::Antialiasing) {
                self.antialiasing(size)?;
            }
            if wanted(Measurement::SeedPort) {
                self.seed_port(size)?;
            }
            if wanted(Measurement::Layers) {
                self.layers(size)?;
            }
            if wanted(Measurement::Triplanar) {
                self.triplanar(size)?;
            }
        }
        if wanted(Measurement::VersusMesh) {
            let size = sizes[0];
            eprintln!(
                "POM against displaced grids at {}x{}{on_path} ...",
                size.0, size.1
            );
            self.versus_mesh
                .push(versus_mesh::compare(&versus_mesh::Setup {
                    size,
                    textures: self.textures,
                    base: &ParallaxOcclusionMaterial {
                        method: ParallaxMethod::Occlusion,
                        ..self.base.clone()
                    },
                    view: &self.view,
                    path: asked,
                    quick: args.quick,
                    frames: (self.warmup, self.frames),
                })?);
        }
        if wanted(Measurement::PyramidBuild) {
            eprintln!("timing max-mip's pyramid rebuilt every frame{on_path} ...");
            self.pyramid_builds(sizes[0], args.quick)?;
        }
        if wanted(Measurement::FirstUse) {
            for &size in sizes {
                eprintln!(
                    "timing the first use of a pipeline variant at {}x{}{on_path} ...",
                    size.0, size.1
                );
                self.first_use(size)?;
            }
        }
        if wanted(Measurement::CpuSide) {
            for case in cpu_side::CASES {
                eprintln!(
                    "timing the CPU side with {} entities, {} % {}, AA {}, {}{on_path} ...",
                    args.entities,
                    case.moving_percent,
                    case.motion.word(),
                    case.anti_aliasing.name(),
                    case.materials.words()
                );
                self.cpu_side.push(cpu_side::measure(
                    args.entities,
                    case,
                    self.textures,
                    asked,
                    self.warmup.frames,
                    self.frames,
                )?);
            }
        }
        Ok(())
    }

    /// Records `numerator / denominator` as `what` at `size`, on the numerator's path.
    fn ratio(&mut self, what: String, size: (u32, u32), numerator: Median, denominator: Median) {
        self.ratios.push(Ratio {
            what,
            width: size.0,
            height: size.1,
            path: numerator.path,
            ratio: numerator.ms / denominator.ms,
        });
    }

    fn case(
        &mut self,
        scene: &mut BenchScene,
        group: &'static str,
        size: (u32, u32),
        tiling: f32,
        material: ParallaxOcclusionMaterial,
    ) -> Result<Median> {
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

    /// Records `times` of `pass` (frames that ran on `path`, as [`BenchScene::path_ran`] says)
    /// as one case; returns their median.
    /// Records each phase of `times` and their sum, the frame, as rows of `group` for the
    /// runner's material; returns the frame's median.
    fn record_phases_and_frame(
        &mut self,
        group: &'static str,
        size: (u32, u32),
        (path, variant): (&'static str, &str),
        times: &scene::PhaseTimes,
    ) -> Result<Median> {
        let (place, material) = ((size, 1.0), self.base.clone());
        for (phase, times) in times {
            let row = (path, *phase, variant.to_owned());
            self.record(group, place, &material, row, times)?;
        }
        let frame: Vec<f64> = (0..self.frames)
            .map(|frame| times.iter().map(|(_, phase)| phase[frame]).sum())
            .collect();
        let row = (path, "frame", variant.to_owned());
        self.record(group, place, &material, row, &frame)
    }

    fn record(
        &mut self,
        group: &'static str,
        (size, tiling): ((u32, u32), f32),
        material: &ParallaxOcclusionMaterial,
        (path, pass, variant): (&'static str, &'static str, String),
        times: &[f64],
    ) -> Result<Median> {
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
            path,
            pass,
            variant,
            spread,
        });
        Ok(Median {
            ms: spread.median_ms,
            path,
        })
    }

    fn case_variant(
        &mut self,
        scene: &mut BenchScene,
        group: &'static str,
        place: ((u32, u32), f32),
        material: ParallaxOcclusionMaterial,
        variant: String,
    ) -> Result<Median> {
        Self::configure(scene, &material);
        let (pass, times) = scene.time(self.warmup, self.frames)?;
        let path = scene.path_ran();
        self.record(group, place, &material, (path, pass, variant), &times)
    }

    /// The base material's frame phase by phase.
    fn phases(&mut self, scene: &mut BenchScene, size: (u32, u32)) -> Result<()> {
        let material = self.base.clone();
        Self::configure(scene, &material);
        let phases = ["prepass", "opaque", "post"];
        let times = scene.time_phases(self.warmup, self.frames, &phases)?;
        let path = scene.path_ran();
        for (phase, times) in &times {
            let place = (size, self.view.tiling);
            let row = (path, *phase, String::new());
            self.record("phases", place, &material, row, times)?;
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
                let what = format!("overdraw: {OVERDRAW_PLANES} planes {order} / 1{offset}");
                self.ratio(what, size, stacked_ms, one_ms);
            }
        }
        Ok(())
    }

    /// The base material on the preview cube and sphere with each silhouette mode, against
    /// `off` on the same shape.
    fn silhouette(&mut self, size: (u32, u32)) -> Result<()> {
        for shape in [PreviewShape::Cube, PreviewShape::Sphere] {
            let view = PreviewView { shape, ..self.view };
            let shape_name = format!("{shape:?}").to_lowercase();
            let mut scene = self.scene(size, &view)?;
            let mut off_ms = None;
            for silhouette in Silhouette::VALUES {
                let material = ParallaxOcclusionMaterial {
                    silhouette: *silhouette,
                    ..self.base.clone()
                };
                let variant = format!("{shape_name}, {}", silhouette.name());
                let place = (size, self.view.tiling);
                let ms = self.case_variant(&mut scene, "silhouette", place, material, variant)?;
                match off_ms {
                    None => off_ms = Some(ms),
                    Some(off) => {
                        let what = format!("silhouette: {shape_name}, {} / off", silhouette.name());
                        self.ratio(what, size, ms, off);
                    }
                }
            }
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
        let mut pom = [None; 3];
        for method in METHODS {
            for (index, shadows) in SHADOWS.into_iter().enumerate() {
                let material = self.with_modes(method, shadows);
                let ms = self.case(scene, "methods", size, self.view.tiling, material)?;
                if method == ParallaxMethod::Occlusion {
                    pom[index] = Some(ms);
                }
            }
        }
        let [Some(off), Some(hard), Some(soft)] = pom else {
            anyhow::bail!("POM was not timed with every shadow mode");
        };
        for (shadows, on) in [("hard", hard), ("soft", soft)] {
            self.ratio(format!("POM {shadows} shadows / no shadows"), size, on, off);
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
        let pom_time = self.case(scene, "texel_rate", size, self.view.tiling, pom.clone())?;
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
        Ok(SampleRate::new(
            size,
            count,
            (pom_time.ms, pom_time.path),
            probe,
            chip,
        ))
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
        self.ratio(
            "far field POM / normal mapping".to_owned(),
            size,
            pom_ms,
            normal_ms,
        );
        Ok(())
    }
}

/// Runs the benchmark.
pub fn run(args: &BenchArgs) -> Result<()> {
    let base = args.material.settings();
    base.validate().context("invalid material")?;
    let files = args.textures.files(base.height_convention);
    let textures = PreviewTextures::load(&files, base.height_scale)?;
    let view = args.view.preview_view();
    let paths = args.path.paths();
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
            ..SceneOptions::timed_plane(sizes[0], paths[0])
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
        path: paths[0],
        textures: &textures,
        base: base.clone(),
        view,
        cases: Vec::new(),
        ratios: Vec::new(),
        sample_rates: Vec::new(),
        versus_mesh: Vec::new(),
        cpu_side: Vec::new(),
        method_rows: Vec::new(),
        method_errors: Vec::new(),
        large_height_map: None,
    };
    let texel_rate = texel_rate::texel_rate(&adapter.name, args.texel_rate.map(f64::from));
    let chip = texel_rate.as_ref().map(|rate| rate.gtexels_per_s);
    // One path after the other, each in scenes built on it: nothing of one path's frames
    // (pipelines, the visibility buffer) is left in the other's.
    for &path in &paths {
        runner.path = path;
        runner.measure(args, &sizes, chip)?;
    }
    let report = BenchReport {
        texel_rate,
        adapter,
        paths: paths.iter().map(|path| path.name()).collect(),
        unix_time: started,
        quick: args.quick,
        warmup_frames: warmup.frames,
        timed_frames: frames,
        cases: runner.cases,
        ratios: runner.ratios,
        sample_rates: runner.sample_rates,
        versus_mesh: runner.versus_mesh,
        cpu_side: runner.cpu_side,
        method_table: runner.method_rows,
        dropped_frames: scene::dropped_frames(),
    };
    print!("{}", report.table());
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("creating {}", args.out.display()))?;
    report.write_files(&args.out)?;
    // One comparison per path asked for, in their order.
    for (versus, asked) in report.versus_mesh.iter().zip(&paths) {
        let several = (paths.len() > 1).then_some(*asked);
        for (file, image) in &versus.images {
            let path = args.out.join(versus_file(file, several));
            pom::files::write_png(&path, image)?;
        }
    }
    let chart_path = args.out.join("bench.png");
    chart::write_chart(&chart_path, &report.adapter.name, &report.cases)?;
    let versus = if !report.versus_mesh.is_empty() {
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

/// `file` (`versus_pom.png`), or with several paths asked for, named for the one its
/// comparison asked for (`versus_pom-deferred.png`).
fn versus_file(file: &str, asked: Option<RenderPath>) -> String {
    match (asked, file.strip_suffix(".png")) {
        (Some(path), Some(stem)) => format!("{stem}-{path}.png"),
        _ => file.to_owned(),
    }
}

/// Repeats across the plane so that one pixel covers 2^(lod_threshold + margin) texels: every
/// pixel is past the LOD threshold and its transition band.
fn far_field_tiling(size: (u32, u32), texture_width: u32, lod_threshold: f32) -> f32 {
    let texels_per_pixel = (lod_threshold + FAR_FIELD_MIP_MARGIN).exp2();
    texels_per_pixel * size.0.max(size.1) as f32 / texture_width.max(1) as f32
}

#[cfg(test)]
mod tests {
    use super::{RenderPath, far_field_tiling, versus_file};

    #[test]
    fn versus_images_are_named_for_their_path_when_there_are_several() {
        assert_eq!(versus_file("versus_pom.png", None), "versus_pom.png");
        assert_eq!(
            versus_file("versus_pom.png", Some(RenderPath::Deferred)),
            "versus_pom-deferred.png"
        );
    }

    #[test]
    fn far_field_puts_every_pixel_past_the_threshold() {
        // 1920 px across, 1024 texels per repeat, threshold 4: 128 texels per pixel.
        let tiling = far_field_tiling((1920, 1080), 1024, 4.0);
        assert!((tiling * 1024.0 / 1920.0 - 128.0).abs() < 1e-3);
    }
}
