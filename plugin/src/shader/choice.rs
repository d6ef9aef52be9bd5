//! Enums whose values shaders see as codes: [`Choice`] (one spelling per value, for serde, the
//! command line and the editor, and a generated WGSL constant per value) and
//! [`crate::choice_enum!`], which declares one.

/// One value of a [`Choice`] type: its spelling (the same in RON, glTF, on the command line and
/// in the editor) and a one-line help.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ChoiceInfo {
    /// The spelling.
    pub name: &'static str,
    /// One line saying what it does.
    pub help: &'static str,
}

/// An enum whose values a parameter chooses between, declared with [`crate::choice_enum!`]: each
/// value has one spelling, used by serde (RON, glTF), the command line and the editor, and a
/// WGSL constant `PREFIX_VALUE` with its code.
pub trait Choice: Copy + PartialEq + 'static {
    /// Every value, in declaration order (its index is its code).
    const VALUES: &'static [Self];
    /// Spelling and help of each value, in the same order.
    const INFO: &'static [ChoiceInfo];
    /// The prefix of the WGSL constants (`METHOD` gives `METHOD_OCCLUSION`).
    const WGSL_PREFIX: &'static str;
    /// The Rust names of the values, for WGSL constant names.
    const RUST_NAMES: &'static [&'static str];

    /// The position of `self` in [`Choice::VALUES`]: the value shaders see.
    fn code(self) -> u32 {
        Self::VALUES
            .iter()
            .position(|value| *value == self)
            .unwrap_or(0) as u32
    }

    /// The one spelling of `self`.
    fn name(self) -> &'static str {
        Self::INFO[self.code() as usize].name
    }

    /// The value spelled `name`.
    fn from_name(name: &str) -> Option<Self> {
        Self::INFO
            .iter()
            .position(|info| info.name == name)
            .map(|index| Self::VALUES[index])
    }

    /// WGSL declarations of one `const PREFIX_VALUE: u32` per value, generated so shaders never
    /// retype the codes.
    fn wgsl_constants() -> String {
        Self::RUST_NAMES
            .iter()
            .enumerate()
            .map(|(code, rust_name)| {
                format!(
                    "const {}_{}: u32 = {code}u;\n",
                    Self::WGSL_PREFIX,
                    screaming_snake_case(rust_name)
                )
            })
            .collect()
    }
}

/// Declares an enum whose values a material parameter chooses between: one spelling per value
/// (serde, command line, editor), a one-line help each, and generated WGSL constants.
///
/// ```
/// pom::choice_enum! {
///     /// How a stripe pattern runs.
///     pub enum Stripes: "STRIPES" {
///         /// Left to right.
///         Horizontal = "horizontal",
///         /// Top to bottom.
///         Vertical = "vertical",
///     }
/// }
/// use pom::shader::Choice;
/// assert_eq!(Stripes::Vertical.name(), "vertical");
/// assert!(Stripes::wgsl_constants().contains("const STRIPES_VERTICAL: u32 = 1u;"));
/// ```
#[macro_export]
macro_rules! choice_enum {
    (
        $(#[$attr:meta])*
        pub enum $name:ident : $prefix:literal {
            $(
                #[doc = $help:literal]
                $variant:ident = $spelling:literal,
            )*
        }
    ) => {
        $(#[$attr])*
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
        #[derive($crate::serde::Serialize, $crate::serde::Deserialize)]
        #[serde(crate = "pom::serde")]
        #[non_exhaustive]
        pub enum $name {
            $(
                #[doc = $help]
                #[serde(rename = $spelling)]
                $variant,
            )*
        }

        impl $crate::shader::Choice for $name {
            const VALUES: &'static [Self] = &[$($name::$variant),*];
            const INFO: &'static [$crate::shader::ChoiceInfo] = &[
                $($crate::shader::ChoiceInfo { name: $spelling, help: $help }),*
            ];
            const WGSL_PREFIX: &'static str = $prefix;
            const RUST_NAMES: &'static [&'static str] = &[$(stringify!($variant)),*];
        }
    };
}

/// `CookTorrance` → `COOK_TORRANCE`.
fn screaming_snake_case(name: &str) -> String {
    let mut out = String::new();
    for (index, character) in name.chars().enumerate() {
        if character.is_uppercase() && index > 0 {
            out.push('_');
        }
        out.push(character.to_ascii_uppercase());
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn screaming_snake_case_splits_words() {
        assert_eq!(screaming_snake_case("CookTorrance"), "COOK_TORRANCE");
        assert_eq!(screaming_snake_case("Occlusion"), "OCCLUSION");
    }
}
