//! GPU copies of meshes and images, uploaded when an asset is new or has changed.

use std::collections::HashMap;

use wgpu::util::DeviceExt;

use super::GpuContext;
use super::Vertex;
use super::derived_textures::{
    DerivedTexture, DerivedTextureBuilds, DerivedTextureCache, GpuDerivedTexture,
};
use super::scatter_upload::ScatterQueue;
use crate::{AssetId, Assets, Image, Mesh, Pixels, TextureKind};

/// A texture as it is bound on the GPU (after any downscaling at upload).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TextureFacts {
    /// Width of mip level 0 in texels.
    pub width: u32,
    /// Height of mip level 0 in texels.
    pub height: u32,
    /// Mip levels of the bound texture.
    pub mip_levels: u32,
}

/// A mesh's vertex and index buffers.
#[derive(Debug)]
pub struct GpuMesh {
    /// Interleaved [`Vertex`] data.
    pub vertices: wgpu::Buffer,
    /// `u32` indices.
    pub indices: wgpu::Buffer,
    /// Number of indices.
    pub index_count: u32,
}

/// An uploaded texture with its full mip chain.
#[derive(Debug)]
pub struct GpuImage {
    /// The texture.
    pub texture: wgpu::Texture,
    /// A view of every mip level.
    pub view: wgpu::TextureView,
    /// Distinguishes re-uploads of the same asset, so bind groups that use it are rebuilt.
    pub upload_serial: u64,
    /// How the image asks to be sampled.
    pub sampler: crate::ImageSampler,
}

impl GpuImage {
    /// Size and mip count of the texture as bound (an image over the device's limit was
    /// downscaled at upload; a GPU-written one has a single level).
    pub fn facts(&self) -> TextureFacts {
        let size = self.texture.size();
        TextureFacts {
            width: size.width,
            height: size.height,
            mip_levels: self.texture.mip_level_count(),
        }
    }
}

/// The state of one asset on the GPU: uploaded, or rejected at a given version.
#[derive(Debug)]
enum Cached<T> {
    Ready { version: u64, gpu: T },
    Rejected { version: u64 },
}

impl<T> Cached<T> {
    fn version(&self) -> u64 {
        match self {
            Cached::Ready { version, .. } | Cached::Rejected { version } => *version,
        }
    }
}

/// Upload counters of the last Prepare stage, for tests and the sandbox's statistics.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct UploadStats {
    /// Meshes uploaded (new or changed).
    pub meshes: u32,
    /// Images uploaded (new or changed).
    pub images: u32,
    /// Textures derived from images (maximum pyramids) queued to be built or rebuilt.
    pub derived: u32,
    /// Bytes written to uniform and storage buffers.
    pub uniform_bytes: u64,
}

/// 1×1 textures bound where a material has no texture of its own.
#[derive(Debug)]
pub struct DefaultTextures {
    /// White, sRGB: a neutral colour texture.
    pub white_srgb: wgpu::TextureView,
    /// (0.5, 0.5, 1): a flat tangent-space normal.
    pub flat_normal: wgpu::TextureView,
    /// White, linear: a height map at the top everywhere (no displacement).
    pub white_linear: wgpu::TextureView,
}

/// A 1×1 texture bound in a material's texture slot where the material has no image.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum DefaultTexture {
    /// White, sRGB: a neutral colour texture.
    WhiteSrgb,
    /// (0.5, 0.5, 1): a flat tangent-space normal.
    FlatNormal,
    /// White, linear: a height map at the top everywhere (no displacement).
    WhiteLinear,
}

impl DefaultTextures {
    /// The view of the named texture.
    pub fn view(&self, texture: DefaultTexture) -> &wgpu::TextureView {
        match texture {
            DefaultTexture::WhiteSrgb => &self.white_srgb,
            DefaultTexture::FlatNormal => &self.flat_normal,
            DefaultTexture::WhiteLinear => &self.white_linear,
        }
    }
}

/// A 1×1 texture of `format` holding the 4 bytes of `texel` (RGBA8, or one 32-bit float).
pub(crate) fn solid_texture(
    gpu: &GpuContext,
    label: &str,
    texel: [u8; 4],
    format: wgpu::TextureFormat,
) -> wgpu::TextureView {
    gpu.device
        .create_texture_with_data(
            &gpu.queue,
            &wgpu::TextureDescriptor {
                label: Some(label),
                size: wgpu::Extent3d::default(),
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage: wgpu::TextureUsages::TEXTURE_BINDING,
                view_formats: &[],
            },
            wgpu::util::TextureDataOrder::LayerMajor,
            &texel,
        )
        .create_view(&wgpu::TextureViewDescriptor {
            label: Some(&format!("{label} view")),
            ..Default::default()
        })
}

/// GPU versions of the assets in [`Assets<Mesh>`] and [`Assets<Image>`].
#[derive(Debug)]
pub struct GpuAssets {
    /// Stand-ins for missing textures.
    pub defaults: DefaultTextures,
    meshes: HashMap<AssetId<Mesh>, Cached<GpuMesh>>,
    images: HashMap<AssetId<Image>, Cached<GpuImage>>,
    derived: DerivedTextureCache,
    next_upload_serial: u64,
    scatters: ScatterQueue,
}

impl GpuAssets {
    /// An empty cache with the default textures uploaded.
    pub fn new(gpu: &GpuContext) -> Self {
        let srgb = wgpu::TextureFormat::Rgba8UnormSrgb;
        let linear = wgpu::TextureFormat::Rgba8Unorm;
        Self {
            defaults: DefaultTextures {
                white_srgb: solid_texture(gpu, "default white", [255; 4], srgb),
                flat_normal: solid_texture(
                    gpu,
                    "default flat normal",
                    [128, 128, 255, 255],
                    linear,
                ),
                white_linear: solid_texture(gpu, "default height", [255; 4], linear),
            },
            meshes: HashMap::new(),
            images: HashMap::new(),
            derived: DerivedTextureCache::new(gpu),
            next_upload_serial: 0,
            scatters: ScatterQueue::default(),
        }
    }

    /// Uploads `id` if it is new or changed since its last upload; returns whether it did.
    /// A mesh that fails validation is logged once per version and not drawn.
    pub fn prepare_mesh(
        &mut self,
        gpu: &GpuContext,
        meshes: &Assets<Mesh>,
        id: AssetId<Mesh>,
    ) -> bool {
        let Some(version) = meshes.version(id) else {
            return false;
        };
        if self
            .meshes
            .get(&id)
            .is_some_and(|cached| cached.version() == version)
        {
            return false;
        }
        let Some(mesh) = meshes.get(id) else {
            return false;
        };
        let cached = match upload_mesh(gpu, mesh, id) {
            Ok(gpu) => Cached::Ready { version, gpu },
            Err(error) => {
                log::error!("mesh {id:?} is not drawn: {error}");
                Cached::Rejected { version }
            }
        };
        self.meshes.insert(id, cached);
        true
    }

    /// Uploads `id` if it is new or changed since its last upload; returns whether it did.
    /// An image larger than the device allows is halved until it fits, with a logged warning.
    pub fn prepare_image(
        &mut self,
        gpu: &GpuContext,
        images: &Assets<Image>,
        id: AssetId<Image>,
    ) -> bool {
        let Some(version) = images.version(id) else {
            return false;
        };
        if self
            .images
            .get(&id)
            .is_some_and(|cached| cached.version() == version)
        {
            return false;
        }
        let Some(image) = images.get(id) else {
            return false;
        };
        let limit = gpu.device.limits().max_texture_dimension_2d;
        let (width, height) = image.size();
        let fitted;
        let image = if width > limit || height > limit {
            fitted = image.fitted_to(limit);
            let (new_width, new_height) = fitted.size();
            log::warn!(
                "image {id:?} is {width}×{height}, over the device's limit of {limit} texels per \
                 side: uploaded at {new_width}×{new_height}"
            );
            &fitted
        } else {
            image
        };
        self.next_upload_serial += 1;
        let cached = Cached::Ready {
            version,
            gpu: upload_image(gpu, image, id, self.next_upload_serial),
        };
        self.images.insert(id, cached);
        true
    }

    /// The uploaded mesh, if it exists and is valid.
    pub fn mesh(&self, id: AssetId<Mesh>) -> Option<&GpuMesh> {
        match self.meshes.get(&id) {
            Some(Cached::Ready { gpu, .. }) => Some(gpu),
            _ => None,
        }
    }

    /// The uploaded image, if it exists and fits the device.
    pub fn image(&self, id: AssetId<Image>) -> Option<&GpuImage> {
        match self.images.get(&id) {
            Some(Cached::Ready { gpu, .. }) => Some(gpu),
            _ => None,
        }
    }

    /// Counts uploads of images and derived textures: a texture's facts can have changed only
    /// where this has.
    pub(crate) fn upload_serial(&self) -> u64 {
        self.next_upload_serial
    }

    /// Queues the derivation of `derived` from its (uploaded) source if it is missing or older than the
    /// source's last upload; returns whether it did.
    pub(crate) fn prepare_derived(&mut self, gpu: &GpuContext, derived: DerivedTexture) -> bool {
        let Some(Cached::Ready { gpu: source, .. }) = self.images.get(&derived.source) else {
            return false;
        };
        let serial = self.next_upload_serial + 1;
        let built = self.derived.prepare(gpu, derived, source, serial);
        if built {
            self.next_upload_serial = serial;
        }
        built
    }

    /// The derived textures' builds queued and not yet submitted, for the frame to record
    /// before its phases.
    pub(crate) fn pending_derived_builds(&self) -> &DerivedTextureBuilds {
        self.derived.pending_builds()
    }

    /// The per-draw buffers' scattered uploads queued in the Prepare stage, for the frame to
    /// record before its phases.
    pub(crate) fn scatters(&mut self) -> &mut ScatterQueue {
        &mut self.scatters
    }

    /// Forgets the queued builds: the frame that recorded them was submitted.
    pub(crate) fn derived_builds_submitted(&mut self) {
        self.derived.builds_submitted();
    }

    /// The derived texture, if its source is on the GPU and it was prepared.
    pub(crate) fn derived(&self, derived: &DerivedTexture) -> Option<&GpuDerivedTexture> {
        self.derived.get(derived)
    }

    /// The view bound in a derived slot a draw leaves empty.
    pub(crate) fn default_derived_view(&self) -> &wgpu::TextureView {
        &self.derived.default_view
    }

    /// Once a frame: drops GPU copies of assets that no longer exist, what was derived from
    /// them, and derived textures no draw used in the last frame.
    pub fn release_freed(&mut self, meshes: &Assets<Mesh>, images: &Assets<Image>) {
        self.meshes.retain(|id, _| meshes.contains(*id));
        self.images.retain(|id, _| images.contains(*id));
        self.derived.sweep(|id| images.contains(id));
    }

    /// How many derived textures (maximum pyramids) the GPU holds.
    pub fn derived_count(&self) -> usize {
        self.derived.len()
    }
}

fn upload_mesh(
    gpu: &GpuContext,
    mesh: &Mesh,
    id: AssetId<Mesh>,
) -> Result<GpuMesh, crate::MeshError> {
    let complete;
    let mesh = if mesh.normals.is_empty() || mesh.uvs.is_empty() || mesh.tangents.is_empty() {
        complete = mesh.clone().with_generated_attributes()?;
        &complete
    } else {
        mesh.validate()?;
        mesh
    };
    // Checked before anything is allocated: wgpu panics making a buffer past the device's limit.
    let limit = gpu.storage_buffer_limit();
    check_buffer_size(
        "vertex buffer",
        mesh.positions.len(),
        size_of::<Vertex>(),
        limit,
    )?;
    check_buffer_size("index buffer", mesh.indices.len(), size_of::<u32>(), limit)?;
    let vertices: Vec<Vertex> = (0..mesh.positions.len())
        .map(|i| Vertex {
            position: mesh.positions[i],
            normal: mesh.normals[i],
            uv: mesh.uvs[i],
            tangent: mesh.tangents[i],
            color: mesh.colors.get(i).copied().unwrap_or([1.0; 4]),
        })
        .collect();
    let label = format!("{id:?}");
    Ok(GpuMesh {
        vertices: gpu
            .device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(&format!("{label} vertices")),
                contents: bytemuck::cast_slice(&vertices),
                // Storage too: the deferred resolve reads the triangles a pixel shows.
                usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::STORAGE,
            }),
        indices: gpu
            .device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(&format!("{label} indices")),
                contents: bytemuck::cast_slice(&mesh.indices),
                usage: wgpu::BufferUsages::INDEX | wgpu::BufferUsages::STORAGE,
            }),
        index_count: mesh.indices.len() as u32,
    })
}

/// Refuses a buffer of `count` elements of `element` bytes over `limit` bytes.
fn check_buffer_size(
    buffer: &'static str,
    count: usize,
    element: usize,
    limit: u64,
) -> Result<(), crate::MeshError> {
    let bytes = (count as u64).saturating_mul(element as u64);
    if bytes > limit {
        return Err(crate::MeshError::TooLarge {
            buffer,
            bytes,
            limit,
        });
    }
    Ok(())
}

/// How a level of an image becomes texels of its GPU format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Encoding {
    /// The stored bytes as they are.
    Raw,
    /// 16-bit values widened to 32-bit floats.
    Float32,
    /// 16-bit values narrowed to half floats.
    Float16,
}

/// The texture format an image is uploaded in, and how its bytes are converted. 16-bit heights
/// stay 16-bit (`R16Unorm`) where the device has the feature, else become floats.
fn gpu_format(gpu: &GpuContext, image: &Image) -> (wgpu::TextureFormat, Encoding) {
    let features = gpu.device.features();
    match (image.pixels(), image.kind()) {
        (Pixels::Rgba8(_), TextureKind::Color) => {
            (wgpu::TextureFormat::Rgba8UnormSrgb, Encoding::Raw)
        }
        (Pixels::Rgba8(_), _) => (wgpu::TextureFormat::Rgba8Unorm, Encoding::Raw),
        (Pixels::Gray8(_), _) => (wgpu::TextureFormat::R8Unorm, Encoding::Raw),
        (Pixels::Gray16(_), _) if features.contains(wgpu::Features::TEXTURE_FORMAT_16BIT_NORM) => {
            (wgpu::TextureFormat::R16Unorm, Encoding::Raw)
        }
        (Pixels::Gray16(_), _) if features.contains(wgpu::Features::FLOAT32_FILTERABLE) => {
            (wgpu::TextureFormat::R32Float, Encoding::Float32)
        }
        (Pixels::Gray16(_), _) => (wgpu::TextureFormat::R16Float, Encoding::Float16),
    }
}

/// The nearest half-float of a value in 0..=1 (enough for normalised heights).
fn f16_bits(value: f32) -> u16 {
    let value = value.clamp(0.0, 1.0);
    if value < 6.103_515_6e-5 {
        // Subnormal halves: steps of 2^-24.
        return (value * 16_777_216.0).round() as u16;
    }
    let bits = value.to_bits();
    let exponent = ((bits >> 23) & 0xff) as i32 - 127 + 15;
    let mantissa = bits & 0x7f_ffff;
    // Round to nearest on the 13 dropped mantissa bits; a carry correctly bumps the exponent.
    let half = ((exponent as u32) << 10) | (mantissa >> 13);
    (half + ((mantissa >> 12) & 1)) as u16
}

fn texel_bytes(pixels: &Pixels, encoding: Encoding) -> (Vec<u8>, u32) {
    match encoding {
        Encoding::Raw => (
            pixels.bytes(),
            pixels.channels() as u32
                * if matches!(pixels, Pixels::Gray16(_)) {
                    2
                } else {
                    1
                },
        ),
        Encoding::Float32 => (
            pixels
                .to_unit_floats()
                .iter()
                .flat_map(|v| v.to_le_bytes())
                .collect(),
            4,
        ),
        Encoding::Float16 => (
            pixels
                .to_unit_floats()
                .iter()
                .flat_map(|v| f16_bits(*v).to_le_bytes())
                .collect(),
            2,
        ),
    }
}

fn upload_image(
    gpu: &GpuContext,
    image: &Image,
    id: AssetId<Image>,
    upload_serial: u64,
) -> GpuImage {
    // A GPU-written image has one level: the pass that writes it keeps no mips up to date.
    let levels = if image.is_gpu_written() {
        vec![image.pixels().clone()]
    } else {
        image.mip_chain()
    };
    let (width, height) = image.size();
    let (format, encoding) = gpu_format(gpu, image);
    let label = format!("{id:?}");
    let texture = gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some(&label),
        size: wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
        mip_level_count: levels.len() as u32,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: if image.is_gpu_written() {
            // COPY_SRC so what the GPU wrote can be inspected.
            wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::COPY_DST
                | wgpu::TextureUsages::COPY_SRC
                | wgpu::TextureUsages::STORAGE_BINDING
        } else {
            wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST
        },
        view_formats: &[],
    });
    for (level, pixels) in levels.iter().enumerate() {
        let (level_width, level_height) = pixels.dimensions();
        let (bytes, bytes_per_texel) = texel_bytes(pixels, encoding);
        gpu.write_texture(
            wgpu::TexelCopyTextureInfo {
                texture: &texture,
                mip_level: level as u32,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            &bytes,
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(bytes_per_texel * level_width),
                rows_per_image: Some(level_height),
            },
            wgpu::Extent3d {
                width: level_width,
                height: level_height,
                depth_or_array_layers: 1,
            },
        );
    }
    let view = texture.create_view(&wgpu::TextureViewDescriptor {
        label: Some(&format!("{label} view")),
        ..Default::default()
    });
    GpuImage {
        texture,
        view,
        upload_serial,
        sampler: image.sampler(),
    }
}

#[cfg(test)]
mod tests {
    use super::{check_buffer_size, f16_bits};

    /// A mesh too large for the device (millions of vertices from a small glTF's flat normals,
    /// or a terrain of many cells) is an error naming the buffer and the limit; wgpu would
    /// panic making the buffer.
    #[test]
    fn a_mesh_buffer_over_the_device_limit_is_an_error() {
        assert!(check_buffer_size("vertex buffer", 1 << 20, 64, 1 << 26).is_ok());
        let error = check_buffer_size("vertex buffer", (1 << 20) + 1, 64, 1 << 26).unwrap_err();
        assert_eq!(
            error.to_string(),
            "mesh vertex buffer would take 67108928 bytes, over the device's limit of 67108864"
        );
        let error = check_buffer_size("index buffer", usize::MAX, 4, u64::MAX - 1).unwrap_err();
        assert!(error.to_string().contains("index buffer"), "{error}");
    }

    #[test]
    fn half_floats_round_to_nearest() {
        assert_eq!(f16_bits(0.0), 0);
        assert_eq!(f16_bits(1.0), 0x3c00);
        assert_eq!(f16_bits(0.5), 0x3800);
        assert_eq!(f16_bits(0.333_333_34), 0x3555);
        assert_eq!(f16_bits(2.0), 0x3c00, "clamped to 1");
        assert_eq!(f16_bits(1e-5), 168, "subnormal");
    }
}
