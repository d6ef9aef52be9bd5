//! Max-mip on rays that enter exactly on a boundary: a texel centre (a corner of level-0
//! cells), a level-0 cell edge, the edge or corner of a cell of pyramid level 1, 2 or 3, or the
//! map's seam. On a map with a flat top at exactly 1 next to a drop and on a random map, at 60°,
//! 80° and 88°, along ±u, ±v and the four diagonals, the CPU reference and the GPU's march
//! (max_mip.wgsl, run by a compute pass on exactly these rays) both equal the exact
//! intersection (`pom::reference::exact_intersection_along`, piecewise along texel-centre
//! lines, no pyramid) on every ray, whatever the height sampler's address mode. Among them are
//! rays that enter on the top's rim, touch the field there and pass above the drop: they hit
//! further on, not at the touch.

use pom::glam::{Vec2, Vec3};
use pom::reference::{MaxPyramid, exact_intersection_along, march_max_mip, ray_offset};
use pom::wgpu;
use pom::{Channel, GpuContext, HeightConvention, HeightField};

/// Side of the maps, in texels: a power of two, so that texel centres are exact in uv.
const SIZE: u32 = 64;
/// Height range: at 88° a ray crosses 128 texels, two repetitions of the map.
const HEIGHT_SCALE: f32 = 0.1;
/// Largest distance, in texels, allowed between two answers for one ray.
const TOLERANCE: f32 = 0.05;

/// One view ray: it enters at `uv` and travels `offset` (the parallax offset vector) while it
/// falls from the top to the bottom of the height range.
#[derive(Clone, Copy, Debug)]
struct ViewRay {
    uv: Vec2,
    to_eye: Vec3,
    offset: Vec2,
}

impl ViewRay {
    /// Its entry in level-0 cell coordinates (texel centre i at i), for messages.
    fn entry_in_cells(&self) -> Vec2 {
        self.uv * SIZE as f32 - 0.5
    }
}

/// Entry points exactly on boundaries, in cell coordinates. For each level k in 0..=3, the
/// edges of level-k cells that are no edge of level k + 1 (odd multiples of 2^k), and the
/// seam (0): crossed by either axis with the other coordinate inside a cell, and corners
/// where two such edges meet (at level 0: texel centres).
fn boundary_entries() -> Vec<Vec2> {
    let odd_multiples = |spacing: u32| -> Vec<f32> {
        (1..SIZE / spacing)
            .step_by(2)
            .map(|index| (index * spacing) as f32)
            .collect()
    };
    let mut entries = Vec::new();
    for edges in (0..=3)
        .map(|level| odd_multiples(1 << level))
        .chain([vec![0.0]])
    {
        for (index, &edge) in edges.iter().enumerate() {
            // Inside a cell, at a different place along each edge.
            let inside = (index as f32 * 7.31 + 0.37) % SIZE as f32;
            let crossing_edge = edges[(index * 5 + 3) % edges.len()];
            entries.extend([
                Vec2::new(edge, inside),
                Vec2::new(inside, edge),
                Vec2::new(edge, crossing_edge),
            ]);
        }
    }
    entries
}

/// The rays from every boundary entry at 60°, 80° and 88° from the normal, travelling along
/// +u, −u, +v, −v and the four diagonals.
fn boundary_rays() -> Vec<ViewRay> {
    let travel_directions = [
        Vec2::X,
        -Vec2::X,
        Vec2::Y,
        -Vec2::Y,
        Vec2::new(1.0, 1.0),
        Vec2::new(-1.0, -1.0),
        Vec2::new(1.0, -1.0),
        Vec2::new(-1.0, 1.0),
    ];
    let mut rays = Vec::new();
    for angle in [60.0_f32, 80.0, 88.0] {
        let radians = angle.to_radians();
        for travel in travel_directions {
            // The eye is on the side the ray comes from.
            let to_eye = (-travel.normalize() * radians.sin()).extend(radians.cos());
            let offset = -ray_offset(to_eye, HEIGHT_SCALE);
            rays.extend(boundary_entries().into_iter().map(|cell| ViewRay {
                uv: (cell + 0.5) / SIZE as f32,
                to_eye,
                offset,
            }));
        }
    }
    rays
}

/// A flat top at exactly 1 over texels [16, 40) × [8, 40) (its rims on boundaries of levels
/// 0, 3 and 4), and around it a floor sloping from 0.7 down to 0.1: rays that start on the
/// rim at the top's height, and rays that leave the top over a drop or meet its side.
fn flat_top_next_to_a_drop() -> HeightField {
    HeightField::from_fn(SIZE, SIZE, |u, v| {
        let (x, y) = (u * SIZE as f32, v * SIZE as f32);
        if (16.0..40.0).contains(&x) && (8.0..40.0).contains(&y) {
            1.0
        } else {
            0.7 - 0.6 * u
        }
    })
    .quantized()
}

/// Heights from a fixed integer hash, in the 8-bit steps the GPU's texture holds.
fn random_map() -> HeightField {
    let hash = |index: u32| {
        let mut state = index.wrapping_mul(0x9E37_79B9) ^ 0x85EB_CA6B;
        state ^= state >> 15;
        state = state.wrapping_mul(0x2C1B_3C6D);
        state ^= state >> 12;
        (state >> 8) as f32 / (1 << 24) as f32
    };
    HeightField::new(SIZE, SIZE, (0..SIZE * SIZE).map(hash).collect())
        .expect("the values fill the map")
        .quantized()
}

/// Distance in texels between two texture coordinates on the repeating map.
fn texels_apart(a: Vec2, b: Vec2) -> f32 {
    let wrapped = pom_tests::pom_scene::wrapped;
    (Vec2::new(wrapped(a.x - b.x), wrapped(a.y - b.y)) * SIZE as f32).length()
}

/// Asserts that on every one of `rays` the hit of `method` is within [`TOLERANCE`] of the
/// hit of `against` (both one per ray), saying how far apart they are at most.
fn assert_hits_agree(
    context: &str,
    rays: &[ViewRay],
    (method, hits): (&str, &[Vec2]),
    (against, others): (&str, &[Vec2]),
) {
    let (largest, ray) = rays
        .iter()
        .zip(hits.iter().zip(others))
        .map(|(ray, (hit, other))| (texels_apart(*hit, *other), ray))
        .max_by(|a, b| a.0.total_cmp(&b.0))
        .expect("there are rays");
    eprintln!(
        "{context}: {} rays, largest |{method} − {against}| {largest:.5} texel",
        rays.len()
    );
    assert!(
        largest <= TOLERANCE,
        "{context}: {method} {largest} texels from the {against} hit for the ray entering at {} \
         along {}",
        ray.entry_in_cells(),
        ray.offset * SIZE as f32
    );
}

/// The maps the tests march, by name.
fn maps() -> [(&'static str, HeightField); 2] {
    [
        ("flat top next to a drop", flat_top_next_to_a_drop()),
        ("random", random_map()),
    ]
}

/// The CPU reference's hit for each ray, and the exact one.
fn cpu_and_exact_hits(field: &HeightField, rays: &[ViewRay]) -> (Vec<Vec2>, Vec<Vec2>) {
    let pyramid = MaxPyramid::new(field);
    rays.iter()
        .map(|ray| {
            let cpu = march_max_mip(&pyramid, ray.uv, ray.to_eye, HEIGHT_SCALE).uv;
            (cpu, exact_intersection_along(field, ray.uv, ray.offset))
        })
        .unzip()
}

#[test]
fn the_cpu_reference_is_exact_on_rays_entering_on_boundaries() {
    let rays = boundary_rays();
    for (name, field) in maps() {
        let (cpu, exact) = cpu_and_exact_hits(&field, &rays);
        assert_hits_agree(name, &rays, ("CPU", &cpu), ("exact", &exact));
    }
}

/// At every angle some boundary rays enter on the flat top's rim at its height (1), touch the
/// field there and pass above the drop, meeting it more than a texel on: the tests above hold
/// their hits to the exact ones.
#[test]
fn some_rays_touch_the_top_at_the_rim_and_go_on_at_every_angle() {
    let field = flat_top_next_to_a_drop();
    let rays = boundary_rays();
    let (_, exact) = cpu_and_exact_hits(&field, &rays);
    let per_angle = rays.len() / 3;
    for (angle, chunk) in [60, 80, 88]
        .into_iter()
        .zip(rays.chunks(per_angle).zip(exact.chunks(per_angle)))
    {
        let gone_on = chunk
            .0
            .iter()
            .zip(chunk.1)
            .filter(|(ray, hit)| {
                field.sample(ray.uv.x, ray.uv.y) == 1.0 && texels_apart(ray.uv, **hit) > 1.0
            })
            .count();
        eprintln!("{angle}°: {gone_on} rays touch the top at the rim and go on");
        assert!(gone_on > 0, "{angle}°: no ray touches the rim and goes on");
    }
}

/// A ray from the rim of a plateau at exactly 1 (texel columns 56..=64, wrapping to column 0;
/// a floor at 0.5 beyond) enters on the top plane and touches the field there. Falling 1/20 of
/// the height range a texel it passes above the drop (0.5 in a texel) and meets the floor 10
/// texels on; falling 2/3 a texel it goes under the drop at once, and so does a ray towards the
/// plateau. The CPU reference, the GPU and the exact intersection all say so.
#[test]
fn a_ray_touching_the_top_at_a_rim_goes_on_unless_it_falls_faster_than_the_drop() {
    let field = HeightField::from_fn(SIZE, SIZE, |u, _| {
        let column = (u * SIZE as f32) as u32;
        if column == 0 || column >= 56 {
            1.0
        } else {
            0.5
        }
    })
    .quantized();
    let floor = field.texel(10, 0);
    // (eye vector, height range: texels travelled along u = 0.75 × 64 × range, expected hit
    // along u in cells).
    let cases = [
        (Vec3::new(-0.6, 0.0, 0.8), 20.0 / 48.0, 20.0 * (1.0 - floor)),
        (Vec3::new(-0.6, 0.0, 0.8), 1.5 / 48.0, 0.0),
        (Vec3::new(0.6, 0.0, 0.8), 20.0 / 48.0, 0.0),
    ];
    let entry = Vec2::splat(0.5 / SIZE as f32);
    let gpu = GpuContext::headless().unwrap();
    for (to_eye, height_scale, expected) in cases {
        let offset = -ray_offset(to_eye, height_scale);
        let ray = ViewRay {
            uv: entry,
            to_eye,
            offset,
        };
        let cpu = march_max_mip(&MaxPyramid::new(&field), entry, to_eye, height_scale).uv;
        let exact = exact_intersection_along(&field, entry, offset);
        let on_gpu = gpu_hits(&gpu, &field, wgpu::AddressMode::Repeat, &[ray])[0];
        for (name, hit) in [("CPU", cpu), ("exact", exact), ("GPU", on_gpu)] {
            let along = pom_tests::pom_scene::wrapped(hit.x) * SIZE as f32 - 0.5;
            assert!(
                (along - expected).abs() < 1e-3,
                "{name}: travelling {} texels the ray meets the field at {along}, not {expected}",
                offset.x * SIZE as f32
            );
        }
    }
}

/// The compute entry point that runs max_mip.wgsl's `march_max_mip` on each of `rays` (entry
/// uv, offset) and stores (hit uv, height, fetches) in `hits`, one texel per ray.
const MARCH_RAYS: &str = "
@group(0) @binding(0) var height_texture: texture_2d<f32>;
@group(0) @binding(1) var height_sampler: sampler;
@group(0) @binding(2) var pyramid: texture_2d<f32>;
@group(0) @binding(3) var<storage, read> rays: array<vec4<f32>>;
@group(0) @binding(4) var hits: texture_storage_2d<rgba32float, write>;

@compute @workgroup_size(64)
fn march_rays(@builtin(global_invocation_id) id: vec3<u32>) {
    let index = id.y * textureDimensions(hits).x + id.x;
    if index >= arrayLength(&rays) {
        return;
    }
    let ray = rays[index];
    let field = HeightField(0u, 0u, 0.0, 0u, vec4<f32>(0.0), 0.0);
    let hit = march_max_mip(height_texture, height_sampler, pyramid, field, ray.xy, ray.zw);
    textureStore(hits, id.xy, vec4<f32>(hit.uv, hit.height, f32(hit.samples)));
}
";

/// Columns of the texture the compute pass stores its hits in (a multiple of 64).
const HITS_WIDTH: u32 = 256;

/// A texture of `format` for `usage`, `levels` mips of `width` × `height`, holding `data`
/// level after level if any.
fn texture(
    gpu: &GpuContext,
    (width, height, levels): (u32, u32, u32),
    format: wgpu::TextureFormat,
    usage: wgpu::TextureUsages,
    data: Option<&[u8]>,
) -> wgpu::Texture {
    use wgpu::util::DeviceExt;
    let descriptor = wgpu::TextureDescriptor {
        label: Some("max-mip edge test texture"),
        size: wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
        mip_level_count: levels,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage,
        view_formats: &[],
    };
    match data {
        Some(data) => gpu.device.create_texture_with_data(
            &gpu.queue,
            &descriptor,
            wgpu::util::TextureDataOrder::LayerMajor,
            data,
        ),
        None => gpu.device.create_texture(&descriptor),
    }
}

/// Where the GPU's max-mip march meets `field` along each of `rays`: the field as an 8-bit
/// texture read through a sampler with `address_mode`, the pyramid the GPU builds from it.
fn gpu_hits(
    gpu: &GpuContext,
    field: &HeightField,
    address_mode: wgpu::AddressMode,
    rays: &[ViewRay],
) -> Vec<Vec2> {
    let device = &gpu.device;
    let out_of_memory = device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
    let validation = device.push_error_scope(wgpu::ErrorFilter::Validation);
    let (width, height) = field.size();
    let image = field.to_image();
    let height_texture = texture(
        gpu,
        (width, height, 1),
        wgpu::TextureFormat::R8Unorm,
        wgpu::TextureUsages::TEXTURE_BINDING,
        Some(&image.pixels().bytes()),
    );
    let levels =
        pom::parallax::read_max_pyramid(gpu, image, Channel::Red, HeightConvention::Height)
            .unwrap();
    let maxima: Vec<f32> = levels
        .iter()
        .flat_map(|(_, _, maxima)| maxima.iter().copied())
        .collect();
    let pyramid = texture(
        gpu,
        (width, height, levels.len() as u32),
        wgpu::TextureFormat::R32Float,
        wgpu::TextureUsages::TEXTURE_BINDING,
        Some(bytemuck::cast_slice(&maxima)),
    );
    let rows = (rays.len() as u32).div_ceil(HITS_WIDTH);
    let hits = texture(
        gpu,
        (HITS_WIDTH, rows, 1),
        wgpu::TextureFormat::Rgba32Float,
        wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::COPY_SRC,
        None,
    );
    let ray_data: Vec<[f32; 4]> = rays
        .iter()
        .map(|ray| [ray.uv.x, ray.uv.y, ray.offset.x, ray.offset.y])
        .collect();
    let ray_buffer = wgpu::util::DeviceExt::create_buffer_init(
        device,
        &wgpu::util::BufferInitDescriptor {
            label: Some("max-mip edge test rays"),
            contents: bytemuck::cast_slice(&ray_data),
            usage: wgpu::BufferUsages::STORAGE,
        },
    );
    let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
        address_mode_u: address_mode,
        address_mode_v: address_mode,
        mag_filter: wgpu::FilterMode::Linear,
        min_filter: wgpu::FilterMode::Linear,
        ..Default::default()
    });
    let source = format!(
        "{}{}\n{}\n{}\n{MARCH_RAYS}",
        pom::parallax::PARALLAX_SHADER.generated(),
        pom::parallax::HEIGHT_CHANNEL.source,
        pom::parallax::PARALLAX_MARCH.source,
        pom::parallax::PARALLAX_MAX_MIP.source,
    );
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("max-mip edge test"),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    });
    let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some("max-mip edge test"),
        layout: None,
        module: &module,
        entry_point: Some("march_rays"),
        compilation_options: Default::default(),
        cache: None,
    });
    let views =
        [&height_texture, &pyramid, &hits].map(|texture| texture.create_view(&Default::default()));
    let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("max-mip edge test"),
        layout: &pipeline.get_bind_group_layout(0),
        entries: &[
            wgpu::BindGroupEntry {
                binding: 0,
                resource: wgpu::BindingResource::TextureView(&views[0]),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: wgpu::BindingResource::Sampler(&sampler),
            },
            wgpu::BindGroupEntry {
                binding: 2,
                resource: wgpu::BindingResource::TextureView(&views[1]),
            },
            wgpu::BindGroupEntry {
                binding: 3,
                resource: ray_buffer.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 4,
                resource: wgpu::BindingResource::TextureView(&views[2]),
            },
        ],
    });
    let mut encoder = device.create_command_encoder(&Default::default());
    {
        let mut pass = encoder.begin_compute_pass(&Default::default());
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &bind_group, &[]);
        pass.dispatch_workgroups(HITS_WIDTH / 64, rows, 1);
    }
    gpu.queue.submit([encoder.finish()]);
    let texels = pom::gpu::read_texture(gpu, &hits).unwrap();
    for scope in [validation, out_of_memory] {
        if let Some(error) = pollster::block_on(scope.pop()) {
            panic!("wgpu error while marching the rays: {error}");
        }
    }
    assert_eq!(gpu.take_uncaptured_errors(), Vec::<String>::new());
    bytemuck::cast_slice::<u8, [f32; 4]>(&texels)[..rays.len()]
        .iter()
        .map(|hit| Vec2::new(hit[0], hit[1]))
        .collect()
}

/// On every boundary ray over both maps, the GPU's hit through a sampler with `address_mode`
/// is the CPU reference's and the exact one.
fn assert_gpu_matches_on_boundary_rays(address_mode: wgpu::AddressMode) {
    let gpu = GpuContext::headless().unwrap();
    let rays = boundary_rays();
    for (name, field) in maps() {
        let (cpu, exact) = cpu_and_exact_hits(&field, &rays);
        let on_gpu = gpu_hits(&gpu, &field, address_mode, &rays);
        let context = format!("{name}, {address_mode:?}");
        assert_hits_agree(&context, &rays, ("GPU", &on_gpu), ("CPU", &cpu));
        assert_hits_agree(&context, &rays, ("GPU", &on_gpu), ("exact", &exact));
    }
}

#[test]
fn the_gpu_equals_the_cpu_reference_on_rays_entering_on_boundaries() {
    assert_gpu_matches_on_boundary_rays(wgpu::AddressMode::Repeat);
}

/// The field max-mip marches repeats whatever the height sampler does past the edge (a glTF
/// sampler may clamp or mirror): the patches across the map's seam are the wrapped ones.
#[test]
fn the_gpu_wraps_across_the_seam_whatever_the_sampler() {
    assert_gpu_matches_on_boundary_rays(wgpu::AddressMode::ClampToEdge);
    assert_gpu_matches_on_boundary_rays(wgpu::AddressMode::MirrorRepeat);
}
