//! `--only seed-port`: Tatarchuk's listing 2 (ported to WGSL, pom::seed_port) beside our
//! material on the same plane, textures and settings, in two forms: as written (a material in
//! the forward raster pass) and as one compute dispatch over the target, the like-for-like
//! figure for our deferred path's compute resolve: rebuilding each pixel from the plane's
//! triangle as the resolve does, and from the plane solved on the CPU (the floor).

use anyhow::Result;
use pom::preview::PreviewView;
use pom::seed_port::{SEED_PORT_COMPUTE_PASS, SeedPortSurface};
use pom::{ParallaxOcclusionMaterial, RenderPhase};

use super::scene::{BenchScene, SceneOptions};
use super::{Median, Runner, far_field_tiling};

/// The `path` of the compute pass's rows: it runs on neither render path.
pub const COMPUTE_PATH: &str = "compute";

/// The names of one plane's rows (the near plane's, or the far field's).
struct RowNames {
    ours: &'static str,
    ours_resolve: &'static str,
    fragment: &'static str,
    compute: &'static str,
    /// The compute pass over the plane solved on the CPU: the floor.
    analytic: &'static str,
    /// Our material's phases over the seed's fragment pass: our path as run against the seed
    /// as written.
    ours_over_fragment: &'static str,
    /// Our resolve over the seed's compute pass: compute against compute.
    resolve_over_compute: &'static str,
    /// Our resolve over the analytic plane's pass: against the floor.
    resolve_over_analytic: &'static str,
}

const NEAR: RowNames = RowNames {
    ours: "ours",
    ours_resolve: "ours, resolve",
    fragment: "seed port, fragment pass",
    compute: "seed port, compute pass",
    analytic: "seed port, compute pass, analytic plane",
    ours_over_fragment: "ours / seed port as written (fragment pass)",
    resolve_over_compute: "ours, resolve / seed port compute",
    resolve_over_analytic: "ours, resolve / seed port compute, analytic plane",
};

const FAR: RowNames = RowNames {
    ours: "ours, far field",
    ours_resolve: "ours, far field, resolve",
    fragment: "seed port, far field, fragment pass",
    compute: "seed port, far field, compute pass",
    analytic: "seed port, far field, compute pass, analytic plane",
    ours_over_fragment: "ours, far field / seed port as written (fragment pass), far field",
    resolve_over_compute: "ours, far field, resolve / seed port compute, far field",
    resolve_over_analytic: "ours, far field, resolve / seed port compute, far field, analytic plane",
};

impl Runner<'_> {
    /// The base material and the seed's own shader (listing 2 ported) on the same plane: our
    /// material's phases (and, deferred, its resolve alone), the port as written and as a
    /// compute pass, and the ratios; then the same far away (every pixel past the LOD
    /// threshold), where both only normal-map: the per-pixel base cost. Ours runs on the path
    /// asked for; the port has no deferred shader, and a registered material without one sends
    /// every frame forward, so it gets a scene of its own.
    pub(super) fn seed_port(&mut self, size: (u32, u32)) -> Result<()> {
        let texture_width = self.textures.height.size().0;
        let far_tiling = far_field_tiling(size, texture_width, self.base.lod_threshold);
        for (tiling, names) in [(self.view.tiling, NEAR), (far_tiling, FAR)] {
            let view = PreviewView {
                tiling,
                ..self.view
            };
            let (ours, resolve) = self.seed_port_ours(size, &view, &names)?;
            let place = (size, tiling);
            let material = self.base.clone();
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
            let row = (scene.path_ran(), pass, names.fragment.into());
            let fragment = self.record("seed_port", place, &material, row, &times)?;
            self.ratio(names.ours_over_fragment.into(), size, ours, fragment);

            for (surface, name, ratio) in [
                (
                    SeedPortSurface::Triangle,
                    names.compute,
                    names.resolve_over_compute,
                ),
                (
                    SeedPortSurface::AnalyticPlane,
                    names.analytic,
                    names.resolve_over_analytic,
                ),
            ] {
                let times = scene.time_seed_port_compute(surface, self.warmup, self.frames)?;
                let row = (COMPUTE_PATH, SEED_PORT_COMPUTE_PASS, name.into());
                let compute = self.record("seed_port", place, &material, row, &times)?;
                if let Some(resolve) = resolve {
                    self.ratio(ratio.into(), size, resolve, compute);
                }
            }
        }
        Ok(())
    }

    /// Our material on the plane seen from `view`: its phases' sum, and its resolve alone where
    /// the frames ran deferred.
    fn seed_port_ours(
        &mut self,
        size: (u32, u32),
        view: &PreviewView,
        names: &RowNames,
    ) -> Result<(Median, Option<Median>)> {
        let material: ParallaxOcclusionMaterial = self.base.clone();
        let mut scene = self.scene(size, view)?;
        Self::configure(&mut scene, &material);
        let (pass, times, phases) = scene.time_material_phases(self.warmup, self.frames)?;
        let path = scene.path_ran();
        let place = (size, view.tiling);
        let ours = self.record(
            "seed_port",
            place,
            &material,
            (path, pass, names.ours.into()),
            &times,
        )?;
        let resolve_name = RenderPhase::Resolve.name();
        let resolve = match phases.iter().find(|(phase, _)| *phase == resolve_name) {
            Some((phase, times)) => {
                let row = (path, *phase, names.ours_resolve.into());
                Some(self.record("seed_port", place, &material, row, times)?)
            }
            None => None,
        };
        Ok((ours, resolve))
    }
}
