//! Windows in tests: a private Xvfb server per test (tests/run installs Xvfb and xdotool),
//! running a windowed program on it with a deadline, and driving its windows with xdotool.
//!
//! Installs nothing: tests/run installs Xvfb (see `ensure_xvfb` in tests/ensure-vulkan.sh).

use std::collections::HashSet;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::sync::{Mutex, MutexGuard};
use std::time::{Duration, Instant};

/// Held while a test's Xvfb runs: two tests starting at once would both pick the first free
/// display number.
static ONE_XVFB_AT_A_TIME: Mutex<()> = Mutex::new(());

/// A running Xvfb server, stopped when dropped however the test ends.
pub struct Xvfb {
    server: Child,
    /// The X display number (`DISPLAY=:n`).
    pub display: u32,
    _serial: MutexGuard<'static, ()>,
}

impl Drop for Xvfb {
    fn drop(&mut self) {
        // SIGTERM first: Xvfb then removes its lock file and socket, which a SIGKILL (all that
        // `Child::kill` sends) leaves behind in /tmp.
        let _ = Command::new("kill")
            .args(["-TERM", &self.server.id().to_string()])
            .status();
        let deadline = Instant::now() + Duration::from_secs(5);
        while Instant::now() < deadline {
            if let Ok(Some(_)) = self.server.try_wait() {
                return;
            }
            std::thread::sleep(Duration::from_millis(20));
        }
        let _ = self.server.kill();
        let _ = self.server.wait();
    }
}

fn on_path(program: &str) -> bool {
    std::env::var_os("PATH")
        .is_some_and(|path| std::env::split_paths(&path).any(|dir| dir.join(program).is_file()))
}

fn socket(display: u32) -> PathBuf {
    PathBuf::from(format!("/tmp/.X11-unix/X{display}"))
}

impl Xvfb {
    /// Starts `Xvfb` (a 1600×1000 screen) on the first free display number from 99 on and
    /// waits for its socket. Panics where Xvfb is missing or does not start: a test needs it.
    pub fn start() -> Self {
        let serial = ONE_XVFB_AT_A_TIME
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner());
        assert!(
            on_path("Xvfb"),
            "Xvfb is not installed: run the tests with tests/run, which installs it (xvfb, xauth)"
        );
        let display = (99..400)
            .find(|n| !socket(*n).exists() && !Path::new(&format!("/tmp/.X{n}-lock")).exists())
            .expect("no free X display number between 99 and 399");
        let server = Command::new("Xvfb")
            .arg(format!(":{display}"))
            .args(["-screen", "0", "1600x1000x24", "-nolisten", "tcp"])
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .expect("starting Xvfb");
        let mut xvfb = Self {
            server,
            display,
            _serial: serial,
        };
        let deadline = Instant::now() + Duration::from_secs(20);
        while !socket(display).exists() {
            if let Ok(Some(status)) = xvfb.server.try_wait() {
                panic!("Xvfb :{display} exited at start ({status})");
            }
            assert!(
                Instant::now() < deadline,
                "Xvfb :{display} did not start in 20 s"
            );
            std::thread::sleep(Duration::from_millis(50));
        }
        xvfb
    }

    /// Runs `command` on this display (and no Wayland one), killing it if it runs past
    /// `timeout`; returns its status and output.
    pub fn run(&self, command: &mut Command, timeout: Duration) -> Output {
        let child = command
            .env("DISPLAY", format!(":{}", self.display))
            .env_remove("WAYLAND_DISPLAY")
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .expect("starting the program");
        wait_for(child, timeout)
    }
}

/// Waits for `child` to exit and returns its status and output, killing it (and failing the
/// test) if it runs past `timeout`.
pub fn wait_for(mut child: Child, timeout: Duration) -> Output {
    let deadline = Instant::now() + timeout;
    loop {
        if child.try_wait().expect("waiting for the program").is_some() {
            return child.wait_with_output().expect("reading its output");
        }
        if Instant::now() > deadline {
            let _ = child.kill();
            let output = child.wait_with_output().expect("reading its output");
            panic!(
                "the program did not exit within {timeout:?}; stderr:\n{}",
                String::from_utf8_lossy(&output.stderr)
            );
        }
        std::thread::sleep(Duration::from_millis(50));
    }
}

impl Xvfb {
    /// Starts `command` on this display (and no Wayland one), its output discarded.
    pub fn spawn(&self, command: &mut Command) -> Child {
        command
            .env("DISPLAY", format!(":{}", self.display))
            .env_remove("WAYLAND_DISPLAY")
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .expect("starting the program")
    }

    /// Runs `xdotool` with `args` on this display, for at most a minute (`search --sync` waits
    /// for a window that may never come), and returns what it printed, trimmed. Panics where it
    /// fails, with what it said.
    pub fn xdotool(&self, args: &[&str]) -> String {
        let output = Command::new("timeout")
            .arg("60")
            .arg("xdotool")
            .args(args)
            .env("DISPLAY", format!(":{}", self.display))
            .output()
            .expect("running xdotool (tests/run installs it)");
        assert!(
            output.status.success(),
            "xdotool {args:?} failed: {}",
            String::from_utf8_lossy(&output.stderr)
        );
        String::from_utf8_lossy(&output.stdout).trim().to_owned()
    }
}

/// How many different colours the pixels of `image` in the rectangle `x` × `y` have.
pub fn distinct_colours(
    image: &image::RgbaImage,
    x: std::ops::Range<u32>,
    y: std::ops::Range<u32>,
) -> usize {
    let mut colours = HashSet::new();
    for y in y {
        for x in x.clone() {
            colours.insert(image.get_pixel(x, y).0);
        }
    }
    colours.len()
}
