// The per-pixel tangent frame of a mesh surface and normal-map decoding.

// normalize() of a zero vector is NaN; degenerate input falls back to `fallback`.
fn safe_normalize(v: vec3<f32>, fallback: vec3<f32>) -> vec3<f32> {
    let length_squared = dot(v, v);
    if length_squared > 1e-20 {
        return v * inverseSqrt(length_squared);
    }
    return fallback;
}

struct TangentFrame {
    // Geometric (interpolated vertex) normal.
    normal: vec3<f32>,
    // Unit dP/du.
    tangent: vec3<f32>,
    // Unit dP/dv (MikkTSpace: cross(normal, tangent) × sign).
    bitangent_v: vec3<f32>,
}

// Orthonormal frame from interpolated vertex attributes; `tangent.w` is the MikkTSpace sign.
fn tangent_frame(world_normal: vec3<f32>, world_tangent: vec4<f32>) -> TangentFrame {
    let normal = safe_normalize(world_normal, vec3<f32>(0.0, 0.0, 1.0));
    // Gram-Schmidt: interpolation leaves the tangent slightly off perpendicular.
    let tangent = safe_normalize(
        world_tangent.xyz - normal * dot(normal, world_tangent.xyz),
        safe_normalize(cross(normal, vec3<f32>(0.0, 1.0, 0.1)), vec3<f32>(1.0, 0.0, 0.0)),
    );
    let sign = select(1.0, -1.0, world_tangent.w < 0.0);
    return TangentFrame(normal, tangent, cross(normal, tangent) * sign);
}

// The frame of the side a fragment shows. A back face (drawn only for double-sided materials)
// gets the reversed normal, as glTF asks before lighting, with dP/dv kept (the MikkTSpace sign
// flips with the normal), so texture space and the normal map keep their orientation and a
// parallax march sees the back as a surface of its own.
fn facing_tangent_frame(world_normal: vec3<f32>, world_tangent: vec4<f32>, front_facing: bool) -> TangentFrame {
    if front_facing {
        return tangent_frame(world_normal, world_tangent);
    }
    return tangent_frame(-world_normal, vec4<f32>(world_tangent.xyz, -world_tangent.w));
}

// A world-space vector in the frame's (u, v, normal) coordinates.
fn to_tangent_space(frame: TangentFrame, v: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(dot(v, frame.tangent), dot(v, frame.bitangent_v), dot(v, frame.normal));
}

// The shading normal from an encoded normal-map texel (OpenGL convention: green points up the
// image, which is −v, so the bitangent dP/dv enters negated). `strength` scales the tilt.
fn perturbed_normal(frame: TangentFrame, encoded: vec3<f32>, strength: f32) -> vec3<f32> {
    let texel = encoded * 2.0 - 1.0;
    let tangent_normal = vec3<f32>(texel.xy * strength, max(texel.z, 1e-3));
    return safe_normalize(
        frame.tangent * tangent_normal.x - frame.bitangent_v * tangent_normal.y
            + frame.normal * tangent_normal.z,
        frame.normal,
    );
}
