//! Scripted scene tests: a RON file describes a scene and a list of steps (advance frames, change
//! a material, move the camera or a light, capture, expect), run headless with a fixed frame
//! time, and checked against reference images and statistics.

mod check;
mod format;
mod lights;
mod runner;
mod stats;

pub use format::{
    CameraDesc, EntityDesc, LightDesc, MAX_ADVANCE_FRAMES, MaterialDesc, MaterialPatch, Rect,
    Script, ShapeDesc, Statistic, Step, TransformDesc,
};
pub use runner::{SCRIPT_FRAME_TIME, parse_script, parse_script_with, run_script, run_script_with};

use std::fmt;
use std::path::PathBuf;

/// How a script run treats references, where it writes failure images, and which render path
/// it draws on.
#[derive(Clone, Debug, Default)]
pub struct RunOptions {
    /// Write missing or changed reference images instead of failing.
    pub bless: bool,
    /// Where `NAME-actual.png` and `NAME-difference.png` of failed comparisons go (default:
    /// next to the reference).
    pub out_dir: Option<PathBuf>,
    /// The render path ([`crate::RenderPath::Auto`] by default: forward on the software driver
    /// CI runs on, where the references were made).
    pub path: crate::RenderPath,
    /// Which files the script may name (its glTF files, maps, presets and references): only
    /// files inside its own folder by default.
    pub file_access: crate::files::FileAccess,
}

/// What became of one step.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum Outcome {
    /// An action was carried out.
    Done,
    /// An expectation held; the text gives the measured value and the bound.
    Passed(String),
    /// An expectation failed; the text says by how much and where the images are.
    Failed(String),
    /// A reference image was written (blessing).
    Blessed(String),
}

/// The render path a captured frame was shaded on (the renderer's decision for that frame, not
/// the path asked for).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum CapturePath {
    /// Forward, as asked for or as [`crate::RenderPath::Auto`] picked on this adapter.
    Forward,
    /// Deferred.
    Deferred,
    /// Forward although the deferred path was wanted, for this reason.
    FellBackToForward(crate::render::DeferredUnavailable),
}

impl fmt::Display for CapturePath {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CapturePath::Forward => f.write_str("forward"),
            CapturePath::Deferred => f.write_str("deferred"),
            CapturePath::FellBackToForward(reason) => {
                write!(f, "forward, deferred unavailable: {reason}")
            }
        }
    }
}

/// One line of a report.
#[derive(Clone, Debug, PartialEq)]
pub struct StepReport {
    /// 1-based step number.
    pub number: usize,
    /// What the step was.
    pub description: String,
    /// What happened.
    pub outcome: Outcome,
    /// The path the captured frame ran on (capture steps only).
    pub path: Option<CapturePath>,
}

/// The result of running one script.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Report {
    /// The script.
    pub script: PathBuf,
    /// Every step that ran, in order.
    pub steps: Vec<StepReport>,
}

impl Report {
    /// Number of failed expectations.
    pub fn failures(&self) -> usize {
        self.steps
            .iter()
            .filter(|step| matches!(step.outcome, Outcome::Failed(_)))
            .count()
    }

    /// Whether every expectation held.
    pub fn passed(&self) -> bool {
        self.failures() == 0
    }

    /// The capture steps and the path each one's frame ran on, in order.
    pub fn capture_paths(&self) -> impl Iterator<Item = (&StepReport, CapturePath)> {
        self.steps
            .iter()
            .filter_map(|step| step.path.map(|path| (step, path)))
    }
}

impl fmt::Display for Report {
    /// One line per step: `name.ron step 4 ExpectMatch "grazing": pass (…)`; a capture says
    /// its frame's path: `name.ron step 3 Capture "grazing": ok (deferred)`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let name = self.script.display();
        for step in &self.steps {
            let (verdict, detail) = match &step.outcome {
                Outcome::Done => (
                    "ok",
                    step.path
                        .map(|path| format!(" ({path})"))
                        .unwrap_or_default(),
                ),
                Outcome::Passed(detail) => ("pass", format!(" ({detail})")),
                Outcome::Failed(detail) => ("FAIL", format!(" ({detail})")),
                Outcome::Blessed(detail) => ("blessed", format!(" ({detail})")),
            };
            writeln!(
                f,
                "{name} step {} {}: {verdict}{detail}",
                step.number, step.description
            )?;
        }
        Ok(())
    }
}

/// Why a script could not be run to its end.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ScriptError {
    /// The file could not be read.
    #[error("{path}: {reason}")]
    Io {
        /// The script.
        path: PathBuf,
        /// What the file system said.
        reason: String,
    },
    /// The text is not a valid script: syntax, an unknown field, a wrong type.
    #[error("{path}:{line}:{column}: {reason}")]
    Parse {
        /// The script.
        path: PathBuf,
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
        /// What is wrong.
        reason: String,
    },
    /// The script refers to something that does not exist (an entity, a capture, a file).
    #[error("{path}:{line}:{column}: {reason}")]
    Reference {
        /// The script.
        path: PathBuf,
        /// 1-based line of the reference.
        line: usize,
        /// 1-based column.
        column: usize,
        /// What is missing.
        reason: String,
    },
    /// The scene could not be built (GPU, textures, glTF).
    #[error("{path}: {reason}")]
    Setup {
        /// The script.
        path: PathBuf,
        /// What failed.
        reason: String,
    },
    /// A step could not be carried out; the report holds every step before it.
    #[error("{path}: step {step}: {reason}")]
    Step {
        /// The script.
        path: PathBuf,
        /// 1-based step number.
        step: usize,
        /// What failed.
        reason: String,
        /// The steps that ran.
        report: Report,
    },
}
