//! Our linear (or Möbius) subdivision of an OFF file, for the peer comparison script:
//! `subdivide_off SCHEME LEVELS IN.off OUT.off [--mobius]`. Exit 2 when the kernel rejects
//! the mesh (the status is printed on stderr).
#![allow(
    clippy::expect_used,
    clippy::unwrap_used,
    clippy::indexing_slicing,
    dead_code
)]

#[path = "../tests/common/mod.rs"]
mod common;

use std::path::Path;

use common::*;
use nlsubdiv::scheme::Scheme;

fn step(s: Scheme, m: &OwnedMesh, mobius_on: bool) -> nlsubdiv::Result<OwnedMesh> {
    if mobius_on {
        Ok(mobius_subdivide(s, m, false)?.0)
    } else {
        subdivide(s, m)
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if args.len() < 5 {
        eprintln!("usage: subdivide_off SCHEME LEVELS IN.off OUT.off [--mobius]");
        std::process::exit(1);
    }
    let s = Scheme::from_name(&args[1]).unwrap_or_else(|| {
        eprintln!("unknown scheme {}", args[1]);
        std::process::exit(1)
    });
    let levels: usize = args[2].parse().expect("levels");
    let mobius_on = args.get(5).is_some_and(|a| a == "--mobius");
    let mut m = read_off(Path::new(&args[3])).unwrap_or_else(|e| {
        eprintln!("{}: {e}", args[3]);
        std::process::exit(1)
    });
    // Wall time of the subdivision (validation, topology and every level), without file I/O,
    // printed for scripts/bench_peers.py.
    let t0 = std::time::Instant::now();
    for _ in 0..levels {
        m = step(s, &m, mobius_on).unwrap_or_else(|e| {
            eprintln!("{}: rejected: {e}", args[3]);
            std::process::exit(2)
        });
    }
    eprintln!(
        "subdivide_off: time_ms={:.3}",
        t0.elapsed().as_secs_f64() * 1e3
    );
    write_off(Path::new(&args[4]), &m).expect("write");
}
