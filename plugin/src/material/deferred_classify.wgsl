// Tile classification for the deferred resolve: for each 8 × 8 tile of the visibility buffer,
// which of a material's resolve batches show in it, by each pixel's visibility key and its
// candidate key (a candidate may win or lose when settled: both batches list the tile). Each
// batch gets the list of its tiles, row by row, and an indirect dispatch of one workgroup per
// tile, so a batch's resolve runs only where it is seen. A tile is first listed in its row's
// list (one counter per batch and tile row: a single counter per batch, taken by every tile of
// the target, serializes the GPU's atomics), then the rows are joined. Where neither key holds
// a draw the classification writes the background, so the frame needs no pass of its own for
// it. Mirrors `ClassifyParams` in material/resolve_tiles.rs (the layout test checks them).

struct ClassifyParams {
    width: u32,
    height: u32,
    tiles_across: u32,
    tile_count: u32,
    batch_count: u32,
    tiles_down: u32,
    _padding: vec2<u32>,
    // The clear colour as the opaque pass would have cleared to (alpha marks it
    // display-referred).
    background: vec4<f32>,
}

@group(0) @binding(0) var<uniform> params: ClassifyParams;
// The visibility keys then the candidate keys (visibility_read.wgsl), before this material's
// resolves settle its candidates.
@group(0) @binding(1) var<storage, read> visibility: array<vec2<u32>>;
// Each batch's visibility ids, first..end, in increasing order.
@group(0) @binding(2) var<storage, read> batch_ids: array<vec2<u32>>;
// Per batch: how many tiles it shows in (written by cs_join_rows).
@group(0) @binding(3) var<storage, read_write> tile_counts: array<u32>;
// Per batch, `tile_count` slots: the tiles it shows in (y × tiles_across + x), row by row.
@group(0) @binding(4) var<storage, read_write> batch_tiles: array<u32>;
// Per batch, the workgroup counts (x, y, z) of its indirect dispatch.
@group(0) @binding(5) var<storage, read_write> dispatch_args: array<u32>;
// Per batch and tile row: how many of the row's tiles it shows in (zeroed by cs_clear_counts
// first each frame).
@group(0) @binding(6) var<storage, read_write> row_counts: array<atomic<u32>>;
// Per batch, `tile_count` slots, `tiles_across` a row: each row's tiles (their x) as listed.
@group(0) @binding(7) var<storage, read_write> row_tiles: array<u32>;
// `SceneOutput` is generated: the target's HDR scene format as a write-only storage texture.
@group(0) @binding(8) var scene_output: SceneOutput;

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

// One invocation per batch and tile row: its count back to 0, before the frame's
// classification.
@compute @workgroup_size(64)
fn cs_clear_counts(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x < params.batch_count * params.tiles_down {
        atomicStore(&row_counts[id.x], 0u);
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
        let visible = visible_id(pixel, params.width);
        let candidate_id = visibility[candidate_index(pixel, vec2<u32>(params.width, params.height))].x;
        if visible == 0u && candidate_id == 0u {
            textureStore(scene_output, pixel, params.background);
        }
        batch = batch_of(visible);
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
    let row = batch * params.tiles_down + tile.y;
    let slot = atomicAdd(&row_counts[row], 1u);
    row_tiles[batch * params.tile_count + tile.y * params.tiles_across + slot] = tile.x;
}

// Lanes of cs_join_rows; each sums a run of consecutive rows.
const JOIN_LANES: u32 = 64u;

// Per lane, the tiles of its run of rows, then (after the scan) of the runs before it.
var<workgroup> run_tiles: array<u32, JOIN_LANES>;

// The rows lane `lane` of cs_join_rows sums: first..end.
fn lane_rows(lane: u32) -> vec2<u32> {
    let run = (params.tiles_down + JOIN_LANES - 1u) / JOIN_LANES;
    return vec2<u32>(min(lane * run, params.tiles_down), min((lane + 1u) * run, params.tiles_down));
}

// One workgroup per batch: where each of its rows starts in its joined list (an exclusive
// scan of the row counts, kept in the counts' place), its tile count, and its indirect
// dispatch, TILES_PER_ROW tiles a row (generated: shaders::deferred_header).
@compute @workgroup_size(JOIN_LANES)
fn cs_join_rows(@builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_index) lane: u32) {
    let batch = group.x;
    let rows = lane_rows(lane);
    var sum = 0u;
    for (var row = rows.x; row < rows.y; row += 1u) {
        sum += atomicLoad(&row_counts[batch * params.tiles_down + row]);
    }
    run_tiles[lane] = sum;
    workgroupBarrier();
    // Inclusive scan of the runs (Hillis-Steele).
    for (var step = 1u; step < JOIN_LANES; step *= 2u) {
        var before = 0u;
        if lane >= step {
            before = run_tiles[lane - step];
        }
        workgroupBarrier();
        run_tiles[lane] += before;
        workgroupBarrier();
    }
    var start = run_tiles[lane] - sum;
    for (var row = rows.x; row < rows.y; row += 1u) {
        let index = batch * params.tiles_down + row;
        let count = atomicLoad(&row_counts[index]);
        atomicStore(&row_counts[index], start);
        start += count;
    }
    if lane == JOIN_LANES - 1u {
        let tiles = run_tiles[lane];
        tile_counts[batch] = tiles;
        dispatch_args[batch * 3u] = min(tiles, TILES_PER_ROW);
        dispatch_args[batch * 3u + 1u] = (tiles + TILES_PER_ROW - 1u) / TILES_PER_ROW;
        dispatch_args[batch * 3u + 2u] = 1u;
    }
}

// One workgroup per tile row and batch: the row's tiles copied to their place in the batch's
// joined list (the row's start, cs_join_rows). The count is the start of the next row, or the
// batch's tile count after its last row.
@compute @workgroup_size(JOIN_LANES)
fn cs_copy_rows(@builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_index) lane: u32) {
    let row = group.x;
    let batch = group.y;
    let index = batch * params.tiles_down + row;
    let start = atomicLoad(&row_counts[index]);
    var end = tile_counts[batch];
    if row + 1u < params.tiles_down {
        end = atomicLoad(&row_counts[index + 1u]);
    }
    let source = batch * params.tile_count + row * params.tiles_across;
    let destination = batch * params.tile_count + start;
    for (var k = lane; k < end - start; k += JOIN_LANES) {
        batch_tiles[destination + k] = row * params.tiles_across + row_tiles[source + k];
    }
}
