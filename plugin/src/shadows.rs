//! Scene shadows through shadow maps: which lights cast them and how ([`LightShadows`]), and
//! which meshes take part ([`NotShadowCaster`], [`NotShadowReceiver`]).
//!
//! A light casts scene shadows when its entity has a [`LightShadows`] component (enabled);
//! without one it casts none, so scenes pay for shadow maps only where asked (the sandbox's
//! `render` and `snapshot` turn them on for every light by default). Every opaque mesh casts
//! and receives unless marked. A directional light renders
//! [`DIRECTIONAL_CASCADES`] cascades over the camera's view out to [`LightShadows::distance`], a
//! spot light one perspective map, a point light six (a cube). Parallax materials write the
//! relief's depth into the maps (they march along the light's view) and look the maps up at the
//! displaced point the view's march found.

/// How many cascades a directional light's shadow map has.
pub const DIRECTIONAL_CASCADES: usize = 3;

/// A light's shadow maps; a component on the light's entity (without one the light casts no
/// scene shadow; `LightShadows::default()` turns them on). Scene scripts write it as
/// `(enabled, map_size, softness, distance)`, absent fields at their defaults.
#[derive(Clone, Copy, Debug, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct LightShadows {
    /// Whether the light casts scene shadows (its parallax self-shadows do not depend on it).
    pub enabled: bool,
    /// Texels along each side of one map (per cascade or cube face), 16 ..= 8192.
    pub map_size: u32,
    /// Width of the filter (PCF), in shadow-map texels: larger is softer, 0 is one
    /// hardware-filtered lookup.
    pub softness: f32,
    /// Directional lights: how far from the camera the cascades reach, in world units.
    pub distance: f32,
}

impl LightShadows {
    /// The smallest map size.
    pub const MIN_MAP_SIZE: u32 = 16;
    /// The largest map size.
    pub const MAX_MAP_SIZE: u32 = 8192;
    /// The widest filter, in texels.
    pub const MAX_SOFTNESS: f32 = 8.0;

    /// The first field out of range and why, naming its limits (`None`: every field is valid);
    /// what scene scripts report where [`LightShadows::sanitized`] would clamp.
    pub fn problem(&self) -> Option<(&'static str, String)> {
        let (min, max) = (Self::MIN_MAP_SIZE, Self::MAX_MAP_SIZE);
        let max_softness = Self::MAX_SOFTNESS;
        if !(min..=max).contains(&self.map_size) {
            Some((
                "map_size",
                format!("map_size {} is outside {min}..={max}", self.map_size),
            ))
        } else if !(0.0..=max_softness).contains(&self.softness) {
            Some((
                "softness",
                format!(
                    "softness {} is outside 0..={max_softness} texels",
                    self.softness
                ),
            ))
        } else if !(self.distance.is_finite() && self.distance > 0.0) {
            Some((
                "distance",
                format!("distance {} must be finite and above 0", self.distance),
            ))
        } else {
            None
        }
    }

    /// Shadows switched off for this light.
    pub fn off() -> Self {
        Self {
            enabled: false,
            ..Self::default()
        }
    }

    /// The settings the renderer uses: the map size clamped to
    /// [`Self::MIN_MAP_SIZE`]`..=`[`Self::MAX_MAP_SIZE`], softness to `0..=`[`Self::MAX_SOFTNESS`]
    /// and the distance to a positive finite value (NaN as the defaults).
    pub fn sanitized(&self) -> Self {
        let default = Self::default();
        let finite_or = |value: f32, fallback: f32| {
            if value.is_finite() { value } else { fallback }
        };
        Self {
            enabled: self.enabled,
            map_size: self.map_size.clamp(Self::MIN_MAP_SIZE, Self::MAX_MAP_SIZE),
            softness: finite_or(self.softness, default.softness).clamp(0.0, Self::MAX_SOFTNESS),
            distance: finite_or(self.distance, default.distance).clamp(1e-3, 1e6),
        }
    }
}

impl Default for LightShadows {
    /// On, 2048² texels per map, a 1.5-texel filter, cascades out to 50 units.
    fn default() -> Self {
        Self {
            enabled: true,
            map_size: 2048,
            softness: 1.5,
            distance: 50.0,
        }
    }
}

/// Marks a mesh entity that casts no shadow (it is left out of every shadow map).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct NotShadowCaster;

/// Marks a mesh entity on which no scene shadow falls (its parallax self-shadows remain).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct NotShadowReceiver;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn out_of_range_settings_are_clamped_and_nan_takes_the_default() {
        let wild = LightShadows {
            enabled: true,
            map_size: 0,
            softness: f32::NAN,
            distance: -5.0,
        }
        .sanitized();
        assert_eq!(wild.map_size, LightShadows::MIN_MAP_SIZE);
        assert_eq!(wild.softness, LightShadows::default().softness);
        assert!(wild.distance > 0.0);
        let huge = LightShadows {
            map_size: u32::MAX,
            softness: 1e9,
            distance: f32::INFINITY,
            ..LightShadows::default()
        }
        .sanitized();
        assert_eq!(huge.map_size, LightShadows::MAX_MAP_SIZE);
        assert_eq!(huge.softness, LightShadows::MAX_SOFTNESS);
        assert_eq!(huge.distance, LightShadows::default().distance);
        assert_eq!(LightShadows::default().sanitized(), LightShadows::default());
        assert!(!LightShadows::off().sanitized().enabled);
    }
}

/// What the shadow maps show, as the materials prepared it: started by each Prepare stage,
/// then added to by every material. Part of the renderer's shadow maps.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct ShadowCasterChanges {
    /// This frame's casters' batches and the pipelines drawing them, hashed (every material's
    /// folded in).
    signature: u64,
    /// Counts the frames on which a caster's per-draw data, or an asset, was uploaded: kept
    /// from frame to frame, so a change on a frame that draws no map is still seen after.
    data_generation: u64,
    /// Whether a caster reads the frame's per-frame noise (`Material::casts_with_frame_noise`).
    read_frame_noise: bool,
}

impl ShadowCasterChanges {
    /// Starts a frame's signature.
    pub(crate) fn begin_frame(&mut self) {
        self.signature = 0;
        self.read_frame_noise = false;
    }

    /// Adds one material's casters: its `signature`, whether its data changed, and whether
    /// one of them reads the frame's noise.
    pub(crate) fn add(&mut self, signature: u64, data_changed: bool, read_frame_noise: bool) {
        self.signature = self.signature.rotate_left(5) ^ signature;
        if data_changed {
            self.data_generation += 1;
        }
        self.read_frame_noise |= read_frame_noise;
    }

    /// Whether a caster reads the frame's per-frame noise: a map it shows changes whenever the
    /// noise moves (every TAA frame).
    pub(crate) fn read_frame_noise(&self) -> bool {
        self.read_frame_noise
    }
}
