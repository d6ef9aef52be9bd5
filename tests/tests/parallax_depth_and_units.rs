//! Depth offset, world-unit heights, and point-light shadows of the parallax material.

use glam::Vec3;
use pom::hecs;
use pom::preview::PreviewView;
use pom::{
    Assets, Color, DebugView, DirectionalLight, HeightConvention, HeightSource, HeightUnits,
    LitMaterial, Mesh, ParallaxMethod, ParallaxOcclusionMaterial, PointLight, ShadowMode,
    TargetFormat, Transform, patterns,
};
use pom_tests::pom_scene::{HeightMaterial, preview_app};
use pom_tests::{render_and_capture, render_and_capture_f32};

const HEIGHT_SCALE: f32 = 0.05;

fn block() -> HeightMaterial {
    HeightMaterial {
        field: patterns::raised_block(128, 0.4),
        height_scale: HEIGHT_SCALE,
    }
}

/// Share of pixels where a red plane half way down the relief shows through.
fn red_share(depth_offset: bool) -> f32 {
    let view = PreviewView {
        view_angle: 20.0,
        ..PreviewView::default()
    };
    let mut app = preview_app(64, TargetFormat::Srgb8, &block(), &view, |material| {
        ParallaxOcclusionMaterial {
            depth_offset,
            shadows: ShadowMode::Off,
            ..material
        }
    })
    .unwrap();
    let plane = app
        .resources
        .get_mut::<Assets<Mesh>>()
        .unwrap()
        .add(Mesh::plane(1.0));
    // Below the polygon, above the floor of the relief (which lies HEIGHT_SCALE down).
    app.world.spawn((
        plane,
        LitMaterial {
            base_color: Color::linear_rgb(1.0, 0.0, 0.0),
            specular_strength: 0.0,
            ..LitMaterial::default()
        },
        Transform::from_xyz(0.0, -HEIGHT_SCALE * 0.5, 0.0),
    ));
    let image = render_and_capture(&mut app).unwrap();
    let red = image
        .pixels()
        .filter(|p| p.0[0] > 100 && p.0[1] < 40 && p.0[2] < 40)
        .count();
    red as f32 / (64 * 64) as f32
}

#[test]
fn depth_offset_lets_geometry_show_through_the_deep_parts_only() {
    let without = red_share(false);
    let with = red_share(true);
    eprintln!(
        "red plane visible: {:.1} % without depth offset, {:.1} % with",
        without * 100.0,
        with * 100.0
    );
    assert_eq!(without, 0.0, "the flat polygon hides everything behind it");
    // The floor (outside the 0.4 × 0.4 block) is 84 % of the plane; the block's top stays in front.
    assert!((0.6..0.9).contains(&with), "{with}");
}

/// Sideways shift, in texture units, of the floor behind the block seen at 60°, for a plane
/// scaled by `scale` with the height given in `units`.
fn floor_shift(units: HeightUnits, scale: f32) -> f32 {
    let view = PreviewView {
        view_angle: 60.0,
        ..PreviewView::default()
    };
    let uv_view = |method| {
        let mut app = preview_app(128, TargetFormat::Float32, &block(), &view, |material| {
            ParallaxOcclusionMaterial {
                method,
                height_units: units,
                debug_view: DebugView::Uv,
                min_samples: 64,
                max_samples: 128,
                lod_threshold: 16.0,
                ..material
            }
        })
        .unwrap();
        for transform in app
            .world
            .query_mut::<&mut Transform>()
            .with::<&ParallaxOcclusionMaterial>()
        {
            transform.scale = Vec3::splat(scale);
        }
        render_and_capture_f32(&mut app).unwrap()
    };
    let entry = uv_view(ParallaxMethod::NormalMapping);
    let seen = uv_view(ParallaxMethod::Occlusion);
    let shifts: Vec<f32> = (0..128)
        .map(|y| (entry.get_pixel(64, y).0[0], seen.get_pixel(64, y).0[0]))
        .filter(|(_, seen)| *seen > 0.72 && *seen < 0.98)
        .map(|(entered, seen)| seen - entered)
        .collect();
    assert!(shifts.len() > 3);
    shifts.iter().sum::<f32>() / shifts.len() as f32
}

#[test]
fn world_unit_heights_keep_their_depth_when_the_object_is_scaled() {
    let tan = 60_f32.to_radians().tan();
    // Texture units: the shift in UV is the same at any object scale.
    let texture_units = floor_shift(HeightUnits::Texture, 2.0);
    assert!(
        (texture_units - HEIGHT_SCALE * tan).abs() < 0.03 * HEIGHT_SCALE * tan,
        "{texture_units}"
    );
    // World units on a plane twice as large: half a texture unit per world unit.
    let world_units = floor_shift(HeightUnits::World, 2.0);
    let expected = HEIGHT_SCALE * 0.5 * tan;
    eprintln!(
        "floor shift at scale 2: texture units {texture_units:.4}, world units {world_units:.4} (expected {expected:.4})"
    );
    assert!(
        (world_units - expected).abs() < 0.03 * expected,
        "{world_units} vs {expected}"
    );
}

#[test]
fn point_lights_cast_self_shadows_too() {
    let mut app = preview_app(
        96,
        TargetFormat::Float32,
        &block(),
        &PreviewView::default(),
        |material| ParallaxOcclusionMaterial {
            debug_view: DebugView::Shadow,
            ..material
        },
    )
    .unwrap();
    // Replace the sun by a point light low over the block's −u side.
    let sun = app
        .world
        .query::<(hecs::Entity, &DirectionalLight)>()
        .iter()
        .map(|(entity, _)| entity)
        .next()
        .unwrap();
    app.world.despawn(sun).unwrap();
    app.world.spawn((
        PointLight {
            intensity: 100_000.0,
            range: 10.0,
            ..PointLight::default()
        },
        Transform::from_xyz(-0.45, 0.06, 0.0),
    ));
    let image = render_and_capture_f32(&mut app).unwrap();
    // Rows run +u upwards; the centre column just past the block's +u edge (u ≈ 0.72) is shadowed,
    // the floor between the light and the block (u ≈ 0.2) is lit.
    let visibility_at = |u: f32| image.get_pixel(48, ((1.0 - u) * 96.0) as u32).0[0];
    assert!(visibility_at(0.73) < 0.2, "behind: {}", visibility_at(0.73));
    assert!(
        visibility_at(0.2) > 0.99,
        "in front: {}",
        visibility_at(0.2)
    );
}

fn uv_view_of(
    configure: impl FnOnce(&mut pom::App) -> ParallaxOcclusionMaterial,
) -> image::Rgba32FImage {
    let view = PreviewView {
        view_angle: 55.0,
        ..PreviewView::default()
    };
    let mut app = pom_tests::pom_scene::pom_app(48, TargetFormat::Float32).unwrap();
    let material = ParallaxOcclusionMaterial {
        debug_view: DebugView::Uv,
        ..configure(&mut app)
    };
    pom::preview::spawn_preview(&mut app, material, &view).unwrap();
    render_and_capture_f32(&mut app).unwrap()
}

#[test]
fn height_in_the_normal_maps_alpha_or_as_a_depth_map_gives_the_same_surface() {
    let field = patterns::cobblestones(64, 3);
    let separate = uv_view_of(|app| {
        let images = app.resources.get_mut::<Assets<pom::Image>>().unwrap();
        ParallaxOcclusionMaterial {
            height_map: Some(HeightSource::Texture(images.add(field.to_image()))),
            ..ParallaxOcclusionMaterial::default()
        }
    });
    let packed = uv_view_of(|app| {
        // McGuire's packing: the normal map's alpha holds the height.
        let mut normal = field.normal_map(HEIGHT_SCALE).to_rgba8();
        for (pixel, height) in normal
            .pixels_mut()
            .zip(field.to_image().to_rgba8().pixels())
        {
            pixel.0[3] = height.0[0];
        }
        let images = app.resources.get_mut::<Assets<pom::Image>>().unwrap();
        let normal = pom::Image::new(normal, pom::TextureKind::Normal).unwrap();
        ParallaxOcclusionMaterial {
            normal_map: Some(images.add(normal)),
            height_map: Some(HeightSource::NormalMapAlpha),
            ..ParallaxOcclusionMaterial::default()
        }
    });
    let depth = uv_view_of(|app| {
        // The same relief stored as a depth map: white is deepest.
        let mut inverted = field.to_image().to_rgba8();
        for pixel in inverted.pixels_mut() {
            for channel in &mut pixel.0[..3] {
                *channel = 255 - *channel;
            }
        }
        let images = app.resources.get_mut::<Assets<pom::Image>>().unwrap();
        let inverted = pom::Image::new(inverted, pom::TextureKind::Height).unwrap();
        ParallaxOcclusionMaterial {
            height_map: Some(HeightSource::Texture(images.add(inverted))),
            height_convention: HeightConvention::Depth,
            ..ParallaxOcclusionMaterial::default()
        }
    });
    let flat = uv_view_of(|_| ParallaxOcclusionMaterial::default());
    let mean_difference = |a: &image::Rgba32FImage, b: &image::Rgba32FImage| {
        let total: f32 = a
            .pixels()
            .zip(b.pixels())
            .map(|(p, q)| (p.0[0] - q.0[0]).abs().max((p.0[1] - q.0[1]).abs()))
            .sum();
        total / (a.width() * a.height()) as f32
    };
    let packed_difference = mean_difference(&separate, &packed);
    assert!(
        packed_difference < 1e-5,
        "alpha-packed height differs by {packed_difference}"
    );
    // Inverting an 8-bit image and its mips rounds ties the other way, which can move a rare
    // crossing by a step; on average the surfaces agree to a fraction of a texel.
    let depth_difference = mean_difference(&separate, &depth);
    assert!(
        depth_difference < 2e-3,
        "depth convention differs by {depth_difference}"
    );
    let relief = mean_difference(&separate, &flat);
    assert!(
        relief > 0.01,
        "the relief should shift texture coordinates ({relief})"
    );
}
