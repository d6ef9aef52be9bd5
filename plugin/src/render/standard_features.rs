//! The render features a [`super::RenderPlugin`] adds besides the core, each of which an app
//! may leave out ([`super::RenderPlugin::without`]).

use super::anti_aliasing::AntiAliasingPlugin;
use super::environment::EnvironmentPlugin;
use super::lights::LightsPlugin;
use super::shadows::ShadowsPlugin;
use super::tonemapping::TonemappingPlugin;
use crate::App;

/// One of the standard render features.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum RenderFeature {
    /// The world's directional, point and spot lights ([`LightsPlugin`]): the other features
    /// read them, so it comes first.
    Lights,
    /// The post chain's display conversion ([`TonemappingPlugin`]); without it (or another
    /// display conversion) frames fail with an error naming it.
    Tonemapping,
    /// TAA with its object motion, and FXAA ([`AntiAliasingPlugin`]).
    AntiAliasing,
    /// The shadow maps' pass ([`ShadowsPlugin`]).
    SceneShadows,
    /// Environment light and sky ([`EnvironmentPlugin`]).
    Environment,
}

impl RenderFeature {
    /// Every standard feature, in the order they are added.
    pub const ALL: [RenderFeature; 5] = [
        RenderFeature::Lights,
        RenderFeature::Tonemapping,
        RenderFeature::AntiAliasing,
        RenderFeature::SceneShadows,
        RenderFeature::Environment,
    ];

    fn bit(self) -> u8 {
        1 << self as u8
    }
}

/// A set of standard features (all of them by default).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RenderFeatures(u8);

impl Default for RenderFeatures {
    fn default() -> Self {
        Self(RenderFeature::ALL.iter().fold(0, |set, f| set | f.bit()))
    }
}

impl RenderFeatures {
    /// The same set without `feature`.
    pub fn without(self, feature: RenderFeature) -> Self {
        Self(self.0 & !feature.bit())
    }

    /// Whether the set holds `feature`.
    pub fn contains(self, feature: RenderFeature) -> bool {
        self.0 & feature.bit() != 0
    }

    /// Adds the plugin of each feature of the set that `app` does not have yet.
    pub(crate) fn add_to(self, app: &mut App) {
        for feature in RenderFeature::ALL.into_iter().filter(|f| self.contains(*f)) {
            match feature {
                RenderFeature::Lights if !app.has_plugin::<LightsPlugin>() => {
                    app.add_plugin(LightsPlugin);
                }
                RenderFeature::Tonemapping if !app.has_plugin::<TonemappingPlugin>() => {
                    app.add_plugin(TonemappingPlugin);
                }
                RenderFeature::AntiAliasing if !app.has_plugin::<AntiAliasingPlugin>() => {
                    app.add_plugin(AntiAliasingPlugin);
                }
                RenderFeature::SceneShadows if !app.has_plugin::<ShadowsPlugin>() => {
                    app.add_plugin(ShadowsPlugin);
                }
                RenderFeature::Environment if !app.has_plugin::<EnvironmentPlugin>() => {
                    app.add_plugin(EnvironmentPlugin);
                }
                _ => {}
            }
        }
    }
}
