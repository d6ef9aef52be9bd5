//! The failures a window run has reported, each once and a bounded number of them: a failure
//! whose text changes every frame must not grow the list.

/// The most distinct failures a run reports.
const MOST_FAILURES_REPORTED: usize = 32;

/// The failures reported so far.
#[derive(Debug, Default)]
pub(super) struct ReportedFailures(Vec<String>);

impl ReportedFailures {
    /// The lines to report for `failure`, noting it: none where it was reported before or
    /// [`MOST_FAILURES_REPORTED`] were; the last one allowed also says so.
    pub(super) fn report(&mut self, failure: String) -> Vec<String> {
        if self.0.len() >= MOST_FAILURES_REPORTED || self.0.contains(&failure) {
            return Vec::new();
        }
        self.0.push(failure.clone());
        let mut lines = vec![failure];
        if self.0.len() == MOST_FAILURES_REPORTED {
            lines.push(format!(
                "{MOST_FAILURES_REPORTED} different failures reported; later ones are not"
            ));
        }
        lines
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_failure_is_reported_once_and_a_bounded_number_of_them() {
        let mut reported = ReportedFailures::default();
        assert_eq!(reported.report("lost".into()), ["lost"]);
        assert!(reported.report("lost".into()).is_empty());
        // A failure whose text changes every frame.
        let lines: Vec<String> = (0..1000)
            .flat_map(|frame| reported.report(format!("frame {frame} failed")))
            .collect();
        assert_eq!(reported.0.len(), MOST_FAILURES_REPORTED);
        assert_eq!(lines.len(), MOST_FAILURES_REPORTED);
        assert!(lines.last().unwrap().contains("later ones are not"));
    }
}
