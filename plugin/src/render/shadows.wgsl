// Scene shadows: the shadow maps the shadows phase rendered, looked up with a filter by every
// material that receives them. Composed after frame.wgsl and mesh_vertex.wgsl. Mirrors
// `ShadowViewGpu` in gpu_types.rs (the layout test checks them against each other).

struct ShadowView {
    view_projection: mat4x4<f32>,
    // The part of its layer the map covers along each side.
    uv_scale: f32,
    // Cascades: the distance along the camera's view up to which this cascade covers.
    far_view_depth: f32,
    // One texel's world size: over the map (orthographic) or at one unit from the light.
    texel_world_size: f32,
    perspective: u32,
    // Filter radius in texels.
    softness: f32,
    layer: u32,
    _padding: vec2<u32>,
}

// Set by the renderer on the shading pipelines of frames that render shadow maps; without it
// the compiler drops every lookup below (and the registers they would hold).
override SCENE_SHADOWS: bool = false;

@group(0) @binding(5) var<storage, read> shadow_views: array<ShadowView>;
@group(0) @binding(6) var shadow_maps: texture_depth_2d_array;
@group(0) @binding(7) var shadow_sampler: sampler_comparison;

// Receiver biases, in shadow-map texels at the point (so each cascade and each distance from a
// spot gets its own): the point moves towards the light by SHADOW_LIGHT_OFFSET texels, and
// along its normal by (filter radius + SHADOW_NORMAL_OFFSET) texels × sin θ, which is what a
// plane tilted by θ needs to stay in front of its own depths across the filter. No caster-side
// bias: the map holds the surfaces' true depths (parallax casters their relief's).
const SHADOW_LIGHT_OFFSET: f32 = 1.0;
const SHADOW_NORMAL_OFFSET: f32 = 1.5;

// Whether scene shadows fall on the object drawn as instance `object_index`.
fn receives_scene_shadows(object_index: u32) -> bool {
    return SCENE_SHADOWS && transforms[object_index].receives_shadows != 0u;
}

// The cube face (+X, −X, +Y, −Y, +Z, −Z) that sees `offset` from the light.
fn cube_face(offset: vec3<f32>) -> u32 {
    let size = abs(offset);
    if size.x >= size.y && size.x >= size.z {
        return select(1u, 0u, offset.x >= 0.0);
    }
    if size.y >= size.z {
        return select(3u, 2u, offset.y >= 0.0);
    }
    return select(5u, 4u, offset.z >= 0.0);
}

// Percentage-closer filtering: 4 × 4 hardware-compared (bilinear) taps spread over ±softness
// texels; one tap without softness.
fn filtered_shadow(view: ShadowView, uv: vec2<f32>, depth: f32) -> f32 {
    if view.softness <= 0.0 {
        return textureSampleCompareLevel(shadow_maps, shadow_sampler, uv, view.layer, depth);
    }
    let texel = 1.0 / vec2<f32>(textureDimensions(shadow_maps));
    let spacing = texel * (2.0 * view.softness / 3.0);
    var lit = 0.0;
    for (var y = 0; y < 4; y += 1) {
        for (var x = 0; x < 4; x += 1) {
            let tap = uv + (vec2<f32>(f32(x), f32(y)) - 1.5) * spacing;
            lit += textureSampleCompareLevel(shadow_maps, shadow_sampler, tap, view.layer, depth);
        }
    }
    return lit / 16.0;
}

// How much of light `light_index` (as light_at numbers them) reaches `world_position` past
// everything in its shadow maps: 1 = all, 0 = none. `normal` is the receiving surface's.
// Outside every map (beyond the cascades, behind a spot) the light is let through.
fn scene_shadow(light_index: u32, world_position: vec3<f32>, normal: vec3<f32>) -> f32 {
    let directional_count = min(frame.light_counts.x, MAX_DIRECTIONAL_LIGHTS);
    var first = 0u;
    var count = 0u;
    var view_offset = 0u;
    var to_light = vec3<f32>(0.0, 0.0, 1.0);
    var distance_to_light = 1.0;
    if light_index < directional_count {
        let light = frame.directional_lights[light_index];
        first = light.first_shadow_view;
        count = light.shadow_view_count;
        to_light = light.direction_to_light.xyz;
        // The first cascade reaching past the point's distance along the camera's view.
        let view_depth = dot(world_position - frame.camera_position.xyz, frame.view_direction.xyz);
        view_offset = count;
        for (var i = 0u; i < count; i += 1u) {
            if view_depth <= shadow_views[first + i].far_view_depth {
                view_offset = i;
                break;
            }
        }
    } else {
        let light = point_lights[light_index - directional_count];
        first = light.first_shadow_view;
        count = light.shadow_view_count;
        let offset = world_position - light.position_range.xyz;
        distance_to_light = length(offset);
        to_light = select(vec3<f32>(0.0, 0.0, 1.0), -offset / distance_to_light, distance_to_light > 1e-6);
        view_offset = select(0u, cube_face(offset), count == 6u);
    }
    if view_offset >= count {
        return 1.0;
    }
    let view = shadow_views[first + view_offset];
    let texel = view.texel_world_size * select(1.0, distance_to_light, view.perspective != 0u);
    let facing = select(-normal, normal, dot(normal, to_light) >= 0.0);
    let cos_theta = clamp(dot(facing, to_light), 0.0, 1.0);
    let sin_theta = sqrt(1.0 - cos_theta * cos_theta);
    let biased = world_position + to_light * (texel * SHADOW_LIGHT_OFFSET)
        + facing * (texel * (view.softness + SHADOW_NORMAL_OFFSET) * sin_theta);
    let clip = view.view_projection * vec4<f32>(biased, 1.0);
    if clip.w <= 0.0 {
        return 1.0;
    }
    let ndc = clip.xyz / clip.w;
    if any(abs(ndc.xy) > vec2<f32>(1.0)) || ndc.z > 1.0 {
        return 1.0;
    }
    let uv = (ndc.xy * vec2<f32>(0.5, -0.5) + 0.5) * view.uv_scale;
    return filtered_shadow(view, uv, max(ndc.z, 0.0));
}
