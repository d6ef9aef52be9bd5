//! The shader vocabulary every other layer writes WGSL with: composing a shader from files and
//! generated constants ([`ComposedShader`]), checking a Rust struct against its WGSL twin
//! ([`check_wgsl_layout`]), and enums whose codes shaders see ([`Choice`]). It depends on
//! nothing else of the crate.

mod choice;
mod composition;
mod layout_check;

pub use choice::{Choice, ChoiceInfo};
#[cfg(test)]
pub(crate) use composition::GENERATED_HEADER;
pub use composition::{ComposedShader, GeneratedWgsl, ShaderTarget, WgslFile};
pub use layout_check::{LayoutMismatch, MemberLayout, WgslLayout, check_wgsl_layout};
