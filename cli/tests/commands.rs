//! `compare`, `metrics`, `check` and `render` on meshes with known answers.

// Test helpers outside #[test] functions: clippy's in-test allowances do not reach them.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use common::*;
use serde_json::Value;

fn json_of(o: &std::process::Output) -> Value {
    serde_json::from_slice(&o.stdout)
        .unwrap_or_else(|e| panic!("not JSON ({e}): {}\n{}", stdout(o), stderr(o)))
}

/// The mesh with vertices renumbered by a random permutation, faces shuffled and each
/// face rotated to start at a random corner.
fn scramble(m: &TMesh, rng: &mut Rng) -> TMesh {
    let n = m.positions.len();
    let mut perm: Vec<u32> = (0..n as u32).collect();
    for i in (1..n).rev() {
        perm.swap(i, rng.below(i + 1));
    }
    let mut positions = vec![[0.0; 3]; n];
    for (old, &new) in perm.iter().enumerate() {
        positions[new as usize] = m.positions[old];
    }
    let mut faces: Vec<Vec<u32>> = m
        .faces
        .iter()
        .map(|f| {
            let g: Vec<u32> = f.iter().map(|&v| perm[v as usize]).collect();
            let r = rng.below(g.len());
            [&g[r..], &g[..r]].concat()
        })
        .collect();
    for i in (1..faces.len()).rev() {
        faces.swap(i, rng.below(i + 1));
    }
    TMesh { positions, faces }
}

#[test]
fn compare_is_independent_of_order_and_sees_differences() {
    let dir = TempDir::new("compare");
    let mut rng = Rng(3);
    let a = torus(40, 30, 2.0, 0.6);
    let pa = dir.path("a.off");
    a.write_off(&pa);
    let b = scramble(&a, &mut rng);
    let pb = dir.path("b.off");
    b.write_off(&pb);
    let (sa, sb) = (pa.to_str().unwrap(), pb.to_str().unwrap());

    let o = run(&["compare", "--json", sa, sb]);
    assert_eq!(code(&o), 0, "{}{}", stdout(&o), stderr(&o));
    let j = json_of(&o);
    assert_eq!(j["max_distance"], 0.0);
    assert_eq!(j["faces_identical"], true);
    assert_eq!(j["one_to_one"], true);
    // Human-readable output and the same answer through another format.
    let pc = dir.path("b.ply");
    assert_eq!(code(&run(&["convert", "-q", sb, pc.to_str().unwrap()])), 0);
    let o = run(&["compare", sa, pc.to_str().unwrap()]);
    assert_eq!(code(&o), 0);
    assert!(stdout(&o).contains("equal"), "{}", stdout(&o));

    // One vertex moved by 1e-6 of the diagonal: different at the default tolerance,
    // equal at 1e-5.
    let diag = (2.0f64 * (2.0 * 2.6f64).powi(2) + (1.2f64).powi(2)).sqrt();
    let mut moved = b.clone();
    moved.positions[17][2] += 1e-6 * diag;
    let pm = dir.path("moved.off");
    moved.write_off(&pm);
    let o = run(&["compare", "--json", sa, pm.to_str().unwrap()]);
    assert_eq!(code(&o), 1, "{}", stdout(&o));
    let rel = json_of(&o)["max_relative"].as_f64().unwrap();
    assert!((rel / 1e-6 - 1.0).abs() < 1e-3, "{rel}");
    let o = run(&["compare", "--tol", "1e-5", sa, pm.to_str().unwrap()]);
    assert_eq!(code(&o), 0, "{}", stdout(&o));

    // One face reversed: orientation counts.
    let mut flipped = b.clone();
    flipped.faces[5].reverse();
    let pf = dir.path("flipped.off");
    flipped.write_off(&pf);
    let o = run(&["compare", "--json", sa, pf.to_str().unwrap()]);
    assert_eq!(code(&o), 1);
    let j = json_of(&o);
    assert_eq!(j["faces_identical"], false);
    assert_eq!(j["faces_not_matched"], 1);
    assert_eq!(j["max_distance"], 0.0);

    // Different counts.
    let small = torus(10, 8, 2.0, 0.6);
    let ps = dir.path("small.off");
    small.write_off(&ps);
    let o = run(&["compare", "--json", sa, ps.to_str().unwrap()]);
    assert_eq!(code(&o), 1);
    assert_eq!(json_of(&o)["same_counts"], false);

    // A file that is not a mesh: 2.
    let bad = dir.path("bad.off");
    std::fs::write(&bad, "OFF\n1 1 0\n0 0\n").unwrap();
    assert_eq!(code(&run(&["compare", sa, bad.to_str().unwrap()])), 2);
}

#[test]
fn compare_handles_coincident_vertices() {
    // Two vertices at the same position (a seam as in the shared cow): each is matched
    // once, and faces still agree after scrambling.
    let dir = TempDir::new("compare-dup");
    let mut m = open_grid(4, 3);
    let extra = m.positions[6];
    m.positions.push(extra);
    let last = m.positions.len() as u32 - 1;
    m.faces[0] = m.faces[0]
        .iter()
        .map(|&v| if v == 6 { last } else { v })
        .collect();
    let pa = dir.path("a.off");
    m.write_off(&pa);
    let pb = dir.path("b.off");
    // Keep the duplicate pair in the same relative order (a tie is broken by index).
    m.write_off(&pb);
    let o = run(&[
        "compare",
        "--json",
        pa.to_str().unwrap(),
        pb.to_str().unwrap(),
    ]);
    assert_eq!(code(&o), 0, "{}", stdout(&o));
    assert_eq!(json_of(&o)["one_to_one"], true);
}

#[test]
fn metrics_of_known_shapes() {
    let dir = TempDir::new("metrics");
    // A sphere: every star is cospherical, the fitted sphere is the unit sphere.
    let s = icosphere(2);
    let ps = dir.path("sphere.off");
    s.write_off(&ps);
    let o = run(&["metrics", "--json", ps.to_str().unwrap()]);
    assert_eq!(code(&o), 0, "{}", stderr(&o));
    let j = json_of(&o);
    assert_eq!(j["vertices"], 162);
    assert_eq!(j["faces"], 320);
    assert_eq!(j["edges"], 480);
    assert_eq!(j["closed"], true);
    assert_eq!(j["topology"]["euler_characteristic"], 2);
    assert_eq!(j["topology"]["per_component"][0]["genus"], 0);
    assert!(
        j["willmore"]["max"].as_f64().unwrap() < 1e-12,
        "{}",
        j["willmore"]
    );
    assert_eq!(j["willmore"]["vertices"], 162);
    let sphere = &j["sphere"];
    assert!(
        (sphere["radius"].as_f64().unwrap() - 1.0).abs() < 1e-14,
        "{sphere}"
    );
    assert!(sphere["max_relative"].as_f64().unwrap() < 1e-14);
    let h = &j["mean_curvature"];
    assert!((h["mean"].as_f64().unwrap() - 1.0).abs() < 0.05, "{h}");
    // The icosahedron itself: Möbius regular at every vertex.
    let ico = icosphere(0);
    let pi = dir.path("ico.off");
    ico.write_off(&pi);
    let j = json_of(&run(&["metrics", "--json", pi.to_str().unwrap()]));
    assert!(
        j["mobius_regularity"]["max"].as_f64().unwrap() < 1e-20,
        "{}",
        j["mobius_regularity"]
    );

    // A torus has genus 1 and no sphere fits it well; a flat grid has one boundary loop,
    // zero Willmore energy and no sphere at all.
    let pt = dir.path("torus.off");
    torus(24, 12, 2.0, 0.5).write_off(&pt);
    let j = json_of(&run(&["metrics", "--json", pt.to_str().unwrap()]));
    assert_eq!(j["topology"]["per_component"][0]["genus"], 1);
    assert_eq!(j["edges"], 2 * 24 * 12);
    assert!(j["sphere"]["rms_relative"].as_f64().unwrap() > 0.05);
    let pg = dir.path("grid.off");
    open_grid(5, 4).write_off(&pg);
    let j = json_of(&run(&["metrics", "--json", pg.to_str().unwrap()]));
    assert_eq!(j["boundary_loops"], 1);
    assert_eq!(j["closed"], false);
    assert_eq!(j["topology"]["per_component"][0]["genus"], 0);
    assert!(j["sphere"].is_null());
    assert!(j["willmore"]["max"].as_f64().unwrap() < 1e-15);
    assert!(j["mean_curvature"]["undefined"].as_u64().unwrap() > 0); // boundary
    let e = &j["edge_length"];
    assert_eq!(
        e["max"].as_f64().unwrap(),
        (0.25f64.powi(2) + (1.0f64 / 3.0).powi(2)).sqrt()
    );
    assert_eq!(e["min"], 0.25);

    // A coloured copy for MeshLab: PLY with red/green/blue and quality; geometry intact.
    let out = dir.path("colored.ply");
    let o = run(&[
        "metrics",
        "-q",
        pt.to_str().unwrap(),
        "--colored",
        out.to_str().unwrap(),
        "--color",
        "mean-curvature",
    ]);
    assert_eq!(code(&o), 0, "{}", stderr(&o));
    let bytes = std::fs::read(&out).unwrap();
    let head = String::from_utf8_lossy(&bytes[..400]);
    for p in [
        "property uchar red",
        "property uchar blue",
        "property float quality",
    ] {
        assert!(head.contains(p), "{head}");
    }
    let back = dir.path("back.off");
    assert_eq!(
        code(&run(&[
            "convert",
            "-q",
            out.to_str().unwrap(),
            back.to_str().unwrap()
        ])),
        0
    );
    assert_eq!(read_off(&back).bits(), read_off(&pt).bits());
    // Human-readable output names the measures.
    let o = run(&["metrics", pt.to_str().unwrap()]);
    for w in [
        "Willmore energy",
        "Möbius regularity",
        "best-fit sphere",
        "genus 1",
    ] {
        assert!(stdout(&o).contains(w), "{}", stdout(&o));
    }
}

#[test]
fn metrics_of_shared_meshes() {
    let Some(dir) = shared_meshes("cli::commands::metrics_of_shared_meshes") else {
        return;
    };
    // On the unit sphere to 3.3e-16 (meshes README): the fit finds it.
    for name in ["sphere_icosphere3_strong.off", "sphere_uv_mixed_pole16.off"] {
        let j = json_of(&run(&[
            "metrics",
            "--json",
            dir.join(name).to_str().unwrap(),
        ]));
        let s = &j["sphere"];
        assert!(
            (s["radius"].as_f64().unwrap() - 1.0).abs() < 1e-12,
            "{name}: {s}"
        );
        assert!(s["max_relative"].as_f64().unwrap() < 1e-12, "{name}: {s}");
        assert!(j["willmore"]["max"].as_f64().unwrap() < 1e-10, "{name}");
    }
    // Genus as the meshes README lists it.
    for (name, genus, loops) in [
        ("fertility.off", 4, 0),
        ("toroidal_tet_tri.off", 3, 0),
        ("yas_island_quad.off", 0, 3),
        ("camelhead.off", 0, 1),
    ] {
        let j = json_of(&run(&[
            "metrics",
            "--json",
            dir.join(name).to_str().unwrap(),
        ]));
        assert_eq!(j["topology"]["per_component"][0]["genus"], genus, "{name}");
        assert_eq!(j["boundary_loops"], loops, "{name}");
    }
}

#[test]
fn render_draws_the_mesh() {
    let dir = TempDir::new("render");
    let pt = dir.path("torus.off");
    torus(32, 16, 2.0, 0.7).write_off(&pt);
    let png = dir.path("torus.png");
    let o = run(&[
        "render",
        pt.to_str().unwrap(),
        png.to_str().unwrap(),
        "--size",
        "320x240",
    ]);
    assert_eq!(code(&o), 0, "{}", stderr(&o));
    let (w, h, rgb) = decode_png(&png);
    assert_eq!((w, h), (320, 240));
    let (var, covered) = picture_stats(w, h, &rgb);
    assert!(var > 100.0, "blank picture? luminance variance {var}");
    assert!(
        (0.15..0.9).contains(&covered),
        "the model covers {covered} of the picture"
    );
    // Deterministic: the same bytes again.
    let png2 = dir.path("torus2.png");
    run(&[
        "render",
        "-q",
        pt.to_str().unwrap(),
        png2.to_str().unwrap(),
        "--size",
        "320x240",
    ]);
    assert_eq!(std::fs::read(&png).unwrap(), std::fs::read(&png2).unwrap());
    // Coloured, with edges and a legend, z up.
    for color in ["willmore", "mean-curvature", "mobius-regularity"] {
        let p = dir.path(&format!("{color}.png"));
        let o = run(&[
            "render",
            "-q",
            pt.to_str().unwrap(),
            p.to_str().unwrap(),
            "--color",
            color,
            "--edges",
            "on",
            "--up",
            "z",
            "--size",
            "400x300",
        ]);
        assert_eq!(code(&o), 0, "{color}: {}", stderr(&o));
        let (w, h, rgb) = decode_png(&p);
        assert_eq!((w, h), (400, 300));
        let (var, _) = picture_stats(w, h, &rgb);
        assert!(var > 100.0, "{color}: {var}");
    }
    // Highlight lines: dark bands on the surface that the plain rendering does not have.
    let dark = |p: &std::path::Path| {
        let (_, _, rgb) = decode_png(p);
        rgb.chunks(3).filter(|c| c.iter().all(|&x| x < 40)).count()
    };
    let hl = dir.path("highlight.png");
    let o = run(&[
        "render",
        "-q",
        pt.to_str().unwrap(),
        hl.to_str().unwrap(),
        "--color",
        "highlight",
        "--size",
        "320x240",
    ]);
    assert_eq!(code(&o), 0, "highlight: {}", stderr(&o));
    let (lines, plain) = (dark(&hl), dark(&png));
    assert!(
        lines > plain + 320 * 240 / 200,
        "dark pixels: highlight {lines}, plain {plain}"
    );
}

#[test]
fn render_shared_bunny() {
    let Some(dir) = shared_meshes("cli::commands::render_shared_bunny") else {
        return;
    };
    let tmp = TempDir::new("render-bunny");
    let png = tmp.path("bunny.png");
    let o = run(&[
        "render",
        dir.join("bunny.off").to_str().unwrap(),
        png.to_str().unwrap(),
        "--color",
        "willmore",
        "--size",
        "480x360",
    ]);
    assert_eq!(code(&o), 0, "{}", stderr(&o));
    let (w, h, rgb) = decode_png(&png);
    assert_eq!((w, h), (480, 360));
    let (var, covered) = picture_stats(w, h, &rgb);
    assert!(var > 100.0 && covered > 0.1, "{var} {covered}");
}

#[test]
fn check_reports_json() {
    let dir = TempDir::new("check");
    let p = dir.path("t.off");
    let mut m = torus(8, 6, 2.0, 0.5);
    m.positions.push([9.0, 9.0, 9.0]); // unreferenced: a warning
    m.write_off(&p);
    let o = run(&["check", "--json", p.to_str().unwrap()]);
    assert_eq!(code(&o), 1);
    let j = json_of(&o);
    assert_eq!(j["errors"], 0);
    assert_eq!(j["warnings"], 1);
    assert_eq!(j["findings"][0]["kind"], "unreferenced-vertex");
    assert_eq!(j["findings"][0]["count"], 1);
    assert!(j["findings"][0]["examples"][0]
        .as_str()
        .unwrap()
        .contains("t.off:51: vertex 48"));
}
