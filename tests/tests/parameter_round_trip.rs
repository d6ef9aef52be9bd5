//! Every parameter of `ParallaxOcclusionMaterial` survives a RON preset and a scene script's
//! `Set` patch, field by field (the glTF round trip is in gltf_loading.rs, the command line's in
//! the sandbox's material_args.rs); the lighting parameters the lit and the parallax material
//! share are one declaration.

use pom::{ParallaxOcclusionMaterial, PomPatch, PomPreset};
use pom_tests::parameters::{assert_same_parameters, every_parameter_changed};

#[test]
fn every_parameter_survives_a_ron_preset() {
    let material = every_parameter_changed();
    let text = material.preset().to_ron();
    let preset = PomPreset::from_ron(&text, "round-trip.ron").unwrap();
    let mut loaded = ParallaxOcclusionMaterial::default();
    loaded.apply_preset(&preset);
    assert_same_parameters(&loaded, &material, "a RON preset");
    assert_eq!(loaded, material);
}

#[test]
fn every_parameter_survives_a_script_patch() {
    let material = every_parameter_changed();
    let text = ron::to_string(&PomPatch::from_material(&material)).unwrap();
    let patch: PomPatch = ron::from_str(&text).unwrap();
    let mut patched = ParallaxOcclusionMaterial::default();
    patch.apply(&mut patched);
    assert_same_parameters(&patched, &material, "a script's Set patch");
}

#[test]
fn a_partial_patch_changes_only_its_fields() {
    let patch: PomPatch = ron::from_str("(max_samples: Some(90), method: Some(steep))").unwrap();
    let mut material = ParallaxOcclusionMaterial::default();
    patch.apply(&mut material);
    assert_eq!(
        material,
        ParallaxOcclusionMaterial {
            max_samples: 90,
            method: pom::ParallaxMethod::Steep,
            ..ParallaxOcclusionMaterial::default()
        }
    );
}

#[test]
fn the_two_materials_share_their_lighting_parameters() {
    use pom::LitMaterial;
    let (lit, parallax) = (LitMaterial::default(), ParallaxOcclusionMaterial::default());
    let shared: Vec<_> = LitMaterial::PARAMETERS
        .iter()
        .filter_map(|lit_param| {
            let parallax_param = ParallaxOcclusionMaterial::PARAMETERS
                .iter()
                .find(|param| param.name == lit_param.name)?;
            Some((lit_param, parallax_param))
        })
        .collect();
    let names: Vec<_> = shared.iter().map(|(param, _)| param.name).collect();
    assert_eq!(
        names,
        [
            "lighting",
            "base_color",
            "normal_strength",
            "specular_strength",
            "shininess",
            "roughness",
            "metallic",
            "double_sided"
        ]
    );
    for (lit_param, parallax_param) in shared {
        assert_eq!(
            lit_param.spec.kind, parallax_param.spec.kind,
            "{}",
            lit_param.name
        );
        // The model is each material's own choice; the rest is declared once.
        if lit_param.name != "lighting" {
            assert_eq!(lit_param.help, parallax_param.help, "{}", lit_param.name);
            assert_eq!(
                (lit_param.get)(&lit),
                (parallax_param.get)(&parallax),
                "the default of {}",
                lit_param.name
            );
        }
    }
}
