//! Where each presented frame's CPU time went, for `POM_FRAME_TIMES`: the runner's own work
//! (window events and input, fitting the target, acquiring, presenting) apart from the app's
//! stages, so the runner's cost can be measured on its own.

use std::fmt::Write;
use std::path::Path;
use std::time::{Duration, Instant};

/// One presented frame's times.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct FrameTime {
    /// Handling window and device events since the last frame (input queued, resizes).
    pub events: Duration,
    /// Checking the device and fitting the render target to the window.
    pub fit: Duration,
    /// The app's stages (`App::update`).
    pub update: Duration,
    /// Waiting for and getting the swapchain image.
    pub acquire: Duration,
    /// Recording the present pass (and any overlay's).
    pub record: Duration,
    /// Submitting it and presenting (on a software driver, also the rendering it waits for).
    pub present: Duration,
}

/// The frames' times, kept only when `POM_FRAME_TIMES` asks for them.
#[derive(Debug, Default)]
pub(crate) struct FrameTimes {
    /// Whether times are kept.
    pub on: bool,
    /// The frame being timed.
    pub current: FrameTime,
    rows: Vec<FrameTime>,
}

impl FrameTimes {
    /// Times kept when `on`.
    pub fn new(on: bool) -> Self {
        Self {
            on,
            ..Self::default()
        }
    }

    /// Adds the time since `start` to the part `part` picks of the current frame.
    pub fn add(&mut self, start: Instant, part: fn(&mut FrameTime) -> &mut Duration) {
        if self.on {
            *part(&mut self.current) += start.elapsed();
        }
    }

    /// Ends the current frame (it was presented).
    pub fn presented(&mut self) {
        if self.on {
            self.rows.push(std::mem::take(&mut self.current));
        }
    }

    /// Writes one row per presented frame, times in milliseconds, with
    /// [`crate::files::write_file`].
    pub fn write_csv(&self, path: &Path) -> Result<(), crate::files::WriteError> {
        crate::files::write_file(path, self.csv().as_bytes())
    }

    /// One row per presented frame under a heading.
    fn csv(&self) -> String {
        let mut file = String::new();
        file.push_str("frame,events_ms,fit_ms,update_ms,acquire_ms,record_ms,present_ms\n");
        let ms = |duration: Duration| duration.as_secs_f64() * 1000.0;
        for (frame, row) in self.rows.iter().enumerate() {
            // Writing into a String cannot fail.
            let _ = writeln!(
                file,
                "{frame},{:.4},{:.4},{:.4},{:.4},{:.4},{:.4}",
                ms(row.events),
                ms(row.fit),
                ms(row.update),
                ms(row.acquire),
                ms(row.record),
                ms(row.present)
            );
        }
        file
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_row_has_a_value_under_each_heading() {
        let mut times = FrameTimes::new(true);
        times.add(Instant::now(), |time| &mut time.update);
        times.presented();
        times.presented();
        let path = std::env::temp_dir().join(format!("frame-times-{}.csv", std::process::id()));
        times.write_csv(&path).unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        std::fs::remove_file(&path).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 3, "a heading and one row per presented frame");
        let columns = lines[0].split(',').count();
        assert!(
            lines.iter().all(|line| line.split(',').count() == columns),
            "{text}"
        );
        assert!(lines[0].contains("record_ms"));
    }

    #[test]
    fn nothing_is_kept_when_off() {
        let mut times = FrameTimes::new(false);
        times.add(Instant::now(), |time| &mut time.update);
        times.presented();
        assert!(times.rows.is_empty());
    }
}
