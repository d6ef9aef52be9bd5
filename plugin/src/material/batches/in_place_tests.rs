//! A frame prepared in place leaves the per-draw data, the order and the batches exactly as the
//! full preparation makes them: two apps run the same edits, one always prepared in full.

use glam::{Quat, Vec3};
use hecs::Entity;

use super::MaterialBatches;
use crate::{
    AntiAliasing, App, Assets, Camera, DirectionalLight, Mesh, ParallaxOcclusionMaterial,
    PomPlugin, RenderPath, RenderPlugin, Transform,
};

type Batches = MaterialBatches<ParallaxOcclusionMaterial>;

/// Twenty planes in a grid under a camera with `anti_aliasing`, rendered on `path`.
fn grid_app(path: RenderPath, anti_aliasing: AntiAliasing) -> (App, Vec<Entity>) {
    let mut app = App::new();
    app.add_plugin(RenderPlugin::new(48, 48).with_path(path))
        .add_plugin(PomPlugin);
    app.finish().expect("a GPU (lavapipe in tests)");
    let plane = app
        .resources
        .get_mut::<Assets<Mesh>>()
        .unwrap()
        .add(Mesh::plane(0.9));
    let entities = (0..20)
        .map(|index| {
            let (x, z) = ((index % 5) as f32 - 2.0, (index / 5) as f32 - 2.0);
            app.world.spawn((
                plane.clone(),
                ParallaxOcclusionMaterial::default(),
                Transform::from_xyz(x, 0.0, z),
            ))
        })
        .collect();
    app.world.spawn((
        Camera::perspective(60.0),
        anti_aliasing,
        Transform::from_xyz(0.0, 4.0, 5.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    app.world.spawn((
        DirectionalLight::default(),
        Transform::IDENTITY.looking_at(Vec3::new(-1.0, -2.0, -1.0), Vec3::Y),
    ));
    (app, entities)
}

/// Frame `frame`'s edit: turns in place, a material edit, a nudge that keeps the order and a
/// move that changes it.
fn edit(app: &mut App, entities: &[Entity], frame: usize) {
    let transform = |index: usize| app.world.get::<&mut Transform>(entities[index]).unwrap();
    match frame {
        2 | 7 => {
            transform(3).rotation = Quat::from_rotation_y(frame as f32 * 0.3);
            transform(7).rotation = Quat::from_rotation_y(frame as f32 * 0.2);
        }
        5 => transform(10).translation.y += 0.001,
        6 => transform(0).translation.z -= 6.0,
        4 => {
            app.world
                .get::<&mut ParallaxOcclusionMaterial>(entities[5])
                .unwrap()
                .height_scale = 0.08;
        }
        _ => {}
    }
}

/// What the batches hold after a frame, as comparable values.
#[derive(Debug, PartialEq)]
struct Prepared {
    transforms: Vec<crate::render::MeshTransform>,
    uniforms: Vec<u8>,
    draws_in_order: Vec<usize>,
    batches: Vec<(std::ops::Range<u32>, std::ops::Range<u32>, bool, u32)>,
}

fn prepared(app: &App) -> Prepared {
    let batches = app.resources.get::<Batches>().unwrap();
    Prepared {
        transforms: batches.transform_data.clone(),
        uniforms: bytemuck::cast_slice(&batches.sorted_uniforms).to_vec(),
        draws_in_order: batches.order.iter().map(|entry| entry.draw).collect(),
        batches: batches
            .batches
            .iter()
            .map(|batch| {
                (
                    batch.instances.clone(),
                    batch.visibility_ids.clone(),
                    batch.moving,
                    batch.nearest_depth.to_bits(),
                )
            })
            .collect(),
    }
}

#[test]
fn a_frame_prepared_in_place_equals_the_full_preparation() {
    for path in [RenderPath::Forward, RenderPath::Deferred] {
        for anti_aliasing in [AntiAliasing::Off, AntiAliasing::Taa] {
            let (mut in_place, entities) = grid_app(path, anti_aliasing);
            let (mut full, full_entities) = grid_app(path, anti_aliasing);
            let mut frames_in_place = Vec::new();
            for frame in 0..9 {
                edit(&mut in_place, &entities, frame);
                edit(&mut full, &full_entities, frame);
                if let Some(batches) = full.resources.get_mut::<Batches>() {
                    batches.prepared_view = None;
                }
                in_place.update().unwrap();
                full.update().unwrap();
                let case = format!("{path:?}, {anti_aliasing:?}, frame {frame}");
                assert_eq!(prepared(&in_place), prepared(&full), "{case}");
                if in_place
                    .resources
                    .get::<Batches>()
                    .unwrap()
                    .prepared_in_place
                {
                    frames_in_place.push(frame);
                }
            }
            // The first frame, the frame after the material edit's (a new uniform value needs
            // no new order: in place) and the move that changes the order are prepared in full.
            assert_eq!(
                frames_in_place,
                [1, 2, 3, 4, 5, 7, 8],
                "{path:?}, {anti_aliasing:?}"
            );
        }
    }
}
