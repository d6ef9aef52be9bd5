// Clears the visibility keys to 0 ("no draw") before the visibility pass. A compute pass rather
// than an encoder clear_buffer, so that the prepass's timestamps begin before it (timing an
// encoder command needs TIMESTAMP_QUERY_INSIDE_ENCODERS): the visibility phase's figure holds
// its clear.

@group(0) @binding(0) var<storage, read_write> cleared_keys: array<vec2<u32>>;

const CLEAR_GROUP_SIZE: u32 = 256u;

@compute @workgroup_size(CLEAR_GROUP_SIZE)
fn cs_clear_visibility(@builtin(global_invocation_id) id: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>) {
    // Rows of workgroups: a 1-D dispatch holds at most 65535 groups, 16.7 M keys.
    let index = id.x + id.y * groups.x * CLEAR_GROUP_SIZE;
    if index < arrayLength(&cleared_keys) {
        cleared_keys[index] = vec2<u32>(0u);
    }
}
