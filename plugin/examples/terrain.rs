//! A terrain of four parallax layers (rock, grass, earth, cobbles) blended by height under the
//! sky: `Mesh::terrain` from a generated height field, a weight map this program paints from
//! its slopes and heights (rock on the steep sides, earth in the hollows, grass elsewhere, a
//! cobbled path winding across), and a flying camera (W/A/S/D, E/Q, drag to look).
//!
//! `cargo run --release -p parallax-occlusion --example terrain --features window`

use pom::prelude::*;

/// The terrain's side and the height of its hills, in metres.
const SIDE: f32 = 40.0;
const HILLS: f32 = 5.0;
/// Texels across the terrain's height field and weight map.
const TEXELS: u32 = 256;

fn main() -> AppExit {
    let mut app = App::new();
    app.add_plugin(DefaultPlugins::windowed(WindowPlugin {
        title: "terrain: rock, grass, earth and cobbles blended by height".to_owned(),
        ..WindowPlugin::default()
    }))
    .add_plugin(FlyCameraPlugin)
    .add_system(Stage::Startup, setup);
    app.insert_resource(EnvironmentLight::sky());
    app.run()
}

/// Rolling hills, 0..1, over the terrain's 0..1 coordinates.
fn hills(u: f32, v: f32) -> f32 {
    let (x, z) = (u * std::f32::consts::TAU, v * std::f32::consts::TAU);
    0.5 + 0.25 * (x * 1.5).sin() * (z * 1.2).cos()
        + 0.15 * (x * 3.1 + z * 2.3).sin()
        + 0.1 * (z * 4.7).cos()
}

/// Where the cobbled path runs: how near (1 on its middle, 0 off it) `(u, v)` is to it.
fn path(u: f32, v: f32) -> f32 {
    let middle = 0.5 + 0.2 * (u * std::f32::consts::TAU).sin();
    (1.0 - (v - middle).abs() / 0.03).clamp(0.0, 1.0)
}

/// The layers' weights (rock, grass, earth, cobbles) from the terrain's slope and height.
fn weight_map(terrain: &HeightField) -> Image {
    let pixels = image::RgbaImage::from_fn(TEXELS, TEXELS, |x, y| {
        let (u, v) = (
            (x as f32 + 0.5) / TEXELS as f32,
            (y as f32 + 0.5) / TEXELS as f32,
        );
        let step = 1.0 / TEXELS as f32;
        let slope = Vec2::new(
            terrain.sample(u + step, v) - terrain.sample(u - step, v),
            terrain.sample(u, v + step) - terrain.sample(u, v - step),
        )
        .length()
            * HILLS
            / (2.0 * step * SIDE);
        let rock = ((slope - 0.35) / 0.2).clamp(0.0, 1.0);
        let earth = ((0.35 - terrain.sample(u, v)) / 0.1_f32).clamp(0.0, 1.0) * (1.0 - rock);
        let cobbles = path(u, v) * (1.0 - rock);
        let grass = (1.0 - rock - earth - cobbles).max(0.0);
        let byte = |weight: f32| (weight.clamp(0.0, 1.0) * 255.0).round() as u8;
        image::Rgba([byte(rock), byte(grass), byte(earth), byte(cobbles)])
    });
    Image::new(pixels, TextureKind::Data).expect("a 256 × 256 image")
}

/// A layer coloured `dark` in its hollows and `light` on its tops, its relief `field`.
fn layer(
    images: &mut Assets<Image>,
    field: &HeightField,
    dark: [f32; 3],
    light: [f32; 3],
    tiling: f32,
    height_scale: f32,
) -> ParallaxLayer {
    let (width, height) = field.size();
    let colours = image::RgbaImage::from_fn(width, height, |x, y| {
        let t = field.texel(i64::from(x), i64::from(y));
        let channel = |i: usize| ((dark[i] + (light[i] - dark[i]) * t) * 255.0) as u8;
        image::Rgba([channel(0), channel(1), channel(2), 255])
    });
    ParallaxLayer {
        base_color_texture: Image::new(colours, TextureKind::Color)
            .ok()
            .map(|image| images.add(image)),
        normal_map: Some(images.add(field.normal_map(0.04 * height_scale))),
        tiling,
        height_scale,
    }
}

fn setup(world: &mut World, resources: &mut Resources) {
    let terrain = HeightField::from_fn(TEXELS, TEXELS, hills);
    let Ok(mesh) = Mesh::terrain(&terrain, Vec3::new(SIDE, HILLS, SIDE), 192) else {
        return;
    };
    let Some(images) = resources.get_mut::<Assets<Image>>() else {
        return;
    };
    let rock = patterns::rock(256, 4);
    let grass = patterns::spikes(256, 6, 0.55);
    let earth = HeightField::from_fn(128, 128, |u, v| {
        0.6 + 0.2 * (u * 37.0).sin() * (v * 29.0).cos() + 0.2 * ((u + v) * 53.0).sin()
    });
    let cobbles = patterns::cobblestones(256, 6);
    let weights = weight_map(&terrain);
    let layers = vec![
        (
            layer(
                images,
                &rock,
                [0.25, 0.24, 0.23],
                [0.6, 0.58, 0.55],
                16.0,
                1.0,
            ),
            Some(&rock),
        ),
        (
            layer(
                images,
                &grass,
                [0.08, 0.2, 0.04],
                [0.3, 0.5, 0.12],
                24.0,
                0.4,
            ),
            Some(&grass),
        ),
        (
            layer(
                images,
                &earth,
                [0.2, 0.12, 0.06],
                [0.42, 0.3, 0.18],
                16.0,
                0.6,
            ),
            Some(&earth),
        ),
        (
            layer(
                images,
                &cobbles,
                [0.22, 0.2, 0.18],
                [0.62, 0.56, 0.48],
                32.0,
                0.8,
            ),
            Some(&cobbles),
        ),
    ];
    let weights = LayerWeights::Texture(images.add(weights));
    let Ok(layers) = ParallaxLayers::new(images, layers, weights) else {
        return;
    };
    let material = ParallaxOcclusionMaterial {
        layers: Some(layers),
        height_scale: 0.06,
        height_units: HeightUnits::World,
        layer_blend_contrast: 0.6,
        lighting: LightingModel::GgxLambert,
        roughness: 0.8,
        ..ParallaxOcclusionMaterial::default()
    };
    let Some(meshes) = resources.get_mut::<Assets<Mesh>>() else {
        return;
    };
    world.spawn((meshes.add(mesh), material, Transform::IDENTITY));
    let eye = Transform::from_xyz(-6.0, HILLS + 2.5, 12.0)
        .looking_at(Vec3::new(2.0, HILLS * 0.4, 0.0), Vec3::Y);
    world.spawn((
        Camera::perspective(55.0),
        FlyCamera::from_transform(&eye),
        eye,
    ));
    let sun = Transform::IDENTITY.looking_at(Vec3::new(-0.6, -0.5, -0.4), Vec3::Y);
    world.spawn((DirectionalLight::default(), sun));
}
