//! How the process ends when something outside the command's control happens: a signal, a
//! closed output pipe, a panic. In every case the temporary output files are removed first
//! ([`crate::io::remove_temporary_files_for_exit`]), so nothing half-written stays behind.
//!
//! * SIGINT, SIGTERM, SIGHUP: a thread of `signal-hook` receives the signal, removes the
//!   temporary files, and ends the process by the same signal (its default action), so the
//!   shell sees what killed it.
//! * SIGXFSZ (a `ulimit -f` file-size limit): handled, so that the kernel does not kill the
//!   process; the write that went past the limit fails with `EFBIG` and the command ends
//!   through its ordinary I/O error (exit 3, the temporary file removed).
//! * SIGPIPE is ignored by the Rust runtime: writing to a closed pipe is an `EPIPE` error,
//!   which ends the command quietly with exit 3 (`io::write_error`, `out`).
//! * A panic (a bug) removes the temporary files and then aborts as before; a failure of
//!   `println!`/`eprintln!` (whose output went to a closed pipe) ends quietly with exit 3
//!   instead.
//!
//! SIGKILL cannot be caught: a killed process may leave a `.NAME.nlsubdiv-PID-N.tmp` file.

use std::io::Write;
use std::sync::atomic::AtomicBool;
use std::sync::Arc;

use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM, SIGXFSZ};
use signal_hook::iterator::Signals;

use crate::error::{sanitize_line, Exit};
use crate::io::remove_temporary_files_for_exit;

/// The longest message line printed (characters): file names and messages of libraries are
/// bounded too.
const MAX_LINE_CHARS: usize = 1000;

/// Installs the signal handlers and the panic hook. Failing to install one (no threads
/// left, say) is not fatal: the command runs without that protection.
pub fn install_handlers() {
    // SIGXFSZ: a flag nobody reads; what matters is that the default action (kill) is gone.
    let _ = signal_hook::flag::register(SIGXFSZ, Arc::new(AtomicBool::new(false)));
    if let Ok(mut signals) = Signals::new([SIGINT, SIGTERM, SIGHUP]) {
        let _ = std::thread::Builder::new()
            .name("signals".into())
            .spawn(move || {
                if let Some(sig) = signals.forever().next() {
                    remove_temporary_files_for_exit();
                    let _ = signal_hook::low_level::emulate_default_handler(sig);
                    // Only reached if the default action did not end the process.
                    std::process::exit(128 + sig);
                }
            });
    }
    let default_hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        remove_temporary_files_for_exit();
        let msg = info
            .payload()
            .downcast_ref::<String>()
            .map(String::as_str)
            .or_else(|| info.payload().downcast_ref::<&str>().copied())
            .unwrap_or("");
        // std's print macros panic when their stream is gone (a closed pipe): not a bug of
        // ours, and nobody is listening for a message.
        if msg.starts_with("failed printing to std") {
            std::process::exit(Exit::Io as i32);
        }
        default_hook(info);
    }));
}

/// Prints an error message on stderr, one `nlsubdiv: error:` line per line, each made safe
/// for a terminal and bounded ([`sanitize_line`]). An empty message prints nothing (a quiet
/// exit); a failure to write stderr is ignored.
pub fn print_error(message: &str) {
    let mut err = std::io::stderr().lock();
    for line in message.lines() {
        let _ = writeln!(
            err,
            "nlsubdiv: error: {}",
            sanitize_line(line, MAX_LINE_CHARS)
        );
    }
}
