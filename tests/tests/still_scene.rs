//! A scene where nothing moves costs nothing again, on both paths: it uploads nothing, frame
//! after frame (every buffer and texture write of the library goes through
//! `GpuContext::write_buffer` and `write_texture`, which count their bytes; one moving entity
//! uploads its own transform only), and its shadow maps are drawn once and kept. Entities that
//! share one material by handle draw and upload as entities with copies of it.

use pom::glam::{Quat, Vec3};
use pom::render::shadows::ShadowMapStats;
use pom::render::{MeshTransform, RenderPath};
use pom::{
    App, Assets, Camera, DirectionalLight, EnvironmentLight, GpuContext, Handle, HeightField,
    Image, LightShadows, LitMaterial, Mesh, ParallaxOcclusionMaterial, PointLight, PomPlugin,
    RenderPlugin, SpotLight, Transform,
};
use pom_tests::{render_and_capture, run_frames, set_path};

/// Parallax planes on a floor under a cube, a shadowed sun, a shadowed spot, a point light and
/// the sky's environment; returns the app, one of the planes and the cube.
fn street(path: RenderPath) -> (App, pom::hecs::Entity, pom::hecs::Entity) {
    let mut app = App::new();
    app.add_plugin(RenderPlugin::new(64, 64))
        .add_plugin(PomPlugin);
    app.finish().unwrap();
    set_path(&mut app, path);
    app.insert_resource(EnvironmentLight::sky());
    let (plane, cube) = {
        let meshes = app.resources.get_mut::<Assets<Mesh>>().unwrap();
        (meshes.add(Mesh::plane(0.9)), meshes.add(Mesh::cube(0.5)))
    };
    let heights = HeightField::from_fn(32, 32, |u, v| {
        (u * 12.0).sin() * (v * 9.0).cos() * 0.5 + 0.5
    });
    let height_map = app
        .resources
        .get_mut::<Assets<Image>>()
        .unwrap()
        .add(heights.to_image());
    let material = ParallaxOcclusionMaterial {
        height_map: Some(pom::HeightSource::Texture(height_map)),
        height_scale: 0.08,
        ..ParallaxOcclusionMaterial::default()
    };
    let planes: Vec<_> = (0..16)
        .map(|index| {
            let (x, z) = ((index % 4) as f32 - 1.5, (index / 4) as f32 - 1.5);
            app.world.spawn((
                plane.clone(),
                material.clone(),
                Transform::from_xyz(x, 0.0, z),
            ))
        })
        .collect();
    let cube = app.world.spawn((
        cube,
        LitMaterial::default(),
        Transform::from_xyz(0.0, 0.3, 0.0),
    ));
    app.world.spawn((
        DirectionalLight::default(),
        LightShadows::default(),
        Transform::IDENTITY.looking_at(Vec3::new(-1.0, -2.0, -0.5), Vec3::Y),
    ));
    app.world.spawn((
        SpotLight::default(),
        LightShadows::default(),
        Transform::from_xyz(1.0, 2.0, 1.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    app.world
        .spawn((PointLight::default(), Transform::from_xyz(-1.0, 1.0, -1.0)));
    app.world.spawn((
        Camera::perspective(60.0),
        Transform::from_xyz(0.0, 3.0, 4.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    (app, planes[5], cube)
}

/// Bytes the app's GPU context uploads over `frames` frames.
fn uploaded_over(app: &mut App, frames: usize) -> u64 {
    let gpu = app.resources.get::<GpuContext>().unwrap().clone();
    let before = gpu.uploaded_bytes();
    run_frames(app, frames).unwrap();
    gpu.uploaded_bytes() - before
}

#[test]
fn a_still_scene_uploads_nothing_and_a_moving_entity_its_own_transform() {
    for path in [RenderPath::Forward, RenderPath::Deferred] {
        let (mut app, plane, _) = street(path);
        let first = uploaded_over(&mut app, 3);
        assert!(first > 0, "{path:?}: the first frames upload the scene");
        assert_eq!(uploaded_over(&mut app, 5), 0, "{path:?}: nothing moved");

        app.world.get::<&mut Transform>(plane).unwrap().rotation = Quat::from_rotation_y(0.4);
        assert_eq!(
            uploaded_over(&mut app, 1),
            std::mem::size_of::<MeshTransform>() as u64,
            "{path:?}: the turned plane's transform, and nothing else"
        );
        assert_eq!(uploaded_over(&mut app, 3), 0, "{path:?}: still again");
    }
}

/// Gives the street's planes one shared material in place of their copies of it.
fn share_plane_materials(app: &mut App) -> Handle<ParallaxOcclusionMaterial> {
    let planes: Vec<_> = app
        .world
        .query::<(pom::hecs::Entity, &ParallaxOcclusionMaterial)>()
        .iter()
        .map(|(entity, material)| (entity, material.clone()))
        .collect();
    let handle = app
        .resources
        .get_mut::<Assets<ParallaxOcclusionMaterial>>()
        .unwrap()
        .add(planes[0].1.clone());
    for (entity, _) in planes {
        app.world
            .remove_one::<ParallaxOcclusionMaterial>(entity)
            .unwrap();
        app.world.insert_one(entity, handle.clone()).unwrap();
    }
    handle
}

#[test]
fn planes_sharing_one_material_draw_and_upload_as_planes_with_copies_of_it() {
    for path in [RenderPath::Forward, RenderPath::Deferred] {
        let (mut copies, ..) = street(path);
        let (mut sharing, ..) = street(path);
        let shared = share_plane_materials(&mut sharing);
        let first = render_and_capture(&mut copies).unwrap();
        assert!(
            first == render_and_capture(&mut sharing).unwrap(),
            "{path:?}: the image"
        );
        assert_eq!(uploaded_over(&mut sharing, 3), 0, "{path:?}: nothing moved");

        for material in copies.world.query_mut::<&mut ParallaxOcclusionMaterial>() {
            material.height_scale = 0.12;
        }
        sharing
            .resources
            .get_mut::<Assets<ParallaxOcclusionMaterial>>()
            .unwrap()
            .get_mut(&shared)
            .unwrap()
            .height_scale = 0.12;
        let changed = uploaded_over(&mut copies, 1);
        assert!(changed > 0, "{path:?}: the planes' uniforms");
        assert_eq!(uploaded_over(&mut sharing, 1), changed, "{path:?}");
        let second = render_and_capture(&mut copies).unwrap();
        assert!(second != first, "{path:?}: the change shows");
        assert!(
            second == render_and_capture(&mut sharing).unwrap(),
            "{path:?}: the image after the change"
        );
        assert_eq!(uploaded_over(&mut sharing, 3), 0, "{path:?}: still again");
    }
}

#[test]
fn every_write_of_the_library_goes_through_the_counted_ones() {
    let src = pom_tests::sources::plugin_src();
    let mut direct = Vec::new();
    for file in pom_tests::sources::rust_files(&src) {
        if file.ends_with("gpu/context.rs") {
            continue;
        }
        let source = std::fs::read_to_string(&file).unwrap();
        // rustfmt may break `queue` and `.write_buffer(` over two lines.
        let joined: String = source.split_whitespace().collect();
        if joined.contains("queue.write_buffer(") || joined.contains("queue.write_texture(") {
            direct.push(file.display().to_string());
        }
    }
    assert!(
        direct.is_empty(),
        "writes past GpuContext's count: {direct:?}"
    );
}

/// Shadow maps (drawn, kept) so far.
fn shadow_maps(app: &App) -> (u64, u64) {
    let stats = app.resources.get::<ShadowMapStats>().unwrap();
    (stats.drawn(), stats.kept())
}

#[test]
fn a_still_scenes_shadow_maps_are_drawn_once_and_again_where_a_caster_or_a_view_moves() {
    for path in [RenderPath::Forward, RenderPath::Deferred] {
        let (mut app, _, cube) = street(path);
        run_frames(&mut app, 1).unwrap();
        let views = shadow_maps(&app).0;
        assert_eq!(views, 4, "three cascades and the spot's map");
        run_frames(&mut app, 99).unwrap();
        assert_eq!(
            shadow_maps(&app),
            (views, 99 * views),
            "{path:?}: drawn once"
        );
        let kept_image = render_and_capture(&mut app).unwrap();
        let (mut fresh, _, _) = street(path);
        assert!(
            render_and_capture(&mut fresh).unwrap() == kept_image,
            "{path:?}: the kept maps shade as freshly drawn ones"
        );

        // A caster moves: every map is drawn again, once.
        let before = shadow_maps(&app);
        app.world.get::<&mut Transform>(cube).unwrap().translation.x += 0.2;
        run_frames(&mut app, 3).unwrap();
        assert_eq!(
            shadow_maps(&app),
            (before.0 + views, before.1 + 2 * views),
            "{path:?}: a caster moved"
        );

        // The camera moves a little: every cascade still covers its slice of the view, and
        // shades as one fitted afresh would.
        let before = shadow_maps(&app);
        move_camera(&mut app, 0.5);
        run_frames(&mut app, 1).unwrap();
        assert_eq!(
            shadow_maps(&app),
            (before.0, before.1 + views),
            "{path:?}: the camera moved a little"
        );
        let kept_image = render_and_capture(&mut app).unwrap();
        let (mut fresh, _, fresh_cube) = street(path);
        fresh
            .world
            .get::<&mut Transform>(fresh_cube)
            .unwrap()
            .translation
            .x += 0.2;
        move_camera(&mut fresh, 0.5);
        let fresh_image = render_and_capture(&mut fresh).unwrap();
        let comparison = pom::flip_compare(&fresh_image, &kept_image, 0.99).unwrap();
        assert!(
            comparison.mean < 0.001,
            "{path:?}: kept cascades against fresh ones, FLIP mean {}",
            comparison.mean
        );

        // The camera walks off: the cascades follow it, the spot's map stays.
        let before = shadow_maps(&app);
        move_camera(&mut app, 30.0);
        run_frames(&mut app, 1).unwrap();
        assert_eq!(
            shadow_maps(&app),
            (before.0 + 3, before.1 + 1),
            "{path:?}: the camera moved"
        );
    }
}

/// Moves the scene's camera `x` along +X.
fn move_camera(app: &mut App, x: f32) {
    for (_, transform) in app.world.query_mut::<(&Camera, &mut Transform)>() {
        transform.translation.x += x;
    }
}

/// Turns the scene's sun by `radians` about +Y.
fn turn_sun(app: &mut App, radians: f32) {
    for (_, transform) in app.world.query_mut::<(&DirectionalLight, &mut Transform)>() {
        transform.rotation = Quat::from_rotation_y(radians) * transform.rotation;
    }
}

#[test]
fn a_turning_sun_redraws_one_cascade_a_frame_and_a_jump_all_of_them() {
    for path in [RenderPath::Forward, RenderPath::Deferred] {
        let (mut app, _, _) = street(path);
        run_frames(&mut app, 2).unwrap();
        let step = 0.1_f32.to_radians();
        for frame in 0..6 {
            let before = shadow_maps(&app);
            turn_sun(&mut app, step);
            run_frames(&mut app, 1).unwrap();
            assert_eq!(
                shadow_maps(&app),
                (before.0 + 1, before.1 + 3),
                "{path:?}, frame {frame}: one cascade follows the sun, the spot's map stays"
            );
        }
        // Still again: within the cascades' turns every map is the sun's, as a fresh app's.
        run_frames(&mut app, 2).unwrap();
        let followed = render_and_capture(&mut app).unwrap();
        let (mut fresh, _, _) = street(path);
        for _ in 0..6 {
            turn_sun(&mut fresh, step);
        }
        assert!(
            render_and_capture(&mut fresh).unwrap() == followed,
            "{path:?}: the cascades caught up with the sun"
        );

        let before = shadow_maps(&app);
        turn_sun(&mut app, 5.0_f32.to_radians());
        run_frames(&mut app, 1).unwrap();
        assert_eq!(
            shadow_maps(&app),
            (before.0 + 3, before.1 + 1),
            "{path:?}: the sun jumped"
        );
    }
}

#[test]
fn under_taa_shadow_maps_are_kept_unless_a_caster_marches_jittered() {
    for path in [RenderPath::Forward, RenderPath::Deferred] {
        let (mut app, plane, _) = street(path);
        pom_tests::anti_aliasing::set_anti_aliasing(&mut app, pom::AntiAliasing::Taa);
        run_frames(&mut app, 2).unwrap();
        let before = shadow_maps(&app);
        run_frames(&mut app, 10).unwrap();
        assert_eq!(
            shadow_maps(&app),
            (before.0, before.1 + 40),
            "{path:?}: TAA's noise moves, no caster reads it"
        );
        app.world
            .get::<&mut ParallaxOcclusionMaterial>(plane)
            .unwrap()
            .jitter_march = true;
        run_frames(&mut app, 1).unwrap();
        let before = shadow_maps(&app);
        run_frames(&mut app, 3).unwrap();
        assert_eq!(
            shadow_maps(&app),
            (before.0 + 12, before.1),
            "{path:?}: a caster's march follows the noise"
        );
    }
}
