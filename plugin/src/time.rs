//! [`Time`]: how long the last frame took and how long the app has run, advanced first in every
//! [`crate::App::update`] whatever drives the app (a window's runner, a loop of its own, a scene
//! script), in real time or, for runs that must repeat exactly, by a fixed step.

use std::time::{Duration, Instant};

/// How [`Time`] advances from one update to the next.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TimeStep {
    /// By the wall clock between the starts of two updates, at most [`Time::MAX_DELTA`] (a
    /// stop in a debugger, or a window dragged, is one long frame, not a jump in the game).
    Real,
    /// By exactly this much every update: scene scripts and tests repeat to the bit.
    Fixed(Duration),
}

/// The app's clock. A resource every app has; systems read it, e.g.
/// `resources.get::<Time>().map_or(0.0, Time::delta_secs)`.
///
/// # Example
/// ```
/// use std::time::Duration;
/// let mut app = pom::App::new();
/// app.insert_resource(pom::Time::fixed(Duration::from_millis(20)));
/// app.update()?;
/// app.update()?;
/// let time = app.resources.get::<pom::Time>().unwrap();
/// assert_eq!((time.delta(), time.elapsed(), time.frame_count()), (Duration::from_millis(20), Duration::from_millis(40), 1));
/// # Ok::<(), pom::AppError>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Time {
    step: TimeStep,
    delta: Duration,
    elapsed: Duration,
    /// Updates begun, minus one: 0 during the first.
    frame_count: u64,
    /// When the last update began (real time only).
    last_start: Option<Instant>,
    /// Whether any update has begun.
    started: bool,
}

impl Default for Time {
    fn default() -> Self {
        Self::with_step(TimeStep::Real)
    }
}

impl Time {
    /// The longest frame [`TimeStep::Real`] counts.
    pub const MAX_DELTA: Duration = Duration::from_millis(250);

    /// A clock that advances by `step` every update.
    pub fn fixed(step: Duration) -> Self {
        Self::with_step(TimeStep::Fixed(step))
    }

    /// A clock that advances as `step` says, from zero.
    pub fn with_step(step: TimeStep) -> Self {
        Self {
            step,
            delta: Duration::ZERO,
            elapsed: Duration::ZERO,
            frame_count: 0,
            last_start: None,
            started: false,
        }
    }

    /// How the clock advances.
    pub fn step(&self) -> TimeStep {
        self.step
    }

    /// Changes how the clock advances from the next update on (elapsed time is kept).
    pub fn set_step(&mut self, step: TimeStep) {
        self.step = step;
        self.last_start = None;
    }

    /// How long the last frame took (0 in the first update of a real-time clock).
    pub fn delta(&self) -> Duration {
        self.delta
    }

    /// [`Time::delta`] in seconds.
    pub fn delta_secs(&self) -> f32 {
        self.delta.as_secs_f32()
    }

    /// Time since the first update, summed from the deltas.
    pub fn elapsed(&self) -> Duration {
        self.elapsed
    }

    /// [`Time::elapsed`] in seconds.
    pub fn elapsed_secs(&self) -> f64 {
        self.elapsed.as_secs_f64()
    }

    /// Which update this is: 0 during the first, then one more each update.
    pub fn frame_count(&self) -> u64 {
        self.frame_count
    }

    /// Begins an update that started at `now`: [`crate::App::update`] calls it first.
    pub fn advance(&mut self, now: Instant) {
        if self.started {
            self.frame_count += 1;
        }
        self.delta = match self.step {
            TimeStep::Fixed(step) => step,
            TimeStep::Real => self.last_start.map_or(Duration::ZERO, |last| {
                now.saturating_duration_since(last).min(Self::MAX_DELTA)
            }),
        };
        self.last_start = (self.step == TimeStep::Real).then_some(now);
        self.elapsed += self.delta;
        self.started = true;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn real_time_starts_at_zero_then_follows_the_clock_up_to_the_cap() {
        let start = Instant::now();
        let mut time = Time::default();
        time.advance(start);
        assert_eq!(
            (time.delta(), time.elapsed(), time.frame_count()),
            (Duration::ZERO, Duration::ZERO, 0)
        );
        time.advance(start + Duration::from_millis(16));
        assert_eq!(time.delta(), Duration::from_millis(16));
        time.advance(start + Duration::from_secs(10));
        assert_eq!(
            time.delta(),
            Time::MAX_DELTA,
            "a long stop is one capped frame"
        );
        assert_eq!(time.elapsed(), Duration::from_millis(16) + Time::MAX_DELTA);
        assert_eq!(time.frame_count(), 2);
        // A clock that went backwards (another thread's instant) counts as no time.
        time.advance(start);
        assert_eq!(time.delta(), Duration::ZERO);
    }

    #[test]
    fn a_fixed_step_ignores_the_clock_and_switching_keeps_the_elapsed_time() {
        let start = Instant::now();
        let mut time = Time::fixed(Duration::from_millis(10));
        for frame in 0..3 {
            time.advance(start + Duration::from_secs(frame));
        }
        assert_eq!(
            (time.delta(), time.elapsed()),
            (Duration::from_millis(10), Duration::from_millis(30))
        );
        time.set_step(TimeStep::Real);
        time.advance(start + Duration::from_secs(5));
        assert_eq!(
            time.delta(),
            Duration::ZERO,
            "no earlier real-time start to measure from"
        );
        time.advance(start + Duration::from_secs(5) + Duration::from_millis(5));
        assert_eq!(time.delta(), Duration::from_millis(5));
        assert_eq!(time.elapsed(), Duration::from_millis(35));
        assert_eq!(time.frame_count(), 4);
    }
}
