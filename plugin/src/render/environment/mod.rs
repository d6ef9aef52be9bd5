//! Environment light and sky: the light arriving from all around the scene, from a constant
//! radiance, Preetham's daylight sky (sky.rs) whose sun follows the scene's first directional
//! light, or an equirectangular `.hdr` / `.exr` image (source.rs). [`EnvironmentPlugin`] joins
//! the frame with two nodes: in the prepass phase, when the environment is set or changes, it
//! prefilters it on the GPU (prefilter.rs: a radiance cube blurred per roughness by GGX
//! importance sampling, the irradiance as nine spherical harmonics, and the split-sum table of
//! split_sum.rs) into the maps every material's group 0 binds (`render/environment_maps.rs`,
//! read through `environment.wgsl`); after the resolve phase it draws the environment behind
//! the scene (background.rs). Which environment, how bright and turned how far is the
//! [`EnvironmentLight`] resource; without one (or with [`EnvironmentSource::Off`]) neither node
//! runs and materials light with the ambient term as before.

mod background;
mod gpu_textures;
mod light;
mod prefilter;
mod sky;
mod source;
mod split_sum;

pub use background::{BACKGROUND, BACKGROUND_ENTRY};
pub use light::{EnvironmentLight, EnvironmentSettings, MAX_ENVIRONMENT_RESOLUTION};
pub use prefilter::{ENVIRONMENT_SOURCE, PREFILTER, PREFILTER_ENTRY, SKY, radiance_levels};
pub use sky::{DEFAULT_SUN, Sky, SkyParams, SkyState};
pub use source::{
    EnvironmentChoice, EnvironmentError, EnvironmentSource, EquirectImage, MAX_UNIFORM_RADIANCE,
};
pub use split_sum::{SPLIT_SUM_SIZE, analytic_fit, split_sum, split_sum_table};

use background::{Background, BackgroundView};
use prefilter::{Capture, EnvironmentGpu};
use source::SourceKind;

use crate::gpu::{GpuContext, PassTimestamps};
use crate::render::shaders::WgslFile;
use crate::render::{
    ExtractedFrame, FrameNode, FrameNodes, FrameView, NodePlace, RenderError, RenderPhase,
    RenderTarget, Renderer,
};
use crate::{App, AppError, DirectionalLight, Plugin, Resources, Stage};

/// The nine spherical harmonics the environment's irradiance is stored in.
pub const SPHERICAL_HARMONICS: WgslFile =
    crate::wgsl_file!(nested "render/environment/spherical_harmonics.wgsl");
/// The environment light as materials read it from their group 0 (`environment_diffuse`,
/// `environment_specular`, `environment_split_sum`); after [`SPHERICAL_HARMONICS`].
pub const ENVIRONMENT: WgslFile = crate::wgsl_file!(nested "render/environment/environment.wgsl");

/// The node the prefiltering is timed under.
pub const ENVIRONMENT_PREFILTER_NODE: &str = "environment prefilter";
/// The node the background is timed under.
pub const ENVIRONMENT_BACKGROUND_NODE: &str = "environment background";

/// Lights the scene with the [`EnvironmentLight`] resource and draws it behind the scene (the
/// render plugin adds it with its standard features; without the resource nothing runs).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct EnvironmentPlugin;

impl Plugin for EnvironmentPlugin {
    fn build(&self, app: &mut App) {
        let nodes = app.resources.get_or_default::<FrameNodes>();
        nodes.add(
            NodePlace::new(ENVIRONMENT_PREFILTER_NODE, RenderPhase::Prepass),
            || PrefilterNode,
        );
        nodes.add(
            NodePlace::new(ENVIRONMENT_BACKGROUND_NODE, RenderPhase::Resolve),
            BackgroundNode::default,
        );
        app.add_system(Stage::Extract, extract_environment);
        app.add_system(Stage::Prepare, prepare_environment);
    }
}

/// This frame's environment, as the Extract stage found it.
#[derive(Clone, Debug, Default)]
struct EnvironmentFrame {
    /// What the maps must hold (`None`: no environment).
    capture: Option<Capture>,
    /// Its turn and the multiplier of its radiance, where it is drawn behind the scene.
    background: Option<(f32, f32)>,
}

/// A finite value ≥ 0, else 0.
fn usable(value: f32) -> f32 {
    if value.is_finite() {
        value.max(0.0)
    } else {
        0.0
    }
}

/// The Extract stage's system: what the maps must hold, and the frame uniform's `environment`.
fn extract_environment(world: &mut hecs::World, resources: &mut Resources) -> Result<(), AppError> {
    let light = resources
        .get::<EnvironmentLight>()
        .cloned()
        .unwrap_or_default();
    let settings = light.settings.sanitized();
    let extracted = resources.require_mut::<ExtractedFrame>()?;
    let size = settings
        .resolution
        .next_power_of_two()
        .min(MAX_ENVIRONMENT_RESOLUTION);
    let mut capture = Capture {
        kind: SourceKind::Uniform,
        uniform: [0.0; 3],
        sky: SkyParams::default(),
        image: None,
        size,
        radiance_scale: 1.0,
    };
    match &light.source {
        EnvironmentSource::Off => {
            resources.insert(EnvironmentFrame::default());
            return Ok(());
        }
        EnvironmentSource::Uniform(radiance) => {
            capture.uniform = radiance.map(usable);
            let brightest = capture.uniform.iter().fold(0.0_f32, |max, c| max.max(*c));
            // Stored as 1 at its brightest: the radiance itself goes in the multiplier.
            capture.radiance_scale = if brightest > 0.0 {
                1.0 / brightest
            } else {
                1.0
            };
        }
        EnvironmentSource::Sky(sky) => {
            let sun = extracted.lights.directional.first().and_then(|entity| {
                let light = world.get::<&DirectionalLight>(*entity).ok()?;
                let direction =
                    glam::Vec4::from(extracted.frame.directional_lights[0].direction_to_light);
                Some((direction.truncate(), usable(light.intensity)))
            });
            let (direction, illuminance) = sun.unwrap_or((sky::DEFAULT_SUN, 0.0));
            capture.kind = SourceKind::Sky;
            capture.sky = SkyState::new(*sky, direction, illuminance).params();
            // Daylight reaches tens of thousands of cd/m²: a 16th keeps it well inside half floats.
            capture.radiance_scale = 1.0 / 16.0;
        }
        EnvironmentSource::Equirect(image) => {
            capture.kind = SourceKind::Equirect;
            capture.radiance_scale = (60_000.0 / image.brightest().max(1e-30)).min(1.0);
            capture.image = Some(image.clone());
        }
    }
    let scale = settings.intensity * extracted.exposure.multiplier();
    let rotation = settings.rotation.to_radians();
    extracted.frame.environment = [
        scale / capture.radiance_scale,
        radiance_levels(size) as f32,
        rotation.cos(),
        rotation.sin(),
    ];
    extracted.frame.environment_options = [
        f32::from(u8::from(settings.energy_compensation)),
        0.0,
        0.0,
        0.0,
    ];
    resources.insert(EnvironmentFrame {
        capture: Some(capture),
        background: settings.background.then_some((rotation, scale)),
    });
    Ok(())
}

/// The Prepare stage's system (before the materials'): readies the prefiltering of a new or
/// changed environment and binds its maps, or the stand-ins when there is none.
fn prepare_environment(_: &mut hecs::World, resources: &mut Resources) -> Result<(), AppError> {
    let capture = resources
        .get::<EnvironmentFrame>()
        .and_then(|frame| frame.capture.clone());
    let gpu = resources.require::<GpuContext>()?;
    if resources
        .get::<EnvironmentGpu>()
        .is_none_or(|state| !state.made_on(gpu))
    {
        let state = EnvironmentGpu::new(gpu);
        resources.insert(state);
    }
    resources.require_scope(|resources, state: &mut EnvironmentGpu| {
        resources.require_scope(|resources, renderer: &mut Renderer| {
            let gpu = resources.require::<GpuContext>()?;
            let Some(capture) = capture else {
                state.skip();
                if renderer.environment.is_installed() {
                    renderer.environment.install(None);
                }
                return Ok(());
            };
            let (new_maps, uploaded) = state.prepare(gpu, capture);
            if let Some(maps) = new_maps.or_else(|| {
                (!renderer.environment.is_installed())
                    .then(|| state.textures())
                    .flatten()
            }) {
                renderer.environment.install(Some(maps));
            }
            renderer.last_upload.uniform_bytes += uploaded;
            Ok(())
        })
    })
}

/// Prefilters the environment in the frames it is set or changes.
struct PrefilterNode;

impl FrameNode for PrefilterNode {
    fn runs(&self, frame: FrameView<'_>) -> bool {
        frame
            .resources
            .get::<EnvironmentGpu>()
            .is_some_and(EnvironmentGpu::has_pending)
    }

    fn record(
        &mut self,
        frame: FrameView<'_>,
        encoder: &mut wgpu::CommandEncoder,
        time: Option<&PassTimestamps>,
    ) -> Result<(), RenderError> {
        frame
            .resources
            .require::<EnvironmentGpu>()?
            .record(encoder, time);
        Ok(())
    }
}

/// Draws the environment behind the scene; its pass is made on the first frame that does.
#[derive(Default)]
struct BackgroundNode {
    /// The pass, the scene format it was made for and the source image it binds.
    background: Option<(Background, wgpu::TextureFormat, u64)>,
}

impl FrameNode for BackgroundNode {
    fn runs(&self, frame: FrameView<'_>) -> bool {
        frame.has_camera
            && frame
                .resources
                .get::<EnvironmentFrame>()
                .is_some_and(|environment| environment.background.is_some())
    }

    fn samples_scene_depth(&self) -> bool {
        true
    }

    fn prepare(&mut self, resources: &mut Resources) -> Result<u64, RenderError> {
        let gpu = resources.require::<GpuContext>()?;
        let target = resources.require::<RenderTarget>()?;
        let state = resources.require::<EnvironmentGpu>()?;
        let extracted = resources.require::<ExtractedFrame>()?;
        let Some((rotation, scale)) = resources
            .get::<EnvironmentFrame>()
            .and_then(|frame| frame.background)
        else {
            return Ok(0);
        };
        let format = target.scene_format();
        if self
            .background
            .as_ref()
            .is_none_or(|(_, made_for, _)| *made_for != format)
        {
            self.background = Some((Background::new(gpu, format), format, u64::MAX));
        }
        let Some((background, _, image)) = &mut self.background else {
            return Ok(0);
        };
        let new_source = *image != state.image_generation();
        *image = state.image_generation();
        let view = BackgroundView {
            view_projection: glam::Mat4::from_cols_array_2d(&extracted.frame.view_projection),
            rotation,
            scale,
        };
        let scene_depth = resources.require::<Renderer>()?.scene_depth(target);
        Ok(background.prepare(gpu, (target, scene_depth), state, (view, new_source)))
    }

    fn record(
        &mut self,
        _: FrameView<'_>,
        encoder: &mut wgpu::CommandEncoder,
        time: Option<&PassTimestamps>,
    ) -> Result<(), RenderError> {
        if let Some((background, ..)) = &self.background {
            background.record(encoder, time);
        }
        Ok(())
    }
}
