//! `subdivide_off` with `--threads N` (default 1): every pass of the call runs on `N` std
//! threads ([`nlsubdiv_threads::Threads`]), the output bit for bit that of one thread. For
//! `scripts/bench_peers.py`'s multi-thread column; the options and what is timed are in
//! `examples/support/subdivide_off_main.rs`.
//!
//! `cargo build --release -p nlsubdiv-threads --example subdivide_off_threads`
#![allow(
    clippy::expect_used,
    clippy::unwrap_used,
    clippy::indexing_slicing,
    dead_code
)]

#[path = "../../tests/common/mod.rs"]
mod common;
#[path = "../../examples/support/subdivide_off_main.rs"]
mod subdivide_off_main;

use nlsubdiv::exec::Executor;
use nlsubdiv_threads::Threads;

fn main() {
    subdivide_off_main::main_with(|n| Some(Box::new(Threads::new(n)) as Box<dyn Executor>));
}
