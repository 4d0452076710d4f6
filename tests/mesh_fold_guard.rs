//! The fold guard of the Möbius schemes (the default of `Options::mobius`; `docs/folds.md`):
//! fewer folds than the paper's literal rules on real meshes, sphere reproduction and
//! Möbius equivariance where it distrusts nothing, a Möbius-invariant choice of what it
//! changes, its report and its strict refusal.
//!
//! A *folded edge* is an interior edge whose two faces have Newell normals (area vectors)
//! more than 90° apart: computed here from the output alone, independently of the library's
//! own fold measures.
#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::indexing_slicing,
    clippy::panic
)]

mod common;

use std::collections::HashMap;

use common::*;
use nlsubdiv::mobius::MobiusMap;
use nlsubdiv::scheme::{Options, Report, Scheme};
use nlsubdiv::{Point, Status};

fn cross(a: Point, b: Point) -> Point {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: Point, b: Point) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The folded interior edges of `m` (module docs).
fn folded_edges(m: &OwnedMesh) -> usize {
    let faces = m.faces();
    let normals: Vec<Point> = faces
        .iter()
        .map(|f| {
            let mut n = [0.0; 3];
            for i in 0..f.len() {
                let c = cross(
                    m.positions[f[i] as usize],
                    m.positions[f[(i + 1) % f.len()] as usize],
                );
                n = [n[0] + c[0], n[1] + c[1], n[2] + c[2]];
            }
            n
        })
        .collect();
    let mut half: HashMap<(u32, u32), usize> = HashMap::new();
    for (k, f) in faces.iter().enumerate() {
        for i in 0..f.len() {
            half.insert((f[i], f[(i + 1) % f.len()]), k);
        }
    }
    half.iter()
        .filter(|(&(a, b), &fa)| {
            a < b
                && half
                    .get(&(b, a))
                    .is_some_and(|&fb| dot(normals[fa], normals[fb]) < 0.0)
        })
        .count()
}

/// `levels` chained one-level steps (linear, guarded Möbius or literal Möbius), the fold
/// count after each level from 1, and the report of each step.
fn chain(s: Scheme, m: &OwnedMesh, levels: usize, opts: Options) -> (Vec<usize>, Vec<Report>) {
    let mut cur = m.clone();
    let (mut folds, mut reports) = (Vec::new(), Vec::new());
    for _ in 0..levels {
        let (next, r) = run(&cur, &opts).unwrap_or_else(|e| panic!("{s:?}: {e}"));
        folds.push(folded_edges(&next));
        reports.push(r);
        cur = next;
    }
    (folds, reports)
}

/// The rows of the fold study (`docs/folds.md`).
const ROWS: [(Scheme, &str); 10] = [
    (Scheme::Loop, "rocker_arm"),
    (Scheme::Loop, "bunny"),
    (Scheme::Loop, "fertility"),
    (Scheme::Loop, "fandisk"),
    (Scheme::ModifiedButterfly, "bunny"),
    (Scheme::ModifiedButterfly, "fertility"),
    (Scheme::ModifiedButterfly, "pawn_tri"),
    (Scheme::CatmullClark, "horse_quad"),
    (Scheme::CatmullClark, "spot_quad"),
    (Scheme::CatmullClark, "helmet_quad"),
];

/// Rows where the guard does not reach the linear scheme's fold count at 2 or 3 levels: on
/// such a row the test asserts only the weaker property that the guard folds no more than
/// the paper's literal rules, and prints the counts. Every row of the study meets the linear
/// count since the output audit (`docs/folds.md`, section 8), so the list is empty; it stays
/// so that a row can be listed, visibly, if a change makes it regress.
const OPEN: [(Scheme, &str); 0] = [];

#[test]
fn the_default_folds_no_more_than_the_linear_scheme() {
    let Some(dir) =
        shared_meshes("mesh_fold_guard::the_default_folds_no_more_than_the_linear_scheme")
    else {
        return;
    };
    let mut failures = Vec::new();
    for (s, name) in ROWS {
        let path = dir.join(format!("{name}.off"));
        let Ok(m) = read_off(&path) else {
            skip(
                "mesh_fold_guard::the_default_folds_no_more_than_the_linear_scheme",
                &format!(
                    "{} not readable; row {s:?} {name} not checked",
                    path.display()
                ),
            );
            continue;
        };
        let (lin, _) = chain(s, &m, 3, Options::new(s));
        let (def, _) = chain(s, &m, 3, Options::new(s).mobius(true));
        let open = OPEN.contains(&(s, name));
        let lit = if open {
            Some(chain(s, &m, 3, Options::new(s).mobius(true).literal(true)).0)
        } else {
            None
        };
        for level in [2usize, 3] {
            let (d, l) = (def[level - 1], lin[level - 1]);
            println!(
                "{s:?} {name} level {level}: folded edges default {d}, linear {l}{}",
                lit.as_ref()
                    .map(|x| format!(", literal {}", x[level - 1]))
                    .unwrap_or_default()
            );
            match &lit {
                None if d > l => failures.push(format!("{s:?} {name} L{level}: {d} > linear {l}")),
                Some(x) if d > x[level - 1] => failures.push(format!(
                    "{s:?} {name} L{level} (open row): {d} > literal {}",
                    x[level - 1]
                )),
                Some(_) if d <= l => {
                    println!("  open row {s:?} {name} now meets the linear count at L{level}")
                }
                _ => {}
            }
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

/// Meshes beyond the study where the Möbius points of distrusted stars, even in the fully
/// interpolated frame, folded more than the linear scheme until the blend toward the linear
/// rule (`docs/folds.md` section 8, step 7): epcot's valence-12 "crown" stars, cow's thin
/// triangles, camelhead's open boundary, polycastle_quad's 90° blocks; for Butterfly, cow
/// and camelhead, which needed the blend to reach two rings; Kobbelt on the quad meshes, where
/// the paper's rules fold untagged (its guard has no re-evaluation: the blend toward the
/// linear rule is its whole fallback), and Doo–Sabin, the simplest scheme and Akleman's
/// operators likewise (dual truncation re-evaluates its distrusted stars in `m_τ` first, as
/// Catmull–Clark does, and the dual's blend reaches three rings; `docs/folds.md` section 12);
/// Doo–Sabin on helmet_quad, which folded at level 3 next to the corners of its open
/// boundary until the audit of the boundary stars (`docs/folds.md` section 10).
/// Asserted at every level from 1, where these folds started.
const BEYOND: [(Scheme, &str); 32] = [
    (Scheme::Loop, "epcot"),
    (Scheme::Loop, "cow"),
    (Scheme::Loop, "camelhead"),
    (Scheme::CatmullClark, "polycastle_quad"),
    (Scheme::ModifiedButterfly, "cow"),
    (Scheme::ModifiedButterfly, "camelhead"),
    (Scheme::Kobbelt, "horse_quad"),
    (Scheme::Kobbelt, "spot_quad"),
    (Scheme::Kobbelt, "helmet_quad"),
    (Scheme::Kobbelt, "polycastle_quad"),
    (Scheme::DooSabin, "horse_quad"),
    (Scheme::DooSabin, "spot_quad"),
    (Scheme::DooSabin, "yas_island_quad"),
    (Scheme::DooSabin, "helmet_quad"),
    (Scheme::Simplest, "horse_quad"),
    (Scheme::Simplest, "spot_quad"),
    (Scheme::Simplest, "helmet_quad"),
    (Scheme::Simplest, "vase_quad"),
    (Scheme::VertexInsertion, "horse_quad"),
    (Scheme::VertexInsertion, "helmet_quad"),
    (Scheme::VertexInsertion, "bunny"),
    (Scheme::VertexInsertion, "spot_quad"),
    (Scheme::DualTruncation, "horse_quad"),
    (Scheme::DualTruncation, "spot_quad"),
    (Scheme::DualTruncation, "helmet_quad"),
    (Scheme::DualTruncation, "bunny"),
    (Scheme::DualTruncation, "cow"),
    (Scheme::Dual, "horse_quad"),
    (Scheme::Dual, "bunny"),
    (Scheme::Dual, "camelhead"),
    (Scheme::Dual, "helmet_quad"),
    (Scheme::Dual, "cow"),
];

#[test]
fn the_default_folds_no_more_than_the_linear_scheme_beyond_the_study() {
    const TEST: &str =
        "mesh_fold_guard::the_default_folds_no_more_than_the_linear_scheme_beyond_the_study";
    let Some(dir) = shared_meshes(TEST) else {
        return;
    };
    let mut failures = Vec::new();
    for (s, name) in BEYOND {
        let path = dir.join(format!("{name}.off"));
        let Ok(m) = read_off(&path) else {
            skip(
                TEST,
                &format!("{} not readable; row {s:?} {name}", path.display()),
            );
            continue;
        };
        let (lin, _) = chain(s, &m, 3, Options::new(s));
        let (def, reports) = chain(s, &m, 3, Options::new(s).mobius(true));
        // The rows are only a test of the fallback if the guard acts on them.
        assert!(reports[0].guarded > 0, "{s:?} {name}: nothing guarded");
        for level in 1..=3 {
            let (d, l) = (def[level - 1], lin[level - 1]);
            println!("{s:?} {name} level {level}: folded edges default {d}, linear {l}");
            if d > l {
                failures.push(format!("{s:?} {name} L{level}: {d} > linear {l}"));
            }
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

/// A Möbius map that keeps the mesh bounded: an inversion in a sphere centred 1.65–2 mesh
/// radii from the centroid, then a rotation and a translation (deterministic).
fn mobius_map(m: &OwnedMesh, seed: u64) -> MobiusMap {
    let mut rng = Lcg(seed);
    let n = m.positions.len() as f64;
    let mut c = [0.0; 3];
    for p in &m.positions {
        c = [c[0] + p[0] / n, c[1] + p[1] / n, c[2] + p[2] / n];
    }
    let r = m
        .positions
        .iter()
        .map(|p| {
            dot(
                [p[0] - c[0], p[1] - c[1], p[2] - c[2]],
                [p[0] - c[0], p[1] - c[1], p[2] - c[2]],
            )
            .sqrt()
        })
        .fold(0.0, f64::max);
    let mut dir = [rng.next(), rng.next(), rng.next()];
    let len = dot(dir, dir).sqrt();
    dir = [dir[0] / len, dir[1] / len, dir[2] / len];
    let t = r * (1.65 + 0.35 * rng.next().abs());
    let centre = [c[0] + t * dir[0], c[1] + t * dir[1], c[2] + t * dir[2]];
    MobiusMap::inversion(centre, r * (1.0 + 0.5 * rng.next().abs()))
        .compose(&MobiusMap::rotation(dir, 3.0 * rng.next()))
        .compose(&MobiusMap::translation([
            rng.next(),
            rng.next(),
            rng.next(),
        ]))
}

fn diameter(m: &OwnedMesh) -> f64 {
    let (mut lo, mut hi) = ([f64::MAX; 3], [f64::MIN; 3]);
    for p in &m.positions {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let d = [hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]];
    dot(d, d).sqrt()
}

/// What the guard changes is Möbius-invariant: on real meshes where it distrusts stars, the
/// number of output vertices it changes, and the first of them, are the same on three
/// Möbius images of the mesh (with the same connectivity, output vertex `k` of the image is
/// the image's counterpart of output vertex `k`).
#[test]
fn what_the_guard_changes_is_the_same_on_every_mobius_image() {
    let test = "mesh_fold_guard::what_the_guard_changes_is_the_same_on_every_mobius_image";
    let Some(dir) = shared_meshes(test) else {
        return;
    };
    let rows = [
        (Scheme::Loop, "rocker_arm"),
        (Scheme::Loop, "bunny"),
        (Scheme::ModifiedButterfly, "pawn_tri"),
        (Scheme::CatmullClark, "helmet_quad"),
        (Scheme::CatmullClark, "spot_quad"),
        (Scheme::Kobbelt, "helmet_quad"),
        (Scheme::Kobbelt, "spot_quad"),
        (Scheme::DooSabin, "horse_quad"),
        (Scheme::DooSabin, "spot_quad"),
        // The audit of its boundary stars, in their frames, distrusts helmet_quad's corners.
        (Scheme::DooSabin, "helmet_quad"),
        (Scheme::Simplest, "spot_quad"),
        (Scheme::Simplest, "helmet_quad"),
    ];
    for (s, name) in rows {
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
        for seed in 1..=3 {
            let f = mobius_map(&m, seed);
            let image = m.map_positions(|p| f.apply(p).unwrap());
            let (_, ri) = run(&image, &opts).unwrap();
            assert_eq!(
                (ri.guarded, ri.first_guarded),
                (r.guarded, r.first_guarded),
                "{s:?} {name}, map {seed}"
            );
        }
    }
}

/// On the shared `sphere_*` meshes the default mode keeps the paper's Möbius equivariance
/// within the bound the paper's rules meet (`tests/mesh_mobius.rs`, 1e-9 of the diameter).
#[test]
fn the_default_is_mobius_equivariant_on_the_sphere_meshes() {
    let test = "mesh_fold_guard::the_default_is_mobius_equivariant_on_the_sphere_meshes";
    let Some(dir) = shared_meshes(test) else {
        return;
    };
    let mut runs = 0;
    for path in off_files(&dir) {
        let name = path.file_name().unwrap().to_string_lossy().to_string();
        if !name.starts_with("sphere_") {
            continue;
        }
        let m = read_off(&path).unwrap();
        for s in Scheme::ALL {
            let opts = Options::new(s).mobius(true);
            let Ok((b, _)) = run(&m, &opts) else {
                continue; // the scheme refuses the mesh (face kinds) or has no Möbius form
            };
            let f = mobius_map(&m, 7);
            let (a, _) = run(&m.map_positions(|p| f.apply(p).unwrap()), &opts).unwrap();
            let scale = diameter(&a);
            let err = a
                .positions
                .iter()
                .zip(&b.positions)
                .map(|(&p, &q)| {
                    let q = f.apply(q).unwrap();
                    let d = [p[0] - q[0], p[1] - q[1], p[2] - q[2]];
                    dot(d, d).sqrt() / scale
                })
                .fold(0.0, f64::max);
            assert!(err < 1e-9, "{name}, {s:?}: equivariance error {err:e}");
            runs += 1;
        }
    }
    assert!(runs > 0, "no sphere_* mesh");
}

/// The report counts what the guard changes at the level it first did; `strict` refuses the
/// first of them with `FallbackInStrictMode` naming it; `literal` changes nothing, so it is
/// neither counted nor refused.
#[test]
fn the_guard_is_reported_and_refused_in_strict_mode() {
    let test = "mesh_fold_guard::the_guard_is_reported_and_refused_in_strict_mode";
    let Some(dir) = shared_meshes(test) else {
        return;
    };
    let path = dir.join("rocker_arm.off");
    let Ok(m) = read_off(&path) else {
        skip(
            test,
            &format!("{} not readable; not checked", path.display()),
        );
        return;
    };
    let s = Scheme::Loop;
    let opts = Options::new(s).mobius(true);
    let (_, r1) = run(&m, &opts).unwrap();
    assert!(r1.guarded > 0 && r1.first_guarded_level == 1);
    assert!((r1.first_guarded as usize) < m.positions.len() + 3 * m.num_faces());
    let (_, r2) = run(&m, &opts.levels(2)).unwrap();
    assert_eq!(r2.first_guarded_level, 1);
    assert_eq!(r2.first_guarded, r1.first_guarded);
    assert!(r2.guarded > r1.guarded);
    let e = run(&m, &opts.strict(true)).unwrap_err();
    assert_eq!(
        (e.status, e.element),
        (Status::FallbackInStrictMode, r1.first_guarded)
    );
    let lit = opts.literal(true);
    let (_, rl) = run(&m, &lit.levels(2)).unwrap();
    assert_eq!(
        (rl.guarded, rl.first_guarded, rl.first_guarded_level),
        (0, u32::MAX, 0)
    );
    assert!(run(&m, &lit.strict(true)).is_ok());
}

/// Where the guard distrusts nothing (fandisk, the regular and spherical meshes of the fold
/// study), the default output is the literal one bit for bit.
#[test]
fn where_nothing_is_distrusted_the_default_is_the_literal_rule() {
    let mut meshes = vec![
        ("icosahedron".to_string(), icosahedron()),
        ("tri grid".to_string(), tri_grid(8, 8)),
        ("quad torus".to_string(), quad_torus(12, 8, 2.0, 0.7)),
    ];
    if let Some(dir) = shared_meshes_partly(
        "mesh_fold_guard::where_nothing_is_distrusted_the_default_is_the_literal_rule",
        "fandisk",
    ) {
        if let Ok(m) = read_off(&dir.join("fandisk.off")) {
            meshes.push(("fandisk".to_string(), m));
        }
    }
    let mut compared = 0;
    for (name, m) in &meshes {
        for s in [
            Scheme::Loop,
            Scheme::ModifiedButterfly,
            Scheme::CatmullClark,
        ] {
            let opts = Options::new(s).mobius(true).levels(2);
            let Ok((d, r)) = run(m, &opts) else {
                continue;
            };
            let (l, _) = run(m, &opts.literal(true)).unwrap();
            if r.guarded == 0 {
                assert_eq!(d.positions, l.positions, "{name} {s:?}");
                compared += 1;
            } else {
                println!("{name} {s:?}: {} elements guarded", r.guarded);
            }
        }
    }
    assert!(compared >= 5, "{compared} comparisons");
}

/// The Möbius–linear spectrum (`Options::spectrum`, seed 000 §7.2): weight 0 is the linear
/// result and weight 1 the Möbius one (guarded or literal), bit for bit; one level at weight
/// `w` is `w · Möbius + (1 − w) · linear` of the same input; the result moves continuously
/// toward either end; NaN and weights outside `[0, 1]` are refused.
#[test]
fn the_spectrum_runs_from_the_linear_to_the_mobius_result() {
    let meshes = [
        (Scheme::Loop, jitter(&tri_torus(12, 8), 0.08, 21)),
        (
            Scheme::ModifiedButterfly,
            jitter(&tri_torus(12, 8), 0.08, 22),
        ),
        (
            Scheme::CatmullClark,
            jitter(&quad_torus(12, 8, 2.0, 0.7), 0.08, 23),
        ),
    ];
    for (s, m) in &meshes {
        let s = *s;
        let mob = Options::new(s).mobius(true).levels(2);
        let (lin, _) = run(m, &Options::new(s).levels(2)).unwrap();
        let (def, _) = run(m, &mob).unwrap();
        let (lit, _) = run(m, &mob.literal(true)).unwrap();
        assert_eq!(
            run(m, &mob.spectrum(0.0)).unwrap().0.positions,
            lin.positions,
            "{s:?} w=0"
        );
        assert_eq!(
            run(m, &mob.spectrum(1.0)).unwrap().0.positions,
            def.positions,
            "{s:?} w=1"
        );
        assert_eq!(
            run(m, &mob.literal(true).spectrum(1.0))
                .unwrap()
                .0
                .positions,
            lit.positions,
            "{s:?} literal w=1"
        );
        // One level at w = 0.25: the blend of the two one-level results.
        let one = Options::new(s).mobius(true);
        let (l1, _) = run(m, &Options::new(s)).unwrap();
        let (m1, _) = run(m, &one).unwrap();
        let (b1, _) = run(m, &one.spectrum(0.25)).unwrap();
        for ((b, p), q) in b1.positions.iter().zip(&m1.positions).zip(&l1.positions) {
            for k in 0..3 {
                let want = 0.25 * p[k] + 0.75 * q[k];
                assert!((b[k] - want).abs() <= 1e-15 * (1.0 + want.abs()), "{s:?}");
            }
        }
        // Continuity at both ends, two levels.
        let scale = diameter(&lin);
        let gap = |a: &OwnedMesh, b: &OwnedMesh| {
            a.positions
                .iter()
                .zip(&b.positions)
                .map(|(p, q)| {
                    let d = [p[0] - q[0], p[1] - q[1], p[2] - q[2]];
                    dot(d, d).sqrt() / scale
                })
                .fold(0.0, f64::max)
        };
        let near0 = run(m, &mob.spectrum(1e-9)).unwrap().0;
        let near1 = run(m, &mob.spectrum(1.0 - 1e-9)).unwrap().0;
        assert!(gap(&near0, &lin) < 1e-7, "{s:?}: {:e}", gap(&near0, &lin));
        assert!(gap(&near1, &def) < 1e-7, "{s:?}: {:e}", gap(&near1, &def));
        assert!(
            gap(&def, &lin) > 1e-6,
            "{s:?}: Möbius and linear agree on this mesh"
        );
        for w in [f64::NAN, -0.1, 1.5, f64::INFINITY] {
            let e = run(m, &mob.spectrum(w)).unwrap_err();
            assert_eq!(e.status, Status::InvalidArgument, "{s:?} w={w}");
        }
    }
}
