//! Checks that a Rust `#[repr(C)]` struct and the WGSL struct it is uploaded into agree, member
//! by member (name, offset, size) and in total size, as naga lays the WGSL out: a moved, added,
//! removed, resized or renamed member fails. (A member of the same size but another scalar type,
//! `f32` for `u32`, is not caught.)

/// One member of a Rust struct as uploaded: its name, byte offset and size.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MemberLayout {
    /// The field name (the WGSL member must have the same).
    pub name: &'static str,
    /// Byte offset in the struct.
    pub offset: usize,
    /// Size in bytes.
    pub size: usize,
}

/// A Rust struct that has a WGSL twin. Implement it with [`crate::wgsl_layout!`].
pub trait WgslLayout: Sized {
    /// The members in declaration order.
    fn members() -> Vec<MemberLayout>;
}

/// Implements [`WgslLayout`] for a `#[repr(C)]` struct from its field names.
///
/// ```
/// #[repr(C)]
/// #[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
/// struct Tint { color: [f32; 4], strength: f32, _padding: [f32; 3] }
/// pom::wgsl_layout!(Tint { color, strength, _padding });
/// // Not `vec3<f32>`: WGSL aligns it to 16 bytes, which `[f32; 3]` is not.
/// let wgsl = "struct Tint { color: vec4<f32>, strength: f32, _padding: array<f32, 3> }";
/// assert!(pom::shader::check_wgsl_layout::<Tint>(wgsl, "Tint").is_ok());
/// ```
#[macro_export]
macro_rules! wgsl_layout {
    ($ty:ty { $($field:ident),* $(,)? }) => {
        impl $crate::shader::WgslLayout for $ty {
            fn members() -> Vec<$crate::shader::MemberLayout> {
                fn size_of_field<S, T>(_: fn(&S) -> &T) -> usize {
                    ::std::mem::size_of::<T>()
                }
                vec![$(
                    $crate::shader::MemberLayout {
                        name: stringify!($field),
                        offset: ::std::mem::offset_of!($ty, $field),
                        size: size_of_field::<$ty, _>(|value| &value.$field),
                    }
                ),*]
            }
        }
    };
}

/// How a Rust struct and its WGSL twin differ.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum LayoutMismatch {
    /// The WGSL does not parse.
    #[error("the WGSL does not parse: {0}")]
    Parse(String),
    /// No struct of that name in the WGSL.
    #[error("no WGSL struct named {0}")]
    NoStruct(String),
    /// Different member lists, or a member at another offset or of another size.
    #[error("{structure}: Rust has {rust:?}, WGSL has {wgsl:?}")]
    Members {
        /// The struct.
        structure: String,
        /// (name, offset, size) of each Rust field.
        rust: Vec<(String, usize, usize)>,
        /// (name, offset, size) of each WGSL member.
        wgsl: Vec<(String, usize, usize)>,
    },
    /// Same members, but the WGSL struct has another size (trailing padding).
    #[error("{structure}: Rust size {rust} bytes, WGSL size {wgsl} bytes")]
    Size {
        /// The struct.
        structure: String,
        /// `size_of` of the Rust struct.
        rust: usize,
        /// naga's span of the WGSL struct.
        wgsl: usize,
    },
}

/// Compares `T`'s layout with the struct `name` in the WGSL `source` (naga's layouter: name,
/// offset and size of every member, and the struct's size).
pub fn check_wgsl_layout<T: WgslLayout>(source: &str, name: &str) -> Result<(), LayoutMismatch> {
    let module = naga::front::wgsl::parse_str(source)
        .map_err(|error| LayoutMismatch::Parse(error.emit_to_string(source)))?;
    let mut layouter = naga::proc::Layouter::default();
    layouter
        .update(module.to_ctx())
        .map_err(|error| LayoutMismatch::Parse(error.to_string()))?;
    let (members, span) = module
        .types
        .iter()
        .find_map(|(_, ty)| match (&ty.name, &ty.inner) {
            (Some(type_name), naga::TypeInner::Struct { members, span }) if type_name == name => {
                Some((members, *span))
            }
            _ => None,
        })
        .ok_or_else(|| LayoutMismatch::NoStruct(name.to_owned()))?;
    let wgsl: Vec<(String, usize, usize)> = members
        .iter()
        .map(|member| {
            (
                member.name.clone().unwrap_or_default(),
                member.offset as usize,
                layouter[member.ty].size as usize,
            )
        })
        .collect();
    let rust: Vec<(String, usize, usize)> = T::members()
        .iter()
        .map(|member| (member.name.to_owned(), member.offset, member.size))
        .collect();
    if rust != wgsl {
        return Err(LayoutMismatch::Members {
            structure: name.to_owned(),
            rust,
            wgsl,
        });
    }
    if span as usize != std::mem::size_of::<T>() {
        return Err(LayoutMismatch::Size {
            structure: name.to_owned(),
            rust: std::mem::size_of::<T>(),
            wgsl: span as usize,
        });
    }
    Ok(())
}
