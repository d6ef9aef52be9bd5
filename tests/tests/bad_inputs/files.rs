//! Files a scene names that are not what they claim: devices, FIFOs, directories, and paths
//! that leave the scene's folder. Made at run time in a scratch folder (a FIFO or a symbolic
//! link cannot be committed); a load that would hang fails the test after 20 s instead.

use std::sync::mpsc;
use std::time::Duration;

use pom::GltfOptions;
use pom::files::FileAccess;

use super::*;

/// A fresh scratch folder for one test.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("pom-bad-files-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn mkfifo(path: &Path) {
    let made = std::process::Command::new("mkfifo")
        .arg(path)
        .status()
        .unwrap();
    assert!(made.success(), "mkfifo {}", path.display());
}

/// Runs `load` on a thread; fails the test if it has not returned in 20 s (a read that never
/// ends, or an open that waits for a FIFO's writer).
fn within_time<T: Send + 'static>(load: impl FnOnce() -> T + Send + 'static) -> T {
    let (send, receive) = mpsc::channel();
    std::thread::spawn(move || {
        let _ = send.send(load());
    });
    receive
        .recv_timeout(Duration::from_secs(20))
        .expect("the load did not finish within 20 s")
}

/// The textured quad of the corpus, its image URI and buffer replaced.
fn quad_gltf(image_uri: &str, buffer_uri: Option<&str>) -> String {
    let template = std::fs::read_to_string(corpus("gltf/missing_image.gltf")).unwrap();
    let text = template.replace("\"absent.png\"", &format!("{image_uri:?}"));
    match buffer_uri {
        Some(uri) => {
            let start = text.find("\"data:application").unwrap();
            let end = start + 1 + text[start + 1..].find('"').unwrap();
            format!("{}{uri:?}{}", &text[..start], &text[end + 1..])
        }
        None => text,
    }
}

/// Loads the glTF text `gltf` written as `dir/scene.gltf` with `access`; returns the error.
fn gltf_load_error(dir: &Path, gltf: &str, access: FileAccess) -> GltfError {
    let path = dir.join("scene.gltf");
    std::fs::write(&path, gltf).unwrap();
    within_time(move || {
        let mut app = pom_app(8, TargetFormat::Float32).unwrap();
        let options = GltfOptions {
            file_access: access,
            ..GltfOptions::default()
        };
        let error = pom::load_gltf_with(&mut app, &path, options).unwrap_err();
        assert_eq!(app.world.len(), 0, "nothing half-loaded is left behind");
        error
    })
}

fn image_reason(error: GltfError) -> String {
    match error {
        GltfError::Image { reason, .. } => reason,
        other => panic!("expected GltfError::Image, got {other:?}"),
    }
}

fn buffer_reason(error: GltfError) -> String {
    match error {
        GltfError::Buffer { reason, .. } => reason,
        other => panic!("expected GltfError::Buffer, got {other:?}"),
    }
}

fn open_reason(error: GltfError) -> String {
    match error {
        GltfError::Open { reason, .. } => reason,
        other => panic!("expected GltfError::Open, got {other:?}"),
    }
}

#[test]
fn gltf_image_and_buffer_uris_of_devices_are_refused() {
    let dir = scratch("devices");
    for device in ["/dev/zero", "/dev/urandom"] {
        let reason = image_reason(gltf_load_error(
            &dir,
            &quad_gltf(device, None),
            FileAccess::AnyPath,
        ));
        assert!(
            reason.contains(&format!(
                "{device} is a character device, not a regular file"
            )),
            "{reason}"
        );
        let gltf = quad_gltf("absent.png", Some(device));
        let reason = buffer_reason(gltf_load_error(&dir, &gltf, FileAccess::AnyPath));
        assert!(
            reason.contains(&format!("{device} is a character device")),
            "{reason}"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn gltf_image_and_buffer_fifos_fail_at_once() {
    let dir = scratch("fifos");
    mkfifo(&dir.join("pipe.png"));
    mkfifo(&dir.join("pipe.bin"));
    let reason = image_reason(gltf_load_error(
        &dir,
        &quad_gltf("pipe.png", None),
        FileAccess::InsideFolder,
    ));
    assert!(
        reason.contains("pipe.png is a FIFO, not a regular file"),
        "{reason}"
    );
    let gltf = quad_gltf("absent.png", Some("pipe.bin"));
    let reason = buffer_reason(gltf_load_error(&dir, &gltf, FileAccess::InsideFolder));
    assert!(
        reason.contains("pipe.bin is a FIFO, not a regular file"),
        "{reason}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_gltf_image_that_is_a_directory_says_so() {
    let dir = scratch("directory-image");
    std::fs::create_dir(dir.join("textures")).unwrap();
    let reason = image_reason(gltf_load_error(
        &dir,
        &quad_gltf("textures", None),
        FileAccess::InsideFolder,
    ));
    assert!(
        reason.contains("textures is a directory, not a regular file"),
        "{reason}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_gltf_scene_path_that_is_a_symlink_to_a_device_or_a_fifo_is_refused() {
    let dir = scratch("scene-path");
    let link = dir.join("level.glb");
    std::os::unix::fs::symlink("/dev/zero", &link).unwrap();
    let fifo = dir.join("level.gltf");
    mkfifo(&fifo);
    for (path, kind) in [(link, "a character device"), (fifo, "a FIFO")] {
        let reason = open_reason(within_time(move || {
            let mut app = pom_app(8, TargetFormat::Float32).unwrap();
            load_gltf(&mut app, &path).unwrap_err()
        }));
        assert!(
            reason.contains(&format!("is {kind}, not a regular file")),
            "{reason}"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A scene folder `dir/levels/one` (returned) beside `dir/outside/secret.png`, a valid PNG.
fn scene_beside_a_secret(dir: &Path) -> PathBuf {
    let scene = dir.join("levels/one");
    std::fs::create_dir_all(&scene).unwrap();
    std::fs::create_dir_all(dir.join("outside")).unwrap();
    GrayImage::from_pixel(4, 4, Luma([77]))
        .save(dir.join("outside/secret.png"))
        .unwrap();
    std::fs::copy(
        dir.join("outside/secret.png"),
        dir.join("levels/secret.png"),
    )
    .unwrap();
    scene
}

#[test]
fn gltf_uris_outside_the_scenes_folder_are_refused() {
    let dir = scratch("outside");
    let scene = scene_beside_a_secret(&dir);
    std::os::unix::fs::symlink(dir.join("outside"), scene.join("linked")).unwrap();
    for (uri, rule) in [
        ("../../outside/secret.png", "`..` leads out of it"),
        ("%2e%2e/secret.png", "`..` leads out of it"),
        ("/etc/shadow", "an absolute path"),
        ("file:///etc/hostname", "has a scheme"),
        ("linked/secret.png", "a symbolic link leads out of it"),
    ] {
        let reason = image_reason(gltf_load_error(
            &scene,
            &quad_gltf(uri, None),
            FileAccess::InsideFolder,
        ));
        assert!(reason.contains(&format!("{uri:?}")), "{reason}");
        assert!(reason.contains(rule), "{uri}: {reason}");
        assert!(
            !reason.contains("bytes"),
            "nothing about the file outside: {reason}"
        );
        let gltf = quad_gltf("absent.png", Some(uri));
        let reason = buffer_reason(gltf_load_error(&scene, &gltf, FileAccess::InsideFolder));
        assert!(reason.contains(rule), "{uri}: {reason}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn file_access_any_path_lets_a_trusted_gltf_reach_outside_its_folder() {
    let dir = scratch("any-path");
    let scene = scene_beside_a_secret(&dir);
    let path = scene.join("scene.gltf");
    let secret = dir.join("outside/secret.png");
    for uri in [
        "../../outside/secret.png".to_owned(),
        format!("file://{}", secret.display()),
    ] {
        std::fs::write(&path, quad_gltf(&uri, None)).unwrap();
        let mut app = pom_app(8, TargetFormat::Float32).unwrap();
        let options = GltfOptions {
            file_access: FileAccess::AnyPath,
            ..GltfOptions::default()
        };
        let scene = pom::load_gltf_with(&mut app, &path, options).unwrap();
        assert!(!scene.entities.is_empty(), "{uri}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A script at `dir/scripts/test.ron` with one entity `entity` (RON) and an `ExpectMatch` of
/// `reference`; returns its path.
fn script_file(dir: &Path, entity: &str, reference: &str) -> PathBuf {
    let scripts = dir.join("scripts");
    std::fs::create_dir_all(&scripts).unwrap();
    let path = scripts.join("test.ron");
    let text = format!(
        "(\n    size: (16, 16),\n    camera: (position: (0.0, 2.0, 0.0), target: (0.0, 0.0, 0.0)),\n    \
         entities: [{entity}],\n    steps: [Capture(name: \"shot\"), ExpectMatch(capture: \"shot\", reference: {reference:?})],\n)\n"
    );
    std::fs::write(&path, text).unwrap();
    path
}

/// The maps of the corpus's `small_maps`, copied to `dir/name`.
fn copy_maps(dir: &Path, name: &str) {
    std::fs::create_dir_all(dir.join(name)).unwrap();
    for file in ["albedo.png", "normal.png", "height.png"] {
        std::fs::copy(
            corpus(&format!("scripts/small_maps/{file}")),
            dir.join(name).join(file),
        )
        .unwrap();
    }
}

fn plane_with_maps(maps: &str) -> String {
    format!("(name: \"plane\", shape: Some(Plane(size: 2.0)), material: Some(Pom(maps: {maps:?})))")
}

fn script_reference_reason(path: &Path, options: &RunOptions) -> String {
    let path = path.to_owned();
    let options = options.clone();
    match within_time(move || run_script_with(&path, &options)) {
        Err(ScriptError::Reference { reason, .. }) => reason,
        other => panic!("expected ScriptError::Reference, got {other:?}"),
    }
}

#[test]
fn script_maps_and_gltf_outside_the_scripts_folder_are_refused() {
    let dir = scratch("script-outside");
    copy_maps(&dir, "shared_maps");
    std::fs::write(dir.join("level.gltf"), quad_gltf("absent.png", None)).unwrap();
    let maps = script_file(&dir, &plane_with_maps("../shared_maps"), "shot.png");
    let reason = script_reference_reason(&maps, &RunOptions::default());
    assert!(
        reason.contains("../shared_maps/albedo.png is refused"),
        "{reason}"
    );
    assert!(reason.contains("`..` leads out of it"), "{reason}");
    let gltf = script_file(
        &dir,
        "(name: \"shot\", gltf: Some(\"../level.gltf\"))",
        "shot.png",
    );
    let reason = script_reference_reason(&gltf, &RunOptions::default());
    assert!(
        reason.contains("glTF file \"../level.gltf\" is refused"),
        "{reason}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn script_maps_that_are_a_directory_or_a_fifo_say_what_they_are() {
    let dir = scratch("script-special");
    copy_maps(&dir.join("scripts"), "maps");
    std::fs::remove_file(dir.join("scripts/maps/height.png")).unwrap();
    std::fs::create_dir(dir.join("scripts/maps/height.png")).unwrap();
    let path = script_file(&dir, &plane_with_maps("maps"), "shot.png");
    let reason = script_reference_reason(&path, &RunOptions::default());
    assert!(
        reason.contains("height.png is a directory, not a regular file"),
        "{reason}"
    );
    std::fs::remove_dir(dir.join("scripts/maps/height.png")).unwrap();
    mkfifo(&dir.join("scripts/maps/height.png"));
    let reason = script_reference_reason(&path, &RunOptions::default());
    assert!(
        reason.contains("height.png is a FIFO, not a regular file"),
        "{reason}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn blessing_a_reference_outside_the_scripts_folder_is_refused() {
    let dir = scratch("bless-outside");
    copy_maps(&dir.join("scripts"), "maps");
    let path = script_file(&dir, &plane_with_maps("maps"), "../escaped.png");
    let options = RunOptions {
        bless: true,
        ..RunOptions::default()
    };
    match run_script_with(&path, &options) {
        Err(ScriptError::Step { reason, .. }) => {
            assert!(reason.contains("../escaped.png is outside"), "{reason}");
        }
        other => panic!("expected ScriptError::Step, got {other:?}"),
    }
    assert!(
        !dir.join("escaped.png").exists(),
        "nothing is written outside"
    );
    let allowed = RunOptions {
        file_access: FileAccess::AnyPath,
        ..options
    };
    run_script_with(&path, &allowed).unwrap();
    assert!(dir.join("escaped.png").exists(), "the opt-in writes it");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn file_access_any_path_lets_a_trusted_script_use_shared_maps() {
    let dir = scratch("script-any-path");
    copy_maps(&dir, "shared_maps");
    let path = script_file(&dir, &plane_with_maps("../shared_maps"), "shot.png");
    let options = RunOptions {
        bless: true,
        file_access: FileAccess::AnyPath,
        ..RunOptions::default()
    };
    run_script_with(&path, &options).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_reference_that_names_no_png_file_is_refused_before_rendering() {
    let dir = scratch("reference-no-file");
    copy_maps(&dir.join("scripts"), "maps");
    // Failure images are named after the reference: a folder would leave them named after
    // the capture, anywhere the capture's name leads.
    for reference in [".", "sub/..", "", "refs/shot.txt"] {
        let path = script_file(&dir, &plane_with_maps("maps"), reference);
        match run_script_with(&path, &RunOptions::default()) {
            Err(ScriptError::Parse { reason, .. }) => assert!(
                reason.contains(&format!("reference {reference:?} names no PNG file")),
                "{reason}"
            ),
            other => panic!("{reference:?}: expected ScriptError::Parse, got {other:?}"),
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn failure_images_through_a_symlink_out_of_the_folder_or_onto_a_fifo_are_refused() {
    let dir = scratch("failure-images");
    copy_maps(&dir.join("scripts"), "maps");
    std::fs::write(dir.join("outside.txt"), b"keep").unwrap();
    std::fs::create_dir_all(dir.join("scripts/refs")).unwrap();
    let actual = dir.join("scripts/refs/shot-actual.png");
    std::os::unix::fs::symlink(dir.join("outside.txt"), &actual).unwrap();
    // The reference is missing: the run writes the capture beside it for a look.
    let path = script_file(&dir, &plane_with_maps("maps"), "refs/shot.png");
    let run = |path: &Path| {
        let path = path.to_owned();
        within_time(move || run_script_with(&path, &RunOptions::default()))
    };
    match run(&path) {
        Err(ScriptError::Step { reason, .. }) => assert!(
            reason.contains("refs/shot-actual.png is outside")
                && reason.contains("a symbolic link leads out of it"),
            "{reason}"
        ),
        other => panic!("expected ScriptError::Step, got {other:?}"),
    }
    assert_eq!(std::fs::read(dir.join("outside.txt")).unwrap(), b"keep");
    std::fs::remove_file(&actual).unwrap();
    mkfifo(&actual);
    match run(&path) {
        Err(ScriptError::Step { reason, .. }) => {
            assert!(reason.contains("is not a regular file"), "{reason}");
        }
        other => panic!("expected ScriptError::Step, got {other:?}"),
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
