//! Curve subdivision throughput: output points per second for every scheme, about 1M output
//! points (a closed curve of 1000 points, 10 levels), single thread, plain `std::time`.
//!
//! Run with `cargo bench --bench curves`. Each scheme runs `REPS` times after one warm-up;
//! the best and the median run are reported.

// A benchmark program: failing loudly is right here.
#![allow(clippy::expect_used, clippy::indexing_slicing)]

use std::hint::black_box;
use std::time::{Duration, Instant};

use nlsubdiv::curve::{self, CurveScheme};
use nlsubdiv::Point;

const N: usize = 1000;
const LEVELS: u32 = 10;
const REPS: usize = 7;

/// A closed, unevenly sampled space curve (a trefoil knot), deterministic.
fn input() -> Vec<Point> {
    (0..N)
        .map(|i| {
            let u = i as f64 / N as f64;
            let t = 2.0
                * std::f64::consts::PI
                * (u + 0.1 * (6.0 * std::f64::consts::PI * u).sin() / 6.0);
            [
                t.sin() + 2.0 * (2.0 * t).sin(),
                t.cos() - 2.0 * (2.0 * t).cos(),
                -(3.0 * t).sin(),
            ]
        })
        .collect()
}

fn main() {
    let p = input();
    let closed = true;
    let m = curve::refined_size(N, closed, LEVELS).expect("size");
    println!("curve subdivision: closed curve, {N} points, {LEVELS} levels -> {m} output points");
    println!(
        "{:<26} {:>12} {:>12} {:>16}",
        "scheme", "best ms", "median ms", "points/s (best)"
    );
    let mut linear_best = None;
    for scheme in CurveScheme::ALL {
        let s = curve::scratch_size(scheme, N, closed, LEVELS).expect("scratch size");
        let mut out = vec![[0.0; 3]; m];
        let mut scratch = vec![[0.0; 3]; s];
        // Warm-up.
        curve::subdivide(scheme, &p, closed, LEVELS, &mut out, &mut scratch).expect("subdivide");
        let mut times: Vec<Duration> = (0..REPS)
            .map(|_| {
                let t0 = Instant::now();
                let w = curve::subdivide(
                    scheme,
                    black_box(&p),
                    closed,
                    LEVELS,
                    black_box(&mut out),
                    &mut scratch,
                )
                .expect("subdivide");
                let dt = t0.elapsed();
                black_box(&out);
                assert_eq!(w, m);
                dt
            })
            .collect();
        times.sort();
        let best = times[0].as_secs_f64();
        let median = times[REPS / 2].as_secs_f64();
        println!(
            "{:<26} {:>12.3} {:>12.3} {:>16.3e}",
            scheme.name(),
            best * 1e3,
            median * 1e3,
            m as f64 / best
        );
        match scheme {
            CurveScheme::FourPoint => linear_best = Some(best),
            CurveScheme::MobiusInterpolating | CurveScheme::MobiusApproximating => {
                if let Some(l) = linear_best {
                    println!("{:<26} {:>12.1}x slower than four-point", "", best / l);
                }
            }
            _ => {}
        }
    }
}
