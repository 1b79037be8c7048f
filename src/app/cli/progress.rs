//! A spinner with the elapsed time on standard error while a long library call runs. It draws
//! only on a terminal and only after the first second, so short runs and pipes stay quiet.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::time::Duration;

/// A running spinner; [`Spinner::finish`] clears it.
pub struct Spinner(ProgressBar);

impl Spinner {
    /// Starts a spinner labelled `what` (hidden when standard error is not a terminal).
    pub fn start(what: &str) -> Spinner {
        let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::stderr());
        bar.set_style(
            ProgressStyle::with_template("{spinner} {msg} {elapsed}")
                .unwrap_or_else(|_| ProgressStyle::default_spinner()),
        );
        bar.set_message(what.to_string());
        // The first tick comes after one second: nothing is drawn for shorter runs.
        bar.enable_steady_tick(Duration::from_millis(1000));
        Spinner(bar)
    }

    /// Clears the spinner.
    pub fn finish(self) {
        self.0.finish_and_clear();
    }
}
