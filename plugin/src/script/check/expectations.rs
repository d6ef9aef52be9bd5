//! Checking the expectation steps before anything renders, so that none can pass on nothing:
//! rectangles inside the image and not empty, bounds that some value fails, tolerances that
//! mean something, orders over at least two captures, and captures taken with the debug view
//! their statistic reads.

use std::collections::HashMap;

use super::ScriptText;
use super::values::{locate_step, step_kind};
use crate::DebugView;
use crate::material::Choice;
use crate::script::ScriptError;
use crate::script::format::{Rect, Script, Statistic, Step};
use crate::script::stats::{required_view, stat_name};

/// What is wrong with one field of one step: the field, as the script spells it, and why.
type Problem = (&'static str, String);

/// Checks every expectation step of `script`.
pub(super) fn check_expectations(
    script: &Script,
    source: &ScriptText<'_>,
) -> Result<(), ScriptError> {
    // The debug view of each capture as taken by the steps so far (a name taken again is
    // the later frame).
    let mut views: HashMap<&str, Option<DebugView>> = HashMap::new();
    for (index, step) in script.steps.iter().enumerate() {
        check_expectation(step, script.size, &views).map_err(|(field, reason)| {
            source.invalid(
                locate_step(source.text, &script.steps, index, field),
                format!("step {} ({}): {reason}", index + 1, step_kind(step)),
            )
        })?;
        if let Step::Capture { name, debug_view } = step {
            views.insert(name, *debug_view);
        }
    }
    Ok(())
}

/// A reference names a PNG file (its failure images are named after it): not a folder such
/// as `.` or `sub/..`.
fn need_png_file(reference: &str) -> Result<(), Problem> {
    let path = std::path::Path::new(reference);
    let png = path
        .extension()
        .is_some_and(|extension| extension.eq_ignore_ascii_case("png"));
    if path.file_name().is_some() && png {
        return Ok(());
    }
    Err((
        "reference",
        format!("reference {reference:?} names no PNG file (a reference is a .png image)"),
    ))
}

/// One step's problem, `views` holding the debug view of every capture taken before it.
fn check_expectation(
    step: &Step,
    size: (u32, u32),
    views: &HashMap<&str, Option<DebugView>>,
) -> Result<(), Problem> {
    match step {
        Step::ExpectMatch {
            reference,
            tolerance,
            ..
        } => {
            need_png_file(reference)?;
            match tolerance.problem() {
                Some((field, reason)) => Err((field, format!("tolerance {reason}"))),
                None => Ok(()),
            }
        }
        Step::ExpectStat {
            capture,
            stat,
            rect,
            min,
            max,
        } => {
            need_rect(*rect, size)?;
            need_bounds(*min, *max)?;
            need_views(stat, std::slice::from_ref(capture), views)
        }
        Step::ExpectMonotonic {
            captures,
            stat,
            rect,
            ..
        } => {
            if captures.len() < 2 {
                return Err((
                    "captures",
                    format!(
                        "captures {captures:?} order nothing: an order needs at least 2 captures"
                    ),
                ));
            }
            need_rect(*rect, size)?;
            need_views(stat, captures, views)
        }
        _ => Ok(()),
    }
}

/// A rectangle (x, y, width, height) must have pixels and lie inside the `size` image.
fn need_rect(rect: Option<Rect>, (width, height): (u32, u32)) -> Result<(), Problem> {
    let Some((x, y, w, h)) = rect else {
        return Ok(());
    };
    if w == 0 || h == 0 {
        return Err((
            "rect",
            format!(
                "rect {:?} (x, y, width, height) has no pixels",
                (x, y, w, h)
            ),
        ));
    }
    let (right, bottom) = (u64::from(x) + u64::from(w), u64::from(y) + u64::from(h));
    if right > u64::from(width) || bottom > u64::from(height) {
        return Err((
            "rect",
            format!(
                "rect {:?} (x, y, width, height) reaches ({right}, {bottom}), outside the \
                 {width}×{height} image",
                (x, y, w, h)
            ),
        ));
    }
    Ok(())
}

/// Bounds that some value fails: at least one, each finite, `min` ≤ `max`.
fn need_bounds(min: Option<f32>, max: Option<f32>) -> Result<(), Problem> {
    if min.is_none() && max.is_none() {
        return Err((
            "stat",
            "gives neither min nor max: it would pass on any value".into(),
        ));
    }
    for (field, bound) in [("min", min), ("max", max)] {
        if let Some(bound) = bound
            && !bound.is_finite()
        {
            return Err((field, format!("{field} {bound} is not a finite number")));
        }
    }
    match (min, max) {
        (Some(min), Some(max)) if min > max => Err((
            "min",
            format!("min {min} is above max {max}: no value can pass"),
        )),
        _ => Ok(()),
    }
}

/// Every capture `stat` reads (and its `UvShift` baseline) was taken with the debug view the
/// statistic needs.
fn need_views(
    stat: &Statistic,
    captures: &[String],
    views: &HashMap<&str, Option<DebugView>>,
) -> Result<(), Problem> {
    let Some(needed) = required_view(stat) else {
        return Ok(());
    };
    let baseline = match stat {
        Statistic::UvShift { baseline } => Some(baseline),
        _ => None,
    };
    for capture in captures.iter().chain(baseline) {
        let taken = views.get(capture.as_str()).copied().flatten();
        if taken != Some(needed) {
            let taken = taken.map_or("no debug view", Choice::name);
            return Err((
                "stat",
                format!(
                    "{} needs capture {capture:?} taken with debug_view: {}, but it was taken \
                     with {taken}",
                    stat_name(stat),
                    needed.name()
                ),
            ));
        }
    }
    Ok(())
}
