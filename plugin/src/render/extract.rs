//! The Extract stage: copy what the renderer needs out of the world, once per frame.

use glam::{Mat4, Vec3};
use hecs::World;

use super::gpu_types::{
    DirectionalLightGpu, FrameUniform, MAX_DIRECTIONAL_LIGHTS, MAX_POINT_LIGHTS, ObjectUniform,
    PointLightGpu,
};
use super::target::RenderTarget;
use crate::{
    AmbientLight, AppError, AssetId, Color, DirectionalLight, GlobalTransform, Handle, Image,
    LitMaterial, Mesh, ParallaxOcclusionMaterial, PointLight, Projection, Resources, active_camera,
};

/// One mesh to draw with its textures and per-object values.
#[derive(Clone, Debug, PartialEq)]
pub struct DrawItem {
    /// The mesh.
    pub mesh: AssetId<Mesh>,
    /// The colour texture, if any.
    pub base_color_texture: Option<AssetId<Image>>,
    /// The normal map, if any.
    pub normal_map: Option<AssetId<Image>>,
    /// Transform and material parameters.
    pub object: ObjectUniform,
}

/// Everything the Prepare and Render stages read about the current frame.
#[derive(Clone, Debug, PartialEq)]
pub struct ExtractedFrame {
    /// Camera and lights in GPU layout.
    pub frame: FrameUniform,
    /// The colour the target is cleared to.
    pub clear_color: Color,
    /// Whether an active camera was found (without one, the frame is only cleared).
    pub has_camera: bool,
    /// The meshes to draw, sorted so draws sharing textures are adjacent.
    pub draws: Vec<DrawItem>,
}

fn columns(matrix: Mat4) -> [[f32; 4]; 4] {
    matrix.to_cols_array_2d()
}

/// The Extract stage's system: reads cameras, lights and mesh entities into [`ExtractedFrame`].
pub fn extract_frame(world: &mut World, resources: &mut Resources) -> Result<(), AppError> {
    let aspect = resources.require::<RenderTarget>()?.aspect();
    let ambient = resources.get::<AmbientLight>().copied().unwrap_or_default();

    let camera = active_camera(world);
    let (view_projection, camera_position, view_direction, clear_color) = match camera {
        Some((camera, transform)) => {
            let view = transform.to_mat4().inverse();
            let orthographic = matches!(camera.projection, Projection::Orthographic { .. });
            (
                camera.projection.matrix(aspect) * view,
                transform.translation(),
                transform
                    .forward()
                    .extend(if orthographic { 1.0 } else { 0.0 }),
                camera.clear_color,
            )
        }
        None => (
            Mat4::IDENTITY,
            Vec3::ZERO,
            Vec3::NEG_Z.extend(0.0),
            Color::BLACK,
        ),
    };

    let mut frame = FrameUniform {
        view_projection: columns(view_projection),
        camera_position: camera_position.extend(1.0).into(),
        view_direction: view_direction.into(),
        ambient: (Vec3::new(ambient.color.r, ambient.color.g, ambient.color.b) * ambient.intensity)
            .extend(0.0)
            .into(),
        light_counts: [0; 4],
        directional_lights: [DirectionalLightGpu::default(); MAX_DIRECTIONAL_LIGHTS],
        point_lights: [PointLightGpu::default(); MAX_POINT_LIGHTS],
    };
    let radiance = |color: Color, intensity: f32| {
        let intensity = if intensity.is_finite() {
            intensity.max(0.0)
        } else {
            0.0
        };
        [
            color.r * intensity,
            color.g * intensity,
            color.b * intensity,
            0.0,
        ]
    };

    let mut directional_count = 0;
    for (light, transform) in world
        .query::<(&DirectionalLight, &GlobalTransform)>()
        .iter()
    {
        if directional_count == MAX_DIRECTIONAL_LIGHTS {
            log::warn!(
                "more than {MAX_DIRECTIONAL_LIGHTS} directional lights: the rest are ignored"
            );
            break;
        }
        frame.directional_lights[directional_count] = DirectionalLightGpu {
            direction_to_light: (-transform.forward()).extend(0.0).into(),
            radiance: radiance(light.color, light.intensity),
        };
        directional_count += 1;
    }
    let mut point_count = 0;
    for (light, transform) in world.query::<(&PointLight, &GlobalTransform)>().iter() {
        if point_count == MAX_POINT_LIGHTS {
            log::warn!("more than {MAX_POINT_LIGHTS} point lights: the rest are ignored");
            break;
        }
        frame.point_lights[point_count] = PointLightGpu {
            position_range: transform.translation().extend(light.range.max(0.0)).into(),
            radiance: radiance(light.color, light.intensity),
        };
        point_count += 1;
    }
    frame.light_counts = [directional_count as u32, point_count as u32, 0, 0];

    let default_material = LitMaterial::default();
    let mut draws: Vec<DrawItem> = world
        .query::<(&Handle<Mesh>, &GlobalTransform, Option<&LitMaterial>)>()
        // Parallax-mapped meshes are drawn by the parallax pass.
        .without::<&ParallaxOcclusionMaterial>()
        .iter()
        .filter_map(|(mesh, transform, material)| {
            let material = material.unwrap_or(&default_material);
            let model = transform.to_mat4();
            if !model.is_finite() {
                log::warn!("mesh {:?} has a non-finite transform: not drawn", mesh.id());
                return None;
            }
            let determinant = transform.0.matrix3.determinant();
            // A zero scale has no inverse; such an object has no area, so any normal will do.
            let normal_matrix = if determinant.abs() > f32::MIN_POSITIVE {
                model.inverse().transpose()
            } else {
                Mat4::IDENTITY
            };
            Some(DrawItem {
                mesh: mesh.id(),
                base_color_texture: material.base_color_texture.as_ref().map(Handle::id),
                normal_map: material.normal_map.as_ref().map(Handle::id),
                object: ObjectUniform {
                    model: columns(model),
                    normal_matrix: columns(normal_matrix),
                    base_color: material.base_color.to_array(),
                    params: [
                        material.normal_strength,
                        material.specular_strength,
                        material.shininess,
                        if determinant < 0.0 { -1.0 } else { 1.0 },
                    ],
                },
            })
        })
        .collect();
    draws.sort_by_key(|draw| (draw.base_color_texture, draw.normal_map, draw.mesh));

    resources.insert(ExtractedFrame {
        frame,
        clear_color,
        has_camera: camera.is_some(),
        draws,
    });
    Ok(())
}
