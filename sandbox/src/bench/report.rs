//! The benchmark's results: what was run on what, printed as a table and written as JSON and CSV.

use std::fmt::Write as _;
use std::path::Path;

use anyhow::{Context, Result};
use pom::RenderPath;
use serde::Serialize;

use super::cpu_side::CpuSide;
use super::method_table::MethodRow;
use super::sample_count::SampleRate;
use super::stats::Spread;
use super::texel_rate::TexelRate;
use super::versus_mesh::VersusMesh;

/// One timed configuration.
#[derive(Clone, Debug, Serialize)]
pub struct CaseResult {
    /// Which measurement it belongs to: "methods", "samples", "lod_sweep" or "far_field".
    pub group: &'static str,
    /// Parallax method (the `--method` spelling).
    pub method: String,
    /// Shadow mode (the `--shadows` spelling).
    pub shadows: String,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Material `min_samples`.
    pub min_samples: u32,
    /// Material `max_samples`.
    pub max_samples: u32,
    /// Material `lod_threshold`.
    pub lod_threshold: f32,
    /// UV repeats across the plane.
    pub tiling: f32,
    /// The path its frames ran, `forward` or `deferred` (not necessarily the one asked for:
    /// auto picks one, and the seed port runs forward).
    pub path: &'static str,
    /// The timed pass or phases.
    pub pass: &'static str,
    /// What else sets the case apart ("4 planes, depth offset"); empty for most.
    pub variant: String,
    /// Its milliseconds over the timed frames.
    pub spread: Spread,
}

/// The adapter, as wgpu reports it.
#[derive(Clone, Debug, Serialize)]
pub struct AdapterReport {
    /// Adapter name.
    pub name: String,
    /// Backend (Vulkan, ...).
    pub backend: String,
    /// Device type (DiscreteGpu, Cpu, ...).
    pub device_type: String,
    /// Driver name.
    pub driver: String,
    /// Driver version text.
    pub driver_info: String,
    /// True for a software rasterizer: its timings are not performance.
    pub software_driver: bool,
}

impl From<pom::wgpu::AdapterInfo> for AdapterReport {
    fn from(info: pom::wgpu::AdapterInfo) -> Self {
        Self {
            software_driver: info.device_type == pom::wgpu::DeviceType::Cpu,
            name: info.name,
            backend: format!("{:?}", info.backend),
            device_type: format!("{:?}", info.device_type),
            driver: info.driver,
            driver_info: info.driver_info,
        }
    }
}

/// Ratios read off the cases.
#[derive(Clone, Debug, Serialize)]
pub struct Ratio {
    /// What is divided by what.
    pub what: String,
    /// Image width.
    pub width: u32,
    /// Image height.
    pub height: u32,
    /// The path the numerator's frames ran, `forward` or `deferred`.
    pub path: &'static str,
    /// Median over median.
    pub ratio: f64,
}

/// Everything one run produced.
#[derive(Clone, Debug, Serialize)]
pub struct BenchReport {
    /// The adapter.
    pub adapter: AdapterReport,
    /// The render paths asked for (`--path`, in order), each measured in turn; every case says
    /// the path its frames ran.
    pub paths: Vec<&'static str>,
    /// Seconds since the Unix epoch when the run started.
    pub unix_time: u64,
    /// Whether `--quick` was given.
    pub quick: bool,
    /// Untimed frames before each case.
    pub warmup_frames: usize,
    /// Timed frames per case.
    pub timed_frames: usize,
    /// The texel-rate limit used, or `None` when the adapter is unknown.
    pub texel_rate: Option<TexelRate>,
    /// Every case.
    pub cases: Vec<CaseResult>,
    /// Far-field POM / normal mapping and the cost of shadows.
    pub ratios: Vec<Ratio>,
    /// POM's height samples per second at each size.
    pub sample_rates: Vec<SampleRate>,
    /// POM on the plane against displaced grids at equal error, once per path asked for
    /// (none when left out by `--only`).
    pub versus_mesh: Vec<VersusMesh>,
    /// The CPU side, once per path asked for (none when left out by `--only`).
    pub cpu_side: Vec<CpuSide>,
    /// Each method's error, fetches and time (none when left out by `--only`).
    pub method_table: Vec<MethodRow>,
    /// Timed frames dropped because their timestamps were rejected or missing (each case
    /// timed its full count of other frames instead).
    pub dropped_frames: usize,
}

/// `text` as one CSV field: quoted (inner quotes doubled) where it holds a comma, a quote or a
/// line break (RFC 4180), as many variants do ("seed port, compute pass").
fn csv_field(text: &str) -> String {
    if text.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", text.replace('"', "\"\""))
    } else {
        text.to_owned()
    }
}

/// CSV columns, in order.
pub const CSV_HEADER: &str = "group,method,shadows,width,height,min_samples,max_samples,\
lod_threshold,tiling,path,pass,frames,median_ms,min_ms,p10_ms,p90_ms,max_ms,variant";

impl BenchReport {
    /// The cases as CSV, one line per case after [`CSV_HEADER`].
    pub fn csv(&self) -> String {
        let mut csv = format!("{CSV_HEADER}\n");
        for c in &self.cases {
            let s = &c.spread;
            let _ = writeln!(
                csv,
                "{},{},{},{},{},{},{},{},{},{},{},{},{:.6},{:.6},{:.6},{:.6},{:.6},{}",
                csv_field(c.group),
                csv_field(&c.method.to_string()),
                csv_field(&c.shadows.to_string()),
                c.width,
                c.height,
                c.min_samples,
                c.max_samples,
                c.lod_threshold,
                c.tiling,
                csv_field(c.path),
                csv_field(c.pass),
                s.count,
                s.median_ms,
                s.min_ms,
                s.p10_ms,
                s.p90_ms,
                s.max_ms,
                csv_field(&c.variant.to_string())
            );
        }
        csv
    }

    /// The human-readable table.
    pub fn table(&self) -> String {
        let a = &self.adapter;
        let mut out = format!(
            "adapter: {} ({}, {}, driver {} {})\n",
            a.name, a.device_type, a.backend, a.driver, a.driver_info
        );
        if a.software_driver {
            out.push_str("SOFTWARE DRIVER: these timings are not performance figures\n");
        }
        let _ = writeln!(
            out,
            "timed frames dropped for rejected or missing timestamps: {}",
            self.dropped_frames
        );
        match &self.texel_rate {
            Some(rate) => {
                let _ = writeln!(
                    out,
                    "texel-rate limit: {:.1} G texels/s ({})",
                    rate.gtexels_per_s, rate.source
                );
            }
            None => out.push_str("texel-rate limit: unknown (pass --texel-rate)\n"),
        }
        let _ = writeln!(
            out,
            "render path asked for: {}; {} warm-up + {} timed frames per case; GPU ms of the \
             pass named (prepass+opaque, +resolve where a frame ran deferred: the material's \
             phases) on the path the frames ran\n",
            self.paths.join(", "),
            self.warmup_frames,
            self.timed_frames
        );
        let _ = writeln!(
            out,
            "{:<10} {:<7} {:<6} {:>10} {:>8} {:>5} {:>7} {:>9} {:>9} {:>9} {:>9} {:>9}  {:<8} pass",
            "group",
            "method",
            "shadow",
            "size",
            "samples",
            "lod",
            "tiling",
            "median",
            "min",
            "p10",
            "p90",
            "max",
            "path"
        );
        for c in &self.cases {
            let s = &c.spread;
            let _ = writeln!(
                out,
                "{:<10} {:<7} {:<6} {:>10} {:>8} {:>5} {:>7} {:>9.4} {:>9.4} {:>9.4} {:>9.4} {:>9.4}  {:<8} {} {}",
                c.group,
                c.method,
                c.shadows,
                format!("{}x{}", c.width, c.height),
                format!("{}-{}", c.min_samples, c.max_samples),
                c.lod_threshold,
                c.tiling,
                s.median_ms,
                s.min_ms,
                s.p10_ms,
                s.p90_ms,
                s.max_ms,
                c.path,
                c.pass,
                c.variant
            );
        }
        out.push('\n');
        for ratio in &self.ratios {
            let _ = writeln!(
                out,
                "{} at {}x{}, {}: {:.3}",
                ratio.what, ratio.width, ratio.height, ratio.path, ratio.ratio
            );
        }
        for rate in &self.sample_rates {
            let chip = rate
                .fraction_of_chip
                .map_or("chip limit unknown".to_owned(), |f| {
                    format!("{:.2} % of the chip's limit", f * 100.0)
                });
            let _ = writeln!(
                out,
                "POM height samples at {}x{}, {}: {} per frame ({:.1} per marching pixel) in {:.4} ms \
                 = {:.3} G samples/s; fragment-stage probe {:.3} G texels/s (one-tap pass \
                 {:.4} ms); POM at {:.1} % of the fragment path, {chip}",
                rate.width,
                rate.height,
                rate.path,
                rate.count.total,
                rate.count.total as f64 / rate.count.marching_pixels.max(1) as f64,
                rate.pom_ms,
                rate.gsamples_per_s,
                rate.fragment_path_gtexels_per_s,
                rate.one_tap_pass_ms,
                rate.fraction_of_fragment_path * 100.0
            );
        }
        for versus_mesh in &self.versus_mesh {
            out.push_str(&versus_mesh.table());
        }
        for cpu in &self.cpu_side {
            let _ = writeln!(
                out,
                "\nCPU, {} parallax entities ({} % {}, {}), AA {}, {}, median ms per frame: \
                 transforms {:.3}, extract {:.3}, prepare {:.3}, render (record + submit) {:.3}, \
                 total {:.3}",
                cpu.entities,
                cpu.moving_percent,
                cpu.motion.word(),
                cpu.materials.words(),
                cpu.anti_aliasing,
                cpu.path,
                cpu.transforms.median_ms,
                cpu.extract.median_ms,
                cpu.prepare.median_ms,
                cpu.render.median_ms,
                cpu.total.median_ms
            );
        }
        out.push_str(&super::method_table::table(&self.method_table));
        out.push_str(&self.phases_side_by_side());
        out
    }

    /// Where the `phases` measurement ran on both paths: per size, the forward and the
    /// deferred frame (the sum of their phases' medians) and forward / deferred; else nothing.
    pub fn phases_side_by_side(&self) -> String {
        let frame = |size: (u32, u32), path: &str| -> Option<(f64, Vec<&str>)> {
            let phases: Vec<&CaseResult> = self
                .cases
                .iter()
                .filter(|c| c.group == "phases" && (c.width, c.height) == size && c.path == path)
                .collect();
            let ms = phases.iter().map(|c| c.spread.median_ms).sum();
            (!phases.is_empty()).then(|| (ms, phases.iter().map(|c| c.pass).collect()))
        };
        let mut sizes: Vec<(u32, u32)> = Vec::new();
        for case in self.cases.iter().filter(|c| c.group == "phases") {
            if !sizes.contains(&(case.width, case.height)) {
                sizes.push((case.width, case.height));
            }
        }
        let mut out = String::new();
        for size in sizes {
            let forward = RenderPath::Forward.name();
            let deferred = RenderPath::Deferred.name();
            let (Some((forward_ms, forward_phases)), Some((deferred_ms, deferred_phases))) =
                (frame(size, forward), frame(size, deferred))
            else {
                continue;
            };
            if out.is_empty() {
                out.push_str("\nphases side by side, frame = sum of the phases' medians:\n");
            }
            let _ = writeln!(
                out,
                "{}x{}: {forward} {forward_ms:.4} ms ({}), {deferred} {deferred_ms:.4} ms ({}): \
                 {forward} / {deferred} {:.2}x",
                size.0,
                size.1,
                forward_phases.join("+"),
                deferred_phases.join("+"),
                forward_ms / deferred_ms
            );
        }
        out
    }

    /// Writes `bench.json` and `bench.csv` into `dir`.
    pub fn write_files(&self, dir: &Path) -> Result<()> {
        let json = serde_json::to_string_pretty(self).context("encoding the JSON report")?;
        let json_path = dir.join("bench.json");
        pom::files::write_file(&json_path, json.as_bytes())?;
        let csv_path = dir.join("bench.csv");
        pom::files::write_file(&csv_path, self.csv().as_bytes())?;
        Ok(())
    }
}

#[cfg(test)]
impl CaseResult {
    /// A case of the default POM material for tests: `pass` of `group` on `path` at `size`,
    /// one frame of `ms`.
    pub(super) fn example(
        group: &'static str,
        size: (u32, u32),
        path: &'static str,
        pass: &'static str,
        ms: f64,
    ) -> Self {
        CaseResult {
            group,
            method: "pom".into(),
            shadows: "soft".into(),
            width: size.0,
            height: size.1,
            min_samples: 8,
            max_samples: 50,
            lod_threshold: 4.0,
            tiling: 1.0,
            path,
            pass,
            variant: String::new(),
            spread: Spread::of(&[ms]).expect("one finite frame time"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn phase(size: (u32, u32), path: &'static str, pass: &'static str, ms: f64) -> CaseResult {
        CaseResult::example("phases", size, path, pass, ms)
    }

    fn report(cases: Vec<CaseResult>) -> BenchReport {
        BenchReport {
            adapter: AdapterReport {
                name: "test".into(),
                backend: "Vulkan".into(),
                device_type: "Cpu".into(),
                driver: String::new(),
                driver_info: String::new(),
                software_driver: true,
            },
            paths: vec!["forward", "deferred"],
            unix_time: 0,
            quick: true,
            warmup_frames: 2,
            timed_frames: 1,
            texel_rate: None,
            cases,
            ratios: Vec::new(),
            sample_rates: Vec::new(),
            versus_mesh: Vec::new(),
            cpu_side: Vec::new(),
            method_table: Vec::new(),
            dropped_frames: 0,
        }
    }

    #[test]
    fn both_paths_frames_are_summed_and_divided_per_size() {
        let (small, large) = ((64, 36), (96, 54));
        let mut cases = Vec::new();
        for size in [small, large] {
            let scale = f64::from(size.0) / 64.0;
            cases.push(phase(size, "forward", "prepass", 1.0 * scale));
            cases.push(phase(size, "forward", "opaque", 8.0 * scale));
            cases.push(phase(size, "forward", "post", 1.0 * scale));
        }
        for size in [small, large] {
            cases.push(phase(size, "deferred", "prepass", 3.0));
            cases.push(phase(size, "deferred", "resolve", 1.0));
            cases.push(phase(size, "deferred", "post", 1.0));
        }
        let summary = report(cases.clone()).phases_side_by_side();
        let lines: Vec<&str> = summary.lines().filter(|l| !l.is_empty()).collect();
        assert_eq!(lines.len(), 3, "{summary}");
        assert_eq!(
            lines[1],
            "64x36: forward 10.0000 ms (prepass+opaque+post), deferred 5.0000 ms \
             (prepass+resolve+post): forward / deferred 2.00x"
        );
        assert!(
            lines[2].starts_with("96x54: forward 15.0000 ms"),
            "{}",
            lines[2]
        );
        assert!(
            lines[2].ends_with("forward / deferred 3.00x"),
            "{}",
            lines[2]
        );
        assert!(report(cases.clone()).table().ends_with(&summary));

        // One path alone: nothing to set side by side.
        cases.retain(|c| c.path == "forward");
        assert_eq!(report(cases).phases_side_by_side(), "");
    }

    #[test]
    fn a_field_with_a_comma_or_a_quote_is_quoted() {
        assert_eq!(csv_field("resolve"), "resolve");
        assert_eq!(
            csv_field("seed port, compute pass"),
            "\"seed port, compute pass\""
        );
        assert_eq!(csv_field("a \"b\""), "\"a \"\"b\"\"\"");
    }

    #[test]
    fn every_csv_row_names_its_path() {
        let csv = report(vec![
            phase((64, 36), "forward", "opaque", 2.0),
            phase((64, 36), "deferred", "resolve", 1.0),
        ])
        .csv();
        let header: Vec<&str> = CSV_HEADER.split(',').collect();
        let column = header.iter().position(|c| *c == "path").unwrap();
        let paths: Vec<&str> = csv
            .lines()
            .skip(1)
            .map(|line| line.split(',').nth(column).unwrap())
            .collect();
        assert_eq!(paths, ["forward", "deferred"]);
    }
}
