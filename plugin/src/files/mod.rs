//! Files a user or a scene names: read only when they are regular files inside the folder they
//! are allowed in, within a bound; written through a temporary file that is renamed over the
//! target only once every byte reached the disk.

mod read;
mod write;

pub use write::{WriteError, write_file, write_image, write_png};
