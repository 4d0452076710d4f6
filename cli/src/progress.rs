//! Progress bars that appear only on runs longer than about a second, only on a terminal,
//! and never with `--quiet`.

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{mpsc, Arc};
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

/// A bar over a few long steps that cannot report progress inside themselves (the levels of
/// a subdivision: one core call each). A helper thread shows it once the command has run
/// for about a second and keeps its elapsed time ticking between the steps; the position
/// moves by each step's weight when the step ends.
#[derive(Debug)]
pub struct Steps {
    stop: Option<mpsc::Sender<()>>,
    thread: Option<JoinHandle<()>>,
    state: Arc<(AtomicU64, AtomicU64)>,
}

impl Steps {
    /// Starts the bar's thread: `total` weight over `steps` steps of `message`.
    pub fn start(
        enabled: bool,
        started: Instant,
        total: u64,
        steps: u64,
        message: &'static str,
    ) -> Steps {
        let state = Arc::new((AtomicU64::new(0), AtomicU64::new(0)));
        if !enabled || steps == 0 {
            return Steps {
                stop: None,
                thread: None,
                state,
            };
        }
        let (tx, rx) = mpsc::channel::<()>();
        let wait = DELAY.saturating_sub(started.elapsed());
        let shared = Arc::clone(&state);
        let thread = std::thread::Builder::new()
            .name("progress".into())
            .spawn(move || {
                if rx.recv_timeout(wait) != Err(mpsc::RecvTimeoutError::Timeout) {
                    return; // finished in time
                }
                let bar = ProgressBar::new(total.max(1));
                if let Ok(style) = ProgressStyle::with_template(
                    "{msg:>16} [{bar:40}] {percent:>3}% {elapsed_precise}",
                ) {
                    bar.set_style(style.progress_chars("=> "));
                }
                bar.enable_steady_tick(Duration::from_millis(200));
                loop {
                    let (pos, done) = (
                        shared.0.load(Ordering::Relaxed),
                        shared.1.load(Ordering::Relaxed),
                    );
                    bar.set_position(pos);
                    bar.set_message(format!("{message} {}/{steps}", (done + 1).min(steps)));
                    if rx.recv_timeout(Duration::from_millis(100))
                        != Err(mpsc::RecvTimeoutError::Timeout)
                    {
                        break;
                    }
                }
                bar.finish_and_clear();
            })
            .ok();
        Steps {
            stop: Some(tx),
            thread,
            state,
        }
    }

    /// One more step is done, of `weight`.
    pub fn step_done(&self, weight: u64) {
        self.state.0.fetch_add(weight, Ordering::Relaxed);
        self.state.1.fetch_add(1, Ordering::Relaxed);
    }
}

impl Drop for Steps {
    fn drop(&mut self) {
        if let Some(tx) = self.stop.take() {
            let _ = tx.send(());
        }
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}
