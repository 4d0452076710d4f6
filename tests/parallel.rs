//! Deterministic parallel evaluation ([`nlsubdiv::exec`]): for every scheme, linear and
//! Möbius (the guarded default, the literal rules, strict mode, the spectrum), the output
//! bits, the report and the errors of [`nlsubdiv::subdivide_with`] equal the serial
//! [`nlsubdiv::subdivide`]'s for 1, 2, 3, 7 and 16 threads, odd chunkings (more chunks than
//! threads, one chunk per output element on small levels) and chunks run in reverse order.
//! The Möbius vertex pass is one of the split passes (its vertex ranges write disjoint slot
//! ranges of the candidates); meshes with isolated vertices, ears, fallbacks and stars the
//! fold guard re-evaluates are among the cases.
#![allow(
    clippy::indexing_slicing,
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic
)]

mod common;

use common::*;
use nlsubdiv::exec::{Chunk, Executor, Serial, MAX_CHUNKS};
use nlsubdiv::scheme::{Options, Scheme, Tags, VertexWeights};
use nlsubdiv::{Report, Result, Status};

/// `threads` scoped std threads over `chunks` chunks per pass (every pass split, however
/// small), optionally each group in reverse order.
struct Pool {
    threads: usize,
    chunks: usize,
    reverse: bool,
}

impl Executor for Pool {
    fn chunks(&self, _len: usize) -> usize {
        self.chunks
    }

    fn run(&self, chunks: &mut [Chunk<'_>], task: &(dyn Fn(&mut Chunk<'_>) + Sync)) {
        let per = chunks.len().div_ceil(self.threads).max(1);
        let rev = self.reverse;
        std::thread::scope(|s| {
            for g in chunks.chunks_mut(per) {
                s.spawn(move || {
                    if rev {
                        g.iter_mut().rev().for_each(task);
                    } else {
                        g.iter_mut().for_each(task);
                    }
                });
            }
        });
    }
}

/// The executors every case runs with: (threads, chunks per pass, reverse).
const POOLS: [(usize, usize, bool); 9] = [
    (1, 1, false),
    (2, 2, false),
    (3, 3, false),
    (7, 7, false),
    (16, 16, false),
    (2, 5, false),
    (3, 13, true),
    (16, MAX_CHUNKS, false),
    (4, 1000, true),
];

fn outcome(m: &OwnedMesh, opts: &Options, exec: &dyn Executor) -> Result<(u64, Report)> {
    run_with(m, opts, exec).map(|(o, r)| (hash(&o), r))
}

/// Every executor gives the serial run's outcome; returns whether it succeeded.
fn same_everywhere(m: &OwnedMesh, opts: &Options, what: &str) -> bool {
    let serial = outcome(m, opts, &Serial);
    let public = run(m, opts).map(|(o, r)| (hash(&o), r));
    assert_eq!(serial, public, "{what}: Serial differs from subdivide");
    for (threads, chunks, reverse) in POOLS {
        let pool = Pool {
            threads,
            chunks,
            reverse,
        };
        assert_eq!(
            outcome(m, opts, &pool),
            serial,
            "{what}: {threads} threads, {chunks} chunks, reverse {reverse}"
        );
    }
    serial.is_ok()
}

fn meshes() -> Vec<(&'static str, OwnedMesh)> {
    vec![
        ("cube", cube()),
        ("quad grid", jitter(&quad_grid(5, 4), 0.05, 1)),
        ("quad torus", quad_torus(6, 5, 2.0, 0.7)),
        ("tri grid", jitter(&tri_grid(4, 5), 0.05, 2)),
        ("tri torus", tri_torus(6, 5)),
        ("icosahedron", icosahedron()),
        ("prism", prism(5)),
        ("fan", fan(7)),
        ("renumbered torus", renumbered(&tri_torus(5, 4), 3)),
    ]
}

#[test]
fn linear_every_scheme_every_chunking() {
    let mut ok = 0;
    for (name, m) in meshes() {
        for s in Scheme::ALL {
            for levels in [1, 3] {
                let opts = Options::new(s).levels(levels);
                ok += same_everywhere(&m, &opts, &format!("{name} {s:?} linear {levels}")) as u32;
            }
        }
    }
    assert!(ok > 60, "only {ok} cases succeeded");
}

#[test]
fn mobius_every_scheme_every_chunking() {
    let mut ok = 0;
    for (name, m) in meshes() {
        for s in Scheme::ALL {
            let base = Options::new(s).mobius(true).levels(2);
            let cases = [
                ("guarded", base),
                ("literal", base.literal(true)),
                ("strict", base.strict(true)),
                ("spectrum", base.spectrum(0.5)),
            ];
            for (mode, opts) in cases {
                ok += same_everywhere(&m, &opts, &format!("{name} {s:?} Möbius {mode}")) as u32;
            }
        }
    }
    assert!(ok > 60, "only {ok} cases succeeded");
}

/// Per-vertex spectrum weights ([`nlsubdiv::subdivide_weighted`]): mixed weights (and
/// uniform ones, which run one step alone), with and without tags, give the serial bits,
/// report and errors for every executor.
#[test]
fn weighted_spectrum_every_scheme_every_chunking() {
    let outcome_w = |m: &OwnedMesh, o: &Options, t: &Tags<'_>, w: &[f64], x: &dyn Executor| {
        run_weighted(m, o, t, Some(VertexWeights::Mobius(w)), x).map(|(o, r)| (hash(&o), r))
    };
    let mut ok = 0;
    for (name, m) in meshes() {
        let n = m.positions.len();
        let mut r = Lcg(17);
        let mixed: Vec<f64> = (0..n).map(|_| 0.5 * (r.next() + 1.0)).collect();
        let ramp: Vec<f64> = (0..n).map(|i| (i % 3) as f64 * 0.5).collect();
        let creases = [[0u32, 1u32]];
        let sharp = [10.0];
        for s in Scheme::ALL.into_iter().filter(|s| s.has_mobius_form()) {
            let tags = if s.takes_tags() && name == "quad torus" {
                Tags::new().creases(&creases, &sharp)
            } else {
                Tags::new()
            };
            let opts = Options::new(s).mobius(true).levels(2);
            for w in [&mixed, &ramp] {
                let serial = outcome_w(&m, &opts, &tags, w, &Serial);
                for (threads, chunks, reverse) in POOLS {
                    let pool = Pool {
                        threads,
                        chunks,
                        reverse,
                    };
                    assert_eq!(
                        outcome_w(&m, &opts, &tags, w, &pool),
                        serial,
                        "{name} {s:?}: {threads} threads, {chunks} chunks, reverse {reverse}"
                    );
                }
                ok += u32::from(serial.is_ok());
            }
        }
    }
    assert!(ok > 60, "only {ok} cases succeeded");
}

/// Errors raised inside a pass: the serial run's error (status and element) for every
/// chunking. Huge coordinates overflow (NumericalFailure at the first non-finite output
/// vertex); coincident points make the spherelike circles degenerate; strict Möbius mode
/// refuses the first fallback.
#[test]
fn errors_equal_the_serial_ones() {
    let huge = quad_grid(6, 6).map_positions(|p| [p[0] * 1e307, p[1] * 1e307, p[2]]);
    for s in [Scheme::CatmullClark, Scheme::Kobbelt, Scheme::DooSabin] {
        let opts = Options::new(s).levels(1);
        same_everywhere(&huge, &opts, &format!("huge {s:?}"));
    }
    let e = run(&huge, &Options::new(Scheme::CatmullClark)).unwrap_err();
    assert_eq!(e.status, Status::NumericalFailure);
    // Two coincident neighbours of a grid.
    let mut flat = quad_grid(6, 6);
    flat.positions[30] = flat.positions[31];
    let opts = Options::new(Scheme::Spherelike).levels(1);
    assert!(!same_everywhere(&flat, &opts, "spherelike coincident"));
    for s in [Scheme::CatmullClark, Scheme::Loop, Scheme::DooSabin] {
        let m = if s == Scheme::Loop {
            let mut t = tri_grid(5, 5);
            t.positions[14] = t.positions[8];
            t
        } else {
            flat.clone()
        };
        let opts = Options::new(s).mobius(true).strict(true).levels(1);
        same_everywhere(&m, &opts, &format!("strict {s:?} coincident"));
        let opts = Options::new(s).mobius(true).levels(2);
        same_everywhere(&m, &opts, &format!("fallbacks {s:?} coincident"));
    }
}

/// A larger mesh, so the std layer's default split (chunks of at least 2048 points, one
/// per thread) is exercised.
#[test]
fn large_levels_every_chunking() {
    let m = jitter(&quad_torus(24, 20, 2.0, 0.7), 0.02, 5);
    for s in [
        Scheme::CatmullClark,
        Scheme::DooSabin,
        Scheme::Kobbelt,
        Scheme::Spherelike,
    ] {
        assert!(same_everywhere(
            &m,
            &Options::new(s).levels(3),
            &format!("{s:?}")
        ));
    }
    for s in [Scheme::CatmullClark, Scheme::DooSabin] {
        let opts = Options::new(s).mobius(true).levels(2);
        assert!(same_everywhere(&m, &opts, &format!("Möbius {s:?}")));
    }
}

/// `m` with isolated vertices (no face) at the front, in the middle and at the end of the
/// vertex order: a vertex range then owns no candidate slot, or its slots start after
/// isolated vertices.
fn with_isolated(m: &OwnedMesh) -> OwnedMesh {
    let mid = (m.positions.len() / 2) as u32;
    let mut positions = vec![[9.0, 9.0, 9.0]];
    for (i, p) in m.positions.iter().enumerate() {
        if i as u32 == mid {
            positions.push([-9.0, 9.0, 9.0]);
        }
        positions.push(*p);
    }
    positions.push([9.0, -9.0, 9.0]);
    let indices = m
        .indices
        .iter()
        .map(|&v| v + 1 + u32::from(v >= mid))
        .collect();
    OwnedMesh {
        positions,
        offsets: m.offsets.clone(),
        indices,
    }
}

/// The Möbius vertex pass on vertex ranges that own no star, or whose stars' candidates
/// start after isolated vertices; with ears (grid corners) and degenerate stars (fallbacks).
#[test]
fn mobius_vertex_ranges_around_isolated_vertices() {
    let mut flat = quad_grid(6, 6);
    flat.positions[30] = flat.positions[31];
    let meshes = [
        (
            "quad grid",
            with_isolated(&jitter(&quad_grid(5, 4), 0.05, 1)),
        ),
        ("tri grid", with_isolated(&jitter(&tri_grid(4, 5), 0.05, 2))),
        ("fan", with_isolated(&fan(7))),
        ("coincident", with_isolated(&flat)),
    ];
    let mut ok = 0;
    let mut fallbacks = 0;
    for (name, m) in &meshes {
        for s in Scheme::ALL {
            if !s.has_mobius_form() {
                continue;
            }
            for (mode, opts) in [
                ("guarded", Options::new(s).mobius(true).levels(2)),
                ("literal", Options::new(s).mobius(true).literal(true)),
                ("strict", Options::new(s).mobius(true).strict(true)),
            ] {
                let what = format!("{name} {s:?} Möbius {mode}");
                if same_everywhere(m, &opts, &what) {
                    ok += 1;
                    fallbacks += run(m, &opts).unwrap().1.fallbacks;
                }
            }
        }
    }
    assert!(ok > 40, "only {ok} cases succeeded");
    assert!(fallbacks > 0, "no case had a fallback");
}

/// Shared meshes on which the fold guard re-evaluates stars (`tests/mesh_fold_guard.rs`):
/// the guarded counts and firsts and the output are the serial run's for every chunking (the
/// re-evaluation and the sphericity raise are split into vertex ranges too, and Kobbelt's
/// raise with its quads' diagonals; Doo–Sabin's derived topology in ranges); in strict mode,
/// the serial run's refusal.
#[test]
fn guarded_meshes_every_chunking() {
    let test = "parallel::guarded_meshes_every_chunking";
    let Some(dir) = shared_meshes(test) else {
        return;
    };
    for (s, name) in [
        (Scheme::ModifiedButterfly, "pawn_tri"),
        (Scheme::CatmullClark, "spot_quad"),
        (Scheme::Loop, "bunny"),
        (Scheme::Kobbelt, "spot_quad"),
        (Scheme::DooSabin, "spot_quad"),
    ] {
        let path = dir.join(format!("{name}.off"));
        let Ok(m) = read_off(&path) else {
            skip(
                test,
                &format!("{} not readable; not checked", path.display()),
            );
            continue;
        };
        let opts = Options::new(s).mobius(true);
        let (_, r) = run(&m, &opts).unwrap();
        assert!(r.guarded > 0, "{s:?} {name}: the guard changes nothing");
        assert!(same_everywhere(&m, &opts, &format!("{name} {s:?}")));
        let strict = opts.strict(true);
        assert!(!same_everywhere(
            &m,
            &strict,
            &format!("{name} {s:?} strict")
        ));
    }
}

/// Records the element count of every pass an executor is handed.
struct Census {
    chunks: usize,
    passes: std::sync::Mutex<Vec<usize>>,
}

impl Executor for Census {
    fn chunks(&self, _len: usize) -> usize {
        self.chunks
    }

    fn run(&self, chunks: &mut [Chunk<'_>], task: &(dyn Fn(&mut Chunk<'_>) + Sync)) {
        let n = chunks.iter().map(|c| c.len()).sum();
        self.passes.lock().unwrap().push(n);
        chunks.iter_mut().for_each(task);
    }
}

/// The Möbius vertex pass itself is split: a literal Loop step on a closed mesh hands the
/// executor the connectivity pass over the `F` parent faces and the check of its `12 F`
/// indices, the fills of the `H` edge and `H` face candidates and of the `V` trusts and
/// radii, two passes over the `V` vertices (the vertex pass and the completion of the vertex
/// points), then the `E` edge blends and the finiteness check; Catmull–Clark also the face
/// blends.
#[test]
fn the_vertex_pass_is_split() {
    let m = jitter(&tri_torus(6, 5), 0.03, 4);
    let (nv, nf) = (m.positions.len(), m.num_faces());
    let (nh, ne) = (m.indices.len(), m.indices.len() / 2);
    let start = |nv| vec![nf, 12 * nf, nh, nh, nv, nv, nv, nv];
    for (s, passes) in [
        (Scheme::Loop, [start(nv), vec![ne, nv + ne]].concat()),
        (
            Scheme::CatmullClark,
            [start(nv), vec![nf, ne, nv + ne + nf]].concat(),
        ),
    ] {
        let census = Census {
            chunks: 3,
            passes: std::sync::Mutex::new(Vec::new()),
        };
        let opts = Options::new(s).mobius(true).literal(true);
        run_with(&m, &opts, &census).unwrap();
        // A build with one chunk per pass (NLSUBDIV_MAX_CHUNKS=1) never calls the executor.
        let passes = if MAX_CHUNKS == 1 { vec![] } else { passes };
        assert_eq!(census.passes.into_inner().unwrap(), passes, "{s:?}");
    }
}

// ---------------------------------------------------------------- differential space

use nlsubdiv::differential::{DifferentialOptions, DifferentialReport, Stencil};

type DiffOutcome =
    std::result::Result<(u64, DifferentialReport), (nlsubdiv::Error, DifferentialReport)>;

fn diff_outcome(
    m: &OwnedMesh,
    opts: &DifferentialOptions<'_>,
    exec: Option<&dyn Executor>,
) -> DiffOutcome {
    differential_subdivide_with(m, opts, exec).map(|(o, r)| (hash(&o), r))
}

/// Every executor gives the serial differential run's output hash, report and error;
/// returns whether it succeeded.
fn diff_same_everywhere(m: &OwnedMesh, opts: &DifferentialOptions<'_>, what: &str) -> bool {
    let public = diff_outcome(m, opts, None);
    let serial = diff_outcome(m, opts, Some(&Serial));
    assert_eq!(serial, public, "{what}: Serial differs from subdivide");
    for (threads, chunks, reverse) in POOLS {
        let pool = Pool {
            threads,
            chunks,
            reverse,
        };
        assert_eq!(
            diff_outcome(m, opts, Some(&pool)),
            serial,
            "{what}: {threads} threads, {chunks} chunks, reverse {reverse}"
        );
    }
    serial.is_ok()
}

/// Every differential stencil (Loop, Modified Butterfly, DirMag with either for one and
/// for every level), closed and open meshes, 1 and 2 levels (3 in the next test), the §4.4
/// edits: the output bits
/// and the report of `differential::subdivide_with` equal the serial run's for 1, 2, 3, 7
/// and 16 threads and 5, 13, 64 and 1000 chunks per pass.
#[test]
fn differential_every_stencil_every_chunking() {
    let meshes: Vec<(&str, OwnedMesh)> = vec![
        ("icosahedron", icosahedron()),
        ("tri grid", jitter(&tri_grid(4, 5), 0.05, 2)),
        ("fan", fan(7)),
        (
            "renumbered torus",
            renumbered(&jitter(&tri_torus(5, 4), 0.03, 7), 3),
        ),
    ];
    let mut ok = 0;
    for (name, m) in &meshes {
        for stencil in [Stencil::Loop, Stencil::ModifiedButterfly] {
            for (dirmag, levels) in [(0, 1), (0, 2), (1, 2), (2, 2)] {
                let opts = DifferentialOptions {
                    stencil,
                    levels,
                    dirmag_levels: dirmag,
                    ..Default::default()
                };
                let what = format!("{name} {stencil:?} dirmag {dirmag} levels {levels}");
                ok += diff_same_everywhere(m, &opts, &what) as u32;
            }
        }
        // §4.4 edits: a curvature scale and a turned normal (a closed and an open mesh).
        if !matches!(*name, "icosahedron" | "tri grid") {
            continue;
        }
        let n = m.positions.len();
        let scale: Vec<f64> = (0..n).map(|i| 1.0 + 0.1 * (i % 3) as f64).collect();
        let mut normals = vec![[0.0; 3]; n];
        normals[0] = [0.3, 0.2, 1.0];
        for stencil in [Stencil::Loop, Stencil::ModifiedButterfly] {
            let mut opts = DifferentialOptions {
                stencil,
                levels: 2,
                ..Default::default()
            };
            opts.curvature_scale = Some(&scale);
            ok += diff_same_everywhere(m, &opts, &format!("{name} {stencil:?} scaled")) as u32;
            opts.curvature_scale = None;
            opts.normals = Some(&normals);
            ok += diff_same_everywhere(m, &opts, &format!("{name} {stencil:?} normal")) as u32;
        }
    }
    assert!(ok > 30, "only {ok} cases succeeded");
}

/// Errors and the report with them: the iteration cap (`NotConverged`, the report of the
/// last iterate) and overflow (`NumericalFailure`) are the serial run's for every chunking.
#[test]
fn differential_errors_equal_the_serial_ones() {
    let m = jitter(&tri_torus(8, 6), 0.03, 9);
    for stencil in [Stencil::Loop, Stencil::ModifiedButterfly] {
        let mut opts = DifferentialOptions {
            stencil,
            levels: 3,
            ..Default::default()
        };
        opts.solve.max_iterations = 2;
        assert!(!diff_same_everywhere(
            &m,
            &opts,
            &format!("{stencil:?} capped")
        ));
        let e = differential_subdivide(&m, &opts).unwrap_err();
        assert_eq!(e.0.status, Status::NotConverged);
    }
    let huge = tri_grid(5, 5).map_positions(|p| [p[0] * 1e307, p[1] * 1e307, p[2]]);
    let opts = DifferentialOptions {
        levels: 2,
        ..Default::default()
    };
    assert!(!diff_same_everywhere(&huge, &opts, "huge"));
}

/// A mesh large enough for the std layer's default split (chunks of at least 2048 rows).
#[test]
fn differential_large_every_chunking() {
    let m = jitter(&tri_torus(16, 12), 0.02, 11);
    for stencil in [Stencil::Loop, Stencil::ModifiedButterfly] {
        let opts = DifferentialOptions {
            stencil,
            levels: 3,
            dirmag_levels: 1,
            ..Default::default()
        };
        assert!(diff_same_everywhere(
            &m,
            &opts,
            &format!("large {stencil:?}")
        ));
    }
}
