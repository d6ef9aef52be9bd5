//! Composing WGSL: a shader is generated constants followed by WGSL files (WGSL has no
//! `#include`), named for error messages and validation.

/// One WGSL file, by its path under `plugin/src`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct WgslFile {
    /// Path relative to `plugin/src`, for error messages and hot reload.
    pub path: &'static str,
    /// The file's text as it was at build time.
    pub source: &'static str,
}

impl WgslFile {
    /// The file `path` (a name for messages) holding `source`, often `include_str!(path)`.
    pub const fn new(path: &'static str, source: &'static str) -> Self {
        Self { path, source }
    }
}

/// A [`WgslFile`] of the plugin's own, embedded from `plugin/src/<path>` (invoked from a module
/// one folder below `src`).
#[macro_export]
#[doc(hidden)]
macro_rules! wgsl_file {
    ($path:literal) => {
        $crate::shader::WgslFile {
            path: $path,
            source: include_str!(concat!("../", $path)),
        }
    };
}

/// WGSL generated from Rust (enum codes, say), prepended to a composed shader.
pub type GeneratedWgsl = fn() -> String;

/// An entry shader: generated constants, then the files it is made of, in order.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ComposedShader {
    /// A name for labels and messages.
    pub name: &'static str,
    /// Declarations generated from Rust types, so WGSL never retypes them.
    pub constants: &'static [GeneratedWgsl],
    /// Library files first, the entry file last.
    pub files: &'static [WgslFile],
}

/// The first line of a composed source, before the generated constants.
pub(crate) const GENERATED_HEADER: &str = "// ---- generated from Rust ----\n";

impl ComposedShader {
    /// The generated constants: the text every composed source starts with.
    pub fn generated(&self) -> String {
        let mut source = String::from(GENERATED_HEADER);
        for constants in self.constants {
            source.push_str(&constants());
        }
        source
    }

    /// The concatenated source: the generated constants, then each file introduced by a
    /// comment naming it.
    pub fn source(&self) -> String {
        self.source_with(|file| file)
    }

    /// Where line `line` (1-based) of [`ComposedShader::source`] comes from: the file's path
    /// and the line in it, or `"generated"` and the line among the generated constants.
    pub fn locate(&self, line: u32) -> (&'static str, u32) {
        let generated_lines = self.generated().matches('\n').count() as u32;
        if line <= generated_lines {
            return ("generated", line);
        }
        // Each file is a header line, its text, and a line break of its own.
        let mut first = generated_lines + 1;
        for file in self.files {
            let lines = file.source.matches('\n').count() as u32 + 1;
            if line <= first + lines {
                return (file.path, line.saturating_sub(first));
            }
            first += lines + 1;
        }
        ("generated", line)
    }

    pub(crate) fn source_with(&self, substitute: impl Fn(WgslFile) -> WgslFile) -> String {
        let mut source = self.generated();
        for file in self.files.iter().map(|file| substitute(*file)) {
            source.push_str("// ---- ");
            source.push_str(file.path);
            source.push_str(" ----\n");
            source.push_str(file.source);
            source.push('\n');
        }
        source
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_line_of_a_composed_source_is_found_in_its_file() {
        const A: WgslFile = WgslFile {
            path: "a.wgsl",
            source: "fn a() {}\nfn b() {}",
        };
        const B: WgslFile = WgslFile {
            path: "b.wgsl",
            source: "// one\n// two\n// three\n",
        };
        fn constants() -> String {
            "const X: u32 = 1u;\nconst Y: u32 = 2u;\n".to_owned()
        }
        let shader = ComposedShader {
            name: "test",
            constants: &[constants],
            files: &[A, B],
        };
        let source = shader.source();
        for (index, text) in source.lines().enumerate() {
            let (path, line) = shader.locate(index as u32 + 1);
            let file = [A, B].into_iter().find(|file| file.path == path);
            match file {
                Some(file) if line > 0 => assert_eq!(
                    file.source.lines().nth(line as usize - 1).unwrap_or(""),
                    text,
                    "line {} of the composed source",
                    index + 1
                ),
                // The header line introducing a file, or a generated line.
                _ => assert!(
                    text.starts_with("// ----") || text.starts_with("const"),
                    "{text}"
                ),
            }
        }
    }
}
