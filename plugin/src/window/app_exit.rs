//! [`AppExit`]: how a windowed app ended, and how a system asks it to end.

use std::num::NonZeroU8;
use std::process::{ExitCode, Termination};

/// How [`crate::App::run`] ended, and, inserted as a resource by a system, a request to end
/// after the current frame. `fn main() -> AppExit` turns it into the process's exit status.
///
/// # Example
/// ```
/// use pom::window::AppExit;
/// fn quit_on_escape(_: &mut pom::hecs::World, resources: &mut pom::Resources) {
///     let keys = resources.get::<pom::window::ButtonInput<pom::window::KeyCode>>();
///     if keys.is_some_and(|keys| keys.just_pressed(pom::window::KeyCode::Escape)) {
///         resources.insert(AppExit::Success);
///     }
/// }
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AppExit {
    /// It ended normally (status 0).
    Success,
    /// It failed, with this status.
    Error(NonZeroU8),
}

impl AppExit {
    /// A failure with status 1.
    pub const fn error() -> Self {
        Self::Error(NonZeroU8::MIN)
    }

    /// Whether it ended normally.
    pub fn is_success(self) -> bool {
        self == Self::Success
    }
}

impl Termination for AppExit {
    fn report(self) -> ExitCode {
        match self {
            Self::Success => ExitCode::SUCCESS,
            Self::Error(status) => ExitCode::from(status.get()),
        }
    }
}
