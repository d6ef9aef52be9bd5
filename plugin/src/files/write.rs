//! Writing files so that a failed write never leaves a truncated file in place of a good one:
//! the bytes go to a new temporary file in the target's folder, which is synced and renamed over
//! the target only once every byte reached the disk.
//!
//! A target that exists and is not a regular file (a device such as `/dev/full` or
//! `/dev/stdout`, a pipe), directly or through a symbolic link, is written in place instead:
//! renaming would replace the link or device node, not write to it. A symbolic link to a regular
//! file is followed, so the file it names is replaced and the link kept.

use std::fs::{File, OpenOptions};
use std::io::{Cursor, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

use image::{DynamicImage, ImageBuffer, ImageFormat};

/// Why a file could not be written. Nothing is left at the target but what was there before.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum WriteError {
    /// The file system refused a step of the write (create, write, sync, rename).
    #[error("writing {}: {reason}", path.display())]
    Io {
        /// The file asked for.
        path: PathBuf,
        /// What the operating system said.
        reason: std::io::Error,
    },
    /// The image could not be encoded in the file's format.
    #[error("encoding {}: {reason}", path.display())]
    Encode {
        /// The file asked for.
        path: PathBuf,
        /// What the encoder said.
        reason: String,
    },
}

impl WriteError {
    /// What went wrong, without the path (for messages that name the file themselves).
    pub fn reason(&self) -> String {
        match self {
            WriteError::Io { reason, .. } => reason.to_string(),
            WriteError::Encode { reason, .. } => reason.clone(),
        }
    }
}

/// Writes `bytes` to `path` completely or not at all: through a temporary file beside it that
/// is synced to disk, closed and renamed over `path` (see the module's notes on devices and
/// links). On any failure the temporary file is removed and the error names `path`.
pub fn write_file(path: &Path, bytes: &[u8]) -> Result<(), WriteError> {
    let io_error = |reason| WriteError::Io {
        path: path.to_owned(),
        reason,
    };
    match std::fs::metadata(path) {
        Ok(existing) if !existing.is_file() && !existing.is_dir() => {
            write_in_place(path, bytes).map_err(io_error)
        }
        Ok(existing) if existing.is_file() => {
            // Follows a symbolic link, so the file it names is replaced rather than the link.
            let target = std::fs::canonicalize(path).map_err(io_error)?;
            write_through_temporary(&target, bytes, Some(existing.permissions())).map_err(io_error)
        }
        _ => write_through_temporary(path, bytes, None).map_err(io_error),
    }
}

/// Encodes `image` as a PNG in memory and writes it with [`write_file`].
pub fn write_png<P, C>(path: &Path, image: &ImageBuffer<P, C>) -> Result<(), WriteError>
where
    P: image::PixelWithColorType,
    [P::Subpixel]: image::EncodableLayout,
    C: std::ops::Deref<Target = [P::Subpixel]>,
{
    encode_and_write(path, |bytes| image.write_to(bytes, ImageFormat::Png))
}

/// Encodes `image` in the format `path`'s extension names (`.png`, `.jpg`) in memory and writes
/// it with [`write_file`].
pub fn write_image(path: &Path, image: &DynamicImage) -> Result<(), WriteError> {
    let format = ImageFormat::from_path(path).map_err(|error| WriteError::Encode {
        path: path.to_owned(),
        reason: error.to_string(),
    })?;
    encode_and_write(path, |bytes| image.write_to(bytes, format))
}

/// Runs `encode` into a buffer, then writes the buffer to `path`.
fn encode_and_write(
    path: &Path,
    encode: impl FnOnce(&mut Cursor<Vec<u8>>) -> image::ImageResult<()>,
) -> Result<(), WriteError> {
    let mut bytes = Cursor::new(Vec::new());
    encode(&mut bytes).map_err(|error| WriteError::Encode {
        path: path.to_owned(),
        reason: error.to_string(),
    })?;
    write_file(path, bytes.get_ref())
}

/// Writes into an existing device or pipe. There is no disk behind it to sync (and syncing a
/// pipe is an error), so the write and flush are what can fail: `/dev/full` fails the write.
fn write_in_place(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let mut file = OpenOptions::new().write(true).open(path)?;
    file.write_all(bytes)?;
    file.flush()
}

/// Writes `bytes` into a new temporary file beside `path` (with `permissions`, those of the file
/// it replaces), syncs and closes it, and renames it over `path`; removes it on failure.
fn write_through_temporary(
    path: &Path,
    bytes: &[u8],
    permissions: Option<std::fs::Permissions>,
) -> std::io::Result<()> {
    let (temporary, mut file) = create_temporary(path)?;
    let written = (|| {
        if let Some(permissions) = permissions {
            file.set_permissions(permissions)?;
        }
        file.write_all(bytes)?;
        file.flush()?;
        // Once synced, closing cannot lose data: every write error has been reported here.
        file.sync_all()?;
        drop(file);
        std::fs::rename(&temporary, path)
    })();
    if written.is_err() {
        let _ = std::fs::remove_file(&temporary);
    }
    written
}

/// Creates a temporary file in `path`'s folder under a name no other write uses: the process
/// and a counter make it unique, and `create_new` refuses to reuse a file someone else made.
fn create_temporary(path: &Path) -> std::io::Result<(PathBuf, File)> {
    static NEXT: AtomicU64 = AtomicU64::new(0);
    let name = path
        .file_name()
        .map_or_else(|| "file".into(), |name| name.to_string_lossy());
    loop {
        let count = NEXT.fetch_add(1, Ordering::Relaxed);
        let temporary = path.with_file_name(format!(".{name}.{}-{count}.tmp", std::process::id()));
        match OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&temporary)
        {
            Ok(file) => return Ok((temporary, file)),
            Err(error) if error.kind() == std::io::ErrorKind::AlreadyExists => continue,
            Err(error) => return Err(error),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A fresh folder under the system temp dir for one test.
    fn folder(test: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("pom-write-{test}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    /// The names in `dir`.
    fn names(dir: &Path) -> Vec<String> {
        let mut names: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|entry| entry.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    }

    #[test]
    fn a_write_replaces_the_file_and_leaves_no_temporary() {
        let dir = folder("replace");
        let path = dir.join("out.txt");
        write_file(&path, b"first").unwrap();
        write_file(&path, b"second").unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), b"second");
        assert_eq!(names(&dir), ["out.txt"]);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_full_device_behind_a_link_is_an_error_naming_the_link() {
        let dir = folder("full");
        let path = dir.join("x.png");
        std::os::unix::fs::symlink("/dev/full", &path).unwrap();
        let error = write_file(&path, b"bytes").unwrap_err();
        let text = error.to_string();
        assert!(text.contains("x.png"), "{text}");
        assert!(
            matches!(&error, WriteError::Io { reason, .. } if reason.raw_os_error() == Some(28)),
            "{error:?}"
        );
        // The link is still a link to the device, not a file that replaced it.
        assert!(std::fs::symlink_metadata(&path).unwrap().is_symlink());
        assert_eq!(names(&dir), ["x.png"]);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_link_to_a_file_is_kept_and_the_file_it_names_replaced() {
        let dir = folder("link");
        let real = dir.join("real.txt");
        let link = dir.join("link.txt");
        std::fs::write(&real, b"old").unwrap();
        std::os::unix::fs::symlink(&real, &link).unwrap();
        write_file(&link, b"new").unwrap();
        assert!(std::fs::symlink_metadata(&link).unwrap().is_symlink());
        assert_eq!(std::fs::read(&real).unwrap(), b"new");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_missing_folder_is_an_error_naming_the_file() {
        let dir = folder("missing");
        let path = dir.join("no-such-folder").join("out.png");
        let error = write_png(&path, &image::RgbaImage::new(2, 2)).unwrap_err();
        assert!(
            error.to_string().contains("no-such-folder/out.png"),
            "{error}"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn an_unknown_extension_is_an_encoding_error() {
        let dir = folder("extension");
        let path = dir.join("out.unknown");
        let image = DynamicImage::ImageRgba8(image::RgbaImage::new(2, 2));
        let error = write_image(&path, &image).unwrap_err();
        assert!(matches!(error, WriteError::Encode { .. }), "{error:?}");
        assert!(names(&dir).is_empty());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
