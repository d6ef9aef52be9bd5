//! What a game needs to run in a window (feature `window`): [`WindowPlugin`] opens it and
//! [`crate::App::run`] hands the app to a winit event loop, which updates the app once per
//! redraw and presents its display target; input arrives as resources ([`ButtonInput`],
//! [`MouseMotion`], ...). `POM_EXIT_AFTER_FRAMES` and `POM_SCREENSHOT` drive any windowed app
//! from CI ([`Automation`]).
//!
//! ```no_run
//! use pom::window::{AppExit, WindowPlugin};
//! fn main() -> AppExit {
//!     let mut app = pom::App::new();
//!     app.add_plugin(pom::DefaultPlugins::windowed(WindowPlugin::default()));
//!     app.run()
//! }
//! ```

mod app_exit;
mod automation;
mod device_watch;
mod fly_camera;
mod frame_times;
mod input;
mod orbit_camera;
mod overlay;
mod panic_report;
mod present;
mod reported_failures;
mod runner;
mod screenshot;
mod surface;

pub use app_exit::AppExit;
pub use automation::{
    Automation, AutomationError, EXIT_AFTER_FRAMES_VAR, FRAME_TIMES_VAR, SCREENSHOT_VAR,
};
pub use device_watch::DeviceWatch;
pub use fly_camera::{FlyCamera, FlyCameraPlugin, fly_cameras};
pub use input::{
    ButtonInput, CursorPosition, KeyCode, MouseButton, MouseMotion, MouseScroll, WindowEvents,
    update_input,
};
pub use orbit_camera::{CameraInput, OrbitCamera, OrbitCameraPlugin, orbit_cameras};
pub use overlay::WindowOverlay;
pub use panic_report::panic_message;
pub use present::{PRESENT_SHADER, PresentError, Presenter, ScreenRect};
pub use screenshot::{ScreenshotRequest, ScreenshotSaved};
pub use surface::WindowSurface;

use crate::{App, BoxedError, DefaultPlugins, Plugin, Stage};

/// Most pixels a window may ask for along either side.
pub const MAX_WINDOW_SIDE: u32 = 16_384;

/// What can go wrong opening or running a window.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum WindowError {
    /// A side of the window is 0 or more than [`MAX_WINDOW_SIDE`].
    #[error("WindowPlugin {field} is {value}: it must be 1 to {MAX_WINDOW_SIDE} pixels")]
    Size {
        /// `width` or `height`.
        field: &'static str,
        /// The value asked for.
        value: u32,
    },
    /// The app has no [`WindowPlugin`] to open a window with.
    #[error(
        "App::run needs WindowPlugin (add pom::window::WindowPlugin, or DefaultPlugins::windowed)"
    )]
    NoWindowPlugin,
    /// No display to open a window on.
    #[error(
        "cannot open a window ({0}): no display? Render headless with RenderPlugin::new and pom::capture instead"
    )]
    NoDisplay(String),
    /// The window could not be created.
    #[error("cannot create the window: {0}")]
    CreateWindow(String),
    /// No GPU driver can draw into the window.
    #[error(
        "cannot draw into the window: no GPU driver can present to it (without a GPU, install Mesa's software Vulkan driver: apt-get install mesa-vulkan-drivers libvulkan1)"
    )]
    CannotPresent,
    /// The GPU could not be set up for the window.
    #[error(transparent)]
    Gpu(#[from] crate::gpu::GpuError),
    /// An automation variable is wrong.
    #[error(transparent)]
    Automation(#[from] AutomationError),
    /// A plugin could not finish its setup on the window's GPU.
    #[error(transparent)]
    App(#[from] crate::AppError),
    /// The frame could not be drawn into the window.
    #[error(transparent)]
    Present(#[from] PresentError),
    /// The GPU device was lost (a driver reset, the GPU removed) and no new one could be made.
    #[error("the GPU device was lost ({reason}) and could not be replaced: {replacing}")]
    DeviceLost {
        /// Why the device was lost.
        reason: String,
        /// Why no new one could be made.
        replacing: String,
    },
    /// The overlay could not start on the window.
    #[error("the window's overlay could not start: {0}")]
    Overlay(String),
    /// The frames' times could not be written where `POM_FRAME_TIMES` says.
    #[error("writing the frame times {path}: {reason}")]
    FrameTimes {
        /// The file.
        path: std::path::PathBuf,
        /// Why it failed.
        reason: String,
    },
    /// The last frame could not be written where `POM_SCREENSHOT` says.
    #[error("writing the screenshot {path}: {reason}")]
    Screenshot {
        /// The file.
        path: std::path::PathBuf,
        /// Why it failed.
        reason: String,
    },
}

/// Opens a window for the app when [`App::run`] starts, sized and titled as its fields say
/// (Bevy's names and defaults where they fit). The renderer's target follows the window's size.
/// While the app runs it is also a resource that says the window's title and size: a system
/// that changes `title`, `width` or `height` retitles or resizes the window.
#[derive(Clone, Debug, PartialEq)]
pub struct WindowPlugin {
    /// The window's title.
    pub title: String,
    /// Its inner width in logical pixels (1 to [`MAX_WINDOW_SIDE`]).
    pub width: u32,
    /// Its inner height in logical pixels (1 to [`MAX_WINDOW_SIDE`]).
    pub height: u32,
    /// How frames are presented: `AutoVsync` (the default) waits for the display.
    pub present_mode: wgpu::PresentMode,
    /// Whether the user may resize it.
    pub resizable: bool,
    /// Whether a system's error or panic ends the app with a non-zero status (by default it
    /// is reported once and the window stays).
    pub exit_on_error: bool,
}

impl Default for WindowPlugin {
    fn default() -> Self {
        Self {
            title: "pom".to_owned(),
            width: 1280,
            height: 720,
            present_mode: wgpu::PresentMode::AutoVsync,
            resizable: true,
            exit_on_error: false,
        }
    }
}

impl WindowPlugin {
    /// Checks the window's size.
    ///
    /// # Errors
    /// [`WindowError::Size`] for a side of 0 or more than [`MAX_WINDOW_SIDE`].
    pub fn validate(&self) -> Result<(), WindowError> {
        for (field, value) in [("width", self.width), ("height", self.height)] {
            if value == 0 || value > MAX_WINDOW_SIDE {
                return Err(WindowError::Size { field, value });
            }
        }
        Ok(())
    }
}

impl Plugin for WindowPlugin {
    fn build(&self, app: &mut App) {
        app.insert_resource(self.clone());
        // A window's frames never wait for a pipeline compile.
        if !app.resources.contains::<crate::gpu::PipelineCompilation>() {
            app.insert_resource(crate::gpu::PipelineCompilation::background());
        }
        // A window's cameras without an `AntiAliasing` of their own run TAA: a moving view
        // is where stair-stepped edges and shimmering relief show.
        if !app.resources.contains::<crate::AntiAliasing>() {
            app.insert_resource(crate::AntiAliasing::Taa);
        }
        // A game in a window gets a sky and the light it gives until it sets its own
        // environment (headless renders keep theirs off, so references stay as they are).
        if !app.resources.contains::<crate::EnvironmentLight>() {
            app.insert_resource(crate::EnvironmentLight::sky());
        }
        input::insert_input_resources(&mut app.resources);
        app.add_system(Stage::PreUpdate, update_input);
    }

    fn finish(&self, _: &mut App) -> Result<(), BoxedError> {
        Ok(self.validate()?)
    }
}

impl DefaultPlugins {
    /// The default plugins drawing into `window`: the [`WindowPlugin`], then
    /// [`DefaultPlugins`] with a target of the window's size (the runner keeps it at the
    /// window's size in pixels).
    pub fn windowed(window: WindowPlugin) -> impl Plugin {
        move |app: &mut App| {
            app.add_plugin(window.clone())
                .add_plugin(DefaultPlugins::headless(window.width, window.height));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_zero_or_absurd_side_is_an_error_naming_the_field_and_the_limit() {
        for (plugin, message) in [
            (
                WindowPlugin {
                    width: 0,
                    ..WindowPlugin::default()
                },
                "WindowPlugin width is 0: it must be 1 to 16384 pixels",
            ),
            (
                WindowPlugin {
                    height: 100_000,
                    ..WindowPlugin::default()
                },
                "WindowPlugin height is 100000: it must be 1 to 16384 pixels",
            ),
        ] {
            assert_eq!(plugin.validate().unwrap_err().to_string(), message);
            let mut app = App::new();
            app.add_plugin(plugin);
            let error = app.finish().unwrap_err().to_string();
            assert!(error.contains(message), "{error}");
        }
        assert!(WindowPlugin::default().validate().is_ok());
    }

    #[test]
    fn running_an_app_without_a_window_plugin_fails_at_once() {
        let mut app = App::new();
        assert_eq!(app.run(), AppExit::error());
    }
}
