//! Many lights: the street corner at night (its sun taken away) lit by 1, 256 and 1,024 point
//! lights over its floor, every one in view and reaching its neighbours: each frame phase by
//! phase on the GPU, and on the CPU the Extract stage (the lights' culling into clusters) and
//! the Prepare stage (their upload) with every light moving each frame, so both run in full.

use std::time::Instant;

use anyhow::{Context, Result};
use glam::Vec3;
use pom::{App, ParallaxOcclusionMaterial, PointLight, RenderPath, Resources, Stage, Transform};

use super::Runner;
use super::scene::{BenchScene, PhaseTimes, Warmup};
use super::scene_shadows::street_corner_app;

/// The cases timed, as (point lights, lights whose relief shadows each pixel marches): one
/// light (the baseline), 256 and 1,024 with the parallax material's default 4 shadowed lights,
/// and 256 with one, which shows what the relief shadows of the other three cost.
pub const LIGHT_CASES: [(usize, u32); 4] = [(1, 4), (256, 4), (256, 1), (1024, 4)];

/// The frame phases (the resolve is added on the deferred path).
const FRAME_PHASES: [&str; 3] = ["prepass", "opaque", "post"];

/// The street corner's floor: 6 m square, centred on the origin.
const FLOOR_SIDE: f32 = 6.0;

/// A light that bobs up and down a centimetre from frame to frame (it is culled and uploaded
/// anew every frame: the worst case).
struct Bobbing(f32);

fn bob(world: &mut pom::hecs::World, resources: &mut Resources) {
    let frame = resources
        .get::<pom::Time>()
        .map_or(0, pom::Time::frame_count);
    let lift = 0.01 * (frame % 2) as f32;
    for (transform, bobbing) in world.query_mut::<(&mut Transform, &Bobbing)>() {
        transform.translation.y = bobbing.0 + lift;
    }
}

/// The CPU milliseconds of the Extract and Prepare stages of every frame so far, marked by
/// systems at the end of PostUpdate, Extract and Prepare.
#[derive(Default)]
struct StageTimes {
    post_update_end: Option<Instant>,
    extract_end: Option<Instant>,
    extract: Vec<f64>,
    prepare: Vec<f64>,
}

fn ms_since(from: Option<Instant>) -> f64 {
    from.map_or(0.0, |from| from.elapsed().as_secs_f64() * 1e3)
}

fn end_of_post_update(_: &mut pom::hecs::World, resources: &mut Resources) {
    resources.get_or_default::<StageTimes>().post_update_end = Some(Instant::now());
}

fn end_of_extract(_: &mut pom::hecs::World, resources: &mut Resources) {
    let times = resources.get_or_default::<StageTimes>();
    let extract = ms_since(times.post_update_end);
    times.extract.push(extract);
    times.extract_end = Some(Instant::now());
}

fn end_of_prepare(_: &mut pom::hecs::World, resources: &mut Resources) {
    let times = resources.get_or_default::<StageTimes>();
    let prepare = ms_since(times.extract_end);
    times.prepare.push(prepare);
}

/// The street corner without its sun, lit by `count` point lights in a square grid over its
/// floor (one light: in the middle, reaching the whole floor), at `size`, on `path`.
fn street_corner_at_night(
    size: (u32, u32),
    (count, shadowed_lights): (usize, u32),
    path: RenderPath,
) -> Result<App> {
    let (mut app, scene) = street_corner_app(size, path, |app| {
        app.add_system(Stage::Update, bob)
            .add_system(Stage::PostUpdate, end_of_post_update)
            .add_system(Stage::Extract, end_of_extract)
            .add_system(Stage::Prepare, end_of_prepare);
    })?;
    for light in scene.lights {
        app.world.despawn(light)?;
    }
    for material in app.world.query_mut::<&mut ParallaxOcclusionMaterial>() {
        material.shadowed_lights = shadowed_lights;
    }
    let side = (count as f32).sqrt().ceil().max(1.0) as usize;
    let spacing = FLOOR_SIDE / side as f32;
    for index in 0..count {
        let (i, j) = ((index % side) as f32, (index / side) as f32);
        let height = 0.1 + 0.4 * spacing;
        let x = -FLOOR_SIDE / 2.0 + spacing * (i + 0.5);
        let z = -FLOOR_SIDE / 2.0 + spacing * (j + 0.5);
        let light = PointLight {
            intensity: 500.0 * spacing * spacing,
            // Far enough to reach the neighbours: a pixel sums several lights.
            range: if count == 1 {
                FLOOR_SIDE
            } else {
                1.5 * spacing
            },
            ..PointLight::default()
        };
        app.world.spawn((
            light,
            Transform::from_translation(Vec3::new(x, height, z)),
            Bobbing(height),
        ));
    }
    Ok(app)
}

/// Per phase, its milliseconds in each timed frame with `count` lights; the CPU milliseconds
/// of the Extract and Prepare stages in the same frames; and the path run.
pub fn time(
    size: (u32, u32),
    case: (usize, u32),
    path: RenderPath,
    (warmup, frames): (Warmup, usize),
) -> Result<(&'static str, PhaseTimes, [Vec<f64>; 2])> {
    let mut scene = BenchScene::from_app(street_corner_at_night(size, case, path)?);
    let times = scene.time_phases(warmup, frames, &FRAME_PHASES)?;
    let stages = scene
        .resource::<StageTimes>()
        .context("the stage markers did not run")?;
    let last = |values: &[f64]| values[values.len().saturating_sub(frames)..].to_vec();
    let cpu = [last(&stages.extract), last(&stages.prepare)];
    Ok((scene.path_ran(), times, cpu))
}

impl Runner<'_> {
    /// The street corner's frame with 1, 256 and 1,024 lights (and 256 with one shadowed), and
    /// the CPU stages that cull and upload them.
    pub(super) fn lights(&mut self, size: (u32, u32)) -> Result<()> {
        let place = (size, 1.0);
        let material = self.base.clone();
        let mut frame_ms = Vec::new();
        for (count, shadowed) in LIGHT_CASES {
            let variant = format!(
                "street corner at night, {count} point lights, relief shadows from {shadowed}"
            );
            let (path, times, [extract, prepare]) = time(
                size,
                (count, shadowed),
                self.path,
                (self.warmup, self.frames),
            )?;
            let frame = self.record_phases_and_frame("lights", size, (path, &variant), &times)?;
            frame_ms.push(frame);
            for (stage, times) in [("cpu extract", extract), ("cpu prepare", prepare)] {
                self.record(
                    "lights",
                    place,
                    &material,
                    (path, stage, variant.clone()),
                    &times,
                )?;
            }
        }
        if let [one, many @ ..] = frame_ms.as_slice() {
            for ((count, shadowed), frame) in LIGHT_CASES[1..].iter().zip(many) {
                self.ratio(
                    format!("street corner frame: {count} lights ({shadowed} shadowed) / 1"),
                    size,
                    *frame,
                    *one,
                );
            }
        }
        Ok(())
    }
}
