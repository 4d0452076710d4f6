//! `curve`: the library's points bit for bit, full-precision text that round-trips, circles
//! kept by the Möbius and circle-blend schemes, and bad files refused by line.

// Test helpers outside #[test] functions: clippy's in-test allowances do not reach them.
#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic,
    clippy::indexing_slicing
)]

mod common;

use std::fmt::Write as _;

use common::*;
use nlsubdiv::curve::{self, CurveScheme};

fn write_points(path: &std::path::Path, pts: &[[f64; 3]]) {
    let mut s = String::from("# a test curve\n\n");
    for p in pts {
        // 17 significant digits, not the command's shortest form: the round trip re-formats.
        writeln!(s, "{:.16e} {:.16e} {:.16e}   # a point", p[0], p[1], p[2]).unwrap();
    }
    std::fs::write(path, s).unwrap();
}

fn library(s: CurveScheme, pts: &[[f64; 3]], closed: bool, levels: u32) -> Vec<[f64; 3]> {
    let n = curve::refined_size(pts.len(), closed, levels).unwrap();
    let mut out = vec![[0.0; 3]; n];
    let mut scratch = vec![[0.0; 3]; curve::scratch_size(s, pts.len(), closed, levels).unwrap()];
    curve::subdivide(s, pts, closed, levels, &mut out, &mut scratch).unwrap();
    out
}

fn run_curve(dir: &TempDir, scheme: &str, levels: u32, closed: bool) -> std::process::Output {
    let mut args = vec![
        "curve".to_string(),
        "--scheme".into(),
        scheme.into(),
        "--levels".into(),
        levels.to_string(),
        dir.path("in.txt").to_str().unwrap().into(),
        dir.path("out.txt").to_str().unwrap().into(),
    ];
    if closed {
        args.insert(5, "--closed".into());
    }
    run(&args)
}

fn bits(p: &[[f64; 3]]) -> Vec<[u64; 3]> {
    p.iter().map(|q| q.map(f64::to_bits)).collect()
}

/// A circle of radius `r` about `c` in a tilted plane: the point at angle `t`.
fn on_circle(t: f64) -> [f64; 3] {
    let (c, r) = ([0.3, -1.2, 2.0], 1.7);
    // An orthonormal pair spanning the plane.
    let u = [2.0 / 3.0, 2.0 / 3.0, 1.0 / 3.0];
    let v = [-2.0 / 3.0, 1.0 / 3.0, 2.0 / 3.0];
    [
        c[0] + r * (t.cos() * u[0] + t.sin() * v[0]),
        c[1] + r * (t.cos() * u[1] + t.sin() * v[1]),
        c[2] + r * (t.cos() * u[2] + t.sin() * v[2]),
    ]
}

#[test]
fn every_scheme_gives_the_library_points_and_they_round_trip() {
    let dir = TempDir::new("curve-all");
    let mut rng = Rng(11);
    let pts: Vec<[f64; 3]> = (0..9)
        .map(|i| {
            let t = f64::from(i) * 0.7;
            [
                t.cos() * 2.0 + 0.1 * rng.f64(),
                t.sin() + 0.3 * rng.f64(),
                0.2 * t,
            ]
        })
        .collect();
    write_points(&dir.path("in.txt"), &pts);
    let pts = read_points(&dir.path("in.txt"));
    let mut names: Vec<&str> = CurveScheme::ALL.iter().map(|s| s.name()).collect();
    names.push("differential");
    for name in names {
        let s = CurveScheme::from_name(name).unwrap();
        for closed in [false, true] {
            let what = format!("{name} closed={closed}");
            let o = run_curve(&dir, name, 3, closed);
            assert_eq!(code(&o), 0, "{what}: {}", stderr(&o));
            let err = stderr(&o);
            assert!(
                err.starts_with("wrote ") && err.contains("9 → ") && err.lines().count() == 1,
                "{what}: {err}"
            );
            let got = read_points(&dir.path("out.txt"));
            assert_eq!(bits(&got), bits(&library(s, &pts, closed, 3)), "{what}");
            // Level 0 of the output is the output: the text loses no bit.
            std::fs::rename(dir.path("out.txt"), dir.path("in.txt")).unwrap();
            let o = run_curve(&dir, name, 0, closed);
            assert_eq!(code(&o), 0, "{what}: {}", stderr(&o));
            assert_eq!(
                bits(&read_points(&dir.path("out.txt"))),
                bits(&got),
                "{what}"
            );
            write_points(&dir.path("in.txt"), &pts);
        }
    }
}

#[test]
fn circles_stay_circles_under_the_mobius_and_circle_blend_schemes() {
    let dir = TempDir::new("curve-circle");
    let c = [0.3, -1.2, 2.0];
    let r = 1.7;
    // Uneven spacing: a closed loop and an open arc.
    let closed: Vec<[f64; 3]> = (0..7)
        .map(|i| on_circle(std::f64::consts::TAU * f64::from(i) / 7.0 + 0.25 * f64::from(i).sin()))
        .collect();
    let open: Vec<[f64; 3]> = (0..6)
        .map(|i| on_circle(0.5 * f64::from(i) + 0.1 * f64::from(i * i).cos()))
        .collect();
    for name in [
        "mobius-interpolating",
        "mobius-approximating",
        "circle-blend",
    ] {
        for (is_closed, pts) in [(true, &closed), (false, &open)] {
            write_points(&dir.path("in.txt"), pts);
            let o = run_curve(&dir, name, 4, is_closed);
            assert_eq!(code(&o), 0, "{name}: {}", stderr(&o));
            let got = read_points(&dir.path("out.txt"));
            let n = pts.len();
            let want = if is_closed {
                n << 4
            } else {
                ((n - 1) << 4) + 1
            };
            assert_eq!(got.len(), want, "{name}");
            let mut worst = 0.0f64;
            for p in &got {
                let d = [p[0] - c[0], p[1] - c[1], p[2] - c[2]];
                let radial = ((d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt() - r).abs() / r;
                // Distance from the plane (normal u × v = (1/3, −2/3, 2/3)).
                let plane = (d[0] / 3.0 - 2.0 * d[1] / 3.0 + 2.0 * d[2] / 3.0).abs() / r;
                worst = worst.max(radial).max(plane);
            }
            assert!(
                worst < 1e-12,
                "{name} closed={is_closed}: {worst:e} off the circle"
            );
        }
    }
    // The linear schemes do not keep it (the test would see it).
    write_points(&dir.path("in.txt"), &closed);
    let o = run_curve(&dir, "bspline", 4, true);
    assert_eq!(code(&o), 0);
    let p = read_points(&dir.path("out.txt"))[0];
    let d = [p[0] - c[0], p[1] - c[1], p[2] - c[2]];
    assert!(((d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt() - r).abs() > 1e-3);
}

#[test]
fn bad_curve_files_are_refused_by_line_and_leave_nothing() {
    let dir = TempDir::new("curve-bad");
    let cases: [(&str, &str, bool, i32, &[&str]); 9] = [
        (
            "# points\n0 0 0\n\n1 0 0\n2 0\n",
            "bspline",
            false,
            2,
            &[":5: point 2", "found 2"],
        ),
        (
            "0 0 0\r\n1 0 0\r\n1 1 zero\r\n",
            "bspline",
            false,
            2,
            &[":3: point 2", "'zero' is not a number"],
        ),
        (
            "0 0 0\n1 nan 0\n",
            "bspline",
            false,
            2,
            &[":2: point 1", "NaN"],
        ),
        (
            "0 0 0\n1 0 inf\n",
            "bspline",
            false,
            2,
            &[":2: point 1", "infinite"],
        ),
        (
            "0 0 0 # one\n1 0 0\n",
            "bspline",
            true,
            2,
            &["2 points", "a closed curve needs at least 3"],
        ),
        ("# nothing\n", "four-point", false, 2, &["0 points"]),
        (
            "0 0 0\n0 0 0\n0 0 0\n1 0 0\n",
            "circle-blend",
            false,
            2,
            &["in.txt:1:", "circle-blend"],
        ),
        (
            "0 0 0\n1 0 0\n",
            "mobius-loop",
            false,
            4,
            &["mesh scheme", "available: four-point"],
        ),
        (
            "0 0 0\n1 0 0\n",
            "spline",
            false,
            4,
            &["unknown curve scheme", "differential-bspline"],
        ),
    ];
    for (text, scheme, closed, status, needles) in cases {
        std::fs::write(dir.path("in.txt"), text).unwrap();
        let o = run_curve(&dir, scheme, 2, closed);
        let err = stderr(&o);
        assert_eq!(code(&o), status, "{text:?}: {err}");
        for n in needles {
            assert!(err.contains(n), "{text:?}: '{n}' not in {err}");
        }
        assert_files(&dir, &["in.txt"], text);
    }
    std::fs::write(dir.path("in.txt"), "0 0 0\n1 0 0\n").unwrap();
    let o = run_curve(&dir, "bspline", 41, false);
    assert_eq!(code(&o), 4, "{}", stderr(&o));
    let o = run_curve(&dir, "bspline", 40, false);
    assert_eq!(code(&o), 4, "{}", stderr(&o));
    assert!(stderr(&o).contains("use fewer levels"), "{}", stderr(&o));
    assert_files(&dir, &["in.txt"], "too many levels");
    std::fs::remove_file(dir.path("in.txt")).unwrap();
    let o = run_curve(&dir, "bspline", 1, false);
    assert_eq!(code(&o), 3, "{}", stderr(&o));
    assert_files(&dir, &[], "missing input");
}
