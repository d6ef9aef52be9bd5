//! Shader hot reload: watch the WGSL files of every registered material on disk and, when one
//! changes, recompose, check and recompile the materials' shaders and swap their pipelines in. A
//! broken edit keeps the last good pipelines and reports the error with the file and line.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::time::SystemTime;

use crate::gpu::GpuContext;
use crate::material::MaterialRegistry;
use crate::render::shaders::{ComposedShader, ShaderTarget};
use crate::{App, AppError, Plugin, Resources, Stage};

/// Why a reload did not swap the pipelines in.
#[derive(Clone, Debug, thiserror::Error, PartialEq, Eq)]
#[non_exhaustive]
pub enum ShaderReloadError {
    /// A WGSL file could not be read.
    #[error("cannot read {path}: {reason}")]
    Read {
        /// The file, on disk.
        path: PathBuf,
        /// The operating system's explanation.
        reason: String,
    },
    /// A WGSL file does not parse or validate.
    #[error("{file}:{line}:{column}: {message}")]
    Invalid {
        /// The file, relative to the plugin's `src` folder.
        file: String,
        /// 1-based line in that file (0 when the error has no position).
        line: u32,
        /// 1-based column.
        column: u32,
        /// naga's message.
        message: String,
    },
    /// The device rejected the shader or its pipelines.
    #[error("{shader}: the GPU device rejected it: {message}")]
    Device {
        /// The composed shader's name.
        shader: &'static str,
        /// wgpu's message.
        message: String,
    },
}

/// Watches WGSL files under a source folder and reloads the shaders that use a changed one.
///
/// Add it after the material plugins; it polls the files' modification times once a frame in
/// [`Stage::PostUpdate`] and keeps its outcome in a [`ShaderReloadStatus`] resource.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ShaderHotReload {
    /// The folder the [`crate::render::shaders::WgslFile`] paths are relative to (the plugin's `src`).
    pub source_dir: PathBuf,
}

impl ShaderHotReload {
    /// Watches the plugin's sources of the repository `dir` lies in (`plugin/src` in `dir` or a
    /// folder above it); `None` outside a checkout. A binary passes its working directory: no
    /// path is baked in at build time, so a binary copied elsewhere watches nothing.
    pub fn from_repository(dir: &Path) -> Option<Self> {
        dir.ancestors()
            .map(|folder| folder.join("plugin").join("src"))
            .find(|sources| sources.join("render").join("frame.wgsl").is_file())
            .map(|source_dir| Self { source_dir })
    }
}

/// The outcome of shader hot reload so far. A resource.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ShaderReloadStatus {
    /// The folder being watched.
    pub source_dir: PathBuf,
    /// How many times changed shaders were swapped in.
    pub reloads: u32,
    /// The error of the last attempt, if it failed (the previous pipelines are still in use).
    pub error: Option<ShaderReloadError>,
}

/// Modification times seen at the last poll. A resource.
#[derive(Debug, Default)]
struct WatchedFiles {
    modified: HashMap<&'static str, Option<SystemTime>>,
}

/// The shaders hot reload rebuilds: every registered material's (the Sobel compute pass is not
/// reloaded).
fn reloaded_shaders(resources: &Resources) -> Vec<ComposedShader> {
    resources
        .get::<MaterialRegistry>()
        .map(|registry| registry.entries.iter().map(|entry| entry.shader).collect())
        .unwrap_or_default()
}

impl Plugin for ShaderHotReload {
    fn build(&self, app: &mut App) {
        let mut watched = WatchedFiles::default();
        for file in reloaded_shaders(&app.resources)
            .iter()
            .flat_map(|shader| shader.files)
        {
            let modified = modified_time(&self.source_dir.join(file.path));
            watched.modified.insert(file.path, modified);
        }
        app.insert_resource(watched);
        app.insert_resource(ShaderReloadStatus {
            source_dir: self.source_dir.clone(),
            ..ShaderReloadStatus::default()
        });
        app.add_system(Stage::PostUpdate, reload_changed_shaders);
    }
}

fn modified_time(path: &Path) -> Option<SystemTime> {
    std::fs::metadata(path).and_then(|m| m.modified()).ok()
}

/// The [`Stage::PostUpdate`] system of [`ShaderHotReload`]: reloads the shaders whose files
/// changed since the last frame.
pub fn reload_changed_shaders(
    _: &mut hecs::World,
    resources: &mut Resources,
) -> Result<(), AppError> {
    let Some(status) = resources.get::<ShaderReloadStatus>() else {
        return Ok(());
    };
    let source_dir = status.source_dir.clone();
    let Some(watched) = resources.get_mut::<WatchedFiles>() else {
        return Ok(());
    };
    let mut changed_files = Vec::new();
    for (path, seen) in &mut watched.modified {
        let now = modified_time(&source_dir.join(path));
        if now != *seen {
            *seen = now;
            changed_files.push(*path);
        }
    }
    if changed_files.is_empty() {
        return Ok(());
    }
    let changed: Vec<ComposedShader> = reloaded_shaders(resources)
        .into_iter()
        .filter(|shader| shader.files.iter().any(|f| changed_files.contains(&f.path)))
        .collect();
    let outcome = reload(resources, &source_dir, &changed);
    match &outcome {
        Ok(()) => log::info!("shaders reloaded after editing {changed_files:?}"),
        Err(error) => log::error!("shader reload failed, keeping the last good pipelines: {error}"),
    }
    if let Some(status) = resources.get_mut::<ShaderReloadStatus>() {
        match outcome {
            Ok(()) => {
                status.reloads += 1;
                status.error = None;
            }
            Err(error) => status.error = Some(error),
        }
    }
    Ok(())
}

/// Checks and compiles every shader in `changed`, then swaps all their pipelines in at once.
fn reload(
    resources: &mut Resources,
    source_dir: &Path,
    changed: &[ComposedShader],
) -> Result<(), ShaderReloadError> {
    let gpu = resources
        .get::<GpuContext>()
        .ok_or_else(|| ShaderReloadError::Device {
            shader: "all",
            message: "no GPU context".into(),
        })?
        .clone();
    let mut rebuilt = Vec::new();
    for shader in changed {
        let device = &gpu.device;
        // A deferred shader writes the scene in the target's format.
        let scene_format = resources
            .get::<crate::render::RenderTarget>()
            .map_or(wgpu::TextureFormat::Rgba16Float, |target| {
                target.scene_format()
            });
        let target = ShaderTarget::of_device(device, scene_format);
        let source = compose_checked(shader, source_dir, &target)?;
        let validation = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let module = crate::render::shaders::create_module(device, shader.name, source);
        if let Some(registry) = resources.get::<MaterialRegistry>() {
            for entry in &registry.entries {
                if entry.shader == *shader
                    && let Some(pipelines) = (entry.rebuild)(resources, device, module.clone())
                {
                    rebuilt.push((entry.swap, pipelines));
                }
            }
        }
        if let Some(error) = pollster::block_on(validation.pop()) {
            return Err(ShaderReloadError::Device {
                shader: shader.name,
                message: error.to_string(),
            });
        }
    }
    for (swap, pipelines) in rebuilt {
        swap(resources, pipelines);
    }
    Ok(())
}

/// Where each file starts in a composed source: (path, first line, 1-based).
type FileLines = Vec<(&'static str, u32)>;

/// `shader`'s source composed for `target` from the files under `source_dir`, parsed and
/// validated by naga so that errors name the file and line they come from.
pub fn compose_checked(
    shader: &ComposedShader,
    source_dir: &Path,
    target: &ShaderTarget,
) -> Result<String, ShaderReloadError> {
    let mut source = shader.generated_for(target);
    let mut starts: FileLines = Vec::new();
    for file in shader.files {
        let path = source_dir.join(file.path);
        let text = crate::files::read_text_bounded(&path, crate::files::MAX_TEXT_FILE_BYTES)
            .map_err(|error| ShaderReloadError::Read {
                path: path.clone(),
                reason: error.to_string(),
            })?;
        // The same layout as ComposedShader::source: a comment line, the file, a newline.
        source.push_str("// ---- ");
        source.push_str(file.path);
        source.push_str(" ----\n");
        starts.push((file.path, line_count(&source) + 1));
        source.push_str(&target.file_text(&text));
        source.push('\n');
    }
    let invalid = |location: Option<naga::SourceLocation>, message: String| {
        let (line, column) = location.map_or((0, 0), |l| (l.line_number, l.line_position));
        let (file, first) = starts
            .iter()
            .rev()
            .find(|(_, first)| line >= *first)
            .copied()
            .unwrap_or((shader.name, 1));
        ShaderReloadError::Invalid {
            file: file.to_owned(),
            line: if line == 0 { 0 } else { line - first + 1 },
            column,
            message,
        }
    };
    let module = naga::front::wgsl::parse_str(&source)
        .map_err(|error| invalid(error.location(&source), error.message().to_owned()))?;
    naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::all(),
    )
    .validate(&module)
    .map_err(|error| invalid(error.location(&source), error.as_inner().to_string()))?;
    Ok(source)
}

fn line_count(text: &str) -> u32 {
    u32::try_from(text.bytes().filter(|b| *b == b'\n').count()).unwrap_or(u32::MAX)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn copy_sources(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("pom-reload-{name}-{}", std::process::id()));
        for file in crate::parallax::PARALLAX_SHADER.files {
            let path = dir.join(file.path);
            std::fs::create_dir_all(path.parent().unwrap()).unwrap();
            std::fs::write(path, file.source).unwrap();
        }
        dir
    }

    #[test]
    fn the_shipped_files_compose_to_the_embedded_source() {
        let dir = copy_sources("same");
        let source = compose_checked(
            &crate::parallax::PARALLAX_SHADER,
            &dir,
            &ShaderTarget::default(),
        )
        .unwrap();
        assert_eq!(source, crate::parallax::PARALLAX_SHADER.source());
        std::fs::remove_dir_all(dir).unwrap();
    }

    #[test]
    fn a_syntax_error_names_the_file_and_its_own_line() {
        let dir = copy_sources("syntax");
        let path = dir.join("parallax/march.wgsl");
        let text = std::fs::read_to_string(&path).unwrap();
        std::fs::write(&path, format!("// first\nfn broken( {{\n{text}")).unwrap();
        let error = compose_checked(
            &crate::parallax::PARALLAX_SHADER,
            &dir,
            &ShaderTarget::default(),
        )
        .unwrap_err();
        let ShaderReloadError::Invalid { file, line, .. } = &error else {
            panic!("{error}");
        };
        assert_eq!(
            (file.as_str(), *line),
            ("parallax/march.wgsl", 2),
            "{error}"
        );
        std::fs::remove_dir_all(dir).unwrap();
    }

    #[test]
    fn a_type_error_is_caught_before_the_gpu_sees_it() {
        let dir = copy_sources("types");
        let path = dir.join("parallax/pom.wgsl");
        let text = std::fs::read_to_string(&path).unwrap();
        std::fs::write(
            &path,
            format!("{text}\nfn wrong() -> f32 {{ return vec2<f32>(1.0); }}\n"),
        )
        .unwrap();
        let error = compose_checked(
            &crate::parallax::PARALLAX_SHADER,
            &dir,
            &ShaderTarget::default(),
        )
        .unwrap_err();
        assert!(
            error.to_string().starts_with("parallax/pom.wgsl:"),
            "{error}"
        );
        let missing =
            compose_checked(&crate::lit::LIT_SHADER, &dir, &ShaderTarget::default()).unwrap_err();
        assert!(
            matches!(missing, ShaderReloadError::Read { .. }),
            "{missing}"
        );
        std::fs::remove_dir_all(dir).unwrap();
    }
}
