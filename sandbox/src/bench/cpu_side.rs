//! CPU cost of many parallax entities: propagating their transforms (PostUpdate), and the
//! Extract, Prepare and Render (command recording and submission) stages, timed separately with
//! the CPU clock by marker systems added at the end of Update, PostUpdate, Extract, Prepare and
//! Render. A share of the entities turns every frame, so that
//! Prepare has their transforms to upload (with none moving it uploads nothing after frame 1:
//! the best case). Under TAA the same frames also follow each moving entity's model (its
//! motion for the object motion pass), which the cases with `taa` measure. The entities hold
//! copies of one material, or (the `shared` cases) handles to one material in the app's store,
//! which the Extract stage tells unchanged by its version without reading it.

use std::time::Instant;

use anyhow::{Context, Result};
use pom::glam::{Quat, Vec3};
use pom::shader::Choice;
use pom::{
    AntiAliasing, App, Assets, Camera, DirectionalLight, Image, Mesh, ParallaxOcclusionMaterial,
    PomPlugin, RenderPlugin, Resources, Stage, Transform,
};
use serde::Serialize;

use super::scene::{last_frame_deferred, path_name};
use super::stats::Spread;
use crate::preview_textures::PreviewTextures;

/// Per-stage CPU milliseconds per frame for `entities` parallax entities.
#[derive(Clone, Debug, Serialize)]
pub struct CpuSide {
    /// Entities with a parallax material.
    pub entities: usize,
    /// The percentage of them that move every frame.
    pub moving_percent: u32,
    /// How they move.
    pub motion: Motion,
    /// Whether each holds a copy of the material or a handle to one shared.
    pub materials: Materials,
    /// The camera's anti-aliasing, `off` or `taa` (which follows each moving entity).
    pub anti_aliasing: &'static str,
    /// The path the frames ran, `forward` or `deferred`.
    pub path: &'static str,
    /// The end of Update to the end of PostUpdate: propagating the transforms.
    pub transforms: Spread,
    /// Extract stage.
    pub extract: Spread,
    /// Prepare stage (uploads; after the first frame only per-object data changes).
    pub prepare: Spread,
    /// Render stage: recording the main pass and submitting (GPU timing off).
    pub render: Spread,
    /// Extract, prepare and render together.
    pub total: Spread,
}

#[derive(Default)]
struct StageMarks([Option<Instant>; 5]);

fn mark<const INDEX: usize>(_: &mut pom::hecs::World, resources: &mut Resources) {
    resources.get_or_default::<StageMarks>().0[INDEX] = Some(Instant::now());
}

/// How the moving entities move.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Motion {
    /// Each turns about its vertical axis: its place in the draw order stays.
    Turning,
    /// Each walks back and forth along the view, passing a few neighbours in depth: its place
    /// in the draw order changes (the grid is jittered in depth, so that no two draws tie).
    Walking,
}

impl Motion {
    /// How the report says it: "moving" for turning (the first cases'), "walking".
    pub fn word(self) -> &'static str {
        match self {
            Self::Turning => "moving",
            Self::Walking => "walking",
        }
    }
}

/// How the entities hold their material.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Materials {
    /// Each a copy of its own (a component), compared with last frame's every frame.
    Copies,
    /// Each a handle to one material in `Assets<ParallaxOcclusionMaterial>`.
    Shared,
}

impl Materials {
    /// How the report says it.
    pub fn words(self) -> &'static str {
        match self {
            Self::Copies => "a material each",
            Self::Shared => "one shared material",
        }
    }
}

/// One measured case: the percentage of moving entities, the anti-aliasing, how they move and
/// how they hold their material.
#[derive(Clone, Copy, Debug)]
pub struct Case {
    /// The percentage of entities that move every frame.
    pub moving_percent: u32,
    /// The camera's anti-aliasing.
    pub anti_aliasing: AntiAliasing,
    /// How the moving ones move.
    pub motion: Motion,
    /// How each holds its material.
    pub materials: Materials,
}

const fn case(
    moving_percent: u32,
    anti_aliasing: AntiAliasing,
    motion: Motion,
    materials: Materials,
) -> Case {
    Case {
        moving_percent,
        anti_aliasing,
        motion,
        materials,
    }
}

/// Marks an entity that moves every frame, with where it was spawned.
struct Moving(Vec3);

/// The cases measured: none moving (the best case), a tenth (a game's usual share) and all,
/// without anti-aliasing; then a tenth and all under TAA, which follows every moving entity's
/// model; then a tenth walking; then none, a tenth, and a tenth under TAA with one shared
/// material.
pub const CASES: [Case; 9] = [
    case(0, AntiAliasing::Off, Motion::Turning, Materials::Copies),
    case(10, AntiAliasing::Off, Motion::Turning, Materials::Copies),
    case(100, AntiAliasing::Off, Motion::Turning, Materials::Copies),
    case(10, AntiAliasing::Taa, Motion::Turning, Materials::Copies),
    case(100, AntiAliasing::Taa, Motion::Turning, Materials::Copies),
    case(10, AntiAliasing::Off, Motion::Walking, Materials::Copies),
    case(0, AntiAliasing::Off, Motion::Turning, Materials::Shared),
    case(10, AntiAliasing::Off, Motion::Turning, Materials::Shared),
    case(10, AntiAliasing::Taa, Motion::Turning, Materials::Shared),
];

/// Turns every moving entity to a new angle about its vertical axis, or walks it along the
/// view (every frame differs from the last, so each moving transform is uploaded again).
fn move_entities(world: &mut pom::hecs::World, resources: &mut Resources) {
    let frame = resources
        .get::<pom::Time>()
        .map_or(0, pom::Time::frame_count) as f32;
    let motion = resources
        .get::<Motion>()
        .copied()
        .unwrap_or(Motion::Turning);
    let rotation = Quat::from_rotation_y(frame * 0.01);
    for (transform, moving) in world.query_mut::<(&mut Transform, &Moving)>() {
        match motion {
            Motion::Turning => transform.rotation = rotation,
            // A walker's pace (a fortieth of the grid's spacing a frame at most), out to half
            // the spacing: past a neighbour or two a frame.
            Motion::Walking => {
                transform.translation.z = moving.0.z + 0.5 * (frame * 0.05 + moving.0.x).sin();
            }
        }
    }
}

/// Where entity `index` of a grid `side` entities wide stands: in rows, each entity of a row
/// a little nearer or farther where `jitter`, so that no two share a depth.
fn grid_place(index: usize, side: usize, jitter: bool) -> Vec3 {
    let (x, z) = ((index % side) as f32, (index / side) as f32);
    let offset = if jitter {
        // The golden ratio's fraction spreads the offsets evenly over the row spacing.
        (index as f32 * 0.618_034).fract() - 0.5
    } else {
        0.0
    };
    Vec3::new(x - side as f32 / 2.0, 0.0, z + offset - side as f32 / 2.0)
}

/// Spawns `entities` small planes in a grid under one camera with the case's anti-aliasing,
/// its share of them moving every frame, and times `frames` frames after `warmup` ones,
/// rendered on `path`.
pub fn measure(
    entities: usize,
    Case {
        moving_percent,
        anti_aliasing,
        motion,
        materials,
    }: Case,
    textures: &PreviewTextures,
    path: pom::RenderPath,
    warmup: usize,
    frames: usize,
) -> Result<CpuSide> {
    let mut app = App::new();
    app.add_plugin(
        RenderPlugin::new(256, 256)
            .with_gpu_timing(None)
            .with_path(path),
    );
    app.add_plugin(PomPlugin);
    app.add_system(Stage::PostUpdate, mark::<0>)
        .add_system(Stage::Extract, mark::<1>)
        .add_system(Stage::Prepare, mark::<2>)
        .add_system(Stage::Render, mark::<3>)
        .add_system(Stage::Update, move_entities)
        .add_system(Stage::Update, mark::<4>);
    app.insert_resource(motion);
    app.finish().context("starting the GPU")?;
    let side = (entities as f32).sqrt().ceil().max(1.0) as usize;
    let plane = app
        .resources
        .get_mut::<Assets<Mesh>>()
        .context("the render plugin provides no mesh store")?
        .add(Mesh::plane(0.9));
    let images = app
        .resources
        .get_mut::<Assets<Image>>()
        .context("the render plugin provides no image store")?;
    let material = textures
        .clone()
        .attach(images, ParallaxOcclusionMaterial::default());
    let shared = app
        .resources
        .get_mut::<Assets<ParallaxOcclusionMaterial>>()
        .context("the parallax plugin provides no material store")?
        .add(material.clone());
    for index in 0..entities {
        let place = grid_place(index, side, motion == Motion::Walking);
        let entity = app
            .world
            .spawn((plane.clone(), Transform::from_translation(place)));
        match materials {
            Materials::Copies => app.world.insert_one(entity, material.clone())?,
            Materials::Shared => app.world.insert_one(entity, shared.clone())?,
        }
        // Spread over the grid: entity i moves when the share reaches past it in its hundred.
        if (index % 100) < moving_percent as usize {
            app.world.insert_one(entity, Moving(place))?;
        }
    }
    let extent = side as f32;
    app.world.spawn((
        Camera::perspective(60.0),
        anti_aliasing,
        Transform::from_xyz(0.0, extent, extent).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    app.world.spawn((
        DirectionalLight::default(),
        Transform::IDENTITY.looking_at(Vec3::new(-1.0, -2.0, -1.0), Vec3::Y),
    ));
    // At least one frame, so the renderer has decided the path before timing.
    for _ in 0..warmup.max(1) {
        app.update().context("rendering a warm-up frame")?;
    }
    let deferred = last_frame_deferred(&app);
    let mut stages: [Vec<f64>; 5] = Default::default();
    for _ in 0..frames {
        app.update().context("rendering a timed frame")?;
        let marks = app
            .resources
            .get::<StageMarks>()
            .context("the stage markers did not run")?;
        let [Some(a), Some(b), Some(c), Some(d), Some(updated)] = marks.0 else {
            anyhow::bail!("a stage marker did not run");
        };
        let ms = |from: Instant, to: Instant| to.duration_since(from).as_secs_f64() * 1e3;
        stages[0].push(ms(a, b));
        stages[1].push(ms(b, c));
        stages[2].push(ms(c, d));
        stages[3].push(ms(a, d));
        stages[4].push(ms(updated, a));
    }
    let spread = |values: &[f64]| Spread::of(values).context("no CPU timings");
    Ok(CpuSide {
        entities,
        moving_percent,
        motion,
        materials,
        anti_aliasing: anti_aliasing.name(),
        path: path_name(deferred),
        transforms: spread(&stages[4])?,
        extract: spread(&stages[0])?,
        prepare: spread(&stages[1])?,
        render: spread(&stages[2])?,
        total: spread(&stages[3])?,
    })
}
