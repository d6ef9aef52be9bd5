//! What a material's plugin checks of its shader when it starts, with naga, before any GPU work:
//! that it compiles (the error names the material, the WGSL file and the line), and that a
//! material whose surface is said to lie on its polygon has no fragment entry that discards or
//! writes its depth.

use std::collections::HashSet;

use crate::shader::ComposedShader;

/// Why a material's shader cannot be used.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum MaterialShaderError {
    /// The WGSL does not compile.
    #[error("the shader of material {material} does not compile: {file} line {line}: {message}")]
    Compile {
        /// The material's name.
        material: &'static str,
        /// The WGSL file the error is in (`generated` for constants generated from Rust).
        file: &'static str,
        /// The line in that file.
        line: u32,
        /// naga's message.
        message: String,
    },
    /// A fragment entry leaves the polygon, which the material says it never does.
    #[error(
        "material {material} says its surface lies on its polygon (Material::SURFACE_ON_POLYGON), \
         but its fragment entry {entry_point} {what}: set SURFACE_ON_POLYGON to false and name \
         its prepass fragment and deferred shader, or do neither"
    )]
    LeavesPolygon {
        /// The material's name.
        material: &'static str,
        /// The fragment entry point.
        entry_point: String,
        /// `discards` or `writes its depth`.
        what: &'static str,
    },
    /// A compute entry discards: the deferred resolve shades pixels whose visibility the
    /// visibility pass has already decided.
    #[error(
        "material {material} discards in its compute entry {entry_point} (the deferred \
         resolve), where each pixel's surface is already decided: a material that cuts holes \
         implements Material itself, with SURFACE_ON_POLYGON false and a prepass fragment that \
         discards"
    )]
    DiscardsInResolve {
        /// The material's name.
        material: &'static str,
        /// The compute entry point.
        entry_point: String,
    },
}

/// Checks `shader`, material `material`'s, as [`MaterialShaderError`] says; `on_polygon` is the
/// material's [`super::Material::SURFACE_ON_POLYGON`].
pub(crate) fn check_material_shader(
    material: &'static str,
    shader: &ComposedShader,
    on_polygon: bool,
) -> Result<(), MaterialShaderError> {
    let source = shader.source();
    let compile_error = |line: Option<u32>, message: String| {
        let (file, line) = shader.locate(line.unwrap_or(0));
        MaterialShaderError::Compile {
            material,
            file,
            line,
            message,
        }
    };
    let module = naga::front::wgsl::parse_str(&source).map_err(|error| {
        let line = error.location(&source).map(|at| at.line_number);
        compile_error(line, error.message().to_owned())
    })?;
    // Before validation, which rejects a discard in a compute entry without saying where.
    check_surface(material, &module, on_polygon)?;
    naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::all(),
    )
    .validate(&module)
    .map_err(|error| {
        let line = error.location(&source).map(|at| at.line_number);
        compile_error(line, error.as_inner().to_string())
    })?;
    Ok(())
}

/// Whether `module`'s entry points keep to the material's surface: no compute entry discards,
/// and, where the surface lies on the polygon, no fragment entry discards or writes its depth.
fn check_surface(
    material: &'static str,
    module: &naga::Module,
    on_polygon: bool,
) -> Result<(), MaterialShaderError> {
    // Compute entries first: a shaded material's resolve says what to do about it.
    let (compute, others): (Vec<_>, Vec<_>) = module
        .entry_points
        .iter()
        .partition(|entry| entry.stage == naga::ShaderStage::Compute);
    for entry in compute.into_iter().chain(others) {
        let discards = || discards(module, &entry.function.body, &mut HashSet::new());
        match entry.stage {
            naga::ShaderStage::Compute if discards() => {
                return Err(MaterialShaderError::DiscardsInResolve {
                    material,
                    entry_point: entry.name.clone(),
                });
            }
            naga::ShaderStage::Fragment if on_polygon => {
                let what = if writes_depth(module, &entry.function) {
                    Some("writes its depth")
                } else if discards() {
                    Some("discards")
                } else {
                    None
                };
                if let Some(what) = what {
                    return Err(MaterialShaderError::LeavesPolygon {
                        material,
                        entry_point: entry.name.clone(),
                        what,
                    });
                }
            }
            _ => {}
        }
    }
    Ok(())
}

/// Whether `function`'s result (or a member of it) is the fragment depth.
fn writes_depth(module: &naga::Module, function: &naga::Function) -> bool {
    let is_depth = |binding: &Option<naga::Binding>| {
        matches!(
            binding,
            Some(naga::Binding::BuiltIn(naga::BuiltIn::FragDepth))
        )
    };
    let Some(result) = &function.result else {
        return false;
    };
    is_depth(&result.binding)
        || matches!(&module.types[result.ty].inner,
            naga::TypeInner::Struct { members, .. } if members.iter().any(|m| is_depth(&m.binding)))
}

/// Whether `block`, or a function it calls, can discard.
fn discards(
    module: &naga::Module,
    block: &naga::Block,
    seen: &mut HashSet<naga::Handle<naga::Function>>,
) -> bool {
    block.iter().any(|statement| match statement {
        naga::Statement::Kill => true,
        naga::Statement::Block(inner) => discards(module, inner, seen),
        naga::Statement::If { accept, reject, .. } => {
            discards(module, accept, seen) || discards(module, reject, seen)
        }
        naga::Statement::Switch { cases, .. } => {
            cases.iter().any(|case| discards(module, &case.body, seen))
        }
        naga::Statement::Loop {
            body, continuing, ..
        } => discards(module, body, seen) || discards(module, continuing, seen),
        naga::Statement::Call { function, .. } => {
            seen.insert(*function) && discards(module, &module.functions[*function].body, seen)
        }
        _ => false,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shader::WgslFile;

    fn shader(source: &'static str) -> ComposedShader {
        let files: &'static [WgslFile] = Box::leak(Box::new([WgslFile {
            path: "test.wgsl",
            source,
        }]));
        ComposedShader {
            name: "test",
            constants: &[],
            files,
        }
    }

    #[test]
    fn a_compile_error_names_the_material_the_file_and_the_line() {
        let broken = shader(
            "@fragment\nfn fs() -> @location(0) vec4<f32> {\n    return vec4<f32>(1.0, 2.0);\n}\n",
        );
        let error = check_material_shader("broken", &broken, true).unwrap_err();
        let MaterialShaderError::Compile {
            material,
            file,
            line,
            ..
        } = &error
        else {
            panic!("{error}");
        };
        assert_eq!(
            (*material, *file, *line),
            ("broken", "test.wgsl", 3),
            "{error}"
        );
    }

    #[test]
    fn a_discard_or_a_depth_write_leaves_the_polygon() {
        let discarding = shader(
            "fn cut(x: f32) { if x < 0.5 { discard; } }\n\
             @fragment\nfn fs_cut() -> @location(0) vec4<f32> { cut(0.2); return vec4<f32>(1.0); }\n",
        );
        let error = check_material_shader("cut", &discarding, true).unwrap_err();
        assert_eq!(
            error,
            MaterialShaderError::LeavesPolygon {
                material: "cut",
                entry_point: "fs_cut".to_owned(),
                what: "discards"
            }
        );
        assert_eq!(check_material_shader("cut", &discarding, false), Ok(()));
        let deep = shader("@fragment\nfn fs_deep() -> @builtin(frag_depth) f32 { return 0.5; }\n");
        assert!(matches!(
            check_material_shader("deep", &deep, true),
            Err(MaterialShaderError::LeavesPolygon {
                what: "writes its depth",
                ..
            })
        ));
        let flat =
            shader("@fragment\nfn fs() -> @location(0) vec4<f32> { return vec4<f32>(1.0); }\n");
        assert_eq!(check_material_shader("flat", &flat, true), Ok(()));
    }
}
