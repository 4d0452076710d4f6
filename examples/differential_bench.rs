//! Seed 001 Table 1 layout: per-stage times of differential-space subdivision at 3 levels
//! (compute Δ, subdivide, reconstruct), and an export of the reconstruction's normal-equation
//! system `(LᵀL + anchors) V = Lᵀδ + anchors` for `benches/direct_solvers.cpp` (CHOLMOD's
//! supernodal Cholesky of the same system, sparse QR of the least-squares problem). Driven
//! by `scripts/bench_differential.py`.
//!
//! `cargo run --release --example differential_bench -- OUT_DIR [MESH_DIR]`
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
use nlsubdiv::differential::{DifferentialOptions, Stencil};
use nlsubdiv::scheme::Scheme;
use std::io::Write;
use std::time::Instant;

fn best<T>(runs: usize, mut f: impl FnMut() -> T) -> (f64, T) {
    let mut t = f64::INFINITY;
    let mut r = None;
    for _ in 0..runs {
        let s = Instant::now();
        let v = f();
        t = t.min(s.elapsed().as_secs_f64());
        r = Some(v);
    }
    (t, r.unwrap())
}

/// Rows, cols, flags of the Laplacian of `m`.
fn lap_of(m: &OwnedMesh) -> (Vec<u32>, Vec<u32>, Vec<u32>) {
    with_topology(m, |t| {
        let n = t.num_vertices();
        let mut r = vec![0u32; n + 1];
        let mut c = vec![0u32; laplacian::laplacian_nnz(t).unwrap()];
        let mut b = vec![0u32; n];
        laplacian::build(t, &mut r, &mut c, &mut b).unwrap();
        (r, c, b)
    })
    .unwrap()
}

fn main() {
    let out_dir = std::path::PathBuf::from(std::env::args().nth(1).expect("OUT_DIR"));
    let dir = std::env::args()
        .nth(2)
        .map(std::path::PathBuf::from)
        .unwrap_or_else(shared_meshes_dir);
    std::fs::create_dir_all(&out_dir).unwrap();
    let k = 3usize;
    for name in ["fertility", "rocker_arm"] {
        let path = dir.join(format!("{name}.off"));
        let Ok(m) = read_off(&path) else {
            println!("{name}: skipped ({} not found)", path.display());
            continue;
        };
        // Stage 1: Δ⁰ = L₀ V⁰ (topology, Laplacian, product).
        let (t_delta, delta0) = best(3, || {
            let (r, c, b) = lap_of(&m);
            let lap = Laplacian {
                rows: &r,
                cols: &c,
                boundary: &b,
            };
            let mut d = vec![[0.0; 3]; m.positions.len()];
            lap.apply(&m.positions, 1.0, &mut d).unwrap();
            d
        });
        // Stage 2: k levels of Loop on Δ (the core also subdivides the spatial warm start).
        let dmesh = OwnedMesh {
            positions: delta0,
            offsets: m.offsets.clone(),
            indices: m.indices.clone(),
        };
        let (t_sub, dk) = best(3, || subdivide_n(Scheme::Loop, &dmesh, k).unwrap());
        let opts = DifferentialOptions {
            stencil: Stencil::Loop,
            levels: k,
            ..Default::default()
        };
        let (t_total, (out, rep)) = best(1, || differential_subdivide(&m, &opts).unwrap());
        let t_rec = t_total - t_delta - 2.0 * t_sub;
        println!(
            "{name}: {} -> {} V; delta {:.3} s, subdivide {:.3} s (x2 with the warm start), \
             total {:.3} s, reconstruct (by difference) {:.3} s; {} iterations, relative \
             residual {:.2e}",
            m.positions.len(),
            out.positions.len(),
            t_delta,
            t_sub,
            t_total,
            t_rec,
            rep.solve.iterations,
            rep.solve.relative_residual
        );
        // The system, for the direct solvers: L_k (weights of Eq. (2)/(8)), δ = 4⁻ᵏ Δ_k, anchor 0 at the
        // spatial subdivision's vertex 0 (closed connected meshes: one anchor), and our result
        // translated so its vertex 0 sits at the anchor (the same solution of that system).
        let spatial = subdivide_n(Scheme::Loop, &m, k).unwrap();
        let (r, c, b) = lap_of(&out);
        let n = out.positions.len();
        let s = 0.25f64.powi(k as i32);
        let mut f = std::io::BufWriter::new(
            std::fs::File::create(out_dir.join(format!("{name}.sys"))).unwrap(),
        );
        let w_u64 = |f: &mut std::io::BufWriter<std::fs::File>, x: u64| {
            f.write_all(&x.to_le_bytes()).unwrap()
        };
        w_u64(&mut f, n as u64);
        // Triplets of L.
        let mut trip: Vec<(u32, u32, f64)> = Vec::new();
        for i in 0..n {
            let ring = &c[r[i] as usize..r[i + 1] as usize];
            if ring.is_empty() {
                continue;
            }
            trip.push((i as u32, i as u32, 1.0));
            if b[i] & laplacian::BOUNDARY != 0 {
                trip.push((i as u32, ring[0], -0.5));
                trip.push((i as u32, ring[ring.len() - 1], -0.5));
            } else {
                let wgt = 1.0 / ring.len() as f64;
                for &j in ring {
                    trip.push((i as u32, j, -wgt));
                }
            }
        }
        w_u64(&mut f, trip.len() as u64);
        for &(i, j, v) in &trip {
            f.write_all(&i.to_le_bytes()).unwrap();
            f.write_all(&j.to_le_bytes()).unwrap();
            f.write_all(&v.to_le_bytes()).unwrap();
        }
        for p in &dk.positions {
            for x in p {
                f.write_all(&(s * x).to_le_bytes()).unwrap();
            }
        }
        w_u64(&mut f, 1);
        w_u64(&mut f, 0);
        for x in spatial.positions[0] {
            f.write_all(&x.to_le_bytes()).unwrap();
        }
        let shift: [f64; 3] =
            std::array::from_fn(|a| spatial.positions[0][a] - out.positions[0][a]);
        for p in &out.positions {
            for a in 0..3 {
                f.write_all(&(p[a] + shift[a]).to_le_bytes()).unwrap();
            }
        }
        f.write_all(&t_rec.to_le_bytes()).unwrap();
        f.flush().unwrap();
        println!(
            "TABLE {name} {} {} {t_delta:.4} {t_sub:.4} {t_rec:.4} {t_total:.4} {} {:.3e}",
            m.positions.len(),
            n,
            rep.solve.iterations,
            rep.solve.relative_residual
        );
    }
}
