//! Images that decode to far more than their file: each is refused by the memory budget (or
//! decoded without inflating what it does not need) with the process's peak resident memory
//! under 1 GB. Each case runs in a child process of its own (this binary, re-run on one test),
//! so the peak it reads (VmHWM) is its own; the parent makes the files.

use std::path::{Path, PathBuf};

use image::{GrayImage, ImageBuffer, ImageEncoder, Luma};
use pom::{Channel, GltfError, Image, ImageError, TargetFormat, TextureKind};

/// Set in a child: the scratch folder holding its files.
const CHILD: &str = "POM_DECODE_BUDGET_DIR";
const ONE_GB: u64 = 1_000_000_000;

/// In the parent: makes the files with `setup` and runs test `name` alone in a child, which
/// must pass. In the child: runs `work` on the folder, then checks the peak resident memory.
fn isolated(name: &str, setup: impl FnOnce(&Path), work: impl FnOnce(&Path)) {
    if let Some(dir) = std::env::var_os(CHILD) {
        work(Path::new(&dir));
        let status = std::fs::read_to_string("/proc/self/status").unwrap();
        let peak_kb: u64 = status
            .lines()
            .find_map(|line| line.strip_prefix("VmHWM:"))
            .and_then(|value| value.trim().trim_end_matches("kB").trim().parse().ok())
            .unwrap();
        assert!(peak_kb * 1000 < ONE_GB, "peak resident memory {peak_kb} kB");
        return;
    }
    let dir: PathBuf =
        std::env::temp_dir().join(format!("pom-decode-budget-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    setup(&dir);
    let output = std::process::Command::new(std::env::current_exe().unwrap())
        .args([name, "--exact", "--nocapture", "--test-threads=1"])
        .env(CHILD, &dir)
        .output()
        .unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    assert!(
        output.status.success(),
        "{}{}",
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    );
}

/// A 16384 × 8192 grey PNG of one value (about 130 KB).
fn flat_grey(path: &Path) {
    GrayImage::from_pixel(16_384, 8_192, Luma([90]))
        .save(path)
        .unwrap();
}

fn assert_over_budget(error: &ImageError, file: &str) {
    let ImageError::OverBudget { name, budget, .. } = error else {
        panic!("expected ImageError::OverBudget, got {error:?}");
    };
    assert!(name.contains(file), "{error}");
    assert_eq!(*budget, pom::IMAGE_MEMORY_BUDGET);
    let message = error.to_string();
    assert!(
        message.contains(" bytes, ") && message.contains(&budget.to_string()),
        "{message}"
    );
}

#[test]
fn a_flat_16384_by_8192_grey_height_is_refused_by_the_budget() {
    isolated(
        "a_flat_16384_by_8192_grey_height_is_refused_by_the_budget",
        |dir| flat_grey(&dir.join("flat.png")),
        |dir| {
            let error = Image::load_height(dir.join("flat.png"), Channel::Red).unwrap_err();
            assert_over_budget(&error, "flat.png");
        },
    );
}

#[test]
fn a_32768_by_4096_sixteen_bit_height_is_refused_by_the_budget() {
    isolated(
        "a_32768_by_4096_sixteen_bit_height_is_refused_by_the_budget",
        |dir| {
            ImageBuffer::<Luma<u16>, _>::from_pixel(32_768, 4_096, Luma([30_000]))
                .save(dir.join("deep.png"))
                .unwrap();
        },
        |dir| {
            let error = Image::load(dir.join("deep.png"), TextureKind::Height).unwrap_err();
            assert_over_budget(&error, "deep.png");
        },
    );
}

/// Bits written least significant first, as deflate packs them.
#[derive(Default)]
struct Bits {
    bytes: Vec<u8>,
    used: u32,
}

impl Bits {
    /// Writes a Huffman code of `length` bits, most significant first.
    fn code(&mut self, code: u32, length: u32) {
        for bit in (0..length).rev() {
            if self.used == 0 {
                self.bytes.push(0);
            }
            *self.bytes.last_mut().unwrap() |= (((code >> bit) & 1) as u8) << self.used;
            self.used = (self.used + 1) % 8;
        }
    }
}

/// A zlib stream of `length` zero bytes (one fixed-Huffman block of 258-byte repeats).
fn zlib_zeros(length: u64) -> Vec<u8> {
    let mut bits = Bits::default();
    bits.code(0b011, 3); // BFINAL = 1, BTYPE = 01, read least significant bit first.
    bits.code(0b0011_0000, 8); // literal 0
    for _ in 0..(length - 1) / 258 {
        bits.code(0b1100_0101, 8); // length 258
        bits.code(0, 5); // distance 1
    }
    for _ in 0..(length - 1) % 258 {
        bits.code(0b0011_0000, 8);
    }
    bits.code(0, 7); // end of block
    let adler = ((length % 65_521) << 16) as u32 | 1;
    let mut stream = vec![0x78, 0x01];
    stream.extend(bits.bytes);
    stream.extend(adler.to_be_bytes());
    stream
}

fn crc32(bytes: &[u8]) -> u32 {
    let mut crc = !0_u32;
    for byte in bytes {
        crc ^= u32::from(*byte);
        for _ in 0..8 {
            crc = if crc & 1 == 1 {
                (crc >> 1) ^ 0xEDB8_8320
            } else {
                crc >> 1
            };
        }
    }
    !crc
}

/// A 4 × 4 grey PNG with an iCCP chunk (27 MB) that inflates to 4 GiB, inserted after IHDR.
fn png_with_huge_iccp(path: &Path) {
    let mut png = Vec::new();
    image::codecs::png::PngEncoder::new(&mut png)
        .write_image(&[100; 16], 4, 4, image::ExtendedColorType::L8)
        .unwrap_or_else(|error| panic!("{error}"));
    let mut chunk = b"iCCPprofile\0\0".to_vec();
    chunk.extend(zlib_zeros(4 << 30));
    let mut iccp = ((chunk.len() - 4) as u32).to_be_bytes().to_vec();
    iccp.extend(&chunk);
    iccp.extend(crc32(&chunk).to_be_bytes());
    // Signature (8) and IHDR (4 + 4 + 13 + 4).
    png.splice(33..33, iccp);
    std::fs::write(path, png).unwrap();
}

#[test]
fn an_iccp_chunk_inflating_to_4_gib_is_refused_without_inflating() {
    isolated(
        "an_iccp_chunk_inflating_to_4_gib_is_refused_without_inflating",
        |dir| png_with_huge_iccp(&dir.join("profiled.png")),
        |dir| {
            // The chunk is more than a decoder may hold beside 16 pixels: refused, not inflated.
            let error = Image::load_height(dir.join("profiled.png"), Channel::Red).unwrap_err();
            let message = error.to_string();
            assert!(
                message.contains("profiled.png") && message.contains("Memory limit"),
                "{message}"
            );
        },
    );
}

/// A glTF of twelve quads whose twelve images all name `file`.
fn twelve_entries(dir: &Path, file: &str) {
    let template = Path::new(env!("CARGO_MANIFEST_DIR")).join("bad_inputs/gltf/missing_image.gltf");
    let mut gltf: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(template).unwrap()).unwrap();
    let quad = gltf["meshes"][0].clone();
    let (mut meshes, mut nodes, mut materials, mut images, mut textures) =
        (vec![], vec![], vec![], vec![], vec![]);
    for index in 0..12 {
        let mut mesh = quad.clone();
        mesh["primitives"][0]["material"] = index.into();
        meshes.push(mesh);
        nodes.push(serde_json::json!({"mesh": index}));
        materials.push(
            serde_json::json!({"pbrMetallicRoughness": {"baseColorTexture": {"index": index}}}),
        );
        images.push(serde_json::json!({"uri": file}));
        textures.push(serde_json::json!({"source": index}));
    }
    gltf["meshes"] = meshes.into();
    gltf["nodes"] = nodes.into();
    gltf["materials"] = materials.into();
    gltf["images"] = images.into();
    gltf["textures"] = textures.into();
    gltf["scenes"][0]["nodes"] = (0..12).collect::<Vec<_>>().into();
    std::fs::write(dir.join("twelve.gltf"), gltf.to_string()).unwrap();
}

#[test]
fn twelve_images_naming_one_huge_file_are_refused_by_the_budget() {
    isolated(
        "twelve_images_naming_one_huge_file_are_refused_by_the_budget",
        |dir| {
            flat_grey(&dir.join("flat.png"));
            twelve_entries(dir, "flat.png");
        },
        |dir| {
            let mut app = pom_tests::pom_scene::pom_app(8, TargetFormat::Float32).unwrap();
            match pom::load_gltf(&mut app, dir.join("twelve.gltf")).unwrap_err() {
                GltfError::Image { reason, .. } => {
                    assert!(
                        reason.contains("flat.png") && reason.contains("over the budget"),
                        "{reason}"
                    )
                }
                other => panic!("expected GltfError::Image, got {other:?}"),
            }
        },
    );
}

#[test]
fn twelve_images_naming_one_file_share_one_decoded_image() {
    isolated(
        "twelve_images_naming_one_file_share_one_decoded_image",
        |dir| {
            GrayImage::from_pixel(4_096, 4_096, Luma([60]))
                .save(dir.join("shared.png"))
                .unwrap();
            twelve_entries(dir, "shared.png");
        },
        |dir| {
            let mut app = pom_tests::pom_scene::pom_app(8, TargetFormat::Float32).unwrap();
            pom::load_gltf(&mut app, dir.join("twelve.gltf")).unwrap();
            let mut textures = app.world.query::<&pom::LitMaterial>();
            let handles: Vec<_> = textures
                .iter()
                .map(|material| material.base_color_texture.clone().unwrap().id())
                .collect();
            assert_eq!(handles.len(), 12);
            assert!(
                handles.iter().all(|id| *id == handles[0]),
                "one image for one file"
            );
        },
    );
}
