// Triplanar mapping (`TextureMapping::Triplanar`): the material's maps projected along each
// world axis and mixed by how squarely the surface faces each. `reference/triplanar.rs` is the
// CPU reference of the projections and their weights. How the march reads the mixed height
// field (`TriplanarProjection`, `triplanar_height`) is in march.wgsl; here, what a pixel's
// projection is, and its colour and shading normal at the visible point.

// The share of the mix below which a projection is left out (the others renormalized): the
// shares are lowered by it before they are normalized, so they stay continuous, and a surface
// that mostly faces one axis reads one texture per height sample instead of three.
const TRIPLANAR_MIN_SHARE: f32 = 0.05;

// The shares of the projections along X, Y and Z for the unit `normal`: each axis's component
// raised to `sharpness`, normalized, lowered by TRIPLANAR_MIN_SHARE and normalized again.
fn triplanar_weights(normal: vec3<f32>, sharpness: f32) -> vec3<f32> {
    let raised = pow(abs(normal), vec3<f32>(max(sharpness, 1.0)));
    let shares = raised / max(dot(raised, vec3<f32>(1.0)), 1e-30);
    let kept = max(shares - vec3<f32>(TRIPLANAR_MIN_SHARE), vec3<f32>(0.0));
    return kept / max(dot(kept, vec3<f32>(1.0)), 1e-30);
}

// The projection of the surface at `position` (world) of frame `frame`, one repeat every
// `scale` world units, mixed with `sharpness`.
fn triplanar_projection(position: vec3<f32>, frame: TangentFrame, scale: f32, sharpness: f32) -> TriplanarProjection {
    return TriplanarProjection(fract(position / scale), frame.tangent, frame.bitangent_v,
        triplanar_weights(frame.normal, sharpness), select(vec3<f32>(-1.0), vec3<f32>(1.0), frame.normal >= vec3<f32>(0.0)));
}

// The axis (0 = X, 1 = Y, 2 = Z) whose projection has the largest share.
fn dominant_axis(weights: vec3<f32>) -> u32 {
    return select(select(2u, 1u, weights.y >= weights.z), 0u, weights.x >= max(weights.y, weights.z));
}

// The frame the march moves in on the surface of unit `normal`: the dominant projection's
// (`projection_frame`), so that on a face looking along an axis the march is the one texture
// coordinates laid out as that projection would give. Where the dominant projection changes
// the frame turns in the tangent plane, which moves no marched point: the coordinate's points
// are the same world points in any orientation.
fn march_frame(normal: vec3<f32>, sharpness: f32) -> TangentFrame {
    let sides = select(vec3<f32>(-1.0), vec3<f32>(1.0), normal >= vec3<f32>(0.0));
    return projection_frame(normal, sides, dominant_axis(triplanar_weights(normal, sharpness)));
}

// The frame in which the projection along `axis` lays its normal map on the surface of unit
// `normal`: the projection's u and v directions made tangent to it, as a mesh whose texture
// coordinates were that projection would give (on a face that looks along the axis, the same).
fn projection_frame(normal: vec3<f32>, sides: vec3<f32>, axis: u32) -> TangentFrame {
    var along_u = vec3<f32>(sides.z, 0.0, 0.0);
    var along_v = vec3<f32>(0.0, -1.0, 0.0);
    if axis == 0u {
        along_u = vec3<f32>(0.0, 0.0, -sides.x);
    } else if axis == 1u {
        along_u = vec3<f32>(1.0, 0.0, 0.0);
        along_v = vec3<f32>(0.0, 0.0, sides.y);
    }
    let tangent = safe_normalize(along_u - normal * dot(normal, along_u), safe_normalize(cross(along_v, normal), along_u));
    let across = cross(normal, tangent);
    return TangentFrame(normal, tangent, across * select(-1.0, 1.0, dot(across, along_v) >= 0.0));
}

// The colour and shading normal the projections give the point at the march's coordinate
// `planar`, its coordinate changing by `ddx_planar` and `ddy_planar` across the pixel. Each
// projection's normal-map texel is resolved in its own frame and the three are mixed as
// surface gradients (Mikkelsen 2020, "Surface Gradient-Based Bump Mapping Framework", §5.3),
// which keeps the mix a true perturbation of the surface where projections meet: a face that
// looks along one axis shows exactly that projection's normal.
fn triplanar_maps(color_texture: texture_2d<f32>, normal_texture: texture_2d<f32>, map_sampler: sampler,
    projection: TriplanarProjection, normal: vec3<f32>, planar: vec2<f32>, ddx_planar: vec2<f32>,
    ddy_planar: vec2<f32>, normal_strength: f32) -> TriplanarMaps {
    let q = projected_point(projection, planar);
    let ddx_q = projection.tangent * ddx_planar.x + projection.bitangent * ddx_planar.y;
    let ddy_q = projection.tangent * ddy_planar.x + projection.bitangent * ddy_planar.y;
    var color = vec4<f32>(0.0);
    var surface_gradient = vec3<f32>(0.0);
    for (var axis = 0u; axis < 3u; axis += 1u) {
        let weight = projection.weights[axis];
        if weight > 0.0 {
            let uv = projection_uv(q, projection.sides, axis);
            let ddx_uv = projection_uv(ddx_q, projection.sides, axis);
            let ddy_uv = projection_uv(ddy_q, projection.sides, axis);
            color += weight * textureSampleGrad(color_texture, map_sampler, uv, ddx_uv, ddy_uv);
            let encoded = textureSampleGrad(normal_texture, map_sampler, uv, ddx_uv, ddy_uv).xyz;
            let perturbed = perturbed_normal(projection_frame(normal, projection.sides, axis), encoded, normal_strength);
            surface_gradient += weight * (normal - perturbed / max(dot(perturbed, normal), 1e-3));
        }
    }
    return TriplanarMaps(color, safe_normalize(normal - surface_gradient, normal));
}

struct TriplanarMaps {
    color: vec4<f32>,
    normal: vec3<f32>,
}
