// Writes packed entries into their slots of a per-draw buffer: the entries that changed arrive
// in one upload, however scattered their slots, and one dispatch puts each in place.

struct Packed {
    count: u32,
    words_per_entry: u32,
    // `count` slot indices, then the entries, `words_per_entry` words each.
    data: array<u32>,
}

@group(0) @binding(0) var<storage, read> packed: Packed;
@group(0) @binding(1) var<storage, read_write> entries: array<u32>;

const GROUP_SIZE: u32 = 64u;

@compute @workgroup_size(64)
fn cs_scatter(
    @builtin(global_invocation_id) id: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
) {
    // Rows of groups: one row holds at most the device's limit of groups along x.
    let word = id.x + id.y * groups.x * GROUP_SIZE;
    let per_entry = packed.words_per_entry;
    if word >= packed.count * per_entry {
        return;
    }
    let entry = word / per_entry;
    entries[packed.data[entry] * per_entry + word % per_entry] = packed.data[packed.count + word];
}
