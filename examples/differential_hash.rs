//! One FNV-1a hash per differential-space subdivision call on a fixed set of inputs (the
//! output positions, faces and report bits), for checking that a change leaves the output of
//! `differential::subdivide` bit-identical: run it before and after and `diff` the outputs.
//!
//! `cargo run --release --example differential_hash [MESH_DIR] > hashes.txt`
//!
//! Inputs: generated meshes (jittered octahedron, open grid) and, when found, the shared
//! meshes epcot, pawn_tri and fertility (a missing file is printed as skipped). Cases: Loop,
//! Modified Butterfly, DirMag 1 and 2 levels, levels 0–3 (fertility: 2), and the edit options
//! set to values that change nothing (unit curvature scale, zero normals).
#![allow(
    clippy::expect_used,
    clippy::unwrap_used,
    clippy::indexing_slicing,
    dead_code
)]

#[path = "../tests/common/mod.rs"]
mod common;

use common::*;
use nlsubdiv::differential::{DifferentialOptions, DifferentialReport, Stencil};
use nlsubdiv::scheme::Scheme;
use nlsubdiv::Point;

struct Fnv(u64);
impl Fnv {
    fn u64(&mut self, x: u64) {
        for b in x.to_le_bytes() {
            self.0 ^= u64::from(b);
            self.0 = self.0.wrapping_mul(0x100_0000_01b3);
        }
    }
    fn f64(&mut self, x: f64) {
        self.u64(x.to_bits());
    }
}

fn hash(r: &Result<(OwnedMesh, DifferentialReport), (nlsubdiv::Error, DifferentialReport)>) -> u64 {
    let mut h = Fnv(0xcbf2_9ce4_8422_2325);
    let rep = match r {
        Ok((m, rep)) => {
            for p in &m.positions {
                for x in p {
                    h.f64(*x);
                }
            }
            for o in &m.offsets {
                h.u64(u64::from(*o));
            }
            for i in &m.indices {
                h.u64(u64::from(*i));
            }
            rep
        }
        Err((e, rep)) => {
            h.u64(u64::from(e.status.code()));
            h.u64(u64::from(e.element));
            rep
        }
    };
    h.u64(u64::from(rep.solve.iterations));
    h.f64(rep.solve.relative_residual);
    h.f64(rep.solve.initial_residual);
    h.u64(u64::from(rep.solve.converged));
    h.u64(u64::from(rep.dirmag_degenerate));
    h.u64(u64::from(rep.anchors));
    h.0
}

fn main() {
    let dir = std::env::args()
        .nth(1)
        .map(std::path::PathBuf::from)
        .unwrap_or_else(shared_meshes_dir);
    let mut meshes: Vec<(String, OwnedMesh, usize)> = vec![
        (
            "octahedron-jitter".into(),
            jitter(&subdivide(Scheme::Loop, &octahedron()).unwrap(), 0.05, 7),
            3,
        ),
        (
            "open-grid".into(),
            jitter(&tri_grid(4, 3), 0.05, 3).map_positions(|p| [p[0], p[1], 0.3 * p[0] * p[1]]),
            3,
        ),
    ];
    for (name, k) in [("epcot", 3), ("pawn_tri", 3), ("fertility", 2)] {
        let p = dir.join(format!("{name}.off"));
        match read_off(&p) {
            Ok(m) => meshes.push((name.into(), m, k)),
            Err(_) => println!("{name}: skipped ({} not found)", p.display()),
        }
    }
    for (name, m, kmax) in &meshes {
        let n = m.positions.len();
        let ones = vec![1.0; n];
        let zeros: Vec<Point> = vec![[0.0; 3]; n];
        for (label, stencil, dm) in [
            ("loop", Stencil::Loop, 0),
            ("butterfly", Stencil::ModifiedButterfly, 0),
            ("dirmag1", Stencil::ModifiedButterfly, 1),
            ("dirmag2", Stencil::ModifiedButterfly, 2),
        ] {
            for k in 0..=*kmax {
                let base = DifferentialOptions {
                    stencil,
                    levels: k,
                    dirmag_levels: dm,
                    ..Default::default()
                };
                let plain = differential_subdivide(m, &base);
                println!("{name} {label} k={k} plain {:016x}", hash(&plain));
                if k == *kmax {
                    let o = DifferentialOptions {
                        curvature_scale: Some(&ones),
                        ..base
                    };
                    println!(
                        "{name} {label} k={k} unit-scale {:016x}",
                        hash(&differential_subdivide(m, &o))
                    );
                    let o = DifferentialOptions {
                        normals: Some(&zeros),
                        ..base
                    };
                    println!(
                        "{name} {label} k={k} zero-normals {:016x}",
                        hash(&differential_subdivide(m, &o))
                    );
                }
            }
        }
    }
}
