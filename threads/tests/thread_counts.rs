//! The same output bits, report and errors for every thread count and chunking of
//! [`Threads`]: every scheme, linear and Möbius (the fold guard's default and the paper's
//! literal rules), on a bumpy torus whose passes split into many chunks. The threads take
//! chunks as they finish others, so each run also hands the chunks out in another order.

use nlsubdiv::{plan, subdivide_with, Mesh, MeshOut, Options, Report, Scheme, Scratch};
use nlsubdiv_threads::Threads;

/// A torus of `n × m` quads (or twice as many triangles), its radius bumped by a fixed hash
/// of the vertex so that stars are irregular in shape and the fold guard has work.
fn torus(n: usize, m: usize, triangles: bool, bump: f64) -> (Vec<[f64; 3]>, Vec<u32>, Vec<u32>) {
    let mut p = Vec::new();
    for i in 0..n {
        for j in 0..m {
            let (u, v) = (
                std::f64::consts::TAU * i as f64 / n as f64,
                std::f64::consts::TAU * j as f64 / m as f64,
            );
            let h = ((i * 7919 + j * 104_729) % 1009) as f64 / 1009.0;
            let r = 0.35 + bump * (h - 0.5);
            p.push([
                (1.0 + r * v.cos()) * u.cos(),
                (1.0 + r * v.cos()) * u.sin(),
                r * v.sin(),
            ]);
        }
    }
    let id = |i: usize, j: usize| ((i % n) * m + j % m) as u32;
    let (mut offsets, mut indices) = (vec![0u32], Vec::new());
    for i in 0..n {
        for j in 0..m {
            let q = [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)];
            let faces: Vec<Vec<u32>> = if triangles {
                vec![vec![q[0], q[1], q[2]], vec![q[0], q[2], q[3]]]
            } else {
                vec![q.to_vec()]
            };
            for f in faces {
                indices.extend(f);
                offsets.push(indices.len() as u32);
            }
        }
    }
    (p, offsets, indices)
}

/// The output (positions' bits, offsets, indices) and report of one call, or its error.
type Output = Result<(Vec<[u64; 3]>, Vec<u32>, Vec<u32>, Report), nlsubdiv::Error>;

fn run(mesh: Mesh<'_>, opts: &Options, threads: &Threads) -> Output {
    let mut u32s = vec![0u32; 1 << 16];
    let pl = plan(mesh, opts, &mut u32s)?;
    let o = pl.output();
    let mut u32s = vec![0u32; pl.scratch.u32s];
    let mut points = vec![[0.0; 3]; pl.scratch.points];
    let (mut pos, mut offs, mut idx) = (
        vec![[0.0; 3]; o.vertices],
        vec![0u32; o.faces + 1],
        vec![0u32; o.indices],
    );
    let mut out = MeshOut::new(&mut pos, &mut offs, &mut idx);
    let scratch = Scratch::new(&mut u32s, &mut points);
    let report = subdivide_with(mesh, opts, scratch, &mut out, threads)?;
    let bits = pos.iter().map(|p| p.map(f64::to_bits)).collect();
    Ok((bits, offs, idx, report))
}

#[test]
fn every_thread_count_and_chunking_gives_the_same_bits() {
    let quads = torus(24, 16, false, 0.08);
    let tris = torus(16, 12, true, 0.4);
    // Small chunks, so that every pass of these small levels splits.
    let executors = [
        Threads::new(2).min_chunk(64),
        Threads::new(3).min_chunk(64),
        Threads::new(7).min_chunk(32),
        Threads::new(16).min_chunk(16),
        Threads::with_chunks(2, 5),
        Threads::with_chunks(3, 64),
        Threads::scoped(2).min_chunk(64),
        Threads::scoped(5).min_chunk(16),
    ];
    let mut split_runs = 0;
    for scheme in Scheme::ALL {
        let (p, o, i) = match scheme {
            Scheme::Loop | Scheme::ModifiedButterfly => &tris,
            _ => &quads,
        };
        let mesh = Mesh::new(p, o, i);
        let modes: &[(bool, bool)] = if scheme.has_mobius_form() {
            &[(false, false), (true, false), (true, true)]
        } else {
            &[(false, false)]
        };
        for &(mobius, literal) in modes {
            let opts = Options::new(scheme)
                .levels(2)
                .mobius(mobius)
                .literal(literal);
            let want = run(mesh, &opts, &Threads::new(1));
            assert!(want.is_ok(), "{scheme:?} {mobius} {literal}: {want:?}");
            for t in &executors {
                let got = run(mesh, &opts, t);
                assert!(
                    got == want,
                    "{scheme:?} mobius {mobius} literal {literal}, {t:?}: the output differs"
                );
                split_runs += 1;
            }
        }
    }
    assert!(split_runs > 60, "{split_runs}");
}

#[test]
fn concurrent_calls_share_the_pool_and_keep_their_bits() {
    // Several host threads subdividing at once: their passes meet in the one process-wide
    // pool (grown when a call asks for more workers), and each call's output is its own.
    let quads = torus(24, 16, false, 0.08);
    let (p, o, i) = &quads;
    let mesh = Mesh::new(p, o, i);
    let opts = Options::new(Scheme::CatmullClark).levels(2).mobius(true);
    let want = run(mesh, &opts, &Threads::new(1));
    assert!(want.is_ok(), "{want:?}");
    std::thread::scope(|s| {
        let calls: Vec<_> = [2, 4, 3, 9]
            .into_iter()
            .map(|n| s.spawn(move || (n, run(mesh, &opts, &Threads::new(n).min_chunk(32)))))
            .collect();
        for c in calls {
            let (n, got) = c.join().expect("a host thread");
            assert!(got == want, "{n} threads: the output differs");
        }
    });
}

#[test]
fn errors_are_the_same_for_every_thread_count() {
    // A non-finite position: the plan refuses it naming the vertex, whatever the threads.
    let (mut p, o, i) = torus(24, 16, false, 0.08);
    p[300][1] = f64::NAN;
    let mesh = Mesh::new(&p, &o, &i);
    let opts = Options::new(Scheme::CatmullClark).levels(2).mobius(true);
    let want = run(mesh, &opts, &Threads::new(1));
    assert!(want.is_err());
    for t in [
        Threads::new(2).min_chunk(64),
        Threads::with_chunks(3, 7),
        Threads::scoped(2).min_chunk(64),
    ] {
        assert!(run(mesh, &opts, &t) == want, "{t:?}");
    }
}
