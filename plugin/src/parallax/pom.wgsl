// Entry points of `ParallaxOcclusionMaterial`. Composed after the generated enum codes,
// frame.wgsl, mesh_vertex.wgsl, tangent_space.wgsl, lighting.wgsl and march.wgsl (see
// parallax/mod.rs). Mirrors `PomUniform` in gpu.rs (the layout test checks them).

// Pipeline-overridable constants: every pipeline is compiled for one combination (see
// parallax/pipelines.rs), so the GPU compiler drops every other path and its registers.
override METHOD: u32 = METHOD_OCCLUSION;
override SHADOW_MODE: u32 = SHADOWS_SOFT;
override LIGHTING_MODEL: u32 = LIGHTING_PHONG;
override DEBUG_VIEW: u32 = DEBUG_NONE;
// Set on the shadow-map pipelines: a caster always marches (no LOD fade: a light far from the
// surface, or at a grazing angle, would otherwise leave the flat polygon in the map, above every
// receiver's relief, which would then read as shadowed).
override SHADOW_CASTER: bool = false;
// Whether the passes that march for their depth write the displaced point's (depth_offset) or
// the polygon's (a silhouette that only clips).
override DEPTH_OFFSET: bool = false;
override SILHOUETTE: u32 = SILHOUETTE_OFF;
// The height's channel (0 = red .. 3 = alpha) and whether white is deepest, set per pipeline
// from the material: the per-sample channel pick and inversion fold away.
override HEIGHT_CHANNEL: u32 = 0u;
override HEIGHT_IS_DEPTH: bool = false;

// `PomParams` (every declared parameter, in declaration order) is generated from the Rust
// declarations and prepended, like the enum codes.
struct PomUniform {
    // The vectors first: their alignment needs no padding whatever the parameters' size.
    layer_tiling: vec4<f32>,
    layer_depth: vec4<f32>,
    params: PomParams,
    // The height texture as bound, in texels (1 × 1 without one), and its mip levels.
    height_texture_width: f32,
    height_texture_height: f32,
    height_mip_levels: f32,
    // 1 when the material has a height map.
    has_height_map: u32,
    // 0: not a layered material.
    layer_count: u32,
    weights_from_texture: u32,
    weight_texture_width: f32,
    weight_texture_height: f32,
    padding: array<u32, 3>,
}

@group(0) @binding(2) var<storage, read> materials: array<PomUniform>;
// A layered material's first layer's colour and normal maps, and its layers' packed heights.
@group(1) @binding(0) var base_color_texture: texture_2d<f32>;
@group(1) @binding(1) var normal_map: texture_2d<f32>;
@group(1) @binding(2) var height_texture: texture_2d<f32>;
// A layered material's weight map and the other layers' colour and normal maps.
@group(1) @binding(3) var layer_weights_texture: texture_2d<f32>;
@group(1) @binding(4) var second_layer_color: texture_2d<f32>;
@group(1) @binding(5) var second_layer_normal: texture_2d<f32>;
@group(1) @binding(6) var third_layer_color: texture_2d<f32>;
@group(1) @binding(7) var third_layer_normal: texture_2d<f32>;
@group(1) @binding(8) var fourth_layer_color: texture_2d<f32>;
@group(1) @binding(9) var fourth_layer_normal: texture_2d<f32>;
@group(1) @binding(10) var material_sampler: sampler;
// The height's maximum pyramid (derived by the core, bound for MaxMip; one texel of 1 otherwise).
@group(1) @binding(11) var height_pyramid: texture_2d<f32>;

// Where the view ray meets the height field, with what shading and depth need of the surface.
struct SurfacePoint {
    surface_frame: TangentFrame,
    to_eye: vec3<f32>,
    ddx_uv: vec2<f32>,
    ddy_uv: vec2<f32>,
    mip: f32,
    // Texture units per world unit (Luna §3).
    uv_per_world: f32,
    // The view ray in tangent space, its parallax offset vector P (the sideways travel over the
    // whole height range) and how much the surface's curvature bends it (`ray_bend`).
    to_eye_ts: vec3<f32>,
    offset: vec2<f32>,
    bend: f32,
    // The surface's curvature along the light rays is read from the same footprint.
    footprint: PixelFootprint,
    height_scale: f32,
    field: HeightField,
    mapping: FieldMapping,
    // 1 past the LOD threshold, 0 before its band.
    fade: f32,
    marched: bool,
    // The march's coordinate where the view ray enters: the mesh's texture coordinate, or under
    // triplanar mapping the origin of the tangent plane's (`TriplanarProjection`).
    entry_uv: vec2<f32>,
    // Where the view ray left the surface before it met the relief (the silhouette): the pixel
    // shows what lies behind.
    clipped: bool,
    uv: vec2<f32>,
    height: f32,
    samples: u32,
}

// Black → red → yellow → white as `t` goes 0 → 1.
fn heat(t: f32) -> vec3<f32> {
    let x = clamp(t, 0.0, 1.0) * 3.0;
    return clamp(vec3<f32>(x, x - 1.0, x - 2.0), vec3<f32>(0.0), vec3<f32>(1.0));
}

// The normal curvature of the surface along `direction` (a world direction in the tangent
// plane; 1 / world units, positive where the surface falls away from its tangent plane, as a
// sphere's outside does), from the pixel's footprint: the change of the interpolated normal
// against the change of position (the shape operator of the triangle's normal field; the
// forward path's derivatives may be a 2 × 2 quad's, the resolve's are the pixel's own). 0
// where the footprint is degenerate (a triangle seen edge-on).
fn normal_curvature(in: VertexOut, frame: TangentFrame, footprint: PixelFootprint, direction: vec3<f32>) -> f32 {
    // `direction` as a · ddx_world + b · ddy_world, solved in the tangent plane's coordinates
    // (a basis of the normal and the footprint alone: the texture's tangents degenerate where
    // its mapping pinches, at a sphere's poles).
    let first = along_plane(frame, footprint.ddx_world);
    let second = cross(frame.normal, first);
    let across = vec2<f32>(dot(footprint.ddx_world, first), dot(footprint.ddx_world, second));
    let down = vec2<f32>(dot(footprint.ddy_world, first), dot(footprint.ddy_world, second));
    let along = vec2<f32>(dot(direction, first), dot(direction, second));
    let determinant = across.x * down.y - down.x * across.y;
    let length_squared = dot(along, along);
    if abs(determinant) <= 1e-12 * max(dot(across, across) * dot(down, down), 1e-30) || length_squared < 1e-12 {
        return 0.0;
    }
    let a = (along.x * down.y - down.x * along.y) / determinant;
    let b = (across.x * along.y - along.x * across.y) / determinant;
    let normal_change = a * footprint.ddx_normal + b * footprint.ddy_normal;
    // The interpolated normal is about unit length; its change along the plane is what the
    // unit normal's is. Seen from the back the surface bends the other way.
    let facing = select(-1.0, 1.0, dot(in.world_normal, frame.normal) >= 0.0);
    return facing * dot(normal_change, direction)
        / (length_squared * max(length(in.world_normal), 1e-6));
}

// How much a ray through the relief bends (`linear_search`'s bend: its height rises by bend ·
// t² after the fraction t of `offset`, the sideways travel over the whole height range) where
// the surface curves by `curvature` (1 / world units) along it: the surface falls ½ k d² below
// its tangent plane at distance d. 0 without the curved silhouette.
fn ray_bend(curvature: f32, offset: vec2<f32>, point: SurfacePoint) -> f32 {
    // Without texture coordinates that change across the pixel (a mesh without UVs) there is
    // no texture space to bend in: straight, as off.
    if SILHOUETTE != SILHOUETTE_CURVED || point.uv_per_world <= 0.0 || point.height_scale <= 0.0 {
        return 0.0;
    }
    let curvature_texture = curvature / max(point.uv_per_world, 1e-30);
    return 0.5 * curvature_texture * dot(offset, offset) / max(point.height_scale, 1e-30);
}

// The world direction along the tangent plane of `v` (a unit vector away from the surface).
fn along_plane(frame: TangentFrame, v: vec3<f32>) -> vec3<f32> {
    return safe_normalize(v - frame.normal * dot(v, frame.normal), frame.tangent);
}

// Interleaved gradient noise (Jimenez 2014) at `pixel`, moved each frame by his step so that a
// pixel's values over 64 frames spread evenly over 0..1: the jittered march's start. Every
// pass of a pixel (prepass, visibility, forward, resolve) draws the same value.
fn march_noise(pixel: vec2<f32>) -> f32 {
    let p = floor(pixel) + 5.588238 * f32(frame.target_size.z % 64u);
    return fract(52.9829189 * fract(dot(p, vec2<f32>(0.06711056, 0.00583715))));
}

// The part of their spacing by which the soft shadow's samples move (`soft_shadow`): the
// march's noise, centred, under TAA, whose history averages it whether or not the march is
// jittered; 0 without TAA, where the noise would stay in the image as grain.
fn shadow_tap_shift(pixel: vec2<f32>) -> f32 {
    return select(0.0, march_noise(pixel) - 0.5, frame.target_size.w != 0u);
}

// The march: the same code for the prepass, which only needs the depth, and the shading.
fn find_surface(in: VertexOut, front_facing: bool, footprint: PixelFootprint) -> SurfacePoint {
    return march_surface(in, view_ray(in, front_facing, footprint));
}

// Everything the march needs to know of the pixel before it samples a height.
fn view_ray(in: VertexOut, front_facing: bool, footprint: PixelFootprint) -> SurfacePoint {
    let material = materials[in.object_index];
    let params = material.params;
    var point: SurfacePoint;
    point.surface_frame = facing_tangent_frame(in.world_normal, in.world_tangent, front_facing);
    point.footprint = footprint;
    point.entry_uv = in.uv;
    // Texture units per world unit (Luna §3), from the areas a pixel really covers in both spaces.
    let world_area = length(cross(footprint.ddx_world, footprint.ddy_world));
    let uv_area = abs(footprint.ddx_uv.x * footprint.ddy_uv.y - footprint.ddx_uv.y * footprint.ddy_uv.x);
    point.uv_per_world = sqrt(uv_area / max(world_area, 1e-30));
    if TRIPLANAR {
        // No texture coordinates or tangents of the mesh: the march moves in the tangent plane
        // of the normal, in texture units, from 0 where the ray enters.
        point.surface_frame = march_frame(point.surface_frame.normal, params.triplanar_sharpness);
        let scale = params.triplanar_scale;
        point.mapping.triplanar = triplanar_projection(in.world_position, point.surface_frame, scale,
            params.triplanar_sharpness);
        point.footprint.ddx_uv = to_tangent_space(point.surface_frame, footprint.ddx_world).xy / scale;
        point.footprint.ddy_uv = to_tangent_space(point.surface_frame, footprint.ddy_world).xy / scale;
        point.entry_uv = vec2<f32>(0.0);
        point.uv_per_world = 1.0 / scale;
    }
    point.to_eye = direction_to_eye(in.world_position, point.surface_frame.normal);
    point.to_eye_ts = to_tangent_space(point.surface_frame, point.to_eye);

    // The gradients every texture read and level of the march take: finer under anti-aliasing.
    point.ddx_uv = point.footprint.ddx_uv * texture_gradient_scale();
    point.ddy_uv = point.footprint.ddy_uv * texture_gradient_scale();
    let texture_size = vec2<f32>(material.height_texture_width, material.height_texture_height);
    point.mip = mip_level(point.ddx_uv * texture_size, point.ddy_uv * texture_size);
    let scale = select(0.0, params.height_scale, material.has_height_map != 0u);
    point.height_scale = select(scale, scale * point.uv_per_world, params.height_units == UNITS_WORLD);

    point.field = HeightField(HEIGHT_CHANNEL, u32(HEIGHT_IS_DEPTH),
        sampler_level(point.ddx_uv * texture_size, point.ddy_uv * texture_size),
        // Triplanar projections have no bounds to leave: uv_bounds draws as off.
        u32(SILHOUETTE == SILHOUETTE_UV_BOUNDS && !TRIPLANAR),
        vec4<f32>(params.bounds_u_min, params.bounds_v_min, params.bounds_u_max, params.bounds_v_max),
        select(0.0, march_noise(in.clip_position.xy), params.jitter_march != 0u));
    point.mapping.layers = layer_blend(material, in.color, point.ddx_uv, point.ddy_uv);
    point.fade = select(lod_fade(point.mip, params.lod_threshold, params.lod_band), 0.0, SHADOW_CASTER);
    // Past the LOD threshold (fade 1) nothing below runs but normal mapping.
    point.marched = point.fade < 1.0 && METHOD != METHOD_NORMAL_MAPPING && point.height_scale > 0.0;

    point.uv = point.entry_uv;
    point.height = 1.0;
    point.samples = 0u;
    point.clipped = false;
    point.offset = -ray_offset(point.to_eye_ts, point.height_scale);
    let curvature = normal_curvature(in, point.surface_frame, point.footprint, along_plane(point.surface_frame, -point.to_eye));
    // Only a ray march bends (parallax offset takes one sample, normal mapping none).
    let marches_a_ray = METHOD != METHOD_PARALLAX_OFFSET && METHOD != METHOD_NORMAL_MAPPING;
    point.bend = select(0.0, ray_bend(curvature, point.offset, point), marches_a_ray);
    return point;
}

// A layered material's layers as the march reads them, for a pixel whose texture coordinate
// moves by `ddx_uv` and `ddy_uv` and whose vertex colour is `vertex_color` (the weights where
// there is no weight map). Unused by other materials.
fn layer_blend(material: PomUniform, vertex_color: vec4<f32>, ddx_uv: vec2<f32>, ddy_uv: vec2<f32>) -> LayerBlend {
    var blend: LayerBlend;
    if LAYERED {
        let tiling = material.layer_tiling;
        let present = select(vec4<f32>(0.0), vec4<f32>(1.0), vec4<u32>(0u, 1u, 2u, 3u) < vec4<u32>(material.layer_count));
        let weight_size = vec2<f32>(material.weight_texture_width, material.weight_texture_height);
        let contrast = clamp(material.params.layer_blend_contrast, 0.0, 0.99);
        blend.tiling = tiling;
        blend.level_offset = log2(tiling / tiling.x);
        blend.depth = material.layer_depth;
        blend.present = present;
        blend.entry_weights = vertex_color;
        blend.sharpness = contrast / (1.0 - contrast);
        blend.weights_from_texture = material.weights_from_texture;
        blend.weight_level = sampler_level(ddx_uv * weight_size, ddy_uv * weight_size);
        blend.weight_inset = 0.5 / weight_size;
        blend.shared_tiling = u32(all(select(tiling, vec4<f32>(tiling.x), present == vec4<f32>(0.0)) == vec4<f32>(tiling.x)));
    }
    return blend;
}

// The visible point's colour (texture × factor × vertex colour, as glTF multiplies them) and
// shading normal (world): a layered material's layers' mixed by their shares there, or the
// triplanar projections'.
struct SurfaceMaps {
    base: vec4<f32>,
    normal: vec3<f32>,
}

fn surface_maps(in: VertexOut, point: SurfacePoint) -> SurfaceMaps {
    let params = materials[in.object_index].params;
    let factor = rgba(params.base_color);
    let frame = point.surface_frame;
    if TRIPLANAR {
        let maps = triplanar_maps(base_color_texture, normal_map, material_sampler, point.mapping.triplanar,
            frame.normal, point.uv, point.ddx_uv, point.ddy_uv, params.normal_strength);
        return SurfaceMaps(maps.color * factor * in.color, maps.normal);
    }
    if !LAYERED {
        return SurfaceMaps(
            textureSampleGrad(base_color_texture, material_sampler, point.uv, point.ddx_uv, point.ddy_uv) * factor * in.color,
            perturbed_normal(frame, textureSampleGrad(normal_map, material_sampler, point.uv, point.ddx_uv, point.ddy_uv).xyz,
                params.normal_strength));
    }
    let blend = point.mapping.layers;
    let heights = layer_heights(height_texture, material_sampler, blend, point.uv, point.field.level);
    let weights = layer_weights(layer_weights_texture, material_sampler, blend, point.uv);
    let shares = layer_shares(heights, weights, blend.sharpness);
    var mix = LayerMix(vec4<f32>(0.0), vec3<f32>(0.0));
    mix = with_layer(mix, base_color_texture, normal_map, shares.x, blend.tiling.x, point);
    mix = with_layer(mix, second_layer_color, second_layer_normal, shares.y, blend.tiling.y, point);
    mix = with_layer(mix, third_layer_color, third_layer_normal, shares.z, blend.tiling.z, point);
    mix = with_layer(mix, fourth_layer_color, fourth_layer_normal, shares.w, blend.tiling.w, point);
    // Vertex colours that are not the weights tint the mix, as they tint one layer.
    let tint = select(vec4<f32>(1.0), in.color, blend.weights_from_texture != 0u);
    return SurfaceMaps(mix.base * factor * tint, perturbed_normal(frame, mix.encoded_normal, params.normal_strength));
}

// Layers' colours and encoded normals, each times its share.
struct LayerMix {
    base: vec4<f32>,
    encoded_normal: vec3<f32>,
}

// `mix` plus `share` of one layer's colour and encoded normal at the visible point (its maps
// tiled `tiling` times); nothing is read for a layer without a share there.
fn with_layer(mix: LayerMix, color: texture_2d<f32>, normal: texture_2d<f32>, share: f32, tiling: f32,
    point: SurfacePoint) -> LayerMix {
    if share <= 0.0 {
        return mix;
    }
    let uv = point.uv * tiling;
    let ddx_uv = point.ddx_uv * tiling;
    let ddy_uv = point.ddy_uv * tiling;
    return LayerMix(mix.base + share * textureSampleGrad(color, material_sampler, uv, ddx_uv, ddy_uv),
        mix.encoded_normal + share * textureSampleGrad(normal, material_sampler, uv, ddx_uv, ddy_uv).xyz);
}

// The texture coordinate the uv debug view shows: the mesh's, or under triplanar mapping the
// one of the projection with the largest share.
fn shown_uv(point: SurfacePoint) -> vec2<f32> {
    if !TRIPLANAR {
        return point.uv;
    }
    let projection = point.mapping.triplanar;
    return projection_uv(projected_point(projection, point.uv), projection.sides, dominant_axis(projection.weights));
}

// Whether the view ray of `point` could leave the surface before it meets the relief: only
// then must a pass that needs no more than coverage march. A straight ray stays on the segment
// from where it enters to its parallax offset, so under uv_bounds it can leave only where that
// segment crosses a bound; a bent one only where it is bent up by more than ¼ (`bent_span`).
fn may_leave_surface(in: VertexOut, point: SurfacePoint) -> bool {
    if !point.marched {
        return false;
    }
    if point.field.bounded != 0u {
        // A hair inside the bounds, so a refinement that rounds past the segment's end still
        // finds the march run here too.
        var inner = point.field;
        inner.bounds += vec4<f32>(1e-5, 1e-5, -1e-5, -1e-5);
        return !inside_bounds(inner, point.entry_uv) || !inside_bounds(inner, point.entry_uv + point.offset);
    }
    return SILHOUETTE == SILHOUETTE_CURVED && point.bend > 0.25;
}

// `point` (from `view_ray`) with the visible point the march finds.
fn march_surface(in: VertexOut, ray: SurfacePoint) -> SurfacePoint {
    var point = ray;
    if point.marched {
        let params = materials[in.object_index].params;
        let texture_size = vec2<f32>(materials[in.object_index].height_texture_width,
            materials[in.object_index].height_texture_height);
        let offset = point.offset;
        let bend = point.bend;
        let texels = length(offset * texture_size) / exp2(point.mip) * bent_span(bend);
        let steps = march_steps(params.min_samples, params.max_samples, dot(point.surface_frame.normal, point.to_eye), texels);
        let refinement_steps = select(params.secant_steps, params.relief_binary_steps, METHOD == METHOD_RELIEF);
        let hit = march_view(height_texture, layer_weights_texture, material_sampler, height_pyramid, point.field, point.mapping, METHOD, point.entry_uv, offset,
            point.to_eye_ts, point.height_scale, steps, refinement_steps, bend);
        // The bent ray's height is over the curved surface; the point lies on the straight view
        // ray, t of its way down below the tangent plane (bend is 0 but for a ray march).
        let t = length(hit.uv - point.entry_uv) / max(length(offset), 1e-30);
        // In the LOD band, fade from the parallax coordinate to the plain one (T §5.4.3).
        point.uv = mix(hit.uv, point.entry_uv, point.fade);
        point.height = mix(hit.height - bend * t * t, 1.0, point.fade);
        point.samples = hit.samples;
        // Through the LOD band too (the plain coordinate is on the polygon): the outline stays.
        point.clipped = !hit.met || (point.field.bounded != 0u && !inside_bounds(point.field, hit.uv));
    }
    return point;
}

// The world position of the visible point: it lies (1 − height) × H below the polygon, offset
// sideways by the change of texture coordinate.
fn displaced_position(in: VertexOut, point: SurfacePoint) -> vec3<f32> {
    let frame_ts = point.surface_frame;
    let du = (point.uv - point.entry_uv) / max(point.uv_per_world, 1e-30);
    let depth_below = (1.0 - point.height) * point.height_scale / max(point.uv_per_world, 1e-30);
    let displaced = in.world_position + frame_ts.tangent * du.x + frame_ts.bitangent_v * du.y
        - frame_ts.normal * depth_below;
    return select(in.world_position, displaced, point.uv_per_world > 0.0);
}

// The depth (clip space, 0..1) of the visible point.
fn displaced_depth(in: VertexOut, point: SurfacePoint) -> f32 {
    let clip = frame.view_projection * vec4<f32>(displaced_position(in, point), 1.0);
    // Never in front of the polygon: the relief lies below it. Where the march found the top
    // (or did not run) the point is the polygon's own, and projecting the interpolated world
    // position can come out a rounding error nearer than the rasterized depth; the opaque
    // phase's early test (rasterized depth ≤ prepass depth) would then drop the pixel.
    return max(clamp(clip.z / max(clip.w, 1e-30), 0.0, 1.0), in.clip_position.z);
}

// How much of the environment's diffuse (x) and specular (y) light reaches the visible point
// past the relief (`relief_occlusion`, searched out to four times the height range), faded
// with the march past the LOD threshold; 1 without an environment (the ambient term is left
// as it was) or where the march did not run.
fn environment_occlusion(in: VertexOut, point: SurfacePoint, surface: Surface, normal: vec3<f32>) -> vec2<f32> {
    let strength = materials[in.object_index].params.relief_occlusion * (1.0 - point.fade);
    if !has_environment() || !point.marched || strength <= 0.0 {
        return vec2<f32>(1.0);
    }
    let material = materials[in.object_index];
    let texels = max(material.height_texture_width, material.height_texture_height);
    let open = relief_occlusion(height_texture, layer_weights_texture, material_sampler, point.field, point.mapping, point.uv, point.height,
        point.height_scale, 4.0 * point.height_scale, texels, shadow_tap_shift(in.clip_position.xy) + 0.5);
    let diffuse = mix(1.0, open, strength);
    return vec2<f32>(diffuse, specular_occlusion(dot(normal, point.to_eye), diffuse, surface.roughness));
}

fn shade(in: VertexOut, point: SurfacePoint) -> vec4<f32> {
    let material = materials[in.object_index];
    let params = material.params;
    let surface_frame = point.surface_frame;
    let uv = point.uv;
    let fade = point.fade;
    let texture_size = vec2<f32>(material.height_texture_width, material.height_texture_height);

    let maps = surface_maps(in, point);
    let base = maps.base;
    let normal = maps.normal;
    let surface = Surface(base.rgb, params.specular_strength, max(params.shininess, 1.0), params.roughness,
        params.metallic, LIGHTING_MODEL);

    var color = ambient_lighting(surface, normal, point.to_eye, environment_occlusion(in, point, surface, normal));
    var first_visibility = 1.0;
    var first_scene_visibility = 1.0;
    // Scene shadows are looked up where the march found the surface, not on the polygon.
    let receives_shadows = receives_scene_shadows(in.object_index);
    let surface_position = displaced_position(in, point);
    let lights = lights_near(in.world_position);
    // The relief's own shadows for the brightest few lights here; the rest light the
    // displaced point unshadowed by it (scene shadows still apply).
    let shadowed_from = brightest_lights_floor(lights, in.world_position, params.shadowed_lights);
    for (var k = 0u; k < lights.count; k += 1u) {
        let i = light_in(lights, k);
        let light = light_at(i, in.world_position);
        var visibility = 1.0;
        let brightness = light_brightness(light.radiance);
        let self_shadowed = brightness >= shadowed_from && brightness > 0.0;
        // Shadow rays only where the light faces the polygon (T §5.4.2) and the march ran.
        if point.marched && SHADOW_MODE != SHADOWS_OFF && self_shadowed && dot(surface_frame.normal, light.to_light) > 0.0 {
            let to_light_ts = to_tangent_space(surface_frame, light.to_light);
            let light_offset = ray_offset(to_light_ts, point.height_scale);
            let light_bend = ray_bend(normal_curvature(in, surface_frame, point.footprint,
                along_plane(surface_frame, light.to_light)), light_offset, point);
            if SHADOW_MODE == SHADOWS_SOFT {
                visibility = soft_shadow(height_texture, layer_weights_texture, material_sampler, point.field, point.mapping, uv, light_offset, params.shadow_softening,
                    light_bend, shadow_tap_shift(in.clip_position.xy));
            } else {
                let texels_per_rise = length(light_offset * texture_size) / exp2(point.mip);
                visibility = hard_shadow(height_texture, layer_weights_texture, material_sampler, height_pyramid, point.field, point.mapping, METHOD, uv,
                    light_offset, params.min_samples, params.max_samples, dot(surface_frame.normal, light.to_light),
                    texels_per_rise, light_bend);
            }
            visibility = mix(visibility, 1.0, fade);
        }
        var scene_visibility = 1.0;
        if receives_shadows && dot(surface_frame.normal, light.to_light) > 0.0 {
            // The bias follows the relief's own surface (the shading normal): on a groove's
            // wall the polygon's normal would leave the point inside its own depths.
            scene_visibility = scene_shadow(i, surface_position, normal);
        }
        if i == 0u {
            first_visibility = visibility;
            first_scene_visibility = scene_visibility;
        }
        // The shadow map holds the relief too, so where both see the same occluder they agree:
        // the darker of the two, never their product, so no point is darkened twice.
        color += light.radiance * min(visibility, scene_visibility)
            * direct_lighting(surface, normal, light.to_light, point.to_eye);
    }

    // Data views carry DEBUG_VIEW_ALPHA (generated): post-processing writes them as they are.
    switch DEBUG_VIEW {
        case DEBUG_LOD: {
            // T's tint: blue grows through the band; deepest blue where only normal mapping runs.
            let tint = select(max(1.0, 2.0 * fade), 3.0, fade >= 1.0);
            return vec4<f32>(color * vec3<f32>(1.0, 1.0, tint), base.a);
        }
        case DEBUG_MIP: {
            return vec4<f32>(vec3<f32>(point.mip / max(material.height_mip_levels - 1.0, 1.0)), DEBUG_VIEW_ALPHA);
        }
        case DEBUG_SAMPLES: {
            return vec4<f32>(heat(f32(point.samples) / max(f32(params.max_samples), 1.0)), DEBUG_VIEW_ALPHA);
        }
        case DEBUG_UV: {
            let region = select(select(0.5, 1.0, fade <= 0.0), 0.0, !point.marched);
            return vec4<f32>(fract(shown_uv(point)), region, DEBUG_VIEW_ALPHA);
        }
        case DEBUG_SHADOW: {
            return vec4<f32>(vec3<f32>(first_visibility), DEBUG_VIEW_ALPHA);
        }
        case DEBUG_SCENE_SHADOW: {
            return vec4<f32>(vec3<f32>(first_scene_visibility), DEBUG_VIEW_ALPHA);
        }
        case DEBUG_NORMAL: {
            return vec4<f32>(to_tangent_space(surface_frame, normal) * 0.5 + 0.5, DEBUG_VIEW_ALPHA);
        }
        default: {
            return vec4<f32>(color, base.a);
        }
    }
}

// Without depth offset, in both the opaque phase and a frame without prepass. The early test is
// forced: the shader writes no depth and never discards, so this is what drivers do anyway,
// and it stays so when a test counts invocations (an atomic is a side effect).
@fragment @early_depth_test(force)
fn fs_main(in: VertexOut, @builtin(front_facing) front_facing: bool) -> @location(0) vec4<f32> {
    count_fragment_invocation();
    return shade(in, find_surface(in, front_facing, fragment_footprint(in)));
}

struct ColorAndDepth {
    @location(0) color: vec4<f32>,
    @builtin(frag_depth) depth: f32,
}

// The depth the passes that march for it write: the displaced point's with depth offset, else
// the polygon's (a silhouette that only clips).
fn marched_depth(in: VertexOut, point: SurfacePoint) -> f32 {
    if DEPTH_OFFSET {
        return displaced_depth(in, point);
    }
    return in.clip_position.z;
}

// `depth_offset` or a silhouette without a prepass: the depth buffer gets the displaced point
// (so other geometry meets the relief where it really is), and pixels the view ray left the
// surface at show what lies behind. The depth only ever moves away from the eye
// (`displaced_depth`), which lets the GPU reject fragments behind nearer geometry before they
// march.
@fragment @early_depth_test(greater_equal)
fn fs_main_marched_depth(in: VertexOut, @builtin(front_facing) front_facing: bool) -> ColorAndDepth {
    count_fragment_invocation();
    let point = find_surface(in, front_facing, fragment_footprint(in));
    if point.clipped {
        discard;
    }
    return ColorAndDepth(shade(in, point), marched_depth(in, point));
}

// `depth_offset` (with or without a silhouette) in the prepass, and every parallax caster in a
// shadow map (where the "eye" is the light, so the march follows the light's view ray and a
// clipped outline casts a clipped shadow): only the march, the coverage and the depth (pushed
// away from the eye only, as above).
@fragment @early_depth_test(greater_equal)
fn fs_prepass_marched_depth(in: VertexOut, @builtin(front_facing) front_facing: bool) -> @builtin(frag_depth) f32 {
    let point = covering_surface(in, view_ray(in, front_facing, fragment_footprint(in)));
    if point.clipped {
        discard;
    }
    return marched_depth(in, point);
}

// A silhouette without depth offset in the prepass: coverage alone. The depth is the polygon's,
// which the rasterizer writes itself: a shader that exports its depth costs the raster units
// their early test.
@fragment
fn fs_prepass_clipped(in: VertexOut, @builtin(front_facing) front_facing: bool) {
    if covering_surface(in, view_ray(in, front_facing, fragment_footprint(in))).clipped {
        discard;
    }
}

// What the depth passes need of `ray`: with depth offset the march; for a silhouette alone the
// march only where the ray could leave the surface (`may_leave_surface`), the polygon elsewhere
// (on a crate's face seen at 45°, a band a twentieth of the face wide marches).
fn covering_surface(in: VertexOut, ray: SurfacePoint) -> SurfacePoint {
    if DEPTH_OFFSET || may_leave_surface(in, ray) {
        return march_surface(in, ray);
    }
    return ray;
}

// `depth_offset` or a silhouette in the opaque phase after the prepass. The hardware test
// (rasterized depth ≤ prepass depth, forced early) drops fragments hidden behind nearer
// geometry before they march; the point then recomputes its depth with the same code as the
// prepass and shades only where that is the depth the prepass kept (bit for bit, as
// tests/tests/render_phases.rs checks), which a clipped pixel never is.
@fragment @early_depth_test(force)
fn fs_main_after_marched_prepass(in: VertexOut, @builtin(front_facing) front_facing: bool) -> @location(0) vec4<f32> {
    count_fragment_invocation();
    let point = find_surface(in, front_facing, fragment_footprint(in));
    let depth = marched_depth(in, point);
    let kept = textureLoad(prepass_depth, vec2<i32>(in.clip_position.xy), 0);
    if point.clipped || depth > kept {
        discard;
    }
    return shade(in, point);
}
