//! Behaviour of the forward renderer that needs no reference image: readback of any size,
//! upload bookkeeping, tangent generation, bad meshes, and the normal-map convention.

use glam::Vec3;
use pom::render::Renderer;
use pom::{
    Assets, Camera, Color, DirectionalLight, Image, LitMaterial, Mesh, TextureKind, Transform,
};
use pom_tests::{headless_app, render_and_capture, run_frames};

fn top_down_camera() -> (Camera, Transform) {
    (
        Camera::orthographic(2.0),
        Transform::from_xyz(0.0, 3.0, 0.0).looking_at(Vec3::ZERO, Vec3::NEG_Z),
    )
}

#[test]
fn capture_of_any_width_is_unpadded_and_exact() {
    for (width, height) in [(37, 23), (1, 1), (65, 3), (64, 64)] {
        let mut app = headless_app(width, height).unwrap();
        app.world.spawn((
            Camera {
                clear_color: Color::srgb_u8(10, 200, 90),
                ..Camera::perspective(45.0)
            },
            Transform::IDENTITY,
        ));
        let image = render_and_capture(&mut app).unwrap();
        assert_eq!(image.dimensions(), (width, height));
        assert!(
            image.pixels().all(|p| p.0 == [10, 200, 90, 255]),
            "{width}×{height}: a pixel differs from the clear colour"
        );
    }
}

#[test]
fn only_what_changed_is_uploaded() {
    let mut app = headless_app(32, 32).unwrap();
    let mesh = app
        .resources
        .get_mut::<Assets<Mesh>>()
        .unwrap()
        .add(Mesh::cube(1.0));
    let texture = app
        .resources
        .get_mut::<Assets<Image>>()
        .unwrap()
        .add(Image::solid([200, 10, 10, 255], TextureKind::Color));
    app.world.spawn(top_down_camera());
    let moving = app.world.spawn((
        mesh.clone(),
        LitMaterial {
            base_color_texture: Some(texture),
            ..LitMaterial::default()
        },
        Transform::IDENTITY,
    ));
    app.world
        .spawn((mesh.clone(), Transform::from_xyz(2.0, 0.0, 0.0)));
    let stats = |app: &pom::App| app.resources.get::<Renderer>().unwrap().last_upload;

    run_frames(&mut app, 1).unwrap();
    let first = stats(&app);
    assert_eq!((first.meshes, first.images), (1, 1));
    assert!(first.uniform_bytes > 0);

    run_frames(&mut app, 1).unwrap();
    assert_eq!(
        stats(&app),
        pom::gpu::UploadStats::default(),
        "nothing changed"
    );

    app.world
        .get::<&mut Transform>(moving)
        .unwrap()
        .translation
        .y = 0.5;
    run_frames(&mut app, 1).unwrap();
    let moved = stats(&app);
    assert_eq!((moved.meshes, moved.images), (0, 0));
    assert_eq!(
        moved.uniform_bytes,
        std::mem::size_of::<pom::render::MeshTransform>() as u64,
        "only the moved object's data"
    );

    app.resources
        .get_mut::<Assets<Mesh>>()
        .unwrap()
        .get_mut(&mesh)
        .unwrap()
        .positions[0][0] += 0.1;
    run_frames(&mut app, 1).unwrap();
    assert_eq!(stats(&app).meshes, 1, "the edited mesh is uploaded again");
}

#[test]
fn meshes_without_normals_uvs_or_tangents_still_render() {
    let mut app = headless_app(48, 48).unwrap();
    let bare = Mesh {
        positions: vec![[-0.8, 0.0, -0.8], [-0.8, 0.0, 0.8], [0.8, 0.0, 0.8]],
        indices: vec![0, 1, 2],
        ..Mesh::default()
    };
    let mesh = app.resources.get_mut::<Assets<Mesh>>().unwrap().add(bare);
    app.world.spawn(top_down_camera());
    app.world.spawn((
        DirectionalLight::default(),
        Transform::IDENTITY.looking_at(Vec3::NEG_Y, Vec3::Z),
    ));
    app.world.spawn((mesh, Transform::IDENTITY));
    let image = render_and_capture(&mut app).unwrap();
    let lit = image.pixels().filter(|p| p.0[0] > 200).count();
    assert!(
        lit > 48 * 48 / 4,
        "the triangle is lit by its generated flat normal ({lit} px)"
    );
}

#[test]
fn an_invalid_mesh_is_skipped_and_the_rest_still_draws() {
    let mut app = headless_app(32, 32).unwrap();
    let broken = Mesh {
        positions: vec![[0.0; 3]; 3],
        indices: vec![0, 1, 7],
        ..Mesh::default()
    };
    let meshes = app.resources.get_mut::<Assets<Mesh>>().unwrap();
    let broken = meshes.add(broken);
    let good = meshes.add(Mesh::plane(2.0));
    app.world.spawn(top_down_camera());
    app.world.spawn((broken, Transform::IDENTITY));
    app.world.spawn((
        good,
        LitMaterial::from_color(Color::BLACK),
        Transform::IDENTITY,
    ));
    let image = render_and_capture(&mut app).unwrap();
    // The good plane covers the view in black; the clear colour would be grey-blue.
    assert!(image.pixels().all(|p| p.0[..3] == [0, 0, 0]));
}

#[test]
fn freed_assets_leave_the_gpu() {
    let mut app = headless_app(16, 16).unwrap();
    let mesh = app
        .resources
        .get_mut::<Assets<Mesh>>()
        .unwrap()
        .add(Mesh::cube(1.0));
    let id = mesh.id();
    app.world.spawn(top_down_camera());
    let entity = app.world.spawn((mesh, Transform::IDENTITY));
    run_frames(&mut app, 1).unwrap();
    assert!(app.resources.get::<Renderer>().unwrap().has_gpu_mesh(id));
    app.world.despawn(entity).unwrap();
    run_frames(&mut app, 1).unwrap();
    assert!(!app.resources.get::<Assets<Mesh>>().unwrap().contains(id));
    assert!(!app.resources.get::<Renderer>().unwrap().has_gpu_mesh(id));
}

/// Brightness at the image centre of a flat plane whose normal map tilts every normal the same
/// way, lit from `light_from` at 45° elevation.
fn centre_brightness(normal_rgb: [u8; 3], light_from: Vec3) -> u8 {
    let mut app = headless_app(16, 16).unwrap();
    let plane = app
        .resources
        .get_mut::<Assets<Mesh>>()
        .unwrap()
        .add(Mesh::plane(2.0));
    let [r, g, b] = normal_rgb;
    let normal_map = app
        .resources
        .get_mut::<Assets<Image>>()
        .unwrap()
        .add(Image::solid([r, g, b, 255], TextureKind::Normal));
    app.world.spawn(top_down_camera());
    let towards_light = (light_from + Vec3::Y).normalize();
    app.world.spawn((
        DirectionalLight::default(),
        Transform::from_translation(towards_light).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    app.world.spawn((
        plane,
        LitMaterial {
            normal_map: Some(normal_map),
            specular_strength: 0.0,
            ..LitMaterial::default()
        },
        Transform::IDENTITY,
    ));
    render_and_capture(&mut app).unwrap().get_pixel(8, 8).0[0]
}

#[test]
fn normal_maps_follow_the_opengl_convention() {
    // Red tilts the normal towards +u (+X on the plane).
    let towards_u = [191, 128, 238];
    assert!(centre_brightness(towards_u, Vec3::X) > centre_brightness(towards_u, Vec3::NEG_X) + 40);
    // Green tilts it up the image, which is −v (−Z on the plane, since v runs along +Z).
    let up_image = [128, 191, 238];
    assert!(centre_brightness(up_image, Vec3::NEG_Z) > centre_brightness(up_image, Vec3::Z) + 40);
}

#[test]
fn an_image_over_the_device_limit_is_halved_until_it_fits() {
    let mut app = headless_app(16, 16).unwrap();
    let limit = app
        .resources
        .get::<pom::GpuContext>()
        .unwrap()
        .device
        .limits()
        .max_texture_dimension_2d;
    let wide = Image::new(image::RgbaImage::new(limit + 10, 2), TextureKind::Color).unwrap();
    let texture = app.resources.get_mut::<Assets<Image>>().unwrap().add(wide);
    let id = texture.id();
    let plane = app
        .resources
        .get_mut::<Assets<Mesh>>()
        .unwrap()
        .add(Mesh::plane(2.0));
    app.world.spawn(top_down_camera());
    app.world.spawn((
        plane,
        LitMaterial {
            base_color_texture: Some(texture),
            ..LitMaterial::default()
        },
        Transform::IDENTITY,
    ));
    run_frames(&mut app, 1).unwrap();
    let renderer = app.resources.get::<Renderer>().unwrap();
    let uploaded = renderer.gpu_texture(id).unwrap();
    assert_eq!((uploaded.width(), uploaded.height()), ((limit + 10) / 2, 1));
}

#[test]
fn sixteen_bit_heights_stay_sixteen_bit_on_the_gpu() {
    let mut app = headless_app(16, 16).unwrap();
    app.add_plugin(pom::PomPlugin);
    app.finish().unwrap();
    let field = pom::patterns::cones(32, 2.0);
    let images = app.resources.get_mut::<Assets<Image>>().unwrap();
    let height = images.add(field.to_image_16());
    let id = height.id();
    let plane = app
        .resources
        .get_mut::<Assets<Mesh>>()
        .unwrap()
        .add(Mesh::plane(2.0));
    app.world.spawn(top_down_camera());
    app.world.spawn((
        plane,
        pom::ParallaxOcclusionMaterial {
            height_map: Some(pom::HeightSource::Texture(height)),
            ..pom::ParallaxOcclusionMaterial::default()
        },
        Transform::IDENTITY,
    ));
    run_frames(&mut app, 1).unwrap();
    let gpu = app.resources.get::<pom::GpuContext>().unwrap();
    let format = app
        .resources
        .get::<Renderer>()
        .unwrap()
        .gpu_texture(id)
        .unwrap()
        .format();
    let expected = if gpu
        .device
        .features()
        .contains(pom::wgpu::Features::TEXTURE_FORMAT_16BIT_NORM)
    {
        pom::wgpu::TextureFormat::R16Unorm
    } else if gpu
        .device
        .features()
        .contains(pom::wgpu::Features::FLOAT32_FILTERABLE)
    {
        pom::wgpu::TextureFormat::R32Float
    } else {
        pom::wgpu::TextureFormat::R16Float
    };
    eprintln!("16-bit height uploaded as {format:?}");
    assert_eq!(format, expected);
}
