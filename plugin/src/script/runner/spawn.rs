//! Spawning a script's entities: a shape with its material, or a whole glTF file.

use std::path::Path;

use glam::{EulerRot, Quat};
use hecs::Entity;

use super::{Runner, vec3};
use crate::files::resolve_inside;
use crate::script::format::{EntityDesc, MaterialDesc, MaterialPatch, ShapeDesc, TransformDesc};
use crate::{
    Assets, Camera, Color, DirectionalLight, GltfOptions, HeightSource, Image, LitMaterial, Mesh,
    ParallaxOcclusionMaterial, PointLight, PomPreset, TextureKind, Transform, load_gltf_with,
};

/// The placement a script gives (Euler degrees applied X, then Y, then Z).
fn transform_of(desc: &TransformDesc) -> Transform {
    let rotation = Quat::from_euler(
        EulerRot::XYZ,
        desc.rotation_degrees[0].to_radians(),
        desc.rotation_degrees[1].to_radians(),
        desc.rotation_degrees[2].to_radians(),
    );
    Transform {
        translation: vec3(desc.translation),
        rotation,
        scale: vec3(desc.scale.unwrap_or([1.0; 3])),
    }
}

impl Runner<'_> {
    /// Where file `name` of the script leads, refused outside the folder its options allow.
    pub(super) fn resolve(&self, name: &str) -> Result<std::path::PathBuf, String> {
        resolve_inside(self.dir, Path::new(name), self.options.file_access)
            .map_err(|error| error.to_string())
    }

    /// Spawns one script entity; returns every entity it made.
    pub(super) fn spawn(&mut self, desc: &EntityDesc) -> Result<Vec<Entity>, String> {
        let transform = transform_of(&desc.transform);
        if let Some(file) = &desc.gltf {
            return self.spawn_gltf(file, transform);
        }
        let entity = self.spawn_shape(desc.shape.as_ref().ok_or("no shape")?, transform)?;
        match &desc.material {
            None => {}
            Some(MaterialDesc::Lit { color }) => {
                let _ = self.app.world.insert_one(
                    entity,
                    LitMaterial::from_color(Color::linear_rgb(color[0], color[1], color[2])),
                );
            }
            Some(MaterialDesc::Pom { maps, preset, set }) => {
                let material = self.pom_material(maps, preset.as_deref(), set)?;
                let _ = self.app.world.insert_one(entity, material);
            }
        }
        Ok(vec![entity])
    }

    /// Loads glTF `file` placed by `transform`, its cameras (and lights, if the script has
    /// its own) removed.
    fn spawn_gltf(&mut self, file: &str, transform: Transform) -> Result<Vec<Entity>, String> {
        let path = self.resolve(file)?;
        let options = GltfOptions {
            file_access: self.options.file_access,
            ..GltfOptions::default()
        };
        let scene =
            load_gltf_with(&mut self.app, path, options).map_err(|error| error.to_string())?;
        // What the loader fixed (a clamped light, a node left out) must not pass unsaid.
        for warning in &scene.warnings {
            log::warn!("{file}: {warning}");
        }
        // Place the whole file by moving its root nodes.
        for entity in &scene.entities {
            if self.app.world.get::<&crate::Parent>(*entity).is_err()
                && let Ok(mut root) = self.app.world.get::<&mut Transform>(*entity)
            {
                *root = Transform::from_affine(transform.to_affine() * root.to_affine());
            }
        }
        // A script's own camera and lights replace the file's.
        for camera in &scene.cameras {
            let _ = self.app.world.remove_one::<Camera>(*camera);
        }
        if !self.lights.is_empty() {
            for light in &scene.lights {
                let _ = self.app.world.remove_one::<DirectionalLight>(*light);
                let _ = self.app.world.remove_one::<PointLight>(*light);
            }
        }
        Ok(scene.entities)
    }

    /// Spawns the mesh of `shape` at `transform`, without a material.
    fn spawn_shape(&mut self, shape: &ShapeDesc, transform: Transform) -> Result<Entity, String> {
        let mesh = match shape {
            ShapeDesc::Plane { size, tiling } => Mesh::plane_tiled(*size, *tiling),
            ShapeDesc::Cube { size } => Mesh::cube(*size),
            ShapeDesc::Sphere { radius } => Mesh::uv_sphere(*radius, 32, 16),
            ShapeDesc::Cylinder { radius, height } => Mesh::cylinder(*radius, *height, 32),
        };
        let mesh = self
            .app
            .resources
            .get_mut::<Assets<Mesh>>()
            .ok_or("no mesh store")?
            .add(mesh);
        Ok(self.app.world.spawn((mesh, transform)))
    }

    /// A parallax material from the maps in folder `maps`, with `preset` (a file) and then
    /// `set` applied.
    fn pom_material(
        &mut self,
        maps: &str,
        preset: Option<&str>,
        set: &MaterialPatch,
    ) -> Result<ParallaxOcclusionMaterial, String> {
        let load = |file: &str, kind| {
            let path = self.resolve(&format!("{maps}/{file}"))?;
            Image::load(path, kind).map_err(|error| error.to_string())
        };
        let (albedo, normal, height) = (
            load("albedo.png", TextureKind::Color)?,
            load("normal.png", TextureKind::Normal)?,
            load("height.png", TextureKind::Height)?,
        );
        let images = self
            .app
            .resources
            .get_mut::<Assets<Image>>()
            .ok_or("no image store")?;
        let mut material = ParallaxOcclusionMaterial {
            base_color_texture: Some(images.add(albedo)),
            normal_map: Some(images.add(normal)),
            height_map: Some(HeightSource::Texture(images.add(height))),
            ..ParallaxOcclusionMaterial::default()
        };
        if let Some(preset) = preset {
            let path = self.resolve(preset)?;
            let preset = PomPreset::load(&path).map_err(|error| error.to_string())?;
            material.apply_preset(&preset);
            // The layers' files are the preset's neighbours.
            let files = preset
                .read_layer_files_beside(&path, self.options.file_access)
                .map_err(|error| format!("preset {}: {error}", path.display()))?;
            if let Some(files) = files {
                let images = self
                    .app
                    .resources
                    .get_mut::<Assets<Image>>()
                    .ok_or("no image store")?;
                let layers = files
                    .into_layers(images)
                    .map_err(|error| error.to_string())?;
                material.layers = Some(layers);
            }
        }
        set.apply(&mut material);
        Ok(material)
    }
}
