//! The parallax material's parameter checks: each bad value named, sanitized to a drawable one.

use super::*;

#[test]
fn defaults_are_valid_and_the_seeds() {
    let material = ParallaxOcclusionMaterial::default();
    assert_eq!(material.validate(), Ok(()));
    assert_eq!((material.min_samples, material.max_samples), (8, 50));
    assert_eq!(material.lod_threshold, 4.0);
    assert_eq!(material.sanitized(), material);
}

#[test]
fn each_bad_value_is_named_and_sanitized() {
    let bad = ParallaxOcclusionMaterial {
        height_scale: f32::NAN,
        lod_band: f32::INFINITY,
        shadow_softening: -1.0,
        min_samples: 0,
        max_samples: 1_000_000,
        roughness: 7.0,
        ..ParallaxOcclusionMaterial::default()
    };
    let messages: Vec<String> = bad.problems().iter().map(ToString::to_string).collect();
    assert_eq!(
        messages,
        [
            "height_scale is NaN, which is not a finite number",
            "min_samples is 0 but must be at least 1",
            "max_samples is 1000000 but must be at most 256",
            "lod_band is inf, which is not a finite number",
            "shadow_softening is -1 but must be at least 0.01",
            "roughness is 7 but must be at most 1",
        ]
    );
    let clean = bad.sanitized();
    assert_eq!(clean.problems(), []);
    assert_eq!(clean.height_scale, 0.05);
    assert_eq!(clean.lod_band, 1.0);
    assert_eq!(clean.shadow_softening, 0.01);
    assert_eq!(
        (clean.min_samples, clean.max_samples),
        (1, MAX_SAMPLES_LIMIT)
    );
}

#[test]
fn inverted_sample_bounds_are_an_error_and_get_swapped() {
    let inverted = ParallaxOcclusionMaterial {
        min_samples: 40,
        max_samples: 10,
        ..ParallaxOcclusionMaterial::default()
    };
    assert_eq!(
        inverted.validate(),
        Err(PomMaterialError::SamplesInverted { min: 40, max: 10 })
    );
    let clean = inverted.sanitized();
    assert_eq!((clean.min_samples, clean.max_samples), (10, 40));
}

#[test]
fn texture_bounds_of_no_area_are_an_error_and_get_drawable() {
    let inverted = ParallaxOcclusionMaterial {
        silhouette: Silhouette::UvBounds,
        bounds_u_min: 0.75,
        bounds_u_max: 0.25,
        ..ParallaxOcclusionMaterial::default()
    };
    assert_eq!(
        inverted.validate().unwrap_err().to_string(),
        "bounds_u_min (0.75) is not below bounds_u_max (0.25): the bounds enclose no area"
    );
    assert!(!inverted.is_valid());
    let clean = inverted.sanitized();
    assert_eq!((clean.bounds_u_min, clean.bounds_u_max), (0.25, 0.75));
    assert!(clean.is_valid());

    let flat = ParallaxOcclusionMaterial {
        bounds_v_min: 2.0,
        bounds_v_max: 2.0,
        ..inverted.clone()
    };
    assert!(flat.problems().contains(&PomMaterialError::BoundsEmpty {
        axis: 'v',
        min: 2.0,
        max: 2.0
    }));
    let clean = flat.sanitized();
    assert_eq!((clean.bounds_v_min, clean.bounds_v_max), (0.0, 1.0));

    let not_a_number = ParallaxOcclusionMaterial {
        bounds_v_max: f32::NAN,
        ..inverted
    };
    assert_eq!(
        not_a_number.validate().unwrap_err().to_string(),
        "bounds_v_max is NaN, which is not a finite number"
    );
    assert!(not_a_number.sanitized().is_valid());
}

#[test]
fn negative_height_scale_is_clamped_to_flat() {
    let material = ParallaxOcclusionMaterial {
        height_scale: -0.2,
        ..ParallaxOcclusionMaterial::default()
    };
    assert!(matches!(
        material.validate(),
        Err(PomMaterialError::Limit(LimitError::TooSmall {
            field: "height_scale",
            ..
        }))
    ));
    assert_eq!(material.sanitized().height_scale, 0.0);
}

#[test]
fn a_negative_or_nan_triplanar_scale_is_named_and_sanitized() {
    for (scale, message, clean) in [
        (
            -2.0,
            "triplanar_scale is -2 but must be at least 0.001",
            TRIPLANAR_SCALE_LIMITS.0,
        ),
        (
            f32::NAN,
            "triplanar_scale is NaN, which is not a finite number",
            1.0,
        ),
        (
            0.0,
            "triplanar_scale is 0 but must be at least 0.001",
            TRIPLANAR_SCALE_LIMITS.0,
        ),
    ] {
        let material = ParallaxOcclusionMaterial {
            mapping: TextureMapping::Triplanar,
            triplanar_scale: scale,
            ..ParallaxOcclusionMaterial::default()
        };
        assert_eq!(material.validate().unwrap_err().to_string(), message);
        assert!(!material.is_valid());
        assert_eq!(material.sanitized().triplanar_scale, clean);
    }
}

#[test]
fn a_triplanar_sharpness_out_of_range_is_named_and_clamped() {
    for (sharpness, message, clean) in [
        (
            0.5,
            "triplanar_sharpness is 0.5 but must be at least 1",
            1.0,
        ),
        (
            100.0,
            "triplanar_sharpness is 100 but must be at most 64",
            64.0,
        ),
    ] {
        let material = ParallaxOcclusionMaterial {
            mapping: TextureMapping::Triplanar,
            triplanar_sharpness: sharpness,
            ..ParallaxOcclusionMaterial::default()
        };
        assert_eq!(material.validate().unwrap_err().to_string(), message);
        assert_eq!(material.sanitized().triplanar_sharpness, clean);
    }
}

#[test]
fn layers_under_triplanar_mapping_are_an_error_and_draw_by_uv() {
    let mut images = crate::Assets::<Image>::default();
    let field = crate::HeightField::from_fn(2, 2, |u, _| u);
    let layers = ParallaxLayers::new(
        &mut images,
        vec![(super::super::ParallaxLayer::default(), Some(&field))],
        super::super::LayerWeights::VertexColors,
    )
    .unwrap();
    let material = ParallaxOcclusionMaterial {
        layers: Some(layers),
        mapping: TextureMapping::Triplanar,
        ..ParallaxOcclusionMaterial::default()
    };
    assert_eq!(material.problems(), [PomMaterialError::TriplanarLayers]);
    assert!(!material.is_valid());
    let clean = material.sanitized();
    assert_eq!(clean.mapping, TextureMapping::Uv);
    assert!(clean.is_valid());
}
