//! Blended surfaces compose back to front across materials, whatever order the file (or the
//! world) holds them in: overlapping half-transparent panes of `LitMaterial` and of a blended
//! material written here, seen from above, equal the analytic back-to-front blend on both
//! paths; a pane moving through another swaps the result.

use pom::glam::Vec3;
use pom::gpu::DefaultTexture;
use pom::material::{MAX_MATERIAL_TEXTURES, MaterialTextures, ShaderEntry, TextureFacts};
use pom::render::Renderer;
use pom::render::shaders::{self, ComposedShader, FRAME, MESH_VERTEX, WgslFile};
use pom::{
    AlphaMode, App, Assets, Camera, Color, LitMaterial, Material, MaterialPlugin, Mesh, RenderPath,
    Tonemapping, Transform,
};
use pom_tests::{headless_app, render_and_capture};

const SIZE: u32 = 32;
/// The opaque floor under the panes (unlit, linear).
const FLOOR: [f32; 3] = [0.2, 0.2, 0.2];
const ALPHA: f32 = 0.5;
/// Most a channel may differ from the analytic blend, in 8-bit steps.
const TOLERANCE: f32 = 2.0;

/// An unlit colour blended over what is behind it: a second blended material beside
/// `LitMaterial`'s `AlphaMode::Blend`.
#[derive(Clone, Debug, Default, PartialEq)]
struct Glaze {
    color: Color,
}

#[repr(C)]
#[derive(Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
struct GlazeUniform {
    color: [f32; 4],
}
pom::wgsl_layout!(GlazeUniform { color });

const GLAZE_WGSL: WgslFile = WgslFile {
    path: "glaze.wgsl",
    source: "struct GlazeUniform { color: vec4<f32> }
@group(0) @binding(2) var<storage, read> materials: array<GlazeUniform>;
@fragment
fn fs_main(in: VertexOut) -> @location(0) vec4<f32> { return materials[in.object_index].color; }",
};

impl Material for Glaze {
    type PerDraw = GlazeUniform;
    type Key = ();
    const NAME: &'static str = "glaze";
    const PER_DRAW_WGSL_NAME: &'static str = "GlazeUniform";
    const TEXTURE_SLOTS: &'static [DefaultTexture] = &[];
    fn shader() -> ComposedShader {
        ComposedShader {
            name: "glaze",
            constants: &[],
            files: &[FRAME, MESH_VERTEX, GLAZE_WGSL],
        }
    }
    // It never draws in the visibility pass (it blends), but an app renders deferred only when
    // every material has a deferred shader.
    fn deferred_shader() -> Option<ComposedShader> {
        Some(ComposedShader {
            name: "glaze (deferred)",
            constants: &[shaders::deferred_header],
            files: &[FRAME, MESH_VERTEX, GLAZE_WGSL, shaders::VISIBILITY],
        })
    }
    fn textures(&self) -> MaterialTextures {
        [None; MAX_MATERIAL_TEXTURES]
    }
    fn key(&self) {}
    fn fragment(_: ()) -> ShaderEntry {
        ShaderEntry::entry("fs_main")
    }
    fn blends(_: ()) -> bool {
        true
    }
    fn per_draw(&self, _: &[Option<TextureFacts>; MAX_MATERIAL_TEXTURES]) -> GlazeUniform {
        GlazeUniform {
            color: self.color.to_array(),
        }
    }
}

/// One pane: its material, its colour and its height above the floor.
#[derive(Clone, Copy, Debug)]
enum Pane {
    Lit([f32; 3], f32),
    Glaze([f32; 3], f32),
}

impl Pane {
    fn color(self) -> [f32; 3] {
        match self {
            Pane::Lit(color, _) | Pane::Glaze(color, _) => color,
        }
    }

    fn height(self) -> f32 {
        match self {
            Pane::Lit(_, height) | Pane::Glaze(_, height) => height,
        }
    }
}

const RED: [f32; 3] = [0.8, 0.05, 0.05];
const GREEN: [f32; 3] = [0.05, 0.7, 0.1];
const BLUE: [f32; 3] = [0.1, 0.1, 0.9];

fn translucent(color: [f32; 3]) -> Color {
    Color {
        a: ALPHA,
        ..Color::linear_rgb(color[0], color[1], color[2])
    }
}

/// A unit plane whose vertices stand `height` above the origin, as a glTF primitive's do: its
/// transform is the identity, only its centre says where it is.
fn plane_at(height: f32) -> Mesh {
    let mut mesh = Mesh::plane(1.0);
    for position in &mut mesh.positions {
        position[1] += height;
    }
    mesh
}

/// An app on `path` with the glaze material, a top-down orthographic camera and the floor.
fn scene(path: RenderPath) -> App {
    let mut app = headless_app(SIZE, SIZE).unwrap();
    app.add_plugin(MaterialPlugin::<Glaze>::default());
    app.finish().unwrap();
    app.resources.get_mut::<Renderer>().unwrap().set_path(path);
    let floor = app
        .resources
        .get_mut::<Assets<Mesh>>()
        .unwrap()
        .add(Mesh::plane(4.0));
    app.world.spawn((
        Camera::orthographic(1.0),
        Tonemapping::None,
        Transform::from_xyz(0.0, 3.0, 0.0).looking_at(Vec3::ZERO, Vec3::NEG_Z),
    ));
    app.world.spawn((
        floor,
        LitMaterial {
            unlit: true,
            ..LitMaterial::from_color(Color::linear_rgb(FLOOR[0], FLOOR[1], FLOOR[2]))
        },
        Transform::IDENTITY,
    ));
    app
}

/// Replaces the panes with `panes`, spawned in that order.
fn set_panes(app: &mut App, panes: &[Pane]) {
    let old: Vec<_> = app
        .world
        .query::<(pom::hecs::Entity, &PaneMarker)>()
        .iter()
        .map(|(entity, _)| entity)
        .collect();
    for entity in old {
        app.world.despawn(entity).unwrap();
    }
    for &pane in panes {
        let mesh = app
            .resources
            .get_mut::<Assets<Mesh>>()
            .unwrap()
            .add(plane_at(pane.height()));
        let transform = Transform::IDENTITY;
        match pane {
            Pane::Lit(color, _) => app.world.spawn((
                mesh,
                LitMaterial {
                    unlit: true,
                    alpha_mode: AlphaMode::Blend,
                    ..LitMaterial::from_color(translucent(color))
                },
                transform,
                PaneMarker,
            )),
            Pane::Glaze(color, _) => app.world.spawn((
                mesh,
                Glaze {
                    color: translucent(color),
                },
                transform,
                PaneMarker,
            )),
        };
    }
}

struct PaneMarker;

/// The panes blended over the floor farthest (lowest) first, as 8-bit sRGB.
fn back_to_front(panes: &[Pane]) -> [f32; 3] {
    let mut sorted = panes.to_vec();
    sorted.sort_by(|a, b| a.height().total_cmp(&b.height()));
    let mut color = FLOOR;
    for pane in sorted {
        for (channel, value) in color.iter_mut().zip(pane.color()) {
            *channel = ALPHA * value + (1.0 - ALPHA) * *channel;
        }
    }
    color.map(|linear| pom::linear_to_srgb(linear) * 255.0)
}

/// Renders a frame and returns the centre pixel, where every pane overlaps, as 8-bit sRGB,
/// checking the frame ran on `path`.
fn centre(app: &mut App, path: RenderPath) -> [f32; 3] {
    let image = render_and_capture(app).unwrap();
    assert_eq!(
        app.resources.get::<Renderer>().unwrap().runs_deferred(),
        path == RenderPath::Deferred,
        "the frame ran on the path asked for"
    );
    let [r, g, b, _] = image.get_pixel(SIZE / 2, SIZE / 2).0;
    [r, g, b].map(f32::from)
}

fn assert_near(actual: [f32; 3], expected: [f32; 3], what: &str) {
    let worst = actual
        .iter()
        .zip(expected)
        .map(|(a, e)| (a - e).abs())
        .fold(0.0, f32::max);
    assert!(
        worst <= TOLERANCE,
        "{what}: {actual:?}, expected {expected:?} (back to front), off by {worst}"
    );
}

/// Every order of `panes`.
fn permutations(panes: &[Pane]) -> Vec<Vec<Pane>> {
    if panes.len() <= 1 {
        return vec![panes.to_vec()];
    }
    let mut all = Vec::new();
    for first in 0..panes.len() {
        let mut rest = panes.to_vec();
        let head = rest.remove(first);
        for mut tail in permutations(&rest) {
            tail.insert(0, head);
            all.push(tail);
        }
    }
    all
}

fn check_every_order(layouts: &[&[Pane]]) {
    for path in [RenderPath::Forward, RenderPath::Deferred] {
        let mut app = scene(path);
        for layout in layouts {
            let expected = back_to_front(layout);
            for order in permutations(layout) {
                set_panes(&mut app, &order);
                assert_near(
                    centre(&mut app, path),
                    expected,
                    &format!("{path:?}, panes spawned as {order:?}"),
                );
            }
        }
    }
}

#[test]
fn two_panes_of_two_materials_blend_back_to_front_in_either_order() {
    check_every_order(&[
        &[Pane::Lit(RED, 0.6), Pane::Glaze(BLUE, 0.3)],
        &[Pane::Lit(RED, 0.3), Pane::Glaze(BLUE, 0.6)],
        // Two of one material: its own draws too go farthest first.
        &[Pane::Lit(RED, 0.3), Pane::Lit(BLUE, 0.6)],
    ]);
}

#[test]
fn three_panes_interleaving_two_materials_blend_back_to_front_in_every_order() {
    check_every_order(&[
        &[
            Pane::Lit(RED, 0.2),
            Pane::Glaze(GREEN, 0.4),
            Pane::Lit(BLUE, 0.6),
        ],
        &[
            Pane::Glaze(RED, 0.2),
            Pane::Lit(GREEN, 0.4),
            Pane::Glaze(BLUE, 0.6),
        ],
    ]);
}

#[test]
fn a_pane_moving_through_another_swaps_the_blend() {
    for path in [RenderPath::Forward, RenderPath::Deferred] {
        let mut app = scene(path);
        set_panes(&mut app, &[Pane::Lit(RED, 0.5)]);
        let mesh = app
            .resources
            .get_mut::<Assets<Mesh>>()
            .unwrap()
            .add(Mesh::plane(1.0));
        let moving = app.world.spawn((
            mesh,
            Glaze {
                color: translucent(BLUE),
            },
            Transform::from_xyz(0.0, 0.2, 0.0),
            PaneMarker,
        ));
        let mut seen = Vec::new();
        for height in [0.2, 0.4, 0.6, 0.8] {
            *app.world.get::<&mut Transform>(moving).unwrap() =
                Transform::from_xyz(0.0, height, 0.0);
            let expected = back_to_front(&[Pane::Lit(RED, 0.5), Pane::Glaze(BLUE, height)]);
            let actual = centre(&mut app, path);
            assert_near(
                actual,
                expected,
                &format!("{path:?}, blue pane at {height}"),
            );
            seen.push(actual);
        }
        // Below the red pane red is on top (more red), above it blue is.
        assert!(seen[0][0] > seen[3][0] + 20.0, "{path:?}: {seen:?}");
        assert!(seen[3][2] > seen[0][2] + 20.0, "{path:?}: {seen:?}");
    }
}
