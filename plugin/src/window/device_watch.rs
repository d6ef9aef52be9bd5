//! Notices when the GPU device is lost (driver reset, GPU removed, device destroyed), so a
//! window can close with one clear message instead of failing on every later GPU call.

use std::sync::{Arc, Mutex};

/// Set by wgpu's device-lost callback; read once per frame.
#[derive(Clone, Debug, Default)]
pub struct DeviceWatch {
    lost: Arc<Mutex<Option<String>>>,
}

impl DeviceWatch {
    /// Watches `device`, replacing any device-lost callback it had.
    pub fn new(device: &wgpu::Device) -> Self {
        let watch = Self::default();
        let lost = Arc::clone(&watch.lost);
        device.set_device_lost_callback(move |reason, message| {
            // A warning: the runner recovers, and says so.
            log::warn!("GPU device lost ({reason:?}): {message}");
            if let Ok(mut lost) = lost.lock() {
                *lost = Some(format!("{reason:?}: {message}"));
            }
        });
        watch
    }

    /// Why the device was lost, once it has been.
    pub fn lost(&self) -> Option<String> {
        self.lost.lock().ok().and_then(|lost| lost.clone())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_destroyed_device_is_reported_as_lost() {
        let gpu = crate::GpuContext::headless().expect("a GPU or lavapipe for this test");
        let watch = DeviceWatch::new(&gpu.device);
        assert_eq!(watch.lost(), None);
        gpu.device.destroy();
        let _ = gpu.device.poll(wgpu::PollType::wait_indefinitely());
        let reason = watch.lost().expect("the callback ran");
        assert!(reason.starts_with("Destroyed"), "{reason}");
    }
}
