// Reflection models shared by every material. A light of radiance E lights a white Lambertian
// surface facing it to E, so switching models keeps the overall brightness.

const PI: f32 = 3.14159265;

// The LIGHTING_* model codes are generated from `LightingModel`: a shader that includes this file
// lists `LightingModel::wgsl_constants` among its constants (see lit/mod.rs, parallax/mod.rs).

struct Surface {
    albedo: vec3<f32>,
    // Phong / Blinn-Phong: weight of the highlight.
    specular_strength: f32,
    // Phong / Blinn-Phong exponent.
    shininess: f32,
    // Cook-Torrance / Oren-Nayar: perceptual roughness in 0..1.
    roughness: f32,
    // Cook-Torrance: 0 = dielectric, 1 = metal.
    metallic: f32,
    model: u32,
}

// Phong as in Tatarchuk's Listing 2: Lambert diffuse plus (R·L)^n around the mirrored view ray.
fn phong(surface: Surface, n_dot_l: f32, normal: vec3<f32>, to_light: vec3<f32>, to_eye: vec3<f32>) -> vec3<f32> {
    let reflected = reflect(-to_eye, normal);
    let specular = surface.specular_strength * pow(max(dot(reflected, to_light), 0.0), surface.shininess);
    return surface.albedo * n_dot_l + vec3<f32>(specular * step(0.0, n_dot_l));
}

// Blinn-Phong: the highlight follows N·H, with H halfway between the light and the eye.
fn blinn_phong(surface: Surface, n_dot_l: f32, normal: vec3<f32>, to_light: vec3<f32>, to_eye: vec3<f32>) -> vec3<f32> {
    let half_vector = safe_normalize(to_light + to_eye, normal);
    let specular = surface.specular_strength * pow(max(dot(normal, half_vector), 0.0), surface.shininess);
    return (surface.albedo + vec3<f32>(specular)) * n_dot_l;
}

// GGX specular (GGX distribution, Smith-Schlick visibility, Schlick Fresnel) and its Fresnel
// term, which the diffuse terms below leave to the specular lobe.
struct Specular {
    reflected: vec3<f32>,
    fresnel: vec3<f32>,
}

fn ggx_specular(surface: Surface, n_dot_l: f32, n_dot_v: f32, normal: vec3<f32>, half_vector: vec3<f32>, to_eye: vec3<f32>) -> Specular {
    let n_dot_h = max(dot(normal, half_vector), 0.0);
    let v_dot_h = max(dot(to_eye, half_vector), 0.0);
    let roughness = clamp(surface.roughness, 0.03, 1.0);
    let alpha = roughness * roughness;
    let alpha2 = alpha * alpha;
    let d_denominator = n_dot_h * n_dot_h * (alpha2 - 1.0) + 1.0;
    let distribution = alpha2 / (PI * d_denominator * d_denominator);
    let k = (roughness + 1.0) * (roughness + 1.0) / 8.0;
    let visibility = 1.0 / ((n_dot_l * (1.0 - k) + k) * (n_dot_v * (1.0 - k) + k));
    let f0 = mix(vec3<f32>(0.04), surface.albedo, surface.metallic);
    let fresnel = f0 + (1.0 - f0) * pow(1.0 - v_dot_h, 5.0);
    // π cancels the 1/π of the BRDF so a light of radiance E behaves as in the Phong models.
    return Specular(fresnel * distribution * visibility * 0.25 * PI, fresnel);
}

// Cook-Torrance specular over an Oren-Nayar diffuse term, as in the source text "Parallax
// Mapping with Self Shadowing" (../shared/seeds).
fn cook_torrance_oren_nayar(surface: Surface, n_dot_l: f32, normal: vec3<f32>, to_light: vec3<f32>, to_eye: vec3<f32>) -> vec3<f32> {
    let n_dot_v = max(dot(normal, to_eye), 1e-4);
    let half_vector = safe_normalize(to_light + to_eye, normal);
    let specular = ggx_specular(surface, n_dot_l, n_dot_v, normal, half_vector, to_eye);

    // Oren-Nayar with σ = roughness: rough surfaces scatter more light back towards the light.
    let roughness = clamp(surface.roughness, 0.03, 1.0);
    let sigma2 = roughness * roughness;
    let a = 1.0 - 0.5 * sigma2 / (sigma2 + 0.33);
    let b = 0.45 * sigma2 / (sigma2 + 0.09);
    let light_in_plane = safe_normalize(to_light - normal * n_dot_l, vec3<f32>(0.0));
    let eye_in_plane = safe_normalize(to_eye - normal * n_dot_v, vec3<f32>(0.0));
    let cos_phi = max(dot(light_in_plane, eye_in_plane), 0.0);
    let sin_alpha = sqrt(max(1.0 - min(n_dot_l, n_dot_v) * min(n_dot_l, n_dot_v), 0.0));
    let tan_beta = sqrt(max(1.0 - max(n_dot_l, n_dot_v) * max(n_dot_l, n_dot_v), 0.0)) / max(max(n_dot_l, n_dot_v), 1e-4);
    let oren_nayar = a + b * cos_phi * sin_alpha * tan_beta;
    let diffuse = surface.albedo * (1.0 - surface.metallic) * (vec3<f32>(1.0) - specular.fresnel) * oren_nayar;
    return (diffuse + specular.reflected) * n_dot_l;
}

// glTF's metallic-roughness BRDF (specification, appendix B): the same GGX lobe over Lambert.
fn ggx_lambert(surface: Surface, n_dot_l: f32, normal: vec3<f32>, to_light: vec3<f32>, to_eye: vec3<f32>) -> vec3<f32> {
    let n_dot_v = max(dot(normal, to_eye), 1e-4);
    let half_vector = safe_normalize(to_light + to_eye, normal);
    let specular = ggx_specular(surface, n_dot_l, n_dot_v, normal, half_vector, to_eye);
    let diffuse = surface.albedo * (1.0 - surface.metallic) * (vec3<f32>(1.0) - specular.fresnel);
    return (diffuse + specular.reflected) * n_dot_l;
}

// The light arriving from all around, reflected: with an environment, its irradiance on the
// diffuse part and its radiance prefiltered at the surface's roughness on the specular part
// (split sum, with multiple-scattering compensation where the frame asks), each darkened by its
// own occlusion (x: diffuse, y: specular); without one, the ambient term on the albedo, darkened
// by the diffuse occlusion. Composed after environment.wgsl.
fn ambient_lighting(surface: Surface, normal: vec3<f32>, to_eye: vec3<f32>, occlusion: vec2<f32>) -> vec3<f32> {
    if !has_environment() {
        return frame.ambient.rgb * surface.albedo * occlusion.x;
    }
    let n_dot_v = clamp(dot(normal, to_eye), 1e-4, 1.0);
    let reflected = reflect(-to_eye, normal);
    let irradiance = environment_diffuse(normal) * occlusion.x;
    if surface.model == LIGHTING_PHONG || surface.model == LIGHTING_BLINN_PHONG {
        // The highlight's lobe s·(R·L)^n integrates to s·2/(n + 1) over the hemisphere; its
        // width as a GGX roughness through Blinn-Phong's α² = 2 / (n + 2).
        let roughness = sqrt(sqrt(2.0 / (surface.shininess + 2.0)));
        let specular = surface.specular_strength * 2.0 / (surface.shininess + 1.0);
        return surface.albedo * irradiance
            + specular * environment_specular(reflected, roughness) * occlusion.y;
    }
    let roughness = clamp(surface.roughness, 0.03, 1.0);
    let f0 = mix(vec3<f32>(0.04), surface.albedo, surface.metallic);
    let split = environment_split_sum(n_dot_v, roughness);
    let single = f0 * split.x + split.y;
    let compensation = 1.0 + frame.environment_options.x * f0 * (1.0 / max(split.x + split.y, 1e-4) - 1.0);
    let diffuse = surface.albedo * (1.0 - surface.metallic) * (vec3<f32>(1.0) - single);
    return diffuse * irradiance + single * compensation * environment_specular(reflected, roughness) * occlusion.y;
}

// The specular occlusion that goes with an ambient occlusion `ao` (Lagarde & de Rousiers 2014,
// "Moving Frostbite to PBR", §4.10.2): smooth surfaces seen head-on are occluded less.
fn specular_occlusion(n_dot_v: f32, ao: f32, roughness: f32) -> f32 {
    return clamp(pow(max(n_dot_v, 0.0) + ao, exp2(-16.0 * roughness - 1.0)) - 1.0 + ao, 0.0, 1.0);
}

// Reflected light for one light of unit radiance arriving from `to_light`.
fn direct_lighting(surface: Surface, normal: vec3<f32>, to_light: vec3<f32>, to_eye: vec3<f32>) -> vec3<f32> {
    let n_dot_l = max(dot(normal, to_light), 0.0);
    if n_dot_l <= 0.0 {
        return vec3<f32>(0.0);
    }
    switch surface.model {
        case LIGHTING_PHONG: {
            return phong(surface, n_dot_l, normal, to_light, to_eye);
        }
        case LIGHTING_COOK_TORRANCE: {
            return cook_torrance_oren_nayar(surface, n_dot_l, normal, to_light, to_eye);
        }
        case LIGHTING_GGX_LAMBERT: {
            return ggx_lambert(surface, n_dot_l, normal, to_light, to_eye);
        }
        default: {
            return blinn_phong(surface, n_dot_l, normal, to_light, to_eye);
        }
    }
}
