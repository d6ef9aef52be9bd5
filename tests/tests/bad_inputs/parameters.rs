//! Material parameters: NaN, ±∞, negative, zero samples, min > max, absurd sample counts.

use super::*;

/// Renders the bad material (its `validate` names `field`), checks the frame is clean and that
/// the clamp was recorded for a warning (logged once per change).
fn clamped_with_a_warning(field: &str, spoil: impl FnOnce(&mut ParallaxOcclusionMaterial)) {
    let mut app = material_app(|images| {
        let height = images.add(pom::patterns::bricks(32, 2.0, 4.0).to_image());
        let mut material = ParallaxOcclusionMaterial {
            height_map: Some(HeightSource::Texture(height)),
            ..ParallaxOcclusionMaterial::default()
        };
        spoil(&mut material);
        let error = material.validate().unwrap_err();
        assert!(error.to_string().contains(field), "{error}");
        assert!(material.sanitized().validate().is_ok());
        material
    });
    renders_cleanly(&mut app);
    renders_cleanly(&mut app);
    let warned = app.resources.get::<MaterialWarnings>().unwrap();
    assert_eq!(warned.len(), 1, "the clamp was not recorded for a warning");
    // Made valid again, the entity is forgotten, so a later bad value is logged anew.
    for material in app.world.query_mut::<&mut ParallaxOcclusionMaterial>() {
        material.apply_preset(&pom::PomPreset::default());
    }
    renders_cleanly(&mut app);
    let warned = app.resources.get::<MaterialWarnings>().unwrap();
    assert!(
        warned.is_empty(),
        "a valid material is still listed as clamped"
    );
}

#[test]
fn material_nan_height_scale() {
    clamped_with_a_warning("height_scale is NaN", |m| m.height_scale = f32::NAN);
}

#[test]
fn material_infinite_height_scale() {
    clamped_with_a_warning("height_scale is inf", |m| m.height_scale = f32::INFINITY);
}

#[test]
fn material_negative_infinite_height_scale() {
    clamped_with_a_warning("height_scale is -inf", |m| {
        m.height_scale = f32::NEG_INFINITY
    });
}

#[test]
fn material_negative_height_scale() {
    clamped_with_a_warning("height_scale is -0.3", |m| m.height_scale = -0.3);
}

#[test]
fn material_zero_samples() {
    clamped_with_a_warning("min_samples is 0", |m| {
        m.min_samples = 0;
        m.max_samples = 0;
    });
}

#[test]
fn material_min_samples_over_max() {
    clamped_with_a_warning("min_samples (60) is greater than max_samples (4)", |m| {
        m.min_samples = 60;
        m.max_samples = 4;
    });
}

#[test]
fn material_inverted_texture_bounds() {
    clamped_with_a_warning("bounds_u_min (0.8) is not below bounds_u_max (0.2)", |m| {
        m.silhouette = pom::Silhouette::UvBounds;
        m.bounds_u_min = 0.8;
        m.bounds_u_max = 0.2;
    });
}

#[test]
fn material_texture_bounds_of_no_area() {
    clamped_with_a_warning("the bounds enclose no area", |m| {
        m.silhouette = pom::Silhouette::UvBounds;
        m.bounds_v_min = 0.5;
        m.bounds_v_max = 0.5;
    });
}

#[test]
fn material_nan_texture_bound() {
    clamped_with_a_warning("bounds_u_max is NaN", |m| {
        m.silhouette = pom::Silhouette::UvBounds;
        m.bounds_u_max = f32::NAN;
    });
}

#[test]
fn material_absurd_sample_count() {
    clamped_with_a_warning("max_samples is 4294967295 but must be at most 256", |m| {
        m.max_samples = u32::MAX
    });
    let clamped = ParallaxOcclusionMaterial {
        max_samples: u32::MAX,
        ..ParallaxOcclusionMaterial::default()
    }
    .sanitized();
    assert_eq!(clamped.max_samples, pom::parallax::MAX_SAMPLES_LIMIT);
}

#[test]
fn material_nan_shadow_softening() {
    clamped_with_a_warning("shadow_softening is NaN", |m| m.shadow_softening = f32::NAN);
}

#[test]
fn material_negative_lod_threshold() {
    clamped_with_a_warning("lod_threshold is -2", |m| m.lod_threshold = -2.0);
}

#[test]
fn material_relief_with_zero_binary_steps() {
    clamped_with_a_warning("relief_binary_steps is 0 but must be at least 1", |m| {
        m.method = ParallaxMethod::Relief;
        m.relief_binary_steps = 0;
    });
}

#[test]
fn material_occlusion_with_zero_secant_steps() {
    clamped_with_a_warning("secant_steps is 0 but must be at least 1", |m| {
        m.method = ParallaxMethod::Occlusion;
        m.secant_steps = 0;
    });
}

#[test]
fn material_nan_base_colour() {
    clamped_with_a_warning("base_color is NaN", |m| m.base_color.g = f32::NAN);
}
