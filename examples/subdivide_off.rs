//! Our linear (or Möbius) subdivision of an OFF file, for the peer comparison script:
//! `subdivide_off SCHEME LEVELS IN.off OUT.off [--mobius [--literal]]`. `--literal` runs the
//! paper's Möbius rules without the fold guard (`Options::literal`). Exit 2 when the kernel
//! rejects the mesh (the status is printed on stderr).
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
use nlsubdiv::mesh::MeshOut;
use nlsubdiv::scheme::{self, Options, Scheme, Scratch};

/// `levels` steps in one call of the public path (`scheme::plan`, then `scheme::subdivide`),
/// buffers allocated here: what a host does. The result equals the chain of one-level calls
/// bit for bit (checked by the tests of the multi-level call).
fn levels_call(
    s: Scheme,
    m: &OwnedMesh,
    levels: usize,
    mobius_on: bool,
    literal: bool,
) -> nlsubdiv::Result<OwnedMesh> {
    let opts = Options::new(s)
        .mobius(mobius_on)
        .literal(literal)
        .levels(levels);
    let mut su = vec![0u32; scheme::plan_scratch_size(&m.view())?];
    let p = scheme::plan(m.view(), &opts, &mut su)?;
    let o = p.output();
    // The call needs the plan's scratch, which is never less than what `plan` itself used.
    su.resize(p.scratch.u32s, 0);
    let mut sp = vec![[0.0f64; 3]; p.scratch.points];
    let mut out = OwnedMesh {
        positions: vec![[0.0; 3]; o.vertices],
        offsets: vec![0; o.faces + 1],
        indices: vec![0; o.indices],
    };
    let mut mo = MeshOut::new(&mut out.positions, &mut out.offsets, &mut out.indices);
    scheme::subdivide(m.view(), &opts, Scratch::new(&mut su, &mut sp), &mut mo)?;
    // Kernel memory of this call: the caller's output buffers plus the scratch the plan asks
    // for (everything the kernel touches), for scripts/bench_peers.py.
    let out_bytes = 24 * o.vertices + 4 * (o.faces + 1) + 4 * o.indices;
    let scratch_bytes = 4 * su.len() + 24 * sp.len();
    eprintln!("subdivide_off: output_bytes={out_bytes} scratch_bytes={scratch_bytes}");
    Ok(out)
}

/// The OFF text of `write_off` (tests/common), streamed through a buffer instead of built
/// as one string, so that the process's peak memory is the kernel's plus a small constant,
/// like the peers' harness (peers/peer_subdivide.cpp streams with fprintf).
fn write_off_streamed(path: &Path, m: &OwnedMesh) -> std::io::Result<()> {
    use std::io::Write as _;
    let mut w = std::io::BufWriter::new(std::fs::File::create(path)?);
    writeln!(w, "OFF\n{} {} 0", m.positions.len(), m.num_faces())?;
    for p in &m.positions {
        writeln!(w, "{:?} {:?} {:?}", p[0], p[1], p[2])?;
    }
    for f in m.offsets.windows(2) {
        let face = &m.indices[f[0] as usize..f[1] as usize];
        write!(w, "{}", face.len())?;
        for i in face {
            write!(w, " {i}")?;
        }
        writeln!(w)?;
    }
    w.flush()
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if args.len() < 5 {
        eprintln!("usage: subdivide_off SCHEME LEVELS IN.off OUT.off [--mobius [--literal]]");
        std::process::exit(1);
    }
    let s = Scheme::from_name(&args[1]).unwrap_or_else(|| {
        eprintln!("unknown scheme {}", args[1]);
        std::process::exit(1)
    });
    let levels: usize = args[2].parse().expect("levels");
    let flags = args.get(5..).unwrap_or(&[]);
    let mobius_on = flags.iter().any(|a| a == "--mobius");
    let literal = flags.iter().any(|a| a == "--literal");
    let m = read_off(Path::new(&args[3])).unwrap_or_else(|e| {
        eprintln!("{}: {e}", args[3]);
        std::process::exit(1)
    });
    // Wall time of the subdivision (buffers, validation, topology and every level), without
    // file I/O, printed for scripts/bench_peers.py.
    let t0 = std::time::Instant::now();
    let m = levels_call(s, &m, levels, mobius_on, literal).unwrap_or_else(|e| {
        eprintln!("{}: rejected: {e}", args[3]);
        std::process::exit(2)
    });
    eprintln!(
        "subdivide_off: time_ms={:.3}",
        t0.elapsed().as_secs_f64() * 1e3
    );
    write_off_streamed(Path::new(&args[4]), &m).expect("write");
}
