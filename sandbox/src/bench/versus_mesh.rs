//! POM on the flat plane against the geometry it imitates (T §5.5): grids displaced by the same
//! height map, every candidate scored by FLIP error against a much finer grid and timed; the
//! speed ratio is read at equal error.

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

/// Grid cells per height-map texel of the reference: far finer than any candidate.
const REFERENCE_CELLS_PER_TEXEL: f32 = 8.0;
/// Grid cells per texel of the mesh candidates (with the shipped 256² bricks: 32² to 1448²
/// cells, 2 thousand to 4.2 million triangles).
const MESH_CELLS_PER_TEXEL: [f32; 7] = [0.125, 0.25, 0.5, 1.0, 2.0, 4.0, 5.66];
/// Finest grids timed: 4096² cells are 33.6 million triangles, 2048² cells 8.4 million.
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

/// The cheapest mesh at most as wrong as the base POM material, and how much slower it is.
#[derive(Clone, Debug, Serialize)]
pub struct EqualError {
    /// The base POM candidate.
    pub pom: Candidate,
    /// The cheapest mesh whose mean FLIP error is at most POM's.
    pub mesh: Candidate,
    /// Mesh median / POM median: how many times faster POM is at equal error.
    pub pom_speedup: f64,
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
    /// Triangles of the reference grid.
    pub reference_triangles: usize,
    /// Every candidate, POM first.
    pub candidates: Vec<Candidate>,
    /// The equal-error ratio; `None` when no mesh was as accurate as POM.
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
                 {:<5} {:>10} {:>8} {:>10} {:>10} {:>10}  path\n",
            v.width,
            v.height,
            v.path,
            v.reference_triangles,
            "kind",
            "triangles",
            "samples",
            "FLIP mean",
            "FLIP p99",
            "median ms"
        );
        for c in &v.candidates {
            let _ = writeln!(
                out,
                "{:<5} {:>10} {:>8} {:>10.4} {:>10.4} {:>10.4}  {}",
                c.kind,
                c.triangles,
                format!("{}-{}", c.samples.0, c.samples.1),
                c.flip_mean,
                c.flip_p99,
                c.spread.median_ms,
                c.path
            );
        }
        match &v.equal_error {
            Some(e) => {
                let _ = writeln!(
                    out,
                    "equal error: POM {}-{} (FLIP {:.4}, {:.4} ms) vs the cheapest grid no worse, \
                         {} triangles (FLIP {:.4}, {:.4} ms): POM {:.2}x faster",
                    e.pom.samples.0,
                    e.pom.samples.1,
                    e.pom.flip_mean,
                    e.pom.spread.median_ms,
                    e.mesh.triangles,
                    e.mesh.flip_mean,
                    e.mesh.spread.median_ms,
                    e.pom_speedup
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
        0,
        base.height_convention == pom::HeightConvention::Depth,
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

    let reference_cells = cells(REFERENCE_CELLS_PER_TEXEL, MAX_REFERENCE_CELLS);
    let reference_mesh = grid(reference_cells).context("building the reference grid")?;
    let reference_triangles = reference_mesh.triangle_count();
    eprintln!("  reference: displaced grid of {reference_triangles} triangles");
    let mut reference = BenchScene::new(
        SceneOptions {
            timestamps: false,
            surface: Some(reference_mesh),
            ..SceneOptions::timed_plane(setup.size, setup.path)
        },
        setup.textures,
        on_mesh.clone(),
        setup.view,
    )?;
    // Alpha 0 marks where the sunken reference leaves the view empty (at the far edge).
    reference.set_clear_color(pom::Color {
        a: 0.0,
        ..pom::Color::BLACK
    });
    let reference = reference.capture()?;

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
        let mut scene = BenchScene::new(
            SceneOptions {
                surface: Some(mesh),
                ..SceneOptions::timed_plane(setup.size, setup.path)
            },
            setup.textures,
            on_mesh.clone(),
            setup.view,
        )?;
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
    if let Some(found) = &equal_error {
        images.push(("versus_mesh.png", found.mesh.image.clone()));
    }
    Ok(VersusMesh {
        width: setup.size.0,
        height: setup.size.1,
        path: pom.path,
        reference_triangles,
        equal_error,
        candidates,
        images,
    })
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
        samples,
        flip_mean: flip.mean,
        flip_p99: flip.at_percentile,
        path: scene.path_ran(),
        spread,
    })
}

/// The cheapest mesh candidate whose error is at most `pom`'s.
fn equal_error(pom: &Candidate, candidates: &[Candidate]) -> Option<EqualError> {
    let mesh = candidates
        .iter()
        .filter(|c| c.kind == "mesh" && c.flip_mean <= pom.flip_mean)
        .min_by(|a, b| a.spread.median_ms.total_cmp(&b.spread.median_ms))?;
    Some(EqualError {
        pom: pom.clone(),
        mesh: mesh.clone(),
        pom_speedup: mesh.spread.median_ms / pom.spread.median_ms,
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
            samples: (0, 0),
            flip_mean,
            flip_p99: flip_mean,
            path: "forward",
            spread: Spread::of(&[median_ms]).unwrap(),
        }
    }

    #[test]
    fn equal_error_takes_the_cheapest_mesh_no_worse_than_pom() {
        let pom = candidate("pom", 0.05, 0.5);
        let candidates = vec![
            pom.clone(),
            candidate("mesh", 0.09, 0.2),
            candidate("mesh", 0.04, 3.0),
            candidate("mesh", 0.01, 9.0),
        ];
        let found = equal_error(&pom, &candidates).unwrap();
        assert_eq!(found.mesh.spread.median_ms, 3.0);
        assert!((found.pom_speedup - 6.0).abs() < 1e-12);
        assert!(equal_error(&candidate("pom", 0.001, 1.0), &candidates).is_none());
    }
}
