//! The body of `subdivide_off` (this crate's example, one thread) and
//! `subdivide_off_threads` (the threads crate's example, `--threads N`): one multi-level
//! subdivision of an OFF file as a host makes it, timed without file I/O, for the benchmark
//! and comparison scripts (`scripts/bench_peers.py`, `scripts/peer_compare.py`,
//! `benches/*.sh`).
//!
//! `SCHEME LEVELS IN.off OUT.off [--mobius [--literal]] [--threads N] [--repeat R]`
//!
//! * `--literal` runs the paper's Möbius rules without the fold guard (`Options::literal`).
//! * `--threads N` runs every pass on `N` threads (only `subdivide_off_threads` accepts
//!   more than 1).
//! * stderr gets `time_ms=` (the cold call: plan, buffers of a fresh process, validation,
//!   topology and every level; the first touch of the output and scratch pages included),
//!   `output_bytes= scratch_bytes=` (everything the kernel touches), and with `--repeat R`
//!   also `warm_ms=`: the best of `R` further calls, plan included, into the same buffers,
//!   which are then already in memory (a host that subdivides again and again).
//!
//! Exit 2 when the kernel rejects the mesh (the status is printed on stderr).

use std::path::Path;
use std::time::Instant;

use crate::common::*;
use nlsubdiv::exec::Executor;
use nlsubdiv::mesh::MeshOut;
use nlsubdiv::scheme::{self, Options, Scheme, Scratch};

/// `levels` steps in one call of the public path (`scheme::plan`, then
/// `scheme::subdivide_with`), buffers allocated here: what a host does. The result equals the
/// chain of one-level calls bit for bit (checked by the tests of the multi-level call), and
/// is the same for every executor. Returns the output, the cold call's time (plan, buffers,
/// subdivision) and the best warm time of `repeat` further calls into the same buffers
/// (`None` without repeats), in milliseconds.
fn levels_call(
    opts: &Options,
    m: &OwnedMesh,
    exec: &dyn Executor,
    repeat: usize,
) -> nlsubdiv::Result<(OwnedMesh, f64, Option<f64>)> {
    let t0 = Instant::now();
    let mut su = vec![0u32; scheme::plan_scratch_size(&m.view())?];
    let p = scheme::plan(m.view(), opts, &mut su)?;
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
    // Call 0 is the cold one (its plan and buffers above are in its time); calls 1..=repeat
    // plan again into the same scratch and write the same, now warm, buffers.
    let (mut cold, mut warm) = (0.0, None::<f64>);
    for call in 0..=repeat {
        let t = Instant::now();
        if call > 0 {
            scheme::plan(m.view(), opts, &mut su)?;
        }
        let scratch = Scratch::new(&mut su, &mut sp);
        kernel_call(m.view(), opts, scratch, &mut mo, exec)?;
        if call == 0 {
            cold = t0.elapsed().as_secs_f64() * 1e3;
        } else {
            let ms = t.elapsed().as_secs_f64() * 1e3;
            warm = Some(warm.map_or(ms, |w| w.min(ms)));
        }
    }
    // Kernel memory of this call: the caller's output buffers plus the scratch the plan asks
    // for (everything the kernel touches), for scripts/bench_peers.py.
    let out_bytes = 24 * o.vertices + 4 * (o.faces + 1) + 4 * o.indices;
    let scratch_bytes = 4 * su.len() + 24 * sp.len();
    eprintln!("subdivide_off: output_bytes={out_bytes} scratch_bytes={scratch_bytes}");
    Ok((out, cold, warm))
}

/// The kernel's call, in a frame of its own: `benches/serial_share.sh` counts the
/// instructions under this symbol (the library's own functions may be inlined into it).
#[inline(never)]
fn kernel_call(
    mesh: nlsubdiv::Mesh<'_>,
    opts: &Options,
    scratch: Scratch<'_>,
    out: &mut MeshOut<'_>,
    exec: &dyn Executor,
) -> nlsubdiv::Result<nlsubdiv::Report> {
    scheme::subdivide_with(mesh, opts, scratch, out, exec)
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

/// The value after `flag` in `flags`, parsed (`default` when the flag is absent); exits 1 on
/// a missing or unparsable value.
fn flag_value(flags: &[String], flag: &str, default: usize) -> usize {
    match flags.iter().position(|a| a == flag) {
        None => default,
        Some(i) => flags
            .get(i + 1)
            .and_then(|v| v.parse().ok())
            .unwrap_or_else(|| {
                eprintln!("{flag} needs a number");
                std::process::exit(1)
            }),
    }
}

/// Runs the command; `executor(n)` gives the executor of `--threads n` (`None`: this binary
/// does not run `n` threads).
pub fn main_with(executor: impl Fn(usize) -> Option<Box<dyn Executor>>) {
    let args: Vec<String> = std::env::args().collect();
    if args.len() < 5 {
        eprintln!(
            "usage: {} SCHEME LEVELS IN.off OUT.off [--mobius [--literal]] [--threads N] [--repeat R]",
            args.first().map_or("subdivide_off", String::as_str)
        );
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
    let threads = flag_value(flags, "--threads", 1);
    let repeat = flag_value(flags, "--repeat", 0);
    let exec = executor(threads).unwrap_or_else(|| {
        eprintln!("--threads {threads}: this binary runs one thread (use subdivide_off_threads)");
        std::process::exit(1)
    });
    let m = read_off(Path::new(&args[3])).unwrap_or_else(|e| {
        eprintln!("{}: {e}", args[3]);
        std::process::exit(1)
    });
    let opts = Options::new(s)
        .mobius(mobius_on)
        .literal(literal)
        .levels(levels);
    let (m, cold, warm) = levels_call(&opts, &m, exec.as_ref(), repeat).unwrap_or_else(|e| {
        eprintln!("{}: rejected: {e}", args[3]);
        std::process::exit(2)
    });
    eprintln!("subdivide_off: time_ms={cold:.3} threads={threads}");
    if let Some(w) = warm {
        eprintln!("subdivide_off: warm_ms={w:.3}");
    }
    write_off_streamed(Path::new(&args[4]), &m).expect("write");
}
