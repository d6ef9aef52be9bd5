//! The street corner with and without scene shadows: the shadow phase per light type (the
//! scene's sun, a spot and a point light in its place) and the whole frame, phase by phase.

use anyhow::{Context, Result};
use glam::Vec3;
use pom::{
    App, DirectionalLight, GlobalTransform, LightShadows, PointLight, PomPlugin, RenderPath,
    RenderPlugin, SpotLight, TimingMode, Transform,
};

use super::scene::{BenchScene, PhaseTimes, Warmup};
use crate::demo_scene;

/// Which light lights the scene, and whether it casts scene shadows.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ShadowCase {
    /// The scene's sun, no shadow maps.
    Off,
    /// The scene's sun: 3 cascades.
    Directional,
    /// A spot light where the sun comes from, aimed at the scene: one map.
    Spot,
    /// A point light there: six cube faces.
    Point,
}

impl ShadowCase {
    /// Every case, in the order they are reported.
    pub const ALL: [ShadowCase; 4] = [Self::Off, Self::Directional, Self::Spot, Self::Point];

    /// The name in the report.
    pub fn name(self) -> &'static str {
        match self {
            Self::Off => "no shadows",
            Self::Directional => "sun, 3 cascades",
            Self::Spot => "spot, 1 map",
            Self::Point => "point, 6 faces",
        }
    }

    /// The phases a frame of this case runs (and, on the deferred path, the resolve).
    pub fn phases(self) -> &'static [&'static str] {
        match self {
            Self::Off => &["prepass", "opaque", "post"],
            _ => &["prepass", "shadows", "opaque", "post"],
        }
    }
}

/// The street corner at `size`, lit as `case` says, timed, rendered on `path`.
pub fn street_corner(size: (u32, u32), case: ShadowCase, path: RenderPath) -> Result<BenchScene> {
    let mut app = App::new();
    app.add_plugin(
        RenderPlugin::new(size.0, size.1)
            .with_gpu_timing(Some(TimingMode::Blocking))
            .with_path(path),
    )
    .add_plugin(PomPlugin);
    app.finish().context("starting the GPU")?;
    // The scene embedded in the binary: the bench runs from any folder.
    let scene = demo_scene::spawn(&mut app)?;
    let sun = *scene
        .lights
        .first()
        .context("the street corner has no light")?;
    let (low, high) = scene
        .framing_bounds
        .context("the street corner has no meshes")?;
    let centre = (low + high) * 0.5;
    let radius = (high - low).length() * 0.5;
    let towards_light = -app
        .world
        .get::<&GlobalTransform>(sun)
        .map(|transform| transform.forward())
        .unwrap_or(Vec3::NEG_Y);
    // The point lights stand where the sun comes from, two scene radii away, as bright on the
    // scene as the sun (candela = lux × distance²).
    let distance = 2.0 * radius;
    let position = centre + towards_light * distance;
    let intensity = DirectionalLight::default().intensity * distance * distance;
    let placed =
        Transform::from_xyz(position.x, position.y, position.z).looking_at(centre, Vec3::Y);
    match case {
        ShadowCase::Off => {}
        ShadowCase::Directional => app.world.insert_one(sun, LightShadows::default())?,
        ShadowCase::Spot | ShadowCase::Point => {
            app.world.despawn(sun)?;
            let shadows = LightShadows::default();
            if case == ShadowCase::Spot {
                let spot = SpotLight {
                    intensity,
                    range: f32::INFINITY,
                    outer_angle: (radius / distance).atan() * 1.3,
                    ..SpotLight::default()
                };
                app.world.spawn((spot, shadows, placed));
            } else {
                let point = PointLight {
                    intensity,
                    range: f32::INFINITY,
                    ..PointLight::default()
                };
                app.world.spawn((point, shadows, placed));
            }
        }
    }
    Ok(BenchScene::from_app(app))
}

/// Per phase of `case` asked to run on `path`, its milliseconds in each timed frame; and the
/// path the frames ran ([`BenchScene::path_ran`]).
pub fn time(
    size: (u32, u32),
    case: ShadowCase,
    path: RenderPath,
    warmup: Warmup,
    frames: usize,
) -> Result<(&'static str, PhaseTimes)> {
    let mut scene = street_corner(size, case, path)?;
    let phases = scene.time_phases(warmup, frames, case.phases())?;
    Ok((scene.path_ran(), phases))
}
