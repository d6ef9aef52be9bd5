//! Light culling into clusters: the image is cut into square tiles of [`TILE_PIXELS`] and the
//! view depth, from the camera's near plane to the farthest light's reach, into
//! [`DEPTH_SLICES`] slices (of equal ratio for a perspective camera, whose pixels grow with
//! the distance, of equal depth for an orthographic one). Each cluster lists every light whose
//! sphere of influence (its range) overlaps the cluster's tile rectangle and depth range: a
//! conservative list, since `light_at` cuts each light off at its range and cone exactly.
//! Done on the CPU in two passes over the lights (count, then fill), so each cluster's list
//! comes out in the lights' order; lights.wgsl's `light_cluster` finds a point's cluster the
//! same way.

use glam::{Mat4, Vec2, Vec3, Vec4Swizzles};

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
/// per cluster its first entry and count, then the lists. They replace what `words` held
/// (whose memory they reuse).
pub(super) fn cull(
    (camera, transform): &(Camera, GlobalTransform),
    aspect: f32,
    size: (u32, u32),
    lights: &[PointLightGpu],
    words: &mut Vec<u32>,
) {
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
            // The fourth word says how many entries the lists hold: none, no cluster to find.
            let grid = [tiles[0], tiles[1], slices, entries as u32];
            words.clear();
            header(words, &view, transform, grid, slicing);
            fill(words, &boxes, grid, entries);
            return;
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

    /// Visits the index of each cluster in the box (x fastest, then y, then z).
    fn for_each_cluster(&self, tiles_x: usize, tiles_y: usize, mut visit: impl FnMut(usize)) {
        for z in self.z.0..=self.z.1 {
            for y in self.y.0..=self.y.1 {
                let row = (z as usize * tiles_y + y as usize) * tiles_x;
                for x in self.x.0..=self.x.1 {
                    visit(row + x as usize);
                }
            }
        }
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
    let whole = (0, tiles[0] - 1, 0, tiles[1] - 1);
    // Where the sphere reaches behind the near plane its image has no bound: every tile.
    let bounds = if view.perspective && depth - range <= view.near {
        None
    } else {
        image_bounds(view, center, range)
    };
    let (x0, x1, y0, y1) = match bounds {
        None => whole,
        Some((low, high)) if low.x > 1.0 || low.y > 1.0 || high.x < -1.0 || high.y < -1.0 => {
            return None;
        }
        Some((low, high)) => {
            let tile = |ndc: f32, count: u32| {
                ((ndc * 0.5 + 0.5) * count as f32)
                    .floor()
                    .clamp(0.0, (count - 1) as f32) as u32
            };
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

/// The rectangle (normalized device coordinates) a sphere in front of the camera covers on
/// the image, `None` where it has no finite bound. In perspective, the lines from the eye
/// tangent to the sphere bound it along each axis (a cube's corners around the sphere would
/// take about half as much area again, and every light in it a cluster more to loop);
/// orthographically, the centre's image plus and minus the range.
fn image_bounds(view: &ClusterView, center: Vec3, range: f32) -> Option<(Vec2, Vec2)> {
    let project = |point: Vec3| {
        let clip = view.projection * point.extend(1.0);
        clip.xy() / clip.w
    };
    let (low, high) = if view.perspective {
        let depth = -center.z;
        // The slopes (offset over depth) of the two tangents in the plane of one axis.
        let tangents = |offset: f32| {
            let tangent = (offset * offset + depth * depth - range * range).sqrt();
            let first = (offset * tangent - depth * range) / (offset * range + depth * tangent);
            let second = (offset * tangent + depth * range) / (depth * tangent - offset * range);
            (first.min(second), first.max(second))
        };
        let (x, y) = (tangents(center.x), tangents(center.y));
        (
            project(Vec3::new(x.0, y.0, -1.0)),
            project(Vec3::new(x.1, y.1, -1.0)),
        )
    } else {
        let (a, b) = (project(center - range), project(center + range));
        (a.min(b), a.max(b))
    };
    (low.is_finite() && high.is_finite()).then_some((low, high))
}

/// The header lights.wgsl's `light_cluster` reads: the grid, the slicing, the camera's
/// view-projection (unjittered, as the lights were culled), position and forward direction.
fn header(
    words: &mut Vec<u32>,
    view: &ClusterView,
    transform: &GlobalTransform,
    grid: [u32; 4],
    slicing: [f32; 4],
) {
    let floats = (view.projection * view.view).to_cols_array();
    let position = transform.translation().extend(0.0).to_array();
    let forward = transform.forward().extend(0.0).to_array();
    let start = words.len();
    words.extend(grid);
    words.extend(
        slicing
            .iter()
            .chain(&floats)
            .chain(&position)
            .chain(&forward)
            .map(|v| v.to_bits()),
    );
    debug_assert_eq!(words.len() - start, LIGHT_CLUSTER_HEADER);
}

/// Appends the clusters to `words` (after the header): per cluster (x fastest, then y, then z)
/// its first entry and count, then every cluster's list of light indices.
fn fill(words: &mut Vec<u32>, boxes: &[Option<ClusterBox>], grid: [u32; 4], entries: usize) {
    let [tiles_x, tiles_y, slices, _] = grid.map(|count| count as usize);
    let cluster_count = tiles_x * tiles_y * slices;
    let start = words.len();
    words.resize(start + 2 * cluster_count + entries, 0);
    let (clusters, lists) = words[start..].split_at_mut(2 * cluster_count);
    for light_box in boxes.iter().flatten() {
        light_box.for_each_cluster(tiles_x, tiles_y, |cluster| clusters[2 * cluster + 1] += 1);
    }
    // Each cluster's first word starts at the end of its list; the lights go in from the last,
    // each stepping it back by one, so it ends at the list's start with the lights in order.
    let mut end = 0;
    for cluster in 0..cluster_count {
        end += clusters[2 * cluster + 1];
        clusters[2 * cluster] = end;
    }
    for (light, light_box) in boxes.iter().enumerate().rev() {
        let Some(light_box) = light_box else { continue };
        light_box.for_each_cluster(tiles_x, tiles_y, |cluster| {
            clusters[2 * cluster] -= 1;
            lists[clusters[2 * cluster] as usize] = light as u32;
        });
    }
    // Entries count from the start of the whole buffer, header included.
    let first_entry = (start + 2 * cluster_count) as u32;
    for cluster in 0..cluster_count {
        clusters[2 * cluster] += first_entry;
    }
}

#[cfg(test)]
mod tests {
    use glam::{Vec3, Vec4};

    use super::cull;
    use crate::render::extract::LIGHT_CLUSTER_HEADER;
    use crate::render::gpu_types::PointLightGpu;
    use crate::{Camera, GlobalTransform, Transform};

    /// The cluster `light_cluster` (lights.wgsl) finds for a point, from the header alone.
    fn cluster_of(words: &[u32], point: Vec3) -> usize {
        let float = |at: usize| f32::from_bits(words[at]);
        let vector = |at: usize| Vec4::new(float(at), float(at + 1), float(at + 2), float(at + 3));
        let grid = [words[0].max(1), words[1].max(1), words[2].max(1)];
        let slicing = vector(4);
        let view_projection = glam::Mat4::from_cols(vector(8), vector(12), vector(16), vector(20));
        let clip = view_projection * point.extend(1.0);
        let ndc = clip.truncate().truncate() / clip.w;
        let tile = |ndc: f32, count: u32| {
            ((ndc * 0.5 + 0.5) * count as f32)
                .floor()
                .clamp(0.0, (count - 1) as f32) as usize
        };
        let depth = (point - vector(24).truncate())
            .dot(vector(28).truncate())
            .max(slicing.w);
        let along = if slicing.z > 0.5 { depth.log2() } else { depth };
        let slice = (along * slicing.x + slicing.y)
            .floor()
            .clamp(0.0, (grid[2] - 1) as f32) as usize;
        (slice * grid[1] as usize + tile(ndc.y, grid[1])) * grid[0] as usize + tile(ndc.x, grid[0])
    }

    /// Every point inside a light's range, seen by the camera, finds that light in its
    /// cluster's list, and every list is in the lights' order.
    fn lists_hold_every_light_where_it_reaches(camera: Camera, seed: u64) {
        let eye = Transform::from_xyz(1.0, 3.0, 6.0).looking_at(Vec3::ZERO, Vec3::Y);
        let view = (camera, GlobalTransform(eye.to_affine()));
        let mut random = crate::test_numbers::seeded(seed);
        let lights: Vec<PointLightGpu> = (0..200)
            .map(|_| {
                let centre = Vec3::new(random() - 0.5, random() * 0.3, random() - 0.5) * 12.0;
                PointLightGpu {
                    position_range: centre.extend(0.2 + random() * 2.5).into(),
                    ..PointLightGpu::default()
                }
            })
            .collect();
        let mut words = vec![7; 3];
        cull(&view, 16.0 / 9.0, (1280, 720), &lights, &mut words);
        let clusters = (words[0] * words[1] * words[2]) as usize;
        let entries = words.len() - LIGHT_CLUSTER_HEADER - 2 * clusters;
        assert_eq!(words[3] as usize, entries, "the header's count of entries");
        assert!(entries > 0);
        for cluster in 0..clusters {
            let (first, count) = (
                words[LIGHT_CLUSTER_HEADER + 2 * cluster],
                words[LIGHT_CLUSTER_HEADER + 2 * cluster + 1],
            );
            let list = &words[first as usize..(first + count) as usize];
            assert!(
                list.windows(2).all(|pair| pair[0] < pair[1]),
                "cluster {cluster}: {list:?}"
            );
        }
        let view_projection = view.0.projection.matrix(16.0 / 9.0) * view.1.to_mat4().inverse();
        let mut checked = 0;
        for (index, light) in lights.iter().enumerate() {
            let [x, y, z, range] = light.position_range;
            for _ in 0..200 {
                let offset = Vec3::new(random(), random(), random()) * 2.0 - 1.0;
                let point =
                    Vec3::new(x, y, z) + offset.normalize_or_zero() * range * random().sqrt();
                let clip = view_projection * point.extend(1.0);
                let seen = clip.w > 0.0
                    && clip.x.abs() <= clip.w
                    && clip.y.abs() <= clip.w
                    && clip.z >= 0.0
                    && clip.z <= clip.w;
                if !seen {
                    continue;
                }
                let at = LIGHT_CLUSTER_HEADER + 2 * cluster_of(&words, point);
                let (first, count) = (words[at] as usize, words[at + 1] as usize);
                assert!(
                    words[first..first + count].contains(&(index as u32)),
                    "light {index} at {x},{y},{z} (range {range}) is missing where it reaches {point}"
                );
                checked += 1;
            }
        }
        assert!(checked > 10_000, "only {checked} points in view");
    }

    #[test]
    fn a_perspective_cameras_clusters_hold_every_light_where_it_reaches() {
        lists_hold_every_light_where_it_reaches(Camera::perspective(50.0), 7);
    }

    #[test]
    fn an_orthographic_cameras_clusters_hold_every_light_where_it_reaches() {
        lists_hold_every_light_where_it_reaches(Camera::orthographic(12.0), 11);
    }
}
