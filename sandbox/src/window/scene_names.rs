//! Names for the entities a glTF file spawned, read from its nodes. The loader does not keep
//! names, so this walks the file's nodes in the loader's order (depth first, children in file
//! order, one extra child entity per triangle primitive when a mesh has several) and pairs them
//! with `GltfScene::entities`. When the counts disagree the names are not trusted.

use std::collections::HashMap;

use pom::hecs::Entity;
use serde_json::Value;

/// Display names of entities; a resource of the sandbox's `pom::App`.
#[derive(Debug, Default)]
pub struct EntityNames(pub HashMap<Entity, String>);

/// The glTF JSON of a `.glb` (its first chunk) or of a `.gltf` file.
fn gltf_json(bytes: &[u8]) -> Option<Value> {
    if bytes.starts_with(b"glTF") {
        let length = u32::from_le_bytes(bytes.get(12..16)?.try_into().ok()?) as usize;
        serde_json::from_slice(bytes.get(20..20usize.checked_add(length)?)?).ok()
    } else {
        serde_json::from_slice(bytes).ok()
    }
}

/// One name per spawned entity, in spawn order, or `None` when the file cannot be read.
fn names_in_spawn_order(json: &Value) -> Option<Vec<String>> {
    let nodes = json.get("nodes")?.as_array()?;
    let meshes = json.get("meshes").and_then(Value::as_array);
    let scenes = json.get("scenes")?.as_array()?;
    let scene = json
        .get("scene")
        .and_then(Value::as_u64)
        .and_then(|index| scenes.get(index as usize))
        .or_else(|| scenes.first())?;
    let indices = |value: Option<&Value>| -> Vec<usize> {
        value
            .and_then(Value::as_array)
            .map(|list| list.iter().filter_map(|i| i.as_u64()).map(|i| i as usize))
            .into_iter()
            .flatten()
            .collect()
    };
    let mut stack = indices(scene.get("nodes"));
    stack.reverse();
    let mut names = Vec::new();
    while let Some(index) = stack.pop() {
        let node = nodes.get(index)?;
        let name = node
            .get("name")
            .and_then(Value::as_str)
            .map_or_else(|| format!("node {index}"), str::to_owned);
        names.push(name.clone());
        let triangle_primitives = node
            .get("mesh")
            .and_then(Value::as_u64)
            .and_then(|mesh| meshes?.get(mesh as usize)?.get("primitives")?.as_array())
            .map_or(0, |primitives| {
                primitives
                    .iter()
                    // Mode 4 (triangles) is the default; the loader skips the others.
                    .filter(|p| p.get("mode").and_then(Value::as_u64).unwrap_or(4) == 4)
                    .count()
            });
        if triangle_primitives > 1 {
            names.extend((0..triangle_primitives).map(|p| format!("{name} / primitive {p}")));
        }
        let mut children = indices(node.get("children"));
        children.reverse();
        stack.extend(children);
    }
    Some(names)
}

/// Pairs the file's node names with the entities the loader spawned from `bytes`.
pub fn name_entities(bytes: &[u8], entities: &[Entity]) -> HashMap<Entity, String> {
    match gltf_json(bytes).as_ref().and_then(names_in_spawn_order) {
        Some(names) if names.len() == entities.len() => {
            entities.iter().copied().zip(names).collect()
        }
        _ => HashMap::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_street_corner_names_match_its_nodes() {
        let json = gltf_json(crate::demo_scene::STREET_CORNER).unwrap();
        let names = names_in_spawn_order(&json).unwrap();
        assert_eq!(names[0], "floor");
        assert!(names.contains(&"ball".to_owned()), "{names:?}");
    }

    #[test]
    fn children_follow_their_parent_and_primitives_get_a_child_each() {
        let json: Value = serde_json::from_str(
            r#"{"scene":0,"scenes":[{"nodes":[0,2]}],
                "nodes":[{"name":"a","children":[1]},{"name":"b","mesh":0},{}],
                "meshes":[{"primitives":[{},{"mode":1},{"mode":4}]}]}"#,
        )
        .unwrap();
        assert_eq!(
            names_in_spawn_order(&json).unwrap(),
            ["a", "b", "b / primitive 0", "b / primitive 1", "node 2"]
        );
    }
}
