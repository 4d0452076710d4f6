//! Progress bars that appear only on runs longer than about a second, only on a terminal,
//! and never with `--quiet`.

use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressStyle};

/// After this long since the command started, long loops show a bar.
const DELAY: Duration = Duration::from_millis(900);

/// A possibly visible progress bar over `total` steps.
#[derive(Debug)]
pub struct Progress {
    bar: Option<ProgressBar>,
    enabled: bool,
    started: Instant,
    total: u64,
    pos: u64,
    next_check: u64,
    message: &'static str,
}

impl Progress {
    /// A bar for `total` steps of `message`; `started` is when the command started.
    pub fn new(enabled: bool, started: Instant, total: u64, message: &'static str) -> Self {
        Progress {
            bar: None,
            enabled,
            started,
            total,
            pos: 0,
            next_check: 0,
            message,
        }
    }

    /// Advances by `n` steps.
    pub fn inc(&mut self, n: u64) {
        self.pos += n;
        if let Some(bar) = &self.bar {
            if self.pos >= self.next_check {
                bar.set_position(self.pos);
                self.next_check = self.pos + (self.total / 200).max(1);
            }
            return;
        }
        if !self.enabled || self.pos < self.next_check {
            return;
        }
        self.next_check = self.pos + (self.total / 1000).max(64);
        if self.started.elapsed() >= DELAY {
            let bar = ProgressBar::new(self.total);
            if let Ok(style) = ProgressStyle::with_template(
                "{msg:>12} [{bar:40}] {percent:>3}% {elapsed_precise} (eta {eta})",
            ) {
                bar.set_style(style.progress_chars("=> "));
            }
            bar.set_message(self.message);
            bar.set_position(self.pos);
            self.bar = Some(bar);
        }
    }

    /// Removes the bar from the terminal.
    pub fn finish(self) {
        if let Some(bar) = self.bar {
            bar.finish_and_clear();
        }
    }
}
