//! Reading a texture back from the GPU into CPU memory.

use std::time::Duration;

use image::{Rgba32FImage, RgbaImage};

use super::GpuContext;

/// What went wrong reading a texture back.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum CaptureError {
    /// The texture's format has no fixed texel size this function can copy.
    #[error("cannot read back a texture of format {0:?}")]
    UnsupportedFormat(wgpu::TextureFormat),
    /// The GPU did not finish in time or the device was lost.
    #[error("waiting for the GPU failed: {0}")]
    Poll(#[from] wgpu::PollError),
    /// Mapping the staging buffer failed.
    #[error("mapping the readback buffer failed: {0}")]
    Map(String),
    /// The texture's format does not match the image type asked for.
    #[error("texture format {found:?} cannot be read as {wanted}")]
    WrongFormat {
        /// The texture's format.
        found: wgpu::TextureFormat,
        /// What the caller asked for.
        wanted: &'static str,
    },
}

/// How long a readback waits for the GPU before giving up (software drivers are slow).
const READBACK_TIMEOUT: Duration = Duration::from_secs(120);

/// The texels of mip level 0 of a 2D texture, tightly packed row by row (no padding), in the
/// texture's own format.
///
/// The copy pads each row to `COPY_BYTES_PER_ROW_ALIGNMENT` as wgpu requires, so any width works.
pub fn read_texture(gpu: &GpuContext, texture: &wgpu::Texture) -> Result<Vec<u8>, CaptureError> {
    read_texture_level(gpu, texture, 0)
}

/// [`read_texture`] of mip level `level` (`UnsupportedFormat` past the last level, too).
#[doc(hidden)] // A test hook.
pub fn read_texture_level(
    gpu: &GpuContext,
    texture: &wgpu::Texture,
    level: u32,
) -> Result<Vec<u8>, CaptureError> {
    let format = texture.format();
    let texel_bytes = format
        .block_copy_size(None)
        .filter(|_| format.block_dimensions() == (1, 1) && level < texture.mip_level_count())
        .ok_or(CaptureError::UnsupportedFormat(format))?;
    let size = texture.size().mip_level_size(level, texture.dimension());
    let (width, height) = (size.width, size.height);
    let row_bytes = width * texel_bytes;
    let padded_row_bytes =
        row_bytes.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
    let staging = gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("readback staging buffer"),
        size: u64::from(padded_row_bytes) * u64::from(height),
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let mut encoder = gpu
        .device
        .create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("readback encoder"),
        });
    encoder.copy_texture_to_buffer(
        wgpu::TexelCopyTextureInfo {
            mip_level: level,
            ..texture.as_image_copy()
        },
        wgpu::TexelCopyBufferInfo {
            buffer: &staging,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(padded_row_bytes),
                rows_per_image: Some(height),
            },
        },
        size,
    );
    let submission = gpu.queue.submit([encoder.finish()]);

    let (sender, receiver) = std::sync::mpsc::channel();
    staging.map_async(wgpu::MapMode::Read, .., move |result| {
        let _ = sender.send(result);
    });
    gpu.device.poll(wgpu::PollType::Wait {
        submission_index: Some(submission),
        timeout: Some(READBACK_TIMEOUT),
    })?;
    receiver
        .recv()
        .map_err(|_| CaptureError::Map("the map callback never ran".into()))?
        .map_err(|error| CaptureError::Map(error.to_string()))?;

    // In 64 bits: a large float target's rows overflow u32.
    let mut texels =
        Vec::with_capacity(usize::try_from(u64::from(row_bytes) * u64::from(height)).unwrap_or(0));
    {
        let mapped = staging
            .get_mapped_range(..)
            .map_err(|error| CaptureError::Map(error.to_string()))?;
        for row in mapped.chunks_exact(padded_row_bytes as usize) {
            texels.extend_from_slice(&row[..row_bytes as usize]);
        }
    }
    staging.unmap();
    Ok(texels)
}

/// Reads an 8-bit RGBA texture (sRGB or not) back into an image, bytes as stored.
pub fn read_rgba8(gpu: &GpuContext, texture: &wgpu::Texture) -> Result<RgbaImage, CaptureError> {
    let format = texture.format();
    if !matches!(
        format,
        wgpu::TextureFormat::Rgba8Unorm | wgpu::TextureFormat::Rgba8UnormSrgb
    ) {
        return Err(CaptureError::WrongFormat {
            found: format,
            wanted: "8-bit RGBA",
        });
    }
    let texels = read_texture(gpu, texture)?;
    RgbaImage::from_raw(texture.width(), texture.height(), texels)
        .ok_or_else(|| CaptureError::Map("readback returned the wrong number of bytes".into()))
}

/// Reads an `Rgba32Float` texture back as raw floats.
pub fn read_rgba32f(
    gpu: &GpuContext,
    texture: &wgpu::Texture,
) -> Result<Rgba32FImage, CaptureError> {
    let format = texture.format();
    if format != wgpu::TextureFormat::Rgba32Float {
        return Err(CaptureError::WrongFormat {
            found: format,
            wanted: "32-bit float RGBA",
        });
    }
    let texels = read_texture(gpu, texture)?;
    let floats: Vec<f32> = bytemuck::pod_collect_to_vec(&texels);
    Rgba32FImage::from_raw(texture.width(), texture.height(), floats)
        .ok_or_else(|| CaptureError::Map("readback returned the wrong number of bytes".into()))
}
