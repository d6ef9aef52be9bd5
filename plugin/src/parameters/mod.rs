//! Material parameters, each declared once: name, type, default, limits, unit and help
//! ([`crate::material_parameters!`]), and what is generated from that declaration (the
//! [`Param`] table that scripts, presets, the command line and editors walk, limit checks,
//! the GPU struct and its WGSL, [`DeclaredMaterial`]). No GPU work: the layer sits above the
//! renderer's vocabulary and below the material seam, which builds on it.

mod declare;
mod param_types;
mod params;

pub use declare::DeclaredMaterial;
pub use param_types::{GpuParam, ParamType};
pub use params::{
    LimitError, Param, ParamError, ParamGroup, ParamKind, ParamSpec, ParamValue,
    every_parameter_changed,
};
