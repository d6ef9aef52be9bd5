//! The light controls: the direction of a directional light as azimuth / elevation sliders,
//! written into the light entity's `Transform`, adding or removing lights, each spot light's
//! intensity and cone, and every light's scene shadows (its `LightShadows`), which the state
//! file keeps per light name.

use std::collections::BTreeMap;

use egui::{CollapsingHeader, ComboBox, Slider, SliderClamping, Ui};
use glam::Vec3;
use pom::hecs::{Entity, World};
use pom::{DirectionalLight, LightShadows, Name, PointLight, SpotLight, Transform};
use serde::{Deserialize, Serialize};

/// Brightness of a light added with "Add light": dimmer than a sun, so it reads as a fill.
const ADDED_LIGHT_INTENSITY: f32 = 50_000.0;
/// The shadow-map sizes the panel offers, in texels per side: from cheap to sharp.
const SHADOW_MAP_SIZES: [u32; 4] = [512, 1024, 2048, 4096];
/// How far a directional light's cascades may reach from the camera, in world units.
const CASCADE_DISTANCE_RANGE: std::ops::RangeInclusive<f32> = 1.0..=1000.0;

/// What the state file keeps of a light's shadows (a `LightShadows`, which has no serde form).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ShadowState {
    /// Whether the light casts scene shadows.
    pub enabled: bool,
    /// Texels per side of one map.
    pub map_size: u32,
    /// Filter width in texels.
    pub softness: f32,
    /// Directional lights: how far the cascades reach.
    pub distance: f32,
}

impl From<LightShadows> for ShadowState {
    fn from(shadows: LightShadows) -> Self {
        Self {
            enabled: shadows.enabled,
            map_size: shadows.map_size,
            softness: shadows.softness,
            distance: shadows.distance,
        }
    }
}

impl From<ShadowState> for LightShadows {
    fn from(state: ShadowState) -> Self {
        Self {
            enabled: state.enabled,
            map_size: state.map_size,
            softness: state.softness,
            distance: state.distance,
        }
        // A hand-edited state file must not reach the renderer out of range.
        .sanitized()
    }
}

/// The shadow settings of every named light that has them, by name: what the state file keeps.
/// Lights without a name (added in the panel) cannot be found again at the next start.
pub fn named_light_shadows(world: &World) -> BTreeMap<String, ShadowState> {
    world
        .query::<(&Name, &LightShadows)>()
        .iter()
        .map(|(name, shadows)| (name.0.clone(), ShadowState::from(*shadows)))
        .collect()
}

/// Gives the named lights of `world` the shadow settings `saved` holds under their names.
pub fn restore_light_shadows(world: &mut World, saved: &BTreeMap<String, ShadowState>) {
    let restored: Vec<(Entity, LightShadows)> = crate::cli_types::light_entities(world)
        .into_iter()
        .filter_map(|light| {
            let name = world.get::<&Name>(light).ok()?;
            saved.get(&name.0).map(|state| (light, (*state).into()))
        })
        .collect();
    for (light, shadows) in restored {
        // Listed just above, so the entity exists.
        let _ = world.insert_one(light, shadows);
    }
}

/// The "Shadows" section of `light`: on/off, map size, softness and, for a directional light,
/// how far its cascades reach. Edits the light's `LightShadows` (adding one on the first
/// change; until then the light has the defaults).
fn shadow_controls(ui: &mut Ui, world: &mut World, light: Entity, directional: bool) {
    let before = world
        .get::<&LightShadows>(light)
        .map_or_else(|_| LightShadows::default(), |shadows| *shadows);
    let mut shadows = before;
    CollapsingHeader::new("Shadows")
        .id_salt(("shadows", light))
        .default_open(true)
        .show(ui, |ui| {
            ui.checkbox(&mut shadows.enabled, "scene shadows")
                .on_hover_text(
                    "Whether this light casts shadows on the scene (shadow maps). The parallax self-shadows are set per material.",
                );
            ui.add_enabled_ui(shadows.enabled, |ui| {
                ComboBox::from_label("shadow map size")
                    .selected_text(shadows.map_size.to_string())
                    .show_ui(ui, |ui| {
                        for size in SHADOW_MAP_SIZES {
                            ui.selectable_value(&mut shadows.map_size, size, size.to_string());
                        }
                    })
                    .response
                    .on_hover_text(
                        "Texels along each side of the shadow map (per cascade or cube face): larger is sharper and costs more memory and time.",
                    );
                // Only edits are clamped: showing a light whose values were set elsewhere (a
                // script, a file) must not change them.
                ui.add(
                    Slider::new(&mut shadows.softness, 0.0..=LightShadows::MAX_SOFTNESS)
                        .clamping(SliderClamping::Edits)
                        .text("shadow softness (texels)"),
                )
                .on_hover_text(
                    "Width of the shadow's filter in shadow-map texels: larger is softer, 0 is one hardware-filtered lookup.",
                );
                if directional {
                    ui.add(
                        Slider::new(&mut shadows.distance, CASCADE_DISTANCE_RANGE)
                            .logarithmic(true)
                            .clamping(SliderClamping::Edits)
                            .text("cascade distance"),
                    )
                    .on_hover_text(
                        "How far from the camera the sun's shadow cascades reach, in world units: shorter is sharper close by.",
                    );
                }
            });
        });
    if shadows != before {
        let _ = world.insert_one(light, shadows);
    }
}

/// The light controls' state: which light is edited.
#[derive(Debug, Default)]
pub struct LightControls {
    /// Index among the directional lights (in entity order).
    pub selected: usize,
}

/// Degrees around +Y (0 = the light comes from +Z) and above the horizon of the direction
/// towards the light (lights shine along their −Z).
pub fn azimuth_elevation(transform: &Transform) -> (f32, f32) {
    let towards_light = transform.rotation * Vec3::Z;
    (
        towards_light.x.atan2(towards_light.z).to_degrees(),
        towards_light.y.clamp(-1.0, 1.0).asin().to_degrees(),
    )
}

/// A light transform at `translation` shining from `azimuth`, `elevation` (degrees).
pub fn light_transform(translation: Vec3, azimuth: f32, elevation: f32) -> Transform {
    let (azimuth, elevation) = (azimuth.to_radians(), elevation.to_radians());
    let towards_light = Vec3::new(
        elevation.cos() * azimuth.sin(),
        elevation.sin(),
        elevation.cos() * azimuth.cos(),
    );
    // looking_at needs an up vector that is not the view direction: straight-down lights use +Z.
    let up = if towards_light.y.abs() > 0.999 {
        Vec3::Z
    } else {
        Vec3::Y
    };
    Transform::from_translation(translation).looking_at(translation - towards_light, up)
}

fn directional_lights(world: &World) -> Vec<Entity> {
    let mut lights: Vec<Entity> = world
        .query::<(Entity, &DirectionalLight)>()
        .iter()
        .map(|(entity, _)| entity)
        .collect();
    lights.sort();
    lights
}

impl LightControls {
    /// Shows the controls; edits `world` directly.
    pub fn show(&mut self, ui: &mut Ui, world: &mut World) {
        let lights = directional_lights(world);
        ui.horizontal(|ui| {
            if ui
                .button("Add light")
                .on_hover_text("Adds a directional light (a second sun) coming from the side.")
                .clicked()
            {
                world.spawn((
                    DirectionalLight {
                        intensity: ADDED_LIGHT_INTENSITY,
                        ..DirectionalLight::default()
                    },
                    light_transform(Vec3::ZERO, 120.0, 35.0),
                ));
                self.selected = lights.len();
            }
            let remove = ui
                .add_enabled(!lights.is_empty(), egui::Button::new("Remove light"))
                .on_hover_text("Removes the light selected below.");
            if remove.clicked()
                && let Some(&entity) = lights.get(self.selected)
            {
                let _ = world.despawn(entity);
                self.selected = self.selected.saturating_sub(1);
            }
        });
        let lights = directional_lights(world);
        if lights.is_empty() {
            ui.label("No directional light: only the ambient light and point lights shine.");
            return;
        }
        self.selected = self.selected.min(lights.len() - 1);
        if lights.len() > 1 {
            ui.add(
                Slider::new(&mut self.selected, 0..=lights.len() - 1)
                    .text("light")
                    .integer(),
            )
            .on_hover_text("Which directional light the controls below move.");
        }
        let entity = lights[self.selected];
        let Ok(mut transform) = world.get::<&mut Transform>(entity) else {
            ui.label("This light has no transform.");
            return;
        };
        let (mut azimuth, mut elevation) = azimuth_elevation(&transform);
        let mut changed = ui
            .add(Slider::new(&mut azimuth, -180.0..=180.0).text("light azimuth °"))
            .on_hover_text("Which side the light comes from, in degrees around the vertical.")
            .changed();
        changed |= ui
            .add(Slider::new(&mut elevation, -10.0..=90.0).text("light elevation °"))
            .on_hover_text(
                "How high the light stands: 0 grazes the ground, 90 is straight overhead.",
            )
            .changed();
        if changed {
            *transform = light_transform(transform.translation, azimuth, elevation);
        }
        drop(transform);
        if let Ok(mut light) = world.get::<&mut DirectionalLight>(entity) {
            ui.add(
                Slider::new(&mut light.intensity, 0.0..=500_000.0)
                    .logarithmic(true)
                    .text("light intensity (lux)"),
            )
            .on_hover_text("How bright this light is.");
        }
        shadow_controls(ui, world, entity, true);
    }
}

/// Shows every spot light's intensity and cone (degrees) and a button that adds one above the
/// origin, shining down; edits `world` directly.
pub fn spot_controls(ui: &mut Ui, world: &mut World) {
    if ui
        .button("Add spot light")
        .on_hover_text("Adds a spot light 3 m above the origin, shining straight down.")
        .clicked()
    {
        world.spawn((
            SpotLight::default(),
            light_transform(Vec3::new(0.0, 3.0, 0.0), 0.0, 90.0),
        ));
    }
    let mut spots: Vec<Entity> = world
        .query::<(Entity, &SpotLight)>()
        .iter()
        .map(|(entity, _)| entity)
        .collect();
    spots.sort();
    for (index, entity) in spots.into_iter().enumerate() {
        let Ok(mut spot) = world.get::<&mut SpotLight>(entity) else {
            continue;
        };
        ui.label(format!("spot {index}"));
        ui.add(
            Slider::new(&mut spot.intensity, 0.0..=10_000_000.0)
                .logarithmic(true)
                .text("spot intensity (cd)"),
        )
        .on_hover_text("Luminous intensity along the axis, in candela.");
        let mut outer = spot.outer_angle.to_degrees();
        let mut inner = spot.inner_angle.to_degrees();
        ui.add(Slider::new(&mut outer, 1.0..=90.0).text("outer cone °"))
            .on_hover_text("Half-angle at which the light reaches zero.");
        ui.add(Slider::new(&mut inner, 0.0..=outer).text("inner cone °"))
            .on_hover_text("Half-angle inside which the light is at full strength.");
        spot.outer_angle = outer.to_radians();
        spot.inner_angle = inner.min(outer).to_radians();
        drop(spot);
        shadow_controls(ui, world, entity, false);
    }
}

/// Shows every point light's scene shadows; edits `world` directly.
pub fn point_controls(ui: &mut Ui, world: &mut World) {
    let mut points: Vec<Entity> = world
        .query::<(Entity, &PointLight)>()
        .iter()
        .map(|(entity, _)| entity)
        .collect();
    points.sort();
    if points.is_empty() {
        ui.label("No point light in this scene.");
    }
    for (index, entity) in points.into_iter().enumerate() {
        ui.label(format!("point {index}"));
        shadow_controls(ui, world, entity, false);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn angles_round_trip_through_the_transform() {
        for (azimuth, elevation) in [(30.0, 45.0), (-120.0, 10.0), (170.0, 80.0)] {
            let transform = light_transform(Vec3::ONE, azimuth, elevation);
            let (a, e) = azimuth_elevation(&transform);
            assert!(
                (a - azimuth).abs() < 0.01 && (e - elevation).abs() < 0.01,
                "{a} {e}"
            );
        }
    }
}
