//! Driving any windowed app from outside, for CI: `POM_EXIT_AFTER_FRAMES=N` closes it after N
//! presented frames, `POM_SCREENSHOT=FILE.png` writes the last presented frame there first.

use std::path::PathBuf;

/// The variable that closes the app after that many presented frames.
pub const EXIT_AFTER_FRAMES_VAR: &str = "POM_EXIT_AFTER_FRAMES";
/// The variable naming the PNG the last presented frame is written to.
pub const SCREENSHOT_VAR: &str = "POM_SCREENSHOT";

/// A bad automation variable.
#[derive(Debug, thiserror::Error, PartialEq, Eq)]
pub enum AutomationError {
    /// `POM_EXIT_AFTER_FRAMES` is not a whole number of frames, at least 1.
    #[error("{EXIT_AFTER_FRAMES_VAR}={value:?} is not a frame count (a whole number, at least 1)")]
    FrameCount {
        /// The variable's value.
        value: String,
    },
    /// `POM_SCREENSHOT` names a file in a folder that does not exist.
    #[error("{SCREENSHOT_VAR}={path:?}: the folder {folder:?} does not exist")]
    ScreenshotFolder {
        /// The path asked for.
        path: PathBuf,
        /// Its folder.
        folder: PathBuf,
    },
    /// A variable is not valid Unicode.
    #[error("{0} is not valid Unicode")]
    NotUnicode(&'static str),
}

/// What the environment asks of the runner.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Automation {
    /// Close after this many presented frames.
    pub exit_after_frames: Option<u64>,
    /// Write the last presented frame here.
    pub screenshot: Option<PathBuf>,
}

impl Automation {
    /// Reads [`EXIT_AFTER_FRAMES_VAR`] and [`SCREENSHOT_VAR`].
    ///
    /// # Errors
    /// A frame count that is not a whole number ≥ 1, a screenshot in a missing folder, or a
    /// value that is not Unicode: [`AutomationError`], naming the variable.
    pub fn from_env() -> Result<Self, AutomationError> {
        let read = |name: &'static str| match std::env::var(name) {
            Ok(value) => Ok(Some(value)),
            Err(std::env::VarError::NotPresent) => Ok(None),
            Err(std::env::VarError::NotUnicode(_)) => Err(AutomationError::NotUnicode(name)),
        };
        Self::parse(
            read(EXIT_AFTER_FRAMES_VAR)?.as_deref(),
            read(SCREENSHOT_VAR)?.as_deref(),
        )
    }

    /// The automation the two variables' values ask for (`None`: unset).
    ///
    /// # Errors
    /// As [`Automation::from_env`].
    pub fn parse(
        exit_after_frames: Option<&str>,
        screenshot: Option<&str>,
    ) -> Result<Self, AutomationError> {
        let exit_after_frames = exit_after_frames
            .map(|value| match value.trim().parse::<u64>() {
                Ok(frames) if frames >= 1 => Ok(frames),
                _ => Err(AutomationError::FrameCount {
                    value: value.to_owned(),
                }),
            })
            .transpose()?;
        let screenshot = screenshot
            .filter(|path| !path.is_empty())
            .map(PathBuf::from);
        if let Some(path) = &screenshot {
            let folder = path
                .parent()
                .filter(|folder| !folder.as_os_str().is_empty())
                .map_or_else(|| PathBuf::from("."), PathBuf::from);
            if !folder.is_dir() {
                return Err(AutomationError::ScreenshotFolder {
                    path: path.clone(),
                    folder,
                });
            }
        }
        Ok(Self {
            exit_after_frames,
            screenshot,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unset_variables_ask_for_nothing() {
        assert_eq!(Automation::parse(None, None), Ok(Automation::default()));
    }

    #[test]
    fn a_frame_count_is_a_whole_number_of_at_least_one() {
        assert_eq!(
            Automation::parse(Some("60"), None)
                .unwrap()
                .exit_after_frames,
            Some(60)
        );
        for bad in ["abc", "-1", "0", "1.5", ""] {
            let error = Automation::parse(Some(bad), None).unwrap_err();
            assert_eq!(
                error.to_string(),
                format!(
                    "POM_EXIT_AFTER_FRAMES={bad:?} is not a frame count (a whole number, at least 1)"
                )
            );
        }
    }

    #[test]
    fn a_screenshot_in_a_missing_folder_is_refused_naming_the_path() {
        let error = Automation::parse(None, Some("/no/such/folder/shot.png")).unwrap_err();
        assert_eq!(
            error.to_string(),
            "POM_SCREENSHOT=\"/no/such/folder/shot.png\": the folder \"/no/such/folder\" does not exist"
        );
        let here = Automation::parse(None, Some("shot.png")).unwrap();
        assert_eq!(here.screenshot, Some(PathBuf::from("shot.png")));
    }
}
