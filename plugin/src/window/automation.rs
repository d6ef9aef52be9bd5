//! Driving any windowed app from outside, for CI: `POM_EXIT_AFTER_FRAMES=N` closes it after N
//! presented frames, `POM_SCREENSHOT=FILE.png` writes the last presented frame there first,
//! `POM_FRAME_TIMES=FILE.csv` writes where each frame's CPU time went (the runner's own work
//! apart from the app's stages).

use std::path::PathBuf;

/// The variable that closes the app after that many presented frames.
pub const EXIT_AFTER_FRAMES_VAR: &str = "POM_EXIT_AFTER_FRAMES";
/// The variable naming the PNG the last presented frame is written to.
pub const SCREENSHOT_VAR: &str = "POM_SCREENSHOT";
/// The variable naming the CSV file the frames' times are written to.
pub const FRAME_TIMES_VAR: &str = "POM_FRAME_TIMES";

/// A bad automation variable.
#[derive(Debug, thiserror::Error, PartialEq, Eq)]
pub enum AutomationError {
    /// `POM_EXIT_AFTER_FRAMES` is not a whole number of frames, at least 1.
    #[error("{EXIT_AFTER_FRAMES_VAR}={value:?} is not a frame count (a whole number, at least 1)")]
    FrameCount {
        /// The variable's value.
        value: String,
    },
    /// `POM_SCREENSHOT` or `POM_FRAME_TIMES` names a file in a folder that does not exist.
    #[error("{variable}={path:?}: the folder {folder:?} does not exist")]
    MissingFolder {
        /// The variable.
        variable: &'static str,
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
    /// Write the frames' times here (CSV).
    pub frame_times: Option<PathBuf>,
}

impl Automation {
    /// Reads [`EXIT_AFTER_FRAMES_VAR`], [`SCREENSHOT_VAR`] and [`FRAME_TIMES_VAR`].
    ///
    /// # Errors
    /// A frame count that is not a whole number ≥ 1, a file in a missing folder, or a
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
            read(FRAME_TIMES_VAR)?.as_deref(),
        )
    }

    /// The automation the three variables' values ask for (`None`: unset).
    ///
    /// # Errors
    /// As [`Automation::from_env`].
    pub fn parse(
        exit_after_frames: Option<&str>,
        screenshot: Option<&str>,
        frame_times: Option<&str>,
    ) -> Result<Self, AutomationError> {
        let exit_after_frames = exit_after_frames
            .map(|value| match value.trim().parse::<u64>() {
                Ok(frames) if frames >= 1 => Ok(frames),
                _ => Err(AutomationError::FrameCount {
                    value: value.to_owned(),
                }),
            })
            .transpose()?;
        Ok(Self {
            exit_after_frames,
            screenshot: output_file(SCREENSHOT_VAR, screenshot)?,
            frame_times: output_file(FRAME_TIMES_VAR, frame_times)?,
        })
    }
}

/// The file `variable` names (empty: none), refused when its folder does not exist.
fn output_file(
    variable: &'static str,
    value: Option<&str>,
) -> Result<Option<PathBuf>, AutomationError> {
    let Some(path) = value.filter(|path| !path.is_empty()).map(PathBuf::from) else {
        return Ok(None);
    };
    let folder = path
        .parent()
        .filter(|folder| !folder.as_os_str().is_empty())
        .map_or_else(|| PathBuf::from("."), PathBuf::from);
    if !folder.is_dir() {
        return Err(AutomationError::MissingFolder {
            variable,
            path,
            folder,
        });
    }
    Ok(Some(path))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unset_variables_ask_for_nothing() {
        assert_eq!(
            Automation::parse(None, None, None),
            Ok(Automation::default())
        );
    }

    #[test]
    fn a_frame_count_is_a_whole_number_of_at_least_one() {
        assert_eq!(
            Automation::parse(Some("60"), None, None)
                .unwrap()
                .exit_after_frames,
            Some(60)
        );
        for bad in ["abc", "-1", "0", "1.5", ""] {
            let error = Automation::parse(Some(bad), None, None).unwrap_err();
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
        let error = Automation::parse(None, Some("/no/such/folder/shot.png"), None).unwrap_err();
        assert_eq!(
            error.to_string(),
            "POM_SCREENSHOT=\"/no/such/folder/shot.png\": the folder \"/no/such/folder\" does not exist"
        );
        let here = Automation::parse(None, Some("shot.png"), None).unwrap();
        assert_eq!(here.screenshot, Some(PathBuf::from("shot.png")));
        let error = Automation::parse(None, None, Some("/no/such/times.csv")).unwrap_err();
        assert_eq!(
            error.to_string(),
            "POM_FRAME_TIMES=\"/no/such/times.csv\": the folder \"/no/such\" does not exist"
        );
    }
}
