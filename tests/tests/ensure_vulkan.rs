//! The driver detection and install decisions of the README's two commands (`sandbox/run`,
//! `tests/run`), run as the scripts themselves under their own `set -euo pipefail`, on a PATH
//! that holds only fakes: `apt-get` (logs its calls, "installs" into temporary folders), `ldconfig`
//! (reports the Vulkan loader once installed), `id`, optionally `sudo`, and `cargo` (prints what
//! it would run). The driver folders are temporary ones (`POM_VULKAN_ICD_DIRS`).

use std::fs;
use std::os::unix::fs::PermissionsExt;
use std::path::{Path, PathBuf};
use std::process::Command;

/// A fake machine: a bin folder that is the whole PATH, driver folders and an apt-get log.
struct FakeMachine {
    root: PathBuf,
}

/// What the fake machine starts with.
#[derive(Clone, Copy, Default)]
struct Setup {
    /// A driver manifest already in the first ICD folder (e.g. a GPU's or lavapipe's).
    manifest: Option<&'static str>,
    loader: bool,
    /// Xvfb and xdotool on the PATH.
    xvfb: bool,
    apt_get: bool,
    apt_get_fails: bool,
    root_user: bool,
    sudo: bool,
    no_cargo: bool,
    /// ldconfig only outside PATH (in /sbin, as a normal Debian user sees it).
    ldconfig_outside_path: bool,
}

impl Setup {
    /// A bare Debian machine where the user is root: nothing Vulkan installed, apt-get works.
    fn bare() -> Self {
        Self {
            apt_get: true,
            root_user: true,
            ..Self::default()
        }
    }
}

/// How a script run ended.
struct Outcome {
    status: i32,
    stdout: String,
    stderr: String,
    apt_calls: String,
}

fn write_executable(path: &Path, text: &str) {
    fs::write(path, text).unwrap();
    fs::set_permissions(path, fs::Permissions::from_mode(0o755)).unwrap();
}

fn real_tool(name: &str) -> PathBuf {
    for dir in ["/usr/bin", "/bin", "/usr/sbin", "/sbin"] {
        let path = Path::new(dir).join(name);
        if path.exists() {
            return path;
        }
    }
    panic!("{name} not found on this machine");
}

impl FakeMachine {
    fn new(name: &str, setup: Setup) -> Self {
        let root = Path::new(env!("CARGO_TARGET_TMPDIR"))
            .join("ensure_vulkan")
            .join(name);
        let _ = fs::remove_dir_all(&root);
        for dir in ["bin", "icd_usr", "icd_etc", "state"] {
            fs::create_dir_all(root.join(dir)).unwrap();
        }
        let machine = Self { root };
        let bin = machine.root.join("bin");
        for tool in ["grep", "env", "dirname", "ls", "head"] {
            std::os::unix::fs::symlink(real_tool(tool), bin.join(tool)).unwrap();
        }
        let state = machine.root.join("state");
        let icd = machine.root.join("icd_usr");
        // `ls` and `head` too: the script once failed silently through them. Inside the fakes only
        // bash builtins and absolute paths: PATH is the fake bin folder.
        let sbin = machine.root.join("sbin");
        fs::create_dir_all(&sbin).unwrap();
        let ldconfig_dir = if setup.ldconfig_outside_path {
            &sbin
        } else {
            &bin
        };
        write_executable(
            &ldconfig_dir.join("ldconfig"),
            &format!(
                "#!/bin/bash\nif [ -e {state}/loader ]; then\n  echo '\tlibvulkan.so.1 (libc6,x86-64) => /usr/lib/x86_64-linux-gnu/libvulkan.so.1'\nfi\necho '\tlibc.so.6 (libc6,x86-64) => /usr/lib/x86_64-linux-gnu/libc.so.6'\n",
                state = state.display()
            ),
        );
        write_executable(
            &bin.join("id"),
            &format!(
                "#!/bin/bash\necho {}\n",
                if setup.root_user { 0 } else { 1000 }
            ),
        );
        if !setup.no_cargo {
            write_executable(
                &bin.join("cargo"),
                "#!/bin/bash\necho \"cargo $*\"\necho \"VK_DRIVER_FILES=${VK_DRIVER_FILES:-} WGPU_BACKEND=${WGPU_BACKEND:-}\"\n",
            );
        }
        if setup.sudo {
            write_executable(
                &bin.join("sudo"),
                &format!(
                    "#!/bin/bash\necho sudo >> {}/apt.log\n\"$@\"\n",
                    state.display()
                ),
            );
        }
        if setup.apt_get {
            let fail = if setup.apt_get_fails {
                "echo 'E: Unable to locate package mesa-vulkan-drivers' >&2\nexit 100\n"
            } else {
                ""
            };
            write_executable(
                &bin.join("apt-get"),
                &format!(
                    "#!/bin/bash\necho \"apt-get $*\" >> {state}/apt.log\n{fail}\
                     for arg in \"$@\"; do case $arg in\n\
                     mesa-vulkan-drivers) : > {icd}/lvp_icd.x86_64.json ;;\n\
                     libvulkan1) : > {state}/loader ;;\n\
                     xvfb) printf '#!/bin/bash\\n' > {bin}/Xvfb; {chmod} +x {bin}/Xvfb ;;\n\
                     xdotool) printf '#!/bin/bash\\n' > {bin}/xdotool; {chmod} +x {bin}/xdotool ;;\n\
                     esac; done\n",
                    state = state.display(),
                    icd = icd.display(),
                    bin = bin.display(),
                    chmod = real_tool("chmod").display(),
                ),
            );
        }
        if setup.loader {
            fs::write(state.join("loader"), "").unwrap();
        }
        if setup.xvfb {
            write_executable(&bin.join("Xvfb"), "#!/bin/bash\n");
            write_executable(&bin.join("xdotool"), "#!/bin/bash\n");
        }
        if let Some(manifest) = setup.manifest {
            fs::write(icd.join(manifest), "{}").unwrap();
        }
        machine
    }

    /// Runs one of the README's commands (`sandbox/run` or `tests/run`) on this machine.
    fn run(&self, script: &str, args: &[&str]) -> Outcome {
        let repo = Path::new(env!("CARGO_MANIFEST_DIR")).parent().unwrap();
        let icd_dirs = format!(
            "{} {}",
            self.root.join("icd_usr").display(),
            self.root.join("icd_etc").display()
        );
        let output = Command::new(real_tool("bash"))
            .arg(repo.join(script))
            .args(args)
            .env_clear()
            .env("PATH", self.root.join("bin"))
            .env("HOME", &self.root)
            .env("POM_VULKAN_ICD_DIRS", icd_dirs)
            .env("POM_LDCONFIG_FALLBACK", self.root.join("sbin/ldconfig"))
            .output()
            .unwrap();
        Outcome {
            status: output.status.code().unwrap_or(-1),
            stdout: String::from_utf8_lossy(&output.stdout).into_owned(),
            stderr: String::from_utf8_lossy(&output.stderr).into_owned(),
            apt_calls: fs::read_to_string(self.root.join("state/apt.log")).unwrap_or_default(),
        }
    }

    fn lavapipe_manifest(&self) -> String {
        self.root
            .join("icd_usr/lvp_icd.x86_64.json")
            .display()
            .to_string()
    }
}

impl Outcome {
    fn assert_went_on(&self, what: &str) {
        assert_eq!(self.status, 0, "{what}: stderr:\n{}", self.stderr);
        assert!(
            self.stdout.contains("cargo "),
            "{what}: cargo never ran:\n{}",
            self.stdout
        );
    }

    /// Stopped before cargo, with exit status non-zero and one error line naming `package`.
    fn assert_stopped_naming(&self, what: &str, package: &str) {
        assert_ne!(self.status, 0, "{what}: should fail");
        assert!(!self.stdout.contains("cargo "), "{what}: cargo ran anyway");
        let errors: Vec<&str> = self
            .stderr
            .lines()
            .filter(|l| l.starts_with("error:"))
            .collect();
        assert_eq!(
            errors.len(),
            1,
            "{what}: want one error line, got:\n{}",
            self.stderr
        );
        assert!(
            errors[0].contains(package),
            "{what}: {:?} does not name {package}",
            errors[0]
        );
    }
}

#[test]
fn sandbox_run_installs_lavapipe_on_a_machine_without_a_driver_and_goes_on() {
    let machine = FakeMachine::new("sandbox_bare", Setup::bare());
    let outcome = machine.run("sandbox/run", &["snapshot", "--out", "x.png"]);
    outcome.assert_went_on("bare machine");
    assert!(
        outcome
            .stdout
            .contains("cargo run --release -- snapshot --out x.png"),
        "{}",
        outcome.stdout
    );
    assert!(
        outcome.apt_calls.contains("install")
            && outcome.apt_calls.contains("mesa-vulkan-drivers libvulkan1"),
        "apt-get calls: {}",
        outcome.apt_calls
    );
}

#[test]
fn sandbox_run_keeps_an_existing_gpu_driver() {
    let setup = Setup {
        manifest: Some("nvidia_icd.json"),
        loader: true,
        ..Setup::bare()
    };
    let outcome = FakeMachine::new("sandbox_gpu", setup).run("sandbox/run", &[]);
    outcome.assert_went_on("GPU driver present");
    assert_eq!(outcome.apt_calls, "", "nothing to install");
}

#[test]
fn sandbox_run_installs_the_loader_when_only_a_manifest_exists() {
    let setup = Setup {
        manifest: Some("nvidia_icd.json"),
        ..Setup::bare()
    };
    let outcome = FakeMachine::new("sandbox_no_loader", setup).run("sandbox/run", &[]);
    outcome.assert_went_on("manifest without loader");
    assert!(
        outcome.apt_calls.contains("libvulkan1"),
        "{}",
        outcome.apt_calls
    );
}

#[test]
fn sandbox_run_uses_sudo_when_not_root() {
    let setup = Setup {
        root_user: false,
        sudo: true,
        ..Setup::bare()
    };
    let outcome = FakeMachine::new("sandbox_sudo", setup).run("sandbox/run", &[]);
    outcome.assert_went_on("sudo");
    assert!(
        outcome.apt_calls.starts_with("sudo\n"),
        "{}",
        outcome.apt_calls
    );
}

#[test]
fn both_commands_say_which_package_to_install_without_root_or_sudo() {
    let setup = Setup {
        root_user: false,
        ..Setup::bare()
    };
    let machine = FakeMachine::new("no_root", setup);
    machine
        .run("sandbox/run", &[])
        .assert_stopped_naming("sandbox/run, no root", "mesa-vulkan-drivers");
    machine
        .run("tests/run", &[])
        .assert_stopped_naming("tests/run, no root", "mesa-vulkan-drivers");
    assert_eq!(
        fs::read_to_string(machine.root.join("state/apt.log")).unwrap_or_default(),
        ""
    );
}

#[test]
fn both_commands_say_which_package_to_install_without_a_package_manager() {
    let setup = Setup {
        apt_get: false,
        ..Setup::bare()
    };
    let machine = FakeMachine::new("no_apt", setup);
    machine
        .run("sandbox/run", &[])
        .assert_stopped_naming("sandbox/run, no apt-get", "mesa-vulkan-drivers");
    machine
        .run("tests/run", &[])
        .assert_stopped_naming("tests/run, no apt-get", "mesa-vulkan-drivers");
}

#[test]
fn both_commands_report_a_failing_install() {
    let setup = Setup {
        apt_get_fails: true,
        ..Setup::bare()
    };
    let machine = FakeMachine::new("apt_fails", setup);
    machine
        .run("sandbox/run", &[])
        .assert_stopped_naming("sandbox/run, apt fails", "mesa-vulkan-drivers");
    machine
        .run("tests/run", &[])
        .assert_stopped_naming("tests/run, apt fails", "mesa-vulkan-drivers");
}

#[test]
fn tests_run_installs_lavapipe_and_xvfb_on_a_bare_machine_and_pins_lavapipe() {
    let machine = FakeMachine::new("tests_bare", Setup::bare());
    let outcome = machine.run("tests/run", &["--locked"]);
    outcome.assert_went_on("bare machine");
    assert!(
        outcome.stdout.contains("cargo test --workspace --locked"),
        "{}",
        outcome.stdout
    );
    let pinned = format!(
        "VK_DRIVER_FILES={} WGPU_BACKEND=vulkan",
        machine.lavapipe_manifest()
    );
    assert!(outcome.stdout.contains(&pinned), "{}", outcome.stdout);
    assert!(
        outcome.apt_calls.contains("mesa-vulkan-drivers libvulkan1"),
        "{}",
        outcome.apt_calls
    );
    assert!(
        outcome.apt_calls.contains("xvfb xauth xdotool"),
        "{}",
        outcome.apt_calls
    );
}

#[test]
fn tests_run_installs_lavapipe_beside_a_gpu_driver() {
    let setup = Setup {
        manifest: Some("nvidia_icd.json"),
        loader: true,
        xvfb: true,
        ..Setup::bare()
    };
    let machine = FakeMachine::new("tests_gpu", setup);
    let outcome = machine.run("tests/run", &[]);
    outcome.assert_went_on("GPU driver present");
    assert!(
        outcome.apt_calls.contains("mesa-vulkan-drivers"),
        "{}",
        outcome.apt_calls
    );
    assert!(!outcome.apt_calls.contains("xvfb"), "{}", outcome.apt_calls);
    assert!(
        outcome.stdout.contains(&machine.lavapipe_manifest()),
        "{}",
        outcome.stdout
    );
}

#[test]
fn tests_run_installs_nothing_when_everything_is_there() {
    let setup = Setup {
        manifest: Some("lvp_icd.x86_64.json"),
        loader: true,
        xvfb: true,
        ..Setup::bare()
    };
    let machine = FakeMachine::new("tests_ready", setup);
    let outcome = machine.run("tests/run", &[]);
    outcome.assert_went_on("all present");
    assert_eq!(outcome.apt_calls, "");
    assert!(
        outcome.stdout.contains(&machine.lavapipe_manifest()),
        "{}",
        outcome.stdout
    );
}

#[test]
fn tests_run_says_which_package_to_install_when_only_xvfb_is_missing_and_no_root() {
    let setup = Setup {
        manifest: Some("lvp_icd.x86_64.json"),
        loader: true,
        root_user: false,
        ..Setup::bare()
    };
    let outcome = FakeMachine::new("tests_no_xvfb", setup).run("tests/run", &[]);
    outcome.assert_stopped_naming("xvfb, no root", "xvfb");
}

#[test]
fn both_commands_say_when_cargo_is_missing() {
    let machine = FakeMachine::new(
        "no_cargo",
        Setup {
            no_cargo: true,
            ..Setup::bare()
        },
    );
    machine
        .run("sandbox/run", &[])
        .assert_stopped_naming("sandbox/run, no cargo", "Rust toolchain");
    machine
        .run("tests/run", &[])
        .assert_stopped_naming("tests/run, no cargo", "Rust toolchain");
}

#[test]
fn ldconfig_outside_path_still_finds_the_loader() {
    let setup = Setup {
        manifest: Some("lvp_icd.x86_64.json"),
        loader: true,
        xvfb: true,
        ldconfig_outside_path: true,
        ..Setup::bare()
    };
    let machine = FakeMachine::new("ldconfig_in_sbin", setup);
    let outcome = machine.run("tests/run", &[]);
    outcome.assert_went_on("ldconfig in sbin");
    assert_eq!(
        outcome.apt_calls, "",
        "the loader was found: nothing to install"
    );
    machine
        .run("sandbox/run", &[])
        .assert_went_on("ldconfig in sbin");
}
