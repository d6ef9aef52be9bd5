//! Tuned material values survive a restart (or a kill): they are written atomically to a RON
//! state file when they change, at most once a second, and applied again at the next start.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use anyhow::{Context, Result};
use pom::PomPreset;
use serde::{Deserialize, Serialize};

/// The shortest time between two writes of the state file.
const MIN_INTERVAL: Duration = Duration::from_secs(1);

/// What the state file holds: per scene, per material entity name, its parameters, and per
/// light name, its shadows; and the display controls (exposure, tonemapping), the same for
/// every scene.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct TunedState {
    /// Scene name → entity name → preset.
    pub scenes: BTreeMap<String, BTreeMap<String, PomPreset>>,
    /// The camera's exposure and operator, once set.
    pub display: Option<super::display_control::DisplayState>,
    /// Scene name → light name → its shadow settings, once set.
    pub light_shadows: BTreeMap<String, BTreeMap<String, super::light_control::ShadowState>>,
}

/// The default state file: under the user's configuration folder, or `target/` without one.
pub fn default_state_path() -> PathBuf {
    let config = std::env::var_os("XDG_CONFIG_HOME")
        .filter(|dir| !dir.is_empty())
        .map(PathBuf::from)
        .or_else(|| {
            std::env::var_os("HOME")
                .filter(|dir| !dir.is_empty())
                .map(|home| PathBuf::from(home).join(".config"))
        });
    match config {
        Some(dir) => dir.join("pom-sandbox").join("state.ron"),
        None => PathBuf::from("target").join("sandbox-state.ron"),
    }
}

/// Reads the state file; a missing file is an empty state.
pub fn load(path: &Path) -> Result<TunedState> {
    if !path.exists() {
        return Ok(TunedState::default());
    }
    let text = pom::files::read_text_bounded(path, pom::files::MAX_TEXT_FILE_BYTES)?;
    ron::from_str(&text).with_context(|| format!("reading {}", path.display()))
}

/// Writes `state` when it differs from what was last written and a second has passed.
#[derive(Debug)]
pub struct Autosave {
    path: PathBuf,
    written: TunedState,
    last_write: Option<Instant>,
}

impl Autosave {
    /// An autosaver for `path` whose file currently holds `on_disk`.
    pub fn new(path: PathBuf, on_disk: TunedState) -> Self {
        Self {
            path,
            written: on_disk,
            last_write: None,
        }
    }

    /// The state file.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Writes `state` if it changed and the last write is a second old (or `force`).
    pub fn maybe_write(&mut self, state: &TunedState, now: Instant, force: bool) -> Result<()> {
        if *state == self.written {
            return Ok(());
        }
        let recent = self
            .last_write
            .is_some_and(|last| now.duration_since(last) < MIN_INTERVAL);
        if recent && !force {
            return Ok(());
        }
        // Remember the attempt either way, so a failing disk is retried once a second, not
        // every frame.
        self.last_write = Some(now);
        if let Some(dir) = self.path.parent().filter(|dir| !dir.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
        }
        let text = ron::ser::to_string_pretty(state, ron::ser::PrettyConfig::default())
            .context("serialising the tuned values")?;
        pom::files::write_file(&self.path, text.as_bytes())?;
        self.written = state.clone();
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn writes_when_changed_at_most_once_a_second_and_reloads() {
        let dir = std::env::temp_dir().join(format!("sandbox-autosave-{}", std::process::id()));
        let path = dir.join("nested").join("state.ron");
        let mut autosave = Autosave::new(path.clone(), TunedState::default());
        let start = Instant::now();
        let mut state = TunedState::default();
        autosave.maybe_write(&state, start, false).unwrap();
        assert!(!path.exists(), "nothing changed, nothing written");
        state.scenes.entry("scene".into()).or_default().insert(
            "floor".into(),
            PomPreset {
                height_scale: 0.07,
                ..PomPreset::default()
            },
        );
        autosave.maybe_write(&state, start, false).unwrap();
        assert_eq!(load(&path).unwrap(), state);
        let first = state.clone();
        state
            .scenes
            .get_mut("scene")
            .unwrap()
            .get_mut("floor")
            .unwrap()
            .height_scale = 0.01;
        autosave
            .maybe_write(&state, start + Duration::from_millis(200), false)
            .unwrap();
        assert_eq!(load(&path).unwrap(), first, "too soon: not written yet");
        autosave
            .maybe_write(&state, start + Duration::from_millis(1100), false)
            .unwrap();
        assert_eq!(load(&path).unwrap(), state);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_missing_file_is_an_empty_state_and_a_bad_one_an_error() {
        assert_eq!(
            load(Path::new("/nonexistent/state.ron")).unwrap(),
            TunedState::default()
        );
        let path =
            std::env::temp_dir().join(format!("sandbox-bad-state-{}.ron", std::process::id()));
        std::fs::write(&path, "(scenes: oops").unwrap();
        assert!(load(&path).is_err());
        std::fs::remove_file(&path).unwrap();
    }
}
