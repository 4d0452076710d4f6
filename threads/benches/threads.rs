//! 1 thread against 2 (or `NLS_BENCH_THREADS`) on the Möbius benchmark rows (`MOBIUS_BENCH_ROWS`),
//! linear and Möbius (the guarded default), interleaved A B C A B C, best of 7 each: each row
//! is one multi-level call as a host makes it (`plan`, the buffers, `subdivide_with` on
//! [`nlsubdiv_threads::Threads`]), on the persistent pool (`Threads::new`) and on threads
//! spawned for each pass (`Threads::scoped`). Every run's output is also compared bit for
//! bit with the one thread's.
//!
//! `cargo bench -p nlsubdiv-threads --bench threads` (reads `../shared/data/meshes`).
#![allow(
    clippy::expect_used,
    clippy::unwrap_used,
    clippy::indexing_slicing,
    dead_code
)]

#[path = "../../tests/common/mod.rs"]
mod common;

use std::time::Instant;

use common::*;
use nlsubdiv::mesh::MeshOut;
use nlsubdiv::scheme::{self, Options, Scratch};
use nlsubdiv::Point;
use nlsubdiv_threads::Threads;

/// Buffers of exactly the planned sizes for `opts` on `m`, allocated and touched once, so
/// that the timed calls measure the kernel on warm buffers (no first-touch page faults,
/// which the kernel cannot split over threads: they belong to the host's allocation).
struct Buffers {
    su: Vec<u32>,
    sp: Vec<Point>,
    out: OwnedMesh,
}

impl Buffers {
    fn new(m: &OwnedMesh, opts: &Options) -> Buffers {
        let mut su = vec![0u32; scheme::plan_scratch_size(&m.view()).expect("size")];
        let p = scheme::plan(m.view(), opts, &mut su).expect("plan");
        su.resize(p.scratch.u32s, 0);
        let o = p.output();
        Buffers {
            su,
            sp: vec![[0.0; 3]; p.scratch.points],
            out: OwnedMesh {
                positions: vec![[0.0; 3]; o.vertices],
                offsets: vec![0; o.faces + 1],
                indices: vec![0; o.indices],
            },
        }
    }

    /// One call as a host with warm buffers makes it (plan, then subdivide), in ms.
    fn call(&mut self, m: &OwnedMesh, opts: &Options, exec: &Threads) -> f64 {
        let t = Instant::now();
        scheme::plan(m.view(), opts, &mut self.su).expect("plan");
        let o = &mut self.out;
        let mut mo = MeshOut::new(&mut o.positions, &mut o.offsets, &mut o.indices);
        scheme::subdivide_with(
            m.view(),
            opts,
            Scratch::new(&mut self.su, &mut self.sp),
            &mut mo,
            exec,
        )
        .expect("subdivide");
        t.elapsed().as_secs_f64() * 1e3
    }
}

fn main() {
    let n: usize = std::env::var("NLS_BENCH_THREADS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(2);
    let reps = 7;
    let dir = shared_meshes_dir();
    println!(
        "| row | output faces | cold: 1 thread ms | {n} threads ms | speed-up | scoped ms | warm: 1 thread ms | {n} threads ms | speed-up | scoped ms |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|");
    for (name, s, levels) in MOBIUS_BENCH_ROWS {
        let Ok(m) = read_off(&dir.join(name)) else {
            println!(
                "| {name} | SKIP: {} not found | | | | | | | | |",
                dir.display()
            );
            continue;
        };
        for mobius in [false, true] {
            let opts = Options::new(s).mobius(mobius).levels(levels);
            let (one, many, scoped) = (Threads::new(1), Threads::new(n), Threads::scoped(n));
            // Cold: a fresh call with its own buffers each time (allocation and first touch
            // inside the timed region, as in a fresh process); warm: the same buffers again.
            let (mut a, mut b, mut c) = (f64::MAX, f64::MAX, f64::MAX);
            let (mut wa, mut wb, mut wc) = (f64::MAX, f64::MAX, f64::MAX);
            let (mut ba, mut bb, mut bc) = (
                Buffers::new(&m, &opts),
                Buffers::new(&m, &opts),
                Buffers::new(&m, &opts),
            );
            let mut faces = 0;
            for _ in 0..reps {
                let t = Instant::now();
                let (oa, _) = run_with(&m, &opts, &one).expect("1 thread");
                a = a.min(t.elapsed().as_secs_f64() * 1e3);
                let t = Instant::now();
                let (ob, _) = run_with(&m, &opts, &many).expect("n threads");
                b = b.min(t.elapsed().as_secs_f64() * 1e3);
                let t = Instant::now();
                let (oc, _) = run_with(&m, &opts, &scoped).expect("n scoped threads");
                c = c.min(t.elapsed().as_secs_f64() * 1e3);
                assert_eq!(hash(&oa), hash(&ob), "{name}: outputs differ");
                assert_eq!(hash(&oa), hash(&oc), "{name}: outputs differ");
                wa = wa.min(ba.call(&m, &opts, &one));
                wb = wb.min(bb.call(&m, &opts, &many));
                wc = wc.min(bc.call(&m, &opts, &scoped));
                assert_eq!(hash(&ba.out), hash(&oa), "{name}: warm output differs");
                assert_eq!(hash(&bb.out), hash(&oa), "{name}: warm output differs");
                assert_eq!(hash(&bc.out), hash(&oa), "{name}: warm output differs");
                faces = ob.num_faces();
            }
            println!(
                "| {} {}{} {levels} | {faces} | {a:.1} | {b:.1} | {:.2} | {c:.1} | {wa:.1} | {wb:.1} | {:.2} | {wc:.1} |",
                s.name(),
                name.trim_end_matches(".off"),
                if mobius { " Möbius" } else { "" },
                a / b,
                wa / wb
            );
        }
    }
}
