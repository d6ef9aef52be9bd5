//! The light controls: the direction of a directional light as azimuth / elevation sliders,
//! written into the light entity's `Transform`, adding or removing lights, and each spot
//! light's intensity and cone.

use egui::{Slider, Ui};
use glam::Vec3;
use pom::hecs::{Entity, World};
use pom::{DirectionalLight, SpotLight, Transform};

/// Brightness of a light added with "Add light": dimmer than a sun, so it reads as a fill.
const ADDED_LIGHT_INTENSITY: f32 = 50_000.0;

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
