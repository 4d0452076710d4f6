//! Where the shared test meshes are, and what a test does when they are not there.
//!
//! The real meshes (`*.off`, the broken ones in `bad/`, and a `README.md` table of their
//! counts) are not part of the repository. They are found in the folder named by the
//! environment variable `NLS_SHARED_DATA`, else in `../shared/data/meshes` beside the
//! repository root. A test that needs them and cannot find them must not pass silently:
//! it calls [`shared_meshes`] or [`shared_meshes_partly`] (or [`skip`] for a single missing
//! file), which
//!
//! * writes `SKIP <test>: <what is missing>` straight to the process's stderr, past the
//!   test harness's output capture, so that `cargo test` shows it even for a passing test;
//! * appends the same line to the file named by `NLS_SKIP_LOG`, when that is set (the test
//!   scripts count these lines as skipped tests);
//! * fails the test instead when `NLS_REQUIRE_SHARED_DATA=1`, for runs that must not skip.
//!
//! Only std is used here, so that every test crate can include this one file by `#[path]`:
//! the core's `tests/common/mod.rs` and the command's `cli/tests/common/mod.rs`.

use std::io::Write as _;
use std::path::{Path, PathBuf};

/// Names the shared meshes folder (the one holding the `*.off` files and `bad/`).
pub const SHARED_DATA_VAR: &str = "NLS_SHARED_DATA";
/// Names a file to which every SKIP line is appended.
pub const SKIP_LOG_VAR: &str = "NLS_SKIP_LOG";
/// `1`: a missing shared file fails the test instead of skipping it.
pub const REQUIRE_VAR: &str = "NLS_REQUIRE_SHARED_DATA";

/// The repository root: the nearest folder above the compiling package that holds the
/// workspace's `Cargo.lock` (the root package itself, or the workspace above `cli/`).
fn repository_root() -> PathBuf {
    let manifest = Path::new(env!("CARGO_MANIFEST_DIR"));
    manifest
        .ancestors()
        .find(|d| d.join("Cargo.lock").is_file())
        .unwrap_or(manifest)
        .to_path_buf()
}

/// The shared meshes folder: `$NLS_SHARED_DATA` when set and not empty, else
/// `../shared/data/meshes` beside the repository root. It may not exist; tests call
/// [`shared_meshes`] instead, which reports that. (Benches and examples use this directly
/// and print their own SKIP rows.)
pub fn shared_meshes_dir() -> PathBuf {
    match std::env::var_os(SHARED_DATA_VAR) {
        Some(dir) if !dir.is_empty() => PathBuf::from(dir),
        _ => {
            let root = repository_root();
            root.parent()
                .unwrap_or(&root)
                .join("shared")
                .join("data")
                .join("meshes")
        }
    }
}

/// The shared meshes folder for a test that needs nothing else, or `None` after reporting
/// `test` as skipped (see [`skip`]). `test` names the test as `file::function`, e.g.
/// `mesh_topology::shared_meshes`.
pub fn shared_meshes(test: &str) -> Option<PathBuf> {
    find(test, "nothing checked")
}

/// The shared meshes folder for a test of which only `part` needs them (the rest runs on
/// generated meshes), or `None` after reporting `part` of `test` as skipped.
pub fn shared_meshes_partly(test: &str, part: &str) -> Option<PathBuf> {
    find(test, &format!("{part} not checked"))
}

fn find(test: &str, consequence: &str) -> Option<PathBuf> {
    let dir = shared_meshes_dir();
    if dir.is_dir() {
        Some(dir)
    } else {
        skip(
            test,
            &format!(
                "shared meshes folder {} not found (set {SHARED_DATA_VAR} to it); {consequence}",
                dir.display()
            ),
        );
        None
    }
}

/// Reports that `test` did not check something for want of shared data: `what` says what
/// is missing and what did not run. Prints `SKIP <test>: <what>` to stderr, appends it to
/// `$NLS_SKIP_LOG`, and panics (fails the test) under `NLS_REQUIRE_SHARED_DATA=1`.
pub fn skip(test: &str, what: &str) {
    let line = format!("SKIP {test}: {what}");
    if std::env::var(REQUIRE_VAR).is_ok_and(|v| v == "1") {
        panic!("{line} ({REQUIRE_VAR}=1: missing shared data is a failure)");
    }
    // `eprintln!` would be captured by the test harness and shown only for failing tests;
    // the stderr handle is not.
    let _ = writeln!(std::io::stderr(), "{line}");
    if let Some(log) = std::env::var_os(SKIP_LOG_VAR).filter(|l| !l.is_empty()) {
        // One write of one line in append mode: lines of tests running in parallel (and of
        // other test binaries) do not interleave.
        let appended = std::fs::OpenOptions::new()
            .create(true)
            .append(true)
            .open(&log)
            .and_then(|mut f| f.write_all(format!("{line}\n").as_bytes()));
        if let Err(e) = appended {
            panic!(
                "{line}; and cannot append it to {SKIP_LOG_VAR}={}: {e}",
                Path::new(&log).display()
            );
        }
    }
}
