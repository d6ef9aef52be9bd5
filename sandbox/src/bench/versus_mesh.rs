//! POM on the flat plane against the geometry it imitates (T §5.5): grids displaced by the same
//! height map, every candidate scored by FLIP error against a much finer grid and timed; the
//! speed ratio is read at equal error: the grid's cost interpolated (by error) between the two
//! grids around POM's error, by the mean alone and by mean and p99 together, reported as the
//! range between the two.

use std::fmt::Write as _;

use anyhow::{Context, Result, bail};
use image::RgbaImage;
use pom::preview::{PLANE_SIZE, PreviewView};
use pom::{
    HeightField, HeightUnits, MAX_GRID_CELLS, Mesh, ParallaxMethod, ParallaxOcclusionMaterial,
};
use serde::Serialize;

use super::scene::{BenchScene, SceneOptions, Warmup};
use super::stats::Spread;
use crate::preview_textures::PreviewTextures;

/// Grid cells per height-map texel of the reference, at least (finer than any candidate): it is
/// built for one texture repeat and tiled, so the plane's tiling does not thin it out.
const REFERENCE_CELLS_PER_TEXEL: f32 = 4.0;
/// Grid cells per texel of the mesh candidates (with the shipped 256² bricks: 32² to 1448²
/// cells, 2 thousand to 4.2 million triangles).
const MESH_CELLS_PER_TEXEL: [f32; 7] = [0.125, 0.25, 0.5, 1.0, 2.0, 4.0, 5.66];
/// Finest grids: the reference's 4096² cells per repeat (33.6 million triangles, four cells per
/// texel of a 1024² map), the timed candidates' 2048² over the whole plane (8.4 million).
const MAX_REFERENCE_CELLS: u32 = 4096;
const MAX_CANDIDATE_CELLS: u32 = 2048;
/// `--quick` keeps every grid at most this fine, so the software driver stays fast.
const QUICK_MAX_CELLS: u32 = 96;
/// `max_samples` of the POM candidates besides the base material's.
const POM_MAX_SAMPLES: [u32; 5] = [8, 16, 32, 64, 128];
const FLIP_PERCENTILE: f32 = 0.99;

/// One image scored and timed.
#[derive(Clone, Debug, Serialize)]
pub struct Candidate {
    /// What it looked like (masked like the reference).
    #[serde(skip)]
    pub image: RgbaImage,
    /// "pom" on the flat plane or "mesh" (normal mapping on the displaced grid).
    pub kind: &'static str,
    /// Triangles drawn.
    pub triangles: usize,
    /// Bytes the GPU holds for it: the mesh's buffers and the material's textures.
    pub gpu_bytes: u64,
    /// POM's `min_samples`–`max_samples`; 0–0 for a mesh.
    pub samples: (u32, u32),
    /// Mean FLIP error against the reference.
    pub flip_mean: f32,
    /// 99th-percentile FLIP error.
    pub flip_p99: f32,
    /// The path its timed frames ran, `forward` or `deferred`.
    pub path: &'static str,
    /// Main pass milliseconds.
    pub spread: Spread,
}

/// A grid's cost at POM's error in one metric, read between the two grids around it.
#[derive(Clone, Debug, Serialize)]
pub struct CostAtError {
    /// The grid milliseconds at POM's error, interpolated linearly in the error between the
    /// coarser grid (error above POM's) and the finer one (at or below it); the cheapest
    /// grid's own where it is already no worse than POM (then an upper bound).
    pub mesh_ms: f64,
    /// Triangles of the two grids it lies between (one grid twice when it is an upper bound).
    pub between_triangles: (usize, usize),
    /// Whether the cheapest grid already matched POM (the cost is then at most `mesh_ms`).
    pub upper_bound: bool,
}

/// The base POM material against the displaced grids at equal error.
#[derive(Clone, Debug, Serialize)]
pub struct EqualError {
    /// The base POM candidate.
    pub pom: Candidate,
    /// The grid's cost at POM's mean FLIP error.
    pub at_mean: CostAtError,
    /// The grid's cost at POM's 99th-percentile FLIP error; `None` when no grid reaches it.
    pub at_p99: Option<CostAtError>,
    /// Grid / POM at equal mean error alone: how many times faster POM is by that measure.
    pub pom_speedup_mean_only: f64,
    /// Grid / POM where the grid matches POM in mean and p99 both (the larger of the two
    /// interpolated costs); `None` when no grid reaches POM's p99.
    pub pom_speedup_mean_and_p99: Option<f64>,
}

impl EqualError {
    /// The speed-up as a range, low to high: the mean-and-p99 and the mean-only figures.
    pub fn speedup_range(&self) -> (f64, f64) {
        let both = self
            .pom_speedup_mean_and_p99
            .unwrap_or(self.pom_speedup_mean_only);
        (
            both.min(self.pom_speedup_mean_only),
            both.max(self.pom_speedup_mean_only),
        )
    }
}

/// Everything the comparison found.
#[derive(Clone, Debug, Serialize)]
pub struct VersusMesh {
    /// Image width.
    pub width: u32,
    /// Image height.
    pub height: u32,
    /// The path the base POM candidate's frames ran, `forward` or `deferred`.
    pub path: &'static str,
    /// Triangles of the reference (its grid per texture repeat times the repeats).
    pub reference_triangles: usize,
    /// Grid cells of the reference per height-map texel (along each side).
    pub reference_cells_per_texel: f32,
    /// Every candidate, POM first.
    pub candidates: Vec<Candidate>,
    /// The equal-error ratio; `None` when no grid was as accurate as POM on the mean.
    pub equal_error: Option<EqualError>,
    /// The compared images (masked like the reference), to look at: the reference, the base POM material
    /// and the equal-error grid, named for their files.
    #[serde(skip)]
    pub images: Vec<(&'static str, RgbaImage)>,
}

impl VersusMesh {
    /// The comparison as the lines the bench prints.
    pub fn table(&self) -> String {
        let v = self;
        let mut out = format!(
            "\nPOM vs displaced grid at {}x{}, {}, FLIP against a {}-triangle grid, shadows off:\n\
                 {:<5} {:>10} {:>9} {:>8} {:>10} {:>10} {:>10}  path\n",
            v.width,
            v.height,
            v.path,
            v.reference_triangles,
            "kind",
            "triangles",
            "GPU MiB",
            "samples",
            "FLIP mean",
            "FLIP p99",
            "median ms"
        );
        for c in &v.candidates {
            let _ = writeln!(
                out,
                "{:<5} {:>10} {:>9.2} {:>8} {:>10.4} {:>10.4} {:>10.4}  {}",
                c.kind,
                c.triangles,
                c.gpu_bytes as f64 / (1024.0 * 1024.0),
                format!("{}-{}", c.samples.0, c.samples.1),
                c.flip_mean,
                c.flip_p99,
                c.spread.median_ms,
                c.path
            );
        }
        match &v.equal_error {
            Some(e) => {
                let (low, high) = e.speedup_range();
                let cost = |at: &CostAtError| {
                    let bound = if at.upper_bound { "at most " } else { "" };
                    format!(
                        "{bound}{:.4} ms (grids of {} and {} triangles)",
                        at.mesh_ms, at.between_triangles.0, at.between_triangles.1
                    )
                };
                let p99 = e
                    .at_p99
                    .as_ref()
                    .map_or("no grid reaches it".to_owned(), cost);
                let _ = writeln!(
                    out,
                    "equal error: POM {}-{} (FLIP mean {:.4}, p99 {:.4}, {:.4} ms); a grid at its \
                     mean {}, at its p99 {p99}: POM {low:.2}x to {high:.2}x faster (mean and \
                     p99, mean only)",
                    e.pom.samples.0,
                    e.pom.samples.1,
                    e.pom.flip_mean,
                    e.pom.flip_p99,
                    e.pom.spread.median_ms,
                    cost(&e.at_mean),
                );
            }
            None => out.push_str("equal error: no grid candidate was as accurate as POM\n"),
        }
        out
    }
}

/// What the comparison needs from the bench run.
pub struct Setup<'a> {
    /// Image size.
    pub size: (u32, u32),
    /// Textures of the material.
    pub textures: &'a PreviewTextures,
    /// The base POM material (shadows are turned off: the grid casts none).
    pub base: &'a ParallaxOcclusionMaterial,
    /// Camera and light.
    pub view: &'a PreviewView,
    /// Forward, deferred or auto (`--path`).
    pub path: pom::RenderPath,
    /// Tiny grids for `--quick`.
    pub quick: bool,
    /// Untimed, then timed frames per candidate.
    pub frames: (Warmup, usize),
}

/// Runs the comparison.
pub fn compare(setup: &Setup) -> Result<VersusMesh> {
    let base = ParallaxOcclusionMaterial {
        shadows: pom::ShadowMode::Off,
        ..setup.base.clone()
    };
    let field = HeightField::from_image(
        &setup.textures.height,
        pom::Channel::Red,
        base.height_convention,
    );
    let tiling = setup.view.tiling.max(f32::MIN_POSITIVE);
    let depth = match base.height_units {
        HeightUnits::World => base.height_scale,
        // One texture repeat spans PLANE_SIZE / tiling world units.
        _ => base.height_scale * PLANE_SIZE / tiling,
    };
    let texels_across = field.size().0 as f32 * tiling;
    let quick_cap = |cap: u32| if setup.quick { QUICK_MAX_CELLS } else { cap };
    let cells = |per_texel: f32, cap: u32| {
        ((texels_across * per_texel).round() as u32).clamp(1, quick_cap(cap).min(MAX_GRID_CELLS))
    };
    let grid = |cells: u32| Mesh::displaced_grid(PLANE_SIZE, tiling, &field, depth, cells);
    // Normal mapping on the true geometry: the same shader and lighting as POM, no march.
    let on_mesh = ParallaxOcclusionMaterial {
        method: ParallaxMethod::NormalMapping,
        ..base.clone()
    };

    let (reference, reference_triangles, reference_cells_per_texel) =
        reference_image(setup, &on_mesh, &field, (depth, tiling))?;

    let mut candidates = Vec::new();
    let mut plane = BenchScene::new(
        SceneOptions::timed_plane(setup.size, setup.path),
        setup.textures,
        base.clone(),
        setup.view,
    )?;
    let mut pom_max_samples = POM_MAX_SAMPLES.to_vec();
    pom_max_samples.push(base.max_samples);
    pom_max_samples.sort_unstable();
    pom_max_samples.dedup();
    let mut base_pom = None;
    for max_samples in pom_max_samples {
        let material = ParallaxOcclusionMaterial {
            min_samples: base.min_samples.min(max_samples),
            max_samples,
            ..base.clone()
        };
        let samples = (material.min_samples, material.max_samples);
        plane.configure(|m| {
            m.min_samples = samples.0;
            m.max_samples = samples.1;
        });
        let candidate = score(&mut plane, &reference, setup.frames, "pom", 2, samples)?;
        if max_samples == base.max_samples {
            base_pom = Some(candidate.clone());
        }
        candidates.push(candidate);
    }
    drop(plane);

    let mut mesh_cells: Vec<u32> = MESH_CELLS_PER_TEXEL
        .iter()
        .map(|&c| cells(c, MAX_CANDIDATE_CELLS))
        .collect();
    mesh_cells.dedup();
    for cells in mesh_cells {
        let mesh = grid(cells).context("building a candidate grid")?;
        let triangles = mesh.triangle_count();
        let mut scene = grid_scene(setup, mesh, &on_mesh, true)?;
        candidates.push(score(
            &mut scene,
            &reference,
            setup.frames,
            "mesh",
            triangles,
            (0, 0),
        )?);
    }
    let Some(pom) = base_pom else {
        bail!("the base material was not among the POM candidates");
    };
    let equal_error = equal_error(&pom, &candidates);
    let mut images = vec![
        ("versus_reference.png", reference),
        ("versus_pom.png", pom.image),
    ];
    // The finer grid around POM's mean error: the one at least as good.
    let finer = equal_error.as_ref().and_then(|found| {
        candidates
            .iter()
            .find(|c| c.kind == "mesh" && c.triangles == found.at_mean.between_triangles.1)
    });
    if let Some(finer) = finer {
        images.push(("versus_mesh.png", finer.image.clone()));
    }
    Ok(VersusMesh {
        width: setup.size.0,
        height: setup.size.1,
        path: pom.path,
        reference_triangles,
        reference_cells_per_texel,
        equal_error,
        candidates,
        images,
    })
}

/// The reference image: normal mapping on a grid of at least [`REFERENCE_CELLS_PER_TEXEL`]
/// (capped at [`MAX_REFERENCE_CELLS`] a side) built for one texture repeat and tiled over the
/// plane, however many repeats it has; with its triangles and cells per texel.
fn reference_image(
    setup: &Setup,
    on_mesh: &ParallaxOcclusionMaterial,
    field: &HeightField,
    (depth, tiling): (f32, f32),
) -> Result<(RgbaImage, usize, f32)> {
    let texels = field.size().0.max(1) as f32;
    let cap = if setup.quick {
        QUICK_MAX_CELLS
    } else {
        MAX_REFERENCE_CELLS
    };
    let cells =
        ((texels * REFERENCE_CELLS_PER_TEXEL).ceil() as u32).clamp(1, cap.min(MAX_GRID_CELLS));
    let repeat = PLANE_SIZE / tiling;
    let mesh = Mesh::displaced_grid(repeat, 1.0, field, depth, cells)
        .context("building the reference grid")?;
    let tiles = tiling.ceil().max(1.0) as u32;
    let triangles = mesh.triangle_count() * (tiles * tiles) as usize;
    let per_texel = cells as f32 / texels;
    eprintln!(
        "  reference: {tiles}x{tiles} displaced grids of {} triangles ({per_texel:.2} cells per texel)",
        mesh.triangle_count()
    );
    let mut reference = grid_scene(setup, mesh, on_mesh, false)?;
    reference.tile_surface(tiles, repeat)?;
    // Alpha 0 marks where the sunken reference leaves the view empty (at the far edge).
    reference.set_clear_color(pom::Color {
        a: 0.0,
        ..pom::Color::BLACK
    });
    Ok((reference.capture()?, triangles, per_texel))
}

/// A bench scene of `setup` drawing the displaced grid `mesh` with `material` (the grid's
/// relief is in its vertices), GPU-timed where `timestamps`.
fn grid_scene(
    setup: &Setup,
    mesh: Mesh,
    material: &ParallaxOcclusionMaterial,
    timestamps: bool,
) -> Result<BenchScene> {
    BenchScene::new(
        SceneOptions {
            timestamps,
            surface: Some(mesh),
            ..SceneOptions::timed_plane(setup.size, setup.path)
        },
        setup.textures,
        material.clone(),
        setup.view,
    )
}

fn score(
    scene: &mut BenchScene,
    reference: &RgbaImage,
    (warmup, frames): (Warmup, usize),
    kind: &'static str,
    triangles: usize,
    samples: (u32, u32),
) -> Result<Candidate> {
    let image = outside_reference_masked(reference, scene.capture()?);
    let flip = pom::flip_compare(reference, &image, FLIP_PERCENTILE)
        .context("reference and candidate differ in size")?;
    let (_, times) = scene.time(warmup, frames)?;
    let spread = Spread::of(&times).context("no valid timings")?;
    eprintln!(
        "  {kind} {triangles} triangles, samples {}-{}: FLIP mean {:.4}, {:.4} ms",
        samples.0, samples.1, flip.mean, spread.median_ms
    );
    Ok(Candidate {
        image,
        kind,
        triangles,
        gpu_bytes: scene.drawn_gpu_bytes(),
        samples,
        flip_mean: flip.mean,
        flip_p99: flip.at_percentile,
        path: scene.path_ran(),
        spread,
    })
}

/// The grids' cost at `target` error in the metric `error` picks: between the coarsest grid (in
/// cost order) whose error is above `target` and the next, which is at or below it; the
/// cheapest grid's own cost when it is already no worse; `None` when no grid is.
fn cost_at_error(
    grids: &[&Candidate],
    target: f32,
    error: impl Fn(&Candidate) -> f32,
) -> Option<CostAtError> {
    let first = grids.first()?;
    if error(first) <= target {
        return Some(CostAtError {
            mesh_ms: first.spread.median_ms,
            between_triangles: (first.triangles, first.triangles),
            upper_bound: true,
        });
    }
    let (coarse, fine) = grids
        .windows(2)
        .map(|pair| (pair[0], pair[1]))
        .find(|(coarse, fine)| error(coarse) > target && error(fine) <= target)?;
    let (coarse_error, fine_error) = (f64::from(error(coarse)), f64::from(error(fine)));
    let along = (coarse_error - f64::from(target)) / (coarse_error - fine_error);
    let (coarse_ms, fine_ms) = (coarse.spread.median_ms, fine.spread.median_ms);
    Some(CostAtError {
        mesh_ms: coarse_ms + (fine_ms - coarse_ms) * along,
        between_triangles: (coarse.triangles, fine.triangles),
        upper_bound: false,
    })
}

/// The grids' cost at `pom`'s mean error and at its p99, and POM's speed-up by the mean alone
/// and by both (the larger of the two costs); `None` when no grid reaches POM's mean.
fn equal_error(pom: &Candidate, candidates: &[Candidate]) -> Option<EqualError> {
    let mut grids: Vec<&Candidate> = candidates.iter().filter(|c| c.kind == "mesh").collect();
    grids.sort_by_key(|c| c.triangles);
    let at_mean = cost_at_error(&grids, pom.flip_mean, |c| c.flip_mean)?;
    let at_p99 = cost_at_error(&grids, pom.flip_p99, |c| c.flip_p99);
    let pom_ms = pom.spread.median_ms;
    Some(EqualError {
        pom: pom.clone(),
        pom_speedup_mean_only: at_mean.mesh_ms / pom_ms,
        pom_speedup_mean_and_p99: at_p99
            .as_ref()
            .map(|p99| p99.mesh_ms.max(at_mean.mesh_ms) / pom_ms),
        at_mean,
        at_p99,
    })
}

/// `image` with the reference's pixels wherever the reference shows no surface: the flat
/// plane fills the frame where the sunken grid does not, which is framing, not accuracy.
fn outside_reference_masked(reference: &RgbaImage, mut image: RgbaImage) -> RgbaImage {
    for (pixel, reference) in image.pixels_mut().zip(reference.pixels()) {
        if reference.0[3] == 0 {
            *pixel = *reference;
        }
    }
    image
}

#[cfg(test)]
mod tests {
    use super::*;

    fn candidate(kind: &'static str, flip_mean: f32, median_ms: f64) -> Candidate {
        Candidate {
            image: RgbaImage::new(1, 1),
            kind,
            triangles: 2,
            gpu_bytes: 0,
            samples: (0, 0),
            flip_mean,
            flip_p99: flip_mean,
            path: "forward",
            spread: Spread::of(&[median_ms]).unwrap(),
        }
    }

    fn grid(triangles: usize, flip_mean: f32, flip_p99: f32, median_ms: f64) -> Candidate {
        Candidate {
            triangles,
            flip_p99,
            ..candidate("mesh", flip_mean, median_ms)
        }
    }

    #[test]
    fn equal_error_interpolates_between_the_grids_around_pom() {
        let pom = Candidate {
            flip_p99: 0.2,
            ..candidate("pom", 0.05, 0.5)
        };
        let candidates = vec![
            pom.clone(),
            grid(200, 0.09, 0.4, 0.2),
            grid(800, 0.04, 0.3, 3.0),
            grid(3200, 0.01, 0.1, 9.0),
        ];
        let found = equal_error(&pom, &candidates).unwrap();
        // Mean 0.05 lies four fifths of the way from 0.09 to 0.04: 0.2 + 0.8 × 2.8 = 2.44 ms.
        assert_eq!(found.at_mean.between_triangles, (200, 800));
        assert!((found.at_mean.mesh_ms - 2.44).abs() < 1e-5);
        assert!((found.pom_speedup_mean_only - 4.88).abs() < 1e-5);
        // p99 0.2 lies halfway from 0.3 to 0.1: 6 ms, the larger cost, so it decides.
        let p99 = found.at_p99.as_ref().unwrap();
        assert_eq!(p99.between_triangles, (800, 3200));
        assert!((p99.mesh_ms - 6.0).abs() < 1e-5);
        assert!((found.pom_speedup_mean_and_p99.unwrap() - 12.0).abs() < 1e-5);
        let (low, high) = found.speedup_range();
        assert!((low - 4.88).abs() < 1e-5 && (high - 12.0).abs() < 1e-5);
    }

    #[test]
    fn a_grid_no_worse_than_pom_at_once_gives_an_upper_bound_and_none_gives_nothing() {
        let pom = candidate("pom", 0.05, 0.5);
        let fine = vec![grid(200, 0.01, 0.01, 1.0), grid(800, 0.005, 0.005, 2.0)];
        let found = equal_error(&pom, &fine).unwrap();
        assert!(found.at_mean.upper_bound);
        assert!((found.pom_speedup_mean_only - 2.0).abs() < 1e-5);
        let coarse = vec![grid(200, 0.2, 0.2, 1.0), grid(800, 0.1, 0.1, 2.0)];
        assert!(equal_error(&pom, &coarse).is_none());
        // The mean is reached, the p99 never: the mean-only figure alone.
        let p99_short = vec![grid(200, 0.2, 0.9, 1.0), grid(800, 0.01, 0.9, 2.0)];
        let found = equal_error(&pom, &p99_short).unwrap();
        assert!(found.at_p99.is_none() && found.pom_speedup_mean_and_p99.is_none());
    }
}
