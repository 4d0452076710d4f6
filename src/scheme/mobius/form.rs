//! The canonical form of one vertex star given by its points (seed 000 §4.2, step 1 of §4.1),
//! and the conventions every Möbius rule shares: rules are evaluated in the form's
//! *normalised* frame `x ↦ −r (T − c)⁻¹`, where the centre vertex is the [`ORIGIN`], and a
//! value that cannot be computed is [`MISSING`].
//!
//! Why the normalised frame: it is the same Möbius class as the paper's `c − r²(T − c)⁻¹` (a
//! similarity apart), without the cancellation in that difference when `|c|` is large; every
//! linear stencil is affine, so nothing else changes (docs/DECISIONS.md, "Möbius mesh
//! schemes").

use crate::error::Result;
use crate::mesh::{Spoke, Topology, NONE};
use crate::mobius::{CanonicalForm, StarKind};
use crate::point::{self, Point};
use crate::stencil::centroid_of_sum;

pub(super) use crate::mesh::gather::Ring;

/// The `u32` entries one spoke takes in a [`Spokes`] buffer (neighbour, edge, half-edge,
/// face).
pub(super) const SPOKE_U32S: usize = 4;

/// The spokes of one vertex star, counter-clockwise, in the caller's memory: a chunk's share
/// of the spoke workspace in the step's `u32` scratch (`workspace.rs`), so that nothing
/// sized by the valence cap is on the stack (docs/firmware.md, "Stack").
pub(super) struct Spokes<'w> {
    buf: &'w mut [u32],
    len: usize,
}

/// The spoke stored in `c` ([`SPOKE_U32S`] entries; a shorter slice, which [`Spokes`] never
/// hands out, reads as a spoke of [`NONE`]s).
#[inline(always)]
fn spoke_of(c: &[u32]) -> Spoke {
    let [neighbour, edge, half_edge, face] = <[u32; SPOKE_U32S]>::try_from(c).unwrap_or([NONE; 4]);
    Spoke {
        neighbour,
        edge,
        half_edge,
        face,
    }
}

impl<'w> Spokes<'w> {
    /// No spokes yet, in `buf` (room for `buf.len() / SPOKE_U32S` of them).
    pub(super) fn new(buf: &'w mut [u32]) -> Self {
        Spokes { buf, len: 0 }
    }

    /// Forgets every spoke.
    pub(super) fn clear(&mut self) {
        self.len = 0;
    }

    /// The number of spokes.
    #[inline(always)]
    pub(super) fn len(&self) -> usize {
        self.len
    }

    /// Appends `s`; `Err(())` when the buffer is full.
    #[inline(always)]
    pub(super) fn try_push(&mut self, s: Spoke) -> core::result::Result<(), ()> {
        let i = self.len * SPOKE_U32S;
        match self.buf.get_mut(i..i + SPOKE_U32S) {
            Some([a, b, c, d]) => {
                (*a, *b, *c, *d) = (s.neighbour, s.edge, s.half_edge, s.face);
                self.len += 1;
                Ok(())
            }
            _ => Err(()),
        }
    }

    /// Spoke `j`, if there is one.
    #[inline(always)]
    pub(super) fn get(&self, j: usize) -> Option<Spoke> {
        if j >= self.len {
            return None;
        }
        let i = j * SPOKE_U32S;
        self.buf.get(i..i + SPOKE_U32S).map(spoke_of)
    }

    /// The spokes in order.
    #[inline(always)]
    pub(super) fn iter(&self) -> impl DoubleEndedIterator<Item = Spoke> + ExactSizeIterator + '_ {
        let used = self.buf.get(..self.len * SPOKE_U32S).unwrap_or(&[]);
        used.chunks_exact(SPOKE_U32S).map(spoke_of)
    }
}

/// The image of the centre vertex in the normalised canonical frame.
pub(super) const ORIGIN: Point = [0.0; 3];

/// Marker of a candidate that could not be computed (NaN: never [`present`]).
pub(super) const MISSING: Point = [f64::NAN; 3];

/// The map from a canonical form's normalised frame back to the mesh, `m_{C→B}` (seed 000
/// §4.1 step 3): [`CanonicalForm::from_normalised`] of a form built from points (the tier-1
/// rules) or of a mesh vertex's memoised form (the drivers). A trait rather than a closure so
/// that the rules evaluated in a form always inline it (it runs once per candidate).
pub(super) trait MapBack {
    /// The point of the mesh whose image in the normalised frame is `p`.
    fn back(&self, p: Point) -> Result<Point>;
}

impl MapBack for CanonicalForm {
    #[inline(always)]
    fn back(&self, p: Point) -> Result<Point> {
        self.from_normalised(p)
    }
}

/// A frame the rules of a star are evaluated in: the images of mesh vertices in it, and
/// [`MapBack`] out of it. The memoised canonical form of a mesh vertex (`memo.rs`: the
/// paper's rules) or the fold guard's interpolated form (`spectrum.rs`).
pub(super) trait Frame: MapBack {
    /// Whether this is the star's canonical form (the pass that also measures the star's
    /// trust, `guard.rs`).
    const CANONICAL: bool;

    /// The star's canonical form when this frame is it (the fold guard keeps it for its
    /// output audit, `audit.rs`); `None` for the interpolated form.
    fn canonical(&self) -> Option<&CanonicalForm>;

    /// The image of vertex `u` (the centre goes to [`ORIGIN`]).
    fn image(&mut self, topo: &Topology<'_, '_>, u: u32) -> Result<Point>;

    /// The centroid of face `f`'s corners taken in the frame: their images summed as the
    /// face is walked ([`crate::stencil::centroid`] of the images bit for bit, with no array
    /// of a face's points on the stack); the first failing image's error.
    #[inline(always)]
    fn face_centroid(&mut self, topo: &Topology<'_, '_>, f: u32) -> Result<Point> {
        let corners = topo.face_vertices(f)?;
        let mut s = ORIGIN;
        for &u in corners {
            s = point::add(s, self.image(topo, u)?);
        }
        centroid_of_sum(s, corners.len())
    }
}

/// An identity [`MapBack`]: a rule *in form* run with it leaves its results in the
/// normalised frame, where the fold guard reads them (`trust.rs`) before the drivers map
/// them back with the star's own frame. `back(p)` of the frame afterwards is the same
/// function of the same value as inside the rule, so the bits are those of the rule run with
/// the frame directly.
pub(super) struct Normalised;

impl MapBack for Normalised {
    #[inline(always)]
    fn back(&self, p: Point) -> Result<Point> {
        Ok(p)
    }
}

/// Whether a candidate was computed (finite).
#[inline]
pub(super) fn present(p: &Point) -> bool {
    point::is_finite(p)
}

/// The star kind of a cyclic (`closed`) or open ring.
pub(super) const fn kind_of(closed: bool) -> StarKind {
    if closed {
        StarKind::Interior
    } else {
        StarKind::Boundary
    }
}

/// Whether spoke `j` of a star of `n` spokes is an interior edge: every spoke of a closed
/// star, the spokes `1 ..= n − 2` of an open one (its first and last spokes are boundary
/// edges).
pub(super) const fn interior_spoke(closed: bool, j: usize, n: usize) -> bool {
    closed || (j >= 1 && j + 1 < n)
}

/// The canonical form of the star `v ring…`, with the ring's images in its normalised frame
/// left in `images` ([`MISSING`] for a neighbour the form sends to infinity).
///
/// The images are made in place from the tangent polygon the form was made of (one array of
/// the ring's length, not two): with a form, every `T_i` exists, and
/// [`CanonicalForm::to_normalised`] of `ring[i]` is `normalised_from_tangent(T_i)` bit for
/// bit. The caller owns the array (a `Ring` returned by value would be copied from frame to
/// frame: 3 KiB each time at the default valence cap, `docs/firmware.md`, "Stack").
pub(super) fn star_form(
    v: Point,
    ring: &[Point],
    closed: bool,
    images: &mut Ring,
) -> Result<CanonicalForm> {
    let cf = CanonicalForm::new_with_tangents(v, ring, kind_of(closed), images)?;
    for t in images.iter_mut() {
        *t = cf.normalised_from_tangent(*t).unwrap_or(MISSING);
    }
    Ok(cf)
}
