//! The seed port as one compute dispatch over the target (seed_port_compute.wgsl): listing 2's
//! march, soft shadow and lighting with no raster pass around them, the like-for-like figure
//! for our compute resolve. It shades the app's seed-port plane as the last frame drew it, into
//! the target's HDR scene texture, where the raster pass draws.

use bytemuck::{Pod, Zeroable};
use wgpu::util::DeviceExt;

use super::{SeedPortError, SeedPortMaterial, SeedPortUniform};
use crate::gpu::{GpuContext, PassTimestamps, time_pass};
use crate::material::{MAX_MATERIAL_TEXTURES, Material, TextureFacts};
use crate::render::shaders::{self, ComposedShader, ShaderTarget, WgslFile};
use crate::render::{ExtractedFrame, MeshTransform, RenderTarget, Renderer};
use crate::{AppError, Assets, GlobalTransform, Handle, Mesh, Resources};

/// The pass name the compute pass is timed under in [`crate::GpuTimings`].
pub const SEED_PORT_COMPUTE_PASS: &str = "seed port compute";
/// Pixels along each side of a workgroup (`@workgroup_size` in seed_port_compute.wgsl).
const WORKGROUP_SIDE: u32 = 8;

/// The compute entry point's file.
pub const SEED_PORT_COMPUTE_ENTRY: WgslFile = crate::wgsl_file!("seed_port/seed_port_compute.wgsl");

/// The seed port's compute shader: the same files as [`super::SEED_PORT_SHADER`], then the
/// compute entry point.
pub const SEED_PORT_COMPUTE_SHADER: ComposedShader =
    super::seed_port_shader!("seed_port_compute.wgsl", [SEED_PORT_COMPUTE_ENTRY]);

/// What the compute pass knows of the view and the plane (`SeedPortView` in
/// seed_port_compute.wgsl).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub(crate) struct SeedPortView {
    /// Clip space back to the world.
    inverse_view_projection: [[f32; 4]; 4],
    /// The plane's first triangle, object space (w unused).
    corner_positions: [[f32; 4]; 3],
    /// Its vertex normals (w unused).
    corner_normals: [[f32; 4]; 3],
    /// Its vertex tangents, w the MikkTSpace sign.
    corner_tangents: [[f32; 4]; 3],
    /// Its texture coordinates in xy.
    corner_uvs: [[f32; 4]; 3],
    /// xy: the target's size in pixels.
    target_size: [u32; 4],
    /// The plane solved on the CPU (world space, [`AnalyticPlane`]): a point of it (w unused).
    plane_point: [f32; 4],
    /// Its geometric normal (w unused).
    plane_normal: [f32; 4],
    /// Each uv as an affine function of the world point: dot with xyz, plus w.
    uv_from_world: [[f32; 4]; 2],
    /// The surface's world normal (w unused).
    surface_normal: [f32; 4],
    /// The surface's world tangent, w the bitangent's sign.
    surface_tangent: [f32; 4],
}

crate::wgsl_layout!(SeedPortView {
    inverse_view_projection,
    corner_positions,
    corner_normals,
    corner_tangents,
    corner_uvs,
    target_size,
    plane_point,
    plane_normal,
    uv_from_world,
    surface_normal,
    surface_tangent
});

/// What the compute pass rebuilds each pixel from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SeedPortSurface {
    /// The plane's first triangle through the vertex stage, as the raster pass has it
    /// (`cs_seed_port`): what our resolve does for every pixel.
    Triangle,
    /// The plane solved once on the CPU (`cs_seed_port_analytic`): a ray–plane intersection a
    /// pixel, no vertex to rebuild; the floor of a compute pass of listing 2.
    AnalyticPlane,
}

impl SeedPortSurface {
    /// The compute entry point.
    fn entry_point(self) -> &'static str {
        match self {
            Self::Triangle => "cs_seed_port",
            Self::AnalyticPlane => "cs_seed_port_analytic",
        }
    }
}

/// The plane of `view`'s triangle moved by `transform`, solved in world space: its point and
/// normal, uv as an affine function of the world point, and the surface frame of its first
/// corner (the plane's are the same at every corner).
fn solve_plane(view: &mut SeedPortView, transform: &MeshTransform) {
    let model = glam::Mat4::from_cols_array_2d(&transform.model);
    let normal_matrix = glam::Mat4::from_cols_array_2d(&transform.normal_matrix);
    let corner =
        |i: usize| model.transform_point3(glam::Vec4::from(view.corner_positions[i]).truncate());
    let uv = |i: usize| glam::Vec2::new(view.corner_uvs[i][0], view.corner_uvs[i][1]);
    let p0 = corner(0);
    let (edge1, edge2) = (corner(1) - p0, corner(2) - p0);
    let (d11, d12, d22) = (edge1.dot(edge1), edge1.dot(edge2), edge2.dot(edge2));
    let determinant = d11 * d22 - d12 * d12;
    // The barycentrics of an offset o from p0 are (o · g1, o · g2) (Cramer's rule on the Gram
    // matrix, as the triangle's pass solves it per pixel).
    let g1 = (edge1 * d22 - edge2 * d12) / determinant;
    let g2 = (edge2 * d11 - edge1 * d12) / determinant;
    let (duv1, duv2) = (uv(1) - uv(0), uv(2) - uv(0));
    let row = |axis: usize| {
        let gradient = g1 * duv1[axis] + g2 * duv2[axis];
        gradient.extend(uv(0)[axis] - gradient.dot(p0)).to_array()
    };
    let normal =
        normal_matrix.transform_vector3(glam::Vec4::from(view.corner_normals[0]).truncate());
    let tangent = glam::Vec4::from(view.corner_tangents[0]);
    view.plane_point = p0.extend(0.0).to_array();
    view.plane_normal = edge1.cross(edge2).extend(0.0).to_array();
    view.uv_from_world = [row(0), row(1)];
    view.surface_normal = normal.extend(0.0).to_array();
    view.surface_tangent = model
        .transform_vector3(tangent.truncate())
        .extend(tangent.w * transform.determinant_sign)
        .to_array();
}

/// Listing 2 as a compute pass over the target, for the one plane drawn with a
/// [`SeedPortMaterial`]: the same textures, settings, camera and light as the raster pass.
#[derive(Debug)]
pub struct SeedPortCompute {
    pipeline: wgpu::ComputePipeline,
    bind_groups: [wgpu::BindGroup; 3],
    workgroups: (u32, u32),
}

/// The plane's first triangle and its transform, as the raster pass draws it.
fn plane_triangle(
    world: &hecs::World,
    resources: &Resources,
) -> Result<(SeedPortMaterial, SeedPortView, MeshTransform), SeedPortError> {
    let mut query = world.query::<(&SeedPortMaterial, &Handle<Mesh>, &GlobalTransform)>();
    let (material, mesh, transform) = query.iter().next().ok_or(SeedPortError::NoPlane)?;
    let meshes = resources.require::<Assets<Mesh>>()?;
    let mesh = meshes.get(mesh).ok_or(SeedPortError::NoTriangle)?;
    let corners = mesh.indices.get(..3).ok_or(SeedPortError::NoTriangle)?;
    let corner =
        |list: &dyn Fn(usize) -> Option<[f32; 4]>| -> Result<[[f32; 4]; 3], SeedPortError> {
            let mut out = [[0.0; 4]; 3];
            for (slot, &index) in out.iter_mut().zip(corners) {
                *slot = list(index as usize).ok_or(SeedPortError::NoTriangle)?;
            }
            Ok(out)
        };
    let extend = |v: &[f32; 3]| [v[0], v[1], v[2], 0.0];
    let view = SeedPortView {
        inverse_view_projection: [[0.0; 4]; 4],
        corner_positions: corner(&|i| mesh.positions.get(i).map(extend))?,
        corner_normals: corner(&|i| mesh.normals.get(i).map(extend))?,
        corner_tangents: corner(&|i| mesh.tangents.get(i).copied())?,
        corner_uvs: corner(&|i| mesh.uvs.get(i).map(|uv| [uv[0], uv[1], 0.0, 0.0]))?,
        target_size: [0; 4],
        ..SeedPortView::zeroed()
    };
    Ok((
        material.clone(),
        view,
        MeshTransform::new(transform.to_mat4(), false),
    ))
}

/// One of the material's images as the renderer uploaded it.
#[derive(Clone, Copy)]
struct Uploaded<'a> {
    view: &'a wgpu::TextureView,
    sampler: crate::ImageSampler,
    facts: TextureFacts,
}

/// The material's images as the renderer uploaded them, slot by slot (`None`: the slot's
/// default), and the per-draw uniform the raster pass gives it.
fn uploaded_textures<'a>(
    material: &SeedPortMaterial,
    renderer: &'a Renderer,
) -> Result<(Vec<Option<Uploaded<'a>>>, SeedPortUniform), SeedPortError> {
    let images: Vec<_> = material.textures()[..SeedPortMaterial::TEXTURE_SLOTS.len()]
        .iter()
        .map(|id| {
            id.map(|id| {
                let image = renderer
                    .assets
                    .image(id)
                    .ok_or(SeedPortError::NotRendered)?;
                Ok::<_, SeedPortError>(Uploaded {
                    view: &image.view,
                    sampler: image.sampler,
                    facts: image.facts(),
                })
            })
            .transpose()
        })
        .collect::<Result<_, _>>()?;
    let mut facts: [Option<TextureFacts>; MAX_MATERIAL_TEXTURES] = [None; MAX_MATERIAL_TEXTURES];
    for (slot, image) in facts.iter_mut().zip(&images) {
        *slot = image.map(|image| image.facts);
    }
    let per_draw = material.per_draw(&facts);
    Ok((images, per_draw))
}

/// Group 1 as the raster pass binds it (TextureBindGroups): each slot's image or its default,
/// and the sampler of the first image (trilinear and repeating without one).
fn texture_group(
    device: &wgpu::Device,
    layout: &wgpu::BindGroupLayout,
    images: &[Option<Uploaded<'_>>],
    renderer: &Renderer,
) -> wgpu::BindGroup {
    let views: Vec<&wgpu::TextureView> = images
        .iter()
        .zip(SeedPortMaterial::TEXTURE_SLOTS)
        .map(|(image, default)| {
            image.map_or(renderer.assets.defaults.view(*default), |image| image.view)
        })
        .collect();
    let sampler_settings = images
        .iter()
        .flatten()
        .next()
        .map_or_else(crate::ImageSampler::default, |image| image.sampler);
    let sampler = sampler_settings.create(device, SEED_PORT_COMPUTE_PASS);
    let mut entries: Vec<wgpu::BindGroupEntry> = views
        .iter()
        .enumerate()
        .map(|(slot, view)| entry(slot as u32, wgpu::BindingResource::TextureView(view)))
        .collect();
    entries.push(entry(
        views.len() as u32,
        wgpu::BindingResource::Sampler(&sampler),
    ));
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some(SEED_PORT_COMPUTE_PASS),
        layout,
        entries: &entries,
    })
}

/// The pass's four buffers, in binding order: frame, transform, material, view.
fn upload_buffers<F: bytemuck::Pod, T: bytemuck::Pod, M: bytemuck::Pod, V: bytemuck::Pod>(
    device: &wgpu::Device,
    frame: &F,
    transform: &T,
    material: &M,
    view: &V,
) -> [wgpu::Buffer; 4] {
    let buffer = |label: &str, contents: &[u8], usage: wgpu::BufferUsages| {
        device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(label),
            contents,
            usage,
        })
    };
    let (uniform, storage) = (wgpu::BufferUsages::UNIFORM, wgpu::BufferUsages::STORAGE);
    [
        buffer(
            "seed port compute frame",
            bytemuck::bytes_of(frame),
            uniform,
        ),
        buffer(
            "seed port compute transform",
            bytemuck::bytes_of(transform),
            storage,
        ),
        buffer(
            "seed port compute material",
            bytemuck::bytes_of(material),
            storage,
        ),
        buffer("seed port compute view", bytemuck::bytes_of(view), uniform),
    ]
}

impl SeedPortCompute {
    /// The pass for the seed-port plane of `world` (the first, if several) as the app's last
    /// frame extracted and uploaded it: its camera and lights, its textures on the GPU, the
    /// target it drew into. Render a frame first; make the pass again after changing any of it.
    ///
    /// # Errors
    /// [`SeedPortError::NoPlane`] without a seed-port plane, [`SeedPortError::NoTriangle`] when
    /// its mesh is not loaded, [`SeedPortError::NotRendered`] before a frame uploaded its
    /// textures, [`SeedPortError::App`] without the render plugin's resources.
    pub fn new(world: &hecs::World, resources: &Resources) -> Result<Self, SeedPortError> {
        Self::on(world, resources, SeedPortSurface::Triangle)
    }

    /// As [`SeedPortCompute::new`], rebuilding each pixel from `surface`.
    ///
    /// # Errors
    /// As [`SeedPortCompute::new`].
    pub fn on(
        world: &hecs::World,
        resources: &Resources,
        surface: SeedPortSurface,
    ) -> Result<Self, SeedPortError> {
        let gpu = resources.require::<GpuContext>()?;
        let target = resources.require::<RenderTarget>()?;
        let renderer = resources.require::<Renderer>()?;
        let frame = resources
            .get::<ExtractedFrame>()
            .ok_or(SeedPortError::NotRendered)?;
        let (material, mut view, transform) = plane_triangle(world, resources)?;
        let view_projection = glam::Mat4::from_cols_array_2d(&frame.frame.view_projection);
        let (width, height) = target.size();
        view.inverse_view_projection = view_projection.inverse().to_cols_array_2d();
        view.target_size = [width, height, 0, 0];
        solve_plane(&mut view, &transform);

        let (images, per_draw) = uploaded_textures(&material, renderer)?;

        let device = &gpu.device;
        let pipeline = compute_pipeline(device, target.scene_format(), surface);
        let buffers = upload_buffers(device, &frame.frame, &transform, &per_draw, &view);
        let group = |index: u32, entries: &[wgpu::BindGroupEntry]| {
            device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some(SEED_PORT_COMPUTE_PASS),
                layout: &pipeline.get_bind_group_layout(index),
                entries,
            })
        };
        // The analytic plane transforms no vertex: its pipeline's layout has no transforms.
        let transforms = (surface == SeedPortSurface::Triangle)
            .then(|| entry(1, buffers[1].as_entire_binding()));
        let frame_entries: Vec<_> = [
            Some(entry(0, buffers[0].as_entire_binding())),
            transforms,
            Some(entry(2, buffers[2].as_entire_binding())),
            // `light_at` reads the point lights (the seed's one light is the first of all).
            Some(entry(
                crate::render::frame_group::POINT_LIGHTS,
                renderer.lights.point_lights().as_entire_binding(),
            )),
        ]
        .into_iter()
        .flatten()
        .collect();
        let frame_group = group(0, &frame_entries);
        let texture_group = texture_group(
            device,
            &pipeline.get_bind_group_layout(1),
            &images,
            renderer,
        );
        let view_group = group(
            2,
            &[
                entry(0, buffers[3].as_entire_binding()),
                entry(1, wgpu::BindingResource::TextureView(&target.scene_view)),
            ],
        );
        Ok(Self {
            pipeline,
            bind_groups: [frame_group, texture_group, view_group],
            workgroups: (
                width.div_ceil(WORKGROUP_SIDE),
                height.div_ceil(WORKGROUP_SIDE),
            ),
        })
    }

    /// Runs the pass over the app's [`RenderTarget`] scene texture, timed as
    /// [`SEED_PORT_COMPUTE_PASS`] when GPU timing is on, and submits. Call
    /// [`crate::gpu::resolve_gpu_timings`] afterwards to read the time.
    ///
    /// # Errors
    /// [`AppError`] without the render plugin's GPU context.
    pub fn render(&self, resources: &mut Resources) -> Result<(), AppError> {
        let timestamps = time_pass(resources, SEED_PORT_COMPUTE_PASS);
        let gpu = resources.require::<GpuContext>()?;
        let mut encoder = gpu
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("seed port compute encoder"),
            });
        {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some(SEED_PORT_COMPUTE_PASS),
                timestamp_writes: timestamps.as_ref().map(PassTimestamps::compute),
            });
            pass.set_pipeline(&self.pipeline);
            for (index, group) in self.bind_groups.iter().enumerate() {
                pass.set_bind_group(index as u32, group, &[]);
            }
            pass.dispatch_workgroups(self.workgroups.0, self.workgroups.1, 1);
        }
        gpu.queue.submit([encoder.finish()]);
        Ok(())
    }
}

/// The pipeline of `surface`'s entry point, writing a scene texture of `scene_format`.
fn compute_pipeline(
    device: &wgpu::Device,
    scene_format: wgpu::TextureFormat,
    surface: SeedPortSurface,
) -> wgpu::ComputePipeline {
    let shader_target = ShaderTarget::of_device(device, scene_format);
    let source = SEED_PORT_COMPUTE_SHADER.source_for(&shader_target);
    let module = shaders::create_module(device, SEED_PORT_COMPUTE_SHADER.name, source);
    device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some(SEED_PORT_COMPUTE_PASS),
        layout: None,
        module: &module,
        entry_point: Some(surface.entry_point()),
        compilation_options: Default::default(),
        cache: None,
    })
}

fn entry(binding: u32, resource: wgpu::BindingResource<'_>) -> wgpu::BindGroupEntry<'_> {
    wgpu::BindGroupEntry { binding, resource }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_view_matches_its_wgsl() {
        let source = SEED_PORT_COMPUTE_SHADER.source();
        assert_eq!(
            crate::shader::check_wgsl_layout::<SeedPortView>(&source, "SeedPortView"),
            Ok(())
        );
    }
}
