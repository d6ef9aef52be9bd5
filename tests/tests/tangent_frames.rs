//! Tangent frames on a mapping mirrored in u: a glTF quad whose right half has its texture
//! mirrored (so the MikkTSpace handedness w flips there), with the file's own TANGENT attribute
//! or with none (generated). On both halves and with both kinds of tangents, a normal map tilted
//! towards the texture's +u and up the image lights the side the texture says, and a parallax
//! march shifts the coordinate the way the view ray runs in texture space. A flipped bitangent
//! sign, the classic convention bug, turns the lit side and the shift's v round (comparing the
//! two kinds of tangents with each other, as the glTF tests once did, misses it in either).

use glam::{Vec2, Vec3};
use image::{GrayImage, Luma, Rgba, RgbaImage};
use pom::render::Renderer;
use pom::{
    App, DirectionalLight, PomPlugin, RenderPath, RenderPlugin, TargetFormat, Transform, load_gltf,
    pick_at,
};
use pom_tests::gltf_fixture::{GltfFixture, png, scratch_dir};
use pom_tests::pom_scene::wrapped;
use pom_tests::{render_and_capture_f32, render_on_path_f32};
use serde_json::json;

/// Side of the rendered images in pixels.
const SIZE: u32 = 64;
/// Depth of the relief in texture units; the height map is all floor (black), so a march ends
/// this deep and the coordinate shifts by the whole ray offset.
const HEIGHT_SCALE: f32 = 0.1;
/// The normal map's tangent-space normal (OpenGL convention): tilted towards +u and up the
/// image (green), which is −v.
const TILTED_NORMAL: Vec3 = Vec3::new(0.6, 0.6, 0.53);

/// Where the mesh's tangents come from.
#[derive(Clone, Copy, Debug)]
enum Tangents {
    /// The file's TANGENT attribute (glTF convention: cross(normal, tangent) × w points up the
    /// image).
    Supplied,
    /// None in the file: the loader generates MikkTSpace tangents.
    Generated,
}

/// One half of the quad and the world directions its texture axes run along.
#[derive(Clone, Copy, Debug)]
struct Half {
    name: &'static str,
    /// World direction of +u (unit: one texture unit per world unit).
    u_axis: Vec3,
}

/// World direction of +v on both halves.
const V_AXIS: Vec3 = Vec3::Z;
/// The left half, mapped as the texture is, and the right one, mirrored in u.
const HALVES: [Half; 2] = [
    Half {
        name: "plain half (u along +X)",
        u_axis: Vec3::X,
    },
    Half {
        name: "mirrored half (u along -X)",
        u_axis: Vec3::NEG_X,
    },
];

/// Which of [`HALVES`] a world point on the quad lies on; `None` near the seam and the edges.
fn half_at(point: Vec3) -> Option<usize> {
    let inside = point.z.abs() < 0.42 && (0.08..0.42).contains(&point.x.abs());
    inside.then_some(usize::from(point.x > 0.0))
}

/// The texture coordinate of a world point on the quad, as the file maps it.
fn plain_uv(point: Vec3) -> Vec2 {
    let u = if point.x < 0.0 {
        point.x + 0.5
    } else {
        0.5 - point.x
    };
    Vec2::new(u, point.z + 0.5)
}

fn push_f32s(bin: &mut Vec<u8>, values: &[f32]) -> serde_json::Value {
    let offset = bin.len();
    for value in values {
        bin.extend_from_slice(&value.to_le_bytes());
    }
    json!({"buffer": 0, "byteOffset": offset, "byteLength": bin.len() - offset})
}

/// A 1 × 1 quad in the XZ plane facing +Y, one texture unit per world unit: the left half
/// (x < 0) maps u = x + ½, the right half mirrors it (u = ½ − x); v = z + ½ on both. Each half
/// has its own four vertices. With [`Tangents::Supplied`], TANGENT holds dP/du with w = +1 on
/// the left and −1 on the mirrored right, as a glTF exporter writes them.
fn mirrored_quad(tangents: Tangents) -> GltfFixture {
    #[rustfmt::skip]
    let positions = [
        -0.5, 0.0, -0.5,  -0.5, 0.0, 0.5,  0.0, 0.0, 0.5,  0.0, 0.0, -0.5,
        0.0, 0.0, -0.5,   0.0, 0.0, 0.5,   0.5, 0.0, 0.5,  0.5, 0.0, -0.5,
    ];
    // Both halves give the seam u = ½.
    let uvs: Vec<f32> = positions
        .chunks(3)
        .flat_map(|p| plain_uv(Vec3::from_slice(p)).to_array())
        .collect();
    #[rustfmt::skip]
    let file_tangents = [
        1.0, 0.0, 0.0, 1.0,  1.0, 0.0, 0.0, 1.0,  1.0, 0.0, 0.0, 1.0,  1.0, 0.0, 0.0, 1.0,
        -1.0, 0.0, 0.0, -1.0,  -1.0, 0.0, 0.0, -1.0,  -1.0, 0.0, 0.0, -1.0,  -1.0, 0.0, 0.0, -1.0,
    ];
    let mut bin = Vec::new();
    let mut views = vec![
        push_f32s(&mut bin, &positions),
        push_f32s(&mut bin, &[0.0, 1.0, 0.0].repeat(8)),
        push_f32s(&mut bin, &uvs),
    ];
    let index_offset = bin.len();
    // Counter-clockwise seen from +Y, as the one-quad fixture.
    for index in [0_u16, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7] {
        bin.extend_from_slice(&index.to_le_bytes());
    }
    views.push(json!({"buffer": 0, "byteOffset": index_offset, "byteLength": 24}));
    let mut attributes = json!({"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2});
    let mut accessors = vec![
        json!({"bufferView": 0, "componentType": 5126, "count": 8, "type": "VEC3",
               "min": [-0.5, 0.0, -0.5], "max": [0.5, 0.0, 0.5]}),
        json!({"bufferView": 1, "componentType": 5126, "count": 8, "type": "VEC3"}),
        json!({"bufferView": 2, "componentType": 5126, "count": 8, "type": "VEC2"}),
        json!({"bufferView": 3, "componentType": 5123, "count": 12, "type": "SCALAR"}),
    ];
    if let Tangents::Supplied = tangents {
        views.push(push_f32s(&mut bin, &file_tangents));
        accessors.push(json!({"bufferView": 4, "componentType": 5126, "count": 8, "type": "VEC4"}));
        attributes["TANGENT"] = json!(4);
    }
    let json = json!({
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"name": "mirrored quad", "mesh": 0}],
        "meshes": [{"name": "mirrored quad", "primitives": [{
            "attributes": attributes, "indices": 3, "material": 0
        }]}],
        "materials": [{"name": "tilted", "pbrMetallicRoughness": {"metallicFactor": 0.0}}],
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"uri": "quad.bin", "byteLength": bin.len()}]
    });
    let mut fixture = GltfFixture {
        json,
        bin,
        images: Vec::new(),
    };
    let encoded = (TILTED_NORMAL.normalize() * 0.5 + 0.5) * 255.0;
    let normal = fixture.add_texture(
        "normal.png",
        png(&RgbaImage::from_pixel(
            8,
            8,
            Rgba([
                encoded.x.round() as u8,
                encoded.y.round() as u8,
                encoded.z.round() as u8,
                255,
            ]),
        )),
    );
    let floor = fixture.add_texture("height.png", png(&GrayImage::from_pixel(8, 8, Luma([0]))));
    fixture.json["materials"][0]["normalTexture"] = json!({"index": normal});
    fixture.json["materials"][0]["extras"] = json!({"pom": {
        "height_texture": floor, "height_scale": HEIGHT_SCALE, "shadows": "off"
    }});
    fixture
}

/// An app showing the quad (written under a folder named after `test`), with an orthographic
/// camera at `camera` and a sun whose light comes from `to_light`; returns it with the sun's
/// entity.
fn quad_app(
    test: &str,
    tangents: Tangents,
    camera: Transform,
    to_light: Vec3,
) -> (App, pom::hecs::Entity) {
    let mut app = App::new();
    app.add_plugin(RenderPlugin::new(SIZE, SIZE).with_format(TargetFormat::Float32))
        .add_plugin(PomPlugin);
    let name = format!("{tangents:?}").to_lowercase();
    let dir = scratch_dir(&format!("{test}-{name}"));
    load_gltf(&mut app, mirrored_quad(tangents).write(&dir, &name)).unwrap();
    app.world.spawn((pom::Camera::orthographic(1.3), camera));
    let sun = app
        .world
        .spawn((DirectionalLight::default(), light_from(to_light)));
    (app, sun)
}

fn light_from(to_light: Vec3) -> Transform {
    Transform::from_translation(to_light).looking_at(Vec3::ZERO, Vec3::Y)
}

/// The quad's point each pixel shows, by the CPU picking ray of the pixel's centre (the app has
/// rendered once, so transforms are propagated).
fn surface_points(app: &App) -> Vec<Option<Vec3>> {
    let viewport = Vec2::splat(SIZE as f32);
    (0..SIZE * SIZE)
        .map(|i| {
            let pixel = Vec2::new((i % SIZE) as f32 + 0.5, (i / SIZE) as f32 + 0.5);
            pick_at(&app.world, &app.resources, viewport, pixel).map(|hit| hit.point)
        })
        .collect()
}

/// Mean red channel (the surface is white: all channels alike) of the pixels on each half,
/// plain half first.
fn half_brightness(image: &image::Rgba32FImage, points: &[Option<Vec3>]) -> [f32; 2] {
    let mut sums = [(0.0_f32, 0_u32); 2];
    for (pixel, point) in image.pixels().zip(points) {
        if let Some(half) = point.and_then(half_at) {
            let slot = &mut sums[half];
            slot.0 += pixel.0[0];
            slot.1 += 1;
        }
    }
    sums.map(|(sum, count)| {
        assert!(count > 100, "only {count} pixels on a half");
        sum / count as f32
    })
}

#[test]
fn a_tilted_normal_map_lights_the_side_its_texture_says_on_both_mirrored_halves() {
    // Straight down, +X to the right of the image and −Z up it.
    let camera = Transform::from_xyz(0.0, 3.0, 0.0).looking_at(Vec3::ZERO, Vec3::NEG_Z);
    // 60° from the zenith, from each side in turn.
    let from = |side: Vec3| (side * 60_f32.to_radians().sin() + Vec3::Y * 0.5).normalize();
    let sides = [Vec3::X, Vec3::NEG_X, V_AXIS, -V_AXIS];
    let mut report = Vec::new();
    let mut failures = Vec::new();
    for tangents in [Tangents::Supplied, Tangents::Generated] {
        let (mut app, sun) = quad_app("tangent-lighting", tangents, camera, from(sides[0]));
        let mut lit_by = Vec::new();
        for side in sides {
            *app.world.get::<&mut Transform>(sun).unwrap() = light_from(from(side));
            let image = render_and_capture_f32(&mut app).unwrap();
            lit_by.push((side, half_brightness(&image, &surface_points(&app))));
        }
        let brightness = |side: Vec3, half: usize| {
            lit_by
                .iter()
                .find(|(s, _)| *s == side)
                .map(|(_, b)| b[half])
                .unwrap()
        };
        for (index, half) in HALVES.iter().enumerate() {
            // The normal leans towards the texture's +u and towards −v (up the image).
            for (axis, towards) in [("+u", half.u_axis), ("up the image (-v)", -V_AXIS)] {
                let lit = brightness(towards, index);
                let unlit = brightness(-towards, index);
                report.push(format!(
                    "{tangents:?} tangents, {}: light from {axis} {lit:.3}, from the opposite side {unlit:.3}",
                    half.name
                ));
                if lit <= 3.0 * unlit {
                    failures.push(format!(
                        "{tangents:?} tangents, {}: the normal map leans towards {axis}, but a light from there gives {lit:.3} and one from the opposite side {unlit:.3}",
                        half.name
                    ));
                }
            }
        }
    }
    eprintln!("{}", report.join("\n"));
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The pixel of one half whose parallax shift is farthest from the expected one.
#[derive(Clone, Copy, Debug, Default)]
struct WorstShift {
    /// |shift − expected| in texture units.
    error: f32,
    shift: Vec2,
    expected: Vec2,
    /// Pixels of the half looked at.
    pixels: u32,
}

/// For each of [`HALVES`], the worst shift of the final texture coordinate (the `uv` view's red
/// and green) from the file's coordinate at the pixel's surface point, against the run of a view
/// ray along `forward` down to the floor, in the half's texture axes. Panics where the full march
/// did not run.
fn worst_shifts(
    uv_view: &image::Rgba32FImage,
    points: &[Option<Vec3>],
    forward: Vec3,
) -> [WorstShift; 2] {
    let mut worst = [WorstShift::default(); 2];
    for (pixel, point) in uv_view.pixels().zip(points) {
        let Some((point, index)) = point.and_then(|p| Some((p, half_at(p)?))) else {
            continue;
        };
        assert_eq!(pixel.0[2], 1.0, "the full march runs at {point}");
        let expected = Vec2::new(forward.dot(HALVES[index].u_axis), forward.dot(V_AXIS))
            * (HEIGHT_SCALE / -forward.y);
        let plain = plain_uv(point);
        let shift = Vec2::new(wrapped(pixel.0[0] - plain.x), wrapped(pixel.0[1] - plain.y));
        let slot = &mut worst[index];
        slot.pixels += 1;
        let error = (shift - expected).length();
        if error >= slot.error {
            *slot = WorstShift {
                error,
                shift,
                expected,
                pixels: slot.pixels,
            };
        }
    }
    worst
}

#[test]
fn the_parallax_shift_follows_the_view_in_texture_space_on_both_mirrored_halves_and_paths() {
    // Looking down at 38° from the zenith, along +X and −Z: the ray runs towards −v on both
    // halves, and towards +u on the plain half but −u on the mirrored one.
    let forward = Vec3::new(0.5, -1.0, -0.6).normalize();
    let camera = Transform::from_translation(-forward * 3.0).looking_at(Vec3::ZERO, Vec3::Y);
    let mut report = Vec::new();
    let mut failures = Vec::new();
    for tangents in [Tangents::Supplied, Tangents::Generated] {
        let (mut app, _) = quad_app("tangent-parallax", tangents, camera, Vec3::Y);
        pom_tests::pom_scene::set_material(&mut app, |material| {
            material.debug_view = pom::DebugView::Uv;
        });
        for path in [RenderPath::Forward, RenderPath::Deferred] {
            let uv_view = render_on_path_f32(&mut app, path).unwrap();
            let ran_deferred = app.resources.get::<Renderer>().unwrap().runs_deferred();
            assert_eq!(ran_deferred, path == RenderPath::Deferred, "{path:?} ran");
            let worst = worst_shifts(&uv_view, &surface_points(&app), forward);
            for (half, worst) in HALVES.iter().zip(worst) {
                let WorstShift {
                    error,
                    shift,
                    expected,
                    pixels,
                } = worst;
                let case = format!("{tangents:?} tangents, {path:?}, {}", half.name);
                report.push(format!(
                    "{case}: worst shift {shift:.4} (expected {expected:.4}, off by {error:.2e}) over {pixels} pixels"
                ));
                assert!(pixels > 100, "{case}: only {pixels} pixels");
                // The march meets a flat floor exactly at the ray's end, so only rounding is
                // left (under 1e-6); a flipped axis is off by twice that component of the shift.
                if error > 0.01 * expected.length() {
                    failures.push(format!(
                        "{case}: the coordinate shifted by {shift:.4}, the view ray runs {expected:.4} in texture space"
                    ));
                }
            }
        }
    }
    eprintln!("{}", report.join("\n"));
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
