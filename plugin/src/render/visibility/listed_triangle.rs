//! One triangle of a draw the polygon pass finds (polygons.wgsl's `VisiblePolygon`): set up
//! once a frame on the CPU as the rasterizer would see it, its corners snapped, its face culled,
//! its depth over the framebuffer solved, its screen rectangle bounded.

use bytemuck::{Pod, Zeroable};
use glam::{Mat4, Vec2, Vec3, Vec4, Vec4Swizzles};

/// The face a draw's pipeline culls (`culled_face` in WGSL).
pub(super) const CULL_NONE: u32 = 0;
pub(super) const CULL_FRONT: u32 = 1;
pub(super) const CULL_BACK: u32 = 2;

/// Bits of sub-pixel precision the rasterizers we run on snap vertices to (Vulkan's
/// `subPixelPrecisionBits` on NVIDIA and lavapipe): the polygon pass snaps alike, so that its
/// coverage is the rasterizer's.
pub(super) const SUB_PIXEL_BITS: u32 = 8;

/// How far off the target (in pixels) a snapped corner may lie: past it the edge functions
/// could overflow (their differences are i32 in polygons.wgsl), and the triangle is tested by
/// its view rays instead.
const SNAP_RANGE: f32 = (1 << 20) as f32;

/// One listed triangle. Mirrors `VisiblePolygon` in polygons.wgsl.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub(crate) struct VisiblePolygon {
    a: [f32; 4],
    b: [f32; 4],
    c: [f32; 4],
    snapped_x: [i32; 4],
    snapped_y: [i32; 4],
    depth_plane: [f32; 4],
    /// The pixels it may cover: x, y from (inclusive) and to (exclusive).
    pub(super) rect: [u32; 4],
    id: u32,
    culled_face: u32,
    _padding: [u32; 2],
}

crate::wgsl_layout!(VisiblePolygon {
    a,
    b,
    c,
    snapped_x,
    snapped_y,
    depth_plane,
    rect,
    id,
    culled_face,
    _padding,
});

impl VisiblePolygon {
    /// World-space triangle `corners` with visibility `id`, drawn with `cull`, as the camera
    /// `view_projection` sees it on a target of `size` pixels; `None` where it cannot show
    /// (off the target, culled, or of no area once snapped).
    pub(crate) fn new(
        corners: [Vec3; 3],
        id: u32,
        cull: Option<wgpu::Face>,
        view_projection: Mat4,
        size: (u32, u32),
    ) -> Option<Self> {
        // Each corner as the vertex stage gives it, read by every step below.
        let clips = corners.map(|corner| view_projection * corner.extend(1.0));
        let rect = screen_rect(clips, size)?;
        let mut culled_face = match cull {
            None => CULL_NONE,
            Some(wgpu::Face::Front) => CULL_FRONT,
            Some(wgpu::Face::Back) => CULL_BACK,
        };
        let (mut snapped_x, mut snapped_y) = ([0; 4], [0; 4]);
        let mut depth_plane = [0.0; 4];
        let mut corners = corners;
        if let Some(snapped) = snapped_corners(clips, size) {
            // The rasterizer's facing: counter-clockwise in clip space (y up) is the front,
            // clockwise in the framebuffer's rows (y down).
            let area = snapped_area(snapped);
            let front = area < 0;
            let culled = match culled_face {
                CULL_FRONT => front,
                CULL_BACK => !front,
                _ => false,
            };
            if area == 0 || culled {
                return None;
            }
            // Ordered so that the inside is where every edge function is positive.
            let order = if front { [0, 2, 1] } else { [0, 1, 2] };
            corners = order.map(|index| corners[index]);
            let snapped = order.map(|index| snapped[index]);
            for (slot, [x, y]) in snapped.into_iter().enumerate() {
                (snapped_x[slot], snapped_y[slot]) = (x, y);
            }
            snapped_x[3] = 1;
            culled_face = CULL_NONE;
            depth_plane = screen_depth_plane(snapped, order.map(|index| clips[index]));
        }
        let point = |p: Vec3| p.extend(1.0).to_array();
        Some(Self {
            a: point(corners[0]),
            b: point(corners[1]),
            c: point(corners[2]),
            snapped_x,
            snapped_y,
            depth_plane,
            rect,
            id,
            culled_face,
            _padding: [0; 2],
        })
    }

    /// No pixel of it lies nearer than this clip depth.
    pub(super) fn nearest_depth(&self) -> f32 {
        self.depth_plane[3]
    }

    /// The pixels of its screen rectangle.
    pub(crate) fn pixels(&self) -> u64 {
        let [x0, y0, x1, y1] = self.rect.map(u64::from);
        (x1 - x0) * (y1 - y0)
    }
}

/// Where clip position `clip` (in front of the eye) lands on a target of `size` pixels, in
/// pixels from its top left corner.
fn framebuffer_position(clip: Vec4, (width, height): (u32, u32)) -> Vec2 {
    let ndc = clip.xy() / clip.w;
    glam::vec2(
        (ndc.x * 0.5 + 0.5) * width as f32,
        (0.5 - ndc.y * 0.5) * height as f32,
    )
}

/// The pixels (x, y from, x, y to) that the corners at clip positions `clips` may cover, a pixel
/// of margin around their projection; the whole target where a corner lies behind the eye (the
/// rasterizer clips there); `None` where nothing of it is on the target or a corner is not a
/// number.
fn screen_rect(clips: [Vec4; 3], (width, height): (u32, u32)) -> Option<[u32; 4]> {
    if !clips.iter().all(|clip| clip.is_finite()) {
        return None;
    }
    if clips.iter().any(|clip| clip.w <= f32::EPSILON) {
        return Some([0, 0, width, height]);
    }
    let pixels = clips.map(|clip| framebuffer_position(clip, (width, height)));
    let low = pixels[0].min(pixels[1]).min(pixels[2]).floor() - 1.0;
    let high = pixels[0].max(pixels[1]).max(pixels[2]).ceil() + 1.0;
    let size = glam::vec2(width as f32, height as f32);
    let (low, high) = (
        low.clamp(glam::Vec2::ZERO, size),
        high.clamp(glam::Vec2::ZERO, size),
    );
    (low.x < high.x && low.y < high.y).then_some([
        low.x as u32,
        low.y as u32,
        high.x as u32,
        high.y as u32,
    ])
}

/// The corners at clip positions `clips` in the framebuffer as the rasterizer snaps them (in
/// 1/2^SUB_PIXEL_BITS pixels), where every corner lies in front of the eye and near enough the
/// target; else `None` (the rasterizer clips such a triangle first, and the pass tests it by
/// its view rays).
fn snapped_corners(clips: [Vec4; 3], size: (u32, u32)) -> Option<[[i32; 2]; 3]> {
    let scale = (1 << SUB_PIXEL_BITS) as f32;
    let mut snapped = [[0; 2]; 3];
    for (slot, clip) in snapped.iter_mut().zip(clips) {
        // Not a number fails too.
        if clip.w.is_nan() || clip.w <= 0.0 {
            return None;
        }
        let pixel = framebuffer_position(clip, size).to_array();
        if !pixel.iter().all(|p| p.abs() < SNAP_RANGE) {
            return None;
        }
        *slot = pixel.map(|p| (p * scale).round() as i32);
    }
    Some(snapped)
}

/// How far below its corners' nearest clip depth a triangle's listed nearest depth lies: the
/// pass evaluates its depth in f32 (a few units in the last place of depths up to 1).
const NEAREST_DEPTH_MARGIN: f64 = 1e-6;

/// The clip depth over the framebuffer of the triangle at `snapped` corners (in front of the
/// eye), as the rasterizer interpolates it (affine in the framebuffer): the first corner's depth
/// and its rise per 1/2^SUB_PIXEL_BITS pixel across and down from that corner, and the nearest
/// depth it reaches, as (across, down, depth, nearest). Solved in f64 from the corners' clip
/// positions `clips` (f32, as the vertex stage gives them).
fn screen_depth_plane(snapped: [[i32; 2]; 3], clips: [Vec4; 3]) -> [f32; 4] {
    let [z0, z1, z2] = clips.map(|clip| f64::from(clip.z) / f64::from(clip.w));
    let from_first = |p: [i32; 2]| {
        (
            f64::from(p[0] - snapped[0][0]),
            f64::from(p[1] - snapped[0][1]),
        )
    };
    let ((x1, y1), (x2, y2)) = (from_first(snapped[1]), from_first(snapped[2]));
    let (dz1, dz2) = (z1 - z0, z2 - z0);
    // Not 0: a triangle of no snapped area is not listed.
    let determinant = x1 * y2 - y1 * x2;
    let across = (dz1 * y2 - dz2 * y1) / determinant;
    let down = (x1 * dz2 - x2 * dz1) / determinant;
    // Affine, the depth inside lies between the corners'; a margin for the pass's roundings.
    let nearest = z0.min(z1).min(z2) - NEAREST_DEPTH_MARGIN;
    [across as f32, down as f32, z0 as f32, nearest as f32]
}

/// Twice the signed area of a snapped triangle, in the framebuffer's rows (y down).
fn snapped_area([a, b, c]: [[i32; 2]; 3]) -> i64 {
    let d = |p: [i32; 2], q: [i32; 2]| (i64::from(q[0] - p[0]), i64::from(q[1] - p[1]));
    let ((abx, aby), (acx, acy)) = (d(a, b), d(a, c));
    abx * acy - aby * acx
}

#[cfg(test)]
mod tests {
    use super::*;

    fn clips_of(corners: [Vec3; 3], view_projection: Mat4) -> [Vec4; 3] {
        corners.map(|corner| view_projection * corner.extend(1.0))
    }

    #[test]
    fn a_triangle_behind_the_eye_spans_the_target_and_one_off_it_is_not_listed() {
        use glam::camera::rh::{proj::directx::perspective, view::look_to_mat4};
        let view_projection =
            perspective(1.0, 1.0, 0.1, 100.0) * look_to_mat4(Vec3::ZERO, Vec3::NEG_Z, Vec3::Y);
        let size = (64, 32);
        let crossing = [
            Vec3::new(-1.0, -1.0, 1.0),
            Vec3::new(1.0, -1.0, -5.0),
            Vec3::new(0.0, 1.0, -5.0),
        ];
        assert_eq!(
            screen_rect(clips_of(crossing, view_projection), size),
            Some([0, 0, 64, 32])
        );
        let ahead = [
            Vec3::new(-0.1, -0.1, -5.0),
            Vec3::new(0.1, -0.1, -5.0),
            Vec3::new(0.0, 0.1, -5.0),
        ];
        let rect = screen_rect(clips_of(ahead, view_projection), size).unwrap();
        assert!(
            rect[0] > 0 && rect[2] < 64 && rect[1] > 0 && rect[3] < 32,
            "{rect:?}"
        );
        let aside = ahead.map(|p| p + Vec3::new(50.0, 0.0, 0.0));
        assert_eq!(screen_rect(clips_of(aside, view_projection), size), None);
        let nan = [Vec3::NAN, ahead[1], ahead[2]];
        assert_eq!(
            VisiblePolygon::new(nan, 1, None, view_projection, size),
            None
        );
    }

    #[test]
    fn a_listed_triangles_depth_in_the_framebuffer_is_its_projected_depth_inside_it() {
        // A triangle tilted away in perspective: points inside it, projected, lie on the plane
        // the pass evaluates (clip depth is affine in the framebuffer).
        use glam::camera::rh::{proj::directx::perspective, view::look_to_mat4};
        let view_projection = perspective(1.0, 16.0 / 9.0, 0.1, 100.0)
            * look_to_mat4(Vec3::ZERO, Vec3::NEG_Z, Vec3::Y);
        let size = (1920, 1080);
        let corners = [
            Vec3::new(-2.0, -1.0, -2.0),
            Vec3::new(2.0, -1.0, -9.0),
            Vec3::new(0.5, 1.5, -4.0),
        ];
        let polygon = VisiblePolygon::new(corners, 1, None, view_projection, size).unwrap();
        assert_eq!(polygon.snapped_x[3], 1, "snapped");
        let [across, down, first, nearest] = polygon.depth_plane;
        let scale = (1 << SUB_PIXEL_BITS) as f32;
        for weights in [[0.2, 0.3, 0.5], [0.6, 0.2, 0.2], [0.1, 0.8, 0.1]] {
            let world = corners[0] * weights[0] + corners[1] * weights[1] + corners[2] * weights[2];
            let clip = view_projection * world.extend(1.0);
            let pixel = glam::vec2(
                (clip.x / clip.w * 0.5 + 0.5) * size.0 as f32,
                (0.5 - clip.y / clip.w * 0.5) * size.1 as f32,
            ) * scale;
            let from_first =
                pixel - glam::vec2(polygon.snapped_x[0] as f32, polygon.snapped_y[0] as f32);
            let depth = first + across * from_first.x + down * from_first.y;
            // Snapping moves a corner by up to half a sub-pixel step.
            assert!(
                (depth - clip.z / clip.w).abs() < 1e-5,
                "{weights:?}: {depth} against {}",
                clip.z / clip.w
            );
            assert!(
                nearest < depth,
                "the nearest depth {nearest} behind {depth}"
            );
        }
    }
}
