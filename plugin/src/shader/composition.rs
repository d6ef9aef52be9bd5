//! Composing WGSL: a shader is generated constants followed by WGSL files (WGSL has no
//! `#include`), named for error messages and validation, composed for a [`ShaderTarget`].

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

/// A [`WgslFile`] of the plugin's own, embedded from `plugin/src/<path>`: invoked from a module
/// one folder below `src`, or with `nested` from one two folders below (`include_str!` reads
/// relative to the invoking file).
#[macro_export]
#[doc(hidden)]
macro_rules! wgsl_file {
    ($path:literal) => {
        $crate::shader::WgslFile {
            path: $path,
            source: include_str!(concat!("../", $path)),
        }
    };
    (nested $path:literal) => {
        $crate::shader::WgslFile {
            path: $path,
            source: include_str!(concat!("../../", $path)),
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

/// What a composition is compiled for. The composer writes it into the WGSL (the shader's text
/// is never searched or edited afterwards): `SceneOutput`, the scene target as the deferred
/// resolve writes it, whether `@early_depth_test` attributes stay, and what
/// `count_fragment_invocation()` does.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ShaderTarget {
    /// The HDR scene target's format (`Rgba16Float` or `Rgba32Float`).
    pub scene_format: wgpu::TextureFormat,
    /// Whether the adapter takes `@early_depth_test` (`SHADER_EARLY_DEPTH_TEST`: Vulkan,
    /// GLES). Without it the composer leaves the attributes out: they only promise what the
    /// shader does anyway (forced early tests where it writes no depth and has no side effects,
    /// depth only ever pushed further away), so leaving them out costs speed, not pixels.
    pub early_depth_test: bool,
    /// The group-0 binding of the atomic counter `count_fragment_invocation()` adds one to
    /// (a test's measurement of how many fragments ran), or `None`: it does nothing.
    pub fragment_counter: Option<u32>,
}

impl Default for ShaderTarget {
    /// An `Rgba16Float` scene, early depth tests kept: what `ComposedShader::source` gives.
    fn default() -> Self {
        Self {
            scene_format: wgpu::TextureFormat::Rgba16Float,
            early_depth_test: true,
            fragment_counter: None,
        }
    }
}

impl ShaderTarget {
    /// The target of `device` with a scene of `scene_format`.
    pub fn of_device(device: &wgpu::Device, scene_format: wgpu::TextureFormat) -> Self {
        Self {
            scene_format,
            early_depth_test: device
                .features()
                .contains(wgpu::Features::SHADER_EARLY_DEPTH_TEST),
            fragment_counter: None,
        }
    }

    /// The declarations every composed source starts with: `SceneOutput` and
    /// `count_fragment_invocation()` (one line each, whatever the target, so line numbers never
    /// depend on it).
    fn declarations(&self) -> String {
        let format = match self.scene_format {
            wgpu::TextureFormat::Rgba32Float => "rgba32float",
            _ => "rgba16float",
        };
        let counter = match self.fragment_counter {
            Some(binding) => format!(
                "@group(0) @binding({binding}) var<storage, read_write> fragment_invocations: atomic<u32>; \
                 fn count_fragment_invocation() {{ atomicAdd(&fragment_invocations, 1u); }}"
            ),
            None => "fn count_fragment_invocation() {}".to_owned(),
        };
        format!("alias SceneOutput = texture_storage_2d<{format}, write>;\n{counter}\n")
    }

    /// `text` as this target compiles it.
    pub(crate) fn file_text<'a>(&self, text: &'a str) -> std::borrow::Cow<'a, str> {
        if self.early_depth_test {
            text.into()
        } else {
            without_early_depth_tests(text).into()
        }
    }
}

/// `source` without its `@early_depth_test(...)` attributes.
fn without_early_depth_tests(source: &str) -> String {
    const ATTRIBUTE: &str = "@early_depth_test(";
    let mut out = String::with_capacity(source.len());
    let mut rest = source;
    while let Some(start) = rest.find(ATTRIBUTE) {
        out.push_str(&rest[..start]);
        let after = &rest[start + ATTRIBUTE.len()..];
        rest = after.find(')').map_or("", |close| &after[close + 1..]);
    }
    out.push_str(rest);
    out
}

impl ComposedShader {
    /// The generated declarations and constants: the text every composed source starts with.
    pub fn generated(&self) -> String {
        self.generated_for(&ShaderTarget::default())
    }

    /// [`ComposedShader::generated`] for `target`.
    pub fn generated_for(&self, target: &ShaderTarget) -> String {
        let mut source = String::from(GENERATED_HEADER);
        for constants in self.constants {
            source.push_str(&constants());
        }
        // Last: directives (`enable`) among the constants must come before any declaration.
        source.push_str(&target.declarations());
        source
    }

    /// The concatenated source for the default [`ShaderTarget`]: the generated constants, then
    /// each file introduced by a comment naming it.
    pub fn source(&self) -> String {
        self.source_for(&ShaderTarget::default())
    }

    /// [`ComposedShader::source`] for `target`.
    pub fn source_for(&self, target: &ShaderTarget) -> String {
        self.source_with(target, |file| file)
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

    pub(crate) fn source_with(
        &self,
        target: &ShaderTarget,
        substitute: impl Fn(WgslFile) -> WgslFile,
    ) -> String {
        let mut source = self.generated_for(target);
        for file in self.files.iter().map(|file| substitute(*file)) {
            source.push_str("// ---- ");
            source.push_str(file.path);
            source.push_str(" ----\n");
            source.push_str(&target.file_text(file.source));
            source.push('\n');
        }
        source
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn early_depth_attributes_are_dropped_and_nothing_else() {
        let source = "@fragment @early_depth_test(force)\nfn a() {}\n@fragment @early_depth_test(greater_equal)\nfn b() -> @builtin(frag_depth) f32 { return 1.0; }";
        assert_eq!(
            without_early_depth_tests(source),
            "@fragment \nfn a() {}\n@fragment \nfn b() -> @builtin(frag_depth) f32 { return 1.0; }"
        );
        assert_eq!(without_early_depth_tests("fn c() {}"), "fn c() {}");
    }

    #[test]
    fn the_target_is_written_by_the_composer() {
        const ENTRY: WgslFile = WgslFile {
            path: "entry.wgsl",
            source: "@fragment @early_depth_test(force)\nfn a() {}",
        };
        let shader = ComposedShader {
            name: "test",
            constants: &[],
            files: &[ENTRY],
        };
        let wide = ShaderTarget {
            scene_format: wgpu::TextureFormat::Rgba32Float,
            early_depth_test: false,
            fragment_counter: Some(4),
        };
        let source = shader.source_for(&wide);
        assert!(
            source.contains("texture_storage_2d<rgba32float, write>"),
            "{source}"
        );
        assert!(!source.contains("early_depth_test"), "{source}");
        assert!(
            source.contains("@group(0) @binding(4) var<storage, read_write> fragment_invocations")
        );
        let default = shader.source();
        assert!(default.contains("texture_storage_2d<rgba16float, write>"));
        assert!(default.contains("@early_depth_test(force)"));
        assert!(default.contains("fn count_fragment_invocation() {}"));
        // The target never moves a line.
        assert_eq!(source.lines().count(), default.lines().count());
    }

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
                    text.starts_with("// ----")
                        || text.starts_with("const")
                        || text.starts_with("alias SceneOutput")
                        || text.starts_with("fn count_fragment_invocation"),
                    "{text}"
                ),
            }
        }
    }
}
