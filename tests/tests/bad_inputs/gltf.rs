//! glTF files: missing buffers, bad indices and accessors, missing attributes, bad modes and extras.

use super::*;

fn gltf_error(file: &str) -> GltfError {
    let mut app = pom_app(8, TargetFormat::Float32).unwrap();
    let error = load_gltf(&mut app, corpus(file)).unwrap_err();
    let name = Path::new(file).file_name().unwrap().to_str().unwrap();
    assert!(error.to_string().contains(name), "{error}");
    assert_eq!(app.world.len(), 0, "nothing half-loaded is left behind");
    error
}

fn assert_mesh_error(file: &str, reason: &str) {
    match gltf_error(file) {
        GltfError::Mesh {
            mesh,
            primitive: 0,
            reason: said,
            ..
        } => {
            assert_eq!(mesh, "\"quad\" (#0)");
            assert!(said.contains(reason), "{said}");
        }
        other => panic!("{file}: expected GltfError::Mesh, got {other:?}"),
    }
}

fn assert_open_error(file: &str, reason: &str) {
    match gltf_error(file) {
        GltfError::Open { reason: said, .. } => assert!(said.contains(reason), "{said}"),
        other => panic!("{file}: expected GltfError::Open, got {other:?}"),
    }
}

fn assert_material_error(file: &str, reason: &str) {
    match gltf_error(file) {
        GltfError::Material {
            material,
            reason: said,
            ..
        } => {
            assert_eq!(material, "\"surface\" (#0)");
            assert!(said.contains(reason), "{said}");
        }
        other => panic!("{file}: expected GltfError::Material, got {other:?}"),
    }
}

/// Loads `file` next to the preview plane and renders; returns the load's warnings.
fn gltf_renders(file: &str) -> Vec<String> {
    let mut app = material_app(|_| ParallaxOcclusionMaterial::default());
    let scene = load_gltf(&mut app, corpus(file)).unwrap();
    assert!(!scene.entities.is_empty());
    renders_cleanly(&mut app);
    scene.warnings
}

fn only_mesh(app: &App) -> pom::Mesh {
    let meshes = app.resources.get::<Assets<pom::Mesh>>().unwrap();
    let mut handles = app.world.query::<&pom::Handle<pom::Mesh>>();
    let handles: Vec<_> = handles.iter().cloned().collect();
    // The preview plane is the first mesh; the file's is the last.
    meshes.get(handles.last().unwrap().id()).unwrap().clone()
}

#[test]
fn gltf_missing_buffer_file() {
    match gltf_error("gltf/missing_buffer.gltf") {
        GltfError::Buffer {
            index: 0, reason, ..
        } => {
            assert!(reason.contains("absent.bin"), "{reason}")
        }
        other => panic!("expected GltfError::Buffer, got {other:?}"),
    }
}

#[test]
fn gltf_buffer_shorter_than_declared() {
    match gltf_error("gltf/short_buffer.gltf") {
        GltfError::Buffer {
            index: 0, reason, ..
        } => {
            assert!(reason.contains("bytes but declares"), "{reason}")
        }
        other => panic!("expected GltfError::Buffer, got {other:?}"),
    }
}

#[test]
fn gltf_index_out_of_range() {
    assert_mesh_error(
        "gltf/index_out_of_range.gltf",
        "index 40 at position 5 is out of range for 4 vertices",
    );
}

#[test]
fn gltf_accessor_past_its_buffer() {
    assert_open_error(
        "gltf/accessor_past_buffer.gltf",
        "accessor 0: 400 elements run past the 48 bytes of its buffer view",
    );
}

#[test]
fn gltf_nan_positions() {
    assert_mesh_error("gltf/nan_positions.gltf", "position 1 is not finite");
}

#[test]
fn gltf_infinite_positions() {
    assert_mesh_error("gltf/infinite_positions.gltf", "position 1 is not finite");
}

#[test]
fn gltf_without_positions() {
    assert_open_error(
        "gltf/no_positions.gltf",
        "attributes[\"POSITION\"]: Missing data",
    );
}

#[test]
fn gltf_without_normals_gets_flat_normals() {
    assert!(gltf_renders("gltf/no_normals.gltf").is_empty());
    let mut app = pom_app(8, TargetFormat::Float32).unwrap();
    load_gltf(&mut app, corpus("gltf/no_normals.gltf")).unwrap();
    let mesh = only_mesh(&app);
    assert!(
        mesh.normals.iter().all(|n| n[1] > 0.999),
        "{:?}",
        mesh.normals
    );
}

#[test]
fn gltf_without_uvs_gets_zero_uvs() {
    assert!(gltf_renders("gltf/no_uvs.gltf").is_empty());
    let mut app = pom_app(8, TargetFormat::Float32).unwrap();
    load_gltf(&mut app, corpus("gltf/no_uvs.gltf")).unwrap();
    assert!(only_mesh(&app).uvs.iter().all(|uv| *uv == [0.0, 0.0]));
}

#[test]
fn gltf_without_tangents_gets_generated_ones() {
    assert!(gltf_renders("gltf/no_tangents.gltf").is_empty());
    let mut app = pom_app(8, TargetFormat::Float32).unwrap();
    load_gltf(&mut app, corpus("gltf/no_tangents.gltf")).unwrap();
    let mesh = only_mesh(&app);
    assert_eq!(mesh.tangents.len(), mesh.positions.len());
    assert!(mesh.tangents.iter().flatten().all(|c| c.is_finite()));
}

#[test]
fn gltf_degenerate_triangles() {
    assert!(gltf_renders("gltf/degenerate_triangles.gltf").is_empty());
}

#[test]
fn gltf_all_vertices_at_one_point() {
    assert!(gltf_renders("gltf/all_vertices_at_one_point.gltf").is_empty());
    let mut app = pom_app(8, TargetFormat::Float32).unwrap();
    load_gltf(&mut app, corpus("gltf/all_vertices_at_one_point.gltf")).unwrap();
    let mesh = only_mesh(&app);
    assert!(mesh.normals.iter().flatten().all(|c| c.is_finite()));
    assert!(mesh.tangents.iter().flatten().all(|c| c.is_finite()));
}

#[test]
fn gltf_points_mode_is_skipped_with_a_warning() {
    let warnings = gltf_renders("gltf/points_mode.gltf");
    assert_eq!(
        warnings,
        ["mesh \"quad\" (#0), primitive 0: mode Points is not supported; skipped"]
    );
}

#[test]
fn gltf_lines_mode_is_skipped_with_a_warning() {
    let warnings = gltf_renders("gltf/lines_mode.gltf");
    assert_eq!(
        warnings,
        ["mesh \"quad\" (#0), primitive 0: mode Lines is not supported; skipped"]
    );
}

#[test]
fn gltf_invalid_primitive_mode() {
    assert_open_error(
        "gltf/invalid_mode.gltf",
        "meshes[0].primitives[0].mode: Invalid value",
    );
}

#[test]
fn gltf_extras_unknown_key() {
    assert_material_error(
        "gltf/extras_unknown_key.gltf",
        "extras.pom: unknown field `hieght_scale`",
    );
}

#[test]
fn gltf_extras_wrong_type() {
    assert_material_error(
        "gltf/extras_wrong_type.gltf",
        "extras.pom.min_samples: invalid type: string \"many\", expected u32",
    );
}

#[test]
fn gltf_extras_unknown_method() {
    assert_material_error(
        "gltf/extras_unknown_method.gltf",
        "extras.pom.method is \"magic\"; expected one of",
    );
}

#[test]
fn gltf_extras_unknown_silhouette() {
    assert_material_error(
        "gltf/extras_unknown_silhouette.gltf",
        "extras.pom.silhouette is \"outline\"; expected one of off, uv_bounds",
    );
}

#[test]
fn gltf_extras_height_texture_out_of_range() {
    assert_material_error(
        "gltf/extras_missing_texture.gltf",
        "extras.pom.height_texture is 7 but the file has 0 textures",
    );
}

#[test]
fn gltf_extras_without_a_height() {
    assert_material_error(
        "gltf/extras_no_height.gltf",
        "extras.pom needs height_texture (or height_in_normal_alpha: true)",
    );
}

#[test]
fn gltf_extras_negative_height_scale() {
    assert_material_error("gltf/extras_negative_height.gltf", "height_scale");
}

#[test]
fn gltf_extras_min_samples_over_max() {
    assert_material_error(
        "gltf/extras_min_over_max.gltf",
        "min_samples (9) is greater than max_samples (3)",
    );
}

#[test]
fn gltf_missing_image_file() {
    match gltf_error("gltf/missing_image.gltf") {
        GltfError::Image { image, reason, .. } => {
            assert_eq!(image, "#0");
            assert!(reason.contains("No such file"), "{reason}");
            // The URI as written and the path it was looked for at.
            let tried = corpus("gltf/absent.png");
            assert!(
                reason.contains(&format!("uri \"absent.png\": {}", tried.display())),
                "{reason}"
            );
        }
        other => panic!("expected GltfError::Image, got {other:?}"),
    }
}

#[test]
fn gltf_without_a_scene() {
    let error = gltf_error("gltf/no_scene.gltf");
    assert!(matches!(error, GltfError::NoScene { .. }), "{error:?}");
}

#[test]
fn gltf_default_scene_out_of_range() {
    assert_open_error("gltf/scene_out_of_range.gltf", "scene");
}

#[test]
fn gltf_node_that_is_its_own_child() {
    assert_open_error(
        "gltf/node_is_its_own_child.gltf",
        "node \"quad\" (#0) is reached twice",
    );
}

#[test]
fn gltf_zero_byte_file() {
    assert_open_error("gltf/empty.gltf", "EOF while parsing");
}

#[test]
fn gltf_broken_json() {
    assert_open_error("gltf/not_json.gltf", "EOF while parsing");
}

#[test]
fn gltf_truncated_glb() {
    let error = gltf_error("gltf/truncated.glb");
    assert!(matches!(error, GltfError::Open { .. }), "{error:?}");
}

#[test]
fn gltf_missing_file() {
    assert_open_error("gltf/no_such_scene.gltf", "No such file");
}

#[test]
fn gltf_color_of_two_components() {
    assert_open_error(
        "gltf/color_vec2.gltf",
        "mesh 0, primitive 0: COLOR_0 (accessor 4) must be Vec3 or Vec4 of [F32, U8, U16]",
    );
}

#[test]
fn gltf_camera_without_the_projection_its_type_names() {
    assert_open_error(
        "gltf/camera_type_mismatch.gltf",
        "camera 0: its type is perspective but it has no `perspective` object",
    );
}

/// Nodes that use one mesh share one copy of it (and so its GPU buffers, drawn as instances):
/// a small file of many nodes on one mesh cannot ask for a copy per node.
#[test]
fn gltf_nodes_sharing_a_mesh_share_one_copy_of_it() {
    let mut json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(corpus("gltf/no_uvs.gltf")).unwrap())
            .unwrap();
    let nodes: Vec<serde_json::Value> = (0..1000)
        .map(|index| serde_json::json!({"mesh": 0, "translation": [index as f32, 0.0, 0.0]}))
        .collect();
    json["scenes"][0]["nodes"] = (0..1000).collect::<Vec<u32>>().into();
    json["nodes"] = nodes.into();
    let dir = std::env::temp_dir().join(format!("pom-gltf-shared-mesh-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("many_nodes.gltf");
    std::fs::write(&path, json.to_string()).unwrap();
    let mut app = pom_app(8, TargetFormat::Float32).unwrap();
    let scene = load_gltf(&mut app, &path).unwrap();
    assert_eq!(scene.entities.len(), 1000);
    assert_eq!(app.resources.get::<Assets<pom::Mesh>>().unwrap().len(), 1);
    let ids: std::collections::HashSet<_> = app
        .world
        .query::<&pom::Handle<pom::Mesh>>()
        .iter()
        .map(|handle| handle.id())
        .collect();
    assert_eq!(ids.len(), 1);
    // The framing box still spans every node's copy.
    let (min, max) = scene.framing_bounds.unwrap();
    assert!(max.x - min.x > 999.0, "{min} {max}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A primitive without normals gets three vertices of its own per triangle: 33.5 MB of byte
/// indices would decode to 33.5 million vertices (over 2 GB). Refused from the accessors'
/// counts before anything is decoded.
#[test]
fn gltf_decoding_to_more_vertices_than_the_limit_is_refused_before_decoding() {
    let indices = pom::MAX_GLTF_VERTICES + 1;
    let buffer_bytes = 12 + indices;
    let gltf = serde_json::json!({
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"name": "heap", "mesh": 0}],
        "meshes": [{"name": "heap", "primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 1, "type": "VEC3",
             "min": [0.0, 0.0, 0.0], "max": [0.0, 0.0, 0.0]},
            {"bufferView": 1, "componentType": 5121, "count": indices, "type": "SCALAR"}
        ],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": 12},
            {"buffer": 0, "byteOffset": 12, "byteLength": indices}
        ],
        "buffers": [{"uri": "heap.bin", "byteLength": buffer_bytes}]
    });
    let dir = std::env::temp_dir().join(format!("pom-gltf-vertex-limit-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = std::fs::File::create(dir.join("heap.bin")).unwrap();
    file.set_len(buffer_bytes).unwrap();
    std::fs::write(dir.join("heap.gltf"), gltf.to_string()).unwrap();
    let mut app = pom_app(8, TargetFormat::Float32).unwrap();
    match load_gltf(&mut app, dir.join("heap.gltf")) {
        Err(GltfError::Mesh { mesh, reason, .. }) => {
            assert_eq!(mesh, "\"heap\" (#0)");
            assert!(
                reason.contains(&format!(
                    "decode to {indices} vertices by here, over the limit of {}",
                    pom::MAX_GLTF_VERTICES
                )),
                "{reason}"
            );
        }
        other => panic!("expected GltfError::Mesh, got {other:?}"),
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
