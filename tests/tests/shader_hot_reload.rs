//! Shader hot reload on a copy of the plugin's WGSL files: a broken edit keeps the last good
//! pipeline and reports the error with the file's name; a good edit swaps the new one in.

use std::path::{Path, PathBuf};
use std::time::{Duration, SystemTime};

use pom::preview::PreviewView;
use pom::{ShaderHotReload, ShaderReloadError, ShaderReloadStatus, TargetFormat, patterns};
use pom_tests::pom_scene::{HeightMaterial, preview_app};
use pom_tests::render_and_capture;

const ENTRY: &str = "parallax/pom.wgsl";
const SHADED_RETURN: &str =
    "return shade(in, find_surface(in, front_facing, fragment_footprint(in)));";

fn copy_shader_sources() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("pom-hot-reload-{}", std::process::id()));
    // The deferred shaders too: where the adapter has primitive_index the materials compile
    // those, and a reload composes what was compiled.
    for file in [
        pom::lit::LIT_SHADER,
        pom::parallax::PARALLAX_SHADER,
        pom::lit::LIT_DEFERRED_SHADER,
        pom::parallax::PARALLAX_DEFERRED_SHADER,
    ]
    .iter()
    .flat_map(|shader| shader.files)
    {
        let path = dir.join(file.path);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(path, file.source).unwrap();
    }
    dir
}

/// Rewrites the entry file with `edit` applied, and moves its modification time forward so
/// the change is seen whatever the file system's time resolution.
fn edit_entry(dir: &Path, step: u64, edit: impl Fn(&str) -> String) {
    let path = dir.join(ENTRY);
    assert!(pom::parallax::PARALLAX_ENTRY.source.contains(SHADED_RETURN));
    std::fs::write(&path, edit(pom::parallax::PARALLAX_ENTRY.source)).unwrap();
    let file = std::fs::File::options().write(true).open(&path).unwrap();
    file.set_modified(SystemTime::now() + Duration::from_secs(10 * step))
        .unwrap();
}

fn status(app: &pom::App) -> ShaderReloadStatus {
    app.resources.get::<ShaderReloadStatus>().unwrap().clone()
}

#[test]
fn a_broken_edit_keeps_the_last_good_pipeline_and_a_good_edit_swaps_in() {
    let dir = copy_shader_sources();
    let material = HeightMaterial {
        field: patterns::bricks(64, 4.0, 8.0),
        height_scale: 0.05,
    };
    let mut app = preview_app(
        48,
        TargetFormat::Srgb8,
        &material,
        &PreviewView::default(),
        |m| m,
    )
    .unwrap();
    app.add_plugin(ShaderHotReload {
        source_dir: dir.clone(),
    });
    // Tonemapping off, so the edit's magenta reaches the image exactly.
    pom::set_camera_display_mapping(
        &mut app.world,
        pom::Exposure::default(),
        pom::Tonemapping::None,
    );
    let original = render_and_capture(&mut app).unwrap();
    assert_eq!(status(&app).reloads, 0);
    assert_eq!(status(&app).error, None);

    edit_entry(&dir, 1, |text| {
        text.replace(
            SHADED_RETURN,
            "return shade(in, find_surface(in, front_facing, fragment_footprint(in))).colour;",
        )
    });
    let after_broken_edit = render_and_capture(&mut app).unwrap();
    let error = status(&app).error.expect("the broken edit is reported");
    assert!(
        matches!(&error, ShaderReloadError::Invalid { file, .. } if file == ENTRY),
        "{error}"
    );
    assert!(
        error.to_string().starts_with("parallax/pom.wgsl:"),
        "{error}"
    );
    assert_eq!(status(&app).reloads, 0);
    assert!(
        after_broken_edit == original,
        "the last good pipeline still draws"
    );

    edit_entry(&dir, 2, |text| {
        text.replace(SHADED_RETURN, "return vec4<f32>(1.0, 0.0, 1.0, 1.0);")
    });
    let after_good_edit = render_and_capture(&mut app).unwrap();
    assert_eq!(status(&app).error, None);
    assert_eq!(status(&app).reloads, 1);
    let centre = after_good_edit.get_pixel(24, 24).0;
    assert_eq!(
        centre,
        [255, 0, 255, 255],
        "the edited shader draws the plane"
    );
    assert_ne!(original.get_pixel(24, 24).0, centre);
    std::fs::remove_dir_all(&dir).unwrap();
}
