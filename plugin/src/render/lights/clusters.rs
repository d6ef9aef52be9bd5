//! Light culling into clusters: the image is cut into square tiles of [`TILE_PIXELS`] and the
//! view depth, from the camera's near plane to the farthest light's reach, into
//! [`DEPTH_SLICES`] slices (of equal ratio for a perspective camera, whose pixels grow with
//! the distance, of equal depth for an orthographic one). Each cluster lists every light whose
//! sphere of influence (its range) overlaps the cluster's tile rectangle and depth range: a
//! conservative list, since `light_at` cuts each light off at its range and cone exactly.
//! Done on the CPU in two passes over the lights (count, then fill), so each cluster's list
//! comes out in the lights' order; lights.wgsl's `light_cluster` finds a point's cluster the
//! same way.

use glam::{Mat4, Vec3, Vec4Swizzles};

use crate::render::extract::LIGHT_CLUSTER_HEADER;
use crate::render::gpu_types::PointLightGpu;
use crate::{Camera, GlobalTransform, Projection};

/// Pixels along each side of a cluster's tile.
const TILE_PIXELS: u32 = 128;
/// The most tiles along each side of the image (wider images get wider tiles).
const MAX_TILES: u32 = 32;
/// Slices of the view depth.
const DEPTH_SLICES: u32 = 24;
/// The most light entries the clusters' lists may hold (16 MB): past it the grid is made
/// coarser until they fit, so that no light is ever dropped for the lists' size.
const MAX_ENTRIES: usize = 1 << 22;

/// The inclusive range of clusters a light reaches along each axis of the grid.
#[derive(Clone, Copy, Debug, PartialEq)]
struct ClusterBox {
    x: (u32, u32),
    y: (u32, u32),
    z: (u32, u32),
}

/// The camera as the culling sees it.
struct ClusterView {
    view: Mat4,
    projection: Mat4,
    perspective: bool,
    near: f32,
    far: f32,
}

impl ClusterView {
    fn new(camera: &Camera, transform: &GlobalTransform, aspect: f32) -> Self {
        let (perspective, near, far) = match camera.projection {
            Projection::Perspective { near, far, .. } => (true, near.max(1e-4), far),
            Projection::Orthographic { near, far, .. } => (false, near, far),
        };
        Self {
            view: transform.to_mat4().inverse(),
            projection: camera.projection.matrix(aspect),
            perspective,
            near,
            far: far.max(near + 1e-3),
        }
    }
}

/// Culls `lights` into clusters for the camera looking at an image of `size` pixels: the
/// words of `light_clusters` (lights.wgsl), a header of [`LIGHT_CLUSTER_HEADER`] words (the
/// grid, the depth slicing, the camera; in a storage buffer, because a condition on uniform
/// values alone makes Mesa 22's lavapipe keep a new copy of the shader at every bind), then
/// per cluster its first entry and count, then the lists.
pub(super) fn cull(
    (camera, transform): &(Camera, GlobalTransform),
    aspect: f32,
    size: (u32, u32),
    lights: &[PointLightGpu],
) -> Vec<u32> {
    let view = ClusterView::new(camera, transform, aspect);
    // The depths each light reaches, in view space; None for a light out of view.
    let reaches: Vec<Option<(Vec3, f32)>> = lights
        .iter()
        .map(|light| {
            let [x, y, z, range] = light.position_range;
            let center = view.view.transform_point3(Vec3::new(x, y, z));
            let depth = -center.z;
            let in_depth = depth + range >= view.near && depth - range <= view.far;
            (in_depth && range > 0.0 && center.is_finite()).then_some((center, range))
        })
        .collect();
    let farthest = reaches
        .iter()
        .flatten()
        .map(|(center, range)| -center.z + range)
        .fold(view.near, f32::max)
        .min(view.far);
    let mut tiles = [
        size.0.div_ceil(TILE_PIXELS).clamp(1, MAX_TILES),
        size.1.div_ceil(TILE_PIXELS).clamp(1, MAX_TILES),
    ];
    let mut slices = DEPTH_SLICES;
    loop {
        let slicing = depth_slicing(&view, farthest, slices);
        let boxes: Vec<Option<ClusterBox>> = reaches
            .iter()
            .map(|reach| reach.and_then(|(c, r)| cluster_box(&view, c, r, tiles, slices, slicing)))
            .collect();
        let entries: usize = boxes.iter().flatten().map(ClusterBox::clusters).sum();
        let coarsest = tiles == [1, 1] && slices == 1;
        if entries <= MAX_ENTRIES || coarsest {
            let grid = [tiles[0], tiles[1], slices, 0];
            let mut words = header(&view, transform, grid, slicing);
            fill(&mut words, &boxes, grid, entries);
            return words;
        }
        tiles = tiles.map(|count| count.div_ceil(2));
        slices = slices.div_ceil(2);
    }
}

/// The depth slicing: slice = floor(f(depth) × scale + bias), f = log2 for a perspective
/// camera, from its near plane to `farthest`.
fn depth_slicing(view: &ClusterView, farthest: f32, slices: u32) -> [f32; 4] {
    let slices = slices as f32;
    if view.perspective {
        let (near, far) = (view.near, farthest.max(view.near * 1.001));
        let scale = slices / (far / near).log2();
        [scale, -near.log2() * scale, 1.0, near]
    } else {
        let (near, far) = (view.near, farthest.max(view.near + 1e-3));
        let scale = slices / (far - near);
        [scale, -near * scale, 0.0, near]
    }
}

impl ClusterBox {
    fn clusters(&self) -> usize {
        let span = |(first, last): (u32, u32)| (last - first + 1) as usize;
        span(self.x) * span(self.y) * span(self.z)
    }
}

/// The clusters a light at `center` (view space) of `range` reaches, `None` where it reaches
/// none on the image.
fn cluster_box(
    view: &ClusterView,
    center: Vec3,
    range: f32,
    tiles: [u32; 2],
    slices: u32,
    slicing: [f32; 4],
) -> Option<ClusterBox> {
    let slice = |depth: f32| {
        let depth = depth.max(slicing[3]);
        let along = if slicing[2] > 0.5 {
            depth.log2()
        } else {
            depth
        };
        (along * slicing[0] + slicing[1])
            .floor()
            .clamp(0.0, (slices - 1) as f32) as u32
    };
    let depth = -center.z;
    let z = (slice(depth - range), slice(depth + range));
    // Where the sphere reaches behind the near plane its image has no bound: every tile.
    let whole = (0, tiles[0] - 1, 0, tiles[1] - 1);
    let (x0, x1, y0, y1) = if view.perspective && depth - range <= view.near {
        whole
    } else {
        let mut low = glam::Vec2::splat(f32::INFINITY);
        let mut high = glam::Vec2::splat(f32::NEG_INFINITY);
        for corner in 0..8 {
            let sign = |bit: u32| if corner & bit == 0 { -1.0 } else { 1.0 };
            let point = center + Vec3::new(sign(1), sign(2), sign(4)) * range;
            let clip = view.projection * point.extend(1.0);
            let ndc = clip.xy() / clip.w;
            low = low.min(ndc);
            high = high.max(ndc);
        }
        let tile = |ndc: f32, count: u32| {
            ((ndc * 0.5 + 0.5) * count as f32)
                .floor()
                .clamp(0.0, (count - 1) as f32) as u32
        };
        if !(low.is_finite() && high.is_finite()) {
            whole
        } else if low.x > 1.0 || low.y > 1.0 || high.x < -1.0 || high.y < -1.0 {
            return None;
        } else {
            (
                tile(low.x, tiles[0]),
                tile(high.x, tiles[0]),
                tile(low.y, tiles[1]),
                tile(high.y, tiles[1]),
            )
        }
    };
    Some(ClusterBox {
        x: (x0, x1),
        y: (y0, y1),
        z,
    })
}

/// The header lights.wgsl's `light_cluster` reads: the grid, the slicing, the camera's
/// view-projection (unjittered, as the lights were culled), position and forward direction.
fn header(
    view: &ClusterView,
    transform: &GlobalTransform,
    grid: [u32; 4],
    slicing: [f32; 4],
) -> Vec<u32> {
    let floats = (view.projection * view.view).to_cols_array();
    let position = transform.translation().extend(0.0).to_array();
    let forward = transform.forward().extend(0.0).to_array();
    let mut words = Vec::with_capacity(LIGHT_CLUSTER_HEADER);
    words.extend(grid);
    words.extend(
        slicing
            .iter()
            .chain(&floats)
            .chain(&position)
            .chain(&forward)
            .map(|v| v.to_bits()),
    );
    debug_assert_eq!(words.len(), LIGHT_CLUSTER_HEADER);
    words
}

/// Appends the clusters to `words` (after the header): per cluster (x fastest, then y, then z)
/// its first entry and count, then every cluster's list of light indices.
fn fill(words: &mut Vec<u32>, boxes: &[Option<ClusterBox>], grid: [u32; 4], entries: usize) {
    let [tiles_x, tiles_y, slices, _] = grid.map(|count| count as usize);
    let cluster_count = tiles_x * tiles_y * slices;
    let each = |light_box: &ClusterBox, visit: &mut dyn FnMut(usize)| {
        for z in light_box.z.0..=light_box.z.1 {
            for y in light_box.y.0..=light_box.y.1 {
                let row = (z as usize * tiles_y + y as usize) * tiles_x;
                for x in light_box.x.0..=light_box.x.1 {
                    visit(row + x as usize);
                }
            }
        }
    };
    let start = words.len();
    words.resize(start + 2 * cluster_count + entries, 0);
    let buffer = &mut words[start..];
    for light_box in boxes.iter().flatten() {
        each(light_box, &mut |cluster| buffer[2 * cluster + 1] += 1);
    }
    // Entries count from the start of the whole buffer, header included.
    let mut next = (start + 2 * cluster_count) as u32;
    for cluster in 0..cluster_count {
        buffer[2 * cluster] = next;
        next += buffer[2 * cluster + 1];
    }
    // The second pass counts each list up again as it fills it.
    let mut filled = vec![0u32; cluster_count];
    for (light, light_box) in boxes.iter().enumerate() {
        let Some(light_box) = light_box else { continue };
        each(light_box, &mut |cluster| {
            let at = buffer[2 * cluster] + filled[cluster];
            buffer[at as usize - start] = light as u32;
            filled[cluster] += 1;
        });
    }
}
