//! Canonical Möbius subdivision (seed 000 §4): the Möbius version of every linear scheme.
//!
//! Per vertex `v` (§4.1, Fig. 6):
//! 1. the canonical form `C_v` of its star ([`CanonicalForm`], §4.2; interior stars use the
//!    barycentre of the tangent polygon, boundary stars the mean of the two boundary
//!    neighbours' images);
//! 2. the linear stencils of [`crate::stencil`] evaluated on the 1-ring mapped into `C_v`;
//! 3. the candidate points mapped back with `m_{C→B}`;
//! 4. blends across stars: an edge point is `F4(v_j, e_j, e_k, v_k)` (§4.4.3), a face point the
//!    sorted F4/F6 chain of [`blend::face_point`]; vertex points come from the vertex's own form.
//!
//! Boundary loops are curves and use the Möbius curve rules (§4.3 "Boundary curves", §4.4.1,
//! DESIGN.md "Mesh boundaries"): the approximating rule for approximating schemes (odd
//! `E_{i+½} = F4(P_{i−1}, P_i, P_{i+1}, P_{i+2})`, even
//! `P'_i = F4(P_{i−1}, E_{i−½}, E_{i+½}, P_{i+1})`), the interpolating rule (odd points only)
//! for the others.
//!
//! **Ear vertices** (boundary vertices with one face) have no usable form for a quad: their
//! canonical form sends the opposite corner to infinity (DESIGN.md). Anything an ear would
//! contribute to its face (a face candidate, a Doo–Sabin corner point) is evaluated in the
//! canonical form of the first non-ear vertex of the face at offset `h, h+1, h−1, h+2, …`
//! (`h = ⌊d/2⌋`), which keeps the rule Möbius-invariant and exact on Möbius images of regular
//! grids. A face of ears only takes its linear centroid, counted as a fallback.
//!
//! **Degenerate neighbourhoods** (coincident points, a star whose canonical form does not
//! exist, a blend at infinity): the element takes its linear rule, evaluated on the original
//! positions; it is counted in the [`MobiusReport`] (count and first output vertex), and with
//! [`MobiusOptions::strict`] it is an error instead ([`Status::FallbackInStrictMode`]). No
//! non-finite value reaches the output.

use arrayvec::ArrayVec;

use super::linear::{face_points, face_points_into, ring_points};
use super::Scheme;
use crate::blend::{self, f4, f4_hinted};
use crate::error::{Error, Result, Status, NO_ELEMENT};
use crate::mesh::refine::write_pattern;
use crate::mesh::{get, internal, set, MeshOut, MeshSizes, Spoke, Topology, NONE};
use crate::mobius::{CanonicalForm, StarKind};
use crate::point::{self, midpoint, Point};
use crate::stencil::{
    akleman, butterfly, catmull_clark, centroid, doo_sabin, kobbelt, loop_scheme, simplest,
};
use crate::{MAX_FACE_SIZE, MAX_VALENCE};

/// Options of the Möbius schemes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct MobiusOptions {
    /// Turn every linear fallback into [`Status::FallbackInStrictMode`] naming the output
    /// vertex.
    pub strict: bool,
}

/// What a Möbius subdivision step had to do besides the paper's rules.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MobiusReport {
    /// Output vertices that took their linear rule (degenerate neighbourhood).
    pub fallbacks: u32,
    /// The first such output vertex, or [`NO_ELEMENT`].
    pub first_fallback: u32,
}

impl Default for MobiusReport {
    fn default() -> Self {
        MobiusReport {
            fallbacks: 0,
            first_fallback: NO_ELEMENT,
        }
    }
}

/// The image of the centre vertex in the normalised canonical frame.
const ORIGIN: Point = [0.0; 3];

/// Marker of a candidate that could not be computed.
const MISSING: Point = [f64::NAN; 3];

fn present(p: &Point) -> bool {
    point::is_finite(p)
}

/// Scratch points [`subdivide`] needs: an edge candidate and a face candidate per half-edge.
///
/// # Errors
/// [`Status::SizeOverflow`].
pub fn scratch_len(topo: &Topology<'_, '_>) -> Result<usize> {
    scratch_len_for(topo.num_half_edges())
}

/// [`scratch_len`] from the number of corners (= half-edges) alone, for callers that size
/// buffers before the mesh is validated (the C ABI): two points per corner.
///
/// # Errors
/// [`Status::SizeOverflow`].
pub fn scratch_len_for(num_corners: usize) -> Result<usize> {
    num_corners
        .checked_mul(2)
        .ok_or(Error::new(Status::SizeOverflow))
}

// ---- rules at one vertex star (tier 1: for hosts that own the connectivity) ----

/// The star kind of a cyclic (`closed`) or open ring.
const fn kind_of(closed: bool) -> StarKind {
    if closed {
        StarKind::Interior
    } else {
        StarKind::Boundary
    }
}

/// Whether spoke `j` of a star of `n` spokes is an interior edge: every spoke of a closed
/// star, the spokes `1 ..= n − 2` of an open one (its first and last spokes are boundary
/// edges).
const fn interior_spoke(closed: bool, j: usize, n: usize) -> bool {
    closed || (j >= 1 && j + 1 < n)
}

/// The canonical form of the star `v ring…` and the ring's images in its normalised frame
/// ([`MISSING`] for a neighbour the form sends to infinity).
fn star_form(
    v: Point,
    ring: &[Point],
    closed: bool,
) -> Result<(CanonicalForm, ArrayVec<Point, MAX_VALENCE>)> {
    let cf = CanonicalForm::new(v, ring, kind_of(closed))?;
    let mut images = ArrayVec::new();
    for u in ring {
        images
            .try_push(cf.to_normalised(*u).unwrap_or(MISSING))
            .map_err(|_| Error::new(Status::ValenceTooHigh))?;
    }
    Ok((cf, images))
}

/// The Loop rules in a star's canonical form (normalised frame, centre at the origin):
/// the vertex point of a closed star, and the edge candidate of every interior spoke `j`,
/// `edge_interior(0, r_j, r_{j+1}, r_{j−1})` (the two apexes of a triangle fan are the ring
/// neighbours of the spoke), each mapped back with `back`. `ring` holds the images of the
/// neighbours; a rule whose value cannot be mapped back leaves its slot [`MISSING`]
/// (`None` for the vertex point). The driver and [`loop_star`] both evaluate the star here.
fn loop_star_in_form(
    ring: &[Point],
    closed: bool,
    back: impl Fn(Point) -> Result<Point>,
    edge_candidates: &mut [Point],
) -> Result<Option<Point>> {
    let n = ring.len();
    let vertex = if closed {
        loop_scheme::vertex_interior(ORIGIN, ring)
            .and_then(&back)
            .ok()
    } else {
        None
    };
    for j in 0..n {
        let c = if interior_spoke(closed, j, n) {
            let b = get(ring, j)?;
            let c = get(ring, (j + 1) % n)?;
            let d = get(ring, (j + n - 1) % n)?;
            back(loop_scheme::edge_interior(ORIGIN, b, c, d)).unwrap_or(MISSING)
        } else {
            MISSING
        };
        set(edge_candidates, j, c)?;
    }
    Ok(vertex)
}

/// The canonical Möbius Loop rules at one vertex star (seed 000 §4.1 steps 1–3), exactly as
/// [`subdivide`] evaluates them for [`Scheme::Loop`]: the canonical form of `v ring…`
/// (`closed`: a cyclic ring of an interior vertex; otherwise the ring runs from one boundary
/// neighbour to the other, counter-clockwise), Loop's stencils on the mapped 1-ring, the
/// results mapped back.
///
/// Returns the vertex point of an interior vertex (`None` for a boundary vertex, whose
/// vertex point is the boundary curve rule, or when it cannot be mapped back), and writes
/// `edge_candidates[j]`, the candidate of the edge to `ring[j]`, for every interior spoke; the
/// other slots (boundary spokes, candidates at infinity) are NaN. An edge point is then
/// `F4(a, e_a, e_b, b)` of the candidates of both end points ([`blend::f4_hinted`], hint the
/// apex of the triangle on the left of `a → b`), the single candidate when only one exists,
/// or the linear rule when none does.
///
/// Bit-identical to the driver when `ring` starts at the same spoke (the driver's star
/// starts at the vertex's lowest-numbered outgoing half-edge, see
/// [`crate::mesh::Topology::star`]); another rotation changes the last bits only.
///
/// # Errors
/// [`Status::BufferTooSmall`] when `edge_candidates` is shorter than `ring`; the errors of
/// [`CanonicalForm::new`] (the star has no canonical form: the driver takes the linear rule
/// for everything this star would give); [`Status::DegenerateGeometry`] naming the ring
/// index of a neighbour the form sends to infinity.
pub fn loop_star(
    v: Point,
    ring: &[Point],
    closed: bool,
    edge_candidates: &mut [Point],
) -> Result<Option<Point>> {
    if edge_candidates.len() < ring.len() {
        return Err(Error::too_small(ring.len()));
    }
    let (cf, images) = star_form(v, ring, closed)?;
    if let Some(i) = images.iter().position(|p| !present(p)) {
        // The driver takes no candidate from a star with a neighbour at infinity.
        return Err(Error::at(Status::DegenerateGeometry, i as u32));
    }
    loop_star_in_form(&images, closed, |p| cf.from_normalised(p), edge_candidates)
}

/// The Catmull–Clark rules in a star's canonical form: `ring` and `faces` hold the images of
/// the neighbours and the canonical centroids of the faces after each spoke ([`MISSING`] when
/// not available). Writes the edge candidate `edge_interior(0, r_j, f_{j−1}, f_j)` of every
/// interior spoke and returns the vertex point of a closed star, all mapped back with `back`.
fn catmull_clark_star_in_form(
    ring: &[Point],
    faces: &[Point],
    closed: bool,
    back: impl Fn(Point) -> Result<Point>,
    edge_candidates: &mut [Point],
) -> Result<Option<Point>> {
    let n = ring.len();
    for j in 0..n {
        let mut c = MISSING;
        if interior_spoke(closed, j, n) {
            let b = get(ring, j)?;
            let f0 = get(faces, (j + n - 1) % n)?;
            let f1 = get(faces, j)?;
            if present(&b) && present(&f0) && present(&f1) {
                c = back(catmull_clark::edge_interior(ORIGIN, b, f0, f1)).unwrap_or(MISSING);
            }
        }
        set(edge_candidates, j, c)?;
    }
    let all = |s: &[Point]| s.iter().take(n).all(present);
    if closed && all(ring) && all(faces) {
        let faces = faces.get(..n).ok_or(internal())?;
        Ok(catmull_clark::vertex_interior(ORIGIN, ring, faces)
            .and_then(&back)
            .ok())
    } else {
        Ok(None)
    }
}

/// The canonical Möbius Catmull–Clark rules at one vertex star, exactly as [`subdivide`]
/// evaluates them for [`Scheme::CatmullClark`]. `ring` as for [`loop_star`]; face `j`
/// (`face_corners[face_offsets[j]..face_offsets[j + 1]]`) is the face between spoke `j` and
/// spoke `j + 1` counter-clockwise, given by the positions of all its corners in face order
/// (`v` included, anywhere in the cycle): `ring.len()` faces for a closed star, one fewer for
/// an open one.
///
/// Returns the vertex point of an interior vertex (`None` as for [`loop_star`]); writes the
/// edge candidate of every interior spoke to `edge_candidates[j]` and the face candidate (the
/// face's centroid taken in this star's form) to `face_candidates[j]`; NaN where there is
/// none. Face points are then [`blend::face_point`] of a face's corners and the candidates of
/// its corners' stars; edge points as for [`loop_star`] (hint: the corner after `b` in the
/// face on the left of `a → b`).
///
/// Bit-identical to the driver when `ring` starts at the driver's first spoke and each face
/// lists its corners from the face's first corner in the mesh.
///
/// # Errors
/// [`Status::BufferTooSmall`] for short candidate buffers; [`Status::InvalidArgument`] when
/// the number of faces does not fit the ring; [`Status::BadOffsets`], [`Status::FaceTooSmall`],
/// [`Status::ValenceTooHigh`] (more than [`MAX_FACE_SIZE`] corners) naming the face; the
/// errors of [`CanonicalForm::new`]; [`Status::NonFiniteInput`] and
/// [`Status::InvalidArgument`] (a face that does not contain `v`) naming the face. Unlike
/// [`loop_star`], a neighbour sent to infinity only removes the rules that use it, as in the
/// driver.
pub fn catmull_clark_star(
    v: Point,
    ring: &[Point],
    closed: bool,
    face_offsets: &[u32],
    face_corners: &[Point],
    edge_candidates: &mut [Point],
    face_candidates: &mut [Point],
) -> Result<Option<Point>> {
    let n = ring.len();
    let nf = if closed { n } else { n.saturating_sub(1) };
    if face_offsets.len() != nf + 1 {
        return Err(Error::new(Status::InvalidArgument));
    }
    if edge_candidates.len() < n {
        return Err(Error::too_small(n));
    }
    if face_candidates.len() < nf {
        return Err(Error::too_small(nf));
    }
    let first = face_offsets.first().copied();
    let last = face_offsets.last().map(|&o| o as usize);
    if first != Some(0) || last != Some(face_corners.len()) {
        return Err(Error::at(Status::BadOffsets, 0));
    }
    // The face lists, checked before any computation.
    let face = |j: usize| -> Result<&[Point]> {
        let bad = |s: Status| Error::at(s, j as u32);
        let a = *face_offsets.get(j).ok_or(internal())? as usize;
        let b = *face_offsets.get(j + 1).ok_or(internal())? as usize;
        let corners = face_corners.get(a..b).ok_or(bad(Status::BadOffsets))?;
        if corners.len() < 3 {
            return Err(bad(Status::FaceTooSmall));
        }
        if corners.len() > MAX_FACE_SIZE {
            return Err(bad(Status::ValenceTooHigh));
        }
        Ok(corners)
    };
    for j in 0..nf {
        face(j)?;
    }
    let (cf, images) = star_form(v, ring, closed)?;
    for j in 0..nf {
        let corners = face(j)?;
        if !corners.iter().all(point::is_finite) {
            return Err(Error::at(Status::NonFiniteInput, j as u32));
        }
        if !corners.contains(&v) {
            return Err(Error::at(Status::InvalidArgument, j as u32));
        }
    }
    let mut centroids: ArrayVec<Point, MAX_VALENCE> = ArrayVec::new();
    for j in 0..n {
        let c = if j < nf {
            let mut pts: ArrayVec<Point, MAX_FACE_SIZE> = ArrayVec::new();
            let mut ok = true;
            for p in face(j)? {
                match cf.to_normalised(*p) {
                    Ok(q) => pts.try_push(q).map_err(|_| internal())?,
                    Err(_) => ok = false,
                }
            }
            if ok {
                centroid(&pts)?
            } else {
                MISSING
            }
        } else {
            MISSING
        };
        centroids.try_push(c).map_err(|_| internal())?;
        if j < nf {
            let back = if present(&c) {
                cf.from_normalised(c).unwrap_or(MISSING)
            } else {
                MISSING
            };
            set(face_candidates, j, back)?;
        }
    }
    catmull_clark_star_in_form(
        &images,
        &centroids,
        closed,
        |p| cf.from_normalised(p),
        edge_candidates,
    )
}

/// Writes one step of the Möbius version of `scheme` on `topo` into `out`, with `scratch`
/// of at least [`scratch_len`] points. The connectivity and the output vertex order are those
/// of the linear scheme ([`super::linear::subdivide`]).
///
/// # Errors
/// Those of [`super::linear::subdivide_size`]; [`Status::BufferTooSmall`] for `out` or
/// `scratch`; [`Status::FallbackInStrictMode`] (element = output vertex) with
/// [`MobiusOptions::strict`]; [`Status::NumericalFailure`] naming an output vertex that is
/// not finite.
pub fn subdivide(
    scheme: Scheme,
    topo: &Topology<'_, '_>,
    out: &mut MeshOut<'_>,
    scratch: &mut [Point],
    opts: MobiusOptions,
) -> Result<(MeshSizes, MobiusReport)> {
    if !scheme.has_mobius_form() {
        // Refused before anything is written (seed 003's spherelike rule has no Möbius form).
        return Err(Error::new(Status::InvalidArgument));
    }
    let sizes = super::linear::subdivide_size(scheme, topo)?;
    out.check(&sizes)?;
    let need = scratch_len(topo)?;
    if scratch.len() < need {
        return Err(Error::too_small(need));
    }
    write_pattern(scheme.pattern(), topo, out.offsets, out.indices)?;
    let pos = out.positions.get_mut(..sizes.vertices).ok_or(internal())?;
    let nh = topo.num_half_edges();
    let (edge_c, rest) = scratch.split_at_mut(nh);
    let face_c = rest.get_mut(..nh).ok_or(internal())?;
    let mut d = Driver {
        topo,
        pos,
        edge_c,
        face_c,
        report: MobiusReport::default(),
        strict: opts.strict,
    };
    d.run(scheme)?;
    for (i, p) in d.pos.iter().enumerate() {
        if !point::is_finite(p) {
            return Err(Error::at(Status::NumericalFailure, i as u32));
        }
    }
    Ok((sizes, d.report))
}

/// A vertex's canonical form with a small cache of mapped points of its neighbourhood.
///
/// About 10 KB (the memo and the tangent polygon): each driver loop keeps one and re-targets
/// it per vertex with [`Driver::local_into`] instead of returning a fresh one, which moved it
/// several times per vertex (memcpy was half of Möbius Catmull–Clark's instructions).
struct Local {
    v: u32,
    cf: CanonicalForm,
    /// Direct-mapped memo of [`Local::canon`]: vertex `u` lives in slot [`memo_slot`]`(u)`,
    /// valid while its stamp is `stamp` (re-targeting bumps the stamp instead of clearing the
    /// slots). A collision only overwrites: the evicted image is recomputed bit for bit.
    memo: [(u32, u32, Point); MEMO_SLOTS],
    stamp: u32,
    /// The tangent polygon of the form (`(u_i − v)⁻¹` over the star's neighbours), from
    /// which the ring's images are put in the memo when the form is made.
    tangents: Ring,
}

/// Slots of [`Local::memo`]: at least twice the vertices a driver maps in one star (the 1-ring
/// and the faces' other corners; Butterfly's wings) for the usual valences.
const MEMO_SLOTS: usize = 256;

/// The memo slot of vertex `u`: Fibonacci hashing, whose top bits spread the nearby ids of
/// one star over the table.
#[inline]
fn memo_slot(u: u32) -> usize {
    (u.wrapping_mul(0x9E37_79B9) >> 24) as usize
}

/// [`Topology::spokes_into`] spoke for spoke, walked on the topology's arrays: one
/// `next_prev_face` per spoke (arithmetic on all-triangle and all-quad meshes, every level of
/// Loop, Butterfly, Catmull–Clark and Doo–Sabin after the first) instead of the star
/// iterator's face lookups. `v` is not isolated. The same errors: [`Status::ValenceTooHigh`]
/// naming `v`, an internal error for arrays that disagree with the valence.
fn star_into(topo: &Topology<'_, '_>, v: u32, out: &mut Spokes) -> Result<()> {
    let r = topo.raw();
    out.clear();
    let n = get(r.valence, v as usize)? as usize;
    let mut cur = get(r.vert_he, v as usize)?;
    for _ in 0..n {
        if cur == NONE {
            // Only for arrays that disagree (the walk stops at a boundary below).
            return Err(internal());
        }
        let (next, prev, f) = r.next_prev_face(cur)?;
        out.try_push(Spoke {
            neighbour: get(r.indices, next as usize)?,
            edge: get(r.edge_of, cur as usize)?,
            half_edge: cur,
            face: f,
        })
        .map_err(|_| Error::at(Status::ValenceTooHigh, v))?;
        let tw = get(r.twin, prev as usize)?;
        if tw == NONE {
            // Closing spoke of a boundary star: the incoming boundary half-edge `prev`.
            if out.len() < n {
                out.try_push(Spoke {
                    neighbour: get(r.indices, prev as usize)?,
                    edge: get(r.edge_of, prev as usize)?,
                    half_edge: NONE,
                    face: NONE,
                })
                .map_err(|_| Error::at(Status::ValenceTooHigh, v))?;
            }
            break;
        }
        cur = tw;
    }
    if out.len() != n {
        return Err(internal());
    }
    Ok(())
}

type Ring = ArrayVec<Point, MAX_VALENCE>;
type FacePts = ArrayVec<Point, MAX_FACE_SIZE>;
type Spokes = ArrayVec<Spoke, MAX_VALENCE>;

impl Local {
    /// A memo holding no form yet (`v = NONE`).
    fn blank() -> Local {
        Local {
            v: NONE,
            cf: CanonicalForm {
                v: ORIGIN,
                c: ORIGIN,
                r: 0.0,
                kind: StarKind::Interior,
            },
            memo: [(NONE, 0, ORIGIN); MEMO_SLOTS],
            stamp: 0,
            tangents: ArrayVec::new(),
        }
    }

    /// Forgets the form and every memo entry (`v = NONE`).
    fn clear(&mut self) {
        self.v = NONE;
        self.stamp = self.stamp.wrapping_add(1);
        if self.stamp == 0 {
            // Stamps wrapped: entries of 2³² re-targets ago would look valid again.
            for e in self.memo.iter_mut() {
                e.1 = 0;
            }
            self.stamp = 1;
        }
    }

    /// Re-targets the memo to the canonical form of `v`'s star: [`StarKind::Interior`] for
    /// a closed star, [`StarKind::Boundary`] for an open one (`boundary`; ring from one
    /// boundary neighbour to the other). `Ok(false)` when the form does not exist (a
    /// degenerate star: the caller's fallback); the memo then holds no form (`v = NONE`).
    /// `Err` only for a failure of the topology queries, which is an error, never a fallback.
    /// `spokes` receives the star of `v` (as [`Topology::spokes_into`]), which the drivers
    /// then walk instead of walking the star again.
    ///
    /// The images of the ring neighbours are cached at once, from the tangent polygon the
    /// form was made of: [`CanonicalForm::to_normalised`] would compute the same `T_i` again
    /// (bit for bit the same images; a neighbour whose image fails is left to `canon`, which
    /// fails the same way).
    fn reset(
        &mut self,
        topo: &Topology<'_, '_>,
        v: u32,
        boundary: bool,
        spokes: &mut Spokes,
    ) -> Result<bool> {
        self.clear();
        star_into(topo, v, spokes)?;
        let kind = if boundary {
            StarKind::Boundary
        } else {
            StarKind::Interior
        };
        let centre = topo.position(v)?;
        // The tangent polygon straight from the mesh: `CanonicalForm::new` of the ring's
        // positions bit for bit (same checks: a finite centre, every `T_i` defined).
        let mut ok = point::is_finite(&centre);
        self.tangents.clear();
        for s in spokes.iter() {
            match CanonicalForm::tangent(centre, topo.position(s.neighbour)?) {
                Some(t) => self.tangents.try_push(t).map_err(|_| internal())?,
                None => ok = false,
            }
        }
        if !ok {
            return Ok(false);
        }
        self.cf = match CanonicalForm::from_tangents(centre, &self.tangents, kind) {
            Ok(cf) => cf,
            Err(_) => return Ok(false),
        };
        self.v = v;
        let stamp = self.stamp;
        for (s, t) in spokes.iter().zip(self.tangents.iter()) {
            if let Ok(p) = self.cf.normalised_from_tangent(*t) {
                if let Some(e) = self.memo.get_mut(memo_slot(s.neighbour)) {
                    *e = (s.neighbour, stamp, p);
                }
            }
        }
        Ok(true)
    }

    /// The image of vertex `u` in the canonical form, in its normalised frame
    /// ([`CanonicalForm::to_normalised`]: `v` itself goes to the origin).
    #[inline(always)]
    fn canon(&mut self, topo: &Topology<'_, '_>, u: u32) -> Result<Point> {
        if u == self.v {
            return Ok(ORIGIN);
        }
        let slot = memo_slot(u);
        if let Some(&(k, st, p)) = self.memo.get(slot) {
            if k == u && st == self.stamp {
                return Ok(p);
            }
        }
        let p = self.cf.to_normalised(topo.position(u)?)?;
        if let Some(e) = self.memo.get_mut(slot) {
            *e = (u, self.stamp, p);
        }
        Ok(p)
    }

    /// The canonical images of the corners of face `f`, in face order, into `pts`.
    #[inline(always)]
    fn face(&mut self, topo: &Topology<'_, '_>, f: u32, pts: &mut FacePts) -> Result<()> {
        pts.clear();
        for &u in topo.face_vertices(f)? {
            pts.try_push(self.canon(topo, u)?)
                .map_err(|_| Error::at(Status::ValenceTooHigh, f))?;
        }
        Ok(())
    }

    /// The centroid of face `f` taken in the canonical form (normalised frame); `pts` is
    /// scratch.
    fn face_centroid(
        &mut self,
        topo: &Topology<'_, '_>,
        f: u32,
        pts: &mut FacePts,
    ) -> Result<Point> {
        self.face(topo, f, pts)?;
        centroid(pts)
    }

    #[inline]
    fn back(&self, p: Point) -> Result<Point> {
        self.cf.from_normalised(p)
    }
}

/// Edges gathered per batch by [`Driver::blend_interior_edges`].
const EDGE_CHUNK: usize = 32;

/// What the F4 of one interior edge `e = (a, b)` reads: its end points, the candidates of the
/// stars of `a` and `b`, and the hint (the apex of the face on the left of `a → b`).
#[derive(Clone, Copy)]
struct EdgeInputs {
    e: u32,
    a: Point,
    b: Point,
    ca: Point,
    cb: Point,
    hint: Point,
}

struct Driver<'t, 'm, 's, 'o> {
    topo: &'t Topology<'m, 's>,
    pos: &'o mut [Point],
    /// Per half-edge `h`: the candidate of `edge(h)` from the form of `origin(h)`.
    edge_c: &'o mut [Point],
    /// Per half-edge (corner) `h`: the candidate of `face(h)` from the form of `origin(h)`.
    face_c: &'o mut [Point],
    report: MobiusReport,
    strict: bool,
}

impl Driver<'_, '_, '_, '_> {
    fn run(&mut self, scheme: Scheme) -> Result<()> {
        for c in self.edge_c.iter_mut().chain(self.face_c.iter_mut()) {
            *c = MISSING;
        }
        match scheme {
            Scheme::Loop => self.run_loop(),
            Scheme::CatmullClark => self.run_catmull_clark(),
            Scheme::ModifiedButterfly => self.run_butterfly(),
            Scheme::Kobbelt => self.run_kobbelt(),
            Scheme::DooSabin => self.run_doo_sabin(),
            Scheme::Simplest => self.run_simplest(),
            Scheme::Dual => self.run_face_scheme(0, false, false),
            Scheme::VertexInsertion => {
                let nv = self.topo.num_vertices();
                self.copy_old()?;
                self.run_face_scheme(nv, false, false)
            }
            Scheme::DualTruncation => {
                let nv = self.topo.num_vertices();
                self.run_face_scheme(nv, true, true)
            }
            // No Möbius form (Scheme::has_mobius_form).
            Scheme::Spherelike => Err(Error::new(Status::InvalidArgument)),
        }
    }

    /// Counts a fallback at output vertex `element`, or fails in strict mode.
    fn fallback(&mut self, element: usize) -> Result<()> {
        let e = element as u32;
        if self.strict {
            return Err(Error::at(Status::FallbackInStrictMode, e));
        }
        self.report.fallbacks = self.report.fallbacks.saturating_add(1);
        if self.report.first_fallback == NO_ELEMENT || e < self.report.first_fallback {
            self.report.first_fallback = e;
        }
        Ok(())
    }

    fn copy_old(&mut self) -> Result<()> {
        for (v, p) in self.topo.mesh().positions().enumerate() {
            set(self.pos, v, p)?;
        }
        Ok(())
    }

    /// A boundary vertex with one face (valence 2), from two lookups: its first spoke has no
    /// twin exactly when it is on the boundary (`Topology::is_boundary_vertex`), and a
    /// boundary vertex has one face fewer than neighbours.
    fn is_ear(&self, v: u32) -> Result<bool> {
        let topo = self.topo;
        let h = topo.vertex_half_edge(v)?;
        Ok(h != NONE && topo.twin(h)? == NONE && topo.valence(v)? == 2)
    }

    /// Re-targets `l` to the canonical form of a non-ear, non-isolated vertex; `false` (and
    /// `l` holds no form) when `v` is isolated or an ear or its form does not exist
    /// (degenerate star). With a form, `spokes` holds `v`'s star.
    fn local_into(&self, v: u32, l: &mut Local, spokes: &mut Spokes) -> Result<bool> {
        let topo = self.topo;
        // `is_isolated`, `is_boundary_vertex` and `is_ear` from one look at the first spoke.
        let h = topo.vertex_half_edge(v)?;
        let boundary = h != NONE && topo.twin(h)? == NONE;
        if h == NONE || (boundary && topo.valence(v)? == 2) {
            l.clear();
            return Ok(false);
        }
        l.reset(topo, v, boundary, spokes)
    }

    /// The vertex whose canonical form evaluates corner `i` of face `f`: the corner's own
    /// vertex, or for an ear the first non-ear corner at offset `h, h+1, h−1, h+2, …`.
    fn form_vertex(&self, f: u32, i: usize) -> Result<Option<u32>> {
        let verts = self.topo.face_vertices(f)?;
        let d = verts.len();
        let own = get(verts, i)?;
        if !self.is_ear(own)? {
            return Ok(Some(own));
        }
        let h = d / 2;
        for k in 0..d {
            // offsets h, h+1, h−1, h+2, h−2, …
            let step = k.div_ceil(2);
            let off = if k % 2 == 1 { h + step } else { h + d - step };
            let j = (i + off) % d.max(1);
            let u = get(verts, j)?;
            if !self.is_ear(u)? {
                return Ok(Some(u));
            }
        }
        Ok(None)
    }

    // ---- face points (Catmull–Clark, Akleman) ----

    /// Face candidates of every corner (the face centroid in the corner's form, ears via
    /// [`Self::form_vertex`]).
    fn face_candidates(&mut self, non_ears: bool) -> Result<()> {
        let topo = self.topo;
        let mut l = Local::blank();
        let mut spokes = Spokes::new();
        let mut pts = FacePts::new();
        for v in 0..topo.num_vertices() as u32 {
            if !non_ears {
                break;
            }
            if !self.local_into(v, &mut l, &mut spokes)? {
                continue;
            }
            for s in spokes.iter() {
                if s.face == NONE {
                    continue;
                }
                if let Ok(c) = l
                    .face_centroid(topo, s.face, &mut pts)
                    .and_then(|c| l.back(c))
                {
                    set(self.face_c, s.half_edge as usize, c)?;
                }
            }
        }
        // Ears: evaluate in the substitute vertex's form.
        for f in 0..topo.num_faces() as u32 {
            for (i, h) in topo.face_half_edges(f)?.enumerate() {
                let v = topo.origin(h)?;
                if !self.is_ear(v)? {
                    continue;
                }
                let Some(u) = self.form_vertex(f, i)? else {
                    continue;
                };
                if !self.local_into(u, &mut l, &mut spokes)? {
                    continue;
                }
                if let Ok(c) = l.face_centroid(topo, f, &mut pts).and_then(|c| l.back(c)) {
                    set(self.face_c, h as usize, c)?;
                }
            }
        }
        Ok(())
    }

    /// Blends the face candidates into face points written at `start + f`.
    fn blend_faces(&mut self, start: usize) -> Result<()> {
        let topo = self.topo;
        let mut verts = FacePts::new();
        let mut cands = FacePts::new();
        for f in 0..topo.num_faces() as u32 {
            face_points_into(topo, f, &mut verts)?;
            cands.clear();
            for h in topo.face_half_edges(f)? {
                cands
                    .try_push(get(self.face_c, h as usize)?)
                    .map_err(|_| internal())?;
            }
            let k = start + f as usize;
            let p = if cands.iter().all(present) {
                // Ties of the §4.4.3 sort go by vertex id, so the face point does not depend
                // on which corner the face is listed from (docs/DECISIONS.md).
                blend::face_point_with_ids(&verts, &cands, topo.face_vertices(f)?).ok()
            } else {
                None
            };
            let p = match p {
                Some(p) => p,
                None => {
                    self.fallback(k)?;
                    centroid(&verts)?
                }
            };
            set(self.pos, k, p)?;
        }
        Ok(())
    }

    /// Dual, vertex insertion, dual truncation: face points at `start`; with `truncate`, the
    /// interior old vertices move by the truncation rule in their own forms; `keep_boundary`
    /// keeps boundary vertices (as the linear driver does).
    fn run_face_scheme(&mut self, start: usize, truncate: bool, keep_boundary: bool) -> Result<()> {
        self.face_candidates(true)?;
        self.blend_faces(start)?;
        if truncate {
            let topo = self.topo;
            let mut l = Local::blank();
            let mut spokes = Spokes::new();
            let mut ring = Ring::new();
            for v in 0..topo.num_vertices() as u32 {
                let p = topo.position(v)?;
                let q = if topo.is_isolated(v)? || (keep_boundary && topo.is_boundary_vertex(v)?) {
                    p
                } else {
                    let m = if self.local_into(v, &mut l, &mut spokes)? {
                        (|| {
                            ring.clear();
                            for s in spokes.iter() {
                                ring.try_push(l.canon(topo, s.neighbour).ok()?).ok()?;
                            }
                            let t = akleman::truncated_vertex(ORIGIN, &ring).ok()?;
                            l.back(t).ok()
                        })()
                    } else {
                        None
                    };
                    match m {
                        Some(q) => q,
                        None => {
                            self.fallback(v as usize)?;
                            akleman::truncated_vertex(p, &ring_points(topo, v)?)?
                        }
                    }
                };
                set(self.pos, v as usize, q)?;
            }
        } else if start == 0 {
            // Dual: face points, then a point on each boundary vertex's outgoing boundary edge
            // (the linear midpoint becomes the Möbius interpolating curve rule), then the
            // boundary vertices themselves, then the isolated vertices (the linear layout).
            let topo = self.topo;
            let (nf, vb) = (topo.num_faces(), topo.num_boundary_vertices());
            for v in 0..topo.num_vertices() as u32 {
                let r = topo.boundary_vertex_rank(v)?;
                if r == NONE {
                    continue;
                }
                let h = topo.vertex_half_edge(v)?;
                let (i0, i3) = self.boundary_outer(h)?;
                let (a, b) = (topo.position(v)?, topo.position(topo.dest(h)?)?);
                let k = nf + r as usize;
                let q = match f4(topo.position(i0)?, a, b, topo.position(i3)?) {
                    Ok(q) => q,
                    Err(_) => {
                        self.fallback(k)?;
                        akleman::boundary_edge_point(a, b)
                    }
                };
                set(self.pos, k, q)?;
            }
            super::linear::boundary_vertices(topo, self.pos, nf + vb)?;
            super::linear::append_isolated(topo, self.pos, nf + 2 * vb)?;
        }
        Ok(())
    }

    // ---- edges ----

    /// Blends the interior edges' candidates with `F4(v_j, e_j, e_k, v_k)` into `start + e`;
    /// an edge with a single candidate takes it; `linear(e)` is the fallback when neither star
    /// gives one.
    fn blend_interior_edges(
        &mut self,
        start: usize,
        linear: &dyn Fn(&Self, u32) -> Result<Point>,
    ) -> Result<()> {
        let topo = self.topo;
        let ne = topo.num_edges() as u32;
        // Gather, then blend, `EDGE_CHUNK` edges at a time: the gathering reads the twin and
        // the two candidates of each edge at scattered addresses, and in one loop of short
        // independent iterations those cache misses overlap; between two F4 evaluations
        // (hundreds of instructions each) they would not. The same blends in the same order,
        // the same fallbacks; only a failing topology lookup (an internal error, never a
        // fallback) is now reported before a strict-mode fallback earlier in its batch.
        let mut chunk = ArrayVec::<EdgeInputs, EDGE_CHUNK>::new();
        let mut first = 0;
        while first < ne {
            let last = ne.min(first.saturating_add(EDGE_CHUNK as u32));
            chunk.clear();
            for e in first..last {
                let h = topo.edge_half_edge(e)?;
                let t = topo.twin(h)?;
                if t == NONE {
                    continue;
                }
                chunk
                    .try_push(EdgeInputs {
                        e,
                        a: topo.position(topo.origin(h)?)?,
                        b: topo.position(topo.dest(h)?)?,
                        ca: get(self.edge_c, h as usize)?,
                        cb: get(self.edge_c, t as usize)?,
                        hint: topo.position(topo.dest(topo.next(h)?)?)?,
                    })
                    .map_err(|_| internal())?;
            }
            for x in &chunk {
                let EdgeInputs {
                    e,
                    a,
                    b,
                    ca,
                    cb,
                    hint,
                } = *x;
                let k = start + e as usize;
                let p = if present(&ca) && present(&cb) {
                    f4_hinted(a, ca, cb, b, hint).ok()
                } else if present(&ca) {
                    // One star gave no candidate (Butterfly next to an irregular vertex, §4.3;
                    // or a star whose form sends a needed vertex to infinity, like a square
                    // corner): the other star's candidate, Möbius-invariant like the ear rule.
                    Some(ca)
                } else if present(&cb) {
                    Some(cb)
                } else {
                    None
                };
                let p = match p {
                    Some(p) if point::is_finite(&p) => p,
                    _ => {
                        self.fallback(k)?;
                        linear(self, e)?
                    }
                };
                set(self.pos, k, p)?;
            }
            first = last;
        }
        Ok(())
    }

    /// The boundary neighbours of boundary half-edge `h = (a → b)`: `(P_{i−1}, P_{i+2})`.
    fn boundary_outer(&self, h: u32) -> Result<(u32, u32)> {
        let topo = self.topo;
        Ok((
            topo.origin(topo.prev_boundary(h)?)?,
            topo.dest(topo.next_boundary(h)?)?,
        ))
    }

    /// Odd points of every boundary loop by the Möbius curve rule
    /// `F4(P_{i−1}, P_i, P_{i+1}, P_{i+2})` into `start + edge`; fallback `linear(p0, a, b, p1)`.
    fn boundary_edges(
        &mut self,
        start: usize,
        linear: fn(Point, Point, Point, Point) -> Point,
    ) -> Result<()> {
        let topo = self.topo;
        for e in 0..topo.num_edges() as u32 {
            let h = topo.edge_half_edge(e)?;
            if topo.twin(h)? != NONE {
                continue;
            }
            let (i0, i3) = self.boundary_outer(h)?;
            let p = [
                topo.position(i0)?,
                topo.position(topo.origin(h)?)?,
                topo.position(topo.dest(h)?)?,
                topo.position(i3)?,
            ];
            let k = start + e as usize;
            let q = match f4(p[0], p[1], p[2], p[3]) {
                Ok(q) => q,
                Err(_) => {
                    self.fallback(k)?;
                    linear(p[0], p[1], p[2], p[3])
                }
            };
            set(self.pos, k, q)?;
        }
        Ok(())
    }

    /// Even points of the boundary loops by the Möbius approximating rule
    /// `P'_i = F4(P_{i−1}, E_{i−½}, E_{i+½}, P_{i+1})`, reading the odd points from
    /// `start + edge`; fallback `3/4 v + 1/8 (b0 + b1)`.
    fn boundary_vertices_approximating(&mut self, start: usize) -> Result<()> {
        let topo = self.topo;
        for v in 0..topo.num_vertices() as u32 {
            if !topo.is_boundary_vertex(v)? {
                continue;
            }
            let out_h = topo.vertex_half_edge(v)?; // v → b0
            let in_h = topo.prev_boundary(out_h)?; // b1 → v
            let (b0, b1) = (topo.dest(out_h)?, topo.origin(in_h)?);
            let e_out = get(self.pos, start + topo.edge(out_h)? as usize)?;
            let e_in = get(self.pos, start + topo.edge(in_h)? as usize)?;
            let (p0, p1) = (topo.position(b1)?, topo.position(b0)?);
            let q = match f4(p0, e_in, e_out, p1) {
                Ok(q) => q,
                Err(_) => {
                    self.fallback(v as usize)?;
                    crate::stencil::crease_vertex(topo.position(v)?, p1, p0)
                }
            };
            set(self.pos, v as usize, q)?;
        }
        Ok(())
    }

    // ---- Loop ----

    fn run_loop(&mut self) -> Result<()> {
        let topo = self.topo;
        let nv = topo.num_vertices();
        let mut l = Local::blank();
        let mut spokes = Spokes::new();
        let mut ring = Ring::new();
        let mut cands = [MISSING; MAX_VALENCE];
        for v in 0..nv as u32 {
            let p = topo.position(v)?;
            if topo.is_isolated(v)? {
                set(self.pos, v as usize, p)?;
                continue;
            }
            let has_form = self.local_into(v, &mut l, &mut spokes)?;
            let boundary = topo.is_boundary_vertex(v)?;
            let mut vertex = None;
            if has_form {
                ring.clear();
                let mut ok = true;
                for s in &spokes {
                    match l.canon(topo, s.neighbour) {
                        Ok(c) => ring.try_push(c).map_err(|_| internal())?,
                        Err(_) => ok = false,
                    }
                }
                if ok {
                    // The apexes of spoke j's triangles are ring[j ± 1] (stars are CCW).
                    vertex = loop_star_in_form(&ring, !boundary, |q| l.back(q), &mut cands)?;
                    // By reference: `zip(cands)` would copy the whole array per vertex.
                    for (s, c) in spokes.iter().zip(cands.iter()) {
                        if s.half_edge != NONE && present(c) {
                            set(self.edge_c, s.half_edge as usize, *c)?;
                        }
                    }
                }
            }
            if !boundary {
                let q = match vertex {
                    Some(q) if point::is_finite(&q) => q,
                    _ => {
                        self.fallback(v as usize)?;
                        loop_scheme::vertex_interior(p, &ring_points(topo, v)?)?
                    }
                };
                set(self.pos, v as usize, q)?;
            }
        }
        let linear = |d: &Self, e: u32| -> Result<Point> {
            let t = d.topo;
            let h = t.edge_half_edge(e)?;
            Ok(loop_scheme::edge_interior(
                t.position(t.origin(h)?)?,
                t.position(t.dest(h)?)?,
                t.position(apex(t, h)?)?,
                t.position(apex(t, t.twin(h)?)?)?,
            ))
        };
        self.blend_interior_edges(nv, &linear)?;
        self.boundary_edges(nv, |_, a, b, _| loop_scheme::edge_boundary(a, b))?;
        self.boundary_vertices_approximating(nv)
    }

    // ---- Catmull–Clark ----

    fn run_catmull_clark(&mut self) -> Result<()> {
        let topo = self.topo;
        let nv = topo.num_vertices();
        let fp0 = nv + topo.num_edges();
        // Ears first (substitute forms); every other corner's candidate comes from the
        // vertex pass below, which maps each face into the corner's form once.
        self.face_candidates(false)?;
        let mut l = Local::blank();
        let mut spokes = Spokes::new();
        let mut ring = Ring::new();
        let mut fc = Ring::new();
        let mut pts = FacePts::new();
        let mut cands = [MISSING; MAX_VALENCE];
        for v in 0..nv as u32 {
            let p = topo.position(v)?;
            if topo.is_isolated(v)? {
                set(self.pos, v as usize, p)?;
                continue;
            }
            let boundary = topo.is_boundary_vertex(v)?;
            let mut vertex = None;
            if self.local_into(v, &mut l, &mut spokes)? {
                // Images of the neighbours and canonical centroids of the faces after each
                // spoke ([`MISSING`] when unavailable).
                ring.clear();
                fc.clear();
                for s in &spokes {
                    let c = if s.face == NONE {
                        MISSING
                    } else {
                        l.face_centroid(topo, s.face, &mut pts).unwrap_or(MISSING)
                    };
                    if present(&c) {
                        if let Ok(b) = l.back(c) {
                            set(self.face_c, s.half_edge as usize, b)?;
                        }
                    }
                    fc.try_push(c).map_err(|_| internal())?;
                    let r = l.canon(topo, s.neighbour).unwrap_or(MISSING);
                    ring.try_push(r).map_err(|_| internal())?;
                }
                vertex =
                    catmull_clark_star_in_form(&ring, &fc, !boundary, |q| l.back(q), &mut cands)?;
                for (s, c) in spokes.iter().zip(cands.iter()) {
                    if s.half_edge != NONE && present(c) {
                        set(self.edge_c, s.half_edge as usize, *c)?;
                    }
                }
            }
            if !boundary {
                let q = match vertex {
                    Some(q) if point::is_finite(&q) => q,
                    _ => {
                        self.fallback(v as usize)?;
                        let mut ring: ArrayVec<Point, MAX_VALENCE> = ArrayVec::new();
                        let mut faces: ArrayVec<Point, MAX_VALENCE> = ArrayVec::new();
                        for s in topo.star(v) {
                            ring.try_push(topo.position(s.neighbour)?)
                                .map_err(|_| internal())?;
                            faces
                                .try_push(centroid(&face_points(topo, s.face)?)?)
                                .map_err(|_| internal())?;
                        }
                        catmull_clark::vertex_interior(p, &ring, &faces)?
                    }
                };
                set(self.pos, v as usize, q)?;
            }
        }
        self.blend_faces(fp0)?;
        let linear = |d: &Self, e: u32| -> Result<Point> {
            let t = d.topo;
            let h = t.edge_half_edge(e)?;
            Ok(catmull_clark::edge_interior(
                t.position(t.origin(h)?)?,
                t.position(t.dest(h)?)?,
                centroid(&face_points(t, t.face(h)?)?)?,
                centroid(&face_points(t, t.face(t.twin(h)?)?)?)?,
            ))
        };
        self.blend_interior_edges(nv, &linear)?;
        self.boundary_edges(nv, |_, a, b, _| catmull_clark::edge_boundary(a, b))?;
        self.boundary_vertices_approximating(nv)
    }

    // ---- Simplest ----

    /// Edge midpoints: interior edges blend the midpoints taken in the two endpoints' forms;
    /// boundary edges use the interpolating curve rule.
    fn run_simplest(&mut self) -> Result<()> {
        let topo = self.topo;
        let mut l = Local::blank();
        let mut spokes = Spokes::new();
        for v in 0..topo.num_vertices() as u32 {
            if !self.local_into(v, &mut l, &mut spokes)? {
                continue;
            }
            for s in spokes.iter() {
                if s.half_edge == NONE || topo.twin(s.half_edge)? == NONE {
                    continue;
                }
                if let Ok(c) = l
                    .canon(topo, s.neighbour)
                    .and_then(|b| l.back(simplest::edge_point(ORIGIN, b)))
                {
                    set(self.edge_c, s.half_edge as usize, c)?;
                }
            }
        }
        let linear = |d: &Self, e: u32| -> Result<Point> {
            let (a, b) = d.topo.edge_vertices(e)?;
            Ok(simplest::edge_point(
                d.topo.position(a)?,
                d.topo.position(b)?,
            ))
        };
        self.blend_interior_edges(0, &linear)?;
        self.boundary_edges(0, |_, a, b, _| midpoint(a, b))?;
        // Then the boundary vertices and the isolated vertices, as the linear layout.
        let ne = topo.num_edges();
        super::linear::boundary_vertices(topo, self.pos, ne)?;
        super::linear::append_isolated(topo, self.pos, ne + topo.num_boundary_vertices())
    }

    // ---- Doo–Sabin ----

    /// Each corner point in the canonical form of its vertex (ears: a substitute's form).
    fn run_doo_sabin(&mut self) -> Result<()> {
        let topo = self.topo;
        let nh = topo.num_half_edges();
        for p in self.pos.iter_mut().take(nh) {
            *p = MISSING;
        }
        // One canonical form per vertex: all its corners.
        let mut l = Local::blank();
        let mut spokes = Spokes::new();
        let mut pts = FacePts::new();
        for v in 0..topo.num_vertices() as u32 {
            if !self.local_into(v, &mut l, &mut spokes)? {
                continue;
            }
            for s in spokes.iter() {
                if s.face == NONE {
                    continue;
                }
                let i = (s.half_edge - topo.face_half_edges(s.face)?.start) as usize;
                let q = l
                    .face(topo, s.face, &mut pts)
                    .and_then(|()| doo_sabin::corner_point(&pts, i))
                    .and_then(|c| l.back(c));
                if let Ok(q) = q {
                    set(self.pos, s.half_edge as usize, q)?;
                }
            }
        }
        // Ears in a substitute's form; anything still missing takes the linear rule.
        let mut linear_pts = FacePts::new();
        for f in 0..topo.num_faces() as u32 {
            // The face's own corners only when one of its corner points is missing (rare).
            let mut gathered = false;
            for (i, h) in topo.face_half_edges(f)?.enumerate() {
                if present(&get(self.pos, h as usize)?) {
                    continue;
                }
                if !gathered {
                    face_points_into(topo, f, &mut linear_pts)?;
                    gathered = true;
                }
                let q = if self.is_ear(topo.origin(h)?)? {
                    self.form_vertex(f, i)?.and_then(|u| {
                        if !self.local_into(u, &mut l, &mut spokes).ok()? {
                            return None;
                        }
                        l.face(topo, f, &mut pts).ok()?;
                        let c = doo_sabin::corner_point(&pts, i).ok()?;
                        l.back(c).ok()
                    })
                } else {
                    None
                };
                let q = match q {
                    Some(q) if point::is_finite(&q) => q,
                    _ => {
                        self.fallback(h as usize)?;
                        doo_sabin::corner_point(&linear_pts, i)?
                    }
                };
                set(self.pos, h as usize, q)?;
            }
        }
        super::linear::append_isolated(topo, self.pos, nh)
    }

    // ---- Modified Butterfly (2-ring: partial candidates, §4.3, Fig. 11 right) ----

    fn run_butterfly(&mut self) -> Result<()> {
        let topo = self.topo;
        let nv = topo.num_vertices();
        self.copy_old()?;
        let mut l = Local::blank();
        let mut spokes = Spokes::new();
        let mut ring = Ring::new();
        for v in 0..nv as u32 {
            if !self.local_into(v, &mut l, &mut spokes)? {
                continue;
            }
            let boundary = topo.is_boundary_vertex(v)?;
            let irregular = !boundary && topo.valence(v)? != 6;
            let n = spokes.len();
            for (j, s) in spokes.iter().enumerate() {
                let h = s.half_edge;
                if h == NONE || topo.twin(h)? == NONE {
                    continue;
                }
                let other = s.neighbour;
                let other_irregular = !topo.is_boundary_vertex(other)? && topo.valence(other)? != 6;
                let cand = (|| -> Result<Option<Point>> {
                    if irregular {
                        // Zorin's stencil of v, ring starting at the other endpoint.
                        ring.clear();
                        for k in 0..n {
                            let sk = spokes.get((j + k) % n).ok_or(internal())?;
                            ring.try_push(l.canon(topo, sk.neighbour)?)
                                .map_err(|_| internal())?;
                        }
                        let z = butterfly::zorin_stencil(ORIGIN, &ring)?;
                        return Ok(Some(l.back(z)?));
                    }
                    if other_irregular {
                        // Only the singular ring contributes (§4.3).
                        return Ok(None);
                    }
                    // Regular–regular: v's half of the 8-point stencil, doubled:
                    // a0, a1 ½; b0, b1 ⅛; v's two wings −⅛ (OpenMesh's reflection across a
                    // boundary edge, evaluated in this form).
                    let t = topo.twin(h)?;
                    let a0 = ORIGIN;
                    let a1 = l.canon(topo, other)?;
                    let b0 = l.canon(topo, apex(topo, h)?)?;
                    let b1 = l.canon(topo, apex(topo, t)?)?;
                    // v's wings lie across the triangle edges at v: prev(h) and next(twin h).
                    let c0 = self.across_in(&mut l, topo.prev(h)?)?;
                    let c3 = self.across_in(&mut l, topo.next(t)?)?;
                    let p = [
                        a0[0] * 0.5 + a1[0] * 0.5 + (b0[0] + b1[0]) * 0.125
                            - (c0[0] + c3[0]) * 0.125,
                        a0[1] * 0.5 + a1[1] * 0.5 + (b0[1] + b1[1]) * 0.125
                            - (c0[1] + c3[1]) * 0.125,
                        a0[2] * 0.5 + a1[2] * 0.5 + (b0[2] + b1[2]) * 0.125
                            - (c0[2] + c3[2]) * 0.125,
                    ];
                    Ok(Some(l.back(p)?))
                })();
                if let Ok(Some(c)) = cand {
                    set(self.edge_c, h as usize, c)?;
                }
            }
        }
        let linear = |d: &Self, e: u32| -> Result<Point> { butterfly_linear_edge(d.topo, e) };
        self.blend_interior_edges(nv, &linear)?;
        self.boundary_edges(nv, butterfly::edge_boundary)
    }

    /// The butterfly "wing" across the triangle edge `g`, in the form `l`: the apex beyond
    /// `g`, or the reflection `u + w − z` (`z` the corner of `g`'s triangle opposite `g`) when
    /// `g` is a boundary edge (OpenMesh).
    fn across_in(&self, l: &mut Local, g: u32) -> Result<Point> {
        let topo = self.topo;
        let t = topo.twin(g)?;
        if t == NONE {
            let u = l.canon(topo, topo.origin(g)?)?;
            let w = l.canon(topo, topo.dest(g)?)?;
            let z = l.canon(topo, apex(topo, g)?)?;
            Ok(butterfly::reflect(u, w, z))
        } else {
            l.canon(topo, apex(topo, t)?)
        }
    }

    // ---- Kobbelt (2-ring: virtual points, F4 edges, F6 faces; §4.3, Fig. 11 left, Fig. 14) ----

    fn run_kobbelt(&mut self) -> Result<()> {
        let topo = self.topo;
        let nv = topo.num_vertices();
        let ne = topo.num_edges();
        self.copy_old()?;
        // Virtual points: per half-edge h = (v → u), the point beyond v away from u, from
        // v's canonical form (regular interior vertices give the actual grid neighbour).
        let mut l = Local::blank();
        let mut spokes = Spokes::new();
        let mut q = Ring::new();
        let mut dg = Ring::new();
        for v in 0..nv as u32 {
            if topo.is_isolated(v)? {
                continue;
            }
            if !self.local_into(v, &mut l, &mut spokes)? {
                continue;
            }
            if topo.is_boundary_vertex(v)? {
                // The linear boundary extrapolation 2v − u, evaluated in v's boundary form.
                for s in spokes.iter() {
                    if s.half_edge == NONE || topo.twin(s.half_edge)? == NONE {
                        continue;
                    }
                    if let Ok(c) = l
                        .canon(topo, s.neighbour)
                        .and_then(|u| l.back(kobbelt::extrapolate(ORIGIN, u)))
                    {
                        set(self.edge_c, s.half_edge as usize, c)?;
                    }
                }
                continue;
            }
            q.clear();
            dg.clear();
            let mut ok = true;
            for s in &spokes {
                match (
                    l.canon(topo, s.neighbour),
                    apex(topo, s.half_edge).and_then(|a| l.canon(topo, a)),
                ) {
                    (Ok(a), Ok(b)) => {
                        q.try_push(a).map_err(|_| internal())?;
                        dg.try_push(b).map_err(|_| internal())?;
                    }
                    _ => ok = false,
                }
            }
            if !ok {
                continue;
            }
            for (j, s) in spokes.iter().enumerate() {
                if let Ok(c) = kobbelt::virtual_point(&q, &dg, j).and_then(|p| l.back(p)) {
                    set(self.edge_c, s.half_edge as usize, c)?;
                }
            }
        }
        // Edge points F4(r0, a0, a1, r1).
        for e in 0..ne as u32 {
            let h = topo.edge_half_edge(e)?;
            let (i0, i1) = (topo.origin(h)?, topo.dest(h)?);
            let (a0, a1) = (topo.position(i0)?, topo.position(i1)?);
            let k = nv + e as usize;
            let (r0, r1) = if topo.twin(h)? == NONE {
                let (o0, o3) = self.boundary_outer(h)?;
                (Some(topo.position(o0)?), Some(topo.position(o3)?))
            } else {
                (self.beyond(i0, h)?, self.beyond(i1, topo.twin(h)?)?)
            };
            let hint = topo.position(topo.dest(topo.next(h)?)?)?;
            let q = match (r0, r1) {
                (Some(r0), Some(r1)) => f4_hinted(r0, a0, a1, r1, hint).ok(),
                _ => None,
            };
            let q = match q {
                Some(q) => q,
                None => {
                    self.fallback(k)?;
                    kobbelt_linear_edge(topo, e)?
                }
            };
            set(self.pos, k, q)?;
        }
        // Face points: F6(w2, F4(w1..w4), w3, w6, F4(w5..w8), w7) over the two grid lines
        // of new edge points through the face (Fig. 14).
        for f in 0..topo.num_faces() as u32 {
            let r = topo.face_half_edges(f)?;
            let (h0, h1, h2, h3) = kobbelt_lines(topo, r.start)?;
            let k = nv + ne + f as usize;
            let line = |d: &Self, hx: u32, hy: u32| -> Result<[Point; 4]> {
                Ok([
                    d.outer_edge_point(hx, hy)?,
                    d.edge_point(hx)?,
                    d.edge_point(hy)?,
                    d.outer_edge_point(hy, hx)?,
                ])
            };
            let w = line(self, h0, h2)?;
            let x = line(self, h1, h3)?;
            let q = f4(w[0], w[1], w[2], w[3])
                .and_then(|pa| {
                    let pb = f4(x[0], x[1], x[2], x[3])?;
                    blend::f6(w[1], pa, w[2], x[1], pb, x[2])
                })
                .ok();
            let q = match q {
                Some(q) => q,
                None => {
                    self.fallback(k)?;
                    let fa = kobbelt::four_point(w[0], w[1], w[2], w[3]);
                    let fb = kobbelt::four_point(x[0], x[1], x[2], x[3]);
                    midpoint(fa, fb)
                }
            };
            set(self.pos, k, q)?;
        }
        Ok(())
    }

    /// The virtual point beyond `v` on the line from the far end of half-edge `h` (which
    /// starts at `v`), computed in `v`'s canonical form (interior: Kobbelt's virtual point;
    /// boundary: the extrapolation `2v − u` of the linear driver); `None` when `v` has no form.
    fn beyond(&self, _v: u32, h: u32) -> Result<Option<Point>> {
        let c = get(self.edge_c, h as usize)?;
        Ok(present(&c).then_some(c))
    }

    fn edge_point(&self, h: u32) -> Result<Point> {
        get(
            self.pos,
            self.topo.num_vertices() + self.topo.edge(h)? as usize,
        )
    }

    /// The new edge point beyond edge `hx` of a quad, away from its opposite edge `hy`: the
    /// edge point of the neighbouring quad's opposite edge, or at the boundary the
    /// extrapolation of the linear driver.
    fn outer_edge_point(&self, hx: u32, hy: u32) -> Result<Point> {
        let topo = self.topo;
        let t = topo.twin(hx)?;
        if t != NONE {
            return self.edge_point(topo.next(topo.next(t)?)?);
        }
        // The Möbius-invariant open-end extrapolation of the curve rules (DESIGN.md "Open
        // ends", cr[P_2, P_1, P_0, P_−1] = −1/3) along the face's grid line; a strip one face
        // wide has no third point and takes the linear `2e − e'`.
        let (e0, e1) = (self.edge_point(hx)?, self.edge_point(hy)?);
        let ty = topo.twin(hy)?;
        if ty != NONE {
            let e2 = self.edge_point(topo.next(topo.next(ty)?)?)?;
            if let Ok(p) = crate::curve::mobius::virtual_end_point(e0, e1, e2) {
                return Ok(p);
            }
        }
        Ok(kobbelt::extrapolate(e0, e1))
    }
}

/// The third vertex of the triangle of half-edge `h`.
fn apex(topo: &Topology<'_, '_>, h: u32) -> Result<u32> {
    topo.dest(topo.next(h)?)
}

/// The linear Modified Butterfly edge point (fallback), as the linear driver computes it.
fn butterfly_linear_edge(topo: &Topology<'_, '_>, e: u32) -> Result<Point> {
    super::linear::butterfly_edge(topo, e)
}

/// The linear Kobbelt edge point (fallback), as the linear driver computes it.
fn kobbelt_linear_edge(topo: &Topology<'_, '_>, e: u32) -> Result<Point> {
    super::linear::kobbelt_edge(topo, e)
}

/// The half-edges `(h0, h1, h2, h3)` of the quad whose first half-edge is `first`, arranged so
/// that Kobbelt's face point `F6(w1, F4(w), w2, x1, F4(x), x2)` over the grid lines `(h0, h2)`
/// and `(h1, h3)` does not depend on where the face starts: F6 is symmetric neither in its two
/// lines nor in their directions, so each line runs from its edge of smaller id, and the line
/// holding the smallest edge id comes first. Edge ids are untouched by Möbius maps, so the
/// rule keeps Möbius equivariance (docs/DECISIONS.md).
fn kobbelt_lines(topo: &Topology<'_, '_>, first: u32) -> Result<(u32, u32, u32, u32)> {
    let edge_of = |h: u32| topo.edge(h).map(|e| (e, h));
    let [p, q, r, t] = [first, first + 1, first + 2, first + 3];
    let (e0, e1, e2, e3) = (edge_of(p)?, edge_of(q)?, edge_of(r)?, edge_of(t)?);
    // Each line from its edge of smaller id; (edge id, half-edge) pairs compare by id first.
    let (a0, a1) = (e0.min(e2), e0.max(e2));
    let (b0, b1) = (e1.min(e3), e1.max(e3));
    Ok(if a0 <= b0 {
        (a0.1, b0.1, a1.1, b1.1)
    } else {
        (b0.1, a0.1, b1.1, a1.1)
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{topology_scratch_len, Mesh};

    /// The drivers' star walk is [`Topology::spokes_into`] spoke for spoke, on all-triangle,
    /// all-quad and mixed meshes with boundaries and on a closed one (the walk's arithmetic
    /// fast paths and the general one).
    #[test]
    fn star_walk_matches_the_topology() {
        // A 3×3 grid of vertices: four quads; eight triangles; three quads and two triangles.
        let mut grid = [[0.0; 3]; 9];
        for (i, p) in grid.iter_mut().enumerate() {
            *p = [(i % 3) as f64, (i / 3) as f64, 0.0];
        }
        let octa = [
            [1.0, 0.0, 0.0],
            [-1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, -1.0, 0.0],
            [0.0, 0.0, 1.0],
            [0.0, 0.0, -1.0],
        ];
        let tri_offs = [0, 3, 6, 9, 12, 15, 18, 21, 24];
        let cases: [(&[Point], &[u32], &[u32]); 4] = [
            (
                &grid,
                &[0, 4, 8, 12, 16],
                &[0, 1, 4, 3, 1, 2, 5, 4, 3, 4, 7, 6, 4, 5, 8, 7],
            ),
            (
                &grid,
                &tri_offs,
                &[
                    0, 1, 4, 0, 4, 3, 1, 2, 5, 1, 5, 4, 3, 4, 7, 3, 7, 6, 4, 5, 8, 4, 8, 7,
                ],
            ),
            (
                &grid,
                &[0, 4, 8, 12, 15, 18],
                &[0, 1, 4, 3, 1, 2, 5, 4, 3, 4, 7, 6, 4, 5, 8, 4, 8, 7],
            ),
            (
                &octa,
                &tri_offs,
                &[
                    0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5,
                ],
            ),
        ];
        let mut buf = [0u32; 1024];
        for (p, offs, idx) in cases {
            let mesh = Mesh::new(p, offs, idx);
            let scratch = &mut buf[..topology_scratch_len(p.len(), idx.len()).unwrap()];
            let topo = Topology::build(mesh, scratch).unwrap();
            let (mut a, mut b) = (Spokes::new(), Spokes::new());
            for v in 0..p.len() as u32 {
                topo.spokes_into(v, &mut a).unwrap();
                star_into(&topo, v, &mut b).unwrap();
                assert_eq!(a, b, "vertex {v}");
                assert!(!b.is_empty());
            }
        }
    }
}
