//! Boulders without texture coordinates under triplanar parallax: lumpy spheres this program
//! shapes from noise, with smooth normals and no UVs or tangents, textured by one rock height
//! field projected along the world axes (`mapping: triplanar`), on a cobbled ground, under the
//! sky and a sun whose shadow maps hold the boulders' relief. A flying camera (W/A/S/D, E/Q,
//! drag to look).
//!
//! `cargo run --release -p parallax-occlusion --example rocks --features window`

use std::collections::HashMap;

use pom::prelude::*;

fn main() -> AppExit {
    let mut app = App::new();
    app.add_plugin(DefaultPlugins::windowed(WindowPlugin {
        title: "rocks: triplanar parallax on meshes without texture coordinates".to_owned(),
        ..WindowPlugin::default()
    }))
    .add_plugin(FlyCameraPlugin)
    .add_system(Stage::Startup, setup);
    app.insert_resource(EnvironmentLight::sky());
    app.run()
}

/// A hash of a lattice point to 0..1.
fn lattice(x: i32, y: i32, z: i32, seed: u32) -> f32 {
    let mut h = (x as u32).wrapping_mul(0x8da6_b343)
        ^ (y as u32).wrapping_mul(0xd816_3841)
        ^ (z as u32).wrapping_mul(0xcb1a_b31f)
        ^ seed.wrapping_mul(0x1656_67b1);
    h ^= h >> 13;
    h = h.wrapping_mul(0x5bd1_e995);
    h ^= h >> 15;
    (h & 0xffff) as f32 / 65535.0
}

/// Smooth value noise in space, 0..1.
fn value_noise(p: Vec3, seed: u32) -> f32 {
    let cell = p.floor();
    let t = p - cell;
    let smooth = t * t * (Vec3::splat(3.0) - 2.0 * t);
    let corner = |dx: i32, dy: i32, dz: i32| {
        lattice(
            cell.x as i32 + dx,
            cell.y as i32 + dy,
            cell.z as i32 + dz,
            seed,
        )
    };
    let along_x = |dy, dz| corner(0, dy, dz) + (corner(1, dy, dz) - corner(0, dy, dz)) * smooth.x;
    let along_y = |dz| along_x(0, dz) + (along_x(1, dz) - along_x(0, dz)) * smooth.y;
    along_y(0) + (along_y(1) - along_y(0)) * smooth.z
}

/// A boulder of about unit radius: a sphere pushed in and out by noise, stretched by
/// `stretch`, with smooth normals and neither texture coordinates nor tangents.
fn boulder(seed: u32, stretch: Vec3) -> Mesh {
    let mut mesh = Mesh::uv_sphere(1.0, 64, 32);
    for position in &mut mesh.positions {
        let p = Vec3::from(*position);
        let lumps =
            value_noise(p * 1.3 + 7.0, seed) * 0.35 + value_noise(p * 3.1 + 3.0, seed + 1) * 0.12;
        *position = (p * (0.8 + lumps) * stretch).into();
    }
    mesh.uvs.clear();
    mesh.tangents.clear();
    mesh.normals = smooth_normals(&mesh);
    mesh
}

/// Each vertex's normal: the area-weighted mean of the faces around its position (vertices
/// at one position, as on a sphere's seam and poles, share it, so no crease shows).
fn smooth_normals(mesh: &Mesh) -> Vec<[f32; 3]> {
    let key = |p: [f32; 3]| p.map(|c| (c * 1e4).round() as i64);
    let mut sums: HashMap<[i64; 3], Vec3> = HashMap::new();
    for triangle in mesh.indices.chunks_exact(3) {
        let [a, b, c] = [0, 1, 2].map(|k| Vec3::from(mesh.positions[triangle[k] as usize]));
        let face = (b - a).cross(c - a);
        for &index in triangle {
            *sums.entry(key(mesh.positions[index as usize])).or_default() += face;
        }
    }
    mesh.positions
        .iter()
        .map(|&p| sums[&key(p)].normalize_or(Vec3::Y).into())
        .collect()
}

/// A colour map of `field`: `dark` in its hollows, `light` on its tops.
fn colours(field: &HeightField, dark: [f32; 3], light: [f32; 3]) -> Image {
    let (width, height) = field.size();
    let pixels = image::RgbaImage::from_fn(width, height, |x, y| {
        let t = field.texel(i64::from(x), i64::from(y));
        let channel = |i: usize| ((dark[i] + (light[i] - dark[i]) * t) * 255.0) as u8;
        image::Rgba([channel(0), channel(1), channel(2), 255])
    });
    Image::new(pixels, TextureKind::Color)
        .unwrap_or_else(|_| Image::solid([128, 128, 128, 255], TextureKind::Color))
}

fn setup(world: &mut World, resources: &mut Resources) {
    let Some(images) = resources.get_mut::<Assets<Image>>() else {
        return;
    };
    let field = patterns::rock(256, 4);
    let rock_material = ParallaxOcclusionMaterial {
        base_color_texture: Some(images.add(colours(
            &field,
            [0.22, 0.21, 0.19],
            [0.62, 0.6, 0.55],
        ))),
        normal_map: Some(images.add(field.normal_map(0.08))),
        height_map: Some(HeightSource::Texture(images.add(field.to_image()))),
        mapping: TextureMapping::Triplanar,
        triplanar_scale: 1.5,
        triplanar_sharpness: 6.0,
        height_scale: 0.06,
        height_units: HeightUnits::World,
        lighting: LightingModel::GgxLambert,
        roughness: 0.85,
        ..ParallaxOcclusionMaterial::default()
    };
    let cobbles = patterns::cobblestones(256, 6);
    let ground_material = ParallaxOcclusionMaterial {
        base_color_texture: Some(images.add(colours(
            &cobbles,
            [0.2, 0.16, 0.12],
            [0.5, 0.44, 0.36],
        ))),
        normal_map: Some(images.add(cobbles.normal_map(0.04))),
        height_map: Some(HeightSource::Texture(images.add(cobbles.to_image()))),
        height_scale: 0.04,
        ..ParallaxOcclusionMaterial::default()
    };
    let Some(meshes) = resources.get_mut::<Assets<Mesh>>() else {
        return;
    };
    world.spawn((
        meshes.add(Mesh::plane_tiled(24.0, 8.0)),
        ground_material,
        Transform::IDENTITY,
    ));
    let boulders = [
        (Vec3::new(0.0, 0.9, 0.0), 1.4, Vec3::new(1.2, 0.8, 1.0)),
        (Vec3::new(3.2, 0.5, -1.5), 0.8, Vec3::new(1.0, 0.9, 1.3)),
        (Vec3::new(-2.8, 0.6, 1.2), 0.9, Vec3::new(1.4, 0.7, 1.0)),
        (Vec3::new(1.5, 0.35, 2.6), 0.5, Vec3::ONE),
        (Vec3::new(-1.2, 1.2, -3.5), 1.7, Vec3::new(1.0, 1.1, 0.9)),
    ];
    for (index, (at, size, stretch)) in boulders.into_iter().enumerate() {
        let transform = Transform {
            translation: at,
            rotation: Quat::from_rotation_y(index as f32 * 1.7),
            scale: Vec3::splat(size),
        };
        world.spawn((
            meshes.add(boulder(index as u32 * 7 + 1, stretch)),
            rock_material.clone(),
            transform,
        ));
    }
    let eye = Transform::from_xyz(-4.5, 2.2, 6.5).looking_at(Vec3::new(0.0, 0.6, 0.0), Vec3::Y);
    world.spawn((
        Camera::perspective(55.0),
        FlyCamera::from_transform(&eye),
        eye,
    ));
    let sun = Transform::IDENTITY.looking_at(Vec3::new(-0.5, -0.7, -0.45), Vec3::Y);
    world.spawn((DirectionalLight::default(), LightShadows::default(), sun));
}
