// Tile classification for the deferred resolve: for each 8 × 8 tile of the visibility buffer,
// which of a material's resolve batches show in it, by each pixel's visibility key and its
// candidate key (a candidate may win or lose when settled: both batches list the tile). Each batch gets the list of its tiles and
// an indirect dispatch of one workgroup per tile, so a batch's resolve runs only where it is
// seen. Mirrors `ClassifyParams` in material/resolve_tiles.rs (the layout test checks them).

struct ClassifyParams {
    width: u32,
    height: u32,
    tiles_across: u32,
    tile_count: u32,
    batch_count: u32,
    _padding_a: u32,
    _padding_b: vec2<u32>,
}

@group(0) @binding(0) var<uniform> params: ClassifyParams;
// The visibility keys then the candidate keys (visibility_read.wgsl), before any resolve
// settles a candidate.
@group(0) @binding(1) var<storage, read> visibility: array<vec2<u32>>;
// Each batch's visibility ids, first..end, in increasing order.
@group(0) @binding(2) var<storage, read> batch_ids: array<vec2<u32>>;
// Per batch: how many tiles it shows in (zeroed by cs_clear_counts first each frame).
@group(0) @binding(3) var<storage, read_write> tile_counts: array<atomic<u32>>;
// Per batch, `tile_count` slots: the tiles it shows in (y × tiles_across + x).
@group(0) @binding(4) var<storage, read_write> batch_tiles: array<u32>;
// Per batch, the workgroup counts (x, y, z) of its indirect dispatch.
@group(0) @binding(5) var<storage, read_write> dispatch_args: array<u32>;

const NO_BATCH: u32 = 0xffffffffu;

// Per lane, the batch of its visibility key then the batch of its candidate key.
var<workgroup> lane_batches: array<u32, 2u * TILE_SIDE * TILE_SIDE>;

// The batch whose ids hold `id` (binary search), or NO_BATCH.
fn batch_of(id: u32) -> u32 {
    var low = 0u;
    var high = params.batch_count;
    while low < high {
        let middle = (low + high) / 2u;
        if id < batch_ids[middle].x {
            high = middle;
        } else if id >= batch_ids[middle].y {
            low = middle + 1u;
        } else {
            return middle;
        }
    }
    return NO_BATCH;
}

// One invocation per batch: its tile count back to 0, before the frame's classification.
@compute @workgroup_size(64)
fn cs_clear_counts(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x < params.batch_count {
        atomicStore(&tile_counts[id.x], 0u);
    }
}

// One workgroup per tile: the first lane that shows a batch lists the tile for it.
@compute @workgroup_size(TILE_SIDE, TILE_SIDE)
fn cs_classify(@builtin(workgroup_id) tile: vec3<u32>, @builtin(local_invocation_id) local: vec3<u32>,
    @builtin(local_invocation_index) lane: u32) {
    let pixel = tile.xy * TILE_SIDE + local.xy;
    var batch = NO_BATCH;
    var candidate = NO_BATCH;
    if pixel.x < params.width && pixel.y < params.height {
        batch = batch_of(visible_id(pixel, params.width));
        let candidate_id = visibility[candidate_index(pixel, vec2<u32>(params.width, params.height))].x;
        if candidate_id != 0u {
            candidate = batch_of(candidate_id);
        }
    }
    lane_batches[2u * lane] = batch;
    lane_batches[2u * lane + 1u] = candidate;
    workgroupBarrier();
    list_tile(tile.xy, 2u * lane, batch);
    list_tile(tile.xy, 2u * lane + 1u, candidate);
}

// Lists `tile` for `batch`, seen at `place` in the lanes' batches, unless an earlier place
// shows it too.
fn list_tile(tile: vec2<u32>, place: u32, batch: u32) {
    if batch == NO_BATCH {
        return;
    }
    for (var other = 0u; other < place; other += 1u) {
        if lane_batches[other] == batch {
            return;
        }
    }
    let slot = atomicAdd(&tile_counts[batch], 1u);
    batch_tiles[batch * params.tile_count + slot] = tile.y * params.tiles_across + tile.x;
}

// One invocation per batch: its tile count as an indirect dispatch, TILES_PER_ROW tiles a row
// (generated: shaders::deferred_header).
@compute @workgroup_size(64)
fn cs_dispatch_args(@builtin(global_invocation_id) id: vec3<u32>) {
    let batch = id.x;
    if batch >= params.batch_count {
        return;
    }
    let tiles = atomicLoad(&tile_counts[batch]);
    dispatch_args[batch * 3u] = min(tiles, TILES_PER_ROW);
    dispatch_args[batch * 3u + 1u] = (tiles + TILES_PER_ROW - 1u) / TILES_PER_ROW;
    dispatch_args[batch * 3u + 2u] = 1u;
}
