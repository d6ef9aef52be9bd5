//! Preview-scene apps with the parallax material, for the material tests.

use pom::preview::{PreviewView, spawn_preview};
use pom::{
    App, Assets, DebugView, HeightField, HeightSource, Image, ParallaxMethod,
    ParallaxOcclusionMaterial, PomPlugin, RenderPlugin, ShadowMode, TargetFormat, TextureKind,
};

use crate::HarnessError;

/// Textures of a test material made from one height field.
pub struct HeightMaterial {
    /// The height field (its 8-bit quantization is what the GPU samples).
    pub field: HeightField,
    /// Height range in texture units, also used for the normal map's slopes.
    pub height_scale: f32,
}

impl HeightMaterial {
    /// Adds the height map, its Sobel normal map and a light grey albedo to `app`, and returns
    /// a material using them with Tatarchuk's defaults otherwise.
    pub fn material(&self, app: &mut App) -> ParallaxOcclusionMaterial {
        let images = app
            .resources
            .get_mut::<Assets<Image>>()
            .expect("render plugin added");
        let height = images.add(self.field.to_image());
        let normal = images.add(self.field.normal_map(self.height_scale));
        let albedo = images.add(Image::solid([200, 190, 170, 255], TextureKind::Color));
        ParallaxOcclusionMaterial {
            base_color_texture: Some(albedo),
            normal_map: Some(normal),
            height_map: Some(HeightSource::Texture(height)),
            height_scale: self.height_scale,
            ..ParallaxOcclusionMaterial::default()
        }
    }
}

/// A headless app with the parallax plugin, rendering `format` at `size`×`size`.
pub fn pom_app(size: u32, format: TargetFormat) -> Result<App, HarnessError> {
    let mut app = App::new();
    app.add_plugin(RenderPlugin::new(size, size).with_format(format));
    app.add_plugin(PomPlugin);
    app.finish()?;
    Ok(app)
}

/// A preview app: the plane with the material `configure` returns, seen from `view`.
pub fn preview_app(
    size: u32,
    format: TargetFormat,
    textures: &HeightMaterial,
    view: &PreviewView,
    configure: impl FnOnce(ParallaxOcclusionMaterial) -> ParallaxOcclusionMaterial,
) -> Result<App, HarnessError> {
    let mut app = pom_app(size, format)?;
    let material = configure(textures.material(&mut app));
    spawn_preview(&mut app, material, view)?;
    Ok(app)
}

/// The raw `uv` debug view (R, G = the final texture coordinate) of `method` on a `size`² float
/// target, shadows off and the full march everywhere (LOD threshold 16): what the GPU's march
/// found, to set beside the CPU reference.
pub fn uv_view(
    size: u32,
    textures: &HeightMaterial,
    view: &PreviewView,
    method: ParallaxMethod,
) -> Result<image::Rgba32FImage, HarnessError> {
    crate::render_and_capture_f32(&mut uv_app(size, textures, view, method)?)
}

/// The app [`uv_view`] renders, for tests that change it between frames.
pub fn uv_app(
    size: u32,
    textures: &HeightMaterial,
    view: &PreviewView,
    method: ParallaxMethod,
) -> Result<App, HarnessError> {
    preview_app(size, TargetFormat::Float32, textures, view, |material| {
        ParallaxOcclusionMaterial {
            method,
            debug_view: DebugView::Uv,
            shadows: ShadowMode::Off,
            lod_threshold: 16.0,
            ..material
        }
    })
}

/// Applies `change` to every parallax material of `app`.
pub fn set_material(app: &mut App, change: impl Fn(&mut ParallaxOcclusionMaterial)) {
    for material in app.world.query_mut::<&mut ParallaxOcclusionMaterial>() {
        change(material);
    }
}

/// The shortest difference between two coordinates on a repeating texture, from their plain
/// difference.
pub fn wrapped(difference: f32) -> f32 {
    difference - difference.round()
}
