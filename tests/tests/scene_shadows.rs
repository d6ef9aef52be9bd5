//! Scene shadows through shadow maps on parallax surfaces: receivers look the map up at the
//! displaced point the march found, casters write the relief's depth, and a lit surface does
//! not shadow itself (no acne) under any light type.

use glam::Vec3;
use pom::{
    App, Assets, Camera, DebugView, DirectionalLight, HeightField, HeightUnits, LightShadows,
    LitMaterial, Mesh, NotShadowCaster, NotShadowReceiver, ParallaxOcclusionMaterial, PointLight,
    SpotLight, TargetFormat, Transform,
};
use pom_tests::pom_scene::{HeightMaterial, pom_app};
use pom_tests::{render_and_capture_f32, render_and_capture_finite};

/// Side of the parallax plane in world units, and texels of its height map across it.
const PLANE: f32 = 2.0;
const TEXELS: u32 = 256;
/// Depth of the step, world units.
const STEP_DEPTH: f32 = 0.3;
/// Height of the bar's underside above the polygon.
const BAR_HEIGHT: f32 = 0.25;
/// The top-down image: 0.01 world units per pixel.
const IMAGE: u32 = 220;
const VIEW_HEIGHT: f32 = 2.2;

fn mesh(app: &mut App, mesh: Mesh) -> pom::Handle<Mesh> {
    app.resources.get_mut::<Assets<Mesh>>().unwrap().add(mesh)
}

/// How the step scene is built (to show what each half of the method contributes).
#[derive(Clone, Copy)]
struct StepScene {
    light_angle_degrees: f32,
    bar_casts: bool,
    floor_receives: bool,
}

/// Scene-shadow visibility of the first light, seen straight down on a parallax floor whose
/// height map is a straight step (upper level for z < 0, `STEP_DEPTH` lower for z > 0), under
/// a thin bar along z floating `BAR_HEIGHT` above the polygon, lit by a sun tilted by the
/// light angle towards +x (parallel to the step's edge, so the step itself casts nothing).
fn step_scene(scene: StepScene) -> image::Rgba32FImage {
    let mut app = pom_app(IMAGE, TargetFormat::Float32).unwrap();
    let step = HeightField::from_fn(TEXELS, TEXELS, |_, v| if v < 0.5 { 1.0 } else { 0.0 });
    let material = ParallaxOcclusionMaterial {
        height_units: HeightUnits::World,
        height_scale: STEP_DEPTH,
        max_samples: 64,
        debug_view: DebugView::SceneShadow,
        ..HeightMaterial {
            field: step,
            height_scale: STEP_DEPTH / PLANE,
        }
        .material(&mut app)
    };
    let floor = mesh(&mut app, Mesh::plane(PLANE));
    let floor = app.world.spawn((floor, material, Transform::IDENTITY));
    if !scene.floor_receives {
        app.world.insert_one(floor, NotShadowReceiver).unwrap();
    }
    let bar = mesh(&mut app, Mesh::cube(1.0));
    let bar = app.world.spawn((
        bar,
        LitMaterial::default(),
        Transform {
            translation: Vec3::new(0.0, BAR_HEIGHT + 0.025, 0.0),
            scale: Vec3::new(0.1, 0.05, 1.8),
            ..Transform::IDENTITY
        },
    ));
    if !scene.bar_casts {
        app.world.insert_one(bar, NotShadowCaster).unwrap();
    }
    let angle = scene.light_angle_degrees.to_radians();
    let to_light = Vec3::new(angle.sin(), angle.cos(), 0.0);
    app.world.spawn((
        DirectionalLight::default(),
        LightShadows {
            softness: 1.0,
            ..LightShadows::default()
        },
        Transform::IDENTITY.looking_at(-to_light, Vec3::Z),
    ));
    app.world.spawn((
        Camera::orthographic(VIEW_HEIGHT),
        Transform::from_xyz(0.0, 3.0, 0.0).looking_at(Vec3::ZERO, Vec3::NEG_Z),
    ));
    render_and_capture_f32(&mut app).unwrap()
}

/// World x of pixel column `x` (the image spans ±VIEW_HEIGHT / 2).
fn world_x(x: f32) -> f32 {
    (x + 0.5) * VIEW_HEIGHT / IMAGE as f32 - VIEW_HEIGHT * 0.5
}

/// The centre (world x) of the shadow stripe along the image row at world z: the middle of
/// its two 0.5 crossings, interpolated between pixels, left of the bar.
fn stripe_centre(image: &image::Rgba32FImage, z: f32) -> Option<f32> {
    let row = ((z + VIEW_HEIGHT * 0.5) / VIEW_HEIGHT * IMAGE as f32) as u32;
    let value = |x: u32| image.get_pixel(x, row).0[0];
    // Only the floor (|x| < 0.98) left of the bar (x < −0.06): the bar itself is drawn lit.
    let column = |x: f32| ((x + VIEW_HEIGHT * 0.5) / VIEW_HEIGHT * IMAGE as f32) as u32;
    let crossings: Vec<f32> = (column(-0.98)..column(-0.06))
        .filter(|&x| (value(x - 1) - 0.5) * (value(x) - 0.5) < 0.0)
        .map(|x| {
            let (a, b) = (value(x - 1), value(x));
            world_x(x as f32 - 1.0 + (a - 0.5) / (a - b))
        })
        .collect();
    match crossings.as_slice() {
        [left, right] => Some(0.5 * (left + right)),
        _ => None,
    }
}

fn measure_step(light_angle_degrees: f32) {
    let image = step_scene(StepScene {
        light_angle_degrees,
        bar_casts: true,
        floor_receives: true,
    });
    assert!(image.pixels().all(|p| p.0.iter().all(|c| c.is_finite())));
    let upper = stripe_centre(&image, -0.5).expect("a stripe on the upper level");
    let lower = stripe_centre(&image, 0.5).expect("a stripe on the lower level");
    let tan = light_angle_degrees.to_radians().tan();
    let texels_per_unit = TEXELS as f32 / PLANE;
    let measured = (upper - lower) * texels_per_unit;
    let expected = STEP_DEPTH * tan * texels_per_unit;
    eprintln!(
        "θL = {light_angle_degrees}°: stripe centres {upper:.4} (upper) and {lower:.4} (lower): \
         shift {measured:.2} texels, depth · tan θL = {expected:.2} texels"
    );
    // The upper level's stripe lies where the bar's shadow meets the polygon.
    assert!(
        (upper + (BAR_HEIGHT + 0.025) * tan).abs() < 0.02,
        "upper stripe at {upper}"
    );
    assert!(
        (measured - expected).abs() <= 0.1 * expected,
        "shift {measured} texels, expected {expected} within 10 %"
    );
}

/// The analytic test of scene shadows: the bar's shadow on the lower level is displaced from its
/// shadow on the upper level by depth · tan θL. Looked up at the polygon instead of the
/// displaced point, both stripes would lie at the same x (shift 0, this fails); with the
/// polygon's flat depth in the map instead of the relief's, the whole lower level would lie
/// below the map's depth and read as shadowed (no stripe to find there: this fails too).
#[test]
fn the_bars_shadow_steps_down_with_the_relief_at_30_degrees() {
    measure_step(30.0);
}

#[test]
fn the_bars_shadow_steps_down_with_the_relief_at_55_degrees() {
    measure_step(55.0);
}

#[test]
fn marked_meshes_neither_cast_nor_receive() {
    let lit_everywhere = |image: &image::Rgba32FImage| {
        let end = (IMAGE as f32 * (0.5 - 0.06 / VIEW_HEIGHT)) as u32;
        (0..IMAGE)
            .flat_map(|y| (0..end).map(move |x| (x, y)))
            .filter(|&(x, y)| {
                let z = (y as f32 + 0.5) * VIEW_HEIGHT / IMAGE as f32 - VIEW_HEIGHT * 0.5;
                world_x(x as f32).abs() < PLANE * 0.5 - 0.02 && z.abs() < PLANE * 0.5 - 0.02
            })
            .map(|(x, y)| (image.get_pixel(x, y).0[0], x, y))
            .fold((f32::INFINITY, 0, 0), |a, b| if b.0 < a.0 { b } else { a })
    };
    for (bar_casts, floor_receives) in [(false, true), (true, false)] {
        let image = step_scene(StepScene {
            light_angle_degrees: 30.0,
            bar_casts,
            floor_receives,
        });
        let (lowest, x, y) = lit_everywhere(&image);
        assert!(
            lowest > 0.99,
            "bar casts {bar_casts}, floor receives {floor_receives}: {lowest} at ({x}, {y})"
        );
    }
}

/// The light types of the acne test, placed at `angle` from the plane's normal.
#[derive(Clone, Copy, Debug)]
enum LightKind {
    Directional,
    Spot,
    Point,
}

/// How deep the lone plane's relief is, and which self-shadow decides what is lit.
#[derive(Clone, Copy)]
struct Relief {
    height_scale: f32,
    self_shadow: pom::ShadowMode,
}

/// Gentle (0.005): no point of it is occluded by its own relief below 80°.
const GENTLE: Relief = Relief {
    height_scale: 0.005,
    self_shadow: pom::ShadowMode::Soft,
};

/// A rolling parallax plane with nothing above it, lit at `angle` by `kind`, seen from 35° off
/// its normal; returns the self-shadow view and the scene-shadow view.
fn lone_plane(
    kind: LightKind,
    angle_degrees: f32,
    relief: Relief,
) -> (image::Rgba32FImage, image::Rgba32FImage) {
    let render = |view: DebugView| {
        let mut app = pom_app(96, TargetFormat::Float32).unwrap();
        let rolling = HeightField::from_fn(256, 256, |u, v| {
            let tau = std::f32::consts::TAU;
            0.5 + 0.25 * ((u * 4.0 * tau).sin() + (v * 4.0 * tau).cos())
        });
        let material = ParallaxOcclusionMaterial {
            debug_view: view,
            shadows: relief.self_shadow,
            ..HeightMaterial {
                field: rolling,
                height_scale: relief.height_scale,
            }
            .material(&mut app)
        };
        let plane = mesh(&mut app, Mesh::plane(PLANE));
        app.world.spawn((plane, material, Transform::IDENTITY));
        let angle = angle_degrees.to_radians();
        let to_light = Vec3::new(angle.sin(), angle.cos(), 0.3 * angle.sin()).normalize();
        let shadows = LightShadows {
            map_size: 512,
            ..LightShadows::default()
        };
        let from_light = |distance: f32| {
            let position = to_light * distance;
            Transform::from_xyz(position.x, position.y, position.z).looking_at(Vec3::ZERO, Vec3::Z)
        };
        match kind {
            LightKind::Directional => {
                app.world.spawn((
                    DirectionalLight::default(),
                    shadows,
                    Transform::IDENTITY.looking_at(-to_light, Vec3::Z),
                ));
            }
            LightKind::Spot => {
                app.world.spawn((
                    SpotLight {
                        range: f32::INFINITY,
                        ..SpotLight::default()
                    },
                    shadows,
                    from_light(4.0),
                ));
            }
            LightKind::Point => {
                app.world.spawn((
                    PointLight {
                        range: f32::INFINITY,
                        ..PointLight::default()
                    },
                    shadows,
                    from_light(4.0),
                ));
            }
        }
        app.world.spawn((
            Camera::perspective(50.0),
            Transform::from_xyz(0.0, 2.6, 1.8).looking_at(Vec3::ZERO, Vec3::Y),
        ));
        render_and_capture_f32(&mut app).unwrap()
    };
    (render(DebugView::Shadow), render(DebugView::SceneShadow))
}

/// No acne: on every pixel the relief's own self-shadowing leaves lit, the shadow maps leave it
/// lit too (visibility ≥ 0.99), for light angles 0–80°: all three light types over a gentle
/// relief, and a sun over a relief four times deeper whose hard (exact) self-shadow march
/// decides what is lit. (Spot and point lights at 80° from the plane's centre reach its far
/// edge beyond 80°, where a deep relief truly occludes itself.)
#[test]
fn a_lit_parallax_plane_does_not_shadow_itself() {
    let deep = Relief {
        height_scale: 0.02,
        self_shadow: pom::ShadowMode::Hard,
    };
    let cases = [
        (LightKind::Directional, GENTLE),
        (LightKind::Spot, GENTLE),
        (LightKind::Point, GENTLE),
        (LightKind::Directional, deep),
    ];
    for (kind, relief) in cases {
        for angle in [0.0, 20.0, 40.0, 60.0, 80.0] {
            let (self_shadow, scene) = lone_plane(kind, angle, relief);
            let finite = |image: &image::Rgba32FImage| {
                image.pixels().all(|p| p.0.iter().all(|c| c.is_finite()))
            };
            assert!(
                finite(&self_shadow) && finite(&scene),
                "{kind:?} at {angle}°: NaN"
            );
            let mut lit = 0;
            let mut worst = 1.0_f32;
            for (own, mapped) in self_shadow.pixels().zip(scene.pixels()) {
                if own.0[..3].iter().all(|&c| c >= 0.999) {
                    lit += 1;
                    worst = worst.min(mapped.0[0]);
                }
            }
            eprintln!("{kind:?} at {angle}°: {lit} lit pixels, lowest visibility {worst:.4}");
            assert!(
                lit > 96 * 96 / 4,
                "{kind:?} at {angle}°: only {lit} lit pixels"
            );
            assert!(worst >= 0.99, "{kind:?} at {angle}°: visibility {worst}");
        }
    }
}

/// Lights a user can place badly: a sun with a zero scale (no direction), a spot pointing
/// straight up, a point light inside the plane, and absurd settings. No NaN, no GPU error.
#[test]
fn badly_placed_lights_and_settings_render_cleanly() {
    let mut app = pom_app(48, TargetFormat::Float32).unwrap();
    let material = HeightMaterial {
        field: pom::patterns::raised_block(64, 0.4),
        height_scale: 0.05,
    }
    .material(&mut app);
    let plane = mesh(&mut app, Mesh::plane(PLANE));
    app.world.spawn((plane, material, Transform::IDENTITY));
    let wild = LightShadows {
        map_size: 0,
        softness: f32::NAN,
        distance: -1.0,
        ..LightShadows::default()
    };
    app.world.spawn((
        DirectionalLight::default(),
        wild,
        Transform {
            scale: Vec3::ZERO,
            ..Transform::IDENTITY
        },
    ));
    app.world.spawn((
        SpotLight::default(),
        LightShadows::default(),
        Transform::from_xyz(0.0, 1.0, 0.0).looking_at(Vec3::new(0.0, 5.0, 0.0), Vec3::Z),
    ));
    app.world.spawn((
        PointLight::default(),
        LightShadows {
            map_size: 64,
            ..LightShadows::default()
        },
        Transform::IDENTITY,
    ));
    app.world.spawn((
        Camera::perspective(50.0),
        Transform::from_xyz(0.0, 2.0, 2.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    if let Err(error) = render_and_capture_finite(&mut app) {
        panic!("{error}");
    }
}

/// Where a spot or point light's map puts a small cube's shadow on a parallax floor: the
/// scene-shadow view, straight down, at the point the ray from the light through the cube's
/// centre meets the floor, and away from it.
fn projected_shadow(light: LightKind, light_at: Vec3, cube_at: Vec3, cube_size: f32) -> (f32, f32) {
    let mut app = pom_app(IMAGE, TargetFormat::Float32).unwrap();
    let rolling = HeightField::from_fn(128, 128, |u, v| {
        0.5 + 0.25
            * ((u * 8.0 * std::f32::consts::PI).sin() + (v * 8.0 * std::f32::consts::PI).cos())
    });
    let material = ParallaxOcclusionMaterial {
        debug_view: DebugView::SceneShadow,
        ..HeightMaterial {
            field: rolling,
            height_scale: 0.005,
        }
        .material(&mut app)
    };
    let floor = mesh(&mut app, Mesh::plane(PLANE));
    app.world.spawn((floor, material, Transform::IDENTITY));
    let cube = mesh(&mut app, Mesh::cube(cube_size));
    app.world.spawn((
        cube,
        LitMaterial::default(),
        Transform::from_xyz(cube_at.x, cube_at.y, cube_at.z),
    ));
    // The floor point behind the cube's centre, seen from the light.
    let t = light_at.y / (light_at.y - cube_at.y);
    let shadow = light_at + (cube_at - light_at) * t;
    let placed =
        Transform::from_xyz(light_at.x, light_at.y, light_at.z).looking_at(shadow, Vec3::Z);
    let shadows = LightShadows {
        map_size: 1024,
        ..LightShadows::default()
    };
    match light {
        LightKind::Spot => app.world.spawn((
            SpotLight {
                range: f32::INFINITY,
                ..SpotLight::default()
            },
            shadows,
            placed,
        )),
        _ => app.world.spawn((
            PointLight {
                range: f32::INFINITY,
                ..PointLight::default()
            },
            shadows,
            placed,
        )),
    };
    app.world.spawn((
        Camera::orthographic(VIEW_HEIGHT),
        Transform::from_xyz(0.0, 3.0, 0.0).looking_at(Vec3::ZERO, Vec3::NEG_Z),
    ));
    let image = render_and_capture_f32(&mut app).unwrap();
    let at = |x: f32, z: f32| {
        let pixel = |w: f32| ((w + VIEW_HEIGHT * 0.5) / VIEW_HEIGHT * IMAGE as f32) as u32;
        image.get_pixel(pixel(x), pixel(z)).0[0]
    };
    // Away from the shadow: the same distance from the light's foot, a quarter turn around it.
    let foot = Vec3::new(light_at.x, 0.0, light_at.z);
    let away = foot + (shadow - foot).cross(Vec3::Y).normalize() * 0.6;
    (at(shadow.x, shadow.z), at(away.x, away.z))
}

/// Positive controls for the perspective maps: a spot's map, a point light's floor face (−Y)
/// and, with the light low over the floor, a side face (−X). Each shadow lies where the light
/// projects its caster, and the floor a quarter turn away stays lit.
#[test]
fn spot_and_point_shadows_fall_where_the_light_projects_the_caster() {
    let cases = [
        (
            LightKind::Spot,
            Vec3::new(1.0, 2.0, 0.0),
            Vec3::new(0.0, 0.5, 0.0),
            0.2,
        ),
        (
            LightKind::Point,
            Vec3::new(1.0, 2.0, 0.0),
            Vec3::new(0.0, 0.5, 0.0),
            0.2,
        ),
        (
            LightKind::Point,
            Vec3::new(0.9, 0.3, 0.0),
            Vec3::new(0.45, 0.2, 0.0),
            0.1,
        ),
    ];
    for (kind, light, cube, size) in cases {
        let (shadowed, lit) = projected_shadow(kind, light, cube, size);
        eprintln!("{kind:?} at {light}: {shadowed:.3} in the shadow, {lit:.3} away from it");
        assert!(
            shadowed < 0.2,
            "{kind:?} at {light}: no shadow ({shadowed})"
        );
        assert!(
            lit > 0.99,
            "{kind:?} at {light}: dark away from the shadow ({lit})"
        );
    }
}
