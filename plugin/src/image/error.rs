//! Why an image could not be built or loaded.

/// What went wrong building or loading an [`Image`](super::Image).
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ImageError {
    /// The file could not be read or decoded.
    #[error("cannot load image {path}: {reason}")]
    Load {
        /// The file (or the name of an embedded image).
        path: std::path::PathBuf,
        /// What the decoder or the file system said.
        reason: String,
    },
    /// Width or height is zero.
    #[error("image is {width}×{height}; both sides must be at least 1")]
    Empty {
        /// Width in pixels.
        width: u32,
        /// Height in pixels.
        height: u32,
    },
    /// The pixel buffer's length does not match the size.
    #[error("image of {width}×{height} needs {expected} bytes of RGBA8 but got {found}")]
    WrongLength {
        /// Width in pixels.
        width: u32,
        /// Height in pixels.
        height: u32,
        /// Bytes needed.
        expected: usize,
        /// Bytes given.
        found: usize,
    },
    /// The file declares a size over [`MAX_IMAGE_SIDE`](super::MAX_IMAGE_SIDE) or
    /// [`MAX_IMAGE_PIXELS`](super::MAX_IMAGE_PIXELS); it is refused before any pixel memory is
    /// allocated.
    #[error(
        "image {name} declares {width}×{height} pixels, over the limit of {max_side} per side \
         and {max_pixels} in all"
    )]
    TooLarge {
        /// The file or image name.
        name: String,
        /// Declared width.
        width: u32,
        /// Declared height.
        height: u32,
        /// [`MAX_IMAGE_SIDE`](super::MAX_IMAGE_SIDE).
        max_side: u32,
        /// [`MAX_IMAGE_PIXELS`](super::MAX_IMAGE_PIXELS).
        max_pixels: u64,
    },
    /// The image has no alpha channel but its alpha was asked for as a height.
    #[error("{name} has no alpha channel to read a height from")]
    NoAlpha {
        /// The file or image name.
        name: String,
    },
    /// Decoding the image (with the other images of its load) would pass the memory budget.
    #[error(
        "image {name} ({file_bytes} bytes, {width}×{height} pixels) needs {needed} bytes of \
         memory with the images loaded before it, over the budget of {budget} bytes"
    )]
    OverBudget {
        /// The file or image name.
        name: String,
        /// The file's size in bytes.
        file_bytes: u64,
        /// Declared width.
        width: u32,
        /// Declared height.
        height: u32,
        /// Bytes the load would claim with this image.
        needed: u64,
        /// The budget ([`IMAGE_MEMORY_BUDGET`](super::IMAGE_MEMORY_BUDGET) unless the load
        /// chose another).
        budget: u64,
    },
}
