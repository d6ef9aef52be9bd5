//! The timing panel: a graph of the last frames' CPU frame times, drawn with egui's painter,
//! and the plugin's per-pass GPU times.

use std::collections::VecDeque;

use egui::{Color32, Sense, Stroke, Ui, pos2, vec2};
use pom::GpuTimings;

/// How many frames the graph shows.
pub const FRAME_HISTORY: usize = 240;
/// Height of the graph, in points.
const GRAPH_HEIGHT: f32 = 60.0;

/// The last [`FRAME_HISTORY`] frame times, oldest first.
#[derive(Clone, Debug, Default)]
pub struct FrameTimes {
    seconds: VecDeque<f32>,
}

impl FrameTimes {
    /// Records one frame's time; the oldest drops out once the history is full. Non-finite or
    /// negative times are ignored.
    pub fn push(&mut self, seconds: f32) {
        if !(seconds.is_finite() && seconds >= 0.0) {
            return;
        }
        if self.seconds.len() == FRAME_HISTORY {
            self.seconds.pop_front();
        }
        self.seconds.push_back(seconds);
    }

    /// How many frames are recorded.
    pub fn len(&self) -> usize {
        self.seconds.len()
    }

    /// The mean and the largest frame time, in seconds (`None` before the first frame).
    pub fn mean_and_max(&self) -> Option<(f32, f32)> {
        let count = self.seconds.len();
        (count > 0).then(|| {
            let sum: f32 = self.seconds.iter().sum();
            let max = self.seconds.iter().copied().fold(0.0, f32::max);
            (sum / count as f32, max)
        })
    }

    /// Draws the summary line and the graph (taller bars are slower frames; the line marks
    /// 16.7 ms, one frame at 60 Hz).
    pub fn show(&self, ui: &mut Ui) {
        match self.mean_and_max() {
            Some((mean, max)) => ui.label(format!(
                "CPU frame: {:.1} ms mean, {:.1} ms max over {} frames",
                mean * 1e3,
                max * 1e3,
                self.len()
            )),
            None => ui.label("CPU frame: no frames yet"),
        }
        .on_hover_text(
            "Time between the starts of consecutive frames: UI, scene update, rendering and \
             presenting together.",
        );
        let (response, painter) =
            ui.allocate_painter(vec2(ui.available_width(), GRAPH_HEIGHT), Sense::hover());
        let rect = response.rect;
        painter.rect_filled(rect, 2.0, Color32::from_gray(20));
        let scale_max = self
            .mean_and_max()
            .map_or(1.0 / 30.0, |(_, max)| max.max(1.0 / 30.0));
        let y_of = |seconds: f32| rect.bottom() - rect.height() * (seconds / scale_max).min(1.0);
        let bar_width = rect.width() / FRAME_HISTORY as f32;
        // Newest frame at the right edge.
        let start = FRAME_HISTORY - self.seconds.len();
        for (index, seconds) in self.seconds.iter().enumerate() {
            let x = rect.left() + (start + index) as f32 * bar_width;
            painter.line_segment(
                [pos2(x, rect.bottom()), pos2(x, y_of(*seconds))],
                Stroke::new(bar_width.max(1.0), Color32::from_rgb(110, 180, 255)),
            );
        }
        let sixty_hz = y_of(1.0 / 60.0);
        painter.line_segment(
            [pos2(rect.left(), sixty_hz), pos2(rect.right(), sixty_hz)],
            Stroke::new(1.0, Color32::from_rgb(255, 190, 90)),
        );
        response.on_hover_text(format!(
            "Last {FRAME_HISTORY} frames, newest on the right; full height = {:.1} ms, the \
             orange line = 16.7 ms.",
            scale_max * 1e3
        ));
    }
}

/// Where the GPU timing rows come from: the plugin's [`GpuTimings`] and whether the adapter is a
/// software rasterizer, whose timings say nothing about GPU speed.
#[derive(Clone, Copy, Debug, Default)]
pub struct GpuTimingSource<'a> {
    /// The plugin's resource, if the render plugin runs.
    pub timings: Option<&'a GpuTimings>,
    /// Whether the adapter is a CPU (software) rasterizer.
    pub software_driver: bool,
}

/// The GPU timing rows: one line per timed pass, or why there are none ("n/a" where the adapter
/// has no timestamp queries or is a software driver).
pub fn gpu_pass_lines(source: GpuTimingSource<'_>) -> Vec<String> {
    if source.software_driver {
        return vec!["GPU time per pass: n/a (software driver: not GPU timings)".to_owned()];
    }
    match source.timings {
        None | Some(GpuTimings::Unsupported) => {
            vec!["GPU time per pass: n/a (no timestamp queries on this adapter)".to_owned()]
        }
        Some(GpuTimings::Supported {
            passes,
            frame,
            rejected,
        }) => {
            if passes.is_empty() {
                return vec!["GPU time per pass: waiting for the first reading".to_owned()];
            }
            let mut lines = vec![format!("GPU time per pass (frame {frame}):")];
            lines.extend(
                passes
                    .iter()
                    .map(|(pass, ms)| format!("  {pass}: {ms:.3} ms")),
            );
            if *rejected > 0 {
                lines.push(format!("  {rejected} invalid readings dropped"));
            }
            lines
        }
    }
}

/// Shows [`gpu_pass_lines`].
pub fn gpu_pass_rows(ui: &mut Ui, source: GpuTimingSource<'_>) {
    let lines = gpu_pass_lines(source);
    for line in &lines {
        ui.label(line).on_hover_text(
            "GPU time of each render pass of the main image, from timestamp queries, a frame or \
             two late so the frame never waits for them. The split view's second image is not \
             timed.",
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_history_keeps_the_newest_frames_and_ignores_bad_times() {
        let mut times = FrameTimes::default();
        assert_eq!(times.mean_and_max(), None);
        for frame in 0..FRAME_HISTORY + 10 {
            times.push(frame as f32 * 1e-3);
        }
        times.push(f32::NAN);
        times.push(-1.0);
        assert_eq!(times.len(), FRAME_HISTORY);
        let (mean, max) = times.mean_and_max().unwrap();
        assert!((max - (FRAME_HISTORY + 9) as f32 * 1e-3).abs() < 1e-6);
        // Frames 10..250 remain: their mean is 129.5 ms.
        assert!((mean - 0.1295).abs() < 1e-5, "{mean}");
    }

    #[test]
    fn gpu_rows_show_each_pass_or_say_why_there_is_none() {
        let of = |timings| GpuTimingSource {
            timings,
            software_driver: false,
        };
        assert_eq!(
            gpu_pass_lines(of(Some(&GpuTimings::Unsupported))),
            ["GPU time per pass: n/a (no timestamp queries on this adapter)"]
        );
        assert_eq!(
            gpu_pass_lines(of(None)),
            gpu_pass_lines(of(Some(&GpuTimings::Unsupported)))
        );
        let mut passes = std::collections::BTreeMap::new();
        let waiting = GpuTimings::Supported {
            passes: passes.clone(),
            frame: 0,
            rejected: 0,
        };
        assert_eq!(
            gpu_pass_lines(of(Some(&waiting))),
            ["GPU time per pass: waiting for the first reading"]
        );
        passes.insert("main pass".to_owned(), 1.25);
        passes.insert("sobel pass".to_owned(), 0.0625);
        let timed = GpuTimings::Supported {
            passes,
            frame: 7,
            rejected: 2,
        };
        assert_eq!(
            gpu_pass_lines(GpuTimingSource {
                timings: Some(&timed),
                software_driver: true,
            }),
            ["GPU time per pass: n/a (software driver: not GPU timings)"]
        );
        assert_eq!(
            gpu_pass_lines(of(Some(&timed))),
            [
                "GPU time per pass (frame 7):",
                "  main pass: 1.250 ms",
                "  sobel pass: 0.062 ms",
                "  2 invalid readings dropped"
            ]
        );
    }
}
