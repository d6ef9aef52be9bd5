//! Where pipelines compile: in the frame that first needs them (blocking, the default: a
//! headless capture is then exact from its first frame), or on worker threads while frames go
//! on drawing a material's fallback variant (a window's frames never wait for a compile).

use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Duration;

use crate::Resources;

/// How the app's material pipelines compile. A resource; without it they compile blocking.
/// `WindowPlugin` inserts [`PipelineCompilation::background`].
#[derive(Clone, Debug, Default)]
pub struct PipelineCompilation {
    background: bool,
    /// Compiles started on worker threads and not finished.
    in_flight: Arc<AtomicUsize>,
}

impl PipelineCompilation {
    /// Pipelines compile in the frame that first needs them.
    pub fn blocking() -> Self {
        Self::default()
    }

    /// Pipelines compile on worker threads; until a variant's are ready, its draws use the
    /// material's fallback ([`crate::Material::fallback_key`]).
    pub fn background() -> Self {
        Self {
            background: true,
            ..Self::default()
        }
    }

    /// Whether pipelines compile on worker threads.
    pub fn is_background(&self) -> bool {
        self.background
    }

    /// How many compiles are running on worker threads.
    pub fn in_flight(&self) -> usize {
        self.in_flight.load(Ordering::Acquire)
    }

    /// The counter the worker threads keep, where compiles run in the background.
    pub(crate) fn background_counter(&self) -> Option<Arc<AtomicUsize>> {
        self.background.then(|| Arc::clone(&self.in_flight))
    }
}

/// Waits until no pipeline compile of the app runs on a worker thread: the next update then
/// draws every variant with its own pipelines. Call it before a capture that must be exact
/// in an app that compiles in the background; with blocking compiles it returns at once.
pub fn wait_for_pipelines(resources: &Resources) {
    if let Some(compilation) = resources.get::<PipelineCompilation>() {
        while compilation.in_flight() > 0 {
            std::thread::sleep(Duration::from_millis(1));
        }
    }
}
