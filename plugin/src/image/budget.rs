//! The memory budget of the images one load decodes: a file that decodes to far more than its
//! size (a small, flat PNG of 16384 × 8192) is refused before its pixels are allocated.

use super::ImageError;

/// Bytes of memory the images of one scene (or one image file loaded on its own) may claim:
/// their decoded pixels, the pixels kept for the GPU, and the largest image's 32-bit float mip
/// levels while they are built. Enough for one 4096 × 4096 RGBA texture beside several others.
pub const IMAGE_MEMORY_BUDGET: u64 = 512 << 20;

/// Bytes a texel claims while a mip chain is built from it: four 32-bit float channels, and the
/// next level's quarter.
const MIP_WORK_BYTES_PER_TEXEL: u64 = 20;

/// What the images of one load claim so far, against a limit.
#[derive(Debug)]
pub(crate) struct ImageBudget {
    limit: u64,
    /// Decoded and converted pixels held until the load ends.
    resident: u64,
    /// The largest working memory of one image beyond what it holds.
    largest_work: u64,
}

impl ImageBudget {
    /// A budget of `limit` bytes, nothing claimed.
    pub(crate) fn new(limit: u64) -> Self {
        Self {
            limit,
            resident: 0,
            largest_work: 0,
        }
    }

    fn check(
        &self,
        name: &str,
        file_bytes: u64,
        (width, height): (u32, u32),
    ) -> Result<(), ImageError> {
        let needed = self.resident.saturating_add(self.largest_work);
        if needed > self.limit {
            return Err(ImageError::OverBudget {
                name: name.to_owned(),
                file_bytes,
                width,
                height,
                needed,
                budget: self.limit,
            });
        }
        Ok(())
    }

    /// Claims the decoding of image `name` (`file_bytes` long) of `size` texels of
    /// `bytes_per_texel`; returns the decoded size.
    pub(crate) fn reserve_decode(
        &mut self,
        name: &str,
        file_bytes: u64,
        size: (u32, u32),
        bytes_per_texel: u64,
    ) -> Result<u64, ImageError> {
        let texels = u64::from(size.0) * u64::from(size.1);
        let decoded = texels.saturating_mul(bytes_per_texel);
        let before = (self.resident, self.largest_work);
        self.resident = self.resident.saturating_add(decoded);
        self.largest_work = self
            .largest_work
            .max(texels.saturating_mul(MIP_WORK_BYTES_PER_TEXEL));
        if let Err(error) = self.check(name, file_bytes, size) {
            (self.resident, self.largest_work) = before;
            return Err(error);
        }
        Ok(decoded)
    }

    /// Claims `bytes` of pixels kept from image `name` (a conversion of a decoded image).
    pub(crate) fn reserve_kept(
        &mut self,
        name: &str,
        file_bytes: u64,
        size: (u32, u32),
        bytes: u64,
    ) -> Result<(), ImageError> {
        self.resident = self.resident.saturating_add(bytes);
        self.check(name, file_bytes, size).inspect_err(|_| {
            self.resident -= bytes;
        })
    }
}
