// The visibility pass, the deferred path's prepass: with its depth, each pixel keeps which draw
// and which triangle it shows. Composed after a material's files (with `enable primitive_index;`)
// where the adapter can run the deferred path.

// The material's tag (its place among the app's materials, from 1), set on each of its
// pipelines: 0 marks a pixel no opaque draw covers (the pass clears to it).
override VISIBILITY_TAG: u32 = 0u;
// The low bits of an id's first word hold the draw's index in its material's per-draw arrays,
// the high ones the tag.
const VISIBILITY_OBJECT_BITS: u32 = 24u;
const VISIBILITY_OBJECT_MASK: u32 = 0xffffffu;

// The id a pixel of draw `object_index`, triangle `triangle`, keeps.
fn visibility_id(object_index: u32, triangle: u32) -> vec2<u32> {
    return vec2<u32>((VISIBILITY_TAG << VISIBILITY_OBJECT_BITS) | (object_index & VISIBILITY_OBJECT_MASK), triangle);
}

// The visibility pass of a material whose prepass has no fragment stage of its own. No depth
// written and no side effects: the depth test runs before it.
@fragment @early_depth_test(force)
fn fs_visibility(in: VertexOut, @builtin(primitive_index) triangle: u32) -> @location(0) vec2<u32> {
    return visibility_id(in.object_index, triangle);
}
