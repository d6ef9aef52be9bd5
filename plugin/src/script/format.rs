//! The scene-script file format (RON). Every struct rejects unknown fields.

use serde::Deserialize;

use crate::FlipTolerance;
use crate::parallax::DebugView;

/// A whole script: what to build, then what to do with it.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Script {
    /// Image size in pixels (width, height).
    #[serde(default = "default_size")]
    pub size: (u32, u32),
    /// The camera.
    pub camera: CameraDesc,
    /// Lights (none: a glTF file's own, if any).
    #[serde(default)]
    pub lights: Vec<LightDesc>,
    /// Ambient light (colour, illuminance in lux).
    #[serde(default)]
    pub ambient: Option<([f32; 3], f32)>,
    /// The light from all around, drawn behind the scene (none unless given).
    #[serde(default)]
    pub environment: Option<EnvironmentDesc>,
    /// Things in the scene.
    #[serde(default)]
    pub entities: Vec<EntityDesc>,
    /// What to do, in order, with a fixed frame time.
    pub steps: Vec<Step>,
}

fn default_size() -> (u32, u32) {
    (256, 256)
}

/// A script's environment light: its source, spelled as `--environment` spells it, and its
/// parameters.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EnvironmentDesc {
    /// `"off"`, `"sky"`, `"uniform:R,G,B"` (a constant radiance in cd/m²) or an equirectangular
    /// `.hdr` / `.exr` file, relative to the script's folder and inside it.
    pub source: String,
    /// Its parameters, absent fields at their defaults (`EnvironmentSettings::PARAMETERS`).
    #[serde(default)]
    pub settings: crate::EnvironmentSettings,
}

/// Where the camera is and how it projects.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CameraDesc {
    /// Eye position.
    pub position: [f32; 3],
    /// Point looked at.
    pub target: [f32; 3],
    /// Vertical field of view in degrees; absent with `orthographic_height`.
    #[serde(default)]
    pub fov_degrees: Option<f32>,
    /// Height of the view in world units for an orthographic camera.
    #[serde(default)]
    pub orthographic_height: Option<f32>,
    /// Exposure in EV100 (`Exposure::RANGE`) [default: `Exposure::DEFAULT_EV100`].
    #[serde(default)]
    pub exposure: Option<f32>,
    /// Tonemapping operator: none, aces, agx or neutral [default: neutral].
    #[serde(default)]
    pub tonemap: Option<crate::Tonemapping>,
    /// Anti-aliasing: off, fxaa or taa [default: off]. Under taa a capture renders the
    /// jitter's whole cycle (`taa.jitter_samples` frames) first, for the history to settle,
    /// and a `Camera` or `OrbitCamera` step is a cut that drops the history.
    #[serde(default)]
    pub aa: Option<crate::AntiAliasing>,
    /// TAA's parameters, absent fields at their defaults
    /// (`TemporalAntiAliasing::PARAMETERS`).
    #[serde(default)]
    pub taa: Option<crate::TemporalAntiAliasing>,
    /// FXAA's parameters, absent fields at their defaults
    /// (`FastApproximateAntiAliasing::PARAMETERS`).
    #[serde(default)]
    pub fxaa: Option<crate::FastApproximateAntiAliasing>,
}

/// A light.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
#[non_exhaustive]
pub enum LightDesc {
    /// Sunlight travelling along `direction`.
    Directional {
        /// Direction the light travels.
        direction: [f32; 3],
        /// Linear colour.
        #[serde(default = "white")]
        color: [f32; 3],
        /// Illuminance in lux.
        #[serde(default = "bright_sun")]
        intensity: f32,
        /// Scene shadows (shadow maps) of this light, absent fields at their defaults [default:
        /// none, the light casts no scene shadow].
        #[serde(default)]
        shadows: Option<crate::LightShadows>,
    },
    /// A point light.
    Point {
        /// Position.
        position: [f32; 3],
        /// Linear colour.
        #[serde(default = "white")]
        color: [f32; 3],
        /// Luminous intensity in candela.
        #[serde(default = "floodlight")]
        intensity: f32,
        /// Distance where it fades out.
        #[serde(default = "twenty")]
        range: f32,
        /// Scene shadows (shadow maps) of this light, absent fields at their defaults [default:
        /// none, the light casts no scene shadow].
        #[serde(default)]
        shadows: Option<crate::LightShadows>,
    },
    /// A spot light at `position` shining along `direction` (glTF's cone).
    Spot {
        /// Position.
        position: [f32; 3],
        /// Direction the light shines.
        direction: [f32; 3],
        /// Linear colour.
        #[serde(default = "white")]
        color: [f32; 3],
        /// Luminous intensity in candela along the axis.
        #[serde(default = "floodlight")]
        intensity: f32,
        /// Distance where it fades out.
        #[serde(default = "twenty")]
        range: f32,
        /// Half-angle of full strength, in degrees.
        #[serde(default)]
        inner_degrees: f32,
        /// Half-angle where it reaches zero, in degrees (≤ 90).
        #[serde(default = "forty_five")]
        outer_degrees: f32,
        /// Scene shadows (shadow maps) of this light, absent fields at their defaults [default:
        /// none, the light casts no scene shadow].
        #[serde(default)]
        shadows: Option<crate::LightShadows>,
    },
}

impl LightDesc {
    /// The light's shadow settings, when the script gives them.
    pub fn shadows(&self) -> Option<crate::LightShadows> {
        let (Self::Directional { shadows, .. }
        | Self::Point { shadows, .. }
        | Self::Spot { shadows, .. }) = self;
        *shadows
    }
}

fn white() -> [f32; 3] {
    [1.0; 3]
}
fn one() -> f32 {
    1.0
}
fn bright_sun() -> f32 {
    100_000.0
}
fn floodlight() -> f32 {
    100_000.0
}
fn forty_five() -> f32 {
    45.0
}
fn twenty() -> f32 {
    20.0
}

/// Position, rotation (Euler degrees, applied X then Y then Z) and scale.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct TransformDesc {
    /// Position.
    pub translation: [f32; 3],
    /// Rotation in degrees about X, Y, Z.
    pub rotation_degrees: [f32; 3],
    /// Scale (default 1, 1, 1).
    pub scale: Option<[f32; 3]>,
}

/// A primitive shape.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
#[non_exhaustive]
pub enum ShapeDesc {
    /// A square in XZ facing +Y, UVs 0..tiling.
    Plane {
        /// Side length.
        size: f32,
        /// UV repeats.
        #[serde(default = "one")]
        tiling: f32,
    },
    /// A cube.
    Cube {
        /// Side length.
        size: f32,
    },
    /// A UV sphere.
    Sphere {
        /// Radius.
        radius: f32,
    },
    /// A closed cylinder about +Y, centred on the origin: the side wraps the texture once
    /// around and once along its height, each cap holds the unit square.
    Cylinder {
        /// Radius.
        radius: f32,
        /// Height along Y.
        height: f32,
    },
}

/// What an entity looks like.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
#[non_exhaustive]
pub enum MaterialDesc {
    /// The normal-mapped default material of one colour.
    Lit {
        /// Linear colour.
        color: [f32; 3],
    },
    /// A parallax material from a folder holding albedo.png, normal.png and height.png (as the
    /// shipped sets under assets/), with parameters from a preset file and/or inline changes.
    Pom {
        /// Folder of the maps, relative to the script.
        maps: String,
        /// A preset RON file, relative to the script.
        #[serde(default)]
        preset: Option<String>,
        /// Changes on top of the preset (boxed: a patch holds every parameter, the other
        /// variants a colour).
        #[serde(default)]
        set: Box<MaterialPatch>,
    },
}

/// An entity: a primitive with a material, or a whole glTF file.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EntityDesc {
    /// The name steps refer to.
    pub name: String,
    /// A primitive shape (or `gltf`).
    #[serde(default)]
    pub shape: Option<ShapeDesc>,
    /// A glTF file relative to the script (or `shape`).
    #[serde(default)]
    pub gltf: Option<String>,
    /// The material of a shape.
    #[serde(default)]
    pub material: Option<MaterialDesc>,
    /// Placement.
    #[serde(default)]
    pub transform: TransformDesc,
}

/// Parameter changes of a parallax material; absent fields stay as they are. Generated from
/// the material's parameter declarations: every parameter, by its name.
pub type MaterialPatch = crate::PomPatch;

/// A rectangle of a capture in pixels: x, y, width, height.
pub type Rect = (u32, u32, u32, u32);

/// A number measured over a rectangle of a capture. The debug-view statistics count only the
/// pixels of parallax surfaces; one with no such pixel in its rectangle is an error.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
#[non_exhaustive]
pub enum Statistic {
    /// Mean Rec. 709 luminance of the linear colour, 0..1, over every pixel.
    MeanLuminance,
    /// Fraction of pixels in the LOD transition band (needs a capture with `debug_view: uv`).
    LodBandFraction,
    /// Fraction of pixels where only normal mapping ran (needs `debug_view: uv`).
    NormalMappingFraction,
    /// Fraction of pixels less than half lit by the height field's self-shadowing of the first
    /// light (needs `debug_view: shadow`).
    ShadowedFraction,
    /// Mean distance in texture units between this capture's coordinates and `baseline`'s
    /// (both with `debug_view: uv`): how far parallax moved the texture.
    UvShift {
        /// The capture to measure from.
        baseline: String,
    },
}

/// The most frames one `Advance` step may run: 10,000 frames are about 167 s of scene time at
/// [`super::SCRIPT_FRAME_TIME`], more than any scene test animates, and bound how long a step
/// renders. A script needing more writes several steps.
pub const MAX_ADVANCE_FRAMES: u32 = 10_000;

/// One step of a script.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
#[non_exhaustive]
pub enum Step {
    /// Runs `frames` updates with the fixed frame time.
    Advance {
        /// Number of frames, at most [`MAX_ADVANCE_FRAMES`].
        frames: u32,
    },
    /// Changes parameters of the parallax materials of `entity` (its own, or a glTF's).
    Set {
        /// Entity name.
        entity: String,
        /// The changes.
        material: MaterialPatch,
    },
    /// Moves the camera.
    Camera {
        /// Eye position.
        position: [f32; 3],
        /// Point looked at.
        target: [f32; 3],
    },
    /// Turns the camera about the vertical axis through its target.
    OrbitCamera {
        /// Degrees, counter-clockwise seen from above.
        degrees: f32,
    },
    /// Moves light number `light` (in the script's order).
    MoveLight {
        /// Light index.
        light: usize,
        /// New direction (directional and spot lights).
        #[serde(default)]
        direction: Option<[f32; 3]>,
        /// New position (point and spot lights).
        #[serde(default)]
        position: Option<[f32; 3]>,
    },
    /// Spins `entity` about Y by `degrees_per_frame` every following frame (0 stops it).
    Spin {
        /// Entity name.
        entity: String,
        /// Degrees per frame.
        degrees_per_frame: f32,
    },
    /// Renders a frame and keeps it under `name`; `debug_view` renders every parallax
    /// material with that view for this capture only.
    Capture {
        /// Name of the capture.
        name: String,
        /// Temporary debug view.
        #[serde(default)]
        debug_view: Option<DebugView>,
    },
    /// Compares a capture with a reference PNG (relative to the script) using FLIP.
    ExpectMatch {
        /// The capture.
        capture: String,
        /// The reference image.
        reference: String,
        /// Allowed difference.
        #[serde(default)]
        tolerance: FlipTolerance,
    },
    /// Checks a statistic of a capture (over `rect`, or the whole image) is within bounds.
    ExpectStat {
        /// The capture.
        capture: String,
        /// What to measure.
        stat: Statistic,
        /// The region, default the whole image.
        #[serde(default)]
        rect: Option<Rect>,
        /// Smallest allowed value (at least one of `min` and `max` is given).
        #[serde(default)]
        min: Option<f32>,
        /// Largest allowed value.
        #[serde(default)]
        max: Option<f32>,
    },
    /// Checks a statistic grows (or shrinks) strictly along a list of captures.
    ExpectMonotonic {
        /// The captures, in order (at least two).
        captures: Vec<String>,
        /// What to measure.
        stat: Statistic,
        /// The region of every capture, default the whole image.
        #[serde(default)]
        rect: Option<Rect>,
        /// Whether it must grow (true) or shrink.
        #[serde(default = "yes")]
        increasing: bool,
    },
}

fn yes() -> bool {
    true
}
