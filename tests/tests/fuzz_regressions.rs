//! Replays, without a fuzzer and on the stable toolchain, what the fuzz targets in `tests/fuzz`
//! run: every input the fuzzer once failed on (`tests/fuzz/regressions/<target>/`) must now load
//! or give an error without a panic; every seed (`tests/fuzz/seeds/<target>/`, valid files) must
//! load; and a few hundred fixed-seed mutations of each seed must not panic.

use std::path::{Path, PathBuf};

use pom_tests::fuzz_entry::{self, panic_during};

type Entry = fn(&[u8]) -> Result<(), String>;

const TARGETS: [(&str, Entry); 4] = [
    ("image", fuzz_entry::image),
    ("gltf", fuzz_entry::gltf),
    ("preset", fuzz_entry::preset),
    ("script", fuzz_entry::script),
];

/// Mutations of each seed file per run of [`mutated_seeds_never_panic`].
const MUTATIONS_PER_SEED: usize = 200;

fn fuzz_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz")
}

/// The files of `fuzz/<folder>/<target>/`, sorted; none if the folder does not exist.
fn files(folder: &str, target: &str) -> Vec<PathBuf> {
    let Ok(entries) = std::fs::read_dir(fuzz_dir().join(folder).join(target)) else {
        return Vec::new();
    };
    let mut files: Vec<PathBuf> = entries
        .map(|entry| entry.expect("readable folder entry").path())
        .filter(|path| path.is_file())
        .collect();
    files.sort();
    files
}

fn entry(target: &str) -> Entry {
    TARGETS
        .iter()
        .find(|(name, _)| *name == target)
        .map(|(_, entry)| *entry)
        .expect("known target")
}

fn replay_regressions(target: &str) {
    let run = entry(target);
    for file in files("regressions", target) {
        let bytes = std::fs::read(&file).unwrap();
        let mut outcome = None;
        let panic = panic_during(std::panic::AssertUnwindSafe(|| outcome = Some(run(&bytes))));
        assert_eq!(panic, None, "{} panicked", file.display());
        eprintln!("{}: {:?}", file.display(), outcome.expect("ran"));
    }
}

fn seeds_load(target: &str) {
    let run = entry(target);
    let seeds = files("seeds", target);
    assert!(
        seeds.len() >= 5,
        "expected the seed corpus in {}",
        fuzz_dir().join("seeds").join(target).display()
    );
    for seed in seeds {
        let bytes = std::fs::read(&seed).unwrap();
        let mut outcome = None;
        let panic = panic_during(std::panic::AssertUnwindSafe(|| outcome = Some(run(&bytes))));
        assert_eq!(panic, None, "{} panicked", seed.display());
        if let Some(Err(error)) = outcome {
            panic!("seed {} must load: {error}", seed.display());
        }
    }
}

#[test]
fn image_regressions_do_not_panic() {
    replay_regressions("image");
}

#[test]
fn gltf_regressions_do_not_panic() {
    replay_regressions("gltf");
}

#[test]
fn preset_regressions_do_not_panic() {
    replay_regressions("preset");
}

#[test]
fn script_regressions_do_not_panic() {
    replay_regressions("script");
}

#[test]
fn image_seeds_load() {
    seeds_load("image");
}

#[test]
fn gltf_seeds_load() {
    seeds_load("gltf");
}

#[test]
fn preset_seeds_load() {
    seeds_load("preset");
}

#[test]
fn script_seeds_load() {
    seeds_load("script");
}

/// xorshift64*: a fixed sequence, so a failure here reproduces exactly.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }

    fn below(&mut self, bound: usize) -> usize {
        (self.next() % bound.max(1) as u64) as usize
    }
}

/// One to four small edits of the kinds libFuzzer makes: flipped bits, bytes set to edge
/// values, removed or repeated runs, truncation. The first byte (the image target's selector)
/// is edited like any other.
fn mutate(seed: &[u8], rng: &mut Rng) -> Vec<u8> {
    let mut bytes = seed.to_vec();
    for _ in 0..1 + rng.below(4) {
        if bytes.is_empty() {
            bytes.push(rng.next() as u8);
            continue;
        }
        let at = rng.below(bytes.len());
        match rng.below(6) {
            0 => bytes[at] ^= 1 << rng.below(8),
            1 => bytes[at] = [0x00, 0x01, 0x7f, 0x80, 0xff, b'-', b'9', b'"'][rng.below(8)],
            2 => {
                let end = (at + 1 + rng.below(16)).min(bytes.len());
                bytes.drain(at..end);
            }
            3 => {
                let end = (at + 1 + rng.below(16)).min(bytes.len());
                let run = bytes[at..end].to_vec();
                bytes.splice(at..at, run);
            }
            4 => bytes.truncate(at),
            _ => {
                // A 32-bit little- or big-endian edge value: sizes, lengths, counts.
                let value = [0_u32, 1, 0x7fff_ffff, 0xffff_ffff, 0x10000][rng.below(5)];
                let encoded = if rng.below(2) == 0 {
                    value.to_le_bytes()
                } else {
                    value.to_be_bytes()
                };
                let end = (at + 4).min(bytes.len());
                bytes.splice(at..end, encoded);
            }
        }
    }
    bytes
}

#[test]
fn mutated_seeds_never_panic() {
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    let mut runs = 0;
    for (target, run) in TARGETS {
        for seed in files("seeds", target) {
            let bytes = std::fs::read(&seed).unwrap();
            for mutation in 0..MUTATIONS_PER_SEED {
                let mutated = mutate(&bytes, &mut rng);
                let panic = panic_during(|| run(&mutated));
                assert_eq!(
                    panic,
                    None,
                    "{target}: mutation {mutation} of {} panicked; input as hex: {}",
                    seed.display(),
                    mutated
                        .iter()
                        .map(|b| format!("{b:02x}"))
                        .collect::<String>()
                );
                runs += 1;
            }
        }
    }
    assert!(runs >= 4 * 5 * MUTATIONS_PER_SEED, "only {runs} runs");
}
