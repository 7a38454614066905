//! A progress bar on stderr, shown only when stderr is a terminal and `--quiet` is not given.

use indicatif::{ProgressBar, ProgressStyle};
use std::io::IsTerminal;
use std::time::Duration;

/// Turns library progress reports into an indicatif bar (or nothing).
pub struct Bar {
    bar: Option<ProgressBar>,
    len: u64,
}

impl Bar {
    /// A bar of `len` steps; hidden when `quiet` or when stderr is not a terminal.
    pub fn new(quiet: bool, len: u64) -> Self {
        let bar = (!quiet && std::io::stderr().is_terminal()).then(|| {
            let b = ProgressBar::new(len);
            if let Ok(style) = ProgressStyle::with_template(
                "{spinner} [{elapsed_precise}] {wide_bar} {percent:>3}% ETA {eta} {msg}",
            ) {
                b.set_style(style);
            }
            b.enable_steady_tick(Duration::from_millis(150));
            b
        });
        Bar { bar, len }
    }

    /// Advances by one step (sweeps: one point done).
    pub fn inc(&self, message: &str) {
        if let Some(b) = &self.bar {
            b.inc(1);
            b.set_message(message.to_string());
        }
    }

    /// Removes the bar from the terminal.
    pub fn finish(&self) {
        if let Some(b) = &self.bar {
            b.finish_and_clear();
        }
    }
}

impl ehl::run::Progress for Bar {
    fn report(&self, fraction: f64, message: &str) {
        if let Some(b) = &self.bar {
            if fraction.is_finite() {
                b.set_position((fraction.clamp(0.0, 1.0) * self.len as f64).round() as u64);
            }
            b.set_message(message.to_string());
        }
    }
}
