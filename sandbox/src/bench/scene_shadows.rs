//! The street corner with and without scene shadows: the shadow phase per light type (the
//! scene's sun, a spot and a point light in its place) and the whole frame, phase by phase, each
//! light type against itself without shadows.

use anyhow::{Context, Result};
use glam::Vec3;
use pom::{
    App, DirectionalLight, GlobalTransform, LightShadows, PointLight, PomPlugin, RenderPath,
    RenderPlugin, SpotLight, TimingMode, Transform,
};

use super::Runner;
use super::scene::{BenchScene, PhaseTimes, Warmup};
use crate::demo_scene;

/// The light that lights the street corner.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ShadowLight {
    /// The scene's sun: 3 cascades.
    Sun,
    /// The scene's sun turning a little every frame: its cascades are drawn every frame (the
    /// still sun's are kept from frame to frame).
    MovingSun,
    /// A spot light where the sun comes from, aimed at the scene: one map.
    Spot,
    /// A point light there: six cube faces.
    Point,
}

/// Which light lights the scene, and whether it casts scene shadows. Each light type is timed
/// without shadows too: its own baseline (a spot or point light shades differently from the
/// sun even without maps).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ShadowCase {
    /// The light.
    pub light: ShadowLight,
    /// Whether it casts scene shadows.
    pub shadows: bool,
}

impl ShadowCase {
    /// Every case, in the order they are reported: each light without shadows, then with.
    pub const ALL: [ShadowCase; 7] = {
        const fn case(light: ShadowLight, shadows: bool) -> ShadowCase {
            ShadowCase { light, shadows }
        }
        [
            case(ShadowLight::Sun, false),
            case(ShadowLight::Sun, true),
            case(ShadowLight::Spot, false),
            case(ShadowLight::Spot, true),
            case(ShadowLight::Point, false),
            case(ShadowLight::Point, true),
            case(ShadowLight::MovingSun, true),
        ]
    };

    /// The name in the report.
    pub fn name(self) -> &'static str {
        match (self.light, self.shadows) {
            (ShadowLight::Sun, false) => "sun, no shadows",
            (ShadowLight::Sun, true) => "sun, 3 cascades",
            (ShadowLight::Spot, false) => "spot, no shadows",
            (ShadowLight::Spot, true) => "spot, 1 map",
            (ShadowLight::Point, false) => "point, no shadows",
            (ShadowLight::Point, true) => "point, 6 faces",
            (ShadowLight::MovingSun, false) => "moving sun, no shadows",
            (ShadowLight::MovingSun, true) => "moving sun, 3 cascades",
        }
    }

    /// The phases a frame of this case runs (and, on the deferred path, the resolve).
    pub fn phases(self) -> &'static [&'static str] {
        if self.shadows {
            &["prepass", "shadows", "opaque", "post"]
        } else {
            &["prepass", "opaque", "post"]
        }
    }
}

/// The street corner at `size`, lit as `case` says, timed, rendered on `path`.
pub fn street_corner(size: (u32, u32), case: ShadowCase, path: RenderPath) -> Result<BenchScene> {
    let (mut app, scene) = street_corner_app(size, path, |_| {})?;
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
    let shadows = case.shadows.then(LightShadows::default);
    match case.light {
        ShadowLight::Sun | ShadowLight::MovingSun => {
            if let Some(shadows) = shadows {
                app.world.insert_one(sun, shadows)?;
            }
            if case.light == ShadowLight::MovingSun {
                app.add_system(pom::Stage::Update, turn_the_sun);
            }
        }
        ShadowLight::Spot | ShadowLight::Point => {
            app.world.despawn(sun)?;
            let light = if case.light == ShadowLight::Spot {
                let spot = SpotLight {
                    intensity,
                    range: f32::INFINITY,
                    outer_angle: (radius / distance).atan() * 1.3,
                    ..SpotLight::default()
                };
                app.world.spawn((spot, placed))
            } else {
                let point = PointLight {
                    intensity,
                    range: f32::INFINITY,
                    ..PointLight::default()
                };
                app.world.spawn((point, placed))
            };
            if let Some(shadows) = shadows {
                app.world.insert_one(light, shadows)?;
            }
        }
    }
    Ok(BenchScene::from_app(app))
}

/// Turns every directional light a tenth of a degree about the vertical.
fn turn_the_sun(world: &mut pom::hecs::World, _: &mut pom::Resources) {
    let turn = glam::Quat::from_rotation_y(0.1_f32.to_radians());
    for (transform, _) in world.query_mut::<(&mut Transform, &DirectionalLight)>() {
        transform.rotation = turn * transform.rotation;
    }
}

/// The street corner embedded in the binary (the bench runs from any folder) in an app that
/// times its GPU passes, `size` pixels on `path`; `before_start` adds what a case needs before
/// the GPU starts.
pub fn street_corner_app(
    size: (u32, u32),
    path: RenderPath,
    before_start: impl FnOnce(&mut App),
) -> Result<(App, pom::GltfScene)> {
    let mut app = App::new();
    app.add_plugin(
        RenderPlugin::new(size.0, size.1)
            .with_gpu_timing(Some(TimingMode::Blocking))
            .with_path(path),
    )
    .add_plugin(PomPlugin);
    before_start(&mut app);
    app.finish().context("starting the GPU")?;
    let scene = demo_scene::spawn(&mut app)?;
    Ok((app, scene))
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

impl Runner<'_> {
    /// The street corner per light type with scene shadows and without: each phase, and the
    /// frame (their sum).
    pub(super) fn scene_shadows(&mut self, size: (u32, u32)) -> Result<()> {
        // Each light type's frame without shadows, its baseline (ALL lists it first; the
        // moving sun's is the still sun's).
        let mut frames_without = Vec::new();
        for case in ShadowCase::ALL {
            let (path, times) = time(size, case, self.path, self.warmup, self.frames)?;
            let frame_ms =
                self.record_phases_and_frame("scene_shadows", size, (path, case.name()), &times)?;
            let baseline_light = match case.light {
                ShadowLight::MovingSun => ShadowLight::Sun,
                light => light,
            };
            if !case.shadows {
                frames_without.push((case, frame_ms));
                continue;
            }
            let Some(&(baseline, without)) = frames_without
                .iter()
                .find(|(baseline, _)| baseline.light == baseline_light)
            else {
                anyhow::bail!("{} was timed before its baseline", case.name());
            };
            let what = format!("street corner frame: {} / {}", case.name(), baseline.name());
            self.ratio(what, size, frame_ms, without);
        }
        Ok(())
    }
}
