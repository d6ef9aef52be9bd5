//! Every WGSL file in the plugin is part of a composed shader, and every composed shader parses
//! and validates with naga: the plugin's own (`pom::SHADERS`), those the core composes
//! around a shaded material's `shade` (the README's `Matte`, and `Lattice`, which cuts holes),
//! and those a `FullScreenPass` composes around a post effect (one with parameters here).

use crate::custom_material::{lattice, matte};

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use pom::Material;
use pom::render::shaders::ComposedShader;

/// Every shader to validate: the plugin's, and both of a shaded material's.
fn every_shader() -> Vec<ComposedShader> {
    let shaded = [
        Some(matte::Matte::shader()),
        matte::Matte::deferred_shader(),
        Some(lattice::Lattice::shader()),
        lattice::Lattice::deferred_shader(),
    ];
    pom::SHADERS
        .iter()
        .copied()
        .chain(shaded.into_iter().flatten())
        .collect()
}

fn src_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../plugin/src")
}

fn wgsl_files(dir: &Path, found: &mut Vec<PathBuf>) {
    let entries = std::fs::read_dir(dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
    for entry in entries {
        let path = entry.unwrap().path();
        if path.is_dir() {
            wgsl_files(&path, found);
        } else if path.extension().is_some_and(|ext| ext == "wgsl") {
            found.push(path);
        }
    }
}

/// A post effect reading its parameters and the helpers every effect may call.
const EFFECT: &str = "struct EffectParams { gain: f32 }
fn effect(pixel: vec2<u32>) -> vec4<f32> {
    let c = textureLoad(input, pixel, 0);
    return vec4<f32>(from_linear(to_linear(c.rgb) * params.gain), c.a);
}
";

#[test]
fn every_composed_shader_validates() {
    let shaders = every_shader();
    assert!(!pom::SHADERS.is_empty());
    let mut failures = Vec::new();
    // Each shader as games compile it, and as FragmentInvocationCounter compiles it for tests.
    let composed = shaders.iter().flat_map(|shader| {
        [shader.source(), shader.counting_source(&Default::default())]
            .map(|source| (shader.name.to_owned(), source))
    });
    // A post effect's every composition.
    let effects = pom::render::FullScreenPass::compositions::<f32>(EFFECT);
    let sources = composed.chain(effects);
    for (shader, source) in sources {
        let module = match naga::front::wgsl::parse_str(&source) {
            Ok(module) => module,
            Err(error) => {
                failures.push(error.emit_to_string_with_path(&source, &shader));
                continue;
            }
        };
        let mut validator = naga::valid::Validator::new(
            naga::valid::ValidationFlags::all(),
            naga::valid::Capabilities::default()
                | naga::valid::Capabilities::EARLY_DEPTH_TEST
                | naga::valid::Capabilities::PRIMITIVE_INDEX
                | naga::valid::Capabilities::SHADER_INT64
                | naga::valid::Capabilities::SHADER_INT64_ATOMIC_MIN_MAX,
        );
        if let Err(error) = validator.validate(&module) {
            failures.push(error.emit_to_string_with_path(&source, &shader));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn every_wgsl_file_on_disk_is_validated_as_embedded() {
    let mut on_disk = Vec::new();
    wgsl_files(&src_dir(), &mut on_disk);
    assert!(
        !on_disk.is_empty(),
        "no WGSL files under {}: did they move?",
        src_dir().display()
    );
    let shaders = every_shader();
    let composed: BTreeSet<(&str, &str)> = shaders
        .iter()
        .flat_map(|shader| shader.files.iter())
        .chain(&pom::render::EFFECT_FILES)
        .map(|file| (file.path, file.source))
        .collect();
    for path in &on_disk {
        let relative = path
            .strip_prefix(src_dir())
            .unwrap()
            .to_string_lossy()
            .replace('\\', "/");
        let text = std::fs::read_to_string(path).unwrap();
        assert!(
            composed.contains(&(relative.as_str(), text.as_str())),
            "{relative} is not part of any shader in pom::SHADERS or a shaded material's (or is stale)"
        );
    }
    eprintln!("{} WGSL files in {} shaders", on_disk.len(), shaders.len());
}
