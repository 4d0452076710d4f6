//! Sharp-feature tags of a mesh (creases and corners, OpenSubdiv's conventions: the rules are
//! in [`crate::stencil::crease`]) and how they are validated and carried from level to level.
//!
//! Tags name edges by their two vertices, not by an edge number, so a host need not know the
//! crate's edge numbering. They are data of the input mesh, like its index arrays, and are
//! passed next to it ([`super::plan_tagged`], [`super::subdivide_tagged`]) rather than in
//! [`super::Options`]: the options stay a `Copy` value without a lifetime that a C caller or
//! a `const` can build.
//!
//! Per level the kernel keeps one sharpness value (`f32` bits in a `u32`) per edge and per
//! vertex in the caller's `u32` scratch, two alternating buffers (a step reads its level's
//! values while writing the child level's): the child edges of a tagged edge take the
//! decayed values ([`crease::child_edge_sharpness`]), an old vertex its decremented corner
//! sharpness, every other child edge and vertex is smooth.

use crate::error::{Error, Result, Status};
use crate::mesh::{get, internal, set, Topology, NONE};
use crate::stencil::crease::{self, CreaseMethod};
use crate::MAX_VALENCE;
use arrayvec::ArrayVec;

/// Sharp-feature tags: crease edges given as vertex pairs with their sharpness, corner
/// vertices with theirs, and the crease method. Sharpness follows OpenSubdiv: 0 smooth,
/// positive semi-sharp (the feature fades over about that many levels), ≥ 10 infinitely
/// sharp; it is finite and non-negative, and evaluated in single precision.
///
/// ```
/// use nlsubdiv::scheme::{CreaseMethod, Tags};
/// let creases = [[0, 1], [1, 2]];
/// let sharpness = [10.0, 1.5];
/// let tags = Tags::new().creases(&creases, &sharpness).method(CreaseMethod::Chaikin);
/// assert_eq!(tags.creases.len(), 2);
/// ```
///
/// Errors name a tag by its index in the creases, then the corners: corner `j` is element
/// `creases.len() + j`.
#[non_exhaustive]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Tags<'a> {
    /// Tagged edges, each as its two vertex indices (either order).
    pub creases: &'a [[u32; 2]],
    /// The sharpness of each tagged edge (same length as `creases`).
    pub crease_sharpness: &'a [f64],
    /// Tagged vertices.
    pub corners: &'a [u32],
    /// The sharpness of each tagged vertex (same length as `corners`).
    pub corner_sharpness: &'a [f64],
    /// How semi-sharp edges decay from level to level.
    pub method: CreaseMethod,
}

impl<'a> Tags<'a> {
    /// No tags, uniform method.
    pub const fn new() -> Tags<'a> {
        Tags {
            creases: &[],
            crease_sharpness: &[],
            corners: &[],
            corner_sharpness: &[],
            method: CreaseMethod::Uniform,
        }
    }

    /// Tagged edges and their sharpness.
    #[must_use]
    pub const fn creases(self, pairs: &'a [[u32; 2]], sharpness: &'a [f64]) -> Tags<'a> {
        Tags {
            creases: pairs,
            crease_sharpness: sharpness,
            ..self
        }
    }

    /// Tagged vertices and their sharpness.
    #[must_use]
    pub const fn corners(self, vertices: &'a [u32], sharpness: &'a [f64]) -> Tags<'a> {
        Tags {
            corners: vertices,
            corner_sharpness: sharpness,
            ..self
        }
    }

    /// The crease method.
    #[must_use]
    pub const fn method(self, method: CreaseMethod) -> Tags<'a> {
        Tags { method, ..self }
    }

    /// Whether there is no tag at all (the method alone changes nothing).
    pub const fn is_empty(&self) -> bool {
        self.creases.is_empty() && self.corners.is_empty()
    }
}

/// The sharpness of one tag as stored: rounded to `f32` (OpenSubdiv's precision), values
/// above [`crease::INFINITE`] clamped to it; [`Status::InvalidSharpness`] for NaN, negative
/// or infinite values.
fn stored(s: f64, element: usize) -> Result<f32> {
    if !s.is_finite() || s < 0.0 {
        return Err(Error::at(Status::InvalidSharpness, element as u32));
    }
    let v = s as f32;
    Ok(if v >= crease::INFINITE {
        crease::INFINITE
    } else {
        v
    })
}

/// The edge between `a` and `b`, or `NONE`.
fn edge_between(topo: &Topology<'_, '_>, a: u32, b: u32) -> u32 {
    topo.star(a)
        .find(|s| s.neighbour == b)
        .map_or(NONE, |s| s.edge)
}

/// Checks `tags` against `topo`, then calls `edge(e, s)` for every tagged edge and
/// `vertex(v, s)` for every tagged vertex with its stored value. `marker` holds at least
/// `edges + vertices` entries ([`marker_size`]) and finds repeated tags.
///
/// # Errors
/// [`Status::InvalidArgument`] when a sharpness list differs in length from its tag list;
/// then, tag by tag (creases first): [`Status::IndexOutOfRange`] for a vertex index not below
/// the vertex count, [`Status::InvalidSharpness`], [`Status::TagNotAnEdge`] for a pair that
/// is not an edge of the mesh, [`Status::RepeatedTag`] for an edge or vertex tagged twice;
/// each names the tag (module docs of [`Tags`]).
pub(crate) fn apply(
    tags: &Tags<'_>,
    topo: &Topology<'_, '_>,
    marker: &mut [u32],
    mut edge: impl FnMut(u32, f32) -> Result<()>,
    mut vertex: impl FnMut(u32, f32) -> Result<()>,
) -> Result<()> {
    if tags.creases.len() != tags.crease_sharpness.len()
        || tags.corners.len() != tags.corner_sharpness.len()
    {
        return Err(Error::new(Status::InvalidArgument));
    }
    let (nv, ne) = (topo.num_vertices(), topo.num_edges());
    let marker = marker.get_mut(..ne + nv).ok_or(internal())?;
    marker.fill(0);
    let (em, vm) = marker.split_at_mut_checked(ne).ok_or(internal())?;
    for (i, (&[a, b], &s)) in tags.creases.iter().zip(tags.crease_sharpness).enumerate() {
        let at = |st: Status| Error::at(st, i as u32);
        if a as usize >= nv || b as usize >= nv {
            return Err(at(Status::IndexOutOfRange));
        }
        let s = stored(s, i)?;
        let e = edge_between(topo, a, b);
        if a == b || e == NONE {
            return Err(at(Status::TagNotAnEdge));
        }
        if get(em, e as usize)? != 0 {
            return Err(at(Status::RepeatedTag));
        }
        set(em, e as usize, 1)?;
        edge(e, s)?;
    }
    let base = tags.creases.len();
    for (j, (&v, &s)) in tags.corners.iter().zip(tags.corner_sharpness).enumerate() {
        let at = |st: Status| Error::at(st, (base + j) as u32);
        if v as usize >= nv {
            return Err(at(Status::IndexOutOfRange));
        }
        let s = stored(s, base + j)?;
        if get(vm, v as usize)? != 0 {
            return Err(at(Status::RepeatedTag));
        }
        set(vm, v as usize, 1)?;
        vertex(v, s)?;
    }
    Ok(())
}

/// The `u32` entries [`apply`] needs to find repeated tags: one per edge and per vertex,
/// bounded before the topology is built by one per corner (an edge has at least one) and
/// per vertex.
pub(crate) fn marker_size(vertices: usize, corners: usize) -> Result<usize> {
    crate::mesh::cadd(vertices, corners)
}

/// One level's sharpness values: `f32` bits, `edges` entries first (by edge id), then one
/// per vertex.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Sharpness<'s> {
    pub(crate) edges: &'s [u32],
    pub(crate) vertices: &'s [u32],
    pub(crate) method: CreaseMethod,
    /// Read every value in whole levels, as the Möbius schemes take them: infinitely sharp
    /// while at least ½, else smooth ([`whole_level`]; `mobius/crease.rs`).
    pub(crate) whole: bool,
}

/// A sharpness value as the Möbius schemes act on it in a level (`mobius/crease.rs`, "whole
/// levels"): infinitely sharp while at least ½, else smooth.
pub(crate) fn whole_level(s: f32) -> f32 {
    if s >= 0.5 {
        crease::INFINITE
    } else {
        0.0
    }
}

impl Sharpness<'_> {
    /// The value of edge `e` of `topo` (boundary edges are infinitely sharp).
    pub(crate) fn edge(&self, topo: &Topology<'_, '_>, e: u32) -> Result<f32> {
        if topo.is_boundary_edge(e)? {
            return Ok(crease::INFINITE);
        }
        let s = f32::from_bits(get(self.edges, e as usize)?);
        Ok(if self.whole { whole_level(s) } else { s })
    }

    /// The value of vertex `v`.
    pub(crate) fn vertex(&self, v: u32) -> Result<f32> {
        let s = f32::from_bits(get(self.vertices, v as usize)?);
        Ok(if self.whole { whole_level(s) } else { s })
    }

    /// The same values read in whole levels ([`Sharpness::whole`]).
    pub(crate) fn in_whole_levels(&self) -> Self {
        Self {
            whole: true,
            ..*self
        }
    }

    /// The incident edges' values of `v` (its star's order) into `parent`, their children's
    /// into `child`.
    pub(crate) fn around(
        &self,
        topo: &Topology<'_, '_>,
        v: u32,
        parent: &mut ArrayVec<f32, MAX_VALENCE>,
        child: &mut ArrayVec<f32, MAX_VALENCE>,
    ) -> Result<()> {
        parent.clear();
        child.clear();
        for s in topo.star(v) {
            parent
                .try_push(self.edge(topo, s.edge)?)
                .map_err(|_| Error::at(Status::ValenceTooHigh, v))?;
            child
                .try_push(0.0)
                .map_err(|_| Error::at(Status::ValenceTooHigh, v))?;
        }
        crease::child_edge_sharpness(self.method, parent, child);
        Ok(())
    }
}

/// Level 0's values of `tags` on `topo` into `buf` (`edges + vertices` entries; validated by
/// the plan, so only internal errors remain).
pub(crate) fn initial(tags: &Tags<'_>, topo: &Topology<'_, '_>, buf: &mut [u32]) -> Result<()> {
    let ne = topo.num_edges();
    let nv = topo.num_vertices();
    let buf = buf.get_mut(..ne + nv).ok_or(internal())?;
    buf.fill(0);
    let (eb, vb) = buf.split_at_mut_checked(ne).ok_or(internal())?;
    for (&[a, b], &s) in tags.creases.iter().zip(tags.crease_sharpness) {
        let e = edge_between(topo, a, b);
        set(eb, e as usize, stored(s, 0)?.to_bits())?;
    }
    for (&v, &s) in tags.corners.iter().zip(tags.corner_sharpness) {
        set(vb, v as usize, stored(s, 0)?.to_bits())?;
    }
    Ok(())
}

/// The child level's values from `parent` (on `topo`) into `out` for `child`, the topology
/// the pattern ([`crate::mesh::refine::Pattern::Split1To4`] or
/// [`crate::mesh::refine::Pattern::Quads`]) made from `topo`: old vertices keep their index,
/// the edge point of edge `e` is vertex `V + e`.
pub(crate) fn carry(
    topo: &Topology<'_, '_>,
    parent: &Sharpness<'_>,
    child: &Topology<'_, '_>,
    out: &mut [u32],
) -> Result<()> {
    let (ne, nv) = (child.num_edges(), child.num_vertices());
    let out = out.get_mut(..ne + nv).ok_or(internal())?;
    out.fill(0);
    let (ce, cv) = out.split_at_mut_checked(ne).ok_or(internal())?;
    let pv = topo.num_vertices() as u32;
    let mut pe = ArrayVec::new();
    let mut cs = ArrayVec::new();
    for v in 0..pv {
        set(
            cv,
            v as usize,
            crease::decrement(parent.vertex(v)?).to_bits(),
        )?;
        parent.around(topo, v, &mut pe, &mut cs)?;
        for (s, &c) in topo.star(v).zip(cs.iter()) {
            if c == 0.0 {
                continue;
            }
            let e = edge_between(child, v, pv + s.edge);
            if e == NONE {
                return Err(internal());
            }
            set(ce, e as usize, c.to_bits())?;
        }
    }
    Ok(())
}
