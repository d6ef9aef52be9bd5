//! The split-view section of the panel: turn it on, move the wipe, and set what image B (the
//! right side) differs in for the selected material: its method, or any parameter after
//! copying A's. The plugin renders B (`pom::SplitView`); the viewport shows A, then B clipped
//! at the wipe.

use egui::{Slider, Ui};
use pom::hecs::Entity;
use pom::{App, ParallaxOcclusionMaterial, SplitView};

use super::material_editor::{choose_method, edit_material};

/// What the split-view section remembers.
#[derive(Clone, Debug, PartialEq)]
pub struct SplitControls {
    /// Whether the viewport shows A and B side by side.
    pub enabled: bool,
    /// Where A ends and B begins, as a fraction of the viewport's width.
    pub wipe: f32,
}

impl Default for SplitControls {
    fn default() -> Self {
        Self {
            enabled: false,
            wipe: 0.5,
        }
    }
}

impl SplitControls {
    /// Shows the section for the `selected` material entity, keeping `app`'s [`SplitView`]
    /// resource present exactly while the split view is on.
    pub fn show(&mut self, ui: &mut Ui, app: &mut App, selected: Option<Entity>) {
        ui.checkbox(&mut self.enabled, "split view (A | B)")
            .on_hover_text(
                "Shows the scene twice, side by side: A (left) as edited above, B (right) with \
                 the differences set below.",
            );
        if !self.enabled {
            app.resources.remove::<SplitView>();
            return;
        }
        ui.add(Slider::new(&mut self.wipe, 0.0..=1.0).text("wipe"))
            .on_hover_text("Where the left image (A) ends and the right one (B) begins.");
        let Some(entity) = selected else {
            return;
        };
        let Ok(a) = app
            .world
            .get::<&ParallaxOcclusionMaterial>(entity)
            .map(|material| (*material).clone())
        else {
            return;
        };
        let split = app.resources.get_or_default::<SplitView>();
        if ui
            .button("Copy A's parameters to B")
            .on_hover_text("B becomes a copy of A's material; then edit B below.")
            .clicked()
        {
            split.overrides.insert(entity, a.clone());
        }
        let b = split.overrides.entry(entity).or_insert_with(|| a.clone());
        // B always uses A's textures: only parameters are compared.
        b.base_color_texture = a.base_color_texture.clone();
        b.normal_map = a.normal_map.clone();
        b.height_map = a.height_map.clone();
        ui.push_id("split view B", |ui| {
            choose_method(ui, "B method", &mut b.method);
            ui.collapsing("B's other parameters", |ui| {
                edit_material(ui, b);
            });
        });
    }
}
