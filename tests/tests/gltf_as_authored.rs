//! glTF files render as their authors meant them: each feature on a small scene the test writes
//! itself, with a reference image where the look matters.

use glam::Vec3;
use pom::{
    App, Camera, DirectionalLight, LitMaterial, PomPlugin, RenderPlugin, Tonemapping, Transform,
    load_gltf,
};
use pom_tests::gltf_fixture::{GltfFixture, scratch_dir};
use pom_tests::{FlipTolerance, check_golden, render_both_paths};
use serde_json::json;

fn app(size: u32) -> App {
    let mut app = App::new();
    app.add_plugin(RenderPlugin::new(size, size))
        .add_plugin(PomPlugin);
    app
}

/// The fixture's quad (facing +Y) seen from below, lit from below, `double_sided` or not.
fn quad_from_behind(double_sided: bool) -> image::RgbaImage {
    let dir = scratch_dir(&format!("double-sided-{double_sided}"));
    let mut fixture = GltfFixture::quad(1.0);
    fixture.json["materials"][0] = json!({
        "name": "orange",
        "doubleSided": double_sided,
        "pbrMetallicRoughness": {
            "baseColorFactor": [0.9, 0.4, 0.1, 1.0],
            "metallicFactor": 0.0,
            "roughnessFactor": 0.6
        }
    });
    let mut app = app(64);
    load_gltf(&mut app, fixture.write(&dir, "quad")).unwrap();
    assert_eq!(
        app.world
            .query::<&LitMaterial>()
            .iter()
            .map(|material| material.double_sided)
            .collect::<Vec<_>>(),
        [double_sided]
    );
    app.world.spawn((
        Camera::perspective(50.0),
        Tonemapping::None,
        Transform::from_xyz(0.3, -1.4, 0.4).looking_at(Vec3::ZERO, Vec3::Z),
    ));
    // The light shines up onto the back: only a reversed normal faces it.
    app.world.spawn((
        DirectionalLight::default(),
        Transform::IDENTITY.looking_at(Vec3::new(0.2, 1.0, 0.1), Vec3::Z),
    ));
    render_both_paths(&mut app, "gltf_quad_from_behind").unwrap()
}

#[test]
fn a_double_sided_quad_seen_from_behind() {
    let culled = quad_from_behind(false);
    let background = *culled.get_pixel(0, 0);
    assert!(
        culled.pixels().all(|p| *p == background),
        "a single-sided quad's back is culled"
    );
    let image = quad_from_behind(true);
    let centre = image.get_pixel(32, 32).0;
    // Lit from the side it shows: the orange is bright, red over green over blue.
    assert!(
        centre[0] > 150 && centre[0] > centre[1] && centre[1] > centre[2],
        "{centre:?}"
    );
    check_golden("gltf_double_sided_back", &image, FlipTolerance::default()).unwrap();
}

#[test]
fn the_first_camera_node_is_the_one_looked_through() {
    let dir = scratch_dir("two-cameras");
    let mut fixture = GltfFixture::quad(1.0);
    // Camera nodes: a parent with one child camera, listed after a sibling camera; the walk is
    // depth first, parents before children, siblings in file order.
    fixture.json["cameras"] = json!([
        {"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}},
        {"type": "orthographic", "orthographic": {"xmag": 1.0, "ymag": 1.0, "znear": 0.1, "zfar": 10.0}}
    ]);
    fixture.json["nodes"] = json!([
        {"name": "quad", "mesh": 0},
        {"name": "rig", "children": [2]},
        {"name": "near", "camera": 1, "translation": [0.0, 2.0, 0.0]},
        {"name": "far", "camera": 0, "translation": [0.0, 5.0, 5.0]}
    ]);
    fixture.json["scenes"] = json!([{"nodes": [0, 1, 3]}]);
    let mut app = app(16);
    let scene = load_gltf(&mut app, fixture.write(&dir, "cameras")).unwrap();
    let names = |app: &App| -> Vec<(String, bool)> {
        scene
            .cameras
            .iter()
            .map(|&entity| {
                let name = app.world.get::<&pom::Name>(entity).unwrap().0.clone();
                (name, app.world.get::<&Camera>(entity).unwrap().active)
            })
            .collect()
    };
    assert_eq!(
        names(&app),
        [("near".to_owned(), true), ("far".to_owned(), false)]
    );
    assert!(scene.activate_camera(&mut app.world, Some(1)));
    assert_eq!(
        names(&app),
        [("near".to_owned(), false), ("far".to_owned(), true)]
    );
    assert!(
        !scene.activate_camera(&mut app.world, Some(2)),
        "no third camera"
    );
    assert!(scene.activate_camera(&mut app.world, None));
    assert!(names(&app).iter().all(|(_, active)| !active));
}

/// What lights the quad seen from above.
#[derive(Clone, Copy, PartialEq)]
enum Light {
    /// Nothing: only what the surface emits shows.
    Dark,
    /// A sun straight above, no ambient light.
    Sun,
    /// A white ambient light of 100,000 lux, nothing else.
    Ambient,
}

/// The fixture's quad seen from straight above under `light`, with `edit` applied to the
/// document first. Returns the image and the loader's warnings.
fn quad_from_above(
    name: &str,
    light: Light,
    edit: impl FnOnce(&mut GltfFixture),
) -> (image::RgbaImage, Vec<String>) {
    let dir = scratch_dir(name);
    let mut fixture = GltfFixture::quad(1.0);
    edit(&mut fixture);
    let mut app = app(48);
    let scene = load_gltf(&mut app, fixture.write(&dir, name)).unwrap();
    *app.resources.get_mut::<pom::AmbientLight>().unwrap() = pom::AmbientLight {
        color: pom::Color::WHITE,
        intensity: if light == Light::Ambient {
            100_000.0
        } else {
            0.0
        },
    };
    app.world.spawn((
        Camera::orthographic(1.25),
        Transform::from_xyz(0.0, 2.0, 0.0).looking_at(Vec3::ZERO, Vec3::NEG_Z),
    ));
    if light == Light::Sun {
        app.world.spawn((
            DirectionalLight::default(),
            Transform::IDENTITY.looking_at(Vec3::NEG_Y, Vec3::NEG_Z),
        ));
    }
    (
        render_both_paths(&mut app, "gltf_quad_from_above").unwrap(),
        scene.warnings,
    )
}

#[test]
fn vertex_colours_tint_the_base_colour() {
    let (image, warnings) = quad_from_above("vertex-colours", Light::Sun, |fixture| {
        // Corners in the fixture's order: (-,-), (-,+), (+,+), (+,-) in x and z.
        fixture.add_vertex_colors([
            [1.0, 0.0, 0.0, 1.0],
            [0.0, 1.0, 0.0, 1.0],
            [0.0, 0.0, 1.0, 1.0],
            [1.0, 1.0, 1.0, 1.0],
        ]);
    });
    assert!(warnings.is_empty(), "{warnings:?}");
    // Seen from above with −Z up the image: x grows to the right, z downwards. Near each
    // corner its colour leads (the quad covers pixels 5 to 43).
    let leads = |pixel: [u8; 4], channel: usize| {
        (0..3).all(|other| other == channel || pixel[channel] > pixel[other] + 100)
    };
    let (top_left, bottom_left) = (image.get_pixel(7, 7).0, image.get_pixel(7, 40).0);
    let (bottom_right, top_right) = (image.get_pixel(40, 40).0, image.get_pixel(40, 7).0);
    assert!(leads(top_left, 0), "{top_left:?}");
    assert!(leads(bottom_left, 1), "{bottom_left:?}");
    assert!(leads(bottom_right, 2), "{bottom_right:?}");
    assert!(top_right.iter().take(3).all(|&c| c > 180), "{top_right:?}");
    check_golden("gltf_vertex_colours", &image, FlipTolerance::default()).unwrap();
}

#[test]
fn emission_glows_without_light() {
    let (image, warnings) = quad_from_above("emissive", Light::Dark, |fixture| {
        fixture.json["extensionsUsed"] = json!(["KHR_materials_emissive_strength"]);
        fixture.json["materials"][0] = json!({
            "name": "lamp",
            "pbrMetallicRoughness": {"baseColorFactor": [0.0, 0.0, 0.0, 1.0], "metallicFactor": 0.0},
            "emissiveFactor": [1.0, 0.5, 0.1],
            "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 0.5}}
        });
    });
    assert!(warnings.is_empty(), "{warnings:?}");
    let centre = image.get_pixel(24, 24).0;
    // (0.5, 0.25, 0.05) through Khronos Neutral (0.04 Fresnel floor off) and the sRGB curve.
    let linear = |byte: u8| pom::srgb_to_linear(f32::from(byte) / 255.0);
    assert!((linear(centre[0]) - 0.46).abs() < 0.02, "{centre:?}");
    assert!((linear(centre[1]) - 0.21).abs() < 0.02, "{centre:?}");
    check_golden("gltf_emissive", &image, FlipTolerance::default()).unwrap();
}

#[test]
fn an_unlit_material_shows_its_colour_as_is() {
    let (image, warnings) = quad_from_above("unlit", Light::Sun, |fixture| {
        fixture.json["extensionsUsed"] = json!(["KHR_materials_unlit"]);
        fixture.json["materials"][0] = json!({
            "name": "flat",
            "pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.5, 0.3, 1.0]},
            "extensions": {"KHR_materials_unlit": {}}
        });
    });
    assert!(warnings.is_empty(), "{warnings:?}");
    let pixels: Vec<_> = image.pixels().collect();
    let centre = *image.get_pixel(24, 24);
    // One flat colour wherever the quad is, whatever the sun does.
    assert!(pixels.iter().filter(|p| ***p == centre).count() > 48 * 48 / 2);
    let linear = |byte: u8| pom::srgb_to_linear(f32::from(byte) / 255.0);
    assert!((linear(centre.0[1]) - 0.46).abs() < 0.02, "{centre:?}");
}

#[test]
fn an_alpha_mask_cuts_the_surface_out() {
    let (image, warnings) = quad_from_above("mask", Light::Sun, |fixture| {
        // 4 × 4 checks of 16² texels: alpha 1 and alpha 0.2 (below the cutoff of 0.3). Large
        // checks, so that filtering only blurs their edges.
        let checker = image::RgbaImage::from_fn(64, 64, |x, y| {
            let alpha = if (x / 16 + y / 16) % 2 == 0 { 255 } else { 51 };
            image::Rgba([230, 200, 160, alpha])
        });
        let texture = fixture.add_texture("checker.png", pom_tests::gltf_fixture::png(&checker));
        fixture.json["materials"][0] = json!({
            "name": "lattice",
            "alphaMode": "MASK",
            "alphaCutoff": 0.3,
            "pbrMetallicRoughness": {"baseColorTexture": {"index": texture}, "metallicFactor": 0.0}
        });
    });
    assert!(warnings.is_empty(), "{warnings:?}");
    let background = *image.get_pixel(0, 0);
    // Centres of neighbouring checks (the quad covers pixels 5 to 43, 9.5 per check): two cut
    // out (background), two drawn.
    let holes = [image.get_pixel(19, 10), image.get_pixel(10, 19)];
    let solid = [image.get_pixel(10, 10), image.get_pixel(19, 19)];
    for pixel in holes {
        assert_eq!(*pixel, background);
    }
    for pixel in solid {
        assert_ne!(*pixel, background);
        assert_eq!(pixel.0[3], 255);
    }
    check_golden("gltf_alpha_mask", &image, FlipTolerance::default()).unwrap();
}

#[test]
fn extensions_the_renderer_does_not_honour_are_named_once() {
    let (_, warnings) = quad_from_above("extensions", Light::Sun, |fixture| {
        fixture.json["extensionsUsed"] = json!([
            "KHR_materials_clearcoat",
            "KHR_materials_transmission",
            "KHR_materials_unlit"
        ]);
    });
    assert_eq!(
        warnings,
        [
            "extension KHR_materials_clearcoat is not supported: ignored",
            "extension KHR_materials_transmission is not supported: ignored"
        ]
    );
}

#[test]
fn an_alpha_cutoff_outside_zero_to_one_is_an_error_naming_it() {
    // JSON has no NaN; these are the values a broken exporter writes instead.
    for (name, cutoff) in [("negative", "-0.5"), ("huge", "2.5"), ("overflow", "1e999")] {
        let dir = scratch_dir(&format!("cutoff-{name}"));
        let fixture = GltfFixture::quad(1.0);
        let path = fixture.write(&dir, name);
        let text = std::fs::read_to_string(&path).unwrap().replace(
            r#""name": "surface""#,
            &format!(r#""name": "surface", "alphaMode": "MASK", "alphaCutoff": {cutoff}"#),
        );
        std::fs::write(&path, text).unwrap();
        let mut app = app(8);
        let error = load_gltf(&mut app, &path).unwrap_err().to_string();
        eprintln!("alphaCutoff {cutoff}: {error}");
        assert!(error.contains(&format!("{name}.gltf")), "{error}");
        assert!(
            error.contains("alphaCutoff")
                || error.contains("alpha_cutoff")
                || error.contains("number"),
            "{error}"
        );
        assert!(app.world.is_empty(), "nothing half-loaded stays");
    }
}

/// A parallax wall (the cobblestone-like raised block) seen at an angle, with or without a
/// half-transparent blue pane from a glTF file floating in front of it.
fn wall_behind_a_pane(pane: bool) -> image::RgbaImage {
    use pom_tests::pom_scene::HeightMaterial;
    let mut app = app(64);
    app.finish().unwrap();
    let textures = HeightMaterial {
        field: pom::patterns::bricks(128, 4.0, 8.0),
        height_scale: 0.06,
    };
    let wall = textures.material(&mut app);
    let plane = app
        .resources
        .get_mut::<pom::Assets<pom::Mesh>>()
        .unwrap()
        .add(pom::Mesh::plane(2.0));
    app.world.spawn((plane, wall, Transform::IDENTITY));
    if pane {
        let dir = scratch_dir("blend-pane");
        let mut fixture = GltfFixture::quad(1.2);
        fixture.json["materials"][0] = json!({
            "name": "glass",
            "alphaMode": "BLEND",
            "doubleSided": true,
            "pbrMetallicRoughness": {
                "baseColorFactor": [0.1, 0.35, 1.0, 0.45],
                "metallicFactor": 0.0
            }
        });
        fixture.json["nodes"][0]["translation"] = json!([0.0, 0.3, 0.0]);
        let scene = load_gltf(&mut app, fixture.write(&dir, "pane")).unwrap();
        assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    }
    app.world.spawn((
        Camera::perspective(45.0),
        Transform::from_xyz(0.0, 1.8, 1.2).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    app.world.spawn((
        DirectionalLight::default(),
        Transform::IDENTITY.looking_at(Vec3::new(0.5, -1.0, -0.4), Vec3::Y),
    ));
    render_both_paths(&mut app, "gltf_wall_behind_a_pane").unwrap()
}

#[test]
fn a_blended_pane_shows_the_parallax_wall_through_it() {
    let bare = wall_behind_a_pane(false);
    let glazed = wall_behind_a_pane(true);
    // The centre 16 × 16 pixels lie under the pane.
    let region = |image: &image::RgbaImage| -> Vec<[f32; 3]> {
        (24..40)
            .flat_map(|y| (24..40).map(move |x| (x, y)))
            .map(|(x, y)| {
                let p = image.get_pixel(x, y).0;
                [f32::from(p[0]), f32::from(p[1]), f32::from(p[2])]
            })
            .collect()
    };
    let spread = |pixels: &[[f32; 3]]| {
        let luma: Vec<f32> = pixels
            .iter()
            .map(|p| 0.3 * p[0] + 0.6 * p[1] + 0.1 * p[2])
            .collect();
        let mean = luma.iter().sum::<f32>() / luma.len() as f32;
        (luma.iter().map(|l| (l - mean).powi(2)).sum::<f32>() / luma.len() as f32).sqrt()
    };
    let mean = |pixels: &[[f32; 3]], channel: usize| {
        pixels.iter().map(|p| p[channel]).sum::<f32>() / pixels.len() as f32
    };
    let (under, clear) = (region(&glazed), region(&bare));
    eprintln!(
        "bricks: spread {:.1} bare, {:.1} through the pane; blue − red {:.1} bare, {:.1} through it",
        spread(&clear),
        spread(&under),
        mean(&clear, 2) - mean(&clear, 0),
        mean(&under, 2) - mean(&under, 0)
    );
    // Tinted blue, and the relief still shows through: more than a third of its contrast.
    assert!(mean(&under, 2) - mean(&under, 0) > mean(&clear, 2) - mean(&clear, 0) + 30.0);
    assert!(spread(&under) > spread(&clear) / 3.0 && spread(&clear) > 5.0);
    // Opaque where the wall is: the pane keeps the pixel's alpha.
    assert!(glazed.pixels().all(|p| p.0[3] == 255));
    check_golden("gltf_blended_pane", &glazed, FlipTolerance::default()).unwrap();
}

/// The unlit quad with a 2 × 2 texture (red, green / blue, white) under `sampler`.
fn sampled_quad(name: &str, sampler: serde_json::Value) -> (image::RgbaImage, Vec<String>) {
    quad_from_above(name, Light::Dark, |fixture| {
        let texels = image::RgbaImage::from_fn(2, 2, |x, y| match (x, y) {
            (0, 0) => image::Rgba([255, 0, 0, 255]),
            (1, 0) => image::Rgba([0, 255, 0, 255]),
            (0, 1) => image::Rgba([0, 0, 255, 255]),
            _ => image::Rgba([255, 255, 255, 255]),
        });
        let texture = fixture.add_texture("texels.png", pom_tests::gltf_fixture::png(&texels));
        fixture.json["extensionsUsed"] = json!(["KHR_materials_unlit"]);
        fixture.json["materials"][0] = json!({
            "name": "texels",
            "pbrMetallicRoughness": {"baseColorTexture": {"index": texture}},
            "extensions": {"KHR_materials_unlit": {}}
        });
        fixture.json["samplers"] = json!([sampler]);
        fixture.json["textures"][texture]["sampler"] = json!(0);
    })
}

#[test]
fn a_gltf_sampler_is_honoured() {
    let distinct = |image: &image::RgbaImage| {
        let mut colours: Vec<[u8; 4]> = image.pixels().map(|p| p.0).collect();
        colours.sort_unstable();
        colours.dedup();
        colours.len()
    };
    // Nearest: four flat quadrants (and the background).
    let (nearest, warnings) = sampled_quad(
        "nearest",
        json!({"magFilter": 9728, "minFilter": 9728, "wrapS": 33071, "wrapT": 33071}),
    );
    assert!(warnings.is_empty(), "{warnings:?}");
    assert!(distinct(&nearest) <= 5, "{} colours", distinct(&nearest));
    // (Khronos Neutral rolls pure red off to (241, 33, 33).)
    let red = nearest.get_pixel(12, 12).0;
    assert!(red[0] > 200 && red[1] < 60 && red[2] < 60, "{red:?}");
    assert!(nearest.get_pixel(36, 36).0[..3].iter().all(|&c| c > 230));
    // Linear (the default): blended texels, many colours.
    let (linear, _) = sampled_quad("linear", json!({}));
    assert!(distinct(&linear) > 50, "{} colours", distinct(&linear));
    check_golden("gltf_sampler_nearest", &nearest, FlipTolerance::default()).unwrap();
}

#[test]
fn a_sampler_with_an_invalid_wrap_mode_is_an_error_naming_the_file() {
    let dir = scratch_dir("bad-wrap");
    let mut fixture = GltfFixture::quad(1.0);
    let texture = fixture.add_texture(
        "texel.png",
        pom_tests::gltf_fixture::png(&image::RgbaImage::from_pixel(1, 1, image::Rgba([9; 4]))),
    );
    fixture.json["materials"][0] = json!({
        "name": "surface",
        "pbrMetallicRoughness": {"baseColorTexture": {"index": texture}}
    });
    fixture.json["samplers"] = json!([{"wrapS": 12345}]);
    fixture.json["textures"][texture]["sampler"] = json!(0);
    let mut app = app(8);
    let error = load_gltf(&mut app, fixture.write(&dir, "bad_wrap"))
        .unwrap_err()
        .to_string();
    eprintln!("{error}");
    assert!(error.contains("bad_wrap.gltf"), "{error}");
    assert!(error.contains("wrapS"), "{error}");
    assert!(app.world.is_empty());
}

#[test]
fn the_metallic_roughness_texture_sets_metalness_and_roughness_per_texel() {
    // 2 × 2 texels, sampled nearest: roughness in green, metalness in blue (red is unused and
    // full, so a shader reading the wrong channel makes everything a metal):
    //   rough metal  | rough dielectric
    //   smooth metal | smooth dielectric
    let (image, warnings) = quad_from_above("metallic-roughness", Light::Sun, |fixture| {
        let texels = image::RgbaImage::from_fn(2, 2, |x, y| {
            let roughness = if y == 0 { 255 } else { 77 };
            let metal = if x == 0 { 255 } else { 0 };
            image::Rgba([255, roughness, metal, 255])
        });
        let png = pom_tests::gltf_fixture::png(&texels);
        let texture = fixture.add_texture("metallic_roughness.png", png);
        fixture.json["materials"][0] = json!({
            "name": "painted metal",
            "pbrMetallicRoughness": {
                "baseColorFactor": [0.8, 0.3, 0.1, 1.0],
                "metallicRoughnessTexture": {"index": texture}
            }
        });
        fixture.json["samplers"] = json!([{"magFilter": 9728, "minFilter": 9728}]);
        fixture.json["textures"][texture]["sampler"] = json!(0);
    });
    assert!(warnings.is_empty(), "{warnings:?}");
    let red = |x, y| pom::srgb_to_linear(f32::from(image.get_pixel(x, y).0[0]) / 255.0);
    let (rough_metal, rough_dielectric) = (red(14, 14), red(34, 14));
    let (smooth_metal, smooth_dielectric) = (red(14, 34), red(34, 34));
    eprintln!(
        "rough metal {rough_metal:.3}, rough dielectric {rough_dielectric:.3}, \
         smooth metal {smooth_metal:.3}, smooth dielectric {smooth_dielectric:.3}"
    );
    // Seen and lit head-on, a fully rough metal reflects a quarter of its colour (GGX at
    // roughness 1), a dielectric its diffuse colour.
    assert!(rough_metal < 0.4 * rough_dielectric, "metalness ignored");
    // The mirror direction is the camera's: a smooth lobe is far brighter there.
    assert!(smooth_metal > 2.5 * rough_metal, "roughness ignored");
    assert!(smooth_dielectric > rough_dielectric, "roughness ignored");
    check_golden("gltf_metallic_roughness", &image, FlipTolerance::default()).unwrap();
}

#[test]
fn occlusion_darkens_the_ambient_light_only() {
    // A 2 × 2 occlusion map (open, closed / closed, open), sampled nearest.
    let render = |name: &str, light: Light, strength: f32| {
        let (image, warnings) = quad_from_above(name, light, |fixture| {
            let occlusion = image::RgbaImage::from_fn(2, 2, |x, y| {
                let open = if (x + y) % 2 == 0 { 255 } else { 0 };
                image::Rgba([open, open, open, 255])
            });
            let png = pom_tests::gltf_fixture::png(&occlusion);
            let texture = fixture.add_texture("occlusion.png", png);
            fixture.json["materials"][0] = json!({
                "name": "grey",
                "pbrMetallicRoughness": {"metallicFactor": 0.0},
                "occlusionTexture": {"index": texture, "strength": strength}
            });
            fixture.json["samplers"] = json!([{"magFilter": 9728, "minFilter": 9728}]);
            fixture.json["textures"][texture]["sampler"] = json!(0);
        });
        assert!(warnings.is_empty(), "{warnings:?}");
        image
    };
    let luminance = |image: &image::RgbaImage, x, y| {
        let p: [u8; 4] = image.get_pixel(x, y).0;
        pom::srgb_to_linear(f32::from(p[1]) / 255.0)
    };
    // Ambient light only: closed checks go dark, half as dark at strength 0.5.
    let ambient = render("occlusion-ambient", Light::Ambient, 1.0);
    let (open, closed) = (luminance(&ambient, 12, 12), luminance(&ambient, 36, 12));
    assert!(open > 0.3 && closed < 0.01, "open {open}, closed {closed}");
    let half = render("occlusion-half", Light::Ambient, 0.5);
    let half_closed = luminance(&half, 36, 12);
    assert!(
        (half_closed / open - 0.5).abs() < 0.08,
        "{half_closed} vs {open}"
    );
    // Direct light is not occluded: open and closed checks look the same in the sun.
    let sun = render("occlusion-sun", Light::Sun, 1.0);
    let (open, closed) = (sun.get_pixel(12, 12).0, sun.get_pixel(36, 12).0);
    assert!(open[1].abs_diff(closed[1]) <= 2, "{open:?} vs {closed:?}");
    check_golden("gltf_occlusion_ambient", &ambient, FlipTolerance::default()).unwrap();
}
