//! A minimal glTF 2.0 binary writer: meshes, PNG textures, materials with POM extras, nodes,
//! cameras and lights.

use serde_json::{Value, json};

/// A glTF document under construction with its single binary buffer.
#[derive(Default)]
pub struct GlbBuilder {
    bin: Vec<u8>,
    buffer_views: Vec<Value>,
    accessors: Vec<Value>,
    scene_extras: Option<Value>,
    images: Vec<Value>,
    textures: Vec<Value>,
    materials: Vec<Value>,
    meshes: Vec<Value>,
    nodes: Vec<Value>,
    cameras: Vec<Value>,
    lights: Vec<Value>,
}

impl GlbBuilder {
    fn view(&mut self, bytes: &[u8], target: Option<u32>) -> usize {
        while !self.bin.len().is_multiple_of(4) {
            self.bin.push(0);
        }
        let mut view =
            json!({"buffer": 0, "byteOffset": self.bin.len(), "byteLength": bytes.len()});
        if let Some(target) = target {
            view["target"] = json!(target);
        }
        self.bin.extend_from_slice(bytes);
        self.buffer_views.push(view);
        self.buffer_views.len() - 1
    }

    fn accessor(&mut self, floats: &[f32], kind: &str, components: usize, bounds: bool) -> usize {
        let bytes: Vec<u8> = floats.iter().flat_map(|v| v.to_le_bytes()).collect();
        let view = self.view(&bytes, Some(34962));
        let mut accessor = json!({
            "bufferView": view, "componentType": 5126, "count": floats.len() / components, "type": kind
        });
        if bounds {
            let (mut min, mut max) = (vec![f32::MAX; components], vec![f32::MIN; components]);
            for chunk in floats.chunks_exact(components) {
                for (k, value) in chunk.iter().enumerate() {
                    min[k] = min[k].min(*value);
                    max[k] = max[k].max(*value);
                }
            }
            accessor["min"] = json!(min);
            accessor["max"] = json!(max);
        }
        self.accessors.push(accessor);
        self.accessors.len() - 1
    }

    /// Adds a mesh of one triangle primitive (no tangents: loaders make MikkTSpace ones).
    pub fn mesh(&mut self, name: &str, mesh: &pom::Mesh, material: usize) -> usize {
        let flat = |v: &[[f32; 3]]| v.iter().flatten().copied().collect::<Vec<f32>>();
        let position = self.accessor(&flat(&mesh.positions), "VEC3", 3, true);
        let normal = self.accessor(&flat(&mesh.normals), "VEC3", 3, false);
        let uv_floats: Vec<f32> = mesh.uvs.iter().flatten().copied().collect();
        let uv = self.accessor(&uv_floats, "VEC2", 2, false);
        let index_bytes: Vec<u8> = mesh.indices.iter().flat_map(|i| i.to_le_bytes()).collect();
        let index_view = self.view(&index_bytes, Some(34963));
        self.accessors.push(json!({
            "bufferView": index_view, "componentType": 5125, "count": mesh.indices.len(), "type": "SCALAR"
        }));
        let indices = self.accessors.len() - 1;
        self.meshes.push(json!({"name": name, "primitives": [{
            "attributes": {"POSITION": position, "NORMAL": normal, "TEXCOORD_0": uv},
            "indices": indices, "material": material
        }]}));
        self.meshes.len() - 1
    }

    /// Embeds a PNG; returns its texture index.
    pub fn texture(&mut self, name: &str, png: &[u8]) -> usize {
        let view = self.view(png, None);
        self.images
            .push(json!({"name": name, "bufferView": view, "mimeType": "image/png"}));
        self.textures.push(json!({"source": self.images.len() - 1}));
        self.textures.len() - 1
    }

    /// Adds a material; returns its index.
    pub fn material(&mut self, material: Value) -> usize {
        self.materials.push(material);
        self.materials.len() - 1
    }

    /// Adds a root node; returns its index.
    pub fn node(&mut self, node: Value) -> usize {
        self.nodes.push(node);
        self.nodes.len() - 1
    }

    /// Adds a perspective camera, with `exposure` (EV100) in its `extras.pom` where given;
    /// returns its index.
    pub fn camera(&mut self, yfov: f32, exposure: Option<f32>) -> usize {
        let mut camera = json!({"type": "perspective", "perspective": {"yfov": yfov, "znear": 0.05, "zfar": 100.0}});
        if let Some(exposure) = exposure {
            camera["extras"] = json!({"pom": {"exposure": exposure}});
        }
        self.cameras.push(camera);
        self.cameras.len() - 1
    }

    /// Sets the scene's `extras`.
    pub fn scene_extras(&mut self, extras: Value) {
        self.scene_extras = Some(extras);
    }

    /// Adds a `KHR_lights_punctual` light; returns its index.
    pub fn light(&mut self, light: Value) -> usize {
        self.lights.push(light);
        self.lights.len() - 1
    }

    /// The finished `.glb` bytes; every node is a root of the one scene.
    pub fn finish(mut self) -> Vec<u8> {
        while !self.bin.len().is_multiple_of(4) {
            self.bin.push(0);
        }
        let mut scene =
            json!({"name": "street corner", "nodes": (0..self.nodes.len()).collect::<Vec<_>>()});
        if let Some(extras) = self.scene_extras.take() {
            scene["extras"] = extras;
        }
        let document = json!({
            "asset": {"version": "2.0", "generator": "pom sandbox generate-assets"},
            "extensionsUsed": ["KHR_lights_punctual"],
            "extensions": {"KHR_lights_punctual": {"lights": self.lights}},
            "scene": 0,
            "scenes": [scene],
            "nodes": self.nodes,
            "meshes": self.meshes,
            "materials": self.materials,
            "textures": self.textures,
            "images": self.images,
            "cameras": self.cameras,
            "accessors": self.accessors,
            "bufferViews": self.buffer_views,
            "buffers": [{"byteLength": self.bin.len()}]
        });
        // Serialising a Value built from plain numbers and strings cannot fail.
        let mut json_bytes = serde_json::to_vec(&document).expect("serialisable");
        while !json_bytes.len().is_multiple_of(4) {
            json_bytes.push(b' ');
        }
        let total = 12 + 8 + json_bytes.len() + 8 + self.bin.len();
        let mut glb = Vec::with_capacity(total);
        glb.extend_from_slice(b"glTF");
        glb.extend_from_slice(&2_u32.to_le_bytes());
        glb.extend_from_slice(&(total as u32).to_le_bytes());
        glb.extend_from_slice(&(json_bytes.len() as u32).to_le_bytes());
        glb.extend_from_slice(b"JSON");
        glb.extend_from_slice(&json_bytes);
        glb.extend_from_slice(&(self.bin.len() as u32).to_le_bytes());
        glb.extend_from_slice(b"BIN\0");
        glb.extend_from_slice(&self.bin);
        glb
    }
}
