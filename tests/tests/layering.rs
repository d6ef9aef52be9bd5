//! The library's layers point one way. Every top-level module of `plugin/src` has a place in
//! [`LAYERS`], lowest first, and may use (through `crate::…` paths, the crate root's
//! re-exports included, and the crate's macros) only modules placed before it: the shader
//! vocabulary and the app at the bottom, then scene data, the renderer core, the material
//! seam, the materials, and what builds on them (loaders, tools, the window, the prelude).
//! Files inside one module may use each other. Unit tests (`#[cfg(test)]` modules) may reach
//! any layer: the seam's tests check the shipped materials.

use std::collections::{BTreeSet, HashMap};
use std::path::{Path, PathBuf};

use pom_tests::sources::{plugin_src, rust_files};

/// The top-level modules, lowest layer first.
const LAYERS: &[&str] = &[
    // The shader vocabulary and the app, and the named files and log lines under them.
    "shader",
    "files",
    "stderr_log",
    "time",
    "app",
    "assets",
    "color",
    "name",
    "transform",
    // Scene data.
    "image",
    "image_compare",
    "normal_map",
    "height_field",
    "mesh",
    "camera",
    "light",
    "shadows",
    "exposure",
    // Parameters: declaration, limits, tables (no GPU).
    "parameters",
    // The GPU layer: the device, pipelines, timing, readback, meshes and images on the GPU.
    "gpu",
    // The renderer core, and reading its frames back.
    "render",
    "capture",
    // The material seam.
    "material",
    // The materials.
    "lighting",
    "dynamic_height",
    "lit",
    "parallax",
    // What builds on them.
    "picking",
    "preview",
    "gltf_loader",
    "default_plugins",
    "reference",
    "split_view",
    "seed_port",
    "texel_rate_probe",
    "shader_reload",
    "script",
    "window",
    "prelude",
];

/// The parts of `render/`, lowest first: the core (every file of the folder but the ones below,
/// and any subfolder not named here), then each feature's folder, then what assembles them.
/// A part may use only parts before it: the core names no feature.
const RENDER_PARTS: &[&str] = &[
    "core",
    // The toolkit for writing a post effect in one file, on the core's post chain.
    "full_screen_pass",
    "tonemapping",
    "shadows",
    "anti_aliasing",
    "assembly",
];

/// The files of `render/` that assemble the core and the standard features: the folder's face
/// and the plugin that adds them.
const RENDER_ASSEMBLY: &[&str] = &["mod", "standard_features", "plugin"];

/// One `crate::…` use that goes up or sideways.
#[derive(Debug, PartialEq, Eq, PartialOrd, Ord)]
struct BackImport {
    file: String,
    from: String,
    to: String,
    through: String,
}

/// What the crate root says: its modules, the module each re-exported name comes from, and
/// the module that defines each exported macro.
struct CrateRoot {
    modules: BTreeSet<String>,
    reexports: HashMap<String, String>,
    macros: HashMap<String, String>,
}

fn identifiers(text: &str) -> impl Iterator<Item = &str> {
    text.split(|c: char| !(c.is_alphanumeric() || c == '_'))
        .filter(|word| word.starts_with(|c: char| c.is_alphabetic() || c == '_'))
}

/// The text after `start` up to the brace that closes the one just before `start`.
fn braced(text: &str, start: usize) -> &str {
    let mut depth = 1;
    for (offset, c) in text[start..].char_indices() {
        match c {
            '{' => depth += 1,
            '}' => {
                depth -= 1;
                if depth == 0 {
                    return &text[start..start + offset];
                }
            }
            _ => {}
        }
    }
    &text[start..]
}

/// `source` without comments and without `#[cfg(test)]` modules.
fn library_code(source: &str) -> String {
    let without_comments: String = source
        .lines()
        .map(|line| line.split("//").next().unwrap_or(""))
        .collect::<Vec<_>>()
        .join("\n");
    let mut code = String::new();
    let mut rest = without_comments.as_str();
    while let Some(at) = rest.find("#[cfg(test)]") {
        code.push_str(&rest[..at]);
        let after = &rest[at..];
        match (after.find("mod "), after.find('{'), after.find(';')) {
            (Some(module), Some(open), semicolon)
                if module < open && semicolon.is_none_or(|semi| semi > open) =>
            {
                let body = braced(after, open + 1);
                rest = &after[open + 1 + body.len() + 1..];
            }
            _ => {
                code.push_str("#[cfg(test)]");
                rest = &after["#[cfg(test)]".len()..];
            }
        }
    }
    code.push_str(rest);
    code
}

/// The first names of every `crate::` path in `code`, `use crate::{…}` groups included.
fn crate_paths(code: &str) -> BTreeSet<String> {
    let mut names = BTreeSet::new();
    let mut rest = code;
    while let Some(at) = rest.find("crate::") {
        let after = &rest[at + "crate::".len()..];
        if let Some(group) = after.strip_prefix('{') {
            let body = braced(group, 0);
            let mut depth = 0;
            let mut item = String::new();
            for c in body.chars().chain([',']) {
                match c {
                    '{' => depth += 1,
                    '}' => depth -= 1,
                    ',' if depth == 0 => {
                        if let Some(first) = identifiers(&item).next() {
                            names.insert(first.to_owned());
                        }
                        item.clear();
                        continue;
                    }
                    _ => {}
                }
                item.push(c);
            }
        } else if let Some(first) = identifiers(after).next()
            && after.starts_with(first)
        {
            names.insert(first.to_owned());
        }
        rest = after;
    }
    names
}

/// The top-level module a file of `src` belongs to (`None`: the crate root).
fn module_of(src: &Path, file: &Path) -> Option<String> {
    let relative = file.strip_prefix(src).ok()?;
    let first = relative.components().next()?.as_os_str().to_str()?;
    let name = first.strip_suffix(".rs").unwrap_or(first);
    (name != "lib").then(|| name.to_owned())
}

fn crate_root(src: &Path, files: &[(PathBuf, String)]) -> CrateRoot {
    let lib = library_code(&std::fs::read_to_string(src.join("lib.rs")).expect("lib.rs"));
    let mut modules = BTreeSet::new();
    let mut reexports = HashMap::new();
    for statement in lib.split(';') {
        let statement = statement.trim();
        let words: Vec<&str> = identifiers(statement).collect();
        // File modules only (lib.rs's inline doctest module is no layer).
        if let Some(at) = words.iter().position(|word| *word == "mod")
            && let Some(name) = words.get(at + 1)
            && (src.join(format!("{name}.rs")).is_file() || src.join(name).is_dir())
        {
            modules.insert((*name).to_owned());
        }
        if let Some(path) = statement
            .strip_prefix("pub use ")
            .filter(|path| !path.starts_with("crate"))
            && let Some((module, names)) = path.split_once("::")
        {
            for name in identifiers(names) {
                reexports.insert(name.to_owned(), module.to_owned());
            }
        }
    }
    let mut macros = HashMap::new();
    for (file, source) in files {
        for (at, _) in source.match_indices("macro_rules!") {
            if let (Some(name), Some(module)) = (
                identifiers(&source[at + "macro_rules!".len()..]).next(),
                module_of(src, file),
            ) {
                macros.insert(name.to_owned(), module);
            }
        }
    }
    CrateRoot {
        modules,
        reexports,
        macros,
    }
}

/// Every use in `files` of a module at or above the user's own layer.
fn back_imports(src: &Path, files: &[(PathBuf, String)]) -> Vec<BackImport> {
    let root = crate_root(src, files);
    let layer = |module: &str| LAYERS.iter().position(|m| *m == module);
    let mut found = Vec::new();
    for (file, source) in files {
        let Some(from) = module_of(src, file) else {
            continue;
        };
        let from_layer = layer(&from)
            .unwrap_or_else(|| panic!("module {from} has no place in LAYERS: give it one"));
        for name in crate_paths(&library_code(source)) {
            let to = if root.modules.contains(&name) {
                Some(name.clone())
            } else {
                root.reexports
                    .get(&name)
                    .or_else(|| root.macros.get(&name))
                    .cloned()
            };
            let Some(to) = to.filter(|to| *to != from) else {
                continue;
            };
            let to_layer =
                layer(&to).unwrap_or_else(|| panic!("module {to} has no place in LAYERS"));
            if to_layer > from_layer {
                found.push(BackImport {
                    file: file.strip_prefix(src).unwrap_or(file).display().to_string(),
                    from: from.clone(),
                    to,
                    through: name,
                });
            }
        }
    }
    found.sort();
    found
}

fn read(src: &Path) -> Vec<(PathBuf, String)> {
    rust_files(src)
        .into_iter()
        .map(|file| {
            let source = std::fs::read_to_string(&file).expect("reading a source file");
            (file, source)
        })
        .collect()
}

/// The part of `render/` a submodule of it (a file or folder name) belongs to.
fn render_part(submodule: &str) -> &'static str {
    if RENDER_ASSEMBLY.contains(&submodule) {
        return "assembly";
    }
    RENDER_PARTS
        .iter()
        .find(|part| **part == submodule)
        .copied()
        .unwrap_or("core")
}

/// What `render/mod.rs` says: its submodules, and the submodule each name it re-exports comes
/// from.
fn render_names(src: &Path) -> HashMap<String, String> {
    let code = library_code(&std::fs::read_to_string(src.join("render/mod.rs")).expect("mod.rs"));
    let mut names = HashMap::new();
    for statement in code.split(';') {
        let words: Vec<&str> = identifiers(statement).collect();
        if let Some(at) = words.iter().position(|word| *word == "mod")
            && let Some(name) = words.get(at + 1)
        {
            names.insert((*name).to_owned(), (*name).to_owned());
        }
        if let Some(at) = statement.find("use ") {
            let path = &statement[at + "use ".len()..];
            if let Some((module, items)) = path.split_once("::") {
                let module = module.trim();
                for name in identifiers(items) {
                    names.entry(name.to_owned()).or_insert(module.to_owned());
                }
            }
        }
    }
    names
}

/// The first names after `prefix` in every path of `code` that starts with it, use groups
/// included.
fn paths_after(code: &str, prefix: &str) -> BTreeSet<String> {
    let marked = code.replace("crate::", "krate::");
    crate_paths(&marked.replace(&prefix.replace("crate::", "krate::"), "crate::"))
}

/// Every use inside `render/` of a part at or above the user's own part.
fn render_back_imports(src: &Path, files: &[(PathBuf, String)]) -> Vec<BackImport> {
    let render = src.join("render");
    let names = render_names(src);
    let root = crate_root(src, files);
    let rank = |part: &str| RENDER_PARTS.iter().position(|p| *p == part).unwrap_or(0);
    let mut found = Vec::new();
    for (file, source) in files {
        let Ok(relative) = file.strip_prefix(&render) else {
            continue;
        };
        let first = relative
            .components()
            .next()
            .and_then(|c| c.as_os_str().to_str());
        let Some(first) = first.map(|name| name.strip_suffix(".rs").unwrap_or(name)) else {
            continue;
        };
        let from = render_part(first);
        let code = library_code(source);
        let mut used: BTreeSet<String> = paths_after(&code, "crate::render::");
        if relative.components().count() == 1 {
            used.extend(paths_after(&code, "super::"));
        }
        // Names the crate root re-exports from the renderer.
        used.extend(
            crate_paths(&code)
                .into_iter()
                .filter(|name| root.reexports.get(name).is_some_and(|m| m == "render")),
        );
        for name in used {
            let Some(submodule) = names.get(&name) else {
                continue;
            };
            let to = render_part(submodule);
            if to != from && rank(to) > rank(from) {
                found.push(BackImport {
                    file: relative.display().to_string(),
                    from: from.to_owned(),
                    to: to.to_owned(),
                    through: name,
                });
            }
        }
    }
    found.sort();
    found
}

/// Fails listing `found`, if any.
fn assert_none(found: &[BackImport], what: &str, path_prefix: &str) {
    assert!(
        found.is_empty(),
        "{} back imports{what}:\n{}",
        found.len(),
        found
            .iter()
            .map(|b| format!(
                "  {}: {} uses {} (through {path_prefix}{})",
                b.file, b.from, b.to, b.through
            ))
            .collect::<Vec<_>>()
            .join("\n")
    );
}

/// The library's files with `code` appended to render/frame.rs.
fn with_frame_rs_ending(src: &Path, code: &str) -> Vec<(PathBuf, String)> {
    let mut files = read(src);
    let frame = src.join("render/frame.rs");
    let (_, source) = files
        .iter_mut()
        .find(|(file, _)| *file == frame)
        .expect("render/frame.rs");
    source.push_str(code);
    files
}

#[test]
fn the_renderers_core_names_no_feature_and_features_only_those_before_them() {
    let src = plugin_src();
    let files = read(&src);
    assert_none(&render_back_imports(&src, &files), " inside render/", "");
    // Every feature part is a folder of render/.
    for part in &RENDER_PARTS[1..RENDER_PARTS.len() - 1] {
        assert!(
            src.join("render").join(part).join("mod.rs").is_file(),
            "{part}"
        );
    }
}

/// Most lines the files of `render/`'s core (Rust and WGSL, outside every part's folder) may
/// hold: what a newcomer reads to follow a frame.
const CORE_LINE_BUDGET: usize = 5_000;

#[test]
fn the_renderers_core_stays_small_enough_to_read() {
    let render = plugin_src().join("render");
    let mut lines_per_part: HashMap<String, usize> = HashMap::new();
    let mut stack = vec![render.clone()];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).expect("reading render/") {
            let path = entry.expect("a directory entry").path();
            if path.is_dir() {
                stack.push(path);
                continue;
            }
            let relative = path.strip_prefix(&render).expect("under render/");
            let part = match relative.components().count() {
                1 => match relative.file_stem().and_then(|stem| stem.to_str()) {
                    Some(stem) if RENDER_ASSEMBLY.contains(&stem) => "assembly",
                    _ => "core",
                },
                _ => relative
                    .iter()
                    .next()
                    .and_then(|p| p.to_str())
                    .unwrap_or("core"),
            };
            let text = std::fs::read_to_string(&path).expect("reading a render/ file");
            *lines_per_part.entry(part.to_owned()).or_default() += text.lines().count();
        }
    }
    let core = lines_per_part["core"] + lines_per_part.get("assembly").copied().unwrap_or(0);
    assert!(
        core < CORE_LINE_BUDGET,
        "render/'s core (with its assembly files) holds {core} lines, over {CORE_LINE_BUDGET}: \
         move a feature into a folder of its own ({lines_per_part:?})"
    );
}

#[test]
fn a_core_file_naming_a_feature_is_caught() {
    let src = plugin_src();
    let files = with_frame_rs_ending(
        &src,
        "\nuse super::anti_aliasing::TAA_PASS;\n\
         fn back() { let _ = crate::render::TonemappingPlugin; let _ = crate::AntiAliasing::Off; }\n",
    );
    let found: Vec<(String, String)> = render_back_imports(&src, &files)
        .into_iter()
        .map(|b| (b.to, b.through))
        .collect();
    assert_eq!(
        found,
        [
            ("anti_aliasing".to_owned(), "AntiAliasing".to_owned()),
            ("anti_aliasing".to_owned(), "anti_aliasing".to_owned()),
            ("tonemapping".to_owned(), "TonemappingPlugin".to_owned()),
        ]
    );
}

#[test]
fn every_module_uses_only_the_layers_below_it() {
    let src = plugin_src();
    let files = read(&src);
    let root = crate_root(&src, &files);
    for module in &root.modules {
        assert!(
            LAYERS.contains(&module.as_str()),
            "module {module} has no place in LAYERS"
        );
    }
    assert_none(&back_imports(&src, &files), "", "crate::");
}

#[test]
fn a_back_import_is_caught_whichever_way_it_is_written() {
    let src = plugin_src();
    // A path, a use group and a root re-export, each reaching up from the renderer.
    let files = with_frame_rs_ending(
        &src,
        "\nfn back() { let _ = crate::material::MAX_MATERIAL_TEXTURES; }\n\
         use crate::{Color, lit::LitMaterial};\n\
         use crate::{ParallaxOcclusionMaterial as _};\n\
         #[cfg(test)]\nmod tests { use crate::window::WindowPlugin; }\n",
    );
    let found: Vec<(String, String)> = back_imports(&src, &files)
        .into_iter()
        .map(|b| (b.to, b.through))
        .collect();
    assert_eq!(
        found,
        [
            ("lit".to_owned(), "lit".to_owned()),
            ("material".to_owned(), "material".to_owned()),
            (
                "parallax".to_owned(),
                "ParallaxOcclusionMaterial".to_owned()
            ),
        ],
        "the test module's use of the window is allowed"
    );
}
