//! A logger for binaries and games that install none: the library's warnings (clamped values,
//! device limits) as `warning: …` lines on stderr. It needs no crate beyond `log`.
//!
//! `RUST_LOG` picks the level: `off`, `error`, `warn` (the default), `info`, `debug` or `trace`.
//! Without it, wgpu's and naga's own messages are shown from `error` only, as their warnings
//! are about the driver rather than the scene.

use std::io::Write;
use std::sync::OnceLock;

use log::{Level, LevelFilter, Log, Metadata, Record};

/// The level shown when `RUST_LOG` is not set.
pub const DEFAULT_LOG_LEVEL: LevelFilter = LevelFilter::Warn;

/// Crates whose warnings are hidden unless `RUST_LOG` is set.
const DRIVER_CRATES: [&str; 2] = ["wgpu", "naga"];

/// What is printed: the level, and whether the driver crates' warnings are hidden.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Filter {
    level: LevelFilter,
    quiet_drivers: bool,
}

impl Filter {
    /// The filter `RUST_LOG`'s value (`None` when unset) asks for, or the text of why it cannot
    /// be read (then the default level is used).
    fn from_env(value: Option<&str>) -> (Self, Option<String>) {
        let default = Self {
            level: DEFAULT_LOG_LEVEL,
            quiet_drivers: true,
        };
        let Some(value) = value.map(str::trim).filter(|value| !value.is_empty()) else {
            return (default, None);
        };
        match value.parse::<LevelFilter>() {
            Ok(level) => (
                Self {
                    level,
                    quiet_drivers: false,
                },
                None,
            ),
            Err(_) => (
                default,
                Some(format!(
                    "RUST_LOG={value:?} is not a level (off, error, warn, info, debug, trace): \
                     showing warnings"
                )),
            ),
        }
    }

    /// Whether a message of `level` from `target` is printed.
    fn shows(&self, level: Level, target: &str) -> bool {
        // wgpu's crates are `wgpu`, `wgpu_core`, `wgpu_hal` and so on.
        let krate = target.split("::").next().unwrap_or_default();
        let driver = DRIVER_CRATES.iter().any(|name| {
            krate == *name
                || krate
                    .strip_prefix(name)
                    .is_some_and(|rest| rest.starts_with('_'))
        });
        let limit = if driver && self.quiet_drivers {
            LevelFilter::Error
        } else {
            self.level
        };
        level <= limit
    }
}

/// Prints records on stderr as `warning: …` lines.
struct StderrLog;

static LOGGER: StderrLog = StderrLog;
static FILTER: OnceLock<Filter> = OnceLock::new();

impl Log for StderrLog {
    fn enabled(&self, metadata: &Metadata<'_>) -> bool {
        FILTER
            .get()
            .is_some_and(|filter| filter.shows(metadata.level(), metadata.target()))
    }

    fn log(&self, record: &Record<'_>) {
        if self.enabled(record.metadata()) {
            print_line(record.level(), record.args());
        }
    }

    fn flush(&self) {}
}

/// Writes one `level: message` line; a stderr that cannot be written to loses it.
fn print_line(level: Level, message: &dyn std::fmt::Display) {
    let label = match level {
        Level::Error => "error",
        Level::Warn => "warning",
        Level::Info => "info",
        Level::Debug => "debug",
        Level::Trace => "trace",
    };
    let _ = writeln!(std::io::stderr().lock(), "{label}: {message}");
}

/// Installs a logger that prints warnings (or the level `RUST_LOG` names) on stderr, unless a
/// logger is installed already; returns whether this one was. [`crate::DefaultPlugins`] calls
/// it, so install your own logger before adding them to use yours instead.
pub fn log_to_stderr() -> bool {
    let value = std::env::var("RUST_LOG").ok();
    let (filter, problem) = Filter::from_env(value.as_deref());
    if log::set_logger(&LOGGER).is_err() {
        return false;
    }
    let _ = FILTER.set(filter);
    log::set_max_level(filter.level);
    if let Some(problem) = problem {
        print_line(Level::Warn, &problem);
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn warnings_are_shown_by_default_and_the_drivers_only_from_errors() {
        let (filter, problem) = Filter::from_env(None);
        assert_eq!(problem, None);
        assert!(filter.shows(Level::Warn, "pom::render::target"));
        assert!(!filter.shows(Level::Info, "pom::render::target"));
        assert!(!filter.shows(Level::Warn, "wgpu_hal::vulkan::instance"));
        assert!(!filter.shows(Level::Warn, "naga::front"));
        assert!(filter.shows(Level::Error, "wgpu_core::device"));
    }

    #[test]
    fn rust_log_sets_the_level_for_every_crate() {
        let (filter, _) = Filter::from_env(Some("debug"));
        assert!(filter.shows(Level::Debug, "pom::gltf_loader"));
        assert!(filter.shows(Level::Warn, "wgpu_hal::vulkan::instance"));
        let (off, _) = Filter::from_env(Some("OFF"));
        assert!(!off.shows(Level::Error, "pom"));
    }

    #[test]
    fn a_rust_log_that_is_not_a_level_keeps_warnings_and_says_so() {
        let (filter, problem) = Filter::from_env(Some("pom=debug"));
        assert_eq!(filter, Filter::from_env(None).0);
        assert!(problem.unwrap().contains("RUST_LOG=\"pom=debug\""));
    }
}
