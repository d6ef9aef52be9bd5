//! Small glTF files written by the tests: a textured quad whose every part can be changed or
//! broken on purpose.

use std::path::{Path, PathBuf};

use serde_json::{Value, json};

/// A one-quad glTF document with its binary buffer, ready to modify and write.
pub struct GltfFixture {
    /// The JSON document.
    pub json: Value,
    /// The bytes of buffer 0.
    pub bin: Vec<u8>,
    /// Image files to write next to the document: (file name, PNG bytes).
    pub images: Vec<(String, Vec<u8>)>,
}

fn push_f32s(bin: &mut Vec<u8>, values: &[f32]) -> (usize, usize) {
    let offset = bin.len();
    for value in values {
        bin.extend_from_slice(&value.to_le_bytes());
    }
    (offset, bin.len() - offset)
}

impl GltfFixture {
    /// A `size`×`size` quad in the XZ plane facing +Y with normals, UVs (0..1), tangents
    /// (Blender-style: w such that cross(n, t) × w points up the image) and u16 indices,
    /// on one node, with material 0 (an empty material).
    pub fn quad(size: f32) -> Self {
        let h = size / 2.0;
        let mut bin = Vec::new();
        let positions = push_f32s(&mut bin, &[-h, 0.0, -h, -h, 0.0, h, h, 0.0, h, h, 0.0, -h]);
        let normals = push_f32s(&mut bin, &[0.0, 1.0, 0.0].repeat(4));
        let uvs = push_f32s(&mut bin, &[0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0, 0.0]);
        let tangents = push_f32s(&mut bin, &[1.0, 0.0, 0.0, 1.0].repeat(4));
        let index_offset = bin.len();
        for index in [0_u16, 1, 2, 0, 2, 3] {
            bin.extend_from_slice(&index.to_le_bytes());
        }
        let view = |(offset, length): (usize, usize)| json!({"buffer": 0, "byteOffset": offset, "byteLength": length});
        let json = json!({
            "asset": {"version": "2.0"},
            "scene": 0,
            "scenes": [{"nodes": [0]}],
            "nodes": [{"name": "quad", "mesh": 0}],
            "meshes": [{"name": "quad", "primitives": [{
                "attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2, "TANGENT": 3},
                "indices": 4,
                "material": 0
            }]}],
            // A white dielectric (glTF's default material would be a rough metal).
            "materials": [{"name": "surface", "pbrMetallicRoughness": {"metallicFactor": 0.0}}],
            "accessors": [
                {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-h, 0.0, -h], "max": [h, 0.0, h]},
                {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
                {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"},
                {"bufferView": 3, "componentType": 5126, "count": 4, "type": "VEC4"},
                {"bufferView": 4, "componentType": 5123, "count": 6, "type": "SCALAR"}
            ],
            "bufferViews": [view(positions), view(normals), view(uvs), view(tangents), view((index_offset, 12))],
            "buffers": [{"uri": "quad.bin", "byteLength": bin.len()}]
        });
        Self {
            json,
            bin,
            images: Vec::new(),
        }
    }

    /// Adds a PNG file as an image and a texture; returns the texture's index.
    pub fn add_texture(&mut self, file: &str, png: Vec<u8>) -> usize {
        let images = self.json["images"].as_array().map_or(0, Vec::len);
        let json = self
            .json
            .as_object_mut()
            .expect("the document is an object");
        json.entry("images")
            .or_insert_with(|| json!([]))
            .as_array_mut()
            .expect("array")
            .push(json!({"uri": file}));
        let textures = json.entry("textures").or_insert_with(|| json!([]));
        let textures = textures.as_array_mut().expect("array");
        textures.push(json!({"source": images}));
        self.images.push((file.to_owned(), png));
        textures.len() - 1
    }

    /// Gives the quad's four vertices the RGBA colours `colors` (`COLOR_0`, floats).
    pub fn add_vertex_colors(&mut self, colors: [[f32; 4]; 4]) {
        let (offset, length) = push_f32s(&mut self.bin, colors.as_flattened());
        let views = self.json["bufferViews"].as_array_mut().expect("array");
        views.push(json!({"buffer": 0, "byteOffset": offset, "byteLength": length}));
        let view = views.len() - 1;
        let accessors = self.json["accessors"].as_array_mut().expect("array");
        accessors
            .push(json!({"bufferView": view, "componentType": 5126, "count": 4, "type": "VEC4"}));
        let accessor = accessors.len() - 1;
        self.json["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"] = json!(accessor);
        self.json["buffers"][0]["byteLength"] = json!(self.bin.len());
    }

    /// Writes `NAME.gltf`, `quad.bin` and the images into `dir`; returns the document's path.
    pub fn write(&self, dir: &Path, name: &str) -> PathBuf {
        std::fs::create_dir_all(dir).expect("test directory");
        std::fs::write(dir.join("quad.bin"), &self.bin).expect("write buffer");
        for (file, png) in &self.images {
            std::fs::write(dir.join(file), png).expect("write image");
        }
        let path = dir.join(format!("{name}.gltf"));
        std::fs::write(&path, serde_json::to_vec_pretty(&self.json).expect("json"))
            .expect("write gltf");
        path
    }

    /// Writes a binary `NAME.glb` holding the document and the buffer (images must be none).
    pub fn write_glb(&self, dir: &Path, name: &str) -> PathBuf {
        assert!(self.images.is_empty(), "GLB fixtures carry no image files");
        let mut json = self.json.clone();
        json["buffers"] = json!([{"byteLength": self.bin.len()}]);
        let mut json_bytes = serde_json::to_vec(&json).expect("json");
        while !json_bytes.len().is_multiple_of(4) {
            json_bytes.push(b' ');
        }
        let mut bin = self.bin.clone();
        while !bin.len().is_multiple_of(4) {
            bin.push(0);
        }
        let total = 12 + 8 + json_bytes.len() + 8 + bin.len();
        let mut glb = Vec::with_capacity(total);
        glb.extend_from_slice(b"glTF");
        glb.extend_from_slice(&2_u32.to_le_bytes());
        glb.extend_from_slice(&(total as u32).to_le_bytes());
        glb.extend_from_slice(&(json_bytes.len() as u32).to_le_bytes());
        glb.extend_from_slice(b"JSON");
        glb.extend_from_slice(&json_bytes);
        glb.extend_from_slice(&(bin.len() as u32).to_le_bytes());
        glb.extend_from_slice(b"BIN\0");
        glb.extend_from_slice(&bin);
        std::fs::create_dir_all(dir).expect("test directory");
        let path = dir.join(format!("{name}.glb"));
        std::fs::write(&path, glb).expect("write glb");
        path
    }
}

/// PNG bytes of an image.
pub fn png<P: image::PixelWithColorType>(image: &image::ImageBuffer<P, Vec<P::Subpixel>>) -> Vec<u8>
where
    [P::Subpixel]: image::EncodableLayout,
{
    let mut bytes = std::io::Cursor::new(Vec::new());
    image
        .write_to(&mut bytes, image::ImageFormat::Png)
        .expect("encode png");
    bytes.into_inner()
}

/// A fresh, empty directory for one test.
pub fn scratch_dir(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("pom-gltf-{test}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("test directory");
    dir
}

impl GltfFixture {
    /// Writes the fixture as `test` in a scratch folder, loads it into `app` and returns the
    /// error message, which must name `needle`.
    pub fn load_error(&self, app: &mut pom::App, test: &str, needle: &str) -> String {
        let dir = scratch_dir(test);
        let error = pom::load_gltf(app, self.write(&dir, test))
            .expect_err("the file must not load")
            .to_string();
        assert!(
            error.contains(needle),
            "{error:?} should mention {needle:?}"
        );
        error
    }
}
