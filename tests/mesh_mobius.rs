//! Canonical Möbius subdivision of meshes (seed 000 §4–5), checked against what the paper
//! proves: sphere reproduction, Möbius equivariance, reproduction of Möbius regularity, and
//! agreement with the linear scheme on regular planar grids.
#![allow(
    clippy::indexing_slicing,
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic
)]

mod common;

use common::*;
use nlsubdiv::mesh::{MeshOut, Topology};
use nlsubdiv::metrics::mobius_regularity;
use nlsubdiv::mobius::MobiusMap;
use nlsubdiv::scheme::mobius;
use nlsubdiv::scheme::{self, Options, Report, Scheme, Scratch};
use nlsubdiv::{Point, Status};

/// One Möbius step ([`mobius_subdivide`] of the shared test support).
fn msub(s: Scheme, m: &OwnedMesh, strict: bool) -> nlsubdiv::Result<(OwnedMesh, Report)> {
    mobius_subdivide(s, m, strict)
}

/// One step of the paper's literal rules (`Options::literal`: no fold guard), for the
/// properties the paper proves for them on every mesh (Möbius equivariance, independence of
/// the numbering) and for the fallback reports, which the guard would precede. The guarded
/// default mode has its own tests in `tests/mesh_fold_guard.rs`.
fn msub_lit(s: Scheme, m: &OwnedMesh, strict: bool) -> nlsubdiv::Result<(OwnedMesh, Report)> {
    run(
        m,
        &Options::new(s).mobius(true).literal(true).strict(strict),
    )
}

fn msub_n(s: Scheme, m: &OwnedMesh, levels: usize) -> (OwnedMesh, u32) {
    msub_n_mode(s, m, levels, false)
}

fn msub_n_mode(s: Scheme, m: &OwnedMesh, levels: usize, literal: bool) -> (OwnedMesh, u32) {
    let mut cur = m.clone();
    let mut fallbacks = 0;
    for _ in 0..levels {
        let step = if literal { msub_lit } else { msub };
        let (next, r) = step(s, &cur, false).unwrap_or_else(|e| panic!("{s:?}: {e}"));
        fallbacks += r.fallbacks;
        cur = next;
    }
    (cur, fallbacks)
}

fn norm(p: Point) -> f64 {
    (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt()
}

fn dist(a: Point, b: Point) -> f64 {
    norm([a[0] - b[0], a[1] - b[1], a[2] - b[2]])
}

fn diameter(m: &OwnedMesh) -> f64 {
    let (mut lo, mut hi) = ([f64::MAX; 3], [f64::MIN; 3]);
    for p in &m.positions {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    dist(lo, hi)
}

/// Whether the Möbius driver accepts `m` for `s` (schemes without a Möbius form never).
fn accepts(s: Scheme, m: &OwnedMesh) -> bool {
    let mut scratch = vec![0u32; scheme::plan_scratch_size(&m.view()).unwrap()];
    s.has_mobius_form()
        && scheme::plan(m.view(), &Options::new(s).mobius(true), &mut scratch).is_ok()
}

/// SplitMix64 in [-1, 1).
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }
    fn unit(&mut self) -> Point {
        loop {
            let p = [self.next(), self.next(), self.next()];
            let n = norm(p);
            if n > 0.1 && n < 1.0 {
                return [p[0] / n, p[1] / n, p[2] / n];
            }
        }
    }
}

/// A random Möbius map with an inversion whose centre lies outside the mesh's bounding
/// sphere (at 1.3–2 bounding radii from its centre), composed with a random similarity.
fn random_mobius(m: &OwnedMesh, rng: &mut Rng) -> MobiusMap {
    let n = m.positions.len() as f64;
    let mut c = [0.0; 3];
    for p in &m.positions {
        for k in 0..3 {
            c[k] += p[k] / n;
        }
    }
    let r = m.positions.iter().map(|&p| dist(p, c)).fold(0.0, f64::max);
    let dir = rng.unit();
    let t = r * (1.65 + 0.35 * rng.next());
    let centre = [c[0] + t * dir[0], c[1] + t * dir[1], c[2] + t * dir[2]];
    MobiusMap::inversion(centre, r * (1.0 + 0.5 * rng.next().abs()))
        .compose(&MobiusMap::rotation(rng.unit(), 3.0 * rng.next()))
        .compose(&MobiusMap::scaling(0.5 + rng.next().abs()))
}

fn map_mesh(m: &OwnedMesh, f: &MobiusMap) -> OwnedMesh {
    m.map_positions(|p| f.apply(p).unwrap())
}

const ALL: [Scheme; 10] = Scheme::ALL;

/// Project a mesh's vertices onto the unit sphere around the origin.
fn onto_sphere(m: &OwnedMesh) -> OwnedMesh {
    m.map_positions(|p| {
        let n = norm(p);
        [p[0] / n, p[1] / n, p[2] / n]
    })
}

/// Generated meshes on the unit sphere, and the shared `sphere_*.off` meshes (`test` names
/// the caller for the skip report when those are missing).
fn spherical_meshes(test: &str) -> Vec<(String, OwnedMesh)> {
    let mut v = vec![
        (
            "cube on the sphere".to_string(),
            onto_sphere(&cube().map_positions(|p| [p[0] - 0.5, p[1] - 0.5, p[2] - 0.5])),
        ),
        (
            "tetrahedron on the sphere".to_string(),
            onto_sphere(&tetrahedron().map_positions(|p| [p[0] - 0.25, p[1] - 0.25, p[2] - 0.25])),
        ),
        (
            "bipyramid(7) on the sphere".to_string(),
            onto_sphere(&bipyramid(7)),
        ),
    ];
    if let Some(dir) = shared_meshes_partly(test, "the shared sphere_*.off meshes") {
        for f in off_files(&dir) {
            let name = f.file_name().unwrap().to_string_lossy().to_string();
            if name.starts_with("sphere_") {
                v.push((name, read_off(&f).unwrap()));
            }
        }
    }
    v
}

#[test]
fn every_mobius_scheme_reproduces_spheres() {
    let mut rng = Rng(7);
    let mut worst: f64 = 0.0;
    let mut runs = 0;
    for (name, m) in spherical_meshes("mesh_mobius::every_mobius_scheme_reproduces_spheres") {
        // The mesh itself and a random Möbius image of it (another sphere).
        let f = random_mobius(&m, &mut rng);
        let image = map_mesh(&m, &f);
        // The image sphere: through the images of four vertices.
        let (cen, rad) = sphere_through(&image.positions);
        for s in ALL {
            if !accepts(s, &m) {
                continue;
            }
            for (mesh, c, r) in [(&m, [0.0; 3], 1.0), (&image, cen, rad)] {
                let (out, _) = msub_n(s, mesh, 3);
                let dev = out
                    .positions
                    .iter()
                    .map(|&p| (dist(p, c) - r).abs() / r)
                    .fold(0.0, f64::max);
                // Target 1e-12 (the figure). Measured exceptions, only Butterfly on the
                // most irregular mesh (sphere_icosphere3_strong, up to 2.6e-12), where the
                // rule extrapolates (edge points up to 22 edge lengths from their edge) and
                // amplifies the inputs' last-bit rounding: the exact rule on the same double
                // inputs is as far off (docs/RESULTS.md, "Why two sphere runs stay above
                // 1e-12"). Printed, and bounded here.
                if dev >= 1e-12 {
                    println!("ABOVE 1e-12: {name}, {s:?}: {dev:.2e}");
                }
                assert!(dev < 2e-11, "{name}, {s:?}: off the sphere by {dev:e}");
                worst = worst.max(dev);
                runs += 1;
            }
        }
    }
    println!("sphere reproduction: {runs} runs of 3 levels, worst relative deviation {worst:.2e}");
}

/// The least-squares sphere `|p|² = 2 c·p + k` through cospherical points (normal equations,
/// Gaussian elimination with partial pivoting), as (centre, radius).
#[allow(clippy::needless_range_loop)] // a 4×5 elimination reads best with indices
fn sphere_through(p: &[Point]) -> (Point, f64) {
    let mut a = [[0.0f64; 5]; 4];
    for q in p {
        let row = [2.0 * q[0], 2.0 * q[1], 2.0 * q[2], 1.0];
        let rhs = q[0] * q[0] + q[1] * q[1] + q[2] * q[2];
        for i in 0..4 {
            for j in 0..4 {
                a[i][j] += row[i] * row[j];
            }
            a[i][4] += row[i] * rhs;
        }
    }
    for col in 0..4 {
        let piv = (col..4)
            .max_by(|&x, &y| a[x][col].abs().total_cmp(&a[y][col].abs()))
            .unwrap();
        a.swap(col, piv);
        for r in 0..4 {
            if r != col {
                let f = a[r][col] / a[col][col];
                for k in col..5 {
                    a[r][k] -= f * a[col][k];
                }
            }
        }
    }
    let x: Vec<f64> = (0..4).map(|i| a[i][4] / a[i][i]).collect();
    let cen = [x[0], x[1], x[2]];
    let r = (x[3] + cen[0] * cen[0] + cen[1] * cen[1] + cen[2] * cen[2]).sqrt();
    (cen, r)
}

/// Generated meshes and a dozen shared ones of every face kind (`test` names the caller for
/// the skip report when those are missing).
fn equivariance_meshes(test: &str) -> Vec<(String, OwnedMesh)> {
    let mut v = vec![
        (
            "jittered quad torus".to_string(),
            jitter(&quad_torus(8, 6, 2.0, 0.7), 0.05, 3),
        ),
        (
            "jittered tri torus".to_string(),
            jitter(&tri_torus(8, 6), 0.05, 4),
        ),
        (
            "jittered open quad grid".to_string(),
            jitter(&quad_grid(5, 4), 0.1, 5),
        ),
        (
            "jittered open tri grid".to_string(),
            jitter(&tri_grid(5, 4), 0.1, 6),
        ),
        ("prism(5)".to_string(), prism(5)),
    ];
    let names = [
        "cube.off",
        "tetrahedron.off",
        "icosahedron.off",
        "hexagon_pyramid.off",
        "pyramid_mixed.off",
        "house_pentagons.off",
        "cross_quad.off",
        "spot_control.off",
        "torus_quad.off",
        "toroidal_tet_tri.off",
        "dome_polygon_pattern.off",
        "rhombitruncated_cuboctahedron.off",
    ];
    if let Some(dir) = shared_meshes_partly(test, "the shared meshes (cube.off, ...)") {
        for n in names {
            let path = dir.join(n);
            match read_off(&path) {
                Ok(m) => {
                    validate(&m).unwrap_or_else(|e| panic!("{n}: {e}"));
                    v.push((n.to_string(), m));
                }
                Err(e) => skip(
                    test,
                    &format!("{} not readable ({e}); not checked", path.display()),
                ),
            }
        }
    }
    v
}

#[test]
fn every_mobius_scheme_commutes_with_mobius_maps() {
    let mut rng = Rng(11);
    let mut worst: f64 = 0.0;
    let (mut runs, mut meshes) = (0, 0);
    for (name, m) in
        equivariance_meshes("mesh_mobius::every_mobius_scheme_commutes_with_mobius_maps")
    {
        meshes += 1;
        for s in ALL {
            if !accepts(s, &m) {
                continue;
            }
            let f = random_mobius(&m, &mut rng);
            // The paper's rules are equivariant on every mesh; the fold guard gives up
            // equivariance at the stars it distrusts (by design: its fallback ends at the
            // linear rule), but which elements it changes is Möbius-invariant.
            let (a, fa) = msub_lit(s, &map_mesh(&m, &f), false).unwrap();
            let (b, fb) = msub_lit(s, &m, false).unwrap();
            assert_eq!(
                (fa.fallbacks, fb.fallbacks),
                (0, 0),
                "{name} {s:?}: fallbacks"
            );
            let (ga, ra) = msub(s, &map_mesh(&m, &f), false).unwrap();
            let (gb, rb) = msub(s, &m, false).unwrap();
            assert_eq!(
                (ra.guarded, ra.first_guarded),
                (rb.guarded, rb.first_guarded),
                "{name} {s:?}: the guard changes other elements on a Möbius image"
            );
            if rb.guarded == 0 {
                assert_eq!(ga.positions, a.positions, "{name} {s:?}: image");
                assert_eq!(gb.positions, b.positions, "{name} {s:?}");
            }
            let fb_mapped = map_mesh(&b, &f);
            let scale = diameter(&a);
            let err = a
                .positions
                .iter()
                .zip(&fb_mapped.positions)
                .map(|(&p, &q)| dist(p, q) / scale)
                .fold(0.0, f64::max);
            assert!(err < 1e-9, "{name}, {s:?}: equivariance error {err:e}");
            worst = worst.max(err);
            runs += 1;
        }
    }
    println!("Möbius equivariance: {meshes} meshes, {runs} (mesh, scheme) runs, worst relative error {worst:.2e}");
}

/// Interior output vertices of a subdivided grid: those farther than `margin` from the
/// grid's outline in the parameter plane.
fn interior_mask(m: &OwnedMesh, lo: f64, hi_x: f64, hi_y: f64, margin: f64) -> Vec<bool> {
    m.positions
        .iter()
        .map(|p| {
            p[0] > lo + margin && p[0] < hi_x - margin && p[1] > lo + margin && p[1] < hi_y - margin
        })
        .collect()
}

#[test]
fn regular_grids_match_the_linear_scheme_and_stay_mobius_regular_under_mobius_maps() {
    let mut rng = Rng(23);
    let mut worst_lin: f64 = 0.0;
    let mut worst_map: f64 = 0.0;
    let mut worst_mr: f64 = 0.0;
    let n = 8;
    let quads = quad_grid(n, n);
    // An equilateral lattice (tri_grid's diagonals run from (i, j) to (i + 1, j + 1)); the
    // interior mask below uses the unsheared parameter positions, which index the same vertices.
    let s3 = 3f64.sqrt() / 2.0;
    let tris_param = tri_grid(n, n);
    let tris = tris_param.map_positions(|p| [p[0] - 0.5 * p[1], s3 * p[1], 0.0]);
    for s in ALL {
        let grid = if accepts(s, &quads) && s != Scheme::Loop && s != Scheme::ModifiedButterfly {
            &quads
        } else {
            &tris
        };
        if !accepts(s, grid) {
            continue;
        }
        let param = if grid == &quads { &quads } else { &tris_param };
        let (hx, hy) = param
            .positions
            .iter()
            .fold((0.0f64, 0.0f64), |(x, y), p| (x.max(p[0]), y.max(p[1])));
        // Linear and Möbius coincide on the planar regular grid (away from the boundary,
        // where the Möbius curve rules differ from the linear ones at the corners).
        let lin = subdivide(s, grid).unwrap();
        let (mob, rep) = msub(s, grid, false).unwrap();
        assert_eq!(rep.fallbacks, 0, "{s:?}");
        let mask = interior_mask(&subdivide(s, param).unwrap(), 0.0, hx, hy, 2.01);
        for (i, (&p, &q)) in lin.positions.iter().zip(&mob.positions).enumerate() {
            if mask[i] {
                let e = dist(p, q);
                assert!(e < 1e-12, "{s:?}: Möbius ≠ linear at {i} by {e:e}");
                worst_lin = worst_lin.max(e);
            }
        }
        // Under a Möbius map: Möbius(M grid) = M linear(grid) away from the boundary.
        let f = random_mobius(grid, &mut rng);
        let (mm, _) = msub(s, &map_mesh(grid, &f), false).unwrap();
        let expect = map_mesh(&lin, &f);
        let scale = diameter(&expect);
        for (i, (&p, &q)) in mm.positions.iter().zip(&expect.positions).enumerate() {
            if mask[i] {
                let e = dist(p, q) / scale;
                assert!(
                    e < 1e-10,
                    "{s:?}: regular grid under a Möbius map off by {e:e} at {i}"
                );
                worst_map = worst_map.max(e);
            }
        }
        // And the subdivided image is Möbius regular at its interior vertices.
        if s.pattern().keeps_old_vertices() {
            with_topology(&mm, |t| {
                for v in 0..t.num_vertices() as u32 {
                    if !mask[v as usize]
                        || t.is_boundary_vertex(v).unwrap()
                        || t.is_isolated(v).unwrap()
                    {
                        continue;
                    }
                    let ring: Vec<Point> = t
                        .ring(v)
                        .unwrap()
                        .iter()
                        .map(|&u| t.position(u).unwrap())
                        .collect();
                    if ring.len() != if grid == &quads { 4 } else { 6 } {
                        continue;
                    }
                    let mr = mobius_regularity(t.position(v).unwrap(), &ring, true).unwrap();
                    assert!(mr < 1e-10, "{s:?}: Möbius regularity defect {mr:e} at {v}");
                    worst_mr = worst_mr.max(mr);
                }
            })
            .unwrap();
        }
    }
    println!(
        "regular grids: Möbius vs linear {worst_lin:.2e}; under a Möbius map {worst_map:.2e} (relative); regularity defect {worst_mr:.2e}"
    );
}

#[test]
fn degenerate_stars_fall_back_and_strict_mode_refuses() {
    // Two coincident vertices on a closed mesh: the stars that contain the zero-length edge
    // have no canonical form.
    let mut m = onto_sphere(&cube().map_positions(|p| [p[0] - 0.5, p[1] - 0.5, p[2] - 0.5]));
    m.positions[1] = m.positions[0];
    for s in [
        Scheme::CatmullClark,
        Scheme::DooSabin,
        Scheme::Simplest,
        Scheme::Dual,
        Scheme::Kobbelt,
    ] {
        // Literal rules: the guard distrusts these stars too, and its strict refusal would
        // come first (tests/mesh_fold_guard.rs).
        let (out, rep) = msub_lit(s, &m, false).unwrap();
        assert!(rep.fallbacks > 0, "{s:?}: no fallback reported");
        assert!((rep.first_fallback as usize) < out.positions.len());
        assert!(out
            .positions
            .iter()
            .all(|p| p.iter().all(|c| c.is_finite())));
        let e = msub_lit(s, &m, true).unwrap_err();
        assert_eq!(e.status, Status::FallbackInStrictMode, "{s:?}");
        assert_eq!(
            e.element, rep.first_fallback,
            "{s:?}: strict names the first fallback"
        );
    }
}

#[test]
fn interpolating_mobius_schemes_keep_old_vertices_bit_exact() {
    let m = jitter(&tri_torus(8, 6), 0.05, 9);
    let (out, _) = msub(Scheme::ModifiedButterfly, &m, false).unwrap();
    assert_eq!(&out.positions[..m.positions.len()], &m.positions[..]);
    let q = jitter(&quad_torus(8, 6, 2.0, 0.7), 0.05, 10);
    for s in [Scheme::Kobbelt, Scheme::VertexInsertion] {
        let (out, _) = msub(s, &q, false).unwrap();
        assert_eq!(
            &out.positions[..q.positions.len()],
            &q.positions[..],
            "{s:?}"
        );
    }
}

#[test]
fn same_input_same_bits() {
    let m = jitter(&quad_torus(8, 6, 2.0, 0.7), 0.05, 12);
    for s in [Scheme::CatmullClark, Scheme::Kobbelt, Scheme::DooSabin] {
        let (a, _) = msub(s, &m, false).unwrap();
        let (b, _) = msub(s, &m, false).unwrap();
        assert_eq!(hash(&a), hash(&b));
    }
}

/// Seed 000 Table 2 and Fig. 9 on tori (no boundary): the maximal edge length shrinks by a
/// rate `10^(−s)` close to 2 (the paper measures 1.79–1.87), and the mean tangent-polygon
/// Willmore energy falls at every level.
#[test]
fn mobius_schemes_contract_and_lower_the_willmore_energy() {
    let quads = jitter(&quad_torus(10, 8, 2.0, 0.8), 0.03, 31);
    let tris = jitter(&tri_torus(10, 8), 0.03, 32);
    for (s, m) in [
        (Scheme::CatmullClark, &quads),
        (Scheme::Kobbelt, &quads),
        (Scheme::Loop, &tris),
        (Scheme::ModifiedButterfly, &tris),
    ] {
        let mut cur = m.clone();
        let (mut len, mut wil) = (vec![max_edge(&cur)], vec![mean_willmore(&cur)]);
        for _ in 0..3 {
            cur = msub(s, &cur, false).unwrap().0;
            len.push(max_edge(&cur));
            wil.push(mean_willmore(&cur));
        }
        let n = len.len() as f64;
        let ys: Vec<f64> = len.iter().map(|l| l.log10()).collect();
        let mx = (n - 1.0) / 2.0;
        let my = ys.iter().sum::<f64>() / n;
        let slope = ys
            .iter()
            .enumerate()
            .map(|(i, y)| (i as f64 - mx) * (y - my))
            .sum::<f64>()
            / (0..len.len()).map(|i| (i as f64 - mx).powi(2)).sum::<f64>();
        let rate = 10f64.powf(-slope);
        println!("{s:?}: max edge {len:.3?}, rate {rate:.3}, mean Willmore {wil:.3?}");
        assert!((1.6..2.2).contains(&rate), "{s:?}: rate {rate}");
        assert!(
            wil.windows(2).all(|w| w[1] < w[0]),
            "{s:?}: Willmore {wil:?}"
        );
    }
}

#[test]
fn mobius_levels_equal_repeated_steps() {
    let meshes = [
        jitter(&quad_torus(6, 5, 2.0, 0.7), 0.05, 21),
        jitter(&tri_grid(4, 3), 0.05, 22),
        jitter(&quad_grid(3, 3), 0.05, 23),
        onto_sphere(&cube().map_positions(|p| [p[0] - 0.5, p[1] - 0.5, p[2] - 0.5])),
    ];
    let mut runs = 0;
    for m in &meshes {
        for s in Scheme::ALL {
            if !accepts(s, m) {
                continue;
            }
            for levels in 0..=3usize {
                let opts = Options::new(s).mobius(true).levels(levels);
                let mut su = vec![0u32; scheme::plan_scratch_size(&m.view()).unwrap()];
                let Ok(p) = scheme::plan(m.view(), &opts, &mut su) else {
                    continue; // a later level above the valence capacity
                };
                let sizes = p.output();
                su.resize(p.scratch.u32s, 0);
                let mut sp = vec![[0.0; 3]; p.scratch.points];
                let mut out = OwnedMesh {
                    positions: vec![[f64::NAN; 3]; sizes.vertices],
                    offsets: vec![u32::MAX; sizes.faces + 1],
                    indices: vec![u32::MAX; sizes.indices],
                };
                let rep = scheme::subdivide(
                    m.view(),
                    &opts,
                    Scratch::new(&mut su, &mut sp),
                    &mut MeshOut::new(&mut out.positions, &mut out.offsets, &mut out.indices),
                )
                .unwrap();
                assert_eq!(rep.sizes, sizes);
                let (want, fallbacks) = msub_n(s, m, levels);
                assert_eq!(hash(&out), hash(&want), "{s:?} x{levels}");
                assert_eq!(rep.fallbacks, fallbacks, "{s:?} x{levels}");
                assert_eq!(rep.first_fallback_level == 0, fallbacks == 0);
                runs += 1;
                // One point too few is refused before anything is computed.
                if let Some(short) = sp.len().checked_sub(1) {
                    let e = scheme::subdivide(
                        m.view(),
                        &opts,
                        Scratch::new(&mut su, &mut sp[..short]),
                        &mut MeshOut::new(&mut out.positions, &mut out.offsets, &mut out.indices),
                    )
                    .unwrap_err();
                    assert_eq!((e.status, e.needed), (Status::BufferTooSmall, sp.len()));
                }
                // One `u32` too few (the spoke workspace is its last part) likewise.
                if let Some(short) = su.len().checked_sub(1) {
                    let e = scheme::subdivide(
                        m.view(),
                        &opts,
                        Scratch::new(&mut su[..short], &mut sp),
                        &mut MeshOut::new(&mut out.positions, &mut out.offsets, &mut out.indices),
                    )
                    .unwrap_err();
                    assert_eq!((e.status, e.needed), (Status::BufferTooSmall, su.len()));
                }
            }
        }
    }
    assert!(runs >= 80, "{runs} runs");
}

#[test]
fn mobius_levels_report_the_first_fallback_and_strict_refuses() {
    let mut m = onto_sphere(&cube().map_positions(|p| [p[0] - 0.5, p[1] - 0.5, p[2] - 0.5]));
    m.positions[1] = m.positions[0];
    let s = Scheme::CatmullClark;
    // Literal rules: the guard's refusal would come first (tests/mesh_fold_guard.rs).
    let opts = Options::new(s).mobius(true).literal(true).levels(2);
    let mut su = vec![0u32; 4096];
    let p = scheme::plan(m.view(), &opts, &mut su).unwrap();
    let mut sp = vec![[0.0; 3]; p.scratch.points];
    let sizes = p.output();
    let mut out = OwnedMesh {
        positions: vec![[f64::NAN; 3]; sizes.vertices],
        offsets: vec![u32::MAX; sizes.faces + 1],
        indices: vec![u32::MAX; sizes.indices],
    };
    let run = |strict: bool, su: &mut [u32], sp: &mut [Point], out: &mut OwnedMesh| {
        scheme::subdivide(
            m.view(),
            &opts.strict(strict),
            Scratch::new(su, sp),
            &mut MeshOut::new(&mut out.positions, &mut out.offsets, &mut out.indices),
        )
    };
    let rep = run(false, &mut su, &mut sp, &mut out).unwrap();
    let (_, first) = msub_lit(s, &m, false).unwrap();
    assert!(first.fallbacks > 0);
    assert_eq!(rep.first_fallback_level, 1);
    assert_eq!(rep.first_fallback, first.first_fallback);
    assert!(rep.fallbacks >= first.fallbacks);
    let e = run(true, &mut su, &mut sp, &mut out).unwrap_err();
    assert_eq!(
        (e.status, e.element),
        (Status::FallbackInStrictMode, first.first_fallback)
    );
}

/// The star of `v` as a host would hand it to the star rules: the ring (star order), for
/// each spoke with a face that face's corners in face order (CSR), the diagonal of each such
/// face (the corner after the spoke's neighbour), and whether the star is closed.
struct HostStar {
    ring: Vec<Point>,
    offsets: Vec<u32>,
    corners: Vec<Point>,
    diagonals: Vec<Point>,
    irregular: Vec<bool>,
    closed: bool,
}

fn star_of(t: &Topology<'_, '_>, v: u32) -> HostStar {
    let mut h = HostStar {
        ring: Vec::new(),
        offsets: vec![0],
        corners: Vec::new(),
        diagonals: Vec::new(),
        irregular: Vec::new(),
        closed: !t.is_boundary_vertex(v).unwrap(),
    };
    for s in t.star(v) {
        h.ring.push(t.position(s.neighbour).unwrap());
        h.irregular.push(
            !t.is_boundary_vertex(s.neighbour).unwrap() && t.valence(s.neighbour).unwrap() != 6,
        );
        if s.face != nlsubdiv::mesh::NONE {
            for &u in t.face_vertices(s.face).unwrap() {
                h.corners.push(t.position(u).unwrap());
            }
            h.offsets.push(h.corners.len() as u32);
            let d = t.dest(t.next(s.half_edge).unwrap()).unwrap();
            h.diagonals.push(t.position(d).unwrap());
        }
    }
    h
}

/// What a star rule gives: the vertex point, one value per spoke (edge candidates, Kobbelt's
/// points beyond the centre), one value per face (face candidates, Doo–Sabin's corner
/// points).
type StarRule = (Option<Point>, Vec<Point>, Vec<Point>);

/// The public star rule of `s` at vertex `v`, on the star as a host gives it; `None` when it
/// fails.
fn star_rule(s: Scheme, t: &Topology<'_, '_>, v: u32) -> Option<StarRule> {
    let h = star_of(t, v);
    let p = t.position(v).unwrap();
    let mut e = vec![[0.0; 3]; h.ring.len()];
    let mut f = vec![[0.0; 3]; h.offsets.len() - 1];
    let vp = match s {
        Scheme::Loop => mobius::loop_star(p, &h.ring, h.closed, &mut e),
        Scheme::CatmullClark => {
            mobius::catmull_clark_star(p, &h.ring, h.closed, &h.offsets, &h.corners, &mut e, &mut f)
        }
        Scheme::ModifiedButterfly => {
            mobius::butterfly_star(p, &h.ring, h.closed, &h.irregular, &mut e).map(|()| None)
        }
        Scheme::Kobbelt => {
            let d: &[Point] = if h.closed { &h.diagonals } else { &[] };
            mobius::kobbelt_star(p, &h.ring, h.closed, d, &mut e).map(|()| None)
        }
        Scheme::DooSabin => {
            mobius::doo_sabin_star(p, &h.ring, h.closed, &h.offsets, &h.corners, &mut f)
                .map(|()| None)
        }
        _ => unreachable!("{s:?} has no star rule"),
    };
    vp.ok().map(|vp| (vp, e, f))
}

/// The value of the spoke from `v` to `u` in `v`'s star rule.
fn candidate(
    t: &Topology<'_, '_>,
    v: u32,
    u: u32,
    rule: &dyn Fn(u32) -> Option<StarRule>,
) -> Point {
    let Some((_, edges, _)) = rule(v) else {
        return [f64::NAN; 3];
    };
    let j = t.star(v).position(|s| s.neighbour == u).unwrap();
    edges[j]
}

/// Whether `u` is an ear: a boundary vertex with one face (the drivers evaluate what it
/// contributes to its face in another corner's form).
fn is_ear(t: &Topology<'_, '_>, u: u32) -> bool {
    t.is_boundary_vertex(u).unwrap() && t.vertex_face_count(u).unwrap() == 1
}

#[test]
fn star_rules_reproduce_the_driver_bit_for_bit() {
    use nlsubdiv::blend::{f4_hinted, face_point_with_ids};
    let centred_cube =
        || onto_sphere(&cube().map_positions(|p| [p[0] - 0.5, p[1] - 0.5, p[2] - 0.5]));
    let cases = [
        (Scheme::Loop, jitter(&tri_torus(7, 5), 0.05, 31)),
        (Scheme::Loop, jitter(&tri_grid(4, 4), 0.05, 32)),
        (Scheme::Loop, onto_sphere(&bipyramid(7))),
        (
            Scheme::CatmullClark,
            jitter(&quad_torus(7, 5, 2.0, 0.7), 0.05, 33),
        ),
        (Scheme::CatmullClark, jitter(&quad_grid(4, 3), 0.05, 34)),
        (Scheme::CatmullClark, jitter(&prism(5), 0.05, 35)),
        (Scheme::CatmullClark, centred_cube()),
        (
            Scheme::ModifiedButterfly,
            jitter(&tri_torus(7, 5), 0.05, 36),
        ),
        (Scheme::ModifiedButterfly, jitter(&tri_grid(4, 4), 0.05, 37)),
        (Scheme::ModifiedButterfly, onto_sphere(&bipyramid(7))),
        (
            Scheme::Kobbelt,
            jitter(&quad_torus(7, 5, 2.0, 0.7), 0.05, 38),
        ),
        (Scheme::Kobbelt, jitter(&quad_grid(4, 3), 0.05, 39)),
        (Scheme::Kobbelt, centred_cube()),
        (
            Scheme::DooSabin,
            jitter(&quad_torus(7, 5, 2.0, 0.7), 0.05, 40),
        ),
        (Scheme::DooSabin, jitter(&quad_grid(4, 3), 0.05, 41)),
        (Scheme::DooSabin, jitter(&prism(5), 0.05, 42)),
        (Scheme::DooSabin, centred_cube()),
    ];
    // Per scheme: vertex points, edge points, face points (corner points for Doo–Sabin).
    let mut checked: Vec<(Scheme, [usize; 3])> = Vec::new();
    for (s, m) in &cases {
        // The paper's rules: the star-rule exports are the paper's rules, and the default's
        // fold guard changes the driver's output wherever it distrusts a star
        // (`mesh_fold_guard.rs`; on the jittered 4×4 grid with Butterfly, 19 output vertices).
        let (out, rep) = msub_lit(*s, m, false).unwrap();
        assert_eq!(rep.fallbacks, 0, "{s:?}");
        let mut count = [0usize; 3];
        with_topology(m, |t| {
            let nv = t.num_vertices();
            let ne = t.num_edges();
            let rule = |v: u32| star_rule(*s, t, v);
            if matches!(s, Scheme::Loop | Scheme::CatmullClark) {
                for v in 0..nv as u32 {
                    if t.is_boundary_vertex(v).unwrap() {
                        continue;
                    }
                    let (vp, _, _) = rule(v).unwrap();
                    assert_eq!(vp.unwrap(), out.positions[v as usize], "{s:?} vertex {v}");
                    count[0] += 1;
                }
            }
            if *s != Scheme::DooSabin {
                for e in 0..ne as u32 {
                    if t.is_boundary_edge(e).unwrap() {
                        continue;
                    }
                    let h = t.edge_half_edge(e).unwrap();
                    let (a, b) = (t.origin(h).unwrap(), t.dest(h).unwrap());
                    let (ca, cb) = (candidate(t, a, b, &rule), candidate(t, b, a, &rule));
                    let hint = t.position(t.dest(t.next(h).unwrap()).unwrap()).unwrap();
                    let (pa, pb) = (t.position(a).unwrap(), t.position(b).unwrap());
                    let p = if *s == Scheme::Kobbelt {
                        // The points beyond both ends of the edge's grid line.
                        f4_hinted(ca, pa, pb, cb, hint).unwrap()
                    } else {
                        match (ca[0].is_nan(), cb[0].is_nan()) {
                            (false, false) => f4_hinted(pa, ca, cb, pb, hint).unwrap(),
                            (false, true) => ca,
                            (true, false) => cb,
                            (true, true) => panic!("{s:?}: no candidate for edge {e}"),
                        }
                    };
                    assert_eq!(p, out.positions[nv + e as usize], "{s:?} edge {e}");
                    count[1] += 1;
                }
            }
            if *s == Scheme::CatmullClark {
                for f in 0..t.num_faces() as u32 {
                    let ids = t.face_vertices(f).unwrap();
                    if ids.iter().any(|&u| is_ear(t, u)) {
                        continue; // ears take a substitute's form (documented)
                    }
                    let verts: Vec<Point> = ids.iter().map(|&u| t.position(u).unwrap()).collect();
                    let cands: Vec<Point> = ids
                        .iter()
                        .map(|&u| {
                            let (_, _, fc) = rule(u).unwrap();
                            let j = t.star(u).position(|sp| sp.face == f).unwrap();
                            fc[j]
                        })
                        .collect();
                    let p = face_point_with_ids(&verts, &cands, ids).unwrap();
                    assert_eq!(p, out.positions[nv + ne + f as usize], "face {f}");
                    count[2] += 1;
                }
            }
            if *s == Scheme::DooSabin {
                for h in 0..t.num_half_edges() as u32 {
                    let u = t.origin(h).unwrap();
                    if is_ear(t, u) {
                        continue; // a substitute's form (documented)
                    }
                    let (_, _, corners) = rule(u).unwrap();
                    let f = t.face(h).unwrap();
                    let j = t.star(u).position(|sp| sp.face == f).unwrap();
                    assert_eq!(corners[j], out.positions[h as usize], "corner {h}");
                    count[2] += 1;
                }
            }
        })
        .unwrap();
        match checked.iter_mut().find(|(t, _)| t == s) {
            Some((_, c)) => (0..3).for_each(|k| c[k] += count[k]),
            None => checked.push((*s, count)),
        }
    }
    println!("star rules = driver (vertices, edges, faces or corners): {checked:?}");
    for (s, c) in &checked {
        let expect = match s {
            Scheme::Loop => [true, true, false],
            Scheme::CatmullClark => [true, true, true],
            Scheme::ModifiedButterfly | Scheme::Kobbelt => [false, true, false],
            _ => [false, false, true],
        };
        for k in 0..3 {
            assert!(!expect[k] || c[k] > 50, "{s:?}: only {c:?} checked");
        }
    }
}

/// The same mesh with every face's corner list rotated by one (same faces, same orientation).
fn rotate_faces(m: &OwnedMesh) -> OwnedMesh {
    let faces: Vec<Vec<u32>> = m
        .offsets
        .windows(2)
        .map(|w| {
            let f = &m.indices[w[0] as usize..w[1] as usize];
            let mut r = f[1..].to_vec();
            r.push(f[0]);
            r
        })
        .collect();
    OwnedMesh::from_faces(m.positions.clone(), &faces)
}

/// Largest distance from a point of `a` to its nearest point of `b`, over the diameter.
fn nearest_gap(a: &OwnedMesh, b: &OwnedMesh) -> f64 {
    let scale = diameter(a);
    a.positions
        .iter()
        .map(|&p| {
            b.positions
                .iter()
                .map(|&q| dist(p, q))
                .fold(f64::INFINITY, f64::min)
        })
        .fold(0.0, f64::max)
        / scale
}

#[test]
fn guarded_boundary_stars_do_not_depend_on_vertex_numbering() {
    // The fold guard audits the boundary stars of Doo–Sabin and the simplest scheme too, and
    // each takes its own verdict only: were a boundary star lowered by its own verdict and
    // then read as interior by a distrusted neighbour after it in vertex order, its trust,
    // and the points around it, would depend on the numbering (`audit.rs`, `Driver::audit`).
    // Open, strongly bumped grids, 2 levels, each under two random renumberings: the same
    // points (up to rounding) where the guard moved some.
    let mut acted = 0;
    for seed in 0..4u64 {
        let k = seed as f64;
        let g = quad_grid(9, 7).map_positions(|p| {
            let z = (0.8 + 0.1 * k) * libm::sin((1.3 + 0.2 * k) * p[0]) * libm::cos(1.1 * p[1]);
            [p[0], p[1], z]
        });
        let m = jitter(&g, 0.2, 40 + seed);
        for s in [Scheme::DooSabin, Scheme::Simplest] {
            let (a, _) = msub_n(s, &m, 2);
            let (lit, _) = msub_n_mode(s, &m, 2, true);
            if nearest_gap(&a, &lit) > 1e-9 {
                acted += 1;
            }
            for r in [3 + seed, 17 + seed] {
                let (b, _) = msub_n(s, &renumbered(&m, r), 2);
                let gap = nearest_gap(&a, &b).max(nearest_gap(&b, &a));
                assert!(
                    gap < 1e-12,
                    "{s:?}, bump {seed}, renumbering {r}: the guarded result moves by {gap:e}"
                );
            }
        }
    }
    assert!(acted >= 4, "the guard moved points in {acted} of 8 runs");
}

#[test]
fn mobius_schemes_versus_vertex_renumbering() {
    // Ties of the §4.4.3 sort go by vertex id, so numbering can only enter through them. The
    // reversed quadruplets of an even face always tie; their chains are oriented by the face
    // (`oriented_start` in src/blend/face_point.rs), which takes the numbering out of those
    // ties. What remains are exact ties between different quadruplets, which only exactly
    // symmetric faces have (a regular tetrahedron's: the F6 chain breaks their symmetry
    // whatever the order), and Kobbelt's two grid lines, ordered and directed by edge id. So:
    // every mesh jittered by 1e-3 of its diameter must give the same result under a random
    // renumbering (Kobbelt printed, not asserted), and the unjittered meshes' figures are
    // printed. Relative to the diameter, 2 levels.
    let mut exact: Vec<(Scheme, f64)> = Vec::new();
    let mut jittered: Vec<(Scheme, f64)> = Vec::new();
    let worst =
        |v: &mut Vec<(Scheme, f64)>, s: Scheme, gap: f64| match v.iter_mut().find(|(t, _)| *t == s)
        {
            Some((_, w)) => *w = w.max(gap),
            None => v.push((s, gap)),
        };
    for (k, (name, m)) in
        equivariance_meshes("mesh_mobius::mobius_schemes_versus_vertex_renumbering")
            .into_iter()
            .enumerate()
    {
        if m.positions.len() > 400 {
            continue; // the nearest-point comparison is quadratic
        }
        let j = jitter(&m, 1e-3 * diameter(&m), 100 + k as u64);
        for (mesh, generic) in [(&m, false), (&j, true)] {
            let r = renumbered(mesh, 11 + k as u64);
            for s in ALL {
                if !s.has_mobius_form() || !accepts(s, mesh) {
                    continue;
                }
                // The paper's rules; the guard's figures are printed below (its distrusted
                // faces' candidates can nearly coincide, and the face chain then orders
                // their near-ties by vertex id).
                let (a, _) = msub_n_mode(s, mesh, 2, true);
                let (b, _) = msub_n_mode(s, &r, 2, true);
                if generic {
                    let (ga, _) = msub_n(s, mesh, 2);
                    let (gb, _) = msub_n(s, &r, 2);
                    let gap = nearest_gap(&ga, &gb).max(nearest_gap(&gb, &ga));
                    if gap >= 1e-12 {
                        println!("guarded: {name} jittered, {s:?}: renumbering moves the result by {gap:.2e}");
                    }
                }
                assert_eq!(a.positions.len(), b.positions.len(), "{name}, {s:?}");
                let gap = nearest_gap(&a, &b).max(nearest_gap(&b, &a));
                if generic {
                    assert!(
                        s == Scheme::Kobbelt || gap < 1e-12,
                        "{name} jittered, {s:?}: renumbering moves the result by {gap:e}"
                    );
                    worst(&mut jittered, s, gap);
                } else {
                    worst(&mut exact, s, gap);
                }
            }
        }
    }
    for ((s, w), (_, e)) in jittered.iter().zip(&exact) {
        println!("vertex renumbering, {s:?}: jittered meshes worst {w:.2e}; exact meshes {e:.2e}");
    }
}

#[test]
fn every_mobius_scheme_is_independent_of_where_faces_start() {
    // The §4.4.3 face-point sort breaks ties by vertex id and Kobbelt's face point orders its
    // grid lines by edge id, so listing every face from another corner changes nothing but
    // rounding (ring sums start elsewhere). Before that rule, Möbius Catmull–Clark moved the
    // tetrahedron's face points by 3.6e-2 of its diagonal.
    let mut worst: f64 = 0.0;
    let mut runs = 0;
    for (name, m) in
        equivariance_meshes("mesh_mobius::every_mobius_scheme_is_independent_of_where_faces_start")
    {
        if m.positions.len() > 400 {
            continue; // the nearest-point comparison is quadratic
        }
        let r = rotate_faces(&m);
        for s in ALL {
            if !s.has_mobius_form() || !accepts(s, &m) {
                continue;
            }
            let (a, _) = msub_n(s, &m, 2);
            let (b, _) = msub_n(s, &r, 2);
            assert_eq!(a.positions.len(), b.positions.len());
            let gap = nearest_gap(&a, &b).max(nearest_gap(&b, &a));
            assert!(
                gap < 1e-12,
                "{name}, {s:?}: face start moves the result by {gap:e}"
            );
            worst = worst.max(gap);
            runs += 1;
        }
    }
    println!("face-start independence: {runs} (mesh, scheme) runs at 2 levels, worst {worst:.2e}");
}

/// Strict mode refuses the first output vertex that the lenient run counts, whichever pass
/// computes it: Kobbelt's interior edge points run in edge ranges and its boundary edge
/// points after them, so the refusal must still name the lowest counted vertex (the one a walk
/// over the outputs in order meets first). An open grid with one vertex moved onto its
/// neighbour, at several places (interior and boundary), literal and guarded.
#[test]
fn strict_refuses_the_lowest_counted_vertex() {
    for s in [Scheme::Kobbelt, Scheme::CatmullClark, Scheme::DooSabin] {
        let mut refused = 0;
        let base = jitter(&quad_grid(5, 4), 0.05, 57);
        for (v, onto) in [(7usize, 8usize), (1, 2), (0, 1), (13, 14), (29, 28)] {
            let mut m = base.clone();
            if onto >= m.positions.len() || v >= m.positions.len() {
                continue;
            }
            m.positions[v] = m.positions[onto];
            for literal in [true, false] {
                let opts = Options::new(s).mobius(true).literal(literal);
                let lenient = run(&m, &opts);
                let strict = run(&m, &opts.strict(true));
                let Ok((_, r)) = lenient else {
                    // Refused before any rule (the same refusal in strict mode).
                    assert_eq!(lenient.unwrap_err().status, strict.unwrap_err().status);
                    continue;
                };
                let counted = r.fallbacks + r.guarded;
                if counted == 0 {
                    assert!(strict.is_ok(), "{s:?} v{v} literal {literal}");
                    continue;
                }
                let first = match (r.fallbacks, r.guarded) {
                    (0, _) => r.first_guarded,
                    (_, 0) => r.first_fallback,
                    _ => r.first_fallback.min(r.first_guarded),
                };
                let e = strict.unwrap_err();
                assert_eq!(
                    (e.status, e.element),
                    (Status::FallbackInStrictMode, first),
                    "{s:?} v{v} literal {literal}: {r:?}"
                );
                refused += 1;
            }
        }
        assert!(refused >= 4, "{s:?}: {refused} refusals");
    }
}

/// A face whose canonical centroid overflows (two corners at a point the star's form sends
/// almost to infinity) has no face candidate: NaN, never the overflowed value. Found by the
/// `primitives` fuzz target (`fuzz/regressions/primitives/cc-star-overflowing-centroid`).
#[test]
fn catmull_clark_star_gives_no_candidate_for_an_overflowing_centroid() {
    let v = [3.0517578125e-5, 5.30498947746e-313, 1.06101859786e-312];
    let mut ring = vec![
        [0.0, 0.0, 5.299808824e-315],
        [
            1.590978778e-314,
            4.5480509667887196e-305,
            4.5480509667887196e-305,
        ],
        [
            1.1125369292536007e-308,
            4.548050968908643e-305,
            1.7765824089018436e-307,
        ],
        [-1.000000000000032, 0.0, 0.0],
    ];
    ring.extend([[0.0; 3]; 89]);
    let faces = ring.len() - 1; // open star: triangles (v, ring[j], ring[j + 1])
    let offsets: Vec<u32> = (0..=faces as u32).map(|j| 3 * j).collect();
    let corners: Vec<Point> = (0..faces).flat_map(|j| [v, ring[j], ring[j + 1]]).collect();
    let mut edges = vec![[0.0; 3]; ring.len()];
    let mut face_c = vec![[0.0; 3]; faces];
    let vp =
        mobius::catmull_clark_star(v, &ring, false, &offsets, &corners, &mut edges, &mut face_c)
            .unwrap();
    assert!(
        face_c.iter().any(|p| p[0].is_nan()),
        "no face without a candidate"
    );
    for p in edges.iter().chain(face_c.iter()).chain(vp.iter()) {
        for x in p {
            assert!(
                x.is_finite() || x.is_nan(),
                "{x} in {edges:?} {face_c:?} {vp:?}"
            );
        }
    }
}
