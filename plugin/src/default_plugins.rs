//! [`DefaultPlugins`]: everything a game needs to draw meshes and parallax materials, as one
//! plugin.

use crate::{App, Plugin, PomPlugin, RenderPlugin, TransformPlugin};

/// The renderer, [`crate::LitMaterial`] (which also draws meshes without a material) and the
/// parallax material: `TransformPlugin`, `RenderPlugin`, `PomPlugin` (which brings
/// `LitPlugin`), in that order. A plugin already added is not added again. Unless a logger
/// is installed already, [`crate::log_to_stderr`] installs one, so the library's warnings
/// (clamped values, device limits) reach the terminal.
///
/// # Example
/// ```no_run
/// let mut app = pom::App::new();
/// app.add_plugin(pom::DefaultPlugins::headless(320, 240));
/// app.update().unwrap();
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DefaultPlugins {
    /// The renderer's settings.
    pub render: RenderPlugin,
}

impl DefaultPlugins {
    /// The default plugins rendering into a `width`×`height` offscreen sRGB image.
    pub fn headless(width: u32, height: u32) -> Self {
        RenderPlugin::new(width, height).into()
    }
}

impl From<RenderPlugin> for DefaultPlugins {
    fn from(render: RenderPlugin) -> Self {
        Self { render }
    }
}

impl Plugin for DefaultPlugins {
    fn build(&self, app: &mut App) {
        crate::log_to_stderr();
        app.add_plugin(TransformPlugin)
            .add_plugin(self.render)
            .add_plugin(PomPlugin);
    }
}
