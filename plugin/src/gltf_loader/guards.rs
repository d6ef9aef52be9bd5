//! Checks of a glTF file's header and JSON for inputs that make gltf 1.4 panic (all found by
//! fuzzing), so the loader reports them as errors instead.

use gltf::json::accessor::{ComponentType, Type};
use gltf::json::mesh::Semantic;
use gltf::json::validation::Checked;

/// A GLB's declared total length must cover its own 12-byte header: gltf subtracts the
/// header's size from it unchecked (an overflow panic in debug builds). A length short of the
/// file's is read anyway (gltf splits the chunks from the whole file), so it gives a warning:
/// the file was cut, appended to, or written by a broken exporter.
pub(super) fn check_glb_length(bytes: &[u8]) -> Result<Option<String>, String> {
    if let [b'g', b'l', b'T', b'F', _, _, _, _, l0, l1, l2, l3, ..] = *bytes {
        let length = u32::from_le_bytes([l0, l1, l2, l3]);
        if length < 12 {
            return Err(format!(
                "the GLB header declares a length of {length} bytes, less than the header's 12"
            ));
        }
        if (length as usize) < bytes.len() {
            return Ok(Some(format!(
                "the GLB header declares a length of {length} bytes but the file holds {}; read whole",
                bytes.len()
            )));
        }
    }
    Ok(None)
}

/// Checks, before gltf validates or reads the document, what it would otherwise panic on.
pub(super) fn check_json(json: &gltf::json::Root) -> Result<(), String> {
    check_position_accessors(json)?;
    check_attribute_types(json)?;
    check_cameras(json)?;
    check_accessors(json)?;
    check_buffer_views(json)?;
    check_images(json)
}

/// Every POSITION attribute must name an existing accessor: gltf-json's validation indexes the
/// accessor list with it unchecked.
fn check_position_accessors(json: &gltf::json::Root) -> Result<(), String> {
    for (mesh, primitives) in json.meshes.iter().map(|mesh| &mesh.primitives).enumerate() {
        for (primitive, attributes) in primitives.iter().map(|p| &p.attributes).enumerate() {
            if let Some(accessor) = attributes.get(&Checked::Valid(Semantic::Positions))
                && accessor.value() >= json.accessors.len()
            {
                return Err(format!(
                    "mesh {mesh}, primitive {primitive}: POSITION is accessor {} but the file has {} accessors",
                    accessor.value(),
                    json.accessors.len()
                ));
            }
        }
    }
    Ok(())
}

/// The attributes the loader reads must have the types glTF prescribes: gltf's readers assume
/// them (a debug assertion, or `unreachable!` for unknown component types).
fn check_attribute_types(json: &gltf::json::Root) -> Result<(), String> {
    use ComponentType::{F32, U8, U16, U32};
    for (mesh, primitives) in json.meshes.iter().map(|mesh| &mesh.primitives).enumerate() {
        for (primitive_index, primitive) in primitives.iter().enumerate() {
            let expected = primitive
                .attributes
                .iter()
                .filter_map(|(semantic, accessor)| {
                    let (name, allowed): (&str, (&[Type], &[ComponentType])) = match semantic {
                        Checked::Valid(Semantic::Positions) => {
                            ("POSITION", (&[Type::Vec3], &[F32]))
                        }
                        Checked::Valid(Semantic::Normals) => ("NORMAL", (&[Type::Vec3], &[F32])),
                        Checked::Valid(Semantic::Tangents) => ("TANGENT", (&[Type::Vec4], &[F32])),
                        Checked::Valid(Semantic::TexCoords(0)) => {
                            ("TEXCOORD_0", (&[Type::Vec2], &[F32, U8, U16]))
                        }
                        Checked::Valid(Semantic::Colors(0)) => {
                            ("COLOR_0", (&[Type::Vec3, Type::Vec4], &[F32, U8, U16]))
                        }
                        _ => return None,
                    };
                    Some((name, accessor.value(), allowed))
                });
            let indices = primitive.indices.map(|accessor| {
                (
                    "indices",
                    accessor.value(),
                    (&[Type::Scalar][..], &[U8, U16, U32][..]),
                )
            });
            for (what, index, (kinds, components)) in expected.chain(indices) {
                let Some(accessor) = json.accessors.get(index) else {
                    continue;
                };
                let fits = matches!(accessor.type_, Checked::Valid(found) if kinds.contains(&found))
                    && matches!(&accessor.component_type, Checked::Valid(found) if components.contains(&found.0));
                if !fits {
                    let kinds = kinds
                        .iter()
                        .map(|kind| format!("{kind:?}"))
                        .collect::<Vec<_>>();
                    return Err(format!(
                        "mesh {mesh}, primitive {primitive_index}: {what} (accessor {index}) must be {} of {components:?}",
                        kinds.join(" or ")
                    ));
                }
            }
        }
    }
    Ok(())
}

/// A camera must hold the projection its `type` names: gltf unwraps it.
fn check_cameras(json: &gltf::json::Root) -> Result<(), String> {
    use gltf::json::camera::Type as Projection;
    for (index, camera) in json.cameras.iter().enumerate() {
        let (held, name) = match camera.type_ {
            Checked::Valid(Projection::Perspective) => {
                (camera.perspective.is_some(), "perspective")
            }
            Checked::Valid(Projection::Orthographic) => {
                (camera.orthographic.is_some(), "orthographic")
            }
            Checked::Invalid => continue,
        };
        if !held {
            return Err(format!(
                "camera {index}: its type is {name} but it has no `{name}` object"
            ));
        }
    }
    Ok(())
}

/// Elements an accessor without a buffer view (its data generated: zeros plus sparse values)
/// may declare beyond one per byte of the file's buffers, so a small file cannot ask for
/// gigabytes of vertices.
const SPARE_VIRTUAL_ELEMENTS: u64 = 1 << 16;

/// An accessor must have elements, lie inside its buffer view with a stride that holds a whole
/// element, and a sparse one must replace at least one element: gltf's readers assume all of
/// it (overflow panics in debug builds).
fn check_accessors(json: &gltf::json::Root) -> Result<(), String> {
    for (index, accessor) in json.accessors.iter().enumerate() {
        if let Some(sparse) = &accessor.sparse
            && sparse.count.0 == 0
        {
            return Err(format!("accessor {index}: sparse.count is 0"));
        }
        let (Checked::Valid(component), Checked::Valid(kind)) =
            (&accessor.component_type, &accessor.type_)
        else {
            continue;
        };
        // Matrices pad their columns to four bytes.
        let element = match (kind, component.0.size()) {
            (Type::Mat2, 1) => 8,
            (Type::Mat3, 1) => 12,
            (Type::Mat3, 2) => 24,
            (kind, size) => kind.multiplicity() * size,
        };
        let count = accessor.count.0;
        if count == 0 {
            return Err(format!("accessor {index}: count is 0"));
        }
        let view = accessor
            .buffer_view
            .and_then(|view| json.buffer_views.get(view.value()));
        let Some(view) = view else {
            // Zeros (plus sparse values): each element is produced, so bound how many.
            let buffer_bytes: u64 = json.buffers.iter().map(|buffer| buffer.byte_length.0).sum();
            let limit = buffer_bytes.saturating_add(SPARE_VIRTUAL_ELEMENTS);
            if count > limit {
                return Err(format!(
                    "accessor {index}: count {count} without a buffer view is over {limit} (the buffers' bytes + {SPARE_VIRTUAL_ELEMENTS})"
                ));
            }
            continue;
        };
        let element = element as u64;
        let stride = view.byte_stride.map_or(element, |stride| stride.0 as u64);
        if stride < element {
            return Err(format!(
                "accessor {index}: its buffer view's byteStride {stride} is less than its {element}-byte elements"
            ));
        }
        let end = stride
            .checked_mul(count - 1)
            .and_then(|span| span.checked_add(element))
            .and_then(|span| span.checked_add(accessor.byte_offset.map_or(0, |offset| offset.0)));
        if end.is_none_or(|end| end > view.byte_length.0) {
            return Err(format!(
                "accessor {index}: {count} elements run past the {} bytes of its buffer view",
                view.byte_length.0
            ));
        }
    }
    Ok(())
}

/// A buffer view must lie inside its buffer's declared length (the loader checks the data is at
/// least that long): gltf slices image data by the view unchecked.
fn check_buffer_views(json: &gltf::json::Root) -> Result<(), String> {
    for (index, view) in json.buffer_views.iter().enumerate() {
        let Some(buffer) = json.buffers.get(view.buffer.value()) else {
            continue;
        };
        let end = view
            .byte_offset
            .map_or(0, |offset| offset.0)
            .checked_add(view.byte_length.0);
        if end.is_none_or(|end| end > buffer.byte_length.0) {
            return Err(format!(
                "buffer view {index} ends past the {} bytes of buffer {}",
                buffer.byte_length.0,
                view.buffer.value()
            ));
        }
    }
    Ok(())
}

/// An image needs a URI, or a buffer view with a MIME type: gltf unwraps both.
fn check_images(json: &gltf::json::Root) -> Result<(), String> {
    for (index, image) in json.images.iter().enumerate() {
        match (&image.buffer_view, &image.mime_type, &image.uri) {
            (Some(_), None, _) => {
                return Err(format!(
                    "image {index}: a bufferView image needs a mimeType"
                ));
            }
            (None, _, None) => {
                return Err(format!(
                    "image {index}: it has neither a uri nor a bufferView"
                ));
            }
            _ => {}
        }
    }
    Ok(())
}

/// A sparse accessor's indices must rise strictly and stay below its element count: gltf's
/// reader silently skips any other index, and every sparse value after it.
pub(super) fn check_sparse_indices(
    document: &gltf::Document,
    buffers: &[gltf::buffer::Data],
) -> Result<(), String> {
    for accessor in document.accessors() {
        let Some(sparse) = accessor.sparse() else {
            continue;
        };
        let indices = sparse.indices();
        let view = indices.view();
        let size = indices.index_type().size();
        let stride = view.stride().unwrap_or(size);
        // Data that is not there is the reader's error to report, with its own message.
        let Some(data) = buffers
            .get(view.buffer().index())
            .and_then(|data| data.0.get(view.offset()..))
            .and_then(|data| data.get(..view.length()))
        else {
            continue;
        };
        let mut previous: Option<u32> = None;
        for entry in 0..sparse.count() {
            let Some(bytes) = entry
                .checked_mul(stride)
                .and_then(|start| start.checked_add(indices.offset()))
                .and_then(|start| data.get(start..))
                .and_then(|rest| rest.get(..size))
            else {
                break;
            };
            // Little-endian, of whichever of the three widths.
            let index = bytes
                .iter()
                .rev()
                .fold(0_u32, |index, &byte| (index << 8) | u32::from(byte));
            let at = accessor.index();
            if index as usize >= accessor.count() {
                return Err(format!(
                    "accessor {at}: sparse index {index} (entry {entry}) is past its {} elements",
                    accessor.count()
                ));
            }
            if let Some(previous) = previous.filter(|&previous| index <= previous) {
                return Err(format!(
                    "accessor {at}: sparse index {index} (entry {entry}) does not rise above the one before it, {previous}"
                ));
            }
            previous = Some(index);
        }
    }
    Ok(())
}
