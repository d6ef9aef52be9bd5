//! The node hierarchy of a glTF scene to entities: transforms, meshes, cameras and lights.

use std::collections::HashMap;

use glam::{Affine3A, Vec3};
use hecs::Entity;

use super::materials::{MaterialCache, MaterialComponent};
use super::primitives::{MAX_GLTF_VERTICES, decoded_vertices, read_primitive};
use super::values::{
    camera_exposure, camera_of, light_output, light_range, node_transform, scene_ambient,
    world_problem,
};
use super::{GltfError, GltfScene, Source, describe};
use crate::{
    App, Assets, Camera, Color, DirectionalLight, Handle, Image, Mesh, Name, Parent, PointLight,
    SpotLight, Transform,
};

/// The world-space box of `mesh` placed by `world` (`None` without vertices).
fn mesh_bounds(world: Affine3A, mesh: &Mesh) -> Option<(Vec3, Vec3)> {
    let mut bounds: Option<(Vec3, Vec3)> = None;
    for position in &mesh.positions {
        let point = world.transform_point3(Vec3::from(*position));
        let (min, max) = bounds.get_or_insert((point, point));
        *min = min.min(point);
        *max = max.max(point);
    }
    bounds
}

/// Spawns the default (or first) scene's nodes, depth first, parents before children.
pub(super) fn spawn_scene(
    app: &mut App,
    source: &Source,
    scene: &mut GltfScene,
) -> Result<(), GltfError> {
    let root = source
        .document
        .default_scene()
        .or_else(|| source.document.scenes().next())
        .ok_or_else(|| GltfError::NoScene {
            path: source.path.clone(),
        })?;
    let ambient = scene_ambient(&root);
    app.resources.get_or_default::<Assets<Mesh>>();
    app.resources.get_or_default::<Assets<Image>>();
    app.resource_scope(|app, meshes: &mut Assets<Mesh>| {
        app.resource_scope(|app, images: &mut Assets<Image>| {
            spawn_nodes(app, source, scene, root, meshes, images)
        })
    })
    .flatten()
    .unwrap_or(Ok(()))?;
    // Only a scene that loaded whole changes the app's ambient light.
    match ambient {
        Ok(Some(ambient)) => {
            app.insert_resource(ambient);
        }
        Ok(None) => {}
        Err(reason) => scene
            .warnings
            .push(format!("the scene's {reason}: ignored")),
    }
    Ok(())
}

/// The walk's state: where it spawns, and the materials, meshes and mesh boxes it has gathered.
struct Spawner<'a> {
    app: &'a mut App,
    source: &'a Source,
    scene: &'a mut GltfScene,
    meshes: &'a mut Assets<Mesh>,
    images: &'a mut Assets<Image>,
    materials: MaterialCache,
    /// Each primitive's mesh, by (mesh, primitive) index, read once however many nodes use it:
    /// nodes sharing a mesh then share its GPU buffers and draw as instances, and a small file
    /// of many nodes on one large mesh cannot ask for a copy per node.
    primitive_meshes: HashMap<(usize, usize), Handle<Mesh>>,
    /// The vertices decoded so far, against [`MAX_GLTF_VERTICES`].
    decoded_vertices: u64,
    mesh_boxes: Vec<(Vec3, Vec3)>,
}

fn spawn_nodes(
    app: &mut App,
    source: &Source,
    scene: &mut GltfScene,
    root: gltf::Scene<'_>,
    meshes: &mut Assets<Mesh>,
    images: &mut Assets<Image>,
) -> Result<(), GltfError> {
    let mut spawner = Spawner {
        app,
        source,
        scene,
        meshes,
        images,
        materials: MaterialCache::default(),
        primitive_meshes: HashMap::new(),
        decoded_vertices: 0,
        mesh_boxes: Vec::new(),
    };
    let mut stack: Vec<(gltf::Node<'_>, Option<Entity>, Affine3A)> = root
        .nodes()
        .map(|node| (node, None, Affine3A::IDENTITY))
        .collect();
    stack.reverse();
    // glTF nodes form a tree: a node reached twice (its own ancestor, or under two parents)
    // would make this walk endless, so it is an error.
    let mut visited = vec![false; source.document.nodes().len()];
    while let Some((node, parent, parent_world)) = stack.pop() {
        if std::mem::replace(&mut visited[node.index()], true) {
            return Err(GltfError::Open {
                path: source.path.clone(),
                reason: format!(
                    "node {} is reached twice (a cycle, or two parents): glTF nodes must form a tree",
                    describe(node.name(), node.index())
                ),
            });
        }
        let Some((entity, world)) = spawner.node(&node, parent, parent_world)? else {
            continue;
        };
        let children: Vec<_> = node.children().collect();
        for child in children.into_iter().rev() {
            stack.push((child, Some(entity), world));
        }
    }
    spawner.finish();
    Ok(())
}

impl Spawner<'_> {
    /// Spawns `node` under `parent` with its mesh, camera and light; returns the entity and
    /// its world transform, or nothing (with a warning) when its transform cannot place it:
    /// then it and its children are left out.
    fn node(
        &mut self,
        node: &gltf::Node<'_>,
        parent: Option<Entity>,
        parent_world: Affine3A,
    ) -> Result<Option<(Entity, Affine3A)>, GltfError> {
        let node_name = describe(node.name(), node.index());
        let placed =
            node_transform(node, &node_name, &mut self.scene.warnings).and_then(|transform| {
                let world = parent_world * transform.to_affine();
                world_problem(world).map_or(Ok((transform, world)), Err)
            });
        let (transform, world) = match placed {
            Ok(placed) => placed,
            Err(problem) => {
                self.scene.warnings.push(format!(
                    "node {node_name}: {problem}; it and its children are left out"
                ));
                return Ok(None);
            }
        };
        // The file's node name, or "node N" for an unnamed node.
        let name = node
            .name()
            .map_or_else(|| format!("node {}", node.index()), str::to_owned);
        let entity = self.app.world.spawn((transform, Name::new(name.clone())));
        if let Some(parent) = parent {
            let _ = self.app.world.insert_one(entity, Parent(parent));
        }
        self.scene.entities.push(entity);

        if node.skin().is_some() {
            self.scene.warnings.push(format!(
                "node {node_name}: skinning is not supported; drawn in its bind pose"
            ));
        }
        if let Some(mesh) = node.mesh() {
            self.mesh(&mesh, entity, &name, world)?;
        }
        if let Some(camera) = node.camera() {
            let unusable = |reason| GltfError::Camera {
                path: self.source.path.clone(),
                camera: describe(camera.name(), camera.index()),
                reason,
            };
            let loaded = camera_of(&camera).map_err(unusable)?;
            if let Some(exposure) = camera_exposure(&camera).map_err(unusable)? {
                let _ = self.app.world.insert_one(entity, exposure);
            }
            // One rule everywhere: the first camera node is the one looked through.
            let camera = Camera {
                active: self.scene.cameras.is_empty(),
                ..loaded
            };
            let _ = self.app.world.insert_one(entity, camera);
            self.scene.cameras.push(entity);
        }
        if let Some(light) = node.light() {
            self.light(&light, entity, &node_name);
        }
        Ok(Some((entity, world)))
    }

    /// The drawable primitives of `mesh` on node `entity` (named `name`, placed by `world`):
    /// one primitive goes on the node itself; several get a child entity each.
    fn mesh(
        &mut self,
        mesh: &gltf::Mesh<'_>,
        entity: Entity,
        name: &str,
        world: Affine3A,
    ) -> Result<(), GltfError> {
        let drawable = self.primitives(mesh, world)?;
        let single = drawable.len() == 1;
        for (primitive, (handle, material)) in drawable.into_iter().enumerate() {
            let target = if single {
                entity
            } else {
                let child = self.app.world.spawn((
                    Transform::IDENTITY,
                    Parent(entity),
                    Name(format!("{name} / primitive {primitive}")),
                ));
                self.scene.entities.push(child);
                child
            };
            let _ = self.app.world.insert_one(target, handle);
            let _ = match material {
                MaterialComponent::Lit(lit) => self.app.world.insert_one(target, lit),
                MaterialComponent::Parallax(parallax) => {
                    self.app.world.insert_one(target, parallax)
                }
            };
        }
        Ok(())
    }

    /// The meshes and materials of `mesh`'s triangle primitives, their boxes gathered; other
    /// modes are skipped and morph targets left out, with a warning each.
    fn primitives(
        &mut self,
        mesh: &gltf::Mesh<'_>,
        world: Affine3A,
    ) -> Result<Vec<(Handle<Mesh>, MaterialComponent)>, GltfError> {
        let mut drawable = Vec::new();
        for primitive in mesh.primitives() {
            if primitive.mode() != gltf::mesh::Mode::Triangles {
                self.scene.warnings.push(format!(
                    "mesh {}, primitive {}: mode {:?} is not supported; skipped",
                    describe(mesh.name(), mesh.index()),
                    primitive.index(),
                    primitive.mode()
                ));
                continue;
            }
            if primitive.morph_targets().len() > 0 {
                self.scene.warnings.push(format!(
                    "mesh {}, primitive {}: morph targets are not supported; drawn unmorphed",
                    describe(mesh.name(), mesh.index()),
                    primitive.index()
                ));
            }
            let material = self.materials.material(
                self.source,
                self.images,
                primitive.material(),
                &mut self.scene.warnings,
            )?;
            if let MaterialComponent::Parallax(parallax) = &material.kind
                && parallax.mapping == crate::TextureMapping::Triplanar
                && primitive.get(&gltf::Semantic::Normals).is_none()
            {
                self.scene.warnings.push(format!(
                    "mesh {}, primitive {}: no NORMAL under triplanar mapping; the flat normals \
                     generated for it change the projections' mix at every edge",
                    describe(mesh.name(), mesh.index()),
                    primitive.index()
                ));
            }
            let key = (mesh.index(), primitive.index());
            let handle = match self.primitive_meshes.get(&key) {
                Some(handle) => handle.clone(),
                None => {
                    self.decoded_vertices += decoded_vertices(&primitive);
                    if self.decoded_vertices > MAX_GLTF_VERTICES {
                        return Err(GltfError::Mesh {
                            path: self.source.path.clone(),
                            mesh: describe(mesh.name(), mesh.index()),
                            primitive: primitive.index(),
                            reason: format!(
                                "the file's meshes decode to {} vertices by here, over the \
                                 limit of {MAX_GLTF_VERTICES}",
                                self.decoded_vertices
                            ),
                        });
                    }
                    let data =
                        read_primitive(self.source, mesh, &primitive, material.uv_transform)?;
                    let handle = self.meshes.add(data);
                    self.primitive_meshes.insert(key, handle.clone());
                    handle
                }
            };
            if let Some(bounds) = self
                .meshes
                .get(&handle)
                .and_then(|data| mesh_bounds(world, data))
            {
                self.mesh_boxes.push(bounds);
            }
            drawable.push((handle, material.kind));
        }
        Ok(drawable)
    }

    /// A `KHR_lights_punctual` light on node `entity`; a colour, intensity or range it cannot
    /// shine with is clamped, with a warning.
    fn light(
        &mut self,
        light: &gltf::khr_lights_punctual::Light<'_>,
        entity: Entity,
        node_name: &str,
    ) {
        let ([r, g, b], intensity) = light_output(light, node_name, &mut self.scene.warnings);
        let color = Color::linear_rgb(r, g, b);
        let range = light_range(light, node_name, &mut self.scene.warnings);
        let inserted = match light.kind() {
            gltf::khr_lights_punctual::Kind::Directional => self
                .app
                .world
                .insert_one(entity, DirectionalLight { color, intensity }),
            gltf::khr_lights_punctual::Kind::Spot {
                inner_cone_angle,
                outer_cone_angle,
            } => {
                let spot = SpotLight {
                    color,
                    intensity,
                    range,
                    inner_angle: inner_cone_angle,
                    outer_angle: outer_cone_angle,
                };
                let spot = self.sanitized_spot(spot, node_name);
                self.app.world.insert_one(entity, spot)
            }
            gltf::khr_lights_punctual::Kind::Point => self.app.world.insert_one(
                entity,
                PointLight {
                    color,
                    intensity,
                    range,
                },
            ),
        };
        if inserted.is_ok() {
            self.scene.lights.push(entity);
        }
    }

    /// `spot` with its cone clamped to 0 ≤ inner ≤ outer ≤ π/2, with a warning if that
    /// changed it.
    fn sanitized_spot(&mut self, spot: SpotLight, node_name: &str) -> SpotLight {
        let (inner, outer) = spot.sanitized_cone();
        if (inner, outer) != (spot.inner_angle, spot.outer_angle) {
            self.scene.warnings.push(format!(
                "node {node_name}: spot cone inner {} / outer {} rad is not 0 ≤ inner ≤ outer ≤ π/2; clamped to {inner} / {outer}",
                spot.inner_angle, spot.outer_angle
            ));
        }
        SpotLight {
            inner_angle: inner,
            outer_angle: outer,
            ..spot
        }
    }

    /// The scene's boxes: of every mesh, and the one an automatic camera frames.
    fn finish(self) {
        self.scene.bounds = self
            .mesh_boxes
            .iter()
            .copied()
            .reduce(|(min_a, max_a), (min_b, max_b)| (min_a.min(min_b), max_a.max(max_b)));
        self.scene.framing_bounds = super::framing::framing_bounds(&self.mesh_boxes);
    }
}
