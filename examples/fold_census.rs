//! Folded edges of canonical Möbius subdivision: where they are, which rule made them, and a
//! prototype of a Möbius-invariant safety criterion with a continuous fallback
//! (docs/folds.md).
//!
//! ```text
//! fold_census census   SCHEME LEVELS IN.off...        folded edges: literal Möbius, linear, guarded
//! fold_census check    SCHEME LEVELS IN.off...        re-implementation == library, bit for bit
//! fold_census trace    SCHEME LEVELS IN.off [--list]  every fold traced to its element and cause
//! fold_census features SCHEME LEVELS IN.off...        per-element features as TSV
//! fold_census probe    SCHEME IN.off EDGE             both stars of one level-1 edge in detail
//! fold_census proto    SCHEME LEVELS IN.off... [--spread=LO,HI] [--t=M] [--rho=LO,HI]
//!                                                     paper / prototype / linear fold counts
//! fold_census equiv    SCHEME IN.off...               flags and output under Möbius maps
//! fold_census regular  SCHEME                         flags on regular grids and their images
//! fold_census selftest SCHEME                         turning-angle sign, weighted F4
//! ```
//!
//! A folded edge is an interior edge of the output whose two faces have (Newell) normals more
//! than 90° apart. SCHEME is `loop`, `butterfly` or `catmull-clark`.
//!
//! The per-element evaluation of the Möbius drivers (seed 000 §4.1–4.4) is re-implemented
//! here from the crate's public primitives (canonical forms, stencils, F4, the face-point
//! chain), so that every output vertex can carry what produced it; `check` confirms that the
//! re-implementation reproduces the library's output bit for bit before `trace` relies on it.
#![allow(
    clippy::expect_used,
    clippy::unwrap_used,
    clippy::indexing_slicing,
    clippy::too_many_arguments,
    clippy::type_complexity,
    clippy::wrong_self_convention,
    dead_code
)]

#[path = "../tests/common/mod.rs"]
mod common;

use std::path::Path;

use common::*;
use nlsubdiv::blend::{f4, f4_hinted, face_point_with_ids, is_negative_real};
use nlsubdiv::mesh::{Spoke, Topology, NONE};
#[allow(unused_imports)]
use nlsubdiv::mobius as _m;
use nlsubdiv::mobius::{CanonicalForm, MobiusMap, StarKind};
use nlsubdiv::point::{add, cross, dot, norm, scale, sub};
use nlsubdiv::quat::{cross_ratio, Quat};
use nlsubdiv::scheme::{self, Options, Scheme};
use nlsubdiv::stencil::{butterfly, catmull_clark, centroid, loop_scheme};
use nlsubdiv::Point;

const ORIGIN: Point = [0.0; 3];
const MISSING: Point = [f64::NAN; 3];

fn present(p: &Point) -> bool {
    p.iter().all(|x| x.is_finite())
}

// ------------------------------------------------------------------------------------------
// Library runs and the fold census
// ------------------------------------------------------------------------------------------

fn build<R>(m: &OwnedMesh, f: impl FnOnce(&Topology<'_, '_>) -> R) -> R {
    let mut scratch = vec![0u32; scheme::plan_scratch_size(&m.view()).unwrap()];
    let topo = Topology::build(m.view(), &mut scratch).unwrap();
    f(&topo)
}

/// One library step, linear or the paper's literal Möbius rules (not strict), and the number
/// of fallbacks. The re-implementation below is of the literal rules.
fn lib_step(s: Scheme, m: &OwnedMesh, mobius_on: bool) -> (OwnedMesh, u32) {
    let (out, report) = run(m, &Options::new(s).mobius(mobius_on).literal(true)).unwrap();
    (out, report.fallbacks)
}

/// One library step of the Möbius rules with the fold guard (the library's default), and the
/// number of elements the guard changed.
fn guarded_step(s: Scheme, m: &OwnedMesh) -> (OwnedMesh, u32) {
    let (out, report) = run(m, &Options::new(s).mobius(true)).unwrap();
    (out, report.guarded)
}

fn lib_levels(s: Scheme, m: &OwnedMesh, levels: usize, mobius_on: bool) -> OwnedMesh {
    let mut cur = m.clone();
    for _ in 0..levels {
        cur = lib_step(s, &cur, mobius_on).0;
    }
    cur
}

/// The Newell normal (area vector) of face `f`.
fn face_normal(m: &OwnedMesh, f: usize) -> Point {
    let idx = &m.indices[m.offsets[f] as usize..m.offsets[f + 1] as usize];
    let mut n = [0.0; 3];
    for i in 0..idx.len() {
        let p = m.positions[idx[i] as usize];
        let q = m.positions[idx[(i + 1) % idx.len()] as usize];
        n = add(n, cross(p, q));
    }
    n
}

/// The folded interior edges of `m`: `(edge, face a, face b)`.
fn folds(m: &OwnedMesh) -> Vec<(u32, u32, u32)> {
    let normals: Vec<Point> = (0..m.num_faces()).map(|f| face_normal(m, f)).collect();
    build(m, |topo| {
        let mut out = Vec::new();
        for e in 0..topo.num_edges() as u32 {
            let h = topo.edge_half_edge(e).unwrap();
            let t = topo.twin(h).unwrap();
            if t == NONE {
                continue;
            }
            let (fa, fb) = (topo.face(h).unwrap(), topo.face(t).unwrap());
            if dot(normals[fa as usize], normals[fb as usize]) < 0.0 {
                out.push((e, fa, fb));
            }
        }
        out
    })
}

fn scheme_arg(a: &str) -> Scheme {
    Scheme::from_name(a).unwrap_or_else(|| {
        eprintln!("unknown scheme {a}");
        std::process::exit(1)
    })
}

fn load(p: &str) -> OwnedMesh {
    read_off(Path::new(p)).unwrap_or_else(|e| {
        eprintln!("{p}: {e}");
        std::process::exit(1)
    })
}

fn stem(p: &str) -> String {
    Path::new(p)
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default()
}

// ------------------------------------------------------------------------------------------
// Per-star diagnostics (all but `pole_ratio` and the Euclidean angles are Möbius-invariant)
// ------------------------------------------------------------------------------------------

/// What one vertex star looks like to its canonical form.
#[derive(Clone, Debug, Default)]
struct StarDiag {
    form: bool,
    boundary: bool,
    n: usize,
    /// Signed turning (sine) of the tangent polygon at each spoke's corner, relative to the
    /// polygon's own area vector; negative = reflex corner = the spoke is non-Delaunay in
    /// the Möbius sense (seed 000 §4.5: "Delaunay = convex tangent polygon"). NaN for the
    /// end corners of an open star.
    turn: Vec<f64>,
    /// The same turning as an angle in (−π, π].
    turn_angle: Vec<f64>,
    /// Wedges `(0, C_i, C_{i+1})` of the canonical star whose orientation disagrees with the
    /// canonical ring's area vector: the canonical star is folded around the centre.
    c_fold: u32,
    /// `|c| / r`: the input's point at infinity sits at distance `r/|c|` from the centre in
    /// the normalised canonical frame (not Möbius-invariant).
    pole_ratio: f64,
    /// `|C_i|` per spoke in the normalised canonical frame (`r / |T_i − c|`): 1 for every
    /// spoke of a Möbius-regular star.
    radial: Vec<f64>,
}

impl StarDiag {
    /// The radial spread `max |C_i| / min |C_i|` of the canonical ring (1: regular).
    fn spread(&self) -> f64 {
        let lo = self.radial.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = self.radial.iter().copied().fold(0.0, f64::max);
        if self.form {
            hi / lo
        } else {
            f64::NAN
        }
    }
}

fn spoke_list(topo: &Topology<'_, '_>, v: u32) -> Vec<Spoke> {
    topo.star(v).collect()
}

fn is_ear(topo: &Topology<'_, '_>, v: u32) -> bool {
    let h = topo.vertex_half_edge(v).unwrap();
    h != NONE && topo.twin(h).unwrap() == NONE && topo.valence(v).unwrap() == 2
}

/// The canonical form the drivers use for `v` (none for isolated vertices, ears and stars
/// without a form), with the star's spokes.
fn form_of(topo: &Topology<'_, '_>, v: u32) -> (Option<CanonicalForm>, Vec<Spoke>) {
    let h = topo.vertex_half_edge(v).unwrap();
    if h == NONE {
        return (None, Vec::new());
    }
    let boundary = topo.twin(h).unwrap() == NONE;
    if boundary && topo.valence(v).unwrap() == 2 {
        return (None, Vec::new());
    }
    let spokes = spoke_list(topo, v);
    let ring: Vec<Point> = spokes
        .iter()
        .map(|s| topo.position(s.neighbour).unwrap())
        .collect();
    let kind = if boundary {
        StarKind::Boundary
    } else {
        StarKind::Interior
    };
    (
        CanonicalForm::new(topo.position(v).unwrap(), &ring, kind).ok(),
        spokes,
    )
}

fn star_diag(topo: &Topology<'_, '_>, v: u32) -> StarDiag {
    let (cf, spokes) = form_of(topo, v);
    let boundary = topo.is_boundary_vertex(v).unwrap_or(false);
    let n = spokes.len();
    let Some(cf) = cf else {
        return StarDiag {
            boundary,
            n,
            turn: vec![f64::NAN; n],
            turn_angle: vec![f64::NAN; n],
            ..Default::default()
        };
    };
    let pv = topo.position(v).unwrap();
    let t: Vec<Point> = spokes
        .iter()
        .map(|s| {
            let d = sub(topo.position(s.neighbour).unwrap(), pv);
            scale(d, -1.0 / dot(d, d)) // (u − v)⁻¹ for an imaginary quaternion
        })
        .collect();
    let area = |p: &[Point]| {
        let mut a = [0.0; 3];
        for i in 0..p.len() {
            a = add(a, cross(p[i], p[(i + 1) % p.len()]));
        }
        a
    };
    let nt = area(&t);
    let ntl = norm(nt).max(1e-300);
    let mut turn = vec![f64::NAN; n];
    let mut turn_angle = vec![f64::NAN; n];
    for i in 0..n {
        if boundary && (i == 0 || i + 1 == n) {
            continue;
        }
        let a = sub(t[i], t[(i + n - 1) % n]);
        let b = sub(t[(i + 1) % n], t[i]);
        let c = cross(a, b);
        let s = dot(c, nt) / (ntl * norm(a) * norm(b));
        turn[i] = s;
        let ang = libm::atan2(norm(c), dot(a, b));
        turn_angle[i] = if s < 0.0 { -ang } else { ang };
    }
    let cimg: Vec<Point> = spokes
        .iter()
        .map(|s| {
            cf.to_normalised(topo.position(s.neighbour).unwrap())
                .unwrap_or(MISSING)
        })
        .collect();
    let nc = area(&cimg);
    let mut c_fold = 0;
    let wedges = if boundary { n.saturating_sub(1) } else { n };
    for i in 0..wedges {
        if dot(cross(cimg[i], cimg[(i + 1) % n]), nc) <= 0.0 {
            c_fold += 1;
        }
    }
    StarDiag {
        form: true,
        boundary,
        n,
        turn,
        turn_angle,
        c_fold,
        pole_ratio: norm(cf.c) / cf.r,
        radial: cimg.iter().map(|p| norm(*p)).collect(),
    }
}

// ------------------------------------------------------------------------------------------
// The re-implemented Möbius step with per-element provenance
// ------------------------------------------------------------------------------------------

#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
enum Kind {
    #[default]
    Vertex,
    Edge,
    Face,
    Old,
    BoundaryEdge,
    BoundaryVertex,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
enum Rule {
    /// From the element's own star (vertex points).
    #[default]
    Star,
    /// `F4(v_j, e_j, e_k, v_k)` of two candidates.
    F4Both,
    /// One star gave a candidate.
    Single,
    /// The linear rule (degenerate neighbourhood).
    Fallback,
    /// A boundary curve rule.
    Curve,
    /// The §4.4.3 face-point chain.
    FaceChain,
    /// Copied (Butterfly's old vertices).
    Copy,
    /// Prototype: blended toward the linear rule.
    Blended,
}

/// Provenance of one output vertex.
#[derive(Clone, Copy, Debug, Default)]
struct Elem {
    kind: Kind,
    /// Input vertex, edge or face.
    src: u32,
    rule: Rule,
    /// Angle of F4's `ρ = cr[e_k, v_j, e_j, v_k]` in [0, π] (π: the negative-real cut).
    rho_angle: f64,
    /// Largest Euclidean distance of a candidate from the edge midpoint over the edge length.
    cand_far: f64,
    /// Smallest distance in the normalised canonical frame between the pole (image of the
    /// input's ∞) and the segment from the centre to a candidate, over the candidate's norm.
    pole_margin: f64,
    /// Prototype: the weight of the Möbius rule (1 = the paper's rule).
    weight: f64,
}

/// How the prototype treats a star it does not trust.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Fallback {
    /// Evaluate the star's stencils in its canonical form interpolated toward a similarity by
    /// the trust `τ` ([`Form`]); blends unchanged.
    Spectrum,
    /// Keep the paper's point and move it toward the linear rule's: `τ p + (1 − τ) p_lin`,
    /// `τ` the least trust of the element's stars.
    Blend,
    /// Möbius-invariant, edges only: an edge with a distrusted star takes the weighted F4
    /// ([`f4_weighted`]) leaning toward the more trusted star's candidate,
    /// `w = τ_k / (τ_j + τ_k)`; vertex and face points keep the paper's rules.
    WeightedF4,
    /// [`Fallback::Spectrum`] for every distrusted star, and its edges blended by the
    /// weighted F4 as in [`Fallback::WeightedF4`].
    SpectrumWeighted,
}

/// Prototype parameters: `None` runs the paper's rules.
#[derive(Clone, Copy, Debug)]
struct Proto {
    fallback: Fallback,
    /// Radial spread `max |C_i| / min |C_i|` of the canonical ring: trust 1 at or below
    /// `spread_lo`, 0 at or above `spread_hi` (linear in log between).
    spread_lo: f64,
    spread_hi: f64,
    /// An edge candidate's position `t = ⟨E_j, C_j⟩ / |C_j|²` along its spoke in its own
    /// canonical frame: trust 1 inside `[t_margin, 1 − t_margin]`, 0 at `t ≤ 0` or `t ≥ 1`.
    t_margin: f64,
    /// Angle of F4's `ρ` (degrees): trust 1 at or below `rho_lo`, 0 at or above `rho_hi`;
    /// applied to both stars of the edge.
    rho_lo: f64,
    rho_hi: f64,
}

const PROTO_DEFAULT: Proto = Proto {
    fallback: Fallback::Spectrum,
    spread_lo: 4.0,
    spread_hi: 8.0,
    t_margin: 0.15,
    rho_lo: 120.0,
    rho_hi: 160.0,
};

fn ramp(x: f64, zero_at: f64, one_at: f64) -> f64 {
    if !x.is_finite() {
        return 1.0;
    }
    ((x - zero_at) / (one_at - zero_at)).clamp(0.0, 1.0)
}

struct Step {
    out: OwnedMesh,
    lin: Vec<Point>,
    elems: Vec<Elem>,
    stars: Vec<StarDiag>,
    /// Per half-edge: the candidate from the origin's form and its normalised-frame image.
    edge_c: Vec<Point>,
    /// Stars flagged by the prototype (trust < 1).
    flagged: u32,
    /// Elements whose weight < 1.
    blended: u32,
}

fn pole_margin(cf: &CanonicalForm, p: Point) -> f64 {
    let c2 = dot(cf.c, cf.c);
    if c2 == 0.0 {
        return f64::INFINITY;
    }
    let pole = scale(cf.c, -cf.r / c2);
    let pp = dot(p, p);
    if pp == 0.0 {
        return f64::INFINITY;
    }
    let s = (dot(pole, p) / pp).clamp(0.0, 1.0);
    norm(sub(pole, scale(p, s))) / pp.sqrt()
}

/// `q^w` for a quaternion off the negative reals (principal branch, via log/exp).
fn qpow(q: Quat, w: f64) -> Option<Quat> {
    Some(q.log()?.scale(w).exp())
}

/// The weighted four-point blend: the point `p` with `cr[c, a, b, p] = χ_w`,
/// `χ_w = −ρ (1 − ρ^w)(ρ^w − ρ)⁻¹`, `ρ = cr[c, a, b, d]`. `w = ½` is F4 (`χ = −√ρ`), `w → 0`
/// gives `b`, `w → 1` gives `c`: in a Möbius frame with `a = 0`, `d = ∞` it is the weighted
/// geometric mean `b^{1−w} c^w`. Every quantity is a function of `ρ`, so it is Möbius
/// equivariant and sphere preserving like F4 (Lemma A.1).
fn f4_weighted(a: Point, b: Point, c: Point, d: Point, w: f64) -> Option<Point> {
    if w <= 0.0 {
        return Some(b);
    }
    if w >= 1.0 {
        return Some(c);
    }
    let rho = cross_ratio(c, a, b, d).ok()?;
    if is_negative_real(rho) {
        return None;
    }
    let rw = qpow(rho, w)?;
    let chi = -(rho * (Quat::ONE - rw) * (rw - rho).inverse()?);
    // Solve cr[c, a, b, p] = χ: p = c + (M + χ)⁻¹ M (b − c), M = (a − c)(b − a)⁻¹.
    let qa = Quat::from_point(a);
    let qb = Quat::from_point(b);
    let qc = Quat::from_point(c);
    let m = (qa - qc) * (qb - qa).inverse()?;
    let off = ((m + chi).inverse()? * m * (qb - qc)).to_point();
    let p = add(c, off);
    present(&p).then_some(p)
}

/// A vertex's evaluation frame: the canonical form (`tau = 1`, the library's maps bit for
/// bit) or the form interpolated toward a similarity, `x ↦ −((x − v)⁻¹ − τc)⁻¹` (seed 000
/// §7.2's spectrum): `τ = 0` is the point reflection `x ↦ v − x` up to the translation, on
/// which every affine stencil gives the linear rule; `τ = 1` is the normalised canonical
/// form up to the scale `r`, which affine stencils ignore.
#[derive(Clone, Debug)]
struct Form {
    cf: CanonicalForm,
    tau: f64,
}

/// `q⁻¹` of an imaginary quaternion: `−q / |q|²`.
fn inv_im(q: Point) -> Option<Point> {
    let d = dot(q, q);
    (d > 0.0 && d.is_finite()).then(|| scale(q, -1.0 / d))
}

impl Form {
    fn to_normalised(&self, x: Point) -> nlsubdiv::Result<Point> {
        if self.tau >= 1.0 {
            return self.cf.to_normalised(x);
        }
        let bad = nlsubdiv::Error::new(nlsubdiv::Status::DegenerateGeometry);
        if x == self.cf.v {
            return Ok(ORIGIN);
        }
        let t = inv_im(sub(x, self.cf.v)).ok_or(bad)?;
        let y = inv_im(sub(t, scale(self.cf.c, self.tau))).ok_or(bad)?;
        Ok(scale(y, -1.0))
    }
    fn from_normalised(&self, p: Point) -> nlsubdiv::Result<Point> {
        if self.tau >= 1.0 {
            return self.cf.from_normalised(p);
        }
        let bad = nlsubdiv::Error::new(nlsubdiv::Status::DegenerateGeometry);
        if p == ORIGIN {
            return Ok(self.cf.v);
        }
        let t = sub(scale(self.cf.c, self.tau), inv_im(p).ok_or(bad)?);
        let x = add(self.cf.v, inv_im(t).ok_or(bad)?);
        if present(&x) {
            Ok(x)
        } else {
            Err(bad)
        }
    }
}

struct Ctx<'a, 't, 'm, 's> {
    /// Per vertex: the interpolation weight of its form (1: canonical).
    tau: Vec<f64>,
    topo: &'a Topology<'m, 's>,
    s: Scheme,
    proto: Option<Proto>,
    stars: Vec<StarDiag>,
    trust: Vec<f64>,
    pos: Vec<Point>,
    elems: Vec<Elem>,
    lin: Vec<Point>,
    edge_c: Vec<Point>,
    face_c: Vec<Point>,
    /// Per half-edge: the pole margin of its edge candidate.
    edge_pm: Vec<f64>,
    _t: std::marker::PhantomData<&'t ()>,
}

impl Ctx<'_, '_, '_, '_> {
    /// The form of `v` the step evaluates in: the canonical form, or (prototype) the form
    /// interpolated toward the similarity by the star's trust.
    fn form(&self, v: u32) -> (Option<Form>, Vec<Spoke>) {
        let (cf, spokes) = form_of(self.topo, v);
        let tau = self.tau.get(v as usize).copied().unwrap_or(1.0);
        (cf.map(|cf| Form { cf, tau }), spokes)
    }

    fn p(&self, v: u32) -> Point {
        self.topo.position(v).unwrap()
    }

    fn canon(&self, cf: &Form, v: u32, u: u32) -> Option<Point> {
        if u == v {
            return Some(ORIGIN);
        }
        cf.to_normalised(self.p(u)).ok()
    }

    fn apex(&self, h: u32) -> u32 {
        self.topo.dest(self.topo.next(h).unwrap()).unwrap()
    }

    fn set(&mut self, k: usize, p: Point, e: Elem) {
        self.pos[k] = p;
        self.elems[k] = e;
    }

    fn trust_of(&self, v: u32) -> f64 {
        self.trust[v as usize]
    }

    /// Whether elements are blended toward their linear rule (output-level fallback).
    fn blending(&self) -> bool {
        matches!(
            self.proto,
            Some(Proto {
                fallback: Fallback::Blend,
                ..
            })
        )
    }

    /// Blend the Möbius point `m` with the linear point `l`: `w m + (1 − w) l`.
    fn toward_linear(m: Point, l: Point, w: f64) -> Point {
        if w >= 1.0 {
            m
        } else {
            add(scale(m, w), scale(l, 1.0 - w))
        }
    }

    // ---- edges ----

    fn blend_interior_edges(&mut self, start: usize) {
        let topo = self.topo;
        for e in 0..topo.num_edges() as u32 {
            let h = topo.edge_half_edge(e).unwrap();
            let t = topo.twin(h).unwrap();
            if t == NONE {
                continue;
            }
            let (va, vb) = (topo.origin(h).unwrap(), topo.dest(h).unwrap());
            let (a, b) = (self.p(va), self.p(vb));
            let ca = self.edge_c[h as usize];
            let cb = self.edge_c[t as usize];
            let hint = self.p(self.apex(h));
            let k = start + e as usize;
            let mut el = Elem {
                kind: Kind::Edge,
                src: e,
                rho_angle: f64::NAN,
                weight: 1.0,
                ..Default::default()
            };
            let len = norm(sub(a, b));
            let mid = scale(add(a, b), 0.5);
            for c in [ca, cb] {
                if present(&c) {
                    el.cand_far = el.cand_far.max(norm(sub(c, mid)) / len);
                }
            }
            el.pole_margin = self.edge_pm[h as usize].min(self.edge_pm[t as usize]);
            if present(&ca) && present(&cb) {
                if let Ok(rho) = cross_ratio(cb, a, ca, b) {
                    el.rho_angle = libm::atan2(rho.abs_im(), rho.w);
                }
            }
            let (ta, tb) = (self.trust_of(va), self.trust_of(vb));
            let weighted = matches!(
                self.proto,
                Some(Proto {
                    fallback: Fallback::WeightedF4 | Fallback::SpectrumWeighted,
                    ..
                })
            ) && ta.min(tb) < 1.0;
            let p = if present(&ca) && present(&cb) {
                el.rule = Rule::F4Both;
                if weighted {
                    f4_weighted(a, ca, cb, b, tb / (ta + tb).max(1e-300))
                        .or_else(|| f4_hinted(a, ca, cb, b, hint).ok())
                } else {
                    f4_hinted(a, ca, cb, b, hint).ok()
                }
            } else if present(&ca) {
                el.rule = Rule::Single;
                Some(ca)
            } else if present(&cb) {
                el.rule = Rule::Single;
                Some(cb)
            } else {
                None
            };
            let p = match p {
                Some(p) if present(&p) => p,
                _ => {
                    el.rule = Rule::Fallback;
                    self.lin[k]
                }
            };
            // Prototype: the edge point leans toward its linear rule by the trust of the two
            // stars at this spoke.
            let w = self.trust_of(va).min(self.trust_of(vb));
            el.weight = w;
            let p = if self.blending() && el.rule != Rule::Fallback && w < 1.0 {
                el.rule = Rule::Blended;
                Self::toward_linear(p, self.lin[k], w)
            } else {
                p
            };
            self.set(k, p, el);
        }
    }

    fn spoke_index(&self, v: u32, h: u32) -> usize {
        self.topo
            .star(v)
            .position(|s| s.half_edge == h)
            .unwrap_or(usize::MAX)
    }

    fn boundary_outer(&self, h: u32) -> (u32, u32) {
        let topo = self.topo;
        (
            topo.origin(topo.prev_boundary(h).unwrap()).unwrap(),
            topo.dest(topo.next_boundary(h).unwrap()).unwrap(),
        )
    }

    fn boundary_edges(&mut self, start: usize) {
        let topo = self.topo;
        for e in 0..topo.num_edges() as u32 {
            let h = topo.edge_half_edge(e).unwrap();
            if topo.twin(h).unwrap() != NONE {
                continue;
            }
            let (i0, i3) = self.boundary_outer(h);
            let p = [
                self.p(i0),
                self.p(topo.origin(h).unwrap()),
                self.p(topo.dest(h).unwrap()),
                self.p(i3),
            ];
            let k = start + e as usize;
            let mut el = Elem {
                kind: Kind::BoundaryEdge,
                src: e,
                rule: Rule::Curve,
                rho_angle: f64::NAN,
                weight: 1.0,
                ..Default::default()
            };
            if let Ok(rho) = cross_ratio(p[2], p[0], p[1], p[3]) {
                el.rho_angle = libm::atan2(rho.abs_im(), rho.w);
            }
            let q = match f4(p[0], p[1], p[2], p[3]) {
                Ok(q) => q,
                Err(_) => {
                    el.rule = Rule::Fallback;
                    self.lin[k]
                }
            };
            self.set(k, q, el);
        }
    }

    fn boundary_vertices_approximating(&mut self, start: usize) {
        let topo = self.topo;
        for v in 0..topo.num_vertices() as u32 {
            if !topo.is_boundary_vertex(v).unwrap() {
                continue;
            }
            let out_h = topo.vertex_half_edge(v).unwrap();
            let in_h = topo.prev_boundary(out_h).unwrap();
            let (b0, b1) = (topo.dest(out_h).unwrap(), topo.origin(in_h).unwrap());
            let e_out = self.pos[start + topo.edge(out_h).unwrap() as usize];
            let e_in = self.pos[start + topo.edge(in_h).unwrap() as usize];
            let (p0, p1) = (self.p(b1), self.p(b0));
            let mut el = Elem {
                kind: Kind::BoundaryVertex,
                src: v,
                rule: Rule::Curve,
                rho_angle: f64::NAN,
                weight: 1.0,
                ..Default::default()
            };
            if let Ok(rho) = cross_ratio(e_out, p0, e_in, p1) {
                el.rho_angle = libm::atan2(rho.abs_im(), rho.w);
            }
            let q = match f4(p0, e_in, e_out, p1) {
                Ok(q) => q,
                Err(_) => {
                    el.rule = Rule::Fallback;
                    self.lin[v as usize]
                }
            };
            self.set(v as usize, q, el);
        }
    }

    /// A vertex point from the star's own form, or its linear rule.
    fn vertex_point(&mut self, v: u32, m: Option<Point>) {
        let k = v as usize;
        let mut el = Elem {
            kind: Kind::Vertex,
            src: v,
            rho_angle: f64::NAN,
            weight: 1.0,
            ..Default::default()
        };
        let mut q = match m {
            Some(q) if present(&q) => q,
            _ => {
                el.rule = Rule::Fallback;
                self.lin[k]
            }
        };
        el.weight = self.trust_of(v);
        if self.blending() && el.rule != Rule::Fallback && el.weight < 1.0 {
            el.rule = Rule::Blended;
            q = Self::toward_linear(q, self.lin[k], el.weight);
        }
        self.set(k, q, el);
    }

    // ---- Loop ----

    fn run_loop(&mut self) {
        let topo = self.topo;
        let nv = topo.num_vertices();
        for v in 0..nv as u32 {
            let p = self.p(v);
            if topo.is_isolated(v).unwrap() {
                self.set(v as usize, p, Elem::default());
                continue;
            }
            let (cf, spokes) = self.form(v);
            let boundary = topo.is_boundary_vertex(v).unwrap();
            let mut vertex = None;
            if let Some(cf) = &cf {
                let ring: Option<Vec<Point>> = spokes
                    .iter()
                    .map(|s| self.canon(cf, v, s.neighbour))
                    .collect();
                if let Some(ring) = ring {
                    let n = ring.len();
                    if !boundary {
                        vertex = loop_scheme::vertex_interior(ORIGIN, &ring)
                            .and_then(|q| cf.from_normalised(q))
                            .ok();
                    }
                    for (j, s) in spokes.iter().enumerate() {
                        if !(!boundary || (j >= 1 && j + 1 < n)) || s.half_edge == NONE {
                            continue;
                        }
                        let q = loop_scheme::edge_interior(
                            ORIGIN,
                            ring[j],
                            ring[(j + 1) % n],
                            ring[(j + n - 1) % n],
                        );
                        if let Ok(c) = cf.from_normalised(q) {
                            if present(&c) {
                                self.edge_c[s.half_edge as usize] = c;
                                self.edge_pm[s.half_edge as usize] = pole_margin(&cf.cf, q);
                            }
                        }
                    }
                }
            }
            if !boundary {
                self.vertex_point(v, vertex);
            }
        }
        self.blend_interior_edges(nv);
        self.boundary_edges(nv);
        self.boundary_vertices_approximating(nv);
    }

    // ---- Catmull–Clark ----

    fn form_vertex(&self, f: u32, i: usize) -> Option<u32> {
        let verts = self.topo.face_vertices(f).unwrap();
        let d = verts.len();
        let own = verts[i];
        if !is_ear(self.topo, own) {
            return Some(own);
        }
        let h = d / 2;
        for k in 0..d {
            let step = k.div_ceil(2);
            let off = if k % 2 == 1 { h + step } else { h + d - step };
            let u = verts[(i + off) % d];
            if !is_ear(self.topo, u) {
                return Some(u);
            }
        }
        None
    }

    fn face_centroid(&self, cf: &Form, v: u32, f: u32) -> Option<Point> {
        let pts: Option<Vec<Point>> = self
            .topo
            .face_vertices(f)
            .unwrap()
            .iter()
            .map(|&u| self.canon(cf, v, u))
            .collect();
        centroid(&pts?).ok()
    }

    fn run_catmull_clark(&mut self) {
        let topo = self.topo;
        let nv = topo.num_vertices();
        let fp0 = nv + topo.num_edges();
        // Ears: their face candidates in a substitute vertex's form.
        for f in 0..topo.num_faces() as u32 {
            for (i, h) in topo.face_half_edges(f).unwrap().enumerate() {
                let v = topo.origin(h).unwrap();
                if !is_ear(topo, v) {
                    continue;
                }
                let Some(u) = self.form_vertex(f, i) else {
                    continue;
                };
                let (Some(cf), _) = self.form(u) else {
                    continue;
                };
                if let Some(c) = self.face_centroid(&cf, u, f) {
                    if let Ok(b) = cf.from_normalised(c) {
                        self.face_c[h as usize] = b;
                    }
                }
            }
        }
        for v in 0..nv as u32 {
            let p = self.p(v);
            if topo.is_isolated(v).unwrap() {
                self.set(v as usize, p, Elem::default());
                continue;
            }
            let boundary = topo.is_boundary_vertex(v).unwrap();
            let (cf, spokes) = self.form(v);
            let mut vertex = None;
            if let Some(cf) = &cf {
                let n = spokes.len();
                let mut ring = Vec::new();
                let mut fc = Vec::new();
                for s in &spokes {
                    let c = if s.face == NONE {
                        MISSING
                    } else {
                        self.face_centroid(cf, v, s.face).unwrap_or(MISSING)
                    };
                    if present(&c) {
                        if let Ok(b) = cf.from_normalised(c) {
                            self.face_c[s.half_edge as usize] = b;
                        }
                    }
                    fc.push(c);
                    ring.push(self.canon(cf, v, s.neighbour).unwrap_or(MISSING));
                }
                for (j, s) in spokes.iter().enumerate() {
                    if !(!boundary || (j >= 1 && j + 1 < n)) {
                        continue;
                    }
                    let b = ring[j];
                    let f0 = fc[(j + n - 1) % n];
                    let f1 = fc[j];
                    if present(&b) && present(&f0) && present(&f1) && s.half_edge != NONE {
                        let q = catmull_clark::edge_interior(ORIGIN, b, f0, f1);
                        if let Ok(c) = cf.from_normalised(q) {
                            if present(&c) {
                                self.edge_c[s.half_edge as usize] = c;
                                self.edge_pm[s.half_edge as usize] = pole_margin(&cf.cf, q);
                            }
                        }
                    }
                }
                if !boundary && ring.iter().all(present) && fc.iter().all(present) {
                    vertex = catmull_clark::vertex_interior(ORIGIN, &ring, &fc)
                        .and_then(|q| cf.from_normalised(q))
                        .ok();
                }
            }
            if !boundary {
                self.vertex_point(v, vertex);
            }
        }
        // Face points.
        for f in 0..topo.num_faces() as u32 {
            let verts: Vec<Point> = topo
                .face_vertices(f)
                .unwrap()
                .iter()
                .map(|&u| self.p(u))
                .collect();
            let cands: Vec<Point> = topo
                .face_half_edges(f)
                .unwrap()
                .map(|h| self.face_c[h as usize])
                .collect();
            let k = fp0 + f as usize;
            let mut el = Elem {
                kind: Kind::Face,
                src: f,
                rule: Rule::FaceChain,
                rho_angle: f64::NAN,
                weight: 1.0,
                ..Default::default()
            };
            let c0 = centroid(&verts).unwrap();
            let diam = verts
                .iter()
                .map(|p| norm(sub(*p, c0)))
                .fold(0.0, f64::max)
                .max(1e-300);
            for c in &cands {
                if present(c) {
                    el.cand_far = el.cand_far.max(norm(sub(*c, c0)) / diam);
                }
            }
            let q = if cands.iter().all(present) {
                face_point_with_ids(&verts, &cands, topo.face_vertices(f).unwrap()).ok()
            } else {
                None
            };
            let mut q = match q {
                Some(q) => q,
                None => {
                    el.rule = Rule::Fallback;
                    self.lin[k]
                }
            };
            let mut w: f64 = 1.0;
            for &u in topo.face_vertices(f).unwrap() {
                w = w.min(self.trust_of(u));
            }
            el.weight = w;
            if self.blending() && el.rule != Rule::Fallback && w < 1.0 {
                el.rule = Rule::Blended;
                q = Self::toward_linear(q, self.lin[k], w);
            }
            self.set(k, q, el);
        }
        self.blend_interior_edges(nv);
        self.boundary_edges(nv);
        self.boundary_vertices_approximating(nv);
    }

    // ---- Modified Butterfly ----

    fn across_in(&self, cf: &Form, v: u32, g: u32) -> Option<Point> {
        let topo = self.topo;
        let t = topo.twin(g).unwrap();
        if t == NONE {
            let u = self.canon(cf, v, topo.origin(g).unwrap())?;
            let w = self.canon(cf, v, topo.dest(g).unwrap())?;
            let z = self.canon(cf, v, self.apex(g))?;
            Some(butterfly::reflect(u, w, z))
        } else {
            self.canon(cf, v, self.apex(t))
        }
    }

    fn run_butterfly(&mut self) {
        let topo = self.topo;
        let nv = topo.num_vertices();
        for v in 0..nv as u32 {
            let el = Elem {
                kind: Kind::Old,
                src: v,
                rule: Rule::Copy,
                rho_angle: f64::NAN,
                weight: 1.0,
                ..Default::default()
            };
            let p = self.p(v);
            self.set(v as usize, p, el);
        }
        for v in 0..nv as u32 {
            let (Some(cf), spokes) = self.form(v) else {
                continue;
            };
            let boundary = topo.is_boundary_vertex(v).unwrap();
            let irregular = !boundary && topo.valence(v).unwrap() != 6;
            let n = spokes.len();
            for (j, s) in spokes.iter().enumerate() {
                let h = s.half_edge;
                if h == NONE || topo.twin(h).unwrap() == NONE {
                    continue;
                }
                let other = s.neighbour;
                let other_irregular =
                    !topo.is_boundary_vertex(other).unwrap() && topo.valence(other).unwrap() != 6;
                let cand: Option<Point> = (|| {
                    if irregular {
                        let ring: Option<Vec<Point>> = (0..n)
                            .map(|k| self.canon(&cf, v, spokes[(j + k) % n].neighbour))
                            .collect();
                        return butterfly::zorin_stencil(ORIGIN, &ring?).ok();
                    }
                    if other_irregular {
                        return None;
                    }
                    let t = topo.twin(h).unwrap();
                    let a0 = ORIGIN;
                    let a1 = self.canon(&cf, v, other)?;
                    let b0 = self.canon(&cf, v, self.apex(h))?;
                    let b1 = self.canon(&cf, v, self.apex(t))?;
                    let c0 = self.across_in(&cf, v, topo.prev(h).unwrap())?;
                    let c3 = self.across_in(&cf, v, topo.next(t).unwrap())?;
                    Some([
                        a0[0] * 0.5 + a1[0] * 0.5 + (b0[0] + b1[0]) * 0.125
                            - (c0[0] + c3[0]) * 0.125,
                        a0[1] * 0.5 + a1[1] * 0.5 + (b0[1] + b1[1]) * 0.125
                            - (c0[1] + c3[1]) * 0.125,
                        a0[2] * 0.5 + a1[2] * 0.5 + (b0[2] + b1[2]) * 0.125
                            - (c0[2] + c3[2]) * 0.125,
                    ])
                })();
                if let Some(q) = cand {
                    if let Ok(c) = cf.from_normalised(q) {
                        self.edge_c[h as usize] = c;
                        self.edge_pm[h as usize] = pole_margin(&cf.cf, q);
                    }
                }
            }
        }
        self.blend_interior_edges(nv);
        self.boundary_edges(nv);
    }
}

/// One re-implemented Möbius step (`proto = None`: the paper's rules as the library runs
/// them).
fn my_step(s: Scheme, m: &OwnedMesh, proto: Option<Proto>) -> Step {
    let trust = proto.map(|p| star_trust(s, m, &p));
    my_step_with(s, m, proto, trust)
}

/// The prototype's trust in every star (1: the paper's rule; docs/folds.md): the least of
/// the radial spread's, its edge candidates' positions' and its edges' F4 angles' trusts.
/// Every quantity is read in a normalised canonical frame or from a cross-ratio, so the
/// trust is Möbius-invariant.
fn star_trust(s: Scheme, m: &OwnedMesh, p: &Proto) -> Vec<f64> {
    let paper = my_step_with(s, m, None, None);
    build(m, |topo| {
        let nv = topo.num_vertices();
        let mut trust: Vec<f64> = paper
            .stars
            .iter()
            .map(|sd| {
                if sd.form && !sd.boundary {
                    // A neighbour sent to infinity (spread ∞) is the least trusted.
                    let sp = sd.spread();
                    if sp.is_finite() {
                        ramp(sp.ln(), p.spread_hi.ln(), p.spread_lo.ln())
                    } else {
                        0.0
                    }
                } else {
                    1.0
                }
            })
            .collect();
        for v in 0..nv as u32 {
            // Boundary stars keep the paper's rules (their forms have their own conditioning:
            // a square corner sends its diagonal neighbour to infinity by construction).
            if topo.is_boundary_vertex(v).unwrap() {
                continue;
            }
            let (Some(cf), spokes) = form_of(topo, v) else {
                continue;
            };
            for sp in &spokes {
                if sp.half_edge == NONE {
                    continue;
                }
                let c = paper.edge_c[sp.half_edge as usize];
                if !present(&c) {
                    continue;
                }
                let (Ok(e), Ok(u)) = (
                    cf.to_normalised(c),
                    cf.to_normalised(topo.position(sp.neighbour).unwrap()),
                ) else {
                    continue;
                };
                let t = dot(e, u) / dot(u, u);
                let g = ramp(t, 0.0, p.t_margin).min(ramp(t, 1.0, 1.0 - p.t_margin));
                trust[v as usize] = trust[v as usize].min(g);
            }
        }
        let ne = topo.num_edges() as u32;
        for e in 0..ne {
            let k = nv + e as usize;
            let el = paper.elems.get(k).copied().unwrap_or_default();
            if el.kind != Kind::Edge || !el.rho_angle.is_finite() {
                continue;
            }
            let g = ramp(deg(el.rho_angle), p.rho_hi, p.rho_lo);
            // Only between two interior stars: a boundary star's candidate can vanish exactly
            // (the paper's rule drops a candidate at infinity) and reappear in a Möbius image.
            let (a, b) = topo.edge_vertices(e).unwrap();
            if !topo.is_boundary_vertex(a).unwrap() && !topo.is_boundary_vertex(b).unwrap() {
                trust[a as usize] = trust[a as usize].min(g);
                trust[b as usize] = trust[b as usize].min(g);
            }
        }
        trust
    })
}

fn my_step_with(s: Scheme, m: &OwnedMesh, proto: Option<Proto>, trust: Option<Vec<f64>>) -> Step {
    let (lin_mesh, _) = lib_step(s, m, false);
    build(m, |topo| {
        let nv = topo.num_vertices();
        let nh = topo.num_half_edges();
        let stars: Vec<StarDiag> = (0..nv as u32).map(|v| star_diag(topo, v)).collect();
        let trust: Vec<f64> = trust.unwrap_or_else(|| vec![1.0; nv]);
        let tau = match proto {
            Some(Proto {
                fallback: Fallback::Spectrum | Fallback::SpectrumWeighted,
                ..
            }) => trust.clone(),
            _ => vec![1.0; nv],
        };
        let mut ctx = Ctx {
            tau,
            topo,
            s,
            proto,
            stars,
            trust,
            pos: vec![MISSING; lin_mesh.positions.len()],
            elems: vec![Elem::default(); lin_mesh.positions.len()],
            lin: lin_mesh.positions.clone(),
            edge_c: vec![MISSING; nh],
            face_c: vec![MISSING; nh],
            edge_pm: vec![f64::INFINITY; nh],
            _t: std::marker::PhantomData,
        };
        match s {
            Scheme::Loop => ctx.run_loop(),
            Scheme::CatmullClark => ctx.run_catmull_clark(),
            Scheme::ModifiedButterfly => ctx.run_butterfly(),
            _ => {
                eprintln!("only loop, butterfly and catmull-clark are re-implemented");
                std::process::exit(1)
            }
        }
        let flagged = ctx.trust.iter().filter(|&&t| t < 1.0).count() as u32;
        let blended = ctx.elems.iter().filter(|e| e.weight < 1.0).count() as u32;
        Step {
            out: OwnedMesh {
                positions: ctx.pos,
                ..lin_mesh.clone()
            },
            lin: ctx.lin,
            elems: ctx.elems,
            stars: ctx.stars,
            edge_c: ctx.edge_c,
            flagged,
            blended,
        }
    })
}

// ------------------------------------------------------------------------------------------
// Commands
// ------------------------------------------------------------------------------------------

fn cmd_census(s: Scheme, levels: usize, files: &[String]) {
    println!("mesh\tlevel\tmobius\tlinear\tfallbacks\tguarded\tguarded_elements");
    for f in files {
        let m = load(f);
        let (mut cm, mut cl, mut cg) = (m.clone(), m.clone(), m.clone());
        for l in 1..=levels {
            let (nm, fb) = lib_step(s, &cm, true);
            cm = nm;
            cl = lib_step(s, &cl, false).0;
            let (ng, ge) = guarded_step(s, &cg);
            cg = ng;
            println!(
                "{}\t{}\t{}\t{}\t{}\t{}\t{}",
                stem(f),
                l,
                folds(&cm).len(),
                folds(&cl).len(),
                fb,
                folds(&cg).len(),
                ge
            );
        }
    }
}

fn cmd_check(s: Scheme, levels: usize, files: &[String]) {
    for f in files {
        let mut cur = load(f);
        for l in 1..=levels {
            let (lib, _) = lib_step(s, &cur, true);
            let mine = my_step(s, &cur, None).out;
            let mut diff = 0usize;
            let mut worst: f64 = 0.0;
            for (a, b) in lib.positions.iter().zip(&mine.positions) {
                if a != b {
                    diff += 1;
                    worst = worst.max(norm(sub(*a, *b)));
                }
            }
            let same_conn = lib.offsets == mine.offsets && lib.indices == mine.indices;
            println!(
                "{}\tlevel {}\tvertices {}\tdiffering {}\tworst {:e}\tconnectivity same: {}",
                stem(f),
                l,
                lib.positions.len(),
                diff,
                worst,
                same_conn
            );
            cur = lib;
        }
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if args.len() < 4 {
        eprintln!("usage: fold_census census|check|trace|proto|equiv SCHEME [LEVELS] IN.off...");
        std::process::exit(1);
    }
    let s = scheme_arg(&args[2]);
    match args[1].as_str() {
        "census" => cmd_census(s, args[3].parse().unwrap(), &args[4..]),
        "check" => cmd_check(s, args[3].parse().unwrap(), &args[4..]),
        "trace" => {
            let list = args.iter().any(|a| a == "--list");
            let files: Vec<String> = args[4..]
                .iter()
                .filter(|a| *a != "--list")
                .cloned()
                .collect();
            cmd_trace(s, args[3].parse().unwrap(), &files, list)
        }
        "selftest" => selftest(),
        "regular" => cmd_regular(),
        "gridprobe" => cmd_gridprobe(),
        "equiv" => cmd_equiv(s, &args[3..]),
        "proto" => {
            let mut p = PROTO_DEFAULT;
            let mut files = Vec::new();
            for a in &args[4..] {
                if let Some(v) = a.strip_prefix("--spread=") {
                    let mut it = v.split(',').map(|x| x.parse::<f64>().unwrap());
                    p.spread_lo = it.next().unwrap();
                    p.spread_hi = it.next().unwrap();
                } else if let Some(v) = a.strip_prefix("--t=") {
                    p.t_margin = v.parse().unwrap();
                } else if let Some(v) = a.strip_prefix("--rho=") {
                    let mut it = v.split(',').map(|x| x.parse::<f64>().unwrap());
                    p.rho_lo = it.next().unwrap();
                    p.rho_hi = it.next().unwrap();
                } else {
                    files.push(a.clone());
                }
            }
            eprintln!("{p:?}");
            cmd_proto(s, args[3].parse().unwrap(), &files, p)
        }
        "probe" => cmd_probe(s, &args[3], args[4].parse().unwrap()),
        "features" => cmd_features(s, args[3].parse().unwrap(), &args[4..]),
        other => {
            eprintln!("unknown command {other}");
            std::process::exit(1)
        }
    }
}

// ------------------------------------------------------------------------------------------
// Tracing folds to elements
// ------------------------------------------------------------------------------------------

fn face_verts(m: &OwnedMesh, f: u32) -> &[u32] {
    &m.indices[m.offsets[f as usize] as usize..m.offsets[f as usize + 1] as usize]
}

fn newell(pos: &[Point], idx: &[u32]) -> Point {
    let mut n = [0.0; 3];
    for i in 0..idx.len() {
        n = add(
            n,
            cross(pos[idx[i] as usize], pos[idx[(i + 1) % idx.len()] as usize]),
        );
    }
    n
}

/// The output vertex held responsible for the fold `(fa, fb)`: among the two faces'
/// vertices, the one whose move to its linear position unfolds the edge, the farthest from
/// its linear position first; `(vertex, unfolded_by_it)`.
fn culprit(st: &Step, fa: u32, fb: u32) -> (u32, bool) {
    let m = &st.out;
    let (ia, ib) = (face_verts(m, fa).to_vec(), face_verts(m, fb).to_vec());
    let mut cand: Vec<u32> = ia.iter().chain(ib.iter()).copied().collect();
    cand.sort();
    cand.dedup();
    let dev = |k: u32| norm(sub(m.positions[k as usize], st.lin[k as usize]));
    cand.sort_by(|a, b| dev(*b).partial_cmp(&dev(*a)).unwrap());
    let mut pos = m.positions.clone();
    for &k in &cand {
        let keep = pos[k as usize];
        pos[k as usize] = st.lin[k as usize];
        let ok = dot(newell(&pos, &ia), newell(&pos, &ib)) >= 0.0;
        pos[k as usize] = keep;
        if ok {
            return (k, true);
        }
    }
    (cand[0], false)
}

/// The Euclidean opposite-angle sum of interior edge `e` of a triangle mesh (> π:
/// non-Delaunay), NaN otherwise.
fn opposite_angle_sum(topo: &Topology<'_, '_>, e: u32) -> f64 {
    let h = topo.edge_half_edge(e).unwrap();
    let t = topo.twin(h).unwrap();
    if t == NONE || topo.face_size(topo.face(h).unwrap()).unwrap() != 3 {
        return f64::NAN;
    }
    if topo.face_size(topo.face(t).unwrap()).unwrap() != 3 {
        return f64::NAN;
    }
    let p = |v: u32| topo.position(v).unwrap();
    let a = p(topo.origin(h).unwrap());
    let b = p(topo.dest(h).unwrap());
    let ang = |c: Point| {
        let (x, y) = (sub(a, c), sub(b, c));
        libm::atan2(norm(cross(x, y)), dot(x, y))
    };
    let c = p(topo.dest(topo.next(h).unwrap()).unwrap());
    let d = p(topo.dest(topo.next(t).unwrap()).unwrap());
    ang(c) + ang(d)
}

/// The cause of one traced fold: the first of these that the culprit element shows (docs/folds.md).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Cause {
    /// A boundary curve rule made the point.
    Boundary,
    /// F4 of the edge's two candidates within 20° of its negative-real cut (ρ angle ≥ 160°).
    F4NearCut,
    /// A candidate lies behind the star's centre or beyond the neighbour along its spoke in
    /// its own canonical frame (`t = ⟨E_j, C_j⟩/|C_j|² ∉ [0, 1]`).
    CandidateOutOfOrder,
    /// An involved star's canonical ring has radial spread `max|C_i|/min|C_i| ≥ 8`.
    HighSpread,
    /// Milder versions: ρ angle in [120°, 160°), `t` within 0.15 of 0 or 1, or spread in [4, 8).
    Marginal,
    /// None of those, but an involved star is non-Delaunay (a reflex tangent-polygon corner).
    NonDelaunayOnly,
    /// A single (partial) candidate taken as the edge point.
    SingleCandidate,
    /// Nothing above: Delaunay, well-conditioned neighbourhood.
    Other,
}

struct Traced {
    level: usize,
    out_vertex: u32,
    repaired: bool,
    elem: Elem,
    cause: Cause,
    /// Turning angles (degrees) of the involved stars' corners at the element.
    turn_at: f64,
    /// Least turning angle (degrees) over the involved stars.
    turn_min: f64,
    c_fold: u32,
    pole_ratio: f64,
    eu_sum: f64,
    inherited: bool,
    /// An involved vertex is an ear (boundary, one face) or on the boundary.
    ear: bool,
    boundary: bool,
    dev_rel: f64,
    /// Angle (degrees) between the two faces' normals with the linear rule's positions at
    /// this level, and with the Möbius positions.
    lin_angle: f64,
    mob_angle: f64,
    where_: Point,
    input_vertex: u32,
}

fn deg(x: f64) -> f64 {
    x.to_degrees()
}

fn trace_step(
    st: &Step,
    topo_mesh: &OwnedMesh,
    level: usize,
    prev_fold_faces: &std::collections::HashSet<u32>,
) -> Vec<Traced> {
    let fl = folds(&st.out);
    build(topo_mesh, |topo| {
        let mut out = Vec::new();
        // Faces of the previous level around a vertex.
        let near_prev_fold = |v: u32| -> bool {
            topo.star(v)
                .chain(topo.star(v).flat_map(|s| topo.star(s.neighbour)))
                .any(|s| s.face != NONE && prev_fold_faces.contains(&s.face))
        };
        for &(_, fa, fb) in &fl {
            let (k, repaired) = culprit(st, fa, fb);
            let el = st.elems[k as usize];
            let mut involved: Vec<(u32, usize)> = Vec::new(); // (vertex, spoke index or MAX)
            let mut eu_sum = f64::NAN;
            let mut input_vertex = el.src;
            match el.kind {
                Kind::Vertex | Kind::BoundaryVertex | Kind::Old => {
                    involved.push((el.src, usize::MAX));
                }
                Kind::Edge | Kind::BoundaryEdge => {
                    let h = topo.edge_half_edge(el.src).unwrap();
                    let t = topo.twin(h).unwrap();
                    let (a, b) = (topo.origin(h).unwrap(), topo.dest(h).unwrap());
                    input_vertex = a;
                    let ja = topo.star(a).position(|s| s.edge == el.src).unwrap();
                    let jb = topo.star(b).position(|s| s.edge == el.src).unwrap();
                    involved.push((a, ja));
                    involved.push((b, jb));
                    if t != NONE {
                        eu_sum = opposite_angle_sum(topo, el.src);
                    }
                }
                Kind::Face => {
                    let vs = topo.face_vertices(el.src).unwrap();
                    input_vertex = vs[0];
                    for &u in vs {
                        let j = topo
                            .star(u)
                            .position(|s| s.face == el.src)
                            .unwrap_or(usize::MAX);
                        involved.push((u, j));
                    }
                }
            }
            let mut turn_at = f64::INFINITY;
            let mut turn_min = f64::INFINITY;
            let mut c_fold = 0;
            let mut pole_ratio: f64 = 0.0;
            for &(v, j) in &involved {
                let sd = &st.stars[v as usize];
                if !sd.form {
                    continue;
                }
                for (i, &a) in sd.turn_angle.iter().enumerate() {
                    if !a.is_finite() {
                        continue;
                    }
                    turn_min = turn_min.min(a);
                    // The spoke's own corner; for a face, the corners of its two spokes.
                    let at = if el.kind == Kind::Face {
                        j != usize::MAX && (i == j || i == (j + 1) % sd.n)
                    } else {
                        j == usize::MAX || i == j
                    };
                    if at {
                        turn_at = turn_at.min(a);
                    }
                }
                c_fold += sd.c_fold;
                pole_ratio = pole_ratio.max(sd.pole_ratio);
            }
            // Candidate positions along their spokes, in their own canonical frames.
            let mut t_bad: f64 = 0.0; // 0 fine, 1 marginal, 2 out of order
            let mut spread: f64 = 0.0;
            for &(v, _) in &involved {
                let sd = &st.stars[v as usize];
                if sd.form {
                    spread = spread.max(sd.spread());
                }
                let (Some(cf), spokes) = form_of(topo, v) else {
                    continue;
                };
                for sp in &spokes {
                    if sp.half_edge == NONE {
                        continue;
                    }
                    // Edge points: only the edge's own spoke; others: every spoke of the star.
                    if matches!(el.kind, Kind::Edge) && sp.edge != el.src {
                        continue;
                    }
                    let c = st.edge_c[sp.half_edge as usize];
                    let (Ok(e), Ok(u)) = (
                        cf.to_normalised(c),
                        cf.to_normalised(topo.position(sp.neighbour).unwrap()),
                    ) else {
                        continue;
                    };
                    let t = dot(e, u) / dot(u, u);
                    if !(0.0..=1.0).contains(&t) {
                        t_bad = 2.0;
                    } else if !(0.15..=0.85).contains(&t) {
                        t_bad = t_bad.max(1.0);
                    }
                }
            }
            let rho = deg(el.rho_angle);
            let cause = if matches!(el.kind, Kind::BoundaryEdge | Kind::BoundaryVertex) {
                Cause::Boundary
            } else if rho >= 160.0 {
                Cause::F4NearCut
            } else if t_bad >= 2.0 {
                Cause::CandidateOutOfOrder
            } else if spread >= 8.0 {
                Cause::HighSpread
            } else if rho >= 120.0 || t_bad >= 1.0 || spread >= 4.0 {
                Cause::Marginal
            } else if turn_min < 0.0 {
                Cause::NonDelaunayOnly
            } else if el.rule == Rule::Single {
                Cause::SingleCandidate
            } else {
                Cause::Other
            };
            let inherited = level > 1 && involved.iter().any(|&(v, _)| near_prev_fold(v));
            // Local scale: the longest edge of the two faces.
            let mut len: f64 = 0.0;
            for f in [fa, fb] {
                let idx = face_verts(&st.out, f);
                for i in 0..idx.len() {
                    let p = st.lin[idx[i] as usize];
                    let q = st.lin[idx[(i + 1) % idx.len()] as usize];
                    len = len.max(norm(sub(p, q)));
                }
            }
            let dev_rel =
                norm(sub(st.out.positions[k as usize], st.lin[k as usize])) / len.max(1e-300);
            let ang = |pos: &[Point]| {
                let (na, nb) = (
                    newell(pos, face_verts(&st.out, fa)),
                    newell(pos, face_verts(&st.out, fb)),
                );
                deg(libm::atan2(norm(cross(na, nb)), dot(na, nb)))
            };
            let ear = involved.iter().any(|&(v, _)| is_ear(topo, v));
            let boundary = involved
                .iter()
                .any(|&(v, _)| topo.is_boundary_vertex(v).unwrap());
            out.push(Traced {
                ear,
                boundary,
                lin_angle: ang(&st.lin),
                mob_angle: ang(&st.out.positions),
                level,
                out_vertex: k,
                repaired,
                elem: el,
                cause,
                turn_at: deg(turn_at),
                turn_min: deg(turn_min),
                c_fold,
                pole_ratio,
                eu_sum: deg(eu_sum),
                inherited,
                dev_rel,
                where_: st.out.positions[k as usize],
                input_vertex,
            });
        }
        out
    })
}

fn fold_faces(m: &OwnedMesh) -> std::collections::HashSet<u32> {
    let mut s = std::collections::HashSet::new();
    for (_, a, b) in folds(m) {
        s.insert(a);
        s.insert(b);
    }
    s
}

fn cmd_trace(s: Scheme, levels: usize, files: &[String], list: bool) {
    for f in files {
        let mut cur = load(f);
        let mut prev_faces = std::collections::HashSet::new();
        for l in 1..=levels {
            let st = my_step(s, &cur, None);
            let tr = trace_step(&st, &cur, l, &prev_faces);
            let mut by: std::collections::BTreeMap<(Cause, bool), usize> = Default::default();
            let mut kinds: std::collections::BTreeMap<String, usize> = Default::default();
            for t in &tr {
                *by.entry((t.cause, t.inherited)).or_default() += 1;
                *kinds
                    .entry(format!("{:?}/{:?}", t.elem.kind, t.elem.rule))
                    .or_default() += 1;
                if list {
                    println!(
                        "  L{} lin {:.0} mob {:.0} out {} {:?}/{:?} src {} inv {} rep {} cause {:?} inh {} dev {:.3} rho {:.1} far {:.2} pm {:.3} turn_at {:.1} turn_min {:.1} cfold {} |c|/r {:.2} eu {:.1} at {:?}",
                        t.level, t.lin_angle, t.mob_angle, t.out_vertex, t.elem.kind, t.elem.rule, t.elem.src,
                        t.input_vertex, t.repaired, t.cause, t.inherited, t.dev_rel,
                        deg(t.elem.rho_angle), t.elem.cand_far, t.elem.pole_margin,
                        t.turn_at, t.turn_min, t.c_fold, t.pole_ratio, t.eu_sum, t.where_
                    );
                }
            }
            let single = tr.iter().filter(|t| t.repaired).count();
            println!(
                "    culprits touching an ear {} | touching a boundary vertex {}",
                tr.iter().filter(|t| t.ear).count(),
                tr.iter().filter(|t| t.boundary).count()
            );
            let bins = [0.0, 30.0, 60.0, 75.0, 90.0, 181.0];
            let mut hist = [0usize; 5];
            for t in &tr {
                for i in 0..5 {
                    if t.lin_angle >= bins[i] && t.lin_angle < bins[i + 1] {
                        hist[i] += 1;
                    }
                }
            }
            println!(
                "    linear angle of the folded pair: <30° {} | 30–60° {} | 60–75° {} | 75–90° {} | ≥90° {}",
                hist[0], hist[1], hist[2], hist[3], hist[4]
            );
            println!(
                "{}\t{:?}\tlevel {}\tfolds {}\trepaired by one vertex {}",
                stem(f),
                s,
                l,
                tr.len(),
                single
            );
            for ((c, inh), n) in &by {
                println!(
                    "    cause {:?}{}\t{}",
                    c,
                    if *inh {
                        " (near a fold of the previous level)"
                    } else {
                        ""
                    },
                    n
                );
            }
            for (k, n) in &kinds {
                println!("    element {k}\t{n}");
            }
            prev_faces = fold_faces(&st.out);
            cur = st.out;
        }
    }
}

/// The weighted F4 against F4 (`w = ½`) and its ends (`w → 0`: `b`, `w → 1`: `c`).
fn selftest_f4_weighted() {
    let pts = [
        [
            [0.0, 0.0, 0.0],
            [1.0, 0.2, 0.1],
            [2.0, -0.1, 0.3],
            [3.1, 0.0, -0.2],
        ],
        [
            [0.3, 1.0, 0.0],
            [1.0, 0.7, 0.4],
            [1.8, 0.9, -0.3],
            [2.2, 2.0, 0.5],
        ],
    ];
    for [a, b, c, d] in pts {
        let half = f4_weighted(a, b, c, d, 0.5).unwrap();
        let f = f4(a, b, c, d).unwrap();
        let lo = f4_weighted(a, b, c, d, 1e-6).unwrap();
        let hi = f4_weighted(a, b, c, d, 1.0 - 1e-6).unwrap();
        println!(
            "f4_weighted: |w=½ − F4| {:.1e}, |w→0 − b| {:.1e}, |w→1 − c| {:.1e}",
            norm(sub(half, f)),
            norm(sub(lo, b)),
            norm(sub(hi, c))
        );
    }
}

/// The sign convention of the tangent-polygon turning on planar stars: a regular hexagon
/// star is convex everywhere; pushing `u_0` out makes the spoke `(v, u_0)` non-Delaunay
/// (opposite angles sum > π), and only its corner must turn negative.
fn selftest() {
    selftest_f4_weighted();
    for push in [1.0, 1.5, 2.5] {
        let mut p = vec![[0.0, 0.0, 0.0]];
        for i in 0..6 {
            let t = std::f64::consts::PI / 3.0 * i as f64;
            let r = if i == 0 { push } else { 1.0 };
            p.push([r * libm::cos(t), r * libm::sin(t), 0.0]);
        }
        let faces: Vec<Vec<u32>> = (0..6).map(|i| vec![0, 1 + i, 1 + (i + 1) % 6]).collect();
        let m = OwnedMesh::from_faces(p, &faces);
        build(&m, |topo| {
            let sd = star_diag(topo, 0);
            let ring: Vec<u32> = topo.star(0).map(|s| s.neighbour).collect();
            let eu: Vec<f64> = topo
                .star(0)
                .map(|s| deg(opposite_angle_sum(topo, s.edge)))
                .collect();
            println!(
                "push {push}: ring {ring:?} turn {:?} eu {:?} cfold {}",
                sd.turn_angle
                    .iter()
                    .map(|a| deg(*a).round())
                    .collect::<Vec<_>>(),
                eu.iter().map(|a| a.round()).collect::<Vec<_>>(),
                sd.c_fold
            );
        });
    }
}

/// Least and greatest turning angle (degrees) of a star's tangent polygon, and the angle at
/// spoke `j` (NaN without a form).
fn star_turns(sd: &StarDiag, j: usize) -> (f64, f64, f64) {
    if !sd.form {
        return (f64::NAN, f64::NAN, f64::NAN);
    }
    let mut lo = f64::INFINITY;
    let mut hi = f64::NEG_INFINITY;
    for a in sd.turn_angle.iter().filter(|a| a.is_finite()) {
        lo = lo.min(*a);
        hi = hi.max(*a);
    }
    let at = sd.turn_angle.get(j).copied().unwrap_or(f64::NAN);
    (deg(lo), deg(hi), deg(at))
}

/// Every element of every level as one TSV row (for docs/folds.md's threshold study).
fn cmd_features(s: Scheme, levels: usize, files: &[String]) {
    println!("mesh\tlevel\tk\tkind\trule\tculprit\tlo_a\thi_a\tat_a\tlo_b\thi_b\tat_b\trho\tcfold\tdis\tdev\tspread\tlograd\tfar");
    for f in files {
        let mut cur = load(f);
        for l in 1..=levels {
            let st = my_step(s, &cur, None);
            let mut culprits = std::collections::HashSet::new();
            for (_, fa, fb) in folds(&st.out) {
                culprits.insert(culprit(&st, fa, fb).0);
            }
            build(&cur, |topo| {
                for (k, el) in st.elems.iter().enumerate() {
                    let (a, b) = match el.kind {
                        Kind::Vertex => {
                            let sd = &st.stars[el.src as usize];
                            (star_turns(sd, usize::MAX), (f64::NAN, f64::NAN, f64::NAN))
                        }
                        Kind::Edge => {
                            let h = topo.edge_half_edge(el.src).unwrap();
                            let (va, vb) = (topo.origin(h).unwrap(), topo.dest(h).unwrap());
                            let ja = topo.star(va).position(|s| s.edge == el.src).unwrap();
                            let jb = topo.star(vb).position(|s| s.edge == el.src).unwrap();
                            (
                                star_turns(&st.stars[va as usize], ja),
                                star_turns(&st.stars[vb as usize], jb),
                            )
                        }
                        Kind::Face => {
                            let vs = topo.face_vertices(el.src).unwrap();
                            let mut lo = f64::INFINITY;
                            let mut hi = f64::NEG_INFINITY;
                            for &u in vs {
                                let (l, h, _) = star_turns(&st.stars[u as usize], usize::MAX);
                                if l.is_finite() {
                                    lo = lo.min(l);
                                    hi = hi.max(h);
                                }
                            }
                            ((lo, hi, f64::NAN), (f64::NAN, f64::NAN, f64::NAN))
                        }
                        _ => continue,
                    };
                    let cf = match el.kind {
                        Kind::Vertex => st.stars[el.src as usize].c_fold,
                        _ => 0,
                    };
                    // Disagreement of an edge's two candidates: |log ρ|, ρ = cr[e_k, v_j, e_j, v_k].
                    let mut dis = f64::NAN;
                    let scale_len;
                    match el.kind {
                        Kind::Edge => {
                            let h = topo.edge_half_edge(el.src).unwrap();
                            let t = topo.twin(h).unwrap();
                            let a = topo.position(topo.origin(h).unwrap()).unwrap();
                            let b = topo.position(topo.dest(h).unwrap()).unwrap();
                            scale_len = norm(sub(a, b));
                            let (ca, cb) = (st.edge_c[h as usize], st.edge_c[t as usize]);
                            if present(&ca) && present(&cb) {
                                if let Ok(r) = cross_ratio(cb, a, ca, b) {
                                    if let Some(lg) = r.log() {
                                        dis = lg.abs();
                                    }
                                }
                            }
                        }
                        Kind::Vertex => {
                            let p = topo.position(el.src).unwrap();
                            let ls: Vec<f64> = topo
                                .star(el.src)
                                .map(|s| norm(sub(topo.position(s.neighbour).unwrap(), p)))
                                .collect();
                            scale_len = ls.iter().sum::<f64>() / ls.len() as f64;
                        }
                        _ => {
                            let vs = topo.face_vertices(el.src).unwrap();
                            let p0 = topo.position(vs[0]).unwrap();
                            scale_len = vs
                                .iter()
                                .map(|&u| norm(sub(topo.position(u).unwrap(), p0)))
                                .fold(0.0, f64::max);
                        }
                    }
                    let dev = norm(sub(st.out.positions[k], st.lin[k])) / scale_len;
                    // The largest radial spread of the involved stars, and the largest
                    // |log |C_j|| at the element's spokes.
                    let mut spread: f64 = f64::NAN;
                    let mut lograd: f64 = f64::NAN;
                    let mut take = |v: u32, j: usize| {
                        let sd = &st.stars[v as usize];
                        if !sd.form {
                            return;
                        }
                        spread = if spread.is_nan() {
                            sd.spread()
                        } else {
                            spread.max(sd.spread())
                        };
                        let lr = if j == usize::MAX {
                            sd.radial.iter().map(|x| x.ln().abs()).fold(0.0, f64::max)
                        } else {
                            sd.radial[j].ln().abs()
                        };
                        lograd = if lograd.is_nan() { lr } else { lograd.max(lr) };
                    };
                    match el.kind {
                        Kind::Vertex => take(el.src, usize::MAX),
                        Kind::Edge => {
                            let h = topo.edge_half_edge(el.src).unwrap();
                            let (va, vb) = (topo.origin(h).unwrap(), topo.dest(h).unwrap());
                            take(va, topo.star(va).position(|s| s.edge == el.src).unwrap());
                            take(vb, topo.star(vb).position(|s| s.edge == el.src).unwrap());
                        }
                        _ => {
                            for &u in topo.face_vertices(el.src).unwrap() {
                                take(u, usize::MAX);
                            }
                        }
                    }
                    println!(
                        "{}\t{}\t{}\t{:?}\t{:?}\t{}\t{:.2}\t{:.2}\t{:.2}\t{:.2}\t{:.2}\t{:.2}\t{:.2}\t{}\t{:.4}\t{:.4}\t{:.4}\t{:.4}\t{:.4}",
                        stem(f),
                        l,
                        k,
                        el.kind,
                        el.rule,
                        culprits.contains(&(k as u32)) as u8,
                        a.0,
                        a.1,
                        a.2,
                        b.0,
                        b.1,
                        b.2,
                        deg(el.rho_angle),
                        cf,
                        dis,
                        dev,
                        spread,
                        lograd,
                        el.cand_far
                    );
                }
            });
            cur = st.out;
        }
    }
}

/// Everything about one edge element of the first level: both stars in their canonical
/// frames, the Loop candidates there and back, the F4 blend and the linear point.
fn cmd_probe(s: Scheme, file: &str, e: u32) {
    let m = load(file);
    let st = my_step(s, &m, None);
    build(&m, |topo| {
        let h = topo.edge_half_edge(e).unwrap();
        let t = topo.twin(h).unwrap();
        let nv = topo.num_vertices();
        let k = nv + e as usize;
        let (va, vb) = (topo.origin(h).unwrap(), topo.dest(h).unwrap());
        let pa = topo.position(va).unwrap();
        let pb = topo.position(vb).unwrap();
        let len = norm(sub(pa, pb));
        println!("edge {e}: {va} -> {vb}, length {len:.4e}");
        println!(
            "  mobius {:?}\n  linear {:?}\n  |mob-lin|/len {:.3}",
            st.out.positions[k],
            st.lin[k],
            norm(sub(st.out.positions[k], st.lin[k])) / len
        );
        for (v, hh) in [(va, h), (vb, t)] {
            let (cf, spokes) = form_of(topo, v);
            let cf = cf.unwrap();
            let sd = &st.stars[v as usize];
            let pv = topo.position(v).unwrap();
            println!(
                "  star {v}: n {} c {:?} r {:.4e} |c|/r {:.3} cfold {}",
                sd.n, cf.c, cf.r, sd.pole_ratio, sd.c_fold
            );
            let frame = |x: Point| sub(x, pv);
            for (j, sp) in spokes.iter().enumerate() {
                let u = topo.position(sp.neighbour).unwrap();
                let ci = cf.to_normalised(u).unwrap();
                println!(
                    "    spoke {j} -> {} turn {:7.1}° |u-v|/len {:.3} C {:?}{}",
                    sp.neighbour,
                    deg(sd.turn_angle[j]),
                    norm(sub(u, pv)) / len,
                    ci.map(|x| (x * 1000.0).round() / 1000.0),
                    if sp.half_edge == hh {
                        "   <== the edge"
                    } else {
                        ""
                    }
                );
                let _ = frame;
            }
            let c = st.edge_c[hh as usize];
            let cn = cf.to_normalised(c).unwrap();
            println!(
                "    candidate (normalised) {:?}, back |c-mid|/len {:.3}, pole {:?}",
                cn.map(|x| (x * 1000.0).round() / 1000.0),
                norm(sub(c, scale(add(pa, pb), 0.5))) / len,
                scale(cf.c, -cf.r / dot(cf.c, cf.c)).map(|x| (x * 1000.0).round() / 1000.0)
            );
        }
        println!("  rho angle {:.1}°", deg(st.elems[k].rho_angle));
    });
}

fn proto_levels(s: Scheme, m: &OwnedMesh, levels: usize, p: Proto) -> (OwnedMesh, Vec<(u32, u32)>) {
    let mut cur = m.clone();
    let mut flags = Vec::new();
    for _ in 0..levels {
        let st = my_step(s, &cur, Some(p));
        let nv = st.stars.len() as u32;
        let _ = nv;
        flags.push((st.flagged, st.stars.len() as u32));
        cur = st.out;
    }
    (cur, flags)
}

/// Folded edges of the paper's rules, the prototype (both fallbacks) and the linear scheme;
/// stars flagged per level.
fn cmd_proto(s: Scheme, levels: usize, files: &[String], p: Proto) {
    println!(
        "mesh\tlevels\tpaper\tspectrum\tblend\tweighted-F4\tspectrum+weighted\tlinear\tflagged stars per level (spectrum run)"
    );
    for f in files {
        let m = load(f);
        for l in 1..=levels {
            let paper = folds(&lib_levels(s, &m, l, true)).len();
            let lin = folds(&lib_levels(s, &m, l, false)).len();
            let (spec, flags) = proto_levels(
                s,
                &m,
                l,
                Proto {
                    fallback: Fallback::Spectrum,
                    ..p
                },
            );
            let (blend, _) = proto_levels(
                s,
                &m,
                l,
                Proto {
                    fallback: Fallback::Blend,
                    ..p
                },
            );
            let (wf4, _) = proto_levels(
                s,
                &m,
                l,
                Proto {
                    fallback: Fallback::WeightedF4,
                    ..p
                },
            );
            let (swf4, _) = proto_levels(
                s,
                &m,
                l,
                Proto {
                    fallback: Fallback::SpectrumWeighted,
                    ..p
                },
            );
            println!(
                "{}\t{}\t{}\t{}\t{}\t{}\t{}\t{}\t{}",
                stem(f),
                l,
                paper,
                folds(&spec).len(),
                folds(&blend).len(),
                folds(&wf4).len(),
                folds(&swf4).len(),
                lin,
                flags
                    .iter()
                    .map(|(a, b)| format!("{a}/{b}"))
                    .collect::<Vec<_>>()
                    .join(" ")
            );
        }
    }
}

/// A deterministic "random" Möbius map for mesh `m`: an inversion in a sphere centred
/// outside the mesh, then a rotation and a translation.
fn random_mobius(m: &OwnedMesh, seed: u64) -> MobiusMap {
    let mut st = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
    let mut rnd = || {
        st ^= st << 13;
        st ^= st >> 7;
        st ^= st << 17;
        (st >> 11) as f64 / (1u64 << 53) as f64
    };
    let n = m.positions.len() as f64;
    let c = scale(
        m.positions.iter().fold([0.0; 3], |a, p| add(a, *p)),
        1.0 / n,
    );
    let diam = m
        .positions
        .iter()
        .map(|p| norm(sub(*p, c)))
        .fold(0.0, f64::max);
    let dir = {
        let d = [rnd() - 0.5, rnd() - 0.5, rnd() - 0.5];
        scale(d, 1.0 / norm(d))
    };
    let centre = add(c, scale(dir, diam * (1.5 + rnd())));
    let inv = MobiusMap::inversion(centre, diam * (0.5 + rnd()));
    let axis = {
        let d = [rnd() - 0.5, rnd() - 0.5, rnd() - 0.5];
        scale(d, 1.0 / norm(d))
    };
    MobiusMap::rotation(axis, 6.0 * rnd())
        .compose(&MobiusMap::translation([rnd(), rnd(), rnd()]))
        .compose(&inv)
}

fn diameter(m: &OwnedMesh) -> f64 {
    let c = m.positions[0];
    2.0 * m
        .positions
        .iter()
        .map(|p| norm(sub(*p, c)))
        .fold(0.0, f64::max)
}

/// Flags and outputs on Möbius images: the trust of every star on `M(X)` against `X`, and
/// the first level of the paper's rules and of the prototype on `M(X)` against `M` of
/// their output on `X`.
fn cmd_equiv(s: Scheme, files: &[String]) {
    println!("mesh\tseed\tflagged X\tflagged M(X)\tflag status differs\tmax |Δτ|\tpaper max dev/diam\tproto dev/diam (unflagged elements)\tproto dev/diam (flagged elements)\tweighted-F4 dev/diam (all)");
    for f in files {
        let x = load(f);
        let tx = star_trust(s, &x, &PROTO_DEFAULT);
        let px = my_step(s, &x, Some(PROTO_DEFAULT));
        let lx = lib_step(s, &x, true).0;
        for seed in 1..=3u64 {
            let map = random_mobius(&x, seed);
            let y = x.map_positions(|p| map.apply(p).unwrap());
            let ty = star_trust(s, &y, &PROTO_DEFAULT);
            let fx = tx.iter().filter(|t| **t < 1.0).count();
            let fy = ty.iter().filter(|t| **t < 1.0).count();
            let differs = tx
                .iter()
                .zip(&ty)
                .filter(|(a, b)| (**a < 1.0) != (**b < 1.0))
                .count();
            let dt = tx
                .iter()
                .zip(&ty)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            let d = diameter(&y);
            let ly = lib_step(s, &y, true).0;
            let paper_dev = lx
                .positions
                .iter()
                .zip(&ly.positions)
                .map(|(a, b)| norm(sub(map.apply(*a).unwrap(), *b)))
                .fold(0.0, f64::max)
                / d;
            let py = my_step(s, &y, Some(PROTO_DEFAULT));
            let (mut dev_ok, mut dev_fl): (f64, f64) = (0.0, 0.0);
            for (k, (a, b)) in px.out.positions.iter().zip(&py.out.positions).enumerate() {
                let dv = norm(sub(map.apply(*a).unwrap(), *b)) / d;
                if px.elems[k].weight < 1.0 {
                    dev_fl = dev_fl.max(dv);
                } else {
                    dev_ok = dev_ok.max(dv);
                }
            }
            let wp = Proto {
                fallback: Fallback::WeightedF4,
                ..PROTO_DEFAULT
            };
            let (wx, wy) = (my_step(s, &x, Some(wp)).out, my_step(s, &y, Some(wp)).out);
            let dev_w = wx
                .positions
                .iter()
                .zip(&wy.positions)
                .map(|(a, b)| norm(sub(map.apply(*a).unwrap(), *b)) / d)
                .fold(0.0, f64::max);
            println!(
                "{}\t{}\t{}\t{}\t{}\t{:.1e}\t{:.1e}\t{:.1e}\t{:.1e}\t{:.1e}",
                stem(f),
                seed,
                fx,
                fy,
                differs,
                dt,
                paper_dev,
                dev_ok,
                dev_fl,
                dev_w
            );
        }
    }
}

/// Regular grids and their Möbius images: stars flagged, and whether the prototype's output
/// equals the paper's bit for bit (it must, where nothing is flagged).
fn cmd_regular() {
    println!("mesh\tscheme\tflagged\tstars\tprototype == paper (bits)");
    let cases: Vec<(&str, Scheme, OwnedMesh)> = vec![
        ("quad_grid 8x8", Scheme::CatmullClark, quad_grid(8, 8)),
        ("tri_grid 8x8", Scheme::Loop, tri_grid(8, 8)),
        ("tri_grid 8x8", Scheme::ModifiedButterfly, tri_grid(8, 8)),
        (
            "quad_torus 12x8",
            Scheme::CatmullClark,
            quad_torus(12, 8, 2.0, 0.5),
        ),
        ("tri_torus 12x8", Scheme::Loop, tri_torus(12, 8)),
        (
            "tri_torus 12x8",
            Scheme::ModifiedButterfly,
            tri_torus(12, 8),
        ),
        ("icosahedron", Scheme::Loop, load_mesh("icosahedron")),
        ("cube", Scheme::CatmullClark, load_mesh("cube")),
    ];
    for (name, s, m) in cases {
        for (label, mesh) in [
            ("", m.clone()),
            (" (Möbius image)", {
                let map = random_mobius(&m, 7);
                m.map_positions(|p| map.apply(p).unwrap())
            }),
        ] {
            let t = star_trust(s, &mesh, &PROTO_DEFAULT);
            let fl = t.iter().filter(|x| **x < 1.0).count();
            let a = my_step(s, &mesh, Some(PROTO_DEFAULT)).out;
            let b = lib_step(s, &mesh, true).0;
            println!(
                "{name}{label}\t{}\t{fl}\t{}\t{}",
                s.name(),
                t.len(),
                a.positions == b.positions
            );
        }
    }
}

fn load_mesh(name: &str) -> OwnedMesh {
    let p = shared_meshes_dir().join(format!("{name}.off"));
    load(&p.to_string_lossy())
}

fn cmd_gridprobe() {
    let m = tri_grid(8, 8);
    let map = random_mobius(&m, 7);
    let y = m.map_positions(|p| map.apply(p).unwrap());
    let (tx, ty) = (
        star_trust(Scheme::Loop, &m, &PROTO_DEFAULT),
        star_trust(Scheme::Loop, &y, &PROTO_DEFAULT),
    );
    let px = my_step(Scheme::Loop, &m, None);
    for v in 0..tx.len() {
        if tx[v] < 1.0 || ty[v] < 1.0 {
            println!(
                "v {v} τ {} vs {} spread {} valence {} boundary {}",
                tx[v],
                ty[v],
                px.stars[v].spread(),
                px.stars[v].n,
                px.stars[v].boundary
            );
        }
    }
}
