//! Our linear (or Möbius) subdivision of an OFF file on one thread, for the benchmark and
//! comparison scripts: `subdivide_off SCHEME LEVELS IN.off OUT.off [--mobius [--literal]]
//! [--repeat R]` (`examples/support/subdivide_off_main.rs` has the options and what is
//! timed; the threads crate's `subdivide_off_threads` adds `--threads N`).
#![allow(
    clippy::expect_used,
    clippy::unwrap_used,
    clippy::indexing_slicing,
    dead_code
)]

#[path = "../tests/common/mod.rs"]
mod common;
#[path = "support/subdivide_off_main.rs"]
mod subdivide_off_main;

use nlsubdiv::exec::{Executor, Serial};

fn main() {
    subdivide_off_main::main_with(|n| (n == 1).then(|| Box::new(Serial) as Box<dyn Executor>));
}
