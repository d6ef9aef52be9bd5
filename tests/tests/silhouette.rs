//! The outline of parallax surfaces (`silhouette`): with `uv_bounds`, a view ray that leaves
//! the texture's bounds before it meets the relief leaves the surface, so the outline of a
//! cube's face drops where its rim is low, on both paths, in the shadow maps too, without
//! NaN or speckle at any angle.

use glam::Vec3;
use pom::preview::{PreviewProjection, PreviewShape, PreviewView};
use pom::{
    App, Assets, Camera, DebugView, DirectionalLight, LightShadows, Mesh,
    ParallaxOcclusionMaterial, Projection, RenderPath, ShadowMode, Silhouette, TargetFormat,
    Transform, patterns,
};
use pom_tests::pom_scene::{HeightMaterial, pom_app, preview_app};
use pom_tests::{FlipTolerance, check_golden, render_both_paths, render_on_path_f32};

const SIZE: u32 = 128;
/// Depth of the rim below the block's top, texture units (the cube's faces are one unit).
const HEIGHT_SCALE: f32 = 0.1;

/// A raised block (its top at the surface) in the middle of each face, on a rim at the
/// deepest height.
fn blocks() -> HeightMaterial {
    HeightMaterial {
        field: patterns::raised_block(128, 0.4),
        height_scale: HEIGHT_SCALE,
    }
}

/// The preview cube seen `view_angle` degrees from its top face's normal, orthographic.
fn cube_view(view_angle: f32) -> PreviewView {
    PreviewView {
        view_angle,
        shape: PreviewShape::Cube,
        ..PreviewView::default()
    }
}

/// The raw `uv` view of the cube with `silhouette`, on `path`: blue is 1 on every marched
/// pixel, which tells the surface from the background.
fn cube_uv(view_angle: f32, silhouette: Silhouette, path: RenderPath) -> image::Rgba32FImage {
    let mut app = preview_app(
        SIZE,
        TargetFormat::Float32,
        &blocks(),
        &cube_view(view_angle),
        |material| ParallaxOcclusionMaterial {
            silhouette,
            debug_view: DebugView::Uv,
            shadows: ShadowMode::Off,
            lod_threshold: 16.0,
            ..material
        },
    )
    .unwrap();
    rendered_finite(&mut app, path, &format!("{view_angle}° {silhouette:?}"))
}

/// The next frame of `app` on `path`, checked for NaN and infinite pixels.
fn rendered_finite(app: &mut App, path: RenderPath, what: &str) -> image::Rgba32FImage {
    let image = render_on_path_f32(app, path).unwrap();
    assert!(
        image.pixels().all(|p| p.0.iter().all(|c| c.is_finite())),
        "{what} {path:?}: a NaN or infinite pixel"
    );
    image
}

fn is_surface(image: &image::Rgba32FImage, x: u32, y: u32) -> bool {
    image.get_pixel(x, y).0[2] == 1.0
}

/// The first row from the top that shows the surface in column `x`.
fn top_of_surface(image: &image::Rgba32FImage, x: u32) -> Option<u32> {
    (0..image.height()).find(|&y| is_surface(image, x, y))
}

#[test]
fn uv_bounds_drops_the_outline_of_a_cube_face_by_the_relief_depth() {
    let angle = 60.0_f32;
    let (camera, _) = cube_view(angle).camera(1.0);
    let Projection::Orthographic { height, .. } = camera.projection else {
        panic!("the preview cube is orthographic");
    };
    let pixels_per_unit = SIZE as f32 / height;
    let (sin, cos) = angle.to_radians().sin_cos();
    // The top face's far edge (u = 1) lies 0.5 cos θ + 0.5 sin θ above the image's centre.
    let edge_row = SIZE as f32 * 0.5 - (0.5 * cos + 0.5 * sin) * pixels_per_unit;
    // A ray entering the face at u reaches the rim's depth H at u + H tan θ: the last ray that
    // meets the rim inside the face enters H tan θ before the edge, which the view foreshortens
    // by cos θ.
    let expected_drop = HEIGHT_SCALE * angle.to_radians().tan() * cos * pixels_per_unit;
    // The middle column crosses the block's centre, and the rim beyond it.
    let column = SIZE / 2;
    for path in [RenderPath::Forward, RenderPath::Deferred] {
        let off = cube_uv(angle, Silhouette::Off, path);
        let clipped = cube_uv(angle, Silhouette::UvBounds, path);
        let off_top = top_of_surface(&off, column).expect("the cube") as f32;
        let clipped_top = top_of_surface(&clipped, column).expect("the clipped cube") as f32;
        let drop = clipped_top - off_top;
        eprintln!(
            "{path:?}: outline at row {off_top} (the cube's edge at {edge_row:.2}), clipped at \
             {clipped_top}: dropped {drop} px, H tan θ cos θ = {expected_drop:.2} px"
        );
        // Row y covers edge rows in [y, y + 1).
        assert!(
            (off_top + 0.5 - edge_row).abs() <= 1.0,
            "{path:?}: off, the outline is at row {off_top}, the cube's edge at {edge_row}"
        );
        assert!(
            (drop - expected_drop).abs() <= 1.0,
            "{path:?}: dropped {drop} px, expected {expected_drop}"
        );
    }
}

/// Background pixels with surface on all four sides (holes a ray slipped through), more than
/// `band` pixels inside the outline of `polygons` (the same view with the silhouette off): in
/// that band the relief decides the outline, a narrow gap in it included.
fn speckles(
    image: &image::Rgba32FImage,
    polygons: &image::Rgba32FImage,
    band: u32,
) -> Vec<(u32, u32)> {
    let (width, height) = image.dimensions();
    let deep_inside = |x: u32, y: u32| {
        let reach = band as i64;
        (-reach..=reach).all(|dy| {
            (-reach..=reach).all(|dx| {
                let (nx, ny) = (x as i64 + dx, y as i64 + dy);
                nx >= 0
                    && ny >= 0
                    && nx < width as i64
                    && ny < height as i64
                    && is_surface(polygons, nx as u32, ny as u32)
            })
        })
    };
    let mut found = Vec::new();
    for y in 1..height - 1 {
        for x in 1..width - 1 {
            let hole = !is_surface(image, x, y)
                && [(x - 1, y), (x + 1, y), (x, y - 1), (x, y + 1)]
                    .iter()
                    .all(|&(nx, ny)| is_surface(image, nx, ny));
            if hole && deep_inside(x, y) {
                found.push((x, y));
            }
        }
    }
    found
}

#[test]
fn the_clipped_cube_has_no_nan_and_no_speckle_over_the_angle_sweep() {
    for angle in [0.0_f32, 15.0, 30.0, 45.0, 60.0, 75.0, 85.0, 89.0] {
        let polygons = cube_uv(angle, Silhouette::Off, RenderPath::Deferred);
        for silhouette in [Silhouette::Off, Silhouette::UvBounds] {
            let image = cube_uv(angle, silhouette, RenderPath::Deferred);
            // Everywhere inside the polygons' outline.
            let holes = speckles(&image, &polygons, 0);
            assert!(
                holes.is_empty(),
                "{angle}° {silhouette:?}: isolated background pixels at {holes:?}"
            );
        }
    }
}

/// The lit cube (soft self-shadows, Tatarchuk's defaults) with `silhouette`, on both paths.
fn lit_shape(name: &str, shape: PreviewShape, view_angle: f32, silhouette: Silhouette) {
    let view = PreviewView {
        view_angle,
        view_azimuth: 20.0,
        light_angle: 50.0,
        light_azimuth: -60.0,
        projection: PreviewProjection::Perspective,
        shape,
        ..PreviewView::default()
    };
    let textures = HeightMaterial {
        field: patterns::cobblestones(128, 3),
        height_scale: 0.08,
    };
    let mut app = preview_app(SIZE, TargetFormat::Srgb8, &textures, &view, |material| {
        ParallaxOcclusionMaterial {
            silhouette,
            ..material
        }
    })
    .unwrap();
    let image = render_both_paths(&mut app, name).unwrap();
    check_golden(name, &image, FlipTolerance::default()).unwrap();
}

#[test]
fn golden_cube_with_its_outline_clipped_at_the_texture_bounds() {
    lit_shape(
        "silhouette_cube_uv_bounds",
        PreviewShape::Cube,
        55.0,
        Silhouette::UvBounds,
    );
}

#[test]
fn golden_cube_with_the_polygons_outline() {
    lit_shape(
        "silhouette_cube_off",
        PreviewShape::Cube,
        55.0,
        Silhouette::Off,
    );
}

#[test]
fn a_curved_silhouette_on_flat_faces_is_the_polygons_outline() {
    // A cube's faces do not curve: `curved` draws them as `off` does, to the golden's tolerance.
    lit_shape(
        "silhouette_cube_off",
        PreviewShape::Cube,
        55.0,
        Silhouette::Curved,
    );
}

#[test]
fn golden_plane_with_its_outline_clipped_at_the_texture_bounds() {
    lit_shape(
        "silhouette_plane_uv_bounds",
        PreviewShape::Plane,
        60.0,
        Silhouette::UvBounds,
    );
}

#[test]
fn golden_sphere_and_cylinder_with_the_polygons_outline() {
    lit_shape(
        "silhouette_sphere_off",
        PreviewShape::Sphere,
        30.0,
        Silhouette::Off,
    );
    lit_shape(
        "silhouette_cylinder_off",
        PreviewShape::Cylinder,
        40.0,
        Silhouette::Off,
    );
}

/// World units across the top-down image of the shadow test.
const SHADOW_VIEW: f32 = 3.0;
const SHADOW_IMAGE: u32 = 192;
/// The sun's angle from straight down, towards +x.
const SUN_ANGLE: f32 = 30.0;
/// Depth of the cube's rim in the shadow test (its faces are one unit).
const SHADOW_RELIEF: f32 = 0.15;

/// The scene-shadow visibility on a flat floor under a parallax cube lifted 0.1 above it, lit
/// by a sun `SUN_ANGLE` from straight down towards +x, seen from straight above.
fn cube_shadow(silhouette: Silhouette, path: RenderPath) -> image::Rgba32FImage {
    let mut app = pom_app(SHADOW_IMAGE, TargetFormat::Float32).unwrap();
    let floor_material = ParallaxOcclusionMaterial {
        height_scale: 0.0,
        debug_view: DebugView::SceneShadow,
        ..blocks().material(&mut app)
    };
    let cube_material = ParallaxOcclusionMaterial {
        silhouette,
        height_scale: SHADOW_RELIEF,
        shadows: ShadowMode::Off,
        ..blocks().material(&mut app)
    };
    let (floor, cube) = {
        let meshes = app.resources.get_mut::<Assets<Mesh>>().unwrap();
        (
            meshes.add(Mesh::plane(SHADOW_VIEW)),
            meshes.add(Mesh::cube(1.0)),
        )
    };
    app.world
        .spawn((floor, floor_material, Transform::IDENTITY));
    app.world
        .spawn((cube, cube_material, Transform::from_xyz(0.0, 0.6, 0.0)));
    spawn_sun_and_camera(&mut app);
    let image = render_on_path_f32(&mut app, path).unwrap();
    assert!(image.pixels().all(|p| p.0.iter().all(|c| c.is_finite())));
    image
}

fn spawn_sun_and_camera(app: &mut App) {
    let angle = SUN_ANGLE.to_radians();
    let to_light = Vec3::new(angle.sin(), angle.cos(), 0.0);
    app.world.spawn((
        DirectionalLight::default(),
        LightShadows {
            softness: 0.5,
            map_size: 2048,
            ..LightShadows::default()
        },
        Transform::IDENTITY.looking_at(-to_light, Vec3::Z),
    ));
    app.world.spawn((
        Camera::orthographic(SHADOW_VIEW),
        Transform::from_xyz(0.0, 4.0, 0.0).looking_at(Vec3::ZERO, Vec3::NEG_Z),
    ));
}

/// World x where the shadow beyond the cube (towards −x) ends along the image's middle row:
/// the 0.5 crossing of the visibility, interpolated between pixels.
fn far_end_of_shadow(image: &image::Rgba32FImage) -> f32 {
    let row = SHADOW_IMAGE / 2;
    let value = |x: u32| image.get_pixel(x, row).0[0];
    let world_x = |x: f32| (x + 0.5) * SHADOW_VIEW / SHADOW_IMAGE as f32 - SHADOW_VIEW * 0.5;
    // From the left edge (lit floor) towards the cube: the first crossing into shadow.
    let x = (1..SHADOW_IMAGE / 2)
        .find(|&x| value(x - 1) >= 0.5 && value(x) < 0.5)
        .expect("a shadow left of the cube");
    let (a, b) = (value(x - 1), value(x));
    world_x(x as f32 - 1.0 + (a - 0.5) / (a - b))
}

#[test]
fn the_clipped_outline_casts_a_clipped_shadow() {
    // The sun sees the top face at SUN_ANGLE: its rays leave the face's far (−x) edge as the
    // view's do, H tan θ in from it, and that edge casts the shadow's far end.
    let expected_shift = SHADOW_RELIEF * SUN_ANGLE.to_radians().tan();
    for path in [RenderPath::Forward, RenderPath::Deferred] {
        let off = far_end_of_shadow(&cube_shadow(Silhouette::Off, path));
        let clipped = far_end_of_shadow(&cube_shadow(Silhouette::UvBounds, path));
        // The top face's −x edge (x = −0.5, 1.1 above the floor) casts to −0.5 − 1.1 tan θ.
        let edge = -0.5 - 1.1 * SUN_ANGLE.to_radians().tan();
        let pixel = SHADOW_VIEW / SHADOW_IMAGE as f32;
        eprintln!(
            "{path:?}: shadow ends at x = {off:.4} off ({edge:.4} the polygon's), {clipped:.4} \
             clipped: shift {:.4}, H tan θ = {expected_shift:.4} (a pixel is {pixel:.4})",
            clipped - off
        );
        assert!((off - edge).abs() <= 1.5 * pixel, "{path:?}: off at {off}");
        assert!(
            (clipped - off - expected_shift).abs() <= 1.5 * pixel,
            "{path:?}: the clipped shadow moved {}, expected {expected_shift}",
            clipped - off
        );
    }
}

/// Depth of the sphere's bumps, world units (the sphere's radius is 0.5).
const BUMP_DEPTH: f32 = 0.025;
const SPHERE_IMAGE: u32 = 320;

/// Eight coarse bumps around the sphere (along u), their tops at the surface, the gaps
/// between them at the deepest height.
fn bumps() -> HeightMaterial {
    HeightMaterial {
        field: pom::HeightField::from_fn(
            128,
            64,
            |u, _| {
                if (u * 8.0).fract() < 0.5 { 1.0 } else { 0.0 }
            },
        ),
        height_scale: 0.05,
    }
}

/// The raw `uv` view of the preview sphere seen from `view_angle` (0: over its pole, so the
/// outline is its equator), with the bumps `BUMP_DEPTH` deep in world units.
fn sphere_uv(view_angle: f32, silhouette: Silhouette, path: RenderPath) -> image::Rgba32FImage {
    let view = PreviewView {
        view_angle,
        shape: PreviewShape::Sphere,
        ..PreviewView::default()
    };
    let mut app = preview_app(
        SPHERE_IMAGE,
        TargetFormat::Float32,
        &bumps(),
        &view,
        |material| ParallaxOcclusionMaterial {
            silhouette,
            height_units: pom::HeightUnits::World,
            height_scale: BUMP_DEPTH,
            debug_view: DebugView::Uv,
            shadows: ShadowMode::Off,
            lod_threshold: 16.0,
            max_samples: 64,
            ..material
        },
    )
    .unwrap();
    rendered_finite(&mut app, path, &format!("{view_angle}° {silhouette:?}"))
}

/// The surface's coverage at image point (x, y): is_surface of the pixels around, bilinearly
/// (pixel centres at half-integers), so an outline has a sub-pixel place where it crosses ½.
fn coverage(image: &image::Rgba32FImage, x: f32, y: f32) -> f32 {
    let (fx, fy) = (x - 0.5, y - 0.5);
    let (x0, y0) = (fx.floor(), fy.floor());
    let (tx, ty) = (fx - x0, fy - y0);
    let at = |dx: f32, dy: f32| {
        let (px, py) = (x0 + dx, y0 + dy);
        let inside =
            px >= 0.0 && py >= 0.0 && px < image.width() as f32 && py < image.height() as f32;
        f32::from(u8::from(inside && is_surface(image, px as u32, py as u32)))
    };
    (at(0.0, 0.0) * (1.0 - tx) + at(1.0, 0.0) * tx) * (1.0 - ty)
        + (at(0.0, 1.0) * (1.0 - tx) + at(1.0, 1.0) * tx) * ty
}

/// The outline's distance from the image's centre, in pixels, along each of `rays` directions:
/// the farthest point on the ray where the coverage is at least ½.
fn outline_radii(image: &image::Rgba32FImage, rays: usize) -> Vec<f32> {
    let centre = image.width() as f32 * 0.5;
    (0..rays)
        .map(|ray| {
            let angle = ray as f32 / rays as f32 * std::f32::consts::TAU;
            let (sin, cos) = angle.sin_cos();
            let steps = (centre * 20.0) as u32;
            (0..steps)
                .rev()
                .map(|step| step as f32 / 20.0)
                .find(|&radius| {
                    coverage(image, centre + cos * radius, centre + sin * radius) >= 0.5
                })
                .unwrap_or(0.0)
        })
        .collect()
}

fn percentile(values: &[f32], fraction: f32) -> f32 {
    let mut sorted = values.to_vec();
    sorted.sort_by(f32::total_cmp);
    sorted[((sorted.len() - 1) as f32 * fraction).round() as usize]
}

#[test]
fn curved_bumps_show_in_the_outline_of_a_sphere_by_their_depth() {
    let (camera, _) = PreviewView {
        shape: PreviewShape::Sphere,
        ..PreviewView::default()
    }
    .camera(1.0);
    let Projection::Orthographic { height, .. } = camera.projection else {
        panic!("the preview sphere is orthographic");
    };
    let pixels_per_unit = SPHERE_IMAGE as f32 / height;
    let depth = BUMP_DEPTH * pixels_per_unit;
    for path in [RenderPath::Forward, RenderPath::Deferred] {
        let off = outline_radii(&sphere_uv(0.0, Silhouette::Off, path), 720);
        let (low, high) = (percentile(&off, 0.02), percentile(&off, 0.98));
        eprintln!(
            "{path:?}, off: outline radius {low:.2}..{high:.2} px (the sphere's {:.2})",
            0.5 * pixels_per_unit
        );
        assert!(high - low <= 1.0, "{path:?}: off, the outline is no circle");
        let curved = outline_radii(&sphere_uv(0.0, Silhouette::Curved, path), 720);
        let (low, high) = (percentile(&curved, 0.02), percentile(&curved, 0.98));
        let varies = high - low;
        eprintln!(
            "{path:?}, curved: outline radius {low:.2}..{high:.2} px: varies by {varies:.2} px, \
             the bumps are {depth:.2} px deep"
        );
        assert!(
            (varies - depth).abs() <= 0.15 * depth,
            "{path:?}: the outline varies by {varies} px, the relief is {depth} px deep"
        );
    }
}

#[test]
fn the_curved_sphere_has_no_nan_and_no_speckle_over_the_angle_sweep() {
    let (camera, _) = PreviewView {
        shape: PreviewShape::Sphere,
        ..PreviewView::default()
    }
    .camera(1.0);
    let Projection::Orthographic { height, .. } = camera.projection else {
        panic!("the preview sphere is orthographic");
    };
    // The band the bumps' depth clips, and a pixel.
    let band = (BUMP_DEPTH * SPHERE_IMAGE as f32 / height).ceil() as u32 + 1;
    for angle in [0.0_f32, 30.0, 60.0, 89.0] {
        for path in [RenderPath::Forward, RenderPath::Deferred] {
            let polygons = sphere_uv(angle, Silhouette::Off, path);
            for silhouette in [Silhouette::Off, Silhouette::Curved] {
                let image = sphere_uv(angle, silhouette, path);
                let holes = speckles(&image, &polygons, band);
                assert!(
                    holes.is_empty(),
                    "{angle}° {silhouette:?} {path:?}: isolated background pixels at {holes:?}"
                );
            }
        }
    }
}

#[test]
fn golden_sphere_and_cylinder_with_curved_outlines() {
    lit_shape(
        "silhouette_sphere_curved",
        PreviewShape::Sphere,
        30.0,
        Silhouette::Curved,
    );
    lit_shape(
        "silhouette_cylinder_curved",
        PreviewShape::Cylinder,
        40.0,
        Silhouette::Curved,
    );
}

#[test]
fn a_curved_silhouette_on_a_mesh_without_normals_or_uvs_warns_once_and_draws_as_off() {
    let render = |silhouette: Silhouette, bare: Mesh| {
        let mut app = pom_app(64, TargetFormat::Float32).unwrap();
        // Half way down everywhere: every pixel marches, whatever its texture coordinate.
        let halfway = HeightMaterial {
            field: pom::HeightField::from_fn(16, 16, |_, _| 0.5),
            height_scale: 0.05,
        };
        let material = ParallaxOcclusionMaterial {
            silhouette,
            debug_view: DebugView::Uv,
            lod_threshold: 16.0,
            ..halfway.material(&mut app)
        };
        let mesh = app.resources.get_mut::<Assets<Mesh>>().unwrap().add(bare);
        let entity = app
            .world
            .spawn((mesh.clone(), material, Transform::IDENTITY));
        app.world.spawn((
            Camera::orthographic(1.2),
            Transform::from_xyz(0.0, 3.0, 0.0).looking_at(Vec3::ZERO, Vec3::NEG_Z),
        ));
        let first = pom_tests::render_and_capture_f32(&mut app).unwrap();
        let second = pom_tests::render_and_capture_f32(&mut app).unwrap();
        assert_eq!(first.as_raw(), second.as_raw());
        let warned = app
            .resources
            .get::<pom::CurvedSilhouetteWarnings>()
            .map_or(0, |warnings| {
                assert!(warnings.len() <= 1, "warned more than once");
                usize::from(warnings.contains(entity, mesh.id()))
            });
        (first, warned)
    };
    // Flat normals do not curve, and without texture coordinates there is no texture space to
    // bend in: the outline is the polygons', as with off.
    let covered = |image: &image::Rgba32FImage| {
        (0..image.height())
            .flat_map(|y| (0..image.width()).map(move |x| (x, y)))
            .filter(|&(x, y)| is_surface(image, x, y))
            .count()
    };
    let sphere = Mesh::uv_sphere(0.5, 32, 16);
    for (what, bare) in [
        (
            "no normals",
            Mesh {
                normals: Vec::new(),
                ..sphere.clone()
            },
        ),
        (
            "no texture coordinates",
            Mesh {
                uvs: Vec::new(),
                ..sphere.clone()
            },
        ),
    ] {
        let (curved, warned) = render(Silhouette::Curved, bare.clone());
        assert_eq!(warned, 1, "{what}: no warning named the mesh");
        let (off, not_warned) = render(Silhouette::Off, bare);
        assert_eq!(not_warned, 0, "{what}");
        assert!(
            covered(&off) > 1000,
            "{what}: the sphere covers {} pixels",
            covered(&off)
        );
        assert_eq!(covered(&curved), covered(&off), "{what}");
    }
}

/// Entities spawned and despawned every frame (particles, projectiles) on a mesh the curved
/// silhouette cannot use are each warned about once, and their warnings go with them.
#[test]
fn warnings_about_despawned_entities_are_forgotten() {
    let mut app = pom_app(8, TargetFormat::Float32).unwrap();
    let material = ParallaxOcclusionMaterial {
        silhouette: Silhouette::Curved,
        ..HeightMaterial {
            field: pom::HeightField::from_fn(4, 4, |_, _| 0.5),
            height_scale: 0.05,
        }
        .material(&mut app)
    };
    let bare = Mesh {
        normals: Vec::new(),
        ..Mesh::uv_sphere(0.5, 8, 4)
    };
    let mesh = app.resources.get_mut::<Assets<Mesh>>().unwrap().add(bare);
    app.world.spawn((
        Camera::orthographic(1.2),
        Transform::from_xyz(0.0, 3.0, 0.0).looking_at(Vec3::ZERO, Vec3::NEG_Z),
    ));
    for _ in 0..30 {
        let entity = app
            .world
            .spawn((mesh.clone(), material.clone(), Transform::IDENTITY));
        app.update().unwrap();
        let warnings = app
            .resources
            .get::<pom::CurvedSilhouetteWarnings>()
            .unwrap();
        assert!(warnings.contains(entity, mesh.id()));
        assert!(
            warnings.len() <= 2,
            "{} entities warned about",
            warnings.len()
        );
        app.world.despawn(entity).unwrap();
    }
}
