//! What can go wrong rendering or capturing a frame.

use super::{CaptureError, GpuError};

/// Everything that can go wrong when rendering or capturing a frame.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum RenderError {
    /// GPU setup failed.
    #[error(transparent)]
    Gpu(#[from] GpuError),
    /// Reading the image back failed.
    #[error(transparent)]
    Capture(#[from] CaptureError),
    /// The render plugin's resources are missing.
    #[error("nothing has been rendered yet: add RenderPlugin and call App::update first")]
    NotRendered,
}
