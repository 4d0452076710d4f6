//! Kobbelt's virtual points at extraordinary vertices (Kobbelt 1996; seed 000 §4.3, Fig. 11
//! and 14), tested from the properties the construction rests on, not from recorded output:
//!
//! * the defining property: the face point of a face next to an extraordinary vertex is the
//!   same whether the 4-point rule runs across the "horizontal" or the "vertical" edge points
//!   (seed 000 §4.3 "Blending face points": the virtual points are designed so that the face
//!   point "can be computed in either direction ... as tensor product of the 4-point
//!   scheme"), on jittered 3-D spider-web meshes of valence 3..8;
//! * the edge points of the extraordinary vertex are the 4-point rule with virtual points whose
//!   differences are the ones that property forces, `r_{j+1} − r_j = q_{j−1} − q_{j+2} +
//!   ŵ (d_{j+2} − d_{j−2})`, `ŵ = w/(1/2 + w)`, and whose mean is the ring's mean;
//! * interpolation (old vertices bit for bit), valence 4 giving the real opposite neighbour,
//!   affine invariance, symmetry about `q_j`, the planar regular `n`-star in closed form;
//! * the spectrum of the local subdivision matrix (3-ring, Fourier blocks): `λ = 1/2` for
//!   valence 4 (the 4-point scheme), and for `n ≠ 4` a real subdominant pair from the
//!   `k = ±1` blocks above every other eigenvalue with a regular characteristic net (the
//!   necessary conditions of Reif's C¹ criterion);
//! * on open nets, boundary edge points depend on the boundary polygon alone (the paper's
//!   abstract: boundary curves that "allow a C0-join of several subdivision patches").
// Test code: indexing and unwrap are fine here.
#![allow(
    clippy::indexing_slicing,
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic
)]

mod common;

use common::*;
use nlsubdiv::scheme::Scheme;
use nlsubdiv::stencil::kobbelt;
use nlsubdiv::Point;
use std::collections::BTreeMap;
use std::f64::consts::PI;

/// The 4-point tension (Kobbelt 1996 uses the interpolating 4-point scheme with `w = 1/16`).
const W: f64 = 1.0 / 16.0;

fn add(a: Point, b: Point) -> Point {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
fn sub(a: Point, b: Point) -> Point {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn mul(a: Point, s: f64) -> Point {
    [a[0] * s, a[1] * s, a[2] * s]
}
fn dist(a: Point, b: Point) -> f64 {
    let d = sub(a, b);
    (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt()
}
/// The 4-point rule, written here independently of the crate.
fn f4(a: Point, b: Point, c: Point, d: Point) -> Point {
    add(mul(add(b, c), 0.5 + W), mul(add(a, d), -W))
}

// ------------------------------------------------------------------ spider-web meshes

/// `n` sectors of `k × k` quads around one vertex of valence `n`; sector `j` has grid
/// coordinates `(a, b)`, its `a` axis is grid line `j`, its `b` axis grid line `j + 1`.
struct Spider {
    n: usize,
    k: usize,
    ids: BTreeMap<(usize, usize, usize), u32>,
    mesh: OwnedMesh,
}

impl Spider {
    /// The canonical key of grid point `(a, b)` of sector `j` (points on a grid line belong to
    /// the sector whose `a` axis it is).
    fn key(n: usize, j: usize, a: usize, b: usize) -> (usize, usize, usize) {
        if a == 0 && b == 0 {
            (0, 0, 0)
        } else if a == 0 {
            ((j + 1) % n, b, 0)
        } else {
            (j % n, a, b)
        }
    }

    fn new(n: usize, k: usize, pos: impl Fn(usize, usize, usize) -> Point) -> Spider {
        let mut ids = BTreeMap::new();
        let mut positions = Vec::new();
        let mut faces = Vec::new();
        let mut id = |j: usize, a: usize, b: usize| -> u32 {
            let key = Spider::key(n, j, a, b);
            *ids.entry(key).or_insert_with(|| {
                positions.push(pos(key.0, key.1, key.2));
                (positions.len() - 1) as u32
            })
        };
        for j in 0..n {
            for a in 0..k {
                for b in 0..k {
                    faces.push(vec![
                        id(j, a, b),
                        id(j, a + 1, b),
                        id(j, a + 1, b + 1),
                        id(j, a, b + 1),
                    ]);
                }
            }
        }
        Spider {
            n,
            k,
            ids,
            mesh: OwnedMesh::from_faces(positions, &faces),
        }
    }

    fn id(&self, j: usize, a: usize, b: usize) -> u32 {
        self.ids[&Spider::key(self.n, j % self.n, a, b)]
    }

    fn p(&self, j: usize, a: usize, b: usize) -> Point {
        self.mesh.positions[self.id(j, a, b) as usize]
    }

    /// Index of face `(a, b)–(a + 1, b + 1)` of sector `j`.
    fn face(&self, j: usize, a: usize, b: usize) -> usize {
        ((j % self.n) * self.k + a) * self.k + b
    }
}

/// A jittered, curved spider web: the planar characteristic layout `a e_j + b e_{j+1}` with
/// a height field and noise, so that nothing is symmetric.
fn curved_spider(n: usize, k: usize, seed: u64) -> Spider {
    let mut r = Lcg(seed);
    let noise: Vec<f64> = (0..3 * (n * (k + 1) * (k + 1) + 1))
        .map(|_| r.next())
        .collect();
    let idx = |j: usize, a: usize, b: usize| {
        if a == 0 && b == 0 {
            0
        } else {
            1 + (j * (k + 1) + a) * (k + 1) + b
        }
    };
    Spider::new(n, k, move |j, a, b| {
        let t = 2.0 * PI / n as f64;
        let (c0, s0) = ((j as f64 * t).cos(), (j as f64 * t).sin());
        let (c1, s1) = (((j + 1) as f64 * t).cos(), ((j + 1) as f64 * t).sin());
        let (a, b) = (a as f64, b as f64);
        let x = a * c0 + b * c1;
        let y = a * s0 + b * s1;
        let i = 3 * idx(j, a as usize, b as usize);
        let amp = 0.15;
        [
            x + amp * noise[i],
            y + amp * noise[i + 1],
            0.1 * x * x - 0.07 * x * y + 0.05 * y * y * y / 3.0 + amp * noise[i + 2],
        ]
    })
}

/// Output index of the edge point of `(u, v)` (old vertices, then edge points, then face
/// points: docs/mesh-and-linear-schemes.md).
fn edge_index(m: &OwnedMesh) -> BTreeMap<(u32, u32), usize> {
    with_topology(m, |t| {
        (0..t.num_edges() as u32)
            .map(|e| {
                let (a, b) = t.edge_vertices(e).unwrap();
                ((a.min(b), a.max(b)), e as usize)
            })
            .collect()
    })
    .unwrap()
}

struct Refined<'a> {
    s: &'a Spider,
    out: OwnedMesh,
    eidx: BTreeMap<(u32, u32), usize>,
}

impl Refined<'_> {
    fn new(s: &Spider) -> Refined<'_> {
        Refined {
            s,
            out: subdivide(Scheme::Kobbelt, &s.mesh).unwrap(),
            eidx: edge_index(&s.mesh),
        }
    }
    fn nv(&self) -> usize {
        self.s.mesh.positions.len()
    }
    fn edge(&self, u: u32, v: u32) -> Point {
        self.out.positions[self.nv() + self.eidx[&(u.min(v), u.max(v))]]
    }
    /// Edge point of `(a0, b0)–(a1, b1)` in sector `j`.
    fn e(&self, j: usize, a0: usize, b0: usize, a1: usize, b1: usize) -> Point {
        self.edge(self.s.id(j, a0, b0), self.s.id(j, a1, b1))
    }
    fn face(&self, f: usize) -> Point {
        self.out.positions[self.nv() + self.eidx.len() + f]
    }
}

// ------------------------------------------------------------------ the defining property

#[test]
fn face_points_next_to_an_extraordinary_vertex_agree_in_both_directions() {
    let mut worst = 0.0f64;
    for n in [3usize, 5, 6, 7, 8] {
        let s = curved_spider(n, 5, 17 + n as u64);
        let r = Refined::new(&s);
        // Interpolation: every old vertex bit for bit.
        assert_eq!(&r.out.positions[..r.nv()], &s.mesh.positions[..], "n = {n}");
        for j in 0..n {
            // Face (v, q_j, d_j, q_{j+1}) = sector j, (0,0)–(1,1).
            // Rows (parallel to grid line j): edges (0,b)–(1,b), b = −1 (face j−1's far edge,
            // (q_{j−1}, d_{j−1})), 0, 1, 2.
            let row_m1 = r.e(j + n - 1, 1, 0, 1, 1);
            let rows = f4(
                row_m1,
                r.e(j, 0, 0, 1, 0),
                r.e(j, 0, 1, 1, 1),
                r.e(j, 0, 2, 1, 2),
            );
            // Columns (parallel to grid line j+1): edges (a,0)–(a,1), a = −1 (face j+1's far
            // edge (q_{j+2}, d_{j+1})), 0, 1, 2.
            let col_m1 = r.e(j + 1, 0, 1, 1, 1);
            let cols = f4(
                col_m1,
                r.e(j, 0, 0, 0, 1),
                r.e(j, 1, 0, 1, 1),
                r.e(j, 2, 0, 2, 1),
            );
            let gap = dist(rows, cols);
            worst = worst.max(gap);
            assert!(
                gap < 1e-14,
                "n = {n}, face {j}: directions differ by {gap:e}"
            );
            let got = r.face(s.face(j, 0, 0));
            assert!(dist(got, rows) < 1e-14, "n = {n}, face {j}: face point");
        }
    }
    println!("worst direction gap next to the extraordinary vertex: {worst:.3e}");
}

#[test]
fn edge_points_of_an_extraordinary_vertex_follow_the_virtual_point_relation() {
    // Back out the virtual points r_j from the output edge points e_j of (v, q_j) and the
    // 4-point rule e_j = (1/2 + w)(v + q_j) − w (r_j + s_j), s_j the point beyond q_j; then
    // check the relation that direction independence forces, and the mean.
    let w_hat = W / (0.5 + W);
    for n in [3usize, 5, 6, 7, 8, 12] {
        let s = curved_spider(n, 4, 5 + n as u64);
        let r = Refined::new(&s);
        let v = s.p(0, 0, 0);
        let q = |j: usize| s.p(j % n, 1, 0);
        let d = |j: usize| s.p(j % n, 1, 1);
        let virt: Vec<Point> = (0..n)
            .map(|j| {
                let e = r.e(j, 0, 0, 1, 0);
                let known = mul(add(v, q(j)), 0.5 + W);
                sub(mul(sub(known, e), 1.0 / W), s.p(j, 2, 0))
            })
            .collect();
        let tol = 1e-12;
        for j in 0..n {
            let lhs = sub(virt[(j + 1) % n], virt[j]);
            let rhs = add(
                sub(q(j + n - 1), q(j + 2)),
                mul(sub(d(j + 2), d(j + n - 2)), w_hat),
            );
            assert!(dist(lhs, rhs) < tol, "n = {n}, j = {j}: {lhs:?} vs {rhs:?}");
            // The library's own virtual point agrees with the backed-out one.
            let ring: Vec<Point> = (0..n).map(q).collect();
            let diag: Vec<Point> = (0..n).map(d).collect();
            let lib = kobbelt::virtual_point(&ring, &diag, j).unwrap();
            assert!(
                dist(lib, virt[j]) < tol,
                "n = {n}, j = {j}: library virtual point"
            );
        }
        let mean_r = mul(
            virt.iter().fold([0.0; 3], |a, &b| add(a, b)),
            1.0 / n as f64,
        );
        let mean_q = mul((0..n).fold([0.0; 3], |a, j| add(a, q(j))), 1.0 / n as f64);
        assert!(
            dist(mean_r, mean_q) < tol,
            "n = {n}: mean of the virtual points"
        );
    }
}

// ------------------------------------------------------------------ the rule itself

fn random_ring(n: usize, seed: u64) -> (Vec<Point>, Vec<Point>) {
    let mut r = Lcg(seed);
    let mut pt = || [r.next() * 3.0, r.next() * 3.0, r.next() * 3.0];
    let q: Vec<Point> = (0..n).map(|_| pt()).collect();
    let d: Vec<Point> = (0..n).map(|_| pt()).collect();
    (q, d)
}

#[test]
fn valence_four_gives_the_opposite_neighbour_bit_for_bit() {
    for seed in 0..20 {
        let (q, d) = random_ring(4, seed);
        for j in 0..4 {
            assert_eq!(kobbelt::virtual_point(&q, &d, j).unwrap(), q[(j + 2) % 4]);
        }
    }
}

#[test]
fn the_rule_is_affine_and_symmetric_about_its_spoke() {
    let mut r = Lcg(99);
    for n in 3..=12usize {
        let (q, d) = random_ring(n, n as u64);
        // A random affine map x ↦ A x + t.
        let a: [[f64; 3]; 3] = core::array::from_fn(|_| core::array::from_fn(|_| r.next()));
        let t = [r.next() * 10.0, r.next() * 10.0, r.next() * 10.0];
        let f = |p: Point| -> Point {
            core::array::from_fn(|i| a[i][0] * p[0] + a[i][1] * p[1] + a[i][2] * p[2] + t[i])
        };
        let qa: Vec<Point> = q.iter().map(|&p| f(p)).collect();
        let da: Vec<Point> = d.iter().map(|&p| f(p)).collect();
        for j in 0..n {
            let v = kobbelt::virtual_point(&q, &d, j).unwrap();
            let va = kobbelt::virtual_point(&qa, &da, j).unwrap();
            assert!(dist(va, f(v)) < 1e-12, "affine, n = {n}, j = {j}");
            // Mirror the ring about q_j: q'_i = q_{2j−i}, d'_i = d_{2j−i−1} (the diagonal
            // between q'_i and q'_{i+1} is the one between q_{2j−i−1} and q_{2j−i}).
            let qm: Vec<Point> = (0..n).map(|i| q[(2 * j + 2 * n - i) % n]).collect();
            let dm: Vec<Point> = (0..n).map(|i| d[(2 * j + 2 * n - i - 1) % n]).collect();
            let vm = kobbelt::virtual_point(&qm, &dm, j).unwrap();
            assert!(dist(vm, v) < 1e-12, "mirror, n = {n}, j = {j}");
        }
    }
}

#[test]
fn planar_regular_star_puts_the_virtual_point_on_the_opposite_ray() {
    // q_j = e^{iθj}, d_j = ρ e^{iθ(j+1/2)}, v = 0, θ = 2π/n. By symmetry r_j = −α q_j;
    // the difference relation gives, in closed form,
    // α = sin(3θ/2)/sin(θ/2) − ŵ ρ sin 2θ / sin(θ/2) = 1 + 2 cos θ − ŵ ρ sin 2θ / sin(θ/2).
    let w_hat = W / (0.5 + W);
    for n in [3usize, 5, 6, 7, 8, 10] {
        for rho in [1.0, 2f64.sqrt(), 1.7] {
            let th = 2.0 * PI / n as f64;
            let q: Vec<Point> = (0..n)
                .map(|j| [(th * j as f64).cos(), (th * j as f64).sin(), 0.0])
                .collect();
            let d: Vec<Point> = (0..n)
                .map(|j| {
                    let a = th * (j as f64 + 0.5);
                    [rho * a.cos(), rho * a.sin(), 0.0]
                })
                .collect();
            let alpha = 1.0 + 2.0 * th.cos() - w_hat * rho * (2.0 * th).sin() / (th / 2.0).sin();
            for j in 0..n {
                let v = kobbelt::virtual_point(&q, &d, j).unwrap();
                let want = mul(q[j], -alpha);
                assert!(
                    dist(v, want) < 1e-14,
                    "n = {n}, ρ = {rho}, j = {j}: {v:?} vs {want:?}"
                );
            }
            if (rho - 2f64.sqrt()).abs() < 1e-15 {
                println!("n = {n}: α = {alpha:.6} (ρ = √2)");
            }
        }
    }
}

// ------------------------------------------------------------------ eigen-analysis

#[derive(Clone, Copy, Debug)]
struct C(f64, f64);
impl C {
    fn add(self, o: C) -> C {
        C(self.0 + o.0, self.1 + o.1)
    }
    fn sub(self, o: C) -> C {
        C(self.0 - o.0, self.1 - o.1)
    }
    fn mul(self, o: C) -> C {
        C(self.0 * o.0 - self.1 * o.1, self.0 * o.1 + self.1 * o.0)
    }
    fn conj(self) -> C {
        C(self.0, -self.1)
    }
    fn abs2(self) -> f64 {
        self.0 * self.0 + self.1 * self.1
    }
    fn div(self, o: C) -> C {
        let m = o.abs2();
        C(
            (self.0 * o.0 + self.1 * o.1) / m,
            (self.1 * o.0 - self.0 * o.1) / m,
        )
    }
}
type Mat = Vec<Vec<C>>;
fn matvec(a: &Mat, x: &[C]) -> Vec<C> {
    a.iter()
        .map(|row| {
            row.iter()
                .zip(x)
                .fold(C(0.0, 0.0), |s, (&r, &v)| s.add(r.mul(v)))
        })
        .collect()
}
fn matmul(a: &Mat, b: &Mat) -> Mat {
    let n = a.len();
    (0..n)
        .map(|i| {
            (0..n)
                .map(|j| (0..n).fold(C(0.0, 0.0), |s, k| s.add(a[i][k].mul(b[k][j]))))
                .collect()
        })
        .collect()
}
fn norm(x: &[C]) -> f64 {
    x.iter().map(|c| c.abs2()).sum::<f64>().sqrt()
}
fn frob(a: &Mat) -> f64 {
    a.iter().flatten().map(|c| c.abs2()).sum::<f64>().sqrt()
}
/// An upper bound of the spectral radius: `‖A^m‖_F^{1/m}`, `m = 2^s`.
fn radius_bound(a: &Mat, s: u32) -> f64 {
    let mut p = a.clone();
    let mut log_scale = 0.0f64;
    for _ in 0..s {
        p = matmul(&p, &p);
        log_scale *= 2.0;
        let f = frob(&p);
        if f == 0.0 {
            return 0.0;
        }
        for x in p.iter_mut().flatten() {
            *x = C(x.0 / f, x.1 / f);
        }
        log_scale += f.ln();
    }
    (log_scale / 2f64.powi(s as i32)).exp()
}
/// Dominant eigenpair by power iteration (Rayleigh quotient), with its residual.
fn power(a: &Mat, iters: usize) -> (C, Vec<C>, f64) {
    let m = a.len();
    let mut x: Vec<C> = (0..m)
        .map(|i| C(1.0 + 0.1 * i as f64, 0.05 * i as f64))
        .collect();
    let mut lam = C(0.0, 0.0);
    for _ in 0..iters {
        let y = matvec(a, &x);
        let num = x
            .iter()
            .zip(&y)
            .fold(C(0.0, 0.0), |s, (&u, &v)| s.add(u.conj().mul(v)));
        let den = x.iter().fold(C(0.0, 0.0), |s, &u| s.add(u.conj().mul(u)));
        lam = num.div(den);
        let ny = norm(&y);
        x = y.iter().map(|c| C(c.0 / ny, c.1 / ny)).collect();
    }
    let ax = matvec(a, &x);
    let res = norm(
        &ax.iter()
            .zip(&x)
            .map(|(&u, &v)| u.sub(lam.mul(v)))
            .collect::<Vec<_>>(),
    );
    (lam, x, res)
}

/// The local subdivision matrix on the 3-ring of the extraordinary vertex (with `v = 0`):
/// 12 unknowns a sector, `L_j(1..3)` and `(a, b) ∈ [1, 3]²`; new points at new-grid
/// coordinates ≤ 3 depend only on old ones at ≤ 3 (the 4-point support is 3/2 old steps).
/// Columns come from subdividing basis data with the library.
fn local_matrix(n: usize) -> Vec<Vec<f64>> {
    let k = 6;
    let s0 = Spider::new(n, k, |_, _, _| [0.0; 3]);
    let slots: Vec<(usize, usize)> = (1..=3)
        .map(|a| (a, 0))
        .chain((1..=3).flat_map(|a| (1..=3).map(move |b| (a, b))))
        .collect();
    let unknowns: Vec<(usize, usize, usize)> = (0..n)
        .flat_map(|j| slots.iter().map(move |&(a, b)| (j, a, b)))
        .collect();
    let u = unknowns.len();
    let eidx = edge_index(&s0.mesh);
    let nv = s0.mesh.positions.len();
    let ne = eidx.len();
    // New value at new-grid (A, B) of sector j.
    let read = |out: &OwnedMesh, j: usize, aa: usize, bb: usize, c: usize| -> f64 {
        let (a, b) = (aa / 2, bb / 2);
        let i = match (aa % 2, bb % 2) {
            (0, 0) => s0.id(j, a, b) as usize,
            (1, 0) => {
                let (x, y) = (s0.id(j, a, b), s0.id(j, a + 1, b));
                nv + eidx[&(x.min(y), x.max(y))]
            }
            (0, 1) => {
                let (x, y) = (s0.id(j, a, b), s0.id(j, a, b + 1));
                nv + eidx[&(x.min(y), x.max(y))]
            }
            _ => nv + ne + s0.face(j, a, b),
        };
        out.positions[i][c]
    };
    let mut m = vec![vec![0.0; u]; u];
    for chunk in (0..u).collect::<Vec<_>>().chunks(3) {
        let mut mesh = s0.mesh.clone();
        for (c, &col) in chunk.iter().enumerate() {
            let (j, a, b) = unknowns[col];
            mesh.positions[s0.id(j, a, b) as usize][c] = 1.0;
        }
        let out = subdivide(Scheme::Kobbelt, &mesh).unwrap();
        for (c, &col) in chunk.iter().enumerate() {
            for (row, &(j, a, b)) in unknowns.iter().enumerate() {
                m[row][col] = read(&out, j, a, b, c);
            }
        }
    }
    // Invariance of the 3-ring: data outside it never reaches it.
    let mut mesh = s0.mesh.clone();
    for (i, p) in mesh.positions.iter_mut().enumerate() {
        p[0] = 1.0 + i as f64;
    }
    mesh.positions[s0.id(0, 0, 0) as usize][0] = 0.0;
    for &(j, a, b) in &unknowns {
        mesh.positions[s0.id(j, a, b) as usize][0] = 0.0;
    }
    let out = subdivide(Scheme::Kobbelt, &mesh).unwrap();
    for &(j, a, b) in &unknowns {
        assert_eq!(
            read(&out, j, a, b, 0),
            0.0,
            "3-ring not invariant at n = {n}"
        );
    }
    m
}

/// The Fourier block `k` of the block-circulant local matrix: 12 × 12.
fn fourier_block(m: &[Vec<f64>], n: usize, k: usize) -> Mat {
    let b = m.len() / n;
    (0..b)
        .map(|r| {
            (0..b)
                .map(|c| {
                    (0..n).fold(C(0.0, 0.0), |s, jj| {
                        let ph = 2.0 * PI * (k * jj) as f64 / n as f64;
                        s.add(C(m[r][jj * b + c] * ph.cos(), m[r][jj * b + c] * ph.sin()))
                    })
                })
                .collect()
        })
        .collect()
}

#[test]
fn local_subdivision_matrix_has_the_c1_eigenstructure() {
    for n in [3usize, 4, 5, 6, 8] {
        let m = local_matrix(n);
        let b = m.len() / n;
        // Block-circulance (rotational symmetry of the rule).
        for r in 0..m.len() {
            for c in 0..m.len() {
                let (r2, c2) = ((r + b) % m.len(), (c + b) % m.len());
                assert!(
                    (m[r][c] - m[r2][c2]).abs() < 1e-15,
                    "n = {n}: not circulant"
                );
            }
        }
        let b1 = fourier_block(&m, n, 1);
        let (lam, x, res) = power(&b1, 400);
        assert!(res < 1e-12, "n = {n}: power iteration residual {res:e}");
        assert!(lam.1.abs() < 1e-12, "n = {n}: complex subdominant {lam:?}");
        let lam = lam.0;
        // Deflate with the left eigenvector and bound the rest of block 1.
        let bh: Mat = (0..b)
            .map(|i| (0..b).map(|j| b1[j][i].conj()).collect())
            .collect();
        let (_, y, _) = power(&bh, 400);
        let yx = y
            .iter()
            .zip(&x)
            .fold(C(0.0, 0.0), |s, (&u, &v)| s.add(u.conj().mul(v)));
        let defl: Mat = (0..b)
            .map(|i| {
                (0..b)
                    .map(|j| b1[i][j].sub(C(lam, 0.0).mul(x[i]).mul(y[j].conj()).div(yx)))
                    .collect()
            })
            .collect();
        let mut others = radius_bound(&defl, 7);
        for k in 0..n {
            if k == 1 || k == n - 1 {
                continue;
            }
            others = others.max(radius_bound(&fourier_block(&m, n, k), 7));
        }
        println!("n = {n}: λ = {lam:.6}, every other |eigenvalue| ≤ {others:.6}");
        if n == 4 {
            // The 4-point scheme's subdominant eigenvalue (it reproduces linears): 1/2.
            assert!((lam - 0.5).abs() < 1e-12, "n = 4: λ = {lam}");
        }
        assert!(lam > 0.0 && lam < 1.0, "n = {n}: λ = {lam}");
        assert!(
            others < lam - 1e-3,
            "n = {n}: λ = {lam} not dominant ({others})"
        );
        // Regular characteristic net: the eigenvector's 3 × 3 grid of sector 0, with the
        // centre at 0, is a consistently oriented quad net in the complex plane.
        let at = |a: usize, bb: usize| -> C {
            if a == 0 && bb == 0 {
                return C(0.0, 0.0);
            }
            // (a, 0) → L_0(a); (0, b) → L_1(b) = x rotated by e^{2πi/n} in block 1.
            let idx = |a: usize, bb: usize| {
                if bb == 0 {
                    a - 1
                } else {
                    3 + (a - 1) * 3 + (bb - 1)
                }
            };
            if a == 0 {
                let ph = 2.0 * PI / n as f64;
                x[idx(bb, 0)].mul(C(ph.cos(), ph.sin()))
            } else {
                x[idx(a, bb)]
            }
        };
        let mut sign = 0.0f64;
        for a in 0..3 {
            for bb in 0..3 {
                let (p0, p1, p2, p3) = (at(a, bb), at(a + 1, bb), at(a + 1, bb + 1), at(a, bb + 1));
                let cross = |u: C, v: C| u.0 * v.1 - u.1 * v.0;
                let area = cross(p1.sub(p0), p3.sub(p0)) + cross(p3.sub(p2), p1.sub(p2));
                if sign == 0.0 {
                    sign = area.signum();
                }
                assert!(
                    area * sign > 0.0,
                    "n = {n}: characteristic net folds at {a},{bb}"
                );
            }
        }
    }
}

// ------------------------------------------------------------------ open nets

#[test]
fn boundary_edge_points_depend_on_the_boundary_polygon_only() {
    // Kobbelt 1996 (abstract): on open nets the scheme "generates boundary curves that allow a
    // C0-join of several subdivision patches" — so a boundary edge point must be a function of
    // the boundary polygon alone. Here: the 4-point rule along the boundary loop, and moving
    // every interior vertex changes no boundary edge point by a single bit.
    let (m_, n_) = (6usize, 4usize);
    let g = jitter(&quad_grid(m_, n_), 0.1, 3).map_positions(|p| [p[0], p[1], 0.2 * p[0] * p[1]]);
    let interior = |p: Point| {
        let (i, j) = (p[0].round() as usize, p[1].round() as usize);
        i > 0 && i < m_ && j > 0 && j < n_
    };
    let base = quad_grid(m_, n_);
    let moved = OwnedMesh {
        positions: g
            .positions
            .iter()
            .zip(&base.positions)
            .map(|(&p, &b)| {
                if interior(b) {
                    add(p, [0.3, -0.2, 0.7])
                } else {
                    p
                }
            })
            .collect(),
        ..g.clone()
    };
    let a = subdivide(Scheme::Kobbelt, &g).unwrap();
    let b = subdivide(Scheme::Kobbelt, &moved).unwrap();
    let eidx = edge_index(&g);
    let nv = g.positions.len();
    // The boundary loop, counter-clockwise: bottom row, right column, top row, left column.
    let id = |i: usize, j: usize| (j * (m_ + 1) + i) as u32;
    let mut lp: Vec<u32> = (0..m_).map(|i| id(i, 0)).collect();
    lp.extend((0..n_).map(|j| id(m_, j)));
    lp.extend((1..=m_).rev().map(|i| id(i, n_)));
    lp.extend((1..=n_).rev().map(|j| id(0, j)));
    let l = lp.len();
    let mut checked = 0;
    for k in 0..l {
        let (u, v) = (lp[k], lp[(k + 1) % l]);
        let e = nv + eidx[&(u.min(v), u.max(v))];
        assert_eq!(
            a.positions[e], b.positions[e],
            "boundary edge {u}-{v} moved"
        );
        let pt = |x: u32| g.positions[x as usize];
        let want = f4(pt(lp[(k + l - 1) % l]), pt(u), pt(v), pt(lp[(k + 2) % l]));
        assert!(dist(a.positions[e], want) < 1e-14, "boundary edge {u}-{v}");
        checked += 1;
    }
    assert_eq!(checked, 2 * (m_ + n_));
}
