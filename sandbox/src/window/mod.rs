//! The live window: pom's window runner with egui over the scene. The plugin renders the scene
//! and the runner presents it in the space the panels leave; the side panel edits the
//! components and resources of the `pom::App`. This module holds UI only.

mod app_state;
mod autosave;
mod camera_control;
mod display_control;
mod egui_painter;
mod environment_control;
mod file_browser;
mod frame_timing;
mod guarded_update;
mod light_control;
mod material_editor;
mod panels;
mod presets;
mod render_path_control;
mod scene_open;
mod shader_status;
mod split_controls;
mod window_app;

#[cfg(test)]
mod layer_panel_tests;
#[cfg(test)]
mod panel_layout_tests;
#[cfg(test)]
mod panel_tests;

use std::path::PathBuf;

use clap::Args;

/// The window's options (the automation flags let scripts and CI drive the real window).
#[derive(Debug, Args)]
pub struct WindowArgs {
    /// Open this glTF scene (.gltf or .glb) instead of the embedded street corner. A file that
    /// cannot be loaded shows its error in the window, which falls back to the street corner.
    #[arg(long, value_name = "PATH")]
    pub scene: Option<PathBuf>,
    /// The scene's camera to open on, counting camera nodes from 0 as `render --help` says, or
    /// auto for a view framing its meshes [default: 0, or auto when the file has no cameras].
    #[arg(long, value_name = "INDEX|auto", value_parser = crate::cli_types::parse_camera)]
    pub camera: Option<crate::cli_types::CameraArg>,
    /// Close the window after this many frames (for scripts and CI).
    #[arg(long, value_name = "N")]
    pub exit_after_frames: Option<u64>,
    /// Write the window's last frame, panels included, to this PNG before exiting.
    #[arg(long, value_name = "FILE")]
    pub screenshot: Option<PathBuf>,
    /// Where tuned material values are saved (atomically, at most once a second) and restored
    /// from at the next start [default: $XDG_CONFIG_HOME/pom-sandbox/state.ron, else
    /// ~/.config/pom-sandbox/state.ron, else target/sandbox-state.ron].
    #[arg(long, value_name = "FILE")]
    pub state: Option<PathBuf>,
    /// Open with the split view on: image B (right of the wipe) draws every parallax material
    /// with this method.
    #[arg(long, value_name = "METHOD", value_parser = crate::material_args::choice_parser::<pom::ParallaxMethod>())]
    pub split_method: Option<pom::ParallaxMethod>,
}

pub use window_app::run;
