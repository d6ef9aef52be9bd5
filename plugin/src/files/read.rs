//! Reading named files: regular files only, inside their allowed folder, within a bound.

use std::io::Read;
use std::path::{Component, Path, PathBuf};

/// Most bytes of a `.gltf` or `.glb` file and the buffer files it names, together.
pub const MAX_SCENE_FILE_BYTES: u64 = 512 << 20;

/// Most bytes of one image file (PNG or JPEG); decoding is bounded separately by
/// [`crate::MAX_IMAGE_PIXELS`] and [`crate::IMAGE_MEMORY_BUDGET`].
pub const MAX_IMAGE_FILE_BYTES: u64 = 256 << 20;

/// Most bytes of a text file: a scene script, a preset, a saved window state.
pub const MAX_TEXT_FILE_BYTES: u64 = 16 << 20;

/// Which files a scene (a glTF file, a scene script) may name.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum FileAccess {
    /// Only files inside the scene's own folder, after resolving `..` and symbolic links: no
    /// absolute paths, no `file:` URIs. A level or a mod cannot read the rest of the disk.
    #[default]
    InsideFolder,
    /// Any path the process can read, absolute or relative to the scene's folder: only for
    /// files you trust.
    AnyPath,
}

/// Why a named file was not read.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum FileError {
    /// The file system refused (missing file, no permission, read error).
    #[error("{path}: {reason}")]
    Io {
        /// The file.
        path: PathBuf,
        /// What the file system said.
        reason: String,
    },
    /// The path names something other than a regular file: a directory, a FIFO, a device.
    #[error("{path} is {kind}, not a regular file")]
    NotRegular {
        /// The file.
        path: PathBuf,
        /// What it is ("a directory", "a FIFO", ...).
        kind: &'static str,
    },
    /// The file is larger than the limit for what it holds.
    #[error("{path} is {size} bytes, over the limit of {limit} bytes")]
    TooLarge {
        /// The file.
        path: PathBuf,
        /// Its size (at least; a file that grew while read is cut at the limit + 1).
        size: u64,
        /// The limit.
        limit: u64,
    },
    /// The path leads outside the folder it must stay in.
    #[error(
        "{name} is outside {folder}: {rule}; only files inside the scene's folder may be named \
         unless FileAccess::AnyPath allows any"
    )]
    OutsideFolder {
        /// The path or URI as the scene wrote it.
        name: String,
        /// The folder it must stay in.
        folder: PathBuf,
        /// Why it is outside.
        rule: &'static str,
    },
}

/// What a non-regular file is, for messages.
fn describe_kind(file_type: std::fs::FileType) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if file_type.is_fifo() {
            return "a FIFO";
        }
        if file_type.is_char_device() {
            return "a character device";
        }
        if file_type.is_block_device() {
            return "a block device";
        }
        if file_type.is_socket() {
            return "a socket";
        }
    }
    if file_type.is_dir() {
        "a directory"
    } else if file_type.is_symlink() {
        "a symbolic link"
    } else {
        "not a file"
    }
}

fn io_error(path: &Path, error: std::io::Error) -> FileError {
    FileError::Io {
        path: path.to_owned(),
        reason: error.to_string(),
    }
}

/// Checks that `path` (following symbolic links) is a regular file no larger than `limit`;
/// returns its size.
pub fn check_regular(path: &Path, limit: u64) -> Result<u64, FileError> {
    let metadata = std::fs::metadata(path).map_err(|error| io_error(path, error))?;
    check_metadata(path, &metadata, limit)
}

fn check_metadata(path: &Path, metadata: &std::fs::Metadata, limit: u64) -> Result<u64, FileError> {
    if !metadata.is_file() {
        return Err(FileError::NotRegular {
            path: path.to_owned(),
            kind: describe_kind(metadata.file_type()),
        });
    }
    let size = metadata.len();
    if size > limit {
        return Err(FileError::TooLarge {
            path: path.to_owned(),
            size,
            limit,
        });
    }
    Ok(size)
}

/// Reads the regular file at `path` whole, refusing anything else (a directory, a FIFO, a
/// device such as `/dev/zero`) and anything over `limit` bytes, before reading a byte.
pub fn read_bounded(path: &Path, limit: u64) -> Result<Vec<u8>, FileError> {
    // Checked before opening: opening a FIFO blocks until a writer comes.
    check_regular(path, limit)?;
    let mut options = std::fs::OpenOptions::new();
    options.read(true);
    #[cfg(target_os = "linux")]
    {
        use std::os::unix::fs::OpenOptionsExt;
        // O_NONBLOCK: a FIFO swapped in after the check opens at once instead of hanging.
        options.custom_flags(0o4000);
    }
    let file = options.open(path).map_err(|error| io_error(path, error))?;
    // The file opened may not be the one checked: check what was opened.
    let metadata = file.metadata().map_err(|error| io_error(path, error))?;
    let size = check_metadata(path, &metadata, limit)?;
    let mut bytes = Vec::with_capacity(size as usize);
    // One byte past the limit tells a file that grew while read from one that fits.
    file.take(limit.saturating_add(1))
        .read_to_end(&mut bytes)
        .map_err(|error| io_error(path, error))?;
    if bytes.len() as u64 > limit {
        return Err(FileError::TooLarge {
            path: path.to_owned(),
            size: bytes.len() as u64,
            limit,
        });
    }
    Ok(bytes)
}

/// [`read_bounded`] of a UTF-8 text file.
pub fn read_text_bounded(path: &Path, limit: u64) -> Result<String, FileError> {
    String::from_utf8(read_bounded(path, limit)?).map_err(|_| FileError::Io {
        path: path.to_owned(),
        reason: "the file is not UTF-8 text".into(),
    })
}

/// Where `name` (a path a scene wrote, relative to its `folder`) leads, under `access`. With
/// [`FileAccess::InsideFolder`], an absolute path, or one whose `..` or symbolic links lead out
/// of `folder`, is refused without reading anything outside; the result is the canonical path
/// (of the deepest part that exists, for a file still to be written).
pub fn resolve_inside(
    folder: &Path,
    name: &Path,
    access: FileAccess,
) -> Result<PathBuf, FileError> {
    // A bare file name's folder is the empty path (`Path::parent` of "scene.gltf"), which
    // names the working folder but does not canonicalize.
    let folder = if folder.as_os_str().is_empty() {
        Path::new(".")
    } else {
        folder
    };
    let joined = folder.join(name);
    if access == FileAccess::AnyPath {
        return Ok(joined);
    }
    let outside = |rule| FileError::OutsideFolder {
        name: name.display().to_string(),
        folder: folder.to_owned(),
        rule,
    };
    let mut depth = 0_usize;
    for component in name.components() {
        match component {
            Component::Prefix(_) | Component::RootDir => return Err(outside("an absolute path")),
            Component::CurDir => {}
            Component::ParentDir => {
                depth = depth
                    .checked_sub(1)
                    .ok_or(outside("`..` leads out of it"))?;
            }
            Component::Normal(_) => depth += 1,
        }
    }
    let canonical_folder = folder
        .canonicalize()
        .map_err(|error| io_error(folder, error))?;
    // Symbolic links resolved: the deepest existing part, then the rest (which has no `..`
    // that could climb back out, or it would have existed up to there).
    let mut existing = joined.as_path();
    let mut rest = Vec::new();
    let canonical = loop {
        match existing.canonicalize() {
            Ok(canonical) => break canonical,
            Err(_) => {
                let (Some(parent), Some(last)) = (existing.parent(), existing.file_name()) else {
                    return Err(outside("it does not resolve to a path"));
                };
                rest.push(last.to_owned());
                existing = parent;
            }
        }
    };
    let resolved = rest
        .iter()
        .rev()
        .fold(canonical, |path, part| path.join(part));
    if !resolved.starts_with(&canonical_folder) {
        return Err(outside("a symbolic link leads out of it"));
    }
    Ok(resolved)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("pom-files-read-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn regular_files_within_the_limit_are_read() {
        let dir = scratch("regular");
        let file = dir.join("a.bin");
        std::fs::write(&file, b"hello").unwrap();
        assert_eq!(read_bounded(&file, 5).unwrap(), b"hello");
        let error = read_bounded(&file, 4).unwrap_err().to_string();
        assert!(
            error.contains("a.bin is 5 bytes, over the limit of 4"),
            "{error}"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn devices_are_refused_before_reading() {
        for device in ["/dev/zero", "/dev/urandom"] {
            let error = read_bounded(Path::new(device), 1 << 20)
                .unwrap_err()
                .to_string();
            assert_eq!(
                error,
                format!("{device} is a character device, not a regular file")
            );
        }
    }

    #[test]
    fn a_symlink_to_a_device_is_refused() {
        let dir = scratch("symlink");
        let link = dir.join("scene.gltf");
        std::os::unix::fs::symlink("/dev/zero", &link).unwrap();
        let error = read_bounded(&link, 1 << 20).unwrap_err().to_string();
        assert!(
            error.contains("scene.gltf is a character device"),
            "{error}"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn fifos_and_directories_say_what_they_are() {
        let dir = scratch("fifo");
        let fifo = dir.join("pipe.png");
        let made = std::process::Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .unwrap();
        assert!(made.success());
        let error = read_bounded(&fifo, 1 << 20).unwrap_err().to_string();
        assert!(
            error.ends_with("pipe.png is a FIFO, not a regular file"),
            "{error}"
        );
        let error = read_bounded(&dir, 1 << 20).unwrap_err().to_string();
        assert!(
            error.ends_with("is a directory, not a regular file"),
            "{error}"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn paths_leaving_the_folder_are_refused() {
        let dir = scratch("confine");
        let scene = dir.join("scene");
        std::fs::create_dir_all(scene.join("textures")).unwrap();
        std::fs::write(dir.join("secret.png"), b"secret").unwrap();
        std::fs::write(scene.join("textures/inside.png"), b"inside").unwrap();
        std::os::unix::fs::symlink(&dir, scene.join("up")).unwrap();
        let access = FileAccess::InsideFolder;
        for (name, rule) in [
            ("../secret.png", "`..` leads out of it"),
            ("textures/../../secret.png", "`..` leads out of it"),
            ("/etc/shadow", "an absolute path"),
            ("up/secret.png", "a symbolic link leads out of it"),
            ("up/missing/new.png", "a symbolic link leads out of it"),
        ] {
            let error = resolve_inside(&scene, Path::new(name), access)
                .unwrap_err()
                .to_string();
            assert!(error.starts_with(&format!("{name} is outside")), "{error}");
            assert!(error.contains(rule), "{error}");
        }
        let inside = resolve_inside(&scene, Path::new("textures/../textures/inside.png"), access);
        assert_eq!(read_bounded(&inside.unwrap(), 100).unwrap(), b"inside");
        let new = resolve_inside(&scene, Path::new("textures/new/ref.png"), access).unwrap();
        assert!(
            new.ends_with("scene/textures/new/ref.png"),
            "{}",
            new.display()
        );
        let allowed = resolve_inside(&scene, Path::new("../secret.png"), FileAccess::AnyPath);
        assert_eq!(read_bounded(&allowed.unwrap(), 100).unwrap(), b"secret");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    /// `Path::parent` of a bare file name ("scene.gltf") is the empty path: its files are the
    /// working folder's (cargo runs tests in the package's folder).
    #[test]
    fn the_folder_of_a_bare_file_name_is_the_working_folder() {
        let here = std::env::current_dir().unwrap().canonicalize().unwrap();
        let access = FileAccess::InsideFolder;
        let manifest = resolve_inside(Path::new(""), Path::new("Cargo.toml"), access).unwrap();
        assert_eq!(manifest, here.join("Cargo.toml"));
        let new = resolve_inside(Path::new(""), Path::new("not-yet/written.png"), access);
        assert_eq!(new.unwrap(), here.join("not-yet/written.png"));
        let error = resolve_inside(Path::new(""), Path::new("../x.png"), access).unwrap_err();
        assert!(
            error.to_string().contains("`..` leads out of it"),
            "{error}"
        );
    }
}
