//! Loading glTF 2.0 scenes (`.gltf` with its files, or `.glb`) into entities.
//!
//! Nodes become entities with [`Transform`] and [`Parent`]; meshes, cameras,
//! `KHR_lights_punctual` lights and materials become components. A material whose `extras` hold
//! a `pom` object (see [`PomExtras`]) becomes a [`crate::ParallaxOcclusionMaterial`]; any other
//! becomes a [`crate::LitMaterial`] (normal mapping). `KHR_texture_transform` is baked into the
//! texture coordinates. Features the renderer does not have (skins, morph targets, points and
//! lines, unknown required extensions) are skipped with one warning each.

mod extras;
mod framing;
mod guards;
mod layer_extras;
mod materials;
mod nodes;
mod primitives;
mod textures;
mod values;

pub use extras::PomExtras;
pub use layer_extras::LayerExtras;
pub use primitives::MAX_GLTF_VERTICES;

use std::path::{Path, PathBuf};

use glam::Vec3;
use hecs::Entity;

use crate::App;
use crate::files::{FileAccess, MAX_SCENE_FILE_BYTES, read_bounded, resolve_inside};

/// How a glTF file may reach other files, and how much memory its images may claim.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct GltfOptions {
    /// Which files its buffer and image URIs may name: by default only files inside the glTF
    /// file's folder ([`FileAccess::InsideFolder`]); [`FileAccess::AnyPath`] for trusted files.
    pub file_access: FileAccess,
    /// Bytes its images may claim, decoded and while their mips are built (see
    /// [`crate::IMAGE_MEMORY_BUDGET`], the default).
    pub image_memory_budget: u64,
}

impl Default for GltfOptions {
    fn default() -> Self {
        Self {
            file_access: FileAccess::InsideFolder,
            image_memory_budget: crate::IMAGE_MEMORY_BUDGET,
        }
    }
}

/// What a loaded scene added to the world.
#[derive(Debug, Default)]
pub struct GltfScene {
    /// Every entity spawned, parents before their children.
    pub entities: Vec<Entity>,
    /// Entities with a [`crate::Camera`]: camera N is the N-th camera node (from 0) of a walk
    /// of the scene's nodes depth first, parents before children, siblings in file order.
    /// Camera 0 is the active one; the others are loaded inactive.
    pub cameras: Vec<Entity>,
    /// Entities with a light.
    pub lights: Vec<Entity>,
    /// World-space bounding box (min, max) of every mesh, if there are any.
    pub bounds: Option<(Vec3, Vec3)>,
    /// What an automatic camera frames: the box of every mesh except flat ones more than four
    /// times wider than the rest (a ground plane, a backdrop), which would leave the scene's
    /// objects a speck.
    pub framing_bounds: Option<(Vec3, Vec3)>,
    /// One line per unsupported feature that was skipped.
    pub warnings: Vec<String>,
}

impl GltfScene {
    /// Makes the file's camera `index` the only active one of the scene's cameras, or none with
    /// `None` (to look through a camera of your own). Returns false, changing nothing, when the
    /// file has no camera `index`.
    pub fn activate_camera(&self, world: &mut hecs::World, index: Option<usize>) -> bool {
        if index.is_some_and(|index| index >= self.cameras.len()) {
            return false;
        }
        for (camera_index, &entity) in self.cameras.iter().enumerate() {
            if let Ok(mut camera) = world.get::<&mut crate::Camera>(entity) {
                camera.active = Some(camera_index) == index;
            }
        }
        true
    }
}

/// Why a glTF file could not be loaded.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum GltfError {
    /// The file is unreadable, truncated, or not valid glTF.
    #[error("{path}: {reason}")]
    Open {
        /// The file.
        path: PathBuf,
        /// What was wrong.
        reason: String,
    },
    /// A buffer is missing or shorter than declared.
    #[error("{path}: buffer {index}: {reason}")]
    Buffer {
        /// The file.
        path: PathBuf,
        /// The buffer's index.
        index: usize,
        /// What was wrong.
        reason: String,
    },
    /// A texture image could not be read.
    #[error("{path}: image {image}: {reason}")]
    Image {
        /// The file.
        path: PathBuf,
        /// The image's name or index.
        image: String,
        /// What was wrong.
        reason: String,
    },
    /// A mesh primitive's data is unusable.
    #[error("{path}: mesh {mesh}, primitive {primitive}: {reason}")]
    Mesh {
        /// The file.
        path: PathBuf,
        /// The mesh's name or index.
        mesh: String,
        /// The primitive's index in the mesh.
        primitive: usize,
        /// What was wrong.
        reason: String,
    },
    /// A material (or its POM `extras`) is invalid.
    #[error("{path}: material {material}: {reason}")]
    Material {
        /// The file.
        path: PathBuf,
        /// The material's name or index.
        material: String,
        /// What was wrong.
        reason: String,
    },
    /// A camera's projection is unusable.
    #[error("{path}: camera {camera}: {reason}")]
    Camera {
        /// The file.
        path: PathBuf,
        /// The camera's name or index.
        camera: String,
        /// What was wrong.
        reason: String,
    },
    /// The file has no scene to load.
    #[error("{path}: the file has no scene")]
    NoScene {
        /// The file.
        path: PathBuf,
    },
}

/// `"name" (#3)` or `#3`, for messages.
fn describe(name: Option<&str>, index: usize) -> String {
    match name {
        Some(name) => format!("{name:?} (#{index})"),
        None => format!("#{index}"),
    }
}

/// Everything read from the file before anything is spawned.
struct Source {
    path: PathBuf,
    document: gltf::Document,
    buffers: Vec<gltf::buffer::Data>,
    /// Where relative URIs point; `None` for documents loaded from memory.
    base: Option<PathBuf>,
    /// Which files URIs may name, and the images' memory budget.
    options: GltfOptions,
    /// Extensions the file requires that this loader does not implement.
    unsupported_required: Vec<String>,
    /// Extensions the file uses (without requiring them) that this loader does not implement.
    unsupported_used: Vec<String>,
    /// What reading the file found odd but read anyway.
    warnings: Vec<String>,
}

/// The extensions this loader implements.
const SUPPORTED_EXTENSIONS: [&str; 4] = [
    "KHR_lights_punctual",
    "KHR_texture_transform",
    "KHR_materials_emissive_strength",
    "KHR_materials_unlit",
];

fn open(path: &Path, options: GltfOptions) -> Result<Source, GltfError> {
    let bytes = read_bounded(path, MAX_SCENE_FILE_BYTES).map_err(|error| GltfError::Open {
        path: path.to_owned(),
        reason: error.to_string(),
    })?;
    let base = path.parent().unwrap_or(Path::new(".")).to_owned();
    parse(path, &bytes, Some(base), options)
}

/// Parses a document held in memory; `base` resolves relative URIs (none: only `data:` URIs and
/// the GLB binary chunk can be used).
fn parse(
    path: &Path,
    bytes: &[u8],
    base: Option<PathBuf>,
    options: GltfOptions,
) -> Result<Source, GltfError> {
    let open_error = |reason: String| GltfError::Open {
        path: path.to_owned(),
        reason,
    };
    let warnings: Vec<String> = guards::check_glb_length(bytes)
        .map_err(open_error)?
        .map(|warning| format!("{}: {warning}", path.display()))
        .into_iter()
        .collect();
    let gltf::Gltf { document, blob } = gltf::Gltf::from_slice_without_validation(bytes)
        .map_err(|error| open_error(error.to_string()))?;
    // Validation rejects files that require extensions it does not know; we draw what we can
    // of those instead, so set the unknown ones aside (with a warning) before validating.
    let mut json = document.into_json();
    let (supported, unsupported): (Vec<String>, Vec<String>) = json
        .extensions_required
        .drain(..)
        .partition(|name| SUPPORTED_EXTENSIONS.contains(&name.as_str()));
    json.extensions_required = supported;
    let unsupported_used: Vec<String> = json
        .extensions_used
        .iter()
        .filter(|name| {
            !SUPPORTED_EXTENSIONS.contains(&name.as_str()) && !unsupported.contains(*name)
        })
        .cloned()
        .collect();
    guards::check_json(&json).map_err(open_error)?;
    let document =
        gltf::Document::from_json(json).map_err(|error| open_error(error.to_string()))?;
    let mut blob = blob;
    let mut buffers = Vec::new();
    // The file and its buffer files share one bound.
    let mut unread = MAX_SCENE_FILE_BYTES.saturating_sub(bytes.len() as u64);
    for buffer in document.buffers() {
        let index = buffer.index();
        let buffer_error = |reason: String| GltfError::Buffer {
            path: path.to_owned(),
            index,
            reason,
        };
        let data = match buffer.source() {
            gltf::buffer::Source::Bin => blob
                .take()
                .ok_or_else(|| buffer_error("the GLB has no binary chunk".into()))?,
            gltf::buffer::Source::Uri(uri) => {
                read_uri(base.as_deref(), uri, options.file_access, unread).map_err(buffer_error)?
            }
        };
        unread = unread.saturating_sub(data.len() as u64);
        if data.len() < buffer.length() {
            return Err(buffer_error(format!(
                "holds {} bytes but declares {}",
                data.len(),
                buffer.length()
            )));
        }
        buffers.push(gltf::buffer::Data(data));
    }
    guards::check_sparse_indices(&document, &buffers).map_err(open_error)?;
    Ok(Source {
        path: path.to_owned(),
        document,
        buffers,
        base,
        options,
        unsupported_required: unsupported,
        unsupported_used,
        warnings,
    })
}

/// The bytes of a `data:` URI.
fn decode_data_uri(data: &str) -> Result<Vec<u8>, String> {
    let (_, encoded) = data
        .split_once(";base64,")
        .ok_or("only base64 data URIs are supported")?;
    decode_base64(encoded).ok_or_else(|| "the data URI is not valid base64".into())
}

/// The file a (non-`data:`) URI names, relative to the glTF file's folder `base`, as `access`
/// allows: percent-escapes decoded; `file:` URIs only with [`FileAccess::AnyPath`].
fn locate_uri(base: Option<&Path>, uri: &str, access: FileAccess) -> Result<PathBuf, String> {
    let base =
        base.ok_or_else(|| format!("{uri}: a document loaded from memory cannot refer to files"))?;
    let decoded = percent_decode(uri);
    // A scheme is letters (and digits, `+`, `-`, `.`) before the first `:`, ahead of any `/`.
    let scheme = decoded
        .split_once(':')
        .map(|(scheme, _)| scheme)
        .filter(|scheme| !scheme.contains('/'));
    let relative = match (scheme, access) {
        (None, _) => decoded.as_str(),
        (Some(_), FileAccess::InsideFolder) => {
            return Err(format!(
                "uri {uri:?} has a scheme: only paths relative to the glTF file's folder, \
                 inside it, may be named unless FileAccess::AnyPath allows any"
            ));
        }
        (Some(_), _) => decoded
            .strip_prefix("file://")
            .ok_or_else(|| format!("uri {uri:?}: only file: URIs and paths are supported"))?,
    };
    resolve_inside(base, Path::new(relative), access)
        .map_err(|error| format!("uri {uri:?}: {error}"))
}

/// Reads a buffer URI: a `data:` URI, or a file relative to the glTF file (of at most `limit`
/// bytes).
fn read_uri(
    base: Option<&Path>,
    uri: &str,
    access: FileAccess,
    limit: u64,
) -> Result<Vec<u8>, String> {
    if let Some(data) = uri.strip_prefix("data:") {
        return decode_data_uri(data);
    }
    let file = locate_uri(base, uri, access)?;
    read_bounded(&file, limit).map_err(|error| format!("uri {uri:?}: {error}"))
}

fn percent_decode(uri: &str) -> String {
    let bytes = uri.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        let escaped = (bytes[i] == b'%')
            .then(|| bytes.get(i + 1..i + 3))
            .flatten()
            .and_then(|hex| std::str::from_utf8(hex).ok())
            .and_then(|hex| u8::from_str_radix(hex, 16).ok());
        match escaped {
            Some(byte) => {
                out.push(byte);
                i += 3;
            }
            None => {
                out.push(bytes[i]);
                i += 1;
            }
        }
    }
    String::from_utf8_lossy(&out).into_owned()
}

fn decode_base64(text: &str) -> Option<Vec<u8>> {
    let value = |c: u8| -> Option<u32> {
        Some(match c {
            b'A'..=b'Z' => c - b'A',
            b'a'..=b'z' => c - b'a' + 26,
            b'0'..=b'9' => c - b'0' + 52,
            b'+' | b'-' => 62,
            b'/' | b'_' => 63,
            _ => return None,
        } as u32)
    };
    let symbols: Vec<u8> = text
        .bytes()
        .filter(|c| !c.is_ascii_whitespace() && *c != b'=')
        .collect();
    let mut out = Vec::with_capacity(symbols.len() * 3 / 4);
    for chunk in symbols.chunks(4) {
        let mut word = 0_u32;
        for (k, c) in chunk.iter().enumerate() {
            word |= value(*c)? << (18 - 6 * k);
        }
        let bytes = word.to_be_bytes();
        match chunk.len() {
            4 => out.extend_from_slice(&bytes[1..4]),
            3 => out.extend_from_slice(&bytes[1..3]),
            2 => out.push(bytes[1]),
            _ => return None,
        }
    }
    Some(out)
}

/// Loads the default scene (or the first) of a `.gltf` or `.glb` file into `app`'s world and
/// asset stores. Needs the render plugin (for the mesh and image stores).
///
/// # Example
/// ```no_run
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// let mut app = pom::App::new();
/// app.add_plugin(pom::RenderPlugin::new(640, 360)).add_plugin(pom::PomPlugin);
/// let scene = pom::load_gltf(&mut app, "assets/street_corner.gltf")?;
/// for warning in &scene.warnings {
///     eprintln!("warning: {warning}");
/// }
/// # Ok(()) }
/// ```
pub fn load_gltf(app: &mut App, path: impl AsRef<Path>) -> Result<GltfScene, GltfError> {
    load_gltf_with(app, path, GltfOptions::default())
}

/// [`load_gltf`] with `options`: which files the glTF file may name, and its images' memory
/// budget.
///
/// # Example
/// ```no_run
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// let mut app = pom::App::new();
/// app.add_plugin(pom::RenderPlugin::new(640, 360)).add_plugin(pom::PomPlugin);
/// // A trusted file whose textures live in a shared folder beside its own.
/// let options = pom::GltfOptions {
///     file_access: pom::files::FileAccess::AnyPath,
///     ..pom::GltfOptions::default()
/// };
/// pom::load_gltf_with(&mut app, "assets/street_corner.gltf", options)?;
/// # Ok(()) }
/// ```
pub fn load_gltf_with(
    app: &mut App,
    path: impl AsRef<Path>,
    options: GltfOptions,
) -> Result<GltfScene, GltfError> {
    let path = path.as_ref();
    spawn_source(app, path, || open(path, options))
}

/// Loads a `.glb` (or a self-contained `.gltf`) held in memory, such as one embedded in a
/// binary with `include_bytes!`. `name` stands for the file in messages.
pub fn load_gltf_bytes(app: &mut App, bytes: &[u8], name: &str) -> Result<GltfScene, GltfError> {
    let path = Path::new(name);
    spawn_source(app, path, || {
        parse(path, bytes, None, GltfOptions::default())
    })
}

fn spawn_source(
    app: &mut App,
    path: &Path,
    read: impl FnOnce() -> Result<Source, GltfError> + std::panic::UnwindSafe,
) -> Result<GltfScene, GltfError> {
    // gltf's accessor readers check every range, but a panic in a dependency must not take the
    // game down with a file it was handed: report it as a broken file instead.
    let source = std::panic::catch_unwind(read).unwrap_or_else(|_| {
        Err(GltfError::Open {
            path: path.to_owned(),
            reason: "the file is malformed (the parser gave up)".into(),
        })
    })?;
    let mut scene = GltfScene {
        warnings: source.warnings.clone(),
        ..GltfScene::default()
    };
    for extension in &source.unsupported_required {
        scene.warnings.push(format!(
            "required extension {extension} is not supported: ignored"
        ));
    }
    for extension in &source.unsupported_used {
        scene
            .warnings
            .push(format!("extension {extension} is not supported: ignored"));
    }
    let mut built = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        nodes::spawn_scene(app, &source, &mut scene)
    }))
    .unwrap_or_else(|_| {
        Err(GltfError::Open {
            path: source.path.clone(),
            reason: "the file is malformed (the parser gave up)".into(),
        })
    });
    if let Err(error) = &mut built {
        // Leave nothing half-loaded behind.
        for entity in scene.entities.drain(..) {
            let _ = app.world.despawn(entity);
        }
        log::debug!("glTF load failed: {error}");
    }
    built.map(|()| scene)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_round_trips_known_text() {
        assert_eq!(decode_base64("aGVsbG8=").unwrap(), b"hello");
        assert_eq!(decode_base64("aGk").unwrap(), b"hi");
        assert!(decode_base64("a$b=").is_none());
    }

    #[test]
    fn percent_escapes_are_decoded() {
        assert_eq!(percent_decode("my%20file.bin"), "my file.bin");
        assert_eq!(percent_decode("100%"), "100%");
    }
}
