//! Replays, without a fuzzer and on the stable toolchain, what the fuzz targets in `tests/fuzz`
//! run: every input the fuzzer once failed on (`tests/fuzz/regressions/<target>/`) and every
//! seed (`tests/fuzz/seeds/<target>/`) must load or give an error without a panic, each within
//! the fuzzer's timeout; every seed (valid files) must load; and a few hundred fixed-seed
//! mutations of each seed must not panic.

use std::panic::AssertUnwindSafe;
use std::path::{Path, PathBuf};
use std::sync::mpsc::RecvTimeoutError;
use std::time::{Duration, Instant};

use pom_tests::fuzz_entry::{self, panic_during};

type Entry = fn(&[u8]) -> Result<(), String>;

const TARGETS: [(&str, Entry); 4] = [
    ("image", fuzz_entry::image),
    ("gltf", fuzz_entry::gltf),
    ("preset", fuzz_entry::preset),
    ("script", fuzz_entry::script),
];

/// The folders under `tests/fuzz/regressions/`: the targets the fuzzer has failed on (preset and
/// script never have), and image inputs that panic inside a dependency. A folder not listed here
/// would be replayed by no test.
const REGRESSION_FOLDERS: [&str; 3] = ["gltf", "image", "image_dependency_panics"];

/// Mutations of each seed file per run of [`mutated_seeds_never_panic`].
const MUTATIONS_PER_SEED: usize = 200;

/// Longest one replayed input may run before its test fails: the fuzzer's `-timeout=10`
/// (tests/fuzz/README.md), past which it saved the `timeout-…` inputs. Every input takes
/// milliseconds now; the bound turns a hang into a failure and measures no speed.
const REPLAY_DEADLINE: Duration = Duration::from_secs(10);

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

/// What one input did when replayed.
#[derive(Debug)]
struct Replay {
    /// The first panic raised while it ran, even one the loader caught and turned into an error.
    panic: Option<String>,
    /// What the entry returned; `None` when a panic escaped it.
    outcome: Option<Result<(), String>>,
}

/// Runs `run` on the bytes of `file` in a thread of its own and waits for it at most
/// [`REPLAY_DEADLINE`]: an input that hangs fails the test (its thread is left behind, and ends
/// with the test process) instead of hanging the test run.
fn replay(run: Entry, file: &Path) -> Replay {
    let bytes = std::fs::read(file).unwrap_or_else(|error| panic!("{}: {error}", file.display()));
    let (sender, receiver) = std::sync::mpsc::channel();
    let started = Instant::now();
    std::thread::Builder::new()
        .name(format!("replay {}", file.display()))
        .spawn(move || {
            let mut outcome = None;
            let panic = panic_during(AssertUnwindSafe(|| outcome = Some(run(&bytes))));
            // The receiver is gone only after a timeout, which has failed the test already.
            let _ = sender.send(Replay { panic, outcome });
        })
        .expect("a thread for the replay");
    match receiver.recv_timeout(REPLAY_DEADLINE) {
        Ok(replay) => {
            eprintln!(
                "{} in {:.0?}: {:?}",
                file.display(),
                started.elapsed(),
                replay.outcome
            );
            replay
        }
        Err(RecvTimeoutError::Timeout) => panic!(
            "{} still runs after {REPLAY_DEADLINE:?} (the fuzzer's timeout): it must load or fail without hanging",
            file.display()
        ),
        Err(RecvTimeoutError::Disconnected) => {
            panic!("the replay of {} ended without a result", file.display())
        }
    }
}

/// Every regression input and seed of `target`, none of which may panic or hang. The seeds make
/// sure the replay runs on something for targets the fuzzer never failed on.
fn replay_regressions(target: &str) {
    let run = entry(target);
    let inputs: Vec<PathBuf> = files("regressions", target)
        .into_iter()
        .chain(files("seeds", target))
        .collect();
    assert!(
        !inputs.is_empty(),
        "nothing to replay for {target}: no file in {} or {}",
        fuzz_dir().join("regressions").join(target).display(),
        fuzz_dir().join("seeds").join(target).display()
    );
    for file in inputs {
        let replay = replay(run, &file);
        assert_eq!(replay.panic, None, "{} panicked", file.display());
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
        let replay = replay(run, &seed);
        assert_eq!(replay.panic, None, "{} panicked", seed.display());
        if let Some(Err(error)) = replay.outcome {
            panic!("seed {} must load: {error}", seed.display());
        }
    }
}

/// Each folder of regression inputs is one a test replays, and holds inputs: a renamed or
/// misspelt folder would otherwise be read by nothing.
#[test]
fn every_regression_folder_is_replayed() {
    let mut folders: Vec<String> = std::fs::read_dir(fuzz_dir().join("regressions"))
        .expect("tests/fuzz/regressions")
        .map(|entry| entry.expect("readable folder entry"))
        .filter(|entry| entry.path().is_dir())
        .map(|entry| entry.file_name().to_string_lossy().into_owned())
        .collect();
    folders.sort();
    assert_eq!(
        folders, REGRESSION_FOLDERS,
        "the folders under tests/fuzz/regressions/"
    );
    for folder in REGRESSION_FOLDERS {
        assert!(
            !files("regressions", folder).is_empty(),
            "tests/fuzz/regressions/{folder}/ holds no file"
        );
    }
}

#[test]
fn image_regressions_do_not_panic() {
    replay_regressions("image");
}

/// Inputs that panic inside a dependency (zune-jpeg's overflow checks) where the loader can only
/// contain the panic: they must come back as errors.
#[test]
fn image_dependency_panics_become_errors() {
    let inputs = files("regressions", "image_dependency_panics");
    assert!(!inputs.is_empty());
    for file in inputs {
        let replay = replay(fuzz_entry::image, &file);
        assert!(
            matches!(replay.outcome, Some(Err(_))),
            "{}: {replay:?}",
            file.display()
        );
    }
}

/// The JPEG the fuzzer timed out on declares 65518×240 pixels in 484 bytes: the side limit must
/// refuse it before decoding. Decoded, it loads, but slowly (2 s in this debug build, past the
/// fuzzer's 10 s with its instrumentation), which the replay's deadline, a bound against hangs,
/// does not catch.
#[test]
fn the_timed_out_jpeg_is_refused_by_its_declared_size() {
    let file =
        fuzz_dir().join("regressions/image/timeout-5e6d196a28681559b2aaba1cc8789807e5f02da3");
    let replay = replay(fuzz_entry::image, &file);
    match replay.outcome {
        Some(Err(error)) => assert!(error.contains("65518×240"), "{error}"),
        other => panic!(
            "{}: expected an error naming its size, got {other:?}",
            file.display()
        ),
    }
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

/// What an outcome says with numbers and quoted names taken out: a new one is a rough sign that
/// an input reached code the corpus had not (the stable loop has no coverage counters).
fn signature(outcome: &Result<(), String>) -> String {
    match outcome {
        Ok(()) => "ok".into(),
        Err(message) => message
            .chars()
            .filter(|c| !c.is_ascii_digit())
            .take(120)
            .collect(),
    }
}

/// Fuzzing on the stable toolchain for a while, for machines without cargo-fuzz: mutates the
/// seeds (keeping mutants with an outcome not seen before as new seeds), and saves any input
/// that panics or takes over two seconds under `tests/fuzz/artifacts/<target>/`.
///
/// `FUZZ_TARGETS=image,gltf FUZZ_SECONDS=600 cargo test -p pom-tests --test fuzz_regressions
/// mutation_fuzz -- --ignored --nocapture`
#[test]
#[ignore = "runs for FUZZ_SECONDS (default 60); start it by hand"]
fn mutation_fuzz() {
    let seconds: u64 = std::env::var("FUZZ_SECONDS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(60);
    let wanted =
        std::env::var("FUZZ_TARGETS").unwrap_or_else(|_| "image,gltf,preset,script".into());
    let seed = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(1, |time| time.as_nanos() as u64)
        | 1;
    let mut failures = Vec::new();
    for (target, run) in TARGETS {
        if !wanted.split(',').any(|name| name.trim() == target) {
            continue;
        }
        let artifacts = fuzz_dir().join("artifacts").join(target);
        let mut rng = Rng(seed);
        let mut corpus: Vec<Vec<u8>> = files("seeds", target)
            .iter()
            .map(|file| std::fs::read(file).unwrap())
            .collect();
        assert!(!corpus.is_empty(), "no seeds for {target}");
        let mut seen = std::collections::HashSet::new();
        let (mut executions, mut crashes, mut slow) = (0_u64, 0, 0);
        let start = Instant::now();
        while start.elapsed().as_secs() < seconds {
            let parent = &corpus[rng.below(corpus.len())];
            let mut input = mutate(parent, &mut rng);
            if rng.below(8) == 0 {
                // Splice: the head of this mutant with the tail of another seed.
                let other = &corpus[rng.below(corpus.len())];
                let (cut, from) = (rng.below(input.len() + 1), rng.below(other.len() + 1));
                input.truncate(cut);
                input.extend_from_slice(&other[from..]);
            }
            let began = Instant::now();
            let mut outcome = None;
            let panic = panic_during(AssertUnwindSafe(|| outcome = Some(run(&input))));
            let took = began.elapsed();
            executions += 1;
            let save = |kind: &str| {
                std::fs::create_dir_all(&artifacts).unwrap();
                let hash = input.iter().fold(0xcbf2_9ce4_8422_2325_u64, |h, b| {
                    (h ^ u64::from(*b)).wrapping_mul(0x100_0000_01b3)
                });
                let file = artifacts.join(format!("{kind}-{hash:016x}"));
                std::fs::write(&file, &input).unwrap();
                file
            };
            if let Some(message) = panic {
                crashes += 1;
                let file = save("crash");
                eprintln!("{target}: PANIC {message}\n  saved {}", file.display());
                continue;
            }
            if took.as_secs_f32() > 2.0 {
                slow += 1;
                let file = save("slow");
                eprintln!("{target}: {took:?} for {}", file.display());
            }
            if let Some(outcome) = outcome
                && seen.insert(signature(&outcome))
                && corpus.len() < 4096
            {
                corpus.push(input);
            }
        }
        eprintln!(
            "{target}: {executions} executions in {:.0} s, {crashes} panics, {slow} slow, corpus {} ({} distinct outcomes)",
            start.elapsed().as_secs_f32(),
            corpus.len(),
            seen.len()
        );
        if crashes + slow > 0 {
            failures.push(format!("{target}: {crashes} panics, {slow} slow"));
        }
    }
    assert!(failures.is_empty(), "{failures:?}");
}
