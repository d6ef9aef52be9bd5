//! Sliders and combo boxes for every artist parameter of a `ParallaxOcclusionMaterial`. Ranges
//! are what artists use (the plugin accepts wider ones); tooltips say in plain words what each
//! control does.

use egui::{ComboBox, Slider, Ui};
use pom::parallax::MAX_SAMPLES_LIMIT;
use pom::{
    DebugView, HeightConvention, HeightUnits, LightingModel, ParallaxMethod,
    ParallaxOcclusionMaterial, ShadowMode,
};

/// Default bisection steps when switching to relief mapping (the glTF extras' default).
const DEFAULT_RELIEF_STEPS: u32 = 6;

/// Shows the editor; returns whether anything changed.
pub fn edit_material(ui: &mut Ui, material: &mut ParallaxOcclusionMaterial) -> bool {
    let before = material.clone();
    depth_rows(ui, material);
    sampling_rows(ui, material);
    shadow_rows(ui, material);
    lighting_rows(ui, material);
    row(
        ui,
        "Shows an inspection image instead of the lit surface: LOD tint, mip level, samples taken, texture coordinates, shadow, or normals.",
        |ui| {
            choose(
                ui,
                "debug view",
                &mut material.debug_view,
                &[
                    (DebugView::None, "None (lit)"),
                    (DebugView::Lod, "LOD tint"),
                    (DebugView::Mip, "Mip level"),
                    (DebugView::Samples, "Samples (heat map)"),
                    (DebugView::Uv, "Texture coordinates"),
                    (DebugView::Shadow, "Shadow"),
                    (DebugView::Normal, "Normal"),
                ],
            );
        },
    );
    *material != before
}

fn depth_rows(ui: &mut Ui, material: &mut ParallaxOcclusionMaterial) {
    choose_method(ui, "method", &mut material.method);
    if let ParallaxMethod::Relief { binary_steps } = &mut material.method {
        row(
            ui,
            "How many times relief mapping halves the gap around the hit point after the search: more steps give a sharper edge.",
            |ui| {
                ui.add(Slider::new(binary_steps, 1..=16).text("relief refinement steps"));
            },
        );
    }
    row(
        ui,
        "How deep the relief looks: the distance from white (the surface) to black (the deepest point) of the height map.",
        |ui| {
            let range = match material.height_units {
                HeightUnits::Texture => 0.0..=0.2,
                HeightUnits::World => 0.0..=1.0,
            };
            ui.add(
                Slider::new(&mut material.height_scale, range)
                    .text("height scale")
                    .clamping(egui::SliderClamping::Never),
            );
        },
    );
    row(
        ui,
        "Texture units change the depth when the texture is tiled or the object scaled; world units keep the same depth in metres.",
        |ui| {
            choose(
                ui,
                "height units",
                &mut material.height_units,
                &[
                    (HeightUnits::Texture, "Texture units"),
                    (HeightUnits::World, "World units"),
                ],
            );
        },
    );
    row(
        ui,
        "Whether white in the height map is the top (height map) or the deepest point (depth map, as LearnOpenGL and Bevy use).",
        |ui| {
            choose(
                ui,
                "height convention",
                &mut material.height_convention,
                &[
                    (HeightConvention::Height, "White is high"),
                    (HeightConvention::Depth, "White is deep"),
                ],
            );
        },
    );
    row(
        ui,
        "Writes the depth of the displaced surface, so objects standing on it sink into the relief where they should. Costs some speed.",
        |ui| {
            ui.checkbox(&mut material.depth_offset, "depth offset");
        },
    );
}

fn sampling_rows(ui: &mut Ui, material: &mut ParallaxOcclusionMaterial) {
    row(
        ui,
        "Height samples taken when looking straight at the surface. Fewer is faster.",
        |ui| {
            ui.add(
                Slider::new(&mut material.min_samples, 1..=MAX_SAMPLES_LIMIT)
                    .text("min samples")
                    .logarithmic(true),
            );
        },
    );
    row(
        ui,
        "Height samples taken at grazing angles, where the relief needs the most. Raise it if steps or slices show.",
        |ui| {
            ui.add(
                Slider::new(&mut material.max_samples, 1..=MAX_SAMPLES_LIMIT)
                    .text("max samples")
                    .logarithmic(true),
            );
        },
    );
    // Keep the pair ordered while dragging either one, rather than showing an invalid state.
    if material.min_samples > material.max_samples {
        material.max_samples = material.min_samples;
    }
    row(
        ui,
        "Mip level beyond which the surface is only normal mapped: lower values switch distant surfaces to the cheap path sooner.",
        |ui| {
            ui.add(Slider::new(&mut material.lod_threshold, 0.0..=12.0).text("LOD threshold"));
        },
    );
    row(
        ui,
        "Width, in mip levels, of the fade from full parallax to normal mapping before the threshold. Wider hides the switch better.",
        |ui| {
            ui.add(Slider::new(&mut material.lod_band, 0.01..=4.0).text("LOD band"));
        },
    );
}

fn shadow_rows(ui: &mut Ui, material: &mut ParallaxOcclusionMaterial) {
    row(
        ui,
        "Whether bumps cast shadows on the surface: off, hard-edged, or soft with a penumbra.",
        |ui| {
            choose(
                ui,
                "self-shadows",
                &mut material.shadows,
                &[
                    (ShadowMode::Off, "Off"),
                    (ShadowMode::Hard, "Hard"),
                    (ShadowMode::Soft, "Soft"),
                ],
            );
        },
    );
    row(
        ui,
        "How wide the soft shadows' penumbra is: larger is softer.",
        |ui| {
            ui.add_enabled(
                material.shadows == ShadowMode::Soft,
                Slider::new(&mut material.shadow_softening, 0.01..=4.0)
                    .text("shadow softening")
                    .logarithmic(true),
            );
        },
    );
}

fn lighting_rows(ui: &mut Ui, material: &mut ParallaxOcclusionMaterial) {
    row(
        ui,
        "Phong and Blinn-Phong use specular strength and shininess; Cook-Torrance uses roughness and metallic.",
        |ui| {
            choose(
                ui,
                "lighting model",
                &mut material.lighting,
                &[
                    (LightingModel::Phong, "Phong"),
                    (LightingModel::BlinnPhong, "Blinn-Phong"),
                    (LightingModel::CookTorrance, "Cook-Torrance (PBR)"),
                ],
            );
        },
    );
    let phong = material.lighting != LightingModel::CookTorrance;
    row(
        ui,
        "How bright the highlight is (Phong and Blinn-Phong).",
        |ui| {
            ui.add_enabled(
                phong,
                Slider::new(&mut material.specular_strength, 0.0..=2.0).text("specular strength"),
            );
        },
    );
    row(
        ui,
        "How small and sharp the highlight is (Phong and Blinn-Phong): higher is glossier.",
        |ui| {
            ui.add_enabled(
                phong,
                Slider::new(&mut material.shininess, 1.0..=512.0)
                    .text("shininess")
                    .logarithmic(true),
            );
        },
    );
    row(
        ui,
        "How rough the surface is (Cook-Torrance): 0 is a mirror-like polish, 1 is chalk.",
        |ui| {
            ui.add_enabled(
                !phong,
                Slider::new(&mut material.roughness, 0.0..=1.0).text("roughness"),
            );
        },
    );
    row(
        ui,
        "How metallic the surface is (Cook-Torrance): metals tint their highlight with the base colour.",
        |ui| {
            ui.add_enabled(
                !phong,
                Slider::new(&mut material.metallic, 0.0..=1.0).text("metallic"),
            );
        },
    );
    row(
        ui,
        "Scales the bumps of the normal map: 0 is flat shading, 1 as authored.",
        |ui| {
            ui.add(Slider::new(&mut material.normal_strength, 0.0..=3.0).text("normal strength"));
        },
    );
    row(ui, "Colour multiplied with the colour texture.", |ui| {
        let mut rgba = material.base_color.to_array();
        ui.horizontal(|ui| {
            ui.color_edit_button_rgba_unmultiplied(&mut rgba);
            ui.label("base colour");
        });
        let [r, g, b, a] = rgba;
        material.base_color = pom::Color { r, g, b, a };
    });
}

/// The method combo box, labelled `label`; switching to relief keeps or defaults its steps.
pub fn choose_method(ui: &mut Ui, label: &str, method: &mut ParallaxMethod) {
    row(
        ui,
        "How the surface is displaced: from plain normal mapping (no depth) to parallax occlusion and relief mapping (most accurate, most samples).",
        |ui| {
            let mut kind = MethodKind::of(*method);
            choose(
                ui,
                label,
                &mut kind,
                &[
                    (MethodKind::NormalMapping, "Normal mapping only"),
                    (MethodKind::ParallaxOffset, "Parallax offset (cheap)"),
                    (MethodKind::Steep, "Steep parallax"),
                    (MethodKind::Occlusion, "Parallax occlusion (POM)"),
                    (MethodKind::Relief, "Relief mapping"),
                ],
            );
            *method = kind.with_steps(*method);
        },
    );
}

/// One control (which carries its own label) that shows `tooltip` on hover.
fn row(ui: &mut Ui, tooltip: &str, control: impl FnOnce(&mut Ui)) {
    ui.scope(control).response.on_hover_text(tooltip);
}

/// A combo box labelled `label` over `options`.
fn choose<T: PartialEq + Copy>(ui: &mut Ui, label: &str, value: &mut T, options: &[(T, &str)]) {
    let selected = options
        .iter()
        .find(|(option, _)| option == value)
        .map_or("?", |(_, name)| name);
    ComboBox::from_label(label)
        .selected_text(selected)
        .show_ui(ui, |ui| {
            for (option, name) in options {
                ui.selectable_value(value, *option, *name);
            }
        });
}

/// The method without its parameter, so a combo box can switch methods.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum MethodKind {
    NormalMapping,
    ParallaxOffset,
    Steep,
    Occlusion,
    Relief,
}

impl MethodKind {
    fn of(method: ParallaxMethod) -> Self {
        match method {
            ParallaxMethod::NormalMapping => Self::NormalMapping,
            ParallaxMethod::ParallaxOffset => Self::ParallaxOffset,
            ParallaxMethod::Steep => Self::Steep,
            ParallaxMethod::Occlusion => Self::Occlusion,
            ParallaxMethod::Relief { .. } => Self::Relief,
        }
    }

    /// The method of this kind, keeping `previous`'s relief steps when it had some.
    fn with_steps(self, previous: ParallaxMethod) -> ParallaxMethod {
        match self {
            Self::NormalMapping => ParallaxMethod::NormalMapping,
            Self::ParallaxOffset => ParallaxMethod::ParallaxOffset,
            Self::Steep => ParallaxMethod::Steep,
            Self::Occlusion => ParallaxMethod::Occlusion,
            Self::Relief => match previous {
                ParallaxMethod::Relief { binary_steps } => ParallaxMethod::Relief { binary_steps },
                _ => ParallaxMethod::Relief {
                    binary_steps: DEFAULT_RELIEF_STEPS,
                },
            },
        }
    }
}
