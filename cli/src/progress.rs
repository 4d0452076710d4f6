//! Progress bars that appear only on runs longer than about a second, only on a terminal,
//! and never with `--quiet`.

use std::sync::mpsc;
use std::thread::JoinHandle;
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

/// A spinner for steps that cannot count their progress (reading a file, building the
/// topology): shown by a helper thread only once the command has run for about a second.
#[derive(Debug)]
pub struct Spinner {
    stop: Option<mpsc::Sender<()>>,
    thread: Option<JoinHandle<()>>,
}

impl Spinner {
    /// Starts the spinner's thread (nothing at all when `enabled` is false).
    pub fn start(enabled: bool, started: Instant, message: &'static str) -> Spinner {
        if !enabled {
            return Spinner {
                stop: None,
                thread: None,
            };
        }
        let (tx, rx) = mpsc::channel::<()>();
        let wait = DELAY.saturating_sub(started.elapsed());
        let thread = std::thread::Builder::new()
            .name("spinner".into())
            .spawn(move || {
                if rx.recv_timeout(wait) != Err(mpsc::RecvTimeoutError::Timeout) {
                    return; // stopped in time
                }
                let bar = ProgressBar::new_spinner();
                if let Ok(style) = ProgressStyle::with_template("{msg:>12} {spinner} {elapsed}") {
                    bar.set_style(style);
                }
                bar.set_message(message);
                bar.enable_steady_tick(Duration::from_millis(120));
                let _ = rx.recv();
                bar.finish_and_clear();
            })
            .ok();
        Spinner {
            stop: Some(tx),
            thread,
        }
    }
}

impl Drop for Spinner {
    fn drop(&mut self) {
        if let Some(tx) = self.stop.take() {
            let _ = tx.send(());
        }
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}
