//! The Möbius primitives at work on small inputs built here: F4 reproducing a circle,
//! canonical forms, Möbius maps and the star measures. (The project's main job on its bundled
//! input is `nlsubdiv demo`, `cli/src/cmd/demo.rs`.)
//!
//! `cargo run --release --example primitives`
#![allow(clippy::expect_used, clippy::indexing_slicing)] // a std program, not the core
use nlsubdiv::blend::f4;
use nlsubdiv::metrics::{mobius_regularity, willmore_energy};
use nlsubdiv::mobius::{CanonicalForm, MobiusMap, StarKind};

fn main() {
    // 1. Circle reproduction: insert points with F4 into an unevenly sampled circle, 5 times.
    let on = |t: f64| [2.0 * t.cos(), 2.0 * t.sin(), 0.5];
    let mut pts: Vec<[f64; 3]> = [0.0, 0.7, 1.9, 2.6, 3.9, 5.1]
        .iter()
        .map(|&t| on(t))
        .collect();
    for _ in 0..5 {
        let n = pts.len();
        let mut next = Vec::with_capacity(2 * n);
        for i in 0..n {
            let p = |k: usize| pts[(i + n + k - 1) % n];
            next.push(p(1));
            next.push(f4(p(0), p(1), p(2), p(3)).expect("F4 on a circle"));
        }
        pts = next;
    }
    let worst = pts
        .iter()
        .map(|p| {
            ((p[0] * p[0] + p[1] * p[1]).sqrt() - 2.0)
                .abs()
                .max((p[2] - 0.5).abs())
        })
        .fold(0.0, f64::max);
    println!(
        "Möbius interpolating curve: 6 → {} points, worst distance from the circle {worst:.2e}",
        pts.len()
    );

    // 2. A Möbius-regular star (a regular hexagonal star under an inversion): its canonical
    //    form is a regular star again, and its regularity defect and Willmore energy are 0.
    let m = MobiusMap::inversion([0.3, -0.2, 1.5], 1.2);
    let regular: Vec<[f64; 3]> = (0..6)
        .map(|i| {
            let t = std::f64::consts::TAU * i as f64 / 6.0;
            [t.cos(), t.sin(), 0.0]
        })
        .collect();
    let v = m.apply([0.0; 3]).expect("centre");
    let ring: Vec<[f64; 3]> = regular.iter().map(|&p| m.apply(p).expect("ring")).collect();
    let cf = CanonicalForm::new(v, &ring, StarKind::Interior).expect("canonical form");
    let radii: Vec<f64> = ring
        .iter()
        .map(|&u| {
            let c = cf.to_canonical(u).expect("canonical point");
            ((c[0] - cf.c[0]).powi(2) + (c[1] - cf.c[1]).powi(2) + (c[2] - cf.c[2]).powi(2)).sqrt()
        })
        .collect();
    let spread = radii.iter().cloned().fold(f64::MIN, f64::max)
        - radii.iter().cloned().fold(f64::MAX, f64::min);
    println!(
        "Möbius-regular star: canonical radii spread {spread:.2e}, regularity defect {:.2e}, Willmore {:.2e}",
        mobius_regularity(v, &ring, true).expect("regularity"),
        willmore_energy(v, &ring, true).expect("willmore")
    );
}
