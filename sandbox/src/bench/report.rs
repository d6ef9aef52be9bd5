//! The benchmark's results: what was run on what, printed as a table and written as JSON and CSV.

use std::fmt::Write as _;
use std::path::Path;

use anyhow::{Context, Result};
use serde::Serialize;

use super::cpu_side::CpuSide;
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
    /// Median over median.
    pub ratio: f64,
}

/// Everything one run produced.
#[derive(Clone, Debug, Serialize)]
pub struct BenchReport {
    /// The adapter.
    pub adapter: AdapterReport,
    /// The render path asked for (`--path`); a case's `pass` says whether it ran deferred.
    pub path: &'static str,
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
    /// POM on the plane against displaced grids at equal error (unless left out by `--only`).
    pub versus_mesh: Option<VersusMesh>,
    /// The CPU side (unless left out by `--only`).
    pub cpu_side: Option<CpuSide>,
}

/// CSV columns, in order.
pub const CSV_HEADER: &str = "group,method,shadows,width,height,min_samples,max_samples,\
lod_threshold,tiling,pass,frames,median_ms,min_ms,p10_ms,p90_ms,max_ms,variant";

impl BenchReport {
    /// The cases as CSV, one line per case after [`CSV_HEADER`].
    pub fn csv(&self) -> String {
        let mut csv = format!("{CSV_HEADER}\n");
        for c in &self.cases {
            let s = &c.spread;
            let _ = writeln!(
                csv,
                "{},{},{},{},{},{},{},{},{},{},{},{:.6},{:.6},{:.6},{:.6},{:.6},{}",
                c.group,
                c.method,
                c.shadows,
                c.width,
                c.height,
                c.min_samples,
                c.max_samples,
                c.lod_threshold,
                c.tiling,
                c.pass,
                s.count,
                s.median_ms,
                s.min_ms,
                s.p10_ms,
                s.p90_ms,
                s.max_ms,
                c.variant
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
             phases)\n",
            self.path, self.warmup_frames, self.timed_frames
        );
        let _ = writeln!(
            out,
            "{:<10} {:<7} {:<6} {:>10} {:>8} {:>5} {:>7} {:>9} {:>9} {:>9} {:>9} {:>9}  pass",
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
            "max"
        );
        for c in &self.cases {
            let s = &c.spread;
            let _ = writeln!(
                out,
                "{:<10} {:<7} {:<6} {:>10} {:>8} {:>5} {:>7} {:>9.4} {:>9.4} {:>9.4} {:>9.4} {:>9.4}  {} {}",
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
                c.pass,
                c.variant
            );
        }
        out.push('\n');
        for ratio in &self.ratios {
            let _ = writeln!(
                out,
                "{} at {}x{}: {:.3}",
                ratio.what, ratio.width, ratio.height, ratio.ratio
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
                "POM height samples at {}x{}: {} per frame ({:.1} per marching pixel) in {:.4} ms \
                 = {:.3} G samples/s; fragment-stage probe {:.3} G texels/s (one-tap pass \
                 {:.4} ms); POM at {:.1} % of the fragment path, {chip}",
                rate.width,
                rate.height,
                rate.count.total,
                rate.count.total as f64 / rate.count.marching_pixels.max(1) as f64,
                rate.pom_ms,
                rate.gsamples_per_s,
                rate.fragment_path_gtexels_per_s,
                rate.one_tap_pass_ms,
                rate.fraction_of_fragment_path * 100.0
            );
        }
        if let Some(versus_mesh) = &self.versus_mesh {
            out.push_str(&versus_mesh.table());
        }
        if let Some(cpu) = &self.cpu_side {
            let _ = writeln!(
                out,
                "\nCPU, {} parallax entities, median ms per frame: extract {:.3}, prepare {:.3}, \
             render (record + submit) {:.3}, total {:.3}",
                cpu.entities,
                cpu.extract.median_ms,
                cpu.prepare.median_ms,
                cpu.render.median_ms,
                cpu.total.median_ms
            );
        }
        out
    }

    /// Writes `bench.json` and `bench.csv` into `dir`.
    pub fn write_files(&self, dir: &Path) -> Result<()> {
        let json = serde_json::to_string_pretty(self).context("encoding the JSON report")?;
        let json_path = dir.join("bench.json");
        std::fs::write(&json_path, json)
            .with_context(|| format!("writing {}", json_path.display()))?;
        let csv_path = dir.join("bench.csv");
        std::fs::write(&csv_path, self.csv())
            .with_context(|| format!("writing {}", csv_path.display()))
    }
}
