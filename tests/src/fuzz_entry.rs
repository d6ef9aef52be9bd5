//! The bodies of the fuzz targets in `tests/fuzz`, shared with the regression test that replays
//! the inputs the fuzzer once failed on, so both run exactly the same code.
//!
//! Each entry feeds arbitrary bytes to one loader and returns `Ok` if the input loaded or the
//! loader's error message; a panic (or a broken invariant, asserted here) is the failure the
//! fuzzer looks for.

use std::cell::RefCell;
use std::path::Path;
use std::sync::Once;

use pom::{App, Channel, Image, Pixels, PomPreset, TextureKind, load_gltf_bytes};

/// Images with more texels than this skip the mip-chain checks: building chains is correct but
/// slow for big images, and the fuzzer should spend its time on decoding.
const MIP_CHAIN_TEXEL_LIMIT: u64 = 1 << 16;

const KINDS: [TextureKind; 4] = [
    TextureKind::Color,
    TextureKind::Normal,
    TextureKind::Height,
    TextureKind::Data,
];

const CHANNELS: [Channel; 4] = [Channel::Red, Channel::Green, Channel::Blue, Channel::Alpha];

/// The image loader path: the first byte picks the texture kind (low two bits) and the height
/// channel (next two bits); the rest is the file (PNG or JPEG) given to [`Image::decode`].
/// A decoded image is checked for the storage its kind promises, and small ones build their
/// mip chains.
pub fn image(data: &[u8]) -> Result<(), String> {
    let Some((&selector, file)) = data.split_first() else {
        return Err("no selector byte".into());
    };
    let kind = KINDS[usize::from(selector) % 4];
    let channel = CHANNELS[usize::from(selector / 4) % 4];
    let image = Image::decode(file, "fuzz input", kind, channel).map_err(|e| e.to_string())?;
    let (width, height) = image.size();
    assert!(width > 0 && height > 0, "a decoded image is never empty");
    let storage_fits_kind = match image.pixels() {
        Pixels::Rgba8(_) => kind != TextureKind::Height,
        Pixels::Gray8(_) | Pixels::Gray16(_) => kind == TextureKind::Height,
        // A storage this check does not know yet.
        _ => false,
    };
    assert!(storage_fits_kind, "{kind:?} stored as {:?}", image.pixels());
    if u64::from(width) * u64::from(height) <= MIP_CHAIN_TEXEL_LIMIT {
        let chain = image.mip_chain();
        assert_eq!(chain.last().map(Pixels::dimensions), Some((1, 1)));
        if let Some(maxima) = image.max_mip_chain() {
            assert_eq!(maxima.len(), chain.len());
        }
        let fitted = image.fitted_to((width.max(height) / 2).max(1));
        let (fitted_width, fitted_height) = fitted.size();
        assert!(fitted_width <= width && fitted_height <= height);
        let _ = image.to_rgba8();
    }
    Ok(())
}

/// The glTF loader: the bytes as a `.glb` or a self-contained `.gltf` (JSON with `data:` URIs),
/// loaded into an empty app. A failed load must leave no entity behind.
pub fn gltf(data: &[u8]) -> Result<(), String> {
    let mut app = App::new();
    match load_gltf_bytes(&mut app, data, "fuzz.glb") {
        Ok(scene) => {
            assert_eq!(app.world.len() as usize, scene.entities.len());
            Ok(())
        }
        Err(error) => {
            assert_eq!(app.world.len(), 0, "a failed load leaves nothing behind");
            Err(error.to_string())
        }
    }
}

/// RON material presets: the bytes as UTF-8 text given to [`PomPreset::from_ron`]. A preset that
/// loads must survive a round trip through [`PomPreset::to_ron`] unchanged.
pub fn preset(data: &[u8]) -> Result<(), String> {
    let text = std::str::from_utf8(data).map_err(|e| e.to_string())?;
    let preset = PomPreset::from_ron(text, "fuzz.ron").map_err(|e| e.to_string())?;
    let written = preset.to_ron();
    let reloaded = PomPreset::from_ron(&written, "round trip.ron")
        .unwrap_or_else(|error| panic!("a loaded preset must reload: {error}\n{written}"));
    // Compared as text: NaN colours (which the material accepts) are not equal to themselves.
    assert_eq!(reloaded.to_ron(), written);
    let _ = preset.to_rust();
    Ok(())
}

/// RON scene scripts: the bytes as UTF-8 text given to [`pom::script::parse_script_with`], which
/// parses and checks names and files. The script is placed in `tests/scenes/`, so relative
/// paths to the shipped maps and presets resolve as they do for the real scripts (which reach
/// `assets/` outside their folder with the same opt-in).
pub fn script(data: &[u8]) -> Result<(), String> {
    let text = std::str::from_utf8(data).map_err(|e| e.to_string())?;
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/fuzz_input.ron");
    pom::script::parse_script_with(text, &path, pom::files::FileAccess::AnyPath)
        .map(|_| ())
        .map_err(|e| e.to_string())
}

thread_local! {
    static PANIC_MESSAGE: RefCell<Option<String>> = const { RefCell::new(None) };
}

/// Runs `f` and returns the message of the first panic raised on this thread while it ran,
/// even one the code under test caught (the glTF loader turns panics of its dependencies into
/// errors; the fuzzer aborts on them all the same, so the regression test must see them too).
pub fn panic_during<T>(f: impl FnOnce() -> T + std::panic::UnwindSafe) -> Option<String> {
    static HOOK: Once = Once::new();
    HOOK.call_once(|| {
        let default_hook = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            PANIC_MESSAGE.with(|message| {
                message.borrow_mut().get_or_insert_with(|| info.to_string());
            });
            default_hook(info);
        }));
    });
    PANIC_MESSAGE.with(|message| message.borrow_mut().take());
    let _ = std::panic::catch_unwind(f);
    PANIC_MESSAGE.with(|message| message.borrow_mut().take())
}
