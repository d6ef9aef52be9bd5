//! The names a game uses, for `use pom::prelude::*;`: the app and its plugins, transforms,
//! cameras and lights, meshes, images and height fields, a layered material's layers, reading a frame back (`capture`), the two shipped materials and what writing one takes
//! (`ShadedMaterial`, `ParamSpec`, `WgslFile`) or a post effect (`PostEffect`,
//! `FullScreenPass`), time, glam's vectors,
//! hecs's world, and (with the `window` feature) the window, its input and the cameras that
//! move with it.
//!
//! ```
//! use pom::prelude::*;
//!
//! let mut app = App::new();
//! app.add_plugin(DefaultPlugins::headless(64, 64));
//! let plane = app.resources.get_or_default::<Assets<Mesh>>().add(Mesh::plane(2.0));
//! app.world.spawn((plane, LitMaterial::from_color(Color::WHITE), Transform::IDENTITY));
//! let eye = Transform::from_xyz(0.0, 2.0, 2.0).looking_at(Vec3::ZERO, Vec3::Y);
//! app.world.spawn((Camera::perspective(45.0), eye));
//! ```

pub use glam::{Mat4, Quat, Vec2, Vec3, Vec4};
pub use hecs::{Entity, World};

pub use crate::{
    AmbientLight, AntiAliasing, App, Assets, Camera, Color, DefaultPlugins, DirectionalLight,
    EnvironmentLight, Exposure, GlobalTransform, Handle, HeightField, HeightSource, HeightUnits,
    Image, LayerWeights, LightShadows, LightingModel, LitMaterial, LitPlugin, Material,
    MaterialPlugin, Mesh, ParallaxLayer, ParallaxLayers, ParallaxMethod, ParallaxOcclusionMaterial,
    Parent, Plugin, PointLight, PomPlugin, Projection, RenderPlugin, Resources, ShadedMaterial,
    SpotLight, Stage, TemporalAntiAliasing, TextureKind, TextureMapping, Time, Tonemapping,
    Transform, capture, load_gltf, patterns,
};
// Writing a material: its parameters' limits and its shading file; a choice parameter's values
// and names (`ParallaxMethod::VALUES`, `method.name()`).
pub use crate::material::{Choice, ParamSpec};
pub use crate::shader::WgslFile;
// Writing a post effect: a node of the post chain and its full-screen pass.
pub use crate::gpu::PassTimestamps;
pub use crate::render::{
    FrameNodes, FrameView, FullScreenPass, PostEffect, PostImage, PostIo, PostStage, RenderError,
};

#[cfg(feature = "window")]
pub use crate::window::{
    AppExit, ButtonInput, FlyCamera, FlyCameraPlugin, KeyCode, MouseButton, OrbitCamera,
    OrbitCameraPlugin, WindowPlugin,
};
