//! Canonical Möbius subdivision (seed 000 §4): the Möbius version of every linear scheme.
//!
//! Per vertex `v` (§4.1, Fig. 6):
//! 1. the canonical form `C_v` of its star ([`crate::mobius::CanonicalForm`], §4.2; interior
//!    stars use the barycentre of the tangent polygon, boundary stars the mean of the two
//!    boundary neighbours' images);
//! 2. the linear stencils of [`crate::stencil`] evaluated on the 1-ring mapped into `C_v`;
//! 3. the candidate points mapped back with `m_{C→B}`;
//! 4. blends across stars: an edge point is `F4(v_j, e_j, e_k, v_k)` (§4.4.3), a face point the
//!    sorted F4/F6 chain of [`crate::blend::face_point`]; vertex points come from the vertex's
//!    own form.
//!
//! Boundary loops are curves and use the Möbius curve rules (§4.3 "Boundary curves",
//! §4.4.1): the approximating rule for approximating schemes (odd
//! `E_{i+½} = F4(P_{i−1}, P_i, P_{i+1}, P_{i+2})`, even
//! `P'_i = F4(P_{i−1}, E_{i−½}, E_{i+½}, P_{i+1})`), the interpolating rule (odd points only)
//! for the others.
//!
//! **Ear vertices** (boundary vertices with one face) have no usable form for a quad: their
//! canonical form sends the opposite corner to infinity. Anything an ear would contribute to
//! its face (a face candidate, a Doo–Sabin corner point) is evaluated in the canonical form
//! of the first non-ear vertex of the face at offset `h, h+1, h−1, h+2, …` (`h = ⌊d/2⌋`),
//! which keeps the rule Möbius-invariant and exact on Möbius images of regular grids. A face
//! of ears only takes its linear centroid, counted as a fallback.
//!
//! **The fold guard** (every scheme with a Möbius form; the default, off with
//! [`Options::literal`](super::Options::literal)): seed 000 §7.1 notes that the scheme
//! can fold non-Delaunay meshes, and `docs/folds.md` traces the folds to ill-conditioned
//! canonical forms. Stars whose Möbius-invariant trust (`trust.rs`) is below 1 are evaluated
//! again in their form interpolated toward the linear rule (`spectrum.rs`, §7.2; not
//! the other schemes, whose stars only feed blends or their own points), and the points
//! near them blend toward the linear
//! rule (`toward_linear.rs`); the changed
//! elements are counted in the [`Report`](super::Report) (`guarded`) or refused in strict
//! mode (`guard.rs`). [`Options::spectrum`](super::Options::spectrum) blends every output
//! with the linear one globally.
//!
//! **Degenerate neighbourhoods** (coincident points, a star whose canonical form does not
//! exist, a blend at infinity): the element takes its linear rule, evaluated on the original
//! positions; it is counted in the [`Report`](super::Report) (count and first output vertex),
//! and with [`Options::strict`](super::Options::strict) it is an error instead
//! ([`Status::FallbackInStrictMode`]). No non-finite value reaches the output.
//!
//! # Where things are
//!
//! * the rules at one vertex star, public for hosts that own the connectivity (tier 1):
//!   [`loop_star`], [`catmull_clark_star`], [`butterfly_star`], [`kobbelt_star`],
//!   [`doo_sabin_star`] (`rules/`, one file per scheme);
//! * steps 1–3 per vertex: `form.rs` (the canonical form of a star given by points and the
//!   conventions of the normalised frame), `memo.rs` (the form of a mesh vertex with a memo
//!   of canonical images), `vertex_pass.rs` (the pass every driver runs, split into
//!   vertex ranges), `workspace.rs` (each range's star workspace in the point scratch: the
//!   per-star arrays of the rules), `slots.rs` (the vertex-major slots of the candidates),
//!   `ears.rs` (substitute forms for ears);
//! * step 4: `edges.rs` (edge blends), `faces.rs` (face-point blends), `boundary.rs`
//!   (boundary curves, closed or open between corners);
//! * sharp features: `crease.rs` (a tagged level refined as the level cut along its sharp
//!   edges, so creases are boundary curves);
//! * the fold guard: `trust.rs` (the criterion), `spectrum.rs` (the interpolated form
//!   `m_τ`), `guard.rs` (its passes and counts);
//! * `drivers/`: one per scheme, choosing the rule and the blends; `driver.rs`: the state of
//!   one step and the fallback report. `step` below dispatches; the public entry is
//!   [`super::subdivide`] with [`Options::mobius`](super::Options::mobius).

mod audit;
mod boundary;
pub(crate) mod crease;
mod driver;
mod drivers;
mod ears;
mod edges;
mod faces;
mod form;
mod guard;
mod memo;
mod rules;
mod slots;
mod spectrum;
mod toward_linear;
mod trust;
mod vertex_pass;
pub(crate) mod workspace;

pub use rules::{butterfly_star, catmull_clark_star, doo_sabin_star, kobbelt_star, loop_star};

use super::Scheme;
use crate::error::{Error, Result, Status, NO_ELEMENT};
use crate::exec::{self, Executor};
use crate::mesh::refine::write_pattern_with;
use crate::mesh::{internal, MeshOut, MeshSizes, Topology};
use crate::point::{self, Point};
use driver::Driver;

/// Options of one Möbius step (from [`super::Options`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct MobiusOptions {
    /// Turn every linear fallback into [`Status::FallbackInStrictMode`] naming the output
    /// vertex (and every element the guard changes).
    pub(crate) strict: bool,
    /// The fold guard (`guard.rs`); `false` runs the paper's rules exactly.
    pub(crate) guard: bool,
    /// The weight `w ∈ (0, 1]` of the Möbius–linear spectrum (seed 000 §7.2): below 1, every
    /// output vertex is `w · (Möbius point) + (1 − w) · (linear point)`, the linear points
    /// written to the scratch after the candidates.
    pub(crate) spectrum: f64,
}

/// What one Möbius step had to do besides the paper's rules (gathered over the levels into
/// [`super::Report`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct MobiusReport {
    /// Output vertices that took their linear rule (degenerate neighbourhood).
    pub(crate) fallbacks: u32,
    /// The first such output vertex, or [`NO_ELEMENT`].
    pub(crate) first_fallback: u32,
    /// Output vertices the fold guard changed.
    pub(crate) guarded: u32,
    /// The first such output vertex, or [`NO_ELEMENT`].
    pub(crate) first_guarded: u32,
}

impl Default for MobiusReport {
    fn default() -> Self {
        MobiusReport {
            fallbacks: 0,
            first_fallback: NO_ELEMENT,
            guarded: 0,
            first_guarded: NO_ELEMENT,
        }
    }
}

/// The candidate points one step needs on a level of `num_vertices` vertices and
/// `num_corners` corners (= half-edges): an edge candidate and a face candidate per
/// half-edge, then per vertex the centre of its canonical form (a point), then per vertex
/// the fold guard's trust and the form's radius, per half-edge its candidates' slot
/// (`slots.rs`) and per edge (at most one per half-edge) the guard's F4-angle term
/// (`guard.rs`), `f64` values three to a point.
///
/// # Errors
/// [`Status::SizeOverflow`].
pub(crate) fn candidate_points(num_vertices: usize, num_corners: usize) -> Result<usize> {
    num_vertices
        .checked_mul(2)
        .and_then(|f| f.checked_add(num_corners))
        .and_then(|f| f.checked_add(num_corners))
        .and_then(|f| f.checked_add(2))
        .map(|f| f / 3)
        .and_then(|f| f.checked_add(num_vertices))
        .and_then(|v| num_corners.checked_mul(2).and_then(|c| c.checked_add(v)))
        .ok_or(Error::new(Status::SizeOverflow))
}

/// Writes one step of the Möbius version of `scheme` on `topo` into `out`, with `scratch`
/// of at least [`candidate_points`] points and the star workspace of `topo`'s largest
/// valence ([`workspace::workspace_points`]), and `spoke_work` of at least
/// [`workspace::spoke_u32s`] entries. The connectivity and the output vertex order are
/// those of the linear scheme ([`super::step::linear`]).
///
/// # Errors
/// Those of [`super::size::step_size`]; [`Status::InvalidArgument`] for a scheme without a
/// Möbius form ([`Scheme::has_mobius_form`]); [`Status::BufferTooSmall`] for `out` or
/// `scratch`; [`Status::FallbackInStrictMode`] (element = output vertex) with
/// [`MobiusOptions::strict`]; [`Status::NumericalFailure`] naming an output vertex that is
/// not finite.
///
/// `corners` marks the vertices where a boundary loop ends as an open curve (sharp
/// features, [`crease`]), and `uncut` is the level before the cut (whose twin of a boundary
/// half-edge of a crease is the crease's half-edge on the other side, and whose tags give
/// the fold guard's linear rule); empty and `None` otherwise.
#[allow(clippy::too_many_arguments)] // the level, its output, two scratch buffers, the options
pub(crate) fn step(
    scheme: Scheme,
    topo: &Topology<'_, '_>,
    out: &mut MeshOut<'_>,
    scratch: &mut [Point],
    spoke_work: &mut [u32],
    opts: MobiusOptions,
    exec: &dyn Executor,
) -> Result<(MeshSizes, MobiusReport)> {
    step_with::<false>(
        scheme,
        topo,
        out,
        scratch,
        spoke_work,
        opts,
        exec,
        &[],
        None,
    )
}

/// [`step`] of a level cut along its sharp edges ([`crease`]), for the schemes that take
/// sharp-feature tags (Loop, Catmull–Clark, Modified Butterfly, Kobbelt; the others are
/// refused before, `TagsNotSupported`). `corners` marks the vertices where a boundary loop
/// ends as an open curve, and `uncut` is the level before the cut (its twin of a half-edge
/// is, for a boundary half-edge of a crease, the crease's half-edge on the other side, and
/// its tags give the fold guard's linear rule); empty and `None` on a level with nothing
/// sharp. Its own instance of the step, whose dispatch holds
/// only those four drivers: the tagged call's deepest stack path does not pass through the
/// drivers it never runs (`docs/firmware.md`, "Stack").
#[allow(clippy::too_many_arguments)]
pub(crate) fn step_cut(
    scheme: Scheme,
    topo: &Topology<'_, '_>,
    out: &mut MeshOut<'_>,
    scratch: &mut [Point],
    spoke_work: &mut [u32],
    opts: MobiusOptions,
    exec: &dyn Executor,
    corners: &[u32],
    uncut: Option<crease::Uncut<'_>>,
) -> Result<(MeshSizes, MobiusReport)> {
    step_with::<true>(
        scheme, topo, out, scratch, spoke_work, opts, exec, corners, uncut,
    )
}

/// [`step`], or with `CUT` [`step_cut`].
#[allow(clippy::too_many_arguments)]
fn step_with<const CUT: bool>(
    scheme: Scheme,
    topo: &Topology<'_, '_>,
    out: &mut MeshOut<'_>,
    scratch: &mut [Point],
    spoke_work: &mut [u32],
    opts: MobiusOptions,
    exec: &dyn Executor,
    corners: &[u32],
    uncut: Option<crease::Uncut<'_>>,
) -> Result<(MeshSizes, MobiusReport)> {
    if !scheme.has_mobius_form() {
        // Refused before anything is written (seed 003's spherelike rule has no Möbius form).
        return Err(Error::new(Status::InvalidArgument));
    }
    super::built::check(scheme, true)?;
    let sizes = super::size::step_size(scheme, topo)?;
    out.check(&sizes)?;
    let nv = topo.num_vertices();
    let candidates = candidate_points(nv, topo.num_half_edges())?;
    let max_valence = workspace::max_valence(topo)?;
    let elements = nv.max(topo.num_faces());
    let work = workspace::workspace_points(max_valence, topo.max_face_size(), elements)?;
    let spokes = workspace::spoke_u32s(max_valence, nv)?;
    if spoke_work.len() < spokes {
        return Err(Error::too_small(spokes));
    }
    let blend = opts.spectrum < 1.0;
    let step_points = candidates
        .checked_add(work)
        .ok_or(Error::new(Status::SizeOverflow))?;
    let need = if blend {
        step_points
            .checked_add(sizes.vertices)
            .ok_or(Error::new(Status::SizeOverflow))?
    } else {
        step_points
    };
    if scratch.len() < need {
        return Err(Error::too_small(need));
    }
    // `split_at_mut_checked`, not `split_at_mut`: the length is checked above, but the
    // panicking form would link a panic path into every export (the link proof refuses it).
    let (scratch, rest) = scratch.split_at_mut_checked(candidates).ok_or(internal())?;
    let (work, linear_pos) = rest.split_at_mut_checked(work).ok_or(internal())?;
    write_pattern_with(scheme.pattern(), topo, out.offsets, out.indices, exec)?;
    let pos = out.positions.get_mut(..sizes.vertices).ok_or(internal())?;
    let nh = topo.num_half_edges();
    let (edge_c, rest) = scratch.split_at_mut_checked(nh).ok_or(internal())?;
    let (face_c, rest) = rest.split_at_mut_checked(nh).ok_or(internal())?;
    let (centre, rest) = rest.split_at_mut_checked(nv).ok_or(internal())?;
    let (trust, rest) = rest
        .as_flattened_mut()
        .split_at_mut_checked(nv)
        .ok_or(internal())?;
    let (radius, rest) = rest.split_at_mut_checked(nv).ok_or(internal())?;
    let (slot_map, rest) = rest.split_at_mut_checked(nh).ok_or(internal())?;
    let edge_trust = rest.get_mut(..topo.num_edges()).ok_or(internal())?;
    slots::write(topo, slot_map)?;
    driver::clear(
        exec,
        [&mut *edge_c, &mut *face_c],
        [(&mut *trust, 1.0), (&mut *radius, 0.0)],
    )?;
    let form = (trust, centre, radius);
    let mut d = Driver::new(topo, pos, (edge_c, face_c, slot_map), form, opts, exec);
    d.work = work;
    d.spoke_work = spoke_work.get_mut(..spokes).ok_or(internal())?;
    d.corners = corners;
    d.uncut = uncut;
    d.edge_trust = edge_trust;
    // A driver is reached only when this build contains its scheme and the Möbius forms
    // (`super::built`): an arm of a scheme left out has a constant `false` guard, so the
    // optimiser removes it and the linker the driver.
    let mobius = cfg!(feature = "mobius");
    match scheme {
        Scheme::Loop if mobius && cfg!(feature = "loop") => drivers::loop_scheme::run(&mut d)?,
        Scheme::CatmullClark if mobius && cfg!(feature = "catmull-clark") => {
            drivers::catmull_clark::run(&mut d)?
        }
        Scheme::ModifiedButterfly if mobius && cfg!(feature = "butterfly") => {
            drivers::butterfly::run(&mut d)?
        }
        Scheme::Kobbelt if mobius && cfg!(feature = "kobbelt") => drivers::kobbelt::run(&mut d)?,
        // Schemes without sharp-feature rules: never a cut level.
        Scheme::DooSabin if !CUT && mobius && cfg!(feature = "doo-sabin") => {
            drivers::doo_sabin::run(&mut d)?
        }
        Scheme::Simplest if !CUT && mobius && cfg!(feature = "simplest") => {
            drivers::simplest::run(&mut d)?
        }
        Scheme::Dual if !CUT && mobius && cfg!(feature = "akleman") => {
            drivers::akleman::dual(&mut d)?
        }
        Scheme::VertexInsertion if !CUT && mobius && cfg!(feature = "akleman") => {
            drivers::akleman::vertex_insertion(&mut d)?
        }
        Scheme::DualTruncation if !CUT && mobius && cfg!(feature = "akleman") => {
            drivers::akleman::dual_truncation(&mut d)?
        }
        // No Möbius form (refused above).
        Scheme::Spherelike => return Err(Error::new(Status::InvalidArgument)),
        // A scheme without sharp-feature rules on a cut level (refused before, by the plan).
        _ if CUT => return Err(Error::new(Status::TagsNotSupported)),
        _ => return Err(super::built::not_built()),
    }
    let report = d.report;
    if blend {
        spectrum_blend(
            scheme,
            topo,
            pos_of(out, sizes.vertices)?,
            linear_pos,
            opts.spectrum,
            exec,
        )?;
    }
    if let Some(i) = exec::first_non_finite(exec, pos_of(out, sizes.vertices)?)? {
        return Err(Error::at(Status::NumericalFailure, i as u32));
    }
    Ok((sizes, report))
}

/// The first `n` output positions.
fn pos_of<'a>(out: &'a mut MeshOut<'_>, n: usize) -> Result<&'a mut [Point]> {
    out.positions.get_mut(..n).ok_or(internal())
}

/// The Möbius–linear spectrum at weight `w` (seed 000 §7.2): `pos[i] ← w · pos[i] + (1 − w) ·
/// lin[i]`, with `lin` the linear rule's positions of the same step, written to `scratch`.
/// Plain multiplications and an addition (no FMA), so the result is continuous in `w` and
/// the same on every platform.
fn spectrum_blend(
    scheme: Scheme,
    topo: &Topology<'_, '_>,
    pos: &mut [Point],
    scratch: &mut [Point],
    w: f64,
    exec: &dyn Executor,
) -> Result<()> {
    let lin = scratch.get_mut(..pos.len()).ok_or(internal())?;
    super::step::positions(scheme, topo, lin, exec)?;
    for (p, l) in pos.iter_mut().zip(lin.iter()) {
        *p = point::add(point::scale(*p, w), point::scale(*l, 1.0 - w));
    }
    Ok(())
}
