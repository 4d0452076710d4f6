//! Per-vertex weights of the Möbius–linear spectrum (seed 000 §7.2): the weight `w` of the
//! Möbius result at every input vertex instead of one global [`super::Options::spectrum`],
//! checked, carried to every output vertex of every level like a vertex attribute, and
//! applied per output vertex, `w · (Möbius point) + (1 − w) · (linear point)`.
//!
//! **The carry rule.** An output vertex takes the mean of the weights of the parent elements
//! its pattern makes it from ([`crate::mesh::refine`]): an old vertex (primal patterns, the
//! boundary and isolated vertices the dual patterns keep) its own weight, an edge point the
//! mean of its edge's two end weights, a face point the mean of its face's corners, a corner
//! point of a dual pattern (Doo–Sabin) its parent vertex's weight, a boundary-edge point of
//! the dual pattern the mean of its edge. Why: the weight field is then continuous in the
//! input weights and stays inside their range, it is refined with the mesh (a region of one
//! weight stays that region, its rim blending over about one face per level), and it needs
//! no geometry, so it is the same for the linear and the Möbius rule.
//!
//! **Exact means.** The mean is `lo + (Σ (wᵢ − lo)) / d`, `lo` the smallest of the `d`
//! weights, clamped to the largest: when every weight is the same, each difference is 0 and
//! the mean is that weight exactly (the plain `Σ wᵢ / d` is not: three times 0.1 is
//! 0.30000000000000004, and `0.5 · w` underflows for the smallest subnormals). So equal
//! weights stay equal exactly, level after level, and equal input weights `w` are the global
//! weight `w` bit for bit; regions of weight exactly 0 or 1 stay exactly 0 or 1.
//!
//! **Two conventions.** [`VertexWeights::Mobius`] gives the weight `w` of the Möbius result
//! (as [`super::Options::spectrum`]), [`VertexWeights::Linear`] the weight `u` of the linear
//! result (as the C ABI's `linear_weight`). The values are carried as given and turned into
//! `w = 1 − u` only at each output vertex, as the global weight of the C ABI is: equal `u`
//! everywhere is then the global `u` bit for bit in either API, and `u` of exactly 0 or 1 is
//! `w` of exactly 1 or 0.
//!
//! **Exact ends.** A level whose weights are all 0 is the linear step alone, all 1 the Möbius
//! step alone (as the global weight's ends are). In a mixed level an output vertex of weight
//! exactly 0 takes the linear point and one of weight exactly 1 the Möbius point, bit for
//! bit; the others the blend of the global weight (plain multiplications and an addition, no
//! FMA).

use super::Scheme;
use crate::error::{Error, Result, Status};
use crate::mesh::refine::Pattern;
use crate::mesh::{get, internal, set, Topology, NONE};
use crate::point::{self, Point};

/// Per-vertex weights of the Möbius–linear spectrum, one per input vertex, each in
/// `[0, 1]` ([`subdivide_weighted`](super::subdivide_weighted); the module docs say how they
/// reach every output vertex).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum VertexWeights<'a> {
    /// The weight `w` of the Möbius result at each vertex (the convention of
    /// [`Options::spectrum`](super::Options::spectrum)): 1 Möbius, 0 linear.
    Mobius(&'a [f64]),
    /// The weight `u` of the linear result at each vertex (the convention of the C ABI's
    /// `linear_weight`): 0 Möbius, 1 linear; each output vertex takes `w = 1 − u`.
    Linear(&'a [f64]),
}

impl<'a> VertexWeights<'a> {
    /// The values as given.
    pub const fn values(&self) -> &'a [f64] {
        match *self {
            VertexWeights::Mobius(v) | VertexWeights::Linear(v) => v,
        }
    }

    /// Whether the values are weights of the linear result.
    pub(super) const fn of_linear(&self) -> bool {
        matches!(self, VertexWeights::Linear(_))
    }
}

/// [`Status::InvalidArgument`] unless `weights` holds one weight per input vertex
/// (`vertices`; no element), each in `[0, 1]` (NaN or outside names the first such vertex).
pub(super) fn check(weights: Option<VertexWeights<'_>>, vertices: usize) -> Result<()> {
    let Some(w) = weights else {
        return Ok(());
    };
    let w = w.values();
    if w.len() != vertices {
        return Err(Error::new(Status::InvalidArgument));
    }
    // `!(0 ≤ x ≤ 1)` is true for NaN too.
    match w.iter().position(|x| !(*x >= 0.0 && *x <= 1.0)) {
        Some(v) => Err(Error::at(Status::InvalidArgument, v as u32)),
        None => Ok(()),
    }
}

/// The `f64` slots of the point scratch that hold one level's weights: `vertices` weights,
/// three to a point.
pub(super) fn points_for(vertices: usize) -> usize {
    vertices.div_ceil(3)
}

/// What a level's weights ask of its step.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Uniform {
    /// Every weight is 0: the linear step.
    Zero,
    /// Every weight is 1: the Möbius step.
    One,
    /// Anything else: both, blended per vertex.
    Mixed,
}

/// Whether the weights `w` (of the linear result with `of_linear`) ask for the linear step,
/// the Möbius step or both (an empty level: the Möbius step, which writes nothing).
pub(super) fn uniform(w: &[f64], of_linear: bool) -> Uniform {
    let (mobius, linear) = if of_linear { (0.0, 1.0) } else { (1.0, 0.0) };
    if w.iter().all(|x| *x == mobius) {
        Uniform::One
    } else if w.iter().all(|x| *x == linear) {
        Uniform::Zero
    } else {
        Uniform::Mixed
    }
}

/// How a step blends its Möbius positions with its linear ones.
#[derive(Clone, Copy, Debug)]
pub(super) enum Blend<'a> {
    /// One weight for every output vertex ([`super::Options::spectrum`]).
    Global(f64),
    /// One weight per output vertex of the step (the carried weights; of the linear result
    /// with `true`).
    PerVertex(&'a [f64], bool),
}

impl Blend<'_> {
    /// `pos[i] ← w · pos[i] + (1 − w) · lin[i]` (module docs: exact at 0 and 1 per vertex).
    pub(super) fn apply(&self, pos: &mut [Point], lin: &[Point]) -> Result<()> {
        match *self {
            Blend::Global(w) => {
                for (p, l) in pos.iter_mut().zip(lin.iter()) {
                    *p = mix(*p, *l, w);
                }
            }
            Blend::PerVertex(ws, of_linear) => {
                if ws.len() < pos.len() || lin.len() < pos.len() {
                    return Err(internal());
                }
                for ((p, l), x) in pos.iter_mut().zip(lin.iter()).zip(ws.iter()) {
                    // `1 − u` as the C ABI's global weight is turned into `w`.
                    let w = &if of_linear { 1.0 - *x } else { *x };
                    if *w == 0.0 {
                        *p = *l;
                    } else if *w != 1.0 {
                        *p = mix(*p, *l, *w);
                    }
                }
            }
        }
        Ok(())
    }
}

/// `w · m + (1 − w) · l`, the formula of the global weight.
fn mix(m: Point, l: Point, w: f64) -> Point {
    point::add(point::scale(m, w), point::scale(l, 1.0 - w))
}

/// The exact mean of the weights `ws` (module docs), 0 for none.
fn mean(ws: impl Iterator<Item = f64> + Clone) -> f64 {
    let (mut lo, mut hi, mut d) = (f64::INFINITY, f64::NEG_INFINITY, 0u32);
    for w in ws.clone() {
        lo = lo.min(w);
        hi = hi.max(w);
        d += 1;
    }
    if d == 0 {
        return 0.0;
    }
    let sum = ws.fold(0.0, |s, w| s + (w - lo));
    (lo + sum / f64::from(d)).min(hi)
}

/// The weights of the output vertices of one step of `scheme` on `topo` (`child`, in the
/// pattern's output order) from those of its vertices (`parent`), by the carry rule (module
/// docs).
pub(super) fn carry(
    scheme: Scheme,
    topo: &Topology<'_, '_>,
    parent: &[f64],
    child: &mut [f64],
) -> Result<()> {
    let nv = topo.num_vertices();
    let ne = topo.num_edges();
    let at = |v: u32| get(parent, v as usize);
    let edge = |e: u32| -> Result<f64> {
        let (a, b) = topo.edge_vertices(e)?;
        Ok(mean([at(a)?, at(b)?].into_iter()))
    };
    let face = |f: u32| -> Result<f64> {
        let vs = topo.face_vertices(f)?;
        for &v in vs {
            at(v)?;
        }
        // Every corner was read above: the fallback value never occurs.
        Ok(mean(vs.iter().map(|&v| {
            parent.get(v as usize).copied().unwrap_or(f64::NAN)
        })))
    };
    let old = |child: &mut [f64]| -> Result<()> {
        for v in 0..nv {
            set(child, v, get(parent, v)?)?;
        }
        Ok(())
    };
    let faces_from = |child: &mut [f64], start: usize| -> Result<()> {
        for f in 0..topo.num_faces() as u32 {
            set(child, start + f as usize, face(f)?)?;
        }
        Ok(())
    };
    let edges_from = |child: &mut [f64], start: usize| -> Result<()> {
        for e in 0..ne as u32 {
            set(child, start + e as usize, edge(e)?)?;
        }
        Ok(())
    };
    // The kept boundary vertices at `start + rank`, the isolated ones after them.
    let kept = |child: &mut [f64], start: usize| -> Result<()> {
        let mut k = start + topo.num_boundary_vertices();
        for v in 0..nv as u32 {
            let r = topo.boundary_vertex_rank(v)?;
            if r != NONE {
                set(child, start + r as usize, at(v)?)?;
            }
        }
        for v in 0..nv as u32 {
            if topo.is_isolated(v)? {
                set(child, k, at(v)?)?;
                k += 1;
            }
        }
        Ok(())
    };
    match scheme.pattern() {
        Pattern::Split1To4 => {
            old(child)?;
            edges_from(child, nv)?;
        }
        Pattern::Quads => {
            old(child)?;
            edges_from(child, nv)?;
            faces_from(child, nv + ne)?;
        }
        Pattern::VertexInsertion | Pattern::DualTruncation => {
            old(child)?;
            faces_from(child, nv)?;
        }
        Pattern::CornerCut => {
            let nh = topo.num_half_edges();
            for h in 0..nh as u32 {
                set(child, h as usize, at(topo.origin(h)?)?)?;
            }
            let mut k = nh;
            for v in 0..nv as u32 {
                if topo.is_isolated(v)? {
                    set(child, k, at(v)?)?;
                    k += 1;
                }
            }
        }
        Pattern::MidEdge => {
            edges_from(child, 0)?;
            kept(child, ne)?;
        }
        Pattern::Dual => {
            let nf = topo.num_faces();
            faces_from(child, 0)?;
            for v in 0..nv as u32 {
                let r = topo.boundary_vertex_rank(v)?;
                if r != NONE {
                    let (b0, _) = topo.boundary_neighbours(v)?;
                    set(child, nf + r as usize, mean([at(v)?, at(b0)?].into_iter()))?;
                }
            }
            kept(child, nf + topo.num_boundary_vertices())?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Equal weights have exactly that mean, also where a plain sum divided would not.
    #[test]
    fn mean_of_equal_weights_is_exact() {
        for w in [0.1, 0.7, 1.0 / 3.0, 5e-324, 0.0, 1.0] {
            for d in 1..=9 {
                assert_eq!(mean(core::iter::repeat_n(w, d)), w, "{w} × {d}");
            }
        }
        // The plain form is not exact (the reason for this one).
        assert_ne!((0.1 + 0.1 + 0.1) / 3.0, 0.1);
    }

    /// The mean stays within the weights' range and is the mean.
    #[test]
    fn mean_in_range() {
        let ws = [0.0, 1.0, 0.25, 0.75];
        assert_eq!(mean(ws.into_iter()), 0.5);
        let ws = [0.9999999999999999, 1.0, 1.0];
        let m = mean(ws.into_iter());
        assert!((0.9999999999999999..=1.0).contains(&m));
    }

    #[test]
    fn check_names_the_vertex() {
        use VertexWeights::{Linear, Mobius};
        assert!(check(None, 3).is_ok());
        assert!(check(Some(Mobius(&[0.0, 0.5, 1.0])), 3).is_ok());
        assert_eq!(
            check(Some(Linear(&[0.0, 0.5])), 3).unwrap_err(),
            Error::new(Status::InvalidArgument)
        );
        for bad in [f64::NAN, -0.1, 1.5, f64::INFINITY] {
            for w in [Mobius(&[0.0, bad, 1.0]), Linear(&[0.0, bad, 1.0])] {
                assert_eq!(
                    check(Some(w), 3).unwrap_err(),
                    Error::at(Status::InvalidArgument, 1)
                );
            }
        }
    }

    #[test]
    fn uniform_levels() {
        assert_eq!(uniform(&[0.0, 0.0], false), Uniform::Zero);
        assert_eq!(uniform(&[1.0, 1.0], false), Uniform::One);
        assert_eq!(uniform(&[0.0, 0.0], true), Uniform::One);
        assert_eq!(uniform(&[1.0, 1.0], true), Uniform::Zero);
        assert_eq!(uniform(&[], false), Uniform::One);
        assert_eq!(uniform(&[1.0, 0.0], true), Uniform::Mixed);
        assert_eq!(uniform(&[0.5, 0.5], false), Uniform::Mixed);
    }
}
