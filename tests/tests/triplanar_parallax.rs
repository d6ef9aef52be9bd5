//! Triplanar parallax on the GPU: on a cube whose faces carry the texture the way the
//! projections do it draws what texture coordinates draw; on a sphere without texture
//! coordinates the relief shifts by its depth and the projections meet without a seam; both
//! paths.

use glam::{Vec2, Vec3};
use image::{Rgba32FImage, RgbaImage};
use pom::{
    App, Assets, Camera, DebugView, DirectionalLight, HeightField, Mesh, ParallaxMethod,
    ParallaxOcclusionMaterial, RenderPath, ShadowMode, TargetFormat, TextureMapping, Transform,
};
use pom_tests::pom_scene::{HeightMaterial, pom_app, set_material, wrapped};
use pom_tests::{render_on_path, render_on_path_f32};

const SIZE: u32 = 384;
/// World units the orthographic cameras show vertically.
const VIEW_HEIGHT: f32 = 2.0;

/// Round bumps, four by four across a repeat, with a normal map from their slopes.
fn bumps(height_scale: f32) -> HeightMaterial {
    HeightMaterial {
        field: HeightField::from_fn(128, 128, |u, v| {
            let (x, y) = ((u * 4.0).fract() * 2.0 - 1.0, (v * 4.0).fract() * 2.0 - 1.0);
            (1.0 - (x * x + y * y)).max(0.0).sqrt()
        }),
        height_scale,
    }
}

/// An app with `mesh` under `material` at `at`, an orthographic camera looking from `eye`
/// towards `target`, and two suns: one over the +X, +Y, +Z side, one over the other.
fn scene(
    mesh: Mesh,
    at: Vec3,
    format: TargetFormat,
    eye: Vec3,
    target: Vec3,
    material: impl FnOnce(&mut App) -> ParallaxOcclusionMaterial,
) -> App {
    let mut app = pom_app(SIZE, format).expect("app");
    let material = material(&mut app);
    let mesh = app
        .resources
        .get_mut::<Assets<Mesh>>()
        .expect("meshes")
        .add(mesh);
    app.world
        .spawn((mesh, material, Transform::from_translation(at)));
    for towards_light in [Vec3::new(0.6, 1.0, 0.8), Vec3::new(-0.7, -1.0, -0.5)] {
        app.world.spawn((
            DirectionalLight::default(),
            Transform::IDENTITY.looking_at(-towards_light, Vec3::Z),
        ));
    }
    app.world.spawn((
        Camera::orthographic(VIEW_HEIGHT),
        Transform::from_translation(eye).looking_at(target, Vec3::Y),
    ));
    app
}

/// The view ray of pixel (`x`, `y`) of the orthographic camera at `eye` looking at `target`
/// (up +Y): its origin on the camera's plane and its direction.
fn pixel_ray(eye: Vec3, target: Vec3, x: u32, y: u32) -> (Vec3, Vec3) {
    let forward = (target - eye).normalize();
    let right = forward.cross(Vec3::Y).normalize();
    let up = right.cross(forward);
    let half = VIEW_HEIGHT * 0.5;
    let ndc = Vec2::new(
        (x as f32 + 0.5) / SIZE as f32 * 2.0 - 1.0,
        1.0 - (y as f32 + 0.5) / SIZE as f32 * 2.0,
    );
    (eye + right * ndc.x * half + up * ndc.y * half, forward)
}

/// The face of the unit cube [0, 1]³ that pixel (`x`, `y`) shows (its outward normal), if it
/// shows one at least `margin` world units inside its edges.
fn cube_face(eye: Vec3, target: Vec3, x: u32, y: u32, margin: f32) -> Option<Vec3> {
    let (origin, direction) = pixel_ray(eye, target, x, y);
    let (mut near, mut far, mut face) = (f32::NEG_INFINITY, f32::INFINITY, Vec3::ZERO);
    for axis in 0..3 {
        let (o, d) = (origin[axis], direction[axis]);
        let (t0, t1) = ((0.0 - o) / d, (1.0 - o) / d);
        let (enter, leave) = (t0.min(t1), t0.max(t1));
        if enter > near {
            near = enter;
            face = Vec3::ZERO;
            face[axis] = -d.signum();
        }
        far = far.min(leave);
    }
    if near > far {
        return None;
    }
    let point = origin + direction * near;
    let inside = (0..3)
        .filter(|&axis| face[axis] == 0.0)
        .all(|axis| point[axis] > margin && point[axis] < 1.0 - margin);
    inside.then_some(face)
}

/// `image` with every pixel but those `keep` keeps black.
fn masked(image: &RgbaImage, keep: impl Fn(u32, u32) -> bool) -> RgbaImage {
    RgbaImage::from_fn(image.width(), image.height(), |x, y| {
        if keep(x, y) {
            *image.get_pixel(x, y)
        } else {
            image::Rgba([0, 0, 0, 255])
        }
    })
}

#[test]
fn triplanar_parallax_matches_uv_parallax_on_every_face_of_a_cube() {
    // The unit cube spans [0, 1]³ and a repeat spans one unit: every projection's coordinate
    // at a face's edge is whole, so each face shows the texture exactly as its texture
    // coordinates lay it (`reference::triplanar_uvs` and `Mesh::cube` agree on the orientation).
    let centre = Vec3::splat(0.5);
    for path in [RenderPath::Forward, RenderPath::Deferred] {
        for eye in [Vec3::new(3.0, 2.5, 2.0), Vec3::new(-2.0, -3.0, -2.5)] {
            let mut app = scene(
                Mesh::cube(1.0),
                centre,
                TargetFormat::Srgb8,
                eye,
                centre,
                |app| ParallaxOcclusionMaterial {
                    shadows: ShadowMode::Soft,
                    lod_threshold: 16.0,
                    ..bumps(0.08).material(app)
                },
            );
            let uv = render_on_path(&mut app, path).expect("uv render");
            set_material(&mut app, |material| {
                material.mapping = TextureMapping::Triplanar
            });
            let triplanar = render_on_path(&mut app, path).expect("triplanar render");
            let margin = 2.0 * VIEW_HEIGHT / SIZE as f32;
            for face in [Vec3::X, Vec3::Y, Vec3::Z].map(|axis| axis * (eye - centre).signum()) {
                let on_face = |x, y| cube_face(eye, centre, x, y, margin) == Some(face);
                let pixels = (0..SIZE * SIZE)
                    .filter(|i| on_face(i % SIZE, i / SIZE))
                    .count();
                assert!(pixels > 2000, "{face}: {pixels} pixels");
                let comparison =
                    pom::flip_compare(&masked(&uv, on_face), &masked(&triplanar, on_face), 0.99)
                        .expect("same size");
                // The masked pixels agree: the mean over the face is the image's over its share.
                let face_mean = comparison.mean * (SIZE * SIZE) as f32 / pixels as f32;
                eprintln!("{path:?}, face {face}: FLIP mean {face_mean:.5} over {pixels} pixels");
                assert!(
                    face_mean <= 0.01,
                    "{path:?}, face {face}: FLIP mean {face_mean}"
                );
            }
        }
    }
}

/// Where the view ray of pixel (`x`, `y`) meets the sphere of `radius` about the origin, and
/// its normal there.
fn sphere_hit(eye: Vec3, x: u32, y: u32, radius: f32) -> Option<(Vec3, Vec3)> {
    let (origin, direction) = pixel_ray(eye, Vec3::ZERO, x, y);
    let along = -origin.dot(direction);
    let closest = origin + direction * along;
    let inside = radius * radius - closest.length_squared();
    (inside > 0.0).then(|| {
        let point = closest - direction * inside.sqrt();
        (point, point / radius)
    })
}

/// A sphere without texture coordinates.
fn bare_sphere() -> Mesh {
    Mesh {
        uvs: Vec::new(),
        tangents: Vec::new(),
        ..Mesh::uv_sphere(0.8, 96, 48)
    }
}

#[test]
fn the_relief_of_a_sphere_without_uvs_shifts_by_its_depth() {
    // A flat floor at the deepest height: every view ray ends at the full depth, shifted
    // height_scale · tan θ along the surface away from the eye.
    let (height_scale, scale) = (0.05, 0.5);
    let eye = Vec3::new(0.0, 0.0, 4.0);
    let floor = HeightMaterial {
        field: HeightField::from_fn(4, 4, |_, _| 0.0),
        height_scale,
    };
    for path in [RenderPath::Forward, RenderPath::Deferred] {
        let mut app = scene(
            bare_sphere(),
            Vec3::ZERO,
            TargetFormat::Float32,
            eye,
            Vec3::ZERO,
            |app| ParallaxOcclusionMaterial {
                mapping: TextureMapping::Triplanar,
                triplanar_scale: scale,
                method: ParallaxMethod::NormalMapping,
                debug_view: DebugView::Uv,
                shadows: ShadowMode::Off,
                lod_threshold: 16.0,
                ..floor.material(app)
            },
        );
        let entry = render_on_path_f32(&mut app, path).expect("entry");
        set_material(&mut app, |material| {
            material.method = ParallaxMethod::Occlusion
        });
        let hit = render_on_path_f32(&mut app, path).expect("hit");
        let (mut checked, mut worst, mut largest) = (0, 0.0_f32, 0.0_f32);
        for (x, y) in (0..SIZE).flat_map(|y| (0..SIZE).map(move |x| (x, y))) {
            let Some((_, normal)) = sphere_hit(eye, x, y, 0.8) else {
                continue;
            };
            // Where the projection along Z is clearly the largest, 60° or nearer the view.
            if normal.z < 0.5 || normal.z - normal.x.abs().max(normal.y.abs()) < 0.1 {
                continue;
            }
            let to_eye = Vec3::Z;
            let sideways = to_eye - normal * normal.dot(to_eye);
            let shift = if sideways.length() < 1e-6 {
                Vec3::ZERO
            } else {
                -sideways.normalize() * sideways.length() / normal.dot(to_eye) * height_scale
            };
            // The projection along +Z: u along +x, v down −y.
            let expected = Vec2::new(shift.x, -shift.y);
            let uv = |image: &Rgba32FImage| {
                let p = image.get_pixel(x, y).0;
                Vec2::new(p[0], p[1])
            };
            let (before, after) = (uv(&entry), uv(&hit));
            let seen = Vec2::new(wrapped(after.x - before.x), wrapped(after.y - before.y));
            worst = worst.max((seen - expected).length() / height_scale);
            largest = largest.max(shift.length());
            checked += 1;
        }
        eprintln!(
            "{path:?}: {checked} pixels, shifts up to {largest:.4} texture units along the surface, worst error {worst:.4} of the depth"
        );
        assert!(checked > 5000, "{checked}");
        assert!(largest > height_scale, "{largest}");
        assert!(
            worst < 0.05,
            "{path:?}: the shift is off by {worst} of the depth"
        );
    }
}

/// Linear luminance of a float pixel.
fn luminance(image: &Rgba32FImage, x: u32, y: u32) -> f32 {
    let [r, g, b, _] = image.get_pixel(x, y).0;
    0.2126 * r + 0.7152 * g + 0.0722 * b
}

/// The lit relief of the sphere over the same sphere lit plain, per pixel, seen from `eye`: the
/// ratio takes the light's fall-off out. Averaged over `phases` renders with the sphere and
/// camera moved together by parts of a repeat, so that the texture lies differently on the
/// same image each time and the average holds the mix's effect rather than where bumps fall.
fn relief_over_plain(eye: Vec3, scale: f32, phases: u32, path: RenderPath) -> Vec<f32> {
    let mut sum = vec![0.0; (SIZE * SIZE) as usize];
    for phase in 0..phases {
        // Steps of irrational parts of a bump (a quarter repeat) along each axis.
        let shift = Vec3::new(0.618, 0.414, 0.732) * phase as f32 * scale / 4.0;
        let mut app = scene(
            bare_sphere(),
            shift,
            TargetFormat::Float32,
            eye + shift,
            shift,
            |app| {
                ParallaxOcclusionMaterial {
                    mapping: TextureMapping::Triplanar,
                    triplanar_scale: scale,
                    shadows: ShadowMode::Soft,
                    lod_threshold: 16.0,
                    // Diffuse light only: a highlight on the plain sphere would not divide out.
                    specular_strength: 0.0,
                    ..bumps(0.06).material(app)
                }
            },
        );
        let relief = render_on_path_f32(&mut app, path).expect("relief");
        set_material(&mut app, |material| {
            material.height_scale = 0.0;
            material.normal_map = None;
        });
        let plain = render_on_path_f32(&mut app, path).expect("plain");
        for (index, (x, y)) in (0..SIZE)
            .flat_map(|y| (0..SIZE).map(move |x| (x, y)))
            .enumerate()
        {
            sum[index] +=
                luminance(&relief, x, y) / luminance(&plain, x, y).max(1e-4) / phases as f32;
        }
    }
    sum
}

#[test]
fn projections_meet_on_a_sphere_without_a_seam() {
    // Along the lines where two projections share the surface equally, a wrongly mixed normal or
    // a flattened relief would brighten or darken the relief against the plain sphere.
    for path in [RenderPath::Forward, RenderPath::Deferred] {
        for (a, b, c) in [(0, 1, 2), (1, 2, 0), (0, 2, 1)] {
            // Looking at the meeting line of projections a and b from across it.
            let mut eye = Vec3::ZERO;
            (eye[a], eye[b], eye[c]) = (2.0, 2.0, 0.6);
            let ratios = relief_over_plain(eye, 0.25, 8, path);
            // Compared band by band along the line (by the third axis's component), so that
            // the light's change along it weighs the same on the line and beside it.
            let bands = 20;
            let (mut line, mut around) = (vec![(0.0, 0); bands], vec![(0.0, 0); bands]);
            let to_light = Vec3::new(0.6, 1.0, 0.8).normalize();
            for (index, (x, y)) in (0..SIZE)
                .flat_map(|y| (0..SIZE).map(move |x| (x, y)))
                .enumerate()
            {
                let Some((_, normal)) = sphere_hit(eye, x, y, 0.8) else {
                    continue;
                };
                // Not at the outline, nor near the light's terminator.
                if normal.dot(eye.normalize()) < 0.3 || normal.dot(to_light) < 0.3 {
                    continue;
                }
                let band = (((normal[c] + 1.0) * 0.5 * bands as f32) as usize).min(bands - 1);
                let across = (normal[a].abs() - normal[b].abs()).abs();
                let add = |sums: &mut Vec<(f32, u32)>| {
                    sums[band].0 += ratios[index];
                    sums[band].1 += 1;
                };
                if across < 0.02 {
                    add(&mut line);
                } else if (0.08..0.16).contains(&across) {
                    add(&mut around);
                }
            }
            let (mut seam, mut counted, mut beside_count) = (0.0, 0, 0);
            for (on, off) in line.iter().zip(&around) {
                if on.1 >= 10 && off.1 >= 20 {
                    seam += (on.0 / on.1 as f32) / (off.0 / off.1 as f32) * on.1 as f32;
                    counted += on.1;
                    beside_count += off.1;
                }
            }
            let seam = seam / counted.max(1) as f32 - 1.0;
            eprintln!(
                "{path:?}, projections {a} and {b}: on their meeting line ({counted} pixels) {:+.2} % against beside it ({beside_count} pixels)",
                seam * 100.0
            );
            assert!(
                counted > 300 && beside_count > 1000,
                "{counted} {beside_count}"
            );
            assert!(
                seam.abs() <= 0.02,
                "{path:?}: the seam of projections {a} and {b} differs by {seam}"
            );
        }
    }
}

#[test]
fn a_mesh_without_normals_under_triplanar_mapping_is_warned_about_once() {
    let warned = |mesh: Mesh| {
        let mut app = scene(
            mesh,
            Vec3::ZERO,
            TargetFormat::Srgb8,
            Vec3::splat(3.0),
            Vec3::ZERO,
            |app| ParallaxOcclusionMaterial {
                mapping: TextureMapping::Triplanar,
                ..bumps(0.05).material(app)
            },
        );
        for _ in 0..2 {
            pom_tests::render_and_capture(&mut app).expect("renders");
        }
        app.resources
            .get::<pom::TriplanarMeshWarnings>()
            .map_or(0, pom::TriplanarMeshWarnings::len)
    };
    assert_eq!(
        warned(bare_sphere()),
        0,
        "texture coordinates are not needed"
    );
    let without_normals = Mesh {
        normals: Vec::new(),
        ..bare_sphere()
    };
    assert_eq!(warned(without_normals), 1);
}

#[test]
fn golden_boulder_of_cobblestones_without_uvs_on_both_paths() {
    // A sphere without texture coordinates, cobblestones projected on it along the three axes,
    // lit from above and the side with soft self-shadows: both paths agree and match the
    // reference.
    let eye = Vec3::new(2.4, 1.6, 3.0);
    let mut app = scene(
        bare_sphere(),
        Vec3::ZERO,
        TargetFormat::Srgb8,
        eye,
        Vec3::ZERO,
        |app| {
            let cobbles = HeightMaterial {
                field: pom::patterns::cobblestones(128, 4),
                height_scale: 0.05,
            };
            ParallaxOcclusionMaterial {
                mapping: TextureMapping::Triplanar,
                triplanar_scale: 0.6,
                triplanar_sharpness: 6.0,
                shadows: ShadowMode::Soft,
                ..cobbles.material(app)
            }
        },
    );
    let image = pom_tests::render_both_paths(&mut app, "triplanar_boulder").expect("paths agree");
    pom_tests::check_golden(
        "triplanar_boulder",
        &image,
        pom_tests::FlipTolerance::default(),
    )
    .expect("matches the reference");
}

#[test]
fn a_triplanar_relief_shadows_itself_through_the_shadow_map_as_uv_parallax_does() {
    // The unit cube under a low sun with scene shadows, its faces raised in deep bumps that
    // shadow each other through the shadow map (the casters' depth is the relief's): the
    // shadow-map visibility on the cube is the same whether the relief comes by its texture
    // coordinates or by the projections, and differs from a flat cube's.
    let centre = Vec3::splat(0.5);
    let eye = Vec3::new(3.0, 2.5, 2.0);
    let shadow_of = |configure: &dyn Fn(&mut ParallaxOcclusionMaterial), path: RenderPath| {
        let mut app = scene(
            Mesh::cube(1.0),
            centre,
            TargetFormat::Float32,
            eye,
            centre,
            |app| {
                let mut material = ParallaxOcclusionMaterial {
                    shadows: ShadowMode::Off,
                    lod_threshold: 16.0,
                    debug_view: DebugView::SceneShadow,
                    ..bumps(0.15).material(app)
                };
                configure(&mut material);
                material
            },
        );
        let lights: Vec<pom::hecs::Entity> = app
            .world
            .query::<(pom::hecs::Entity, &DirectionalLight)>()
            .iter()
            .map(|(entity, _)| entity)
            .collect();
        for light in lights {
            let shadows = pom::LightShadows {
                map_size: 2048,
                softness: 0.0,
                ..pom::LightShadows::default()
            };
            app.world.insert_one(light, shadows).expect("the light");
        }
        render_on_path_f32(&mut app, path).expect("render")
    };
    let difference = |a: &Rgba32FImage, b: &Rgba32FImage| {
        a.pixels()
            .zip(b.pixels())
            .filter(|(p, q)| (p.0[0] - q.0[0]).abs() > 0.25)
            .count()
    };
    for path in [RenderPath::Forward, RenderPath::Deferred] {
        let uv = shadow_of(&|_| {}, path);
        let triplanar = shadow_of(
            &|material| material.mapping = TextureMapping::Triplanar,
            path,
        );
        let flat = shadow_of(
            &|material| material.method = ParallaxMethod::NormalMapping,
            path,
        );
        let (apart, relief) = (difference(&uv, &triplanar), difference(&uv, &flat));
        eprintln!(
            "{path:?}: triplanar's shadow-map visibility differs from uv's at {apart} pixels, the flat cube's at {relief}"
        );
        assert!(
            relief > 300,
            "the relief shows in the shadow map: {relief} pixels"
        );
        assert!(apart * 20 < relief, "{apart} of {relief}");
    }
}
