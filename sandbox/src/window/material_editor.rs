//! The editor rows of a material: one per declared parameter, made from its declaration (label,
//! range, unit, tooltip, group), so a new parameter shows up here without an edit. Rows sit
//! under a collapsing heading per declared group, the essential group open. Sliders span the
//! range artists use and show the unit beside the value; a value typed past the range is kept
//! within the parameter's declared limits.

use egui::{CollapsingHeader, ComboBox, Slider, SliderClamping, Ui};
use pom::material::{Param, ParamGroup, ParamKind, ParamValue};
use pom::{ParallaxMethod, ParallaxOcclusionMaterial};

/// Shows a row for every parameter of the parallax material, group by group; returns whether
/// anything changed.
pub fn edit_material(ui: &mut Ui, material: &mut ParallaxOcclusionMaterial) -> bool {
    let before = material.clone();
    // Narrower sliders leave room for the units beside the values within the panel's width.
    ui.spacing_mut().slider_width = 80.0;
    for group in ParamGroup::ALL {
        let mut params = ParallaxOcclusionMaterial::PARAMETERS
            .iter()
            .filter(|param| param.spec.group == group)
            .peekable();
        if params.peek().is_none() {
            continue;
        }
        CollapsingHeader::new(group.heading())
            .default_open(group == ParamGroup::Essential)
            .show(ui, |ui| {
                for param in params {
                    parameter_row(ui, param, material);
                }
            });
    }
    if material.layers.is_some() {
        CollapsingHeader::new("Layers")
            .default_open(true)
            .show(ui, |ui| edit_layers(ui, material));
    }
    // Keep the pair ordered while dragging either one, rather than showing an invalid state.
    if material.min_samples > material.max_samples {
        material.max_samples = material.min_samples;
    }
    *material != before
}

/// The weight channel of each layer, in order.
const WEIGHT_CHANNELS: [&str; 4] = ["red", "green", "blue", "alpha"];

/// A row of sliders for each drawn layer of a layered material: its tiling and its depth share
/// (the blend contrast is a declared parameter, among the method's rows).
fn edit_layers(ui: &mut Ui, material: &mut ParallaxOcclusionMaterial) {
    let Some(layers) = material.layers.as_mut() else {
        return;
    };
    let weights = match layers.weights {
        pom::LayerWeights::Texture(_) => "the weight map",
        _ => "the vertex colours",
    };
    ui.label(format!(
        "{} layers, weighed by {weights}",
        layers.layers.len()
    ));
    let (fewest, most) = pom::parallax::LAYER_TILING_LIMITS;
    for (index, layer) in layers
        .layers
        .iter_mut()
        .take(pom::parallax::MAX_LAYERS)
        .enumerate()
    {
        let channel = WEIGHT_CHANNELS[index];
        ui.label(format!("layer {} ({channel} weight)", index + 1));
        ui.add(
            Slider::new(&mut layer.tiling, 0.25..=64.0)
                .text(format!("layer {} tiling", index + 1))
                .logarithmic(true)
                .clamping(SliderClamping::Never),
        )
        .on_hover_text("Repeats of the layer's maps across the mesh's texture coordinates 0..1.");
        ui.add(
            Slider::new(&mut layer.height_scale, 0.0..=1.0)
                .text(format!("layer {} depth", index + 1)),
        )
        .on_hover_text(
            "The layer's relief depth as a share of height scale: a shallower layer stands higher in the blend.",
        );
        // Typed values may leave the slider's range, never the layer's limits.
        layer.tiling = if layer.tiling.is_finite() {
            layer.tiling.clamp(fewest, most)
        } else {
            1.0
        };
    }
}

/// The tooltip: the declared help, and the unit when there is one.
fn tooltip<M>(param: &Param<M>) -> String {
    if param.spec.unit.is_empty() {
        param.help.trim().to_owned()
    } else {
        format!("{} ({})", param.help.trim(), param.spec.unit)
    }
}

/// The text after a slider's value: its unit, when it has one.
fn unit_suffix<M>(param: &Param<M>) -> String {
    if param.spec.unit.is_empty() {
        String::new()
    } else {
        format!(" {}", param.spec.unit)
    }
}

/// One control for `param`, labelled with its name, greyed out where it has no effect.
pub fn parameter_row<M>(ui: &mut Ui, param: &Param<M>, material: &mut M) {
    let label = param.label();
    let suffix = unit_suffix(param);
    let before = (param.get)(material);
    let mut value = before;
    let enabled = (param.spec.applies)(material);
    let response = ui
        .add_enabled_ui(enabled, |ui| match (param.spec.kind, &mut value) {
            (
                ParamKind::Float {
                    editor: (low, high),
                    logarithmic,
                    ..
                },
                ParamValue::Float(number),
            ) => {
                ui.add(
                    Slider::new(number, low..=high)
                        .text(label)
                        .suffix(suffix)
                        .logarithmic(logarithmic)
                        .clamping(SliderClamping::Never),
                );
            }
            (
                ParamKind::Integer {
                    min,
                    max,
                    logarithmic,
                },
                ParamValue::Integer(number),
            ) => {
                ui.add(
                    Slider::new(number, min..=max)
                        .text(label)
                        .suffix(suffix)
                        .logarithmic(logarithmic),
                );
            }
            (ParamKind::Toggle, ParamValue::Toggle(on)) => {
                ui.checkbox(on, label);
            }
            (ParamKind::Choice(choices), ParamValue::Choice(name)) => {
                ComboBox::from_label(label)
                    .selected_text(*name)
                    .show_ui(ui, |ui| {
                        for choice in choices {
                            ui.selectable_value(name, choice.name, choice.name)
                                .on_hover_text(choice.help);
                        }
                    });
            }
            (ParamKind::Color, ParamValue::Color(rgba)) => {
                ui.horizontal(|ui| {
                    ui.color_edit_button_rgba_unmultiplied(rgba);
                    ui.label(label);
                });
            }
            _ => {
                ui.label(format!("{label}: {value}"));
            }
        })
        .response;
    response.on_hover_text(tooltip(param));
    if let (ParamKind::Float { min, max, .. }, ParamValue::Float(number)) =
        (param.spec.kind, &mut value)
    {
        // Typed values may leave the slider's range, never the declared limits.
        *number = if number.is_finite() {
            number.clamp(min, max)
        } else {
            min
        };
    }
    if value != before {
        // The value came from this parameter's own kind.
        let _ = (param.set)(material, value);
    }
}

/// The method combo box, labelled `label`, with each method's help on hover.
pub fn choose_method(ui: &mut Ui, label: &str, method: &mut ParallaxMethod) {
    choose(ui, label, method);
}

/// A combo box over every value of a [`pom::material::Choice`] enum, labelled `label`, with each
/// value's help on hover.
pub fn choose<C: pom::material::Choice>(ui: &mut Ui, label: &str, choice: &mut C) {
    ComboBox::from_label(label)
        .selected_text(choice.name())
        .show_ui(ui, |ui| {
            for (value, info) in C::VALUES.iter().zip(C::INFO) {
                ui.selectable_value(choice, *value, info.name)
                    .on_hover_text(info.help);
            }
        });
}
