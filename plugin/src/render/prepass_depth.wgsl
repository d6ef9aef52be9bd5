// The depth the prepass wrote, for materials whose fragments move their depth (parallax depth
// offset): in the opaque phase they compare their own depth with it (a dummy 1 × 1 texture is
// bound in the prepass itself and when there is no prepass).
@group(0) @binding(3) var prepass_depth: texture_depth_2d;
