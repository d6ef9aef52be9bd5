//! The GPU context: instance, adapter, device and queue, with or without a window surface.

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex, PoisonError};

/// What went wrong setting up the GPU.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum GpuError {
    /// No adapter matched the request.
    #[error(
        "no GPU adapter found ({reason}); on a machine without a GPU install Mesa's software \
         Vulkan driver (Debian/Ubuntu: apt-get install mesa-vulkan-drivers libvulkan1)"
    )]
    NoAdapter {
        /// wgpu's explanation.
        reason: String,
    },
    /// The adapter refused to create a device.
    #[error("the GPU adapter {adapter} could not create a device: {source}")]
    RequestDevice {
        /// The adapter's name.
        adapter: String,
        /// wgpu's error.
        source: wgpu::RequestDeviceError,
    },
}

/// The one instance of the process's headless contexts. With an instance per app, the Vulkan
/// loader loaded the driver with each app and unloaded it with it, and a driver may not survive
/// that: NVIDIA's takes a new piece of the process's static TLS with every load (glibc never
/// gives it back) and, after about 30 apps, no longer loads at all. Kept only once a context was
/// made on it, so a failed start is retried on a fresh instance.
static HEADLESS_INSTANCE: Mutex<Option<wgpu::Instance>> = Mutex::new(None);

fn kept_headless_instance() -> Option<wgpu::Instance> {
    HEADLESS_INSTANCE
        .lock()
        .unwrap_or_else(PoisonError::into_inner)
        .clone()
}

/// Keeps `instance` for later headless contexts unless one is kept already.
fn keep_headless_instance(instance: &wgpu::Instance) {
    HEADLESS_INSTANCE
        .lock()
        .unwrap_or_else(PoisonError::into_inner)
        .get_or_insert_with(|| instance.clone());
}

/// Owns the wgpu device and queue every renderer in the app shares.
///
/// Errors that no error scope catches are logged and kept (see
/// [`GpuContext::take_uncaptured_errors`]) instead of panicking, which is wgpu's default.
#[derive(Clone, Debug)]
pub struct GpuContext {
    /// The wgpu instance the adapter came from (needed to create window surfaces).
    pub instance: wgpu::Instance,
    /// The physical device.
    pub adapter: wgpu::Adapter,
    /// The logical device.
    pub device: wgpu::Device,
    /// The submission queue.
    pub queue: wgpu::Queue,
    uncaptured: Arc<Mutex<UncapturedErrors>>,
    /// Bytes written through [`GpuContext::write_buffer`] and [`GpuContext::write_texture`].
    uploaded: Arc<AtomicU64>,
}

impl GpuContext {
    /// Whether the adapter can write `format` from a compute shader (as a storage texture).
    pub fn can_store(&self, format: wgpu::TextureFormat) -> bool {
        self.adapter
            .get_texture_format_features(format)
            .allowed_usages
            .contains(wgpu::TextureUsages::STORAGE_BINDING)
    }

    /// A context for offscreen rendering, with a device and queue of its own. Honours wgpu's
    /// environment variables (`WGPU_BACKEND`, `WGPU_ADAPTER_NAME`, `WGPU_POWER_PREF`).
    ///
    /// Every headless context of the process shares one `wgpu::Instance`, made by the first
    /// (so `WGPU_BACKEND` is read then): dropping the app drops its device, not the driver.
    pub fn headless() -> Result<Self, GpuError> {
        let instance = kept_headless_instance().unwrap_or_else(|| {
            wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env())
        });
        let context = pollster::block_on(Self::from_instance(instance, None))?;
        keep_headless_instance(&context.instance);
        Ok(context)
    }

    /// A context whose adapter can present to `surface`, created from the same `instance`.
    pub fn for_surface(
        instance: wgpu::Instance,
        surface: &wgpu::Surface<'_>,
    ) -> Result<Self, GpuError> {
        pollster::block_on(Self::from_instance(instance, Some(surface)))
    }

    async fn from_instance(
        instance: wgpu::Instance,
        surface: Option<&wgpu::Surface<'_>>,
    ) -> Result<Self, GpuError> {
        let adapter = wgpu::util::initialize_adapter_from_env_or_default(&instance, surface)
            .await
            .map_err(|error| GpuError::NoAdapter {
                reason: error.to_string(),
            })?;
        let info = adapter.get_info();
        // Optional features the renderer uses when present: 16-bit height maps stay 16-bit
        // (R16Unorm) or exact (filterable R32Float); passes are timed (GpuTimings); fragment
        // shaders that test depth themselves still get the early test (shaders::create_module);
        // transparent surfaces blend into float measurement targets too; the deferred path's
        // visibility pass knows each pixel's triangle.
        let wanted = wgpu::Features::TEXTURE_FORMAT_16BIT_NORM
            | wgpu::Features::FLOAT32_FILTERABLE
            | wgpu::Features::TIMESTAMP_QUERY
            | wgpu::Features::SHADER_EARLY_DEPTH_TEST
            | wgpu::Features::FLOAT32_BLENDABLE
            | DEFERRED_FEATURES;
        let (device, queue) = adapter
            .request_device(&wgpu::DeviceDescriptor {
                label: Some("pom device"),
                required_features: adapter.features() & wanted,
                // Ask for what the adapter has, so large textures work where the hardware allows.
                required_limits: adapter.limits(),
                ..Default::default()
            })
            .await
            .map_err(|source| GpuError::RequestDevice {
                adapter: info.name.clone(),
                source,
            })?;
        let uncaptured = Arc::new(Mutex::new(UncapturedErrors::default()));
        let sink = Arc::clone(&uncaptured);
        device.on_uncaptured_error(Arc::new(move |error: wgpu::Error| {
            log::error!("wgpu error: {error}");
            if let Ok(mut errors) = sink.lock() {
                errors.keep(error.to_string());
            }
        }));
        log::info!(
            "GPU: {} ({:?}, {:?}, driver {} {})",
            info.name,
            info.device_type,
            info.backend,
            info.driver,
            info.driver_info
        );
        Ok(Self {
            instance,
            adapter,
            device,
            queue,
            uncaptured,
            uploaded: Arc::default(),
        })
    }

    /// The adapter's name, type, backend and driver.
    pub fn adapter_info(&self) -> wgpu::AdapterInfo {
        self.adapter.get_info()
    }

    /// Whether the device can make a buffer of `bytes` and bind it whole as storage.
    pub(crate) fn storage_buffer_fits(&self, bytes: u64) -> bool {
        bytes <= self.storage_buffer_limit()
    }

    /// The largest buffer the device can make and bind whole as storage, in bytes.
    pub(crate) fn storage_buffer_limit(&self) -> u64 {
        let limits = self.device.limits();
        limits
            .max_buffer_size
            .min(limits.max_storage_buffer_binding_size)
    }

    /// Writes `bytes` into `buffer` at `offset` through the queue (before the next submission's
    /// commands), counted in [`GpuContext::uploaded_bytes`]: every buffer write of the library
    /// goes through here, so a test can see what a frame uploads.
    pub fn write_buffer(&self, buffer: &wgpu::Buffer, offset: u64, bytes: &[u8]) {
        self.uploaded
            .fetch_add(bytes.len() as u64, Ordering::Relaxed);
        self.queue.write_buffer(buffer, offset, bytes);
    }

    /// Writes `bytes` into a texture through the queue, counted like
    /// [`GpuContext::write_buffer`].
    pub fn write_texture(
        &self,
        texture: wgpu::TexelCopyTextureInfo<'_>,
        bytes: &[u8],
        layout: wgpu::TexelCopyBufferLayout,
        size: wgpu::Extent3d,
    ) {
        self.uploaded
            .fetch_add(bytes.len() as u64, Ordering::Relaxed);
        self.queue.write_texture(texture, bytes, layout, size);
    }

    /// Writes `value` into `buffer` unless it equals `uploaded`, what the buffer last got (kept
    /// by its owner), which it then becomes; returns the bytes written.
    pub(crate) fn write_changed<T: bytemuck::Pod + PartialEq>(
        &self,
        buffer: &wgpu::Buffer,
        uploaded: &mut Option<T>,
        value: T,
    ) -> u64 {
        if *uploaded == Some(value) {
            return 0;
        }
        self.write_buffer(buffer, 0, bytemuck::bytes_of(&value));
        *uploaded = Some(value);
        std::mem::size_of::<T>() as u64
    }

    /// Bytes the library has written to buffers and textures through the queue since this
    /// context was made (shared by its clones).
    pub fn uploaded_bytes(&self) -> u64 {
        self.uploaded.load(Ordering::Relaxed)
    }

    /// Returns and clears the errors no error scope caught since the last call: the first
    /// [`MAX_KEPT_ERRORS`], then one line counting those past them.
    pub fn take_uncaptured_errors(&self) -> Vec<String> {
        self.uncaptured
            .lock()
            .map(|mut errors| std::mem::take(&mut *errors).into_lines())
            .unwrap_or_default()
    }
}

/// The most uncaptured errors kept between two calls of
/// [`GpuContext::take_uncaptured_errors`]: an app that never asks for them (a game, the editor)
/// and repeats an error every frame only counts the rest.
pub const MAX_KEPT_ERRORS: usize = 64;

/// The uncaptured errors kept, and how many came past [`MAX_KEPT_ERRORS`].
#[derive(Debug, Default)]
struct UncapturedErrors {
    kept: Vec<String>,
    past_the_limit: usize,
}

impl UncapturedErrors {
    fn keep(&mut self, error: String) {
        if self.kept.len() < MAX_KEPT_ERRORS {
            self.kept.push(error);
        } else {
            self.past_the_limit += 1;
        }
    }

    fn into_lines(mut self) -> Vec<String> {
        if self.past_the_limit > 0 {
            self.kept.push(format!(
                "{} more errors past the first {MAX_KEPT_ERRORS} (logged, not kept)",
                self.past_the_limit
            ));
        }
        self.kept
    }
}

/// The adapter features the deferred path needs: each pixel's triangle, and 64-bit atomic max
/// on the visibility keys.
pub const DEFERRED_FEATURES: wgpu::Features = wgpu::Features::PRIMITIVE_INDEX
    .union(wgpu::Features::SHADER_INT64)
    .union(wgpu::Features::SHADER_INT64_ATOMIC_MIN_MAX);
