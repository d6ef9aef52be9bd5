//! Files a user or a scene names: read only when they are regular files inside the folder they
//! are allowed in, within a bound; written through a temporary file that is renamed over the
//! target only once every byte reached the disk.

mod read;
mod write;

pub use read::{
    FileAccess, FileError, MAX_IMAGE_FILE_BYTES, MAX_SCENE_FILE_BYTES, MAX_TEXT_FILE_BYTES,
    check_regular, read_bounded, read_text_bounded, resolve_inside,
};
pub use write::{WriteError, write_file, write_image, write_png};
