//! What can go wrong rendering or capturing a frame.

use super::{NodeOrderError, PostChainError};
use crate::AppError;
use crate::gpu::{CaptureError, GpuError};

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
    /// The frame's feature nodes cannot be put in order.
    #[error(transparent)]
    NodeOrder(#[from] NodeOrderError),
    /// The post chain cannot run as its effects are.
    #[error(transparent)]
    PostChain(#[from] PostChainError),
    /// A resource the frame needs is missing.
    #[error(transparent)]
    App(#[from] AppError),
    /// The render plugin's resources are missing.
    #[error("nothing has been rendered yet: add RenderPlugin and call App::update first")]
    NotRendered,
}
