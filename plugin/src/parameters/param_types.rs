//! The Rust types a declared parameter can have ([`ParamType`]: numbers, `bool`, colours and
//! [`Choice`] enums), how each is uploaded ([`GpuParam`]), and the codes and WGSL constants of
//! choice enums.

use super::params::{LimitError, ParamKind, ParamValue};
use crate::shader::Choice;

/// A Rust type a parameter can have: numbers, `bool`, and [`Choice`] enums.
pub trait ParamType: Copy + Sized {
    /// As a table value.
    fn to_value(self) -> ParamValue;
    /// From a table value of the right kind.
    fn from_value(value: ParamValue) -> Option<Self>;
    /// Whether it lies within `kind`'s limits; the error names `field`.
    fn check(self, field: &'static str, kind: &ParamKind) -> Result<(), LimitError> {
        let _ = (field, kind);
        Ok(())
    }
    /// Brought within `kind`'s limits; `fallback` replaces a value that has no nearest valid one
    /// (NaN).
    fn clamped(self, kind: &ParamKind, fallback: Self) -> Self {
        let _ = (kind, fallback);
        self
    }
    /// The value as a Rust expression, for "copy as Rust".
    fn rust_literal(self) -> String;
}

impl ParamType for f32 {
    fn to_value(self) -> ParamValue {
        ParamValue::Float(self)
    }

    fn rust_literal(self) -> String {
        format!("{self:?}")
    }

    fn from_value(value: ParamValue) -> Option<Self> {
        match value {
            ParamValue::Float(value) => Some(value),
            ParamValue::Integer(value) => Some(value as f32),
            _ => None,
        }
    }

    fn check(self, field: &'static str, kind: &ParamKind) -> Result<(), LimitError> {
        let ParamKind::Float { min, max, .. } = *kind else {
            return Ok(());
        };
        if !self.is_finite() {
            Err(LimitError::NotFinite { field, value: self })
        } else if self < min {
            Err(LimitError::TooSmall {
                field,
                value: ParamValue::Float(self),
                min: ParamValue::Float(min),
            })
        } else if self > max {
            Err(LimitError::TooLarge {
                field,
                value: ParamValue::Float(self),
                max: ParamValue::Float(max),
            })
        } else {
            Ok(())
        }
    }

    fn clamped(self, kind: &ParamKind, fallback: Self) -> Self {
        match *kind {
            ParamKind::Float { min, max, .. } if self.is_finite() => self.clamp(min, max),
            ParamKind::Float { .. } => fallback,
            _ => self,
        }
    }
}

impl ParamType for u32 {
    fn to_value(self) -> ParamValue {
        ParamValue::Integer(self)
    }

    fn rust_literal(self) -> String {
        self.to_string()
    }

    fn from_value(value: ParamValue) -> Option<Self> {
        match value {
            ParamValue::Integer(value) => Some(value),
            _ => None,
        }
    }

    fn check(self, field: &'static str, kind: &ParamKind) -> Result<(), LimitError> {
        let ParamKind::Integer { min, max, .. } = *kind else {
            return Ok(());
        };
        if self < min {
            Err(LimitError::TooSmall {
                field,
                value: ParamValue::Integer(self),
                min: ParamValue::Integer(min),
            })
        } else if self > max {
            Err(LimitError::TooLarge {
                field,
                value: ParamValue::Integer(self),
                max: ParamValue::Integer(max),
            })
        } else {
            Ok(())
        }
    }

    fn clamped(self, kind: &ParamKind, _: Self) -> Self {
        match *kind {
            ParamKind::Integer { min, max, .. } => self.clamp(min, max),
            _ => self,
        }
    }
}

impl ParamType for bool {
    fn to_value(self) -> ParamValue {
        ParamValue::Toggle(self)
    }

    fn rust_literal(self) -> String {
        self.to_string()
    }

    fn from_value(value: ParamValue) -> Option<Self> {
        match value {
            ParamValue::Toggle(value) => Some(value),
            _ => None,
        }
    }
}

impl ParamType for crate::Color {
    fn to_value(self) -> ParamValue {
        ParamValue::Color(self.to_array())
    }

    fn rust_literal(self) -> String {
        let Self { r, g, b, a } = self;
        format!("Color {{ r: {r:?}, g: {g:?}, b: {b:?}, a: {a:?} }}")
    }

    fn from_value(value: ParamValue) -> Option<Self> {
        match value {
            ParamValue::Color([r, g, b, a]) => Some(Self { r, g, b, a }),
            _ => None,
        }
    }

    fn check(self, field: &'static str, _: &ParamKind) -> Result<(), LimitError> {
        match self.to_array().into_iter().find(|c| !c.is_finite()) {
            Some(value) => Err(LimitError::NotFinite { field, value }),
            None => Ok(()),
        }
    }

    fn clamped(self, _: &ParamKind, fallback: Self) -> Self {
        let finite_or =
            |value: f32, fallback: f32| if value.is_finite() { value } else { fallback };
        Self {
            r: finite_or(self.r, fallback.r),
            g: finite_or(self.g, fallback.g),
            b: finite_or(self.b, fallback.b),
            a: finite_or(self.a, fallback.a),
        }
    }
}

/// How a parameter is uploaded in the GPU struct [`crate::material_parameters!`] generates:
/// 4-byte aligned types only, so the struct has no padding and WGSL lays it out as Rust does.
pub trait GpuParam: Copy {
    /// The uploaded value.
    type Gpu: bytemuck::Pod + std::fmt::Debug + PartialEq;
    /// Its WGSL type.
    const WGSL: &'static str;
    /// The value as uploaded.
    fn to_gpu(self) -> Self::Gpu;
}

impl GpuParam for f32 {
    type Gpu = f32;
    const WGSL: &'static str = "f32";
    fn to_gpu(self) -> f32 {
        self
    }
}

impl GpuParam for u32 {
    type Gpu = u32;
    const WGSL: &'static str = "u32";
    fn to_gpu(self) -> u32 {
        self
    }
}

impl GpuParam for bool {
    type Gpu = u32;
    const WGSL: &'static str = "u32";
    fn to_gpu(self) -> u32 {
        u32::from(self)
    }
}

impl GpuParam for crate::Color {
    type Gpu = [f32; 4];
    // Not `vec4<f32>`, which WGSL aligns to 16 bytes.
    const WGSL: &'static str = "array<f32, 4>";
    fn to_gpu(self) -> [f32; 4] {
        self.to_array()
    }
}

impl<T: Choice> GpuParam for T {
    type Gpu = u32;
    const WGSL: &'static str = "u32";
    fn to_gpu(self) -> u32 {
        self.code()
    }
}

impl<T: Choice> ParamType for T {
    fn to_value(self) -> ParamValue {
        ParamValue::Choice(self.name())
    }

    fn rust_literal(self) -> String {
        let type_name = std::any::type_name::<T>();
        let short = type_name.rsplit("::").next().unwrap_or(type_name);
        format!("{short}::{}", T::RUST_NAMES[self.code() as usize])
    }

    fn from_value(value: ParamValue) -> Option<Self> {
        match value {
            ParamValue::Choice(name) => Self::from_name(name),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn whole_numbers_out_of_range_are_printed_exactly() {
        let kind = ParamKind::Integer {
            min: 1,
            max: 256,
            logarithmic: false,
        };
        let error = u32::MAX.check("max_samples", &kind).unwrap_err();
        assert_eq!(
            error.to_string(),
            "max_samples is 4294967295 but must be at most 256"
        );
    }

    #[test]
    fn real_numbers_out_of_range_are_printed_as_written() {
        let kind = ParamKind::Float {
            min: 0.0,
            max: 0.5,
            editor: (0.0, 0.5),
            logarithmic: false,
        };
        let error = 0.75_f32.check("height_scale", &kind).unwrap_err();
        assert_eq!(
            error.to_string(),
            "height_scale is 0.75 but must be at most 0.5"
        );
    }
}
