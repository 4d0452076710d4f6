//! Seed 001 §4.3 and §3.4 tables, measured with the library's own calls:
//!
//! 1. Normalised thin-plate energy `E = ∫(κ₁² + κ₂²)/∫1` ([`thin_plate_energy`]) at levels
//!    1–3 on fertility, rocker_arm and epcot for differential-space Loop, Modified Butterfly
//!    and DirMag (Butterfly stencil, DirMag for the first 1 or 2 levels) against spatial Loop
//!    and spatial Modified Butterfly; and the distance between consecutive levels
//!    ([`level_distance`], the largest displacement of the vertices two levels share,
//!    relative to the control mesh's bounding-box diagonal).
//! 2. DirMag against plain linear subdivision of `Δ` on Platonic cages (§3.4 Case 1, Fig. 5–6):
//!    every control vertex has the same `|δ|` and normals that differ, so the ideal refined
//!    mean curvature is uniform; the measure is its spread over the result at level k.
//!
//! `cargo run --release --example differential_tables [MESH_DIR]`
#![allow(
    clippy::expect_used,
    clippy::unwrap_used,
    clippy::indexing_slicing,
    dead_code
)]

#[path = "../tests/common/mod.rs"]
mod common;

use common::*;
use nlsubdiv::differential::laplacian::{self, Laplacian};
use nlsubdiv::differential::metrics::{level_distance, thin_plate_energy, vertex_curvatures};
use nlsubdiv::differential::{DifferentialOptions, Stencil};
use nlsubdiv::scheme::Scheme;
use std::time::Instant;

const LEVELS: usize = 3;

#[derive(Clone, Copy)]
enum Method {
    Spatial(Scheme),
    Differential(Stencil, usize),
}

impl Method {
    fn name(self) -> String {
        match self {
            Method::Spatial(Scheme::Loop) => "spatial Loop".into(),
            Method::Spatial(_) => "spatial Modified Butterfly".into(),
            Method::Differential(Stencil::Loop, 0) => "differential Loop".into(),
            Method::Differential(Stencil::ModifiedButterfly, 0) => "differential Butterfly".into(),
            Method::Differential(Stencil::Loop, d) => format!("differential DirMag-Loop ({d})"),
            Method::Differential(Stencil::ModifiedButterfly, d) => {
                format!("differential DirMag ({d})")
            }
        }
    }

    /// Level `k` of `m`, and the solver iterations for differential methods.
    fn run(self, m: &OwnedMesh, k: usize) -> Result<(OwnedMesh, Option<u32>), String> {
        match self {
            Method::Spatial(s) => subdivide_n(s, m, k)
                .map(|o| (o, None))
                .map_err(|e| format!("{e}")),
            Method::Differential(stencil, dirmag_levels) => {
                let opts = DifferentialOptions {
                    stencil,
                    levels: k,
                    dirmag_levels,
                    ..Default::default()
                };
                differential_subdivide(m, &opts)
                    .map(|(o, r)| (o, Some(r.solve.iterations)))
                    .map_err(|(e, r)| format!("{e} ({:?})", r.solve))
            }
        }
    }
}

fn thin_plate(m: &OwnedMesh) -> f64 {
    with_topology(m, |t| {
        let mut s = vec![[0.0; 3]; m.positions.len()];
        thin_plate_energy(t, &mut s).unwrap()
    })
    .unwrap()
}

fn diagonal(m: &OwnedMesh) -> f64 {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in &m.positions {
        for i in 0..3 {
            lo[i] = lo[i].min(p[i]);
            hi[i] = hi[i].max(p[i]);
        }
    }
    ((hi[0] - lo[0]).powi(2) + (hi[1] - lo[1]).powi(2) + (hi[2] - lo[2]).powi(2)).sqrt()
}

fn thin_plate_table(dir: &std::path::Path) {
    let methods = [
        Method::Spatial(Scheme::Loop),
        Method::Spatial(Scheme::ModifiedButterfly),
        Method::Differential(Stencil::Loop, 0),
        Method::Differential(Stencil::ModifiedButterfly, 0),
        Method::Differential(Stencil::ModifiedButterfly, 1),
        Method::Differential(Stencil::ModifiedButterfly, 2),
    ];
    println!("## Normalised thin-plate energy E (seed 001 §4.3) and level distances\n");
    println!(
        "E in 1/length² of the mesh's own units; E·d² (d = control bounding-box diagonal) is \
         scale-free. h_k = max displacement of the vertices levels k−1 and k share, / d.\n"
    );
    for name in ["fertility", "rocker_arm", "epcot"] {
        let path = dir.join(format!("{name}.off"));
        let m = match read_off(&path) {
            Ok(m) => m,
            Err(e) => {
                println!("SKIP {name}: {} not readable ({e})\n", path.display());
                continue;
            }
        };
        let d = diagonal(&m);
        let e0 = thin_plate(&m);
        println!(
            "### {name}: {} V, {} F, diagonal d = {d:.4}, control E·d² = {:.1}\n",
            m.positions.len(),
            m.num_faces(),
            e0 * d * d
        );
        println!("| method | E·d² k=1 | E·d² k=2 | E·d² k=3 | h1/d | h2/d | h3/d | CG it. k=1,2,3 | time k=3 (s) |");
        println!("|---|---|---|---|---|---|---|---|---|");
        for meth in methods {
            let mut prev = m.clone();
            let mut es = Vec::new();
            let mut hs = Vec::new();
            let mut its = Vec::new();
            let mut secs = 0.0;
            let mut failed = None;
            for k in 1..=LEVELS {
                let t = Instant::now();
                match meth.run(&m, k) {
                    Ok((o, it)) => {
                        secs = t.elapsed().as_secs_f64();
                        es.push(format!("{:.2}", thin_plate(&o) * d * d));
                        hs.push(format!(
                            "{:.2e}",
                            level_distance(&prev.positions, &o.positions).unwrap() / d
                        ));
                        its.push(it.map_or("–".to_string(), |i| i.to_string()));
                        prev = o;
                    }
                    Err(e) => {
                        failed = Some(format!("k={k}: {e}"));
                        break;
                    }
                }
            }
            while es.len() < LEVELS {
                es.push("failed".into());
                hs.push("–".into());
            }
            println!(
                "| {} | {} | {} | {:.2} |{}",
                meth.name(),
                [es.join(" | "), hs.join(" | ")].join(" | "),
                its.join(","),
                secs,
                failed.map_or(String::new(), |f| format!(" {f}"))
            );
        }
        println!();
    }
}

/// Area-weighted mean, coefficient of variation (σ/|mean|) and max/min of `H` over the
/// vertices (all closed cages here).
fn spread(vals: &[(f64, f64)]) -> (f64, f64, f64) {
    let a: f64 = vals.iter().map(|v| v.1).sum();
    let mean = vals.iter().map(|v| v.0 * v.1).sum::<f64>() / a;
    let var = vals.iter().map(|v| (v.0 - mean).powi(2) * v.1).sum::<f64>() / a;
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in vals {
        lo = lo.min(v.0);
        hi = hi.max(v.0);
    }
    (mean, var.sqrt() / mean.abs(), hi / lo)
}

/// Per vertex `(H, A)` from the curvature tensor of [`vertex_curvatures`].
fn tensor_h(m: &OwnedMesh) -> Vec<(f64, f64)> {
    with_topology(m, |t| {
        let mut s = vec![[0.0; 3]; m.positions.len()];
        vertex_curvatures(t, &mut s).unwrap();
        s.iter().map(|c| (c[1], c[2])).collect()
    })
    .unwrap()
}

/// Per vertex `(4ᵏ ‖(L_k Ṽᵏ)_i‖, 1)`: the paper's discrete mean-curvature magnitude `|H_i|`
/// (§3.1, §3.4 "|H_i| = ‖δ_i‖") on the result, combinatorial Laplacian of level k.
fn combinatorial_h(m: &OwnedMesh, k: usize) -> Vec<(f64, f64)> {
    with_topology(m, |t| {
        let n = t.num_vertices();
        let mut rows = vec![0u32; n + 1];
        let mut cols = vec![0u32; laplacian::laplacian_nnz(t).unwrap()];
        let mut bnd = vec![0u32; n];
        laplacian::build(t, &mut rows, &mut cols, &mut bnd).unwrap();
        let lap = Laplacian {
            rows: &rows,
            cols: &cols,
            boundary: &bnd,
        };
        let mut y = vec![[0.0; 3]; n];
        lap.apply(&m.positions, 4f64.powi(k as i32), &mut y)
            .unwrap();
        y.iter()
            .map(|d| ((d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt(), 1.0))
            .collect()
    })
    .unwrap()
}

/// A generated fallback for a cage missing from the mesh directory.
type Builtin = fn() -> OwnedMesh;

fn dirmag_table(dir: &std::path::Path) {
    println!("## DirMag vs linear subdivision of Δ on coarse cages (seed 001 §3.4, Fig. 5–6)\n");
    println!(
        "Result at level k = 4 (tolerance 1e-10). CV = area-weighted σ(H)/|mean H| of the \
         curvature-tensor mean curvature H = (κ₁+κ₂)/2; max/min of H; CV and max/min of the \
         combinatorial |δ| = 4ᵏ‖L_k Ṽ‖. All control vertices of a Platonic cage have equal |δ|, \
         so uniform values are the ideal (0 and 1).\n"
    );
    let k = 4;
    let cages: [(&str, Option<Builtin>); 3] = [
        ("tetrahedron", Some(tetrahedron)),
        ("octahedron", Some(octahedron)),
        ("icosahedron", None),
    ];
    println!("| cage | method | CV(H) | max/min H | CV(‖δ‖) | max/min ‖δ‖ | E·d² |");
    println!("|---|---|---|---|---|---|---|");
    for (name, builtin) in cages {
        let m = match read_off(&dir.join(format!("{name}.off"))) {
            Ok(m) => m,
            Err(e) => match builtin {
                Some(f) => f(),
                None => {
                    println!("| {name} | SKIP: {e} | | | | | |");
                    continue;
                }
            },
        };
        let d = diagonal(&m);
        for meth in [
            Method::Differential(Stencil::ModifiedButterfly, 0),
            Method::Differential(Stencil::ModifiedButterfly, 1),
            Method::Differential(Stencil::ModifiedButterfly, 2),
            Method::Differential(Stencil::ModifiedButterfly, k),
            Method::Differential(Stencil::Loop, 0),
            Method::Differential(Stencil::Loop, 1),
            Method::Differential(Stencil::Loop, 2),
            Method::Spatial(Scheme::ModifiedButterfly),
            Method::Spatial(Scheme::Loop),
        ] {
            match meth.run(&m, k) {
                Ok((o, _)) => {
                    let (_, cv, r) = spread(&tensor_h(&o));
                    let (_, cvd, rd) = spread(&combinatorial_h(&o, k));
                    println!(
                        "| {name} | {} | {cv:.4} | {r:.3} | {cvd:.4} | {rd:.3} | {:.2} |",
                        meth.name(),
                        thin_plate(&o) * d * d
                    );
                }
                Err(e) => println!("| {name} | {} | failed: {e} | | | | |", meth.name()),
            }
        }
    }
    println!();
}

fn main() {
    let dir = std::env::args()
        .nth(1)
        .map(std::path::PathBuf::from)
        .unwrap_or_else(shared_meshes_dir);
    let which = std::env::args().nth(2).unwrap_or_default();
    if which != "dirmag" {
        thin_plate_table(&dir);
    }
    if which != "energy" {
        dirmag_table(&dir);
    }
}
