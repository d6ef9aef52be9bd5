//! Work on the app with panics caught (the split view's second image; the window runner
//! catches the update's own): a panicking user system must not take the window (and the
//! unsaved tuned values) down; the panel reports it instead.

use std::panic::{AssertUnwindSafe, catch_unwind};

use pom::AppError;

/// Why a frame's update did not complete.
#[derive(Debug, thiserror::Error)]
pub enum UpdateFailure {
    /// A system returned an error.
    #[error("updating the scene: {0}")]
    Failed(#[from] AppError),
    /// The split view's second image failed.
    #[error(transparent)]
    SplitView(#[from] pom::SplitViewError),
    /// A system panicked; the rest of that frame's systems did not run.
    #[error("a system panicked while updating the scene: {0}")]
    Panicked(String),
}

/// Runs `work`, turning a panic inside it into [`UpdateFailure::Panicked`].
pub fn catching_panics<E: Into<UpdateFailure>>(
    work: impl FnOnce() -> Result<(), E>,
) -> Result<(), UpdateFailure> {
    // The world stays consistent across an unwind: hecs releases its borrows on drop, and a
    // half-run frame only means some systems skipped one frame.
    match catch_unwind(AssertUnwindSafe(work)) {
        Ok(result) => result.map_err(Into::into),
        Err(payload) => Err(UpdateFailure::Panicked(pom::window::panic_message(
            payload.as_ref(),
        ))),
    }
}

#[cfg(test)]
mod tests {
    use std::time::Instant;

    use pom::hecs::World;
    use pom::{App, ParallaxOcclusionMaterial, Resources, Stage};

    use super::super::app_state::record_tuned;
    use super::super::autosave::{self, Autosave, TunedState};
    use super::*;

    /// A user system that tunes the material each frame and panics on the third.
    fn tune_then_panic(world: &mut World, resources: &mut Resources) {
        let frame = resources.get_or_default::<u32>();
        *frame += 1;
        let frame = *frame;
        for material in world.query_mut::<&mut ParallaxOcclusionMaterial>() {
            material.height_scale = 0.01 * frame as f32;
        }
        if frame == 3 {
            panic!("user system failed on frame {frame}");
        }
    }

    #[test]
    fn a_panicking_system_is_reported_and_the_state_file_still_parses() {
        let dir = std::env::temp_dir().join(format!("sandbox-panic-{}", std::process::id()));
        let path = dir.join("state.ron");
        let mut app = App::new();
        app.world.spawn((ParallaxOcclusionMaterial::default(),));
        app.add_system(Stage::Update, tune_then_panic);
        let mut autosave = Autosave::new(path.clone(), TunedState::default());
        let mut tuned = TunedState::default();
        let mut failures = Vec::new();
        for _ in 0..5 {
            if let Err(failure) = catching_panics(|| app.update()) {
                failures.push(failure.to_string());
            }
            // What the window does after every frame, panicking or not.
            record_tuned(&app, "scene", &mut tuned);
            autosave.maybe_write(&tuned, Instant::now(), true).unwrap();
            let on_disk = autosave::load(&path).expect("the state file parses after every frame");
            assert_eq!(on_disk, tuned);
        }
        assert_eq!(
            failures,
            ["a system panicked while updating the scene: user system failed on frame 3"]
        );
        let saved = &autosave::load(&path).unwrap().scenes["scene"]["entity 0"];
        assert!((saved.height_scale - 0.05).abs() < 1e-6, "{saved:?}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
