//! Planning a mesh subdivision: validation of the mesh and the options, the exact sizes of
//! every level and the exact scratch of [`super::subdivide`], all before any point is
//! computed, so that a caller allocates once (the crate allocates nothing).
//!
//! [`plan`] builds the input's topology (the validation), then follows a handful of counts
//! from level to level (vertices, faces, corners, edges, boundary edges, isolated vertices,
//! valence sums and maxima): for every pattern these counts of level `k + 1` are exact
//! functions of the counts of level `k` (each pattern's own, in [`crate::mesh::refine`]), so
//! no intermediate level has to be built to know its size. The level loop checks every
//! planned size against what the step really writes.

use super::levels::Layout;
use super::size::step_size;
use super::tags::{self, Tags};
use super::weights::VertexWeights;
use super::{Options, Scheme, MAX_LEVELS};
use crate::error::{Error, Result, Status};
use crate::mesh::refine::LevelCounts;
use crate::mesh::topology::Counts;
use crate::mesh::{
    cadd, cmul, internal, topology_scratch_size, Mesh, MeshSizes, Topology, MAX_COUNT,
};

/// Scratch sizes, each counted in elements of the buffer it sizes: `u32` entries and points
/// (`[f64; 3]`, 24 bytes each).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ScratchSizes {
    /// Entries of the `u32` scratch ([`Scratch::u32s`](super::Scratch::u32s)).
    pub u32s: usize,
    /// Points of the point scratch ([`Scratch::points`](super::Scratch::points)).
    pub points: usize,
}

/// The exact sizes of every level of a [`subdivide`](super::subdivide) call and the exact
/// scratch it needs, from [`plan`].
#[non_exhaustive]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Plan {
    /// Number of levels.
    pub levels: usize,
    /// `sizes[0]` is the input, `sizes[k]` level `k`; entries above `levels` are zero.
    pub sizes: [MeshSizes; MAX_LEVELS + 1],
    /// Exactly the scratch [`subdivide`](super::subdivide) needs for these options (a
    /// shorter buffer is [`Status::BufferTooSmall`]):
    ///
    /// * `u32s`: the topologies of the levels that are stepped from, plus the offsets and
    ///   indices of the intermediate levels (two alternating buffers). The topology buffer
    ///   is one (the largest level stepped from) for most patterns; for those whose child
    ///   topology is derived from the parent's (Catmull–Clark, Kobbelt, Spherelike, Loop,
    ///   Modified Butterfly) two alternate (a derivation reads one while writing the other).
    ///   Never less than [`plan_scratch_size`]: with zero levels it is the input's topology,
    ///   since the call still validates the input.
    ///   With sharp-feature tags ([`plan_tagged`]) two more alternating buffers of one
    ///   value per edge and per vertex of the largest level stepped from (the sharpness of
    ///   the level stepped from and of its child), and at least
    ///   [`plan_scratch_size_tagged`]; with tags and [`Options::mobius`], the scratch of the
    ///   largest step on a level cut along its sharp edges (its cut flags, vertex copies,
    ///   indices, topology and the child's connectivity). With [`Options::mobius`], at
    ///   least the spoke workspace of the vertex pass (four entries per spoke of the largest
    ///   valence stepped from, one more with tags, for each of at most
    ///   `min(`[`crate::exec::MAX_CHUNKS`]`, vertices)` chunks: a star's spokes, kept off the
    ///   stack).
    /// * `points`: the positions of the intermediate levels (two alternating buffers) and,
    ///   for the Möbius version, the candidates of the largest step (two per corner of the
    ///   level stepped from: an edge and a face candidate per half-edge, seed 000 §4.1) and,
    ///   per vertex, the centre of its canonical form (one point) and the fold guard's trust
    ///   and the form's radius (two `f64`), and per corner the slot of its candidates (one
    ///   `f64`; `f64` values three to a point), and the star workspace of the vertex pass
    ///   (for each of at most `min(`[`crate::exec::MAX_CHUNKS`]`, max(vertices, faces))`
    ///   chunks, four arrays of the largest valence stepped from — the tangent polygon of
    ///   the star's canonical form and the per-star arrays of the scheme's rule — or the F4
    ///   points and sort keys of the largest face's face-point chain if that is more; kept
    ///   off the stack) — with tags, at least the cut
    ///   level's positions, its step's output and candidates; with a
    ///   spectrum weight below 1 ([`Options::spectrum`]) or per-vertex weights
    ///   ([`plan_weighted`]), the linear positions of the largest level written; with
    ///   per-vertex weights also two buffers of one weight per vertex of the largest level
    ///   written (three weights to a point).
    pub scratch: ScratchSizes,
    /// `u32` entries of one of the two sharpness buffers of a tagged mesh (one value per
    /// edge and per vertex of the largest level stepped from); 0 without tags.
    pub(super) sharpness: usize,
    /// The scratch of the largest tagged Möbius step (the level cut along its sharp edges,
    /// [`super::mobius::crease::scratch`]); zero without tags or without Möbius.
    pub(super) crease: ScratchSizes,
    /// The largest valence of the levels stepped from (a bound from the refinement rule
    /// for the derived levels), which sizes the Möbius star workspace
    /// ([`super::mobius::workspace`]).
    pub(super) star_valence: usize,
    /// The largest face of the levels stepped from, which sizes the face-point chain's
    /// arrays in the Möbius star workspace.
    pub(super) star_face: usize,
    /// The `u32` scratch of the largest Möbius step: its spoke workspace
    /// ([`super::mobius::workspace::spoke_u32s`]) or, with tags, the cut step's
    /// ([`Plan::crease`]); zero without Möbius.
    pub(super) step_u32s: usize,
}

impl Plan {
    /// The sizes of the last level: what the output buffers must hold.
    pub fn output(&self) -> MeshSizes {
        self.sizes.get(self.levels).copied().unwrap_or_default()
    }

    /// The linear positions a Möbius step blends with for a spectrum weight below 1
    /// ([`Options::spectrum`]): the vertices of the largest level written (0 for zero
    /// levels).
    pub(super) fn spectrum_points(&self) -> Result<usize> {
        let mut vertices = 0usize;
        for k in 1..=self.levels {
            vertices = vertices.max(self.sizes.get(k).ok_or(internal())?.vertices);
        }
        Ok(vertices)
    }

    /// The candidate points of the largest Möbius step: two per corner of the largest level
    /// stepped from and an `f64` per corner for their slots, and per vertex a point and two
    /// `f64` for the fold guard
    /// ([`super::mobius::candidate_points`]; 0 for zero levels), and the star workspace of
    /// the largest valence and face stepped from
    /// ([`super::mobius::workspace::workspace_points`]);
    /// with tags, at least the points of the largest tagged step ([`Plan::crease`]).
    pub(super) fn mobius_step_points(&self) -> Result<usize> {
        if self.levels == 0 {
            return Ok(self.crease.points);
        }
        let (mut vertices, mut corners, mut elements) = (0usize, 0usize, 0usize);
        for k in 0..self.levels {
            let sz = self.sizes.get(k).ok_or(internal())?;
            vertices = vertices.max(sz.vertices);
            corners = corners.max(sz.indices);
            elements = elements.max(sz.vertices.max(sz.faces));
        }
        let (v, f) = (self.star_valence, self.star_face);
        let work = super::mobius::workspace::workspace_points(v, f, elements)?;
        let step = cadd(super::mobius::candidate_points(vertices, corners)?, work)?;
        Ok(step.max(self.crease.points))
    }
}

/// The `u32` scratch entries [`plan`] needs for `mesh`: the input's half-edge topology
/// ([`topology_scratch_size`], `4·corners + 3·vertices`), from the counts alone (nothing
/// is read).
///
/// # Errors
/// [`Status::SizeOverflow`].
pub fn plan_scratch_size(mesh: &Mesh<'_>) -> Result<usize> {
    topology_scratch_size(mesh.num_vertices(), mesh.num_corners())
}

/// The `u32` scratch entries [`plan_tagged`] needs for `mesh` with `tags`: those of
/// [`plan_scratch_size`], plus one per vertex and per corner to find repeated tags when
/// there is a tag.
///
/// # Errors
/// [`Status::SizeOverflow`].
pub fn plan_scratch_size_tagged(mesh: &Mesh<'_>, tags: &Tags<'_>) -> Result<usize> {
    let topo = plan_scratch_size(mesh)?;
    if tags.is_empty() {
        return Ok(topo);
    }
    cadd(
        topo,
        tags::marker_size(mesh.num_vertices(), mesh.num_corners())?,
    )
}

/// [`plan`] for a mesh with sharp-feature tags ([`Tags`]; the rules in
/// [`crate::stencil::crease`]): `scratch_u32` holds at least [`plan_scratch_size_tagged`]
/// entries. Empty tags are [`plan`] exactly.
///
/// # Errors
/// Those of [`plan`], and after [`Options`] are checked: [`Status::TagsNotSupported`] for
/// tags with a scheme that takes none ([`Scheme::takes_tags`]: all but [`Scheme::Loop`],
/// [`Scheme::CatmullClark`], [`Scheme::ModifiedButterfly`] and [`Scheme::Kobbelt`], linear
/// or Möbius); after the mesh is validated, the tag errors ([`Tags`]: a length
/// mismatch is [`Status::InvalidArgument`]; [`Status::IndexOutOfRange`],
/// [`Status::InvalidSharpness`], [`Status::TagNotAnEdge`], [`Status::RepeatedTag`] naming
/// the tag).
pub fn plan_tagged(
    mesh: Mesh<'_>,
    opts: &Options,
    tags: &Tags<'_>,
    scratch_u32: &mut [u32],
) -> Result<Plan> {
    plan_with_topology(mesh, opts, tags, None, scratch_u32).map(|(p, _)| p)
}

/// [`plan_tagged`] with per-vertex weights of the Möbius–linear spectrum (seed 000 §7.2),
/// the plan of [`subdivide_weighted`](super::subdivide_weighted) with the same arguments:
/// `weights` holds a weight at every input vertex ([`VertexWeights`]; they replace
/// [`Options::spectrum`]), `None` is [`plan_tagged`] exactly. With
/// [`Options::mobius`] the point scratch also holds the linear positions of the largest
/// level written and two buffers of the weights of the largest level written (three
/// weights to a point). Checked, and without effect, for the linear schemes.
///
/// # Errors
/// Those of [`plan_tagged`]; after [`Options`] (and before the mesh is validated):
/// [`Status::InvalidArgument`] for weights that are not one per vertex (no element) or a
/// weight that is NaN or outside `[0, 1]` (naming the first such vertex).
pub fn plan_weighted(
    mesh: Mesh<'_>,
    opts: &Options,
    tags: &Tags<'_>,
    weights: Option<VertexWeights<'_>>,
    scratch_u32: &mut [u32],
) -> Result<Plan> {
    plan_with_topology(mesh, opts, tags, weights, scratch_u32).map(|(p, _)| p)
}

/// Validates `mesh` and `opts` and returns the exact sizes of every level and the exact
/// scratch of [`subdivide`](super::subdivide) with the same arguments. `scratch_u32` holds
/// at least [`plan_scratch_size`] entries; its contents are unspecified afterwards.
///
/// # Errors
/// In this order: [`Status::InvalidArgument`] for more than [`MAX_LEVELS`] levels or
/// [`Options::mobius`] with a scheme without a Möbius form; [`Status::BufferTooSmall`] (with
/// the needed size) when `scratch_u32` is below [`plan_scratch_size`]; the validation errors
/// of [`Topology::build`] (naming the face or vertex); for one or more levels, the scheme's
/// own refusals of the input ([`Status::UnsupportedFaceType`] naming the face: Loop and
/// Modified Butterfly accept triangles, Kobbelt quads; those of
/// [`crate::mesh::refine::pattern_size`]); [`Status::SizeOverflow`] when a level has more
/// than [`MAX_COUNT`] vertices, faces or corners; [`Status::ValenceTooHigh`] (no element:
/// the vertex does not exist yet) when a later level would exceed [`crate::MAX_VALENCE`] or
/// [`crate::MAX_FACE_SIZE`]; for [`Scheme::Spherelike`], [`Status::NumericalFailure`] for a
/// mesh outside the sizes its squared distances can represent
/// ([`crate::mesh::check_extent`]).
pub fn plan(mesh: Mesh<'_>, opts: &Options, scratch_u32: &mut [u32]) -> Result<Plan> {
    plan_with_topology(mesh, opts, &Tags::new(), None, scratch_u32).map(|(p, _)| p)
}

/// [`plan`], also returning the counts of the input's topology, which stays in
/// `scratch_u32[..plan_scratch_size(mesh)]` for the first step of the level loop.
pub(super) fn plan_with_topology(
    mesh: Mesh<'_>,
    opts: &Options,
    tags: &Tags<'_>,
    weights: Option<VertexWeights<'_>>,
    scratch_u32: &mut [u32],
) -> Result<(Plan, Counts)> {
    opts.check()?;
    let tagged = !tags.is_empty();
    if tagged && !opts.scheme.takes_tags() {
        return Err(Error::new(Status::TagsNotSupported));
    }
    super::weights::check(weights, mesh.num_vertices())?;
    let weighted = opts.mobius && weights.is_some();
    let need = plan_scratch_size_tagged(&mesh, tags)?;
    if scratch_u32.len() < need {
        return Err(Error::too_small(need));
    }
    let (mut p, counts) = levels_plan(
        super::built::narrow(opts.scheme)?,
        opts.mobius,
        mesh,
        opts.levels,
        scratch_u32,
        tagged.then_some(tags),
    )?;
    // The plan's own scratch (topology and tag markers) is also the start of the call's.
    p.scratch.u32s = p.scratch.u32s.max(need);
    if opts.mobius && (opts.spectrum < 1.0 || weighted) {
        p.scratch.points = cadd(p.scratch.points, p.spectrum_points()?)?;
    }
    if weighted {
        let w = super::weights::points_for(p.spectrum_points()?);
        p.scratch.points = cadd(p.scratch.points, cmul(w, 2)?)?;
    }
    // The circle blend measures squared distances: outside this range they underflow or
    // overflow and the shape is lost (mesh/extent.rs).
    if opts.scheme == Scheme::Spherelike && opts.levels > 0 {
        crate::mesh::check_extent(&mesh)?;
    }
    Ok((p, counts))
}

/// The plan of `levels` linear levels of `scheme`, validating `mesh` into `scratch`: the
/// sizes of differential-space subdivision (seed 001), which steps its fields with the
/// linear rules.
pub(crate) fn plan_levels(
    scheme: Scheme,
    mesh: Mesh<'_>,
    levels: usize,
    scratch: &mut [u32],
) -> Result<Plan> {
    let scheme = super::built::narrow(scheme)?;
    levels_plan(scheme, false, mesh, levels, scratch, None).map(|(p, _)| p)
}

/// The plan of `levels` levels of `scheme` (linear, or Möbius with `mobius`), validating
/// `mesh` into `scratch` (the options are checked by the callers), and `tags` if any (their
/// repeats found with the scratch after the topology).
fn levels_plan(
    scheme: Scheme,
    mobius: bool,
    mesh: Mesh<'_>,
    levels: usize,
    scratch: &mut [u32],
    tags: Option<&Tags<'_>>,
) -> Result<(Plan, Counts)> {
    if levels > MAX_LEVELS {
        return Err(Error::new(Status::InvalidArgument));
    }
    // A short scratch is the topology's to report (with the size it needs).
    let cut = plan_scratch_size(&mesh)?.min(scratch.len());
    let (scratch, marker) = scratch.split_at_mut_checked(cut).ok_or(internal())?;
    let topo = Topology::build(mesh, scratch)?;
    if let Some(t) = tags {
        tags::apply(t, &topo, marker, |_, _| Ok(()), |_, _| Ok(()))?;
    }
    let counts = topo.counts();
    let mut stats = LevelCounts::of(&topo)?;
    let mut p = Plan {
        levels,
        sizes: [MeshSizes::default(); MAX_LEVELS + 1],
        scratch: ScratchSizes::default(),
        sharpness: 0,
        crease: ScratchSizes::default(),
        star_valence: 0,
        star_face: 0,
        step_u32s: 0,
    };
    // One sharpness value per edge and vertex of the largest level stepped from.
    let mut sharpness = cadd(stats.edges(), stats.sizes().vertices)?;
    *p.sizes.get_mut(0).ok_or(internal())? = stats.sizes();
    let pattern = scheme.pattern();
    if levels > 0 {
        // Level 1 exactly as the single step computes it (face types, per-vertex valences).
        let first = step_size(scheme, &topo)?;
        p.star_valence = stats.max_valence();
        p.star_face = stats.max_face();
        for k in 1..=levels {
            stats = stats.next(pattern)?;
            let sz = stats.sizes();
            if k < levels {
                sharpness = sharpness.max(cadd(stats.edges(), sz.vertices)?);
                p.star_valence = p.star_valence.max(stats.max_valence());
                p.star_face = p.star_face.max(stats.max_face());
            }
            if k == 1 && sz != first {
                return Err(internal());
            }
            *p.sizes.get_mut(k).ok_or(internal())? = sz;
        }
    }
    let lay = Layout::of(&p, pattern)?;
    p.sharpness = if tags.is_some() && levels > 0 {
        sharpness
    } else {
        0
    };
    if mobius && p.sharpness > 0 {
        for k in 0..levels {
            let sz = p.sizes.get(k).copied().ok_or(internal())?;
            let next = p.sizes.get(k + 1).copied().ok_or(internal())?;
            let (v, c, f) = (sz.vertices, sz.indices, sz.faces);
            let c = super::mobius::crease::scratch(v, c, f, next, p.star_valence, p.star_face)?;
            p.crease.u32s = p.crease.u32s.max(c.u32s);
            p.crease.points = p.crease.points.max(c.points);
        }
    }
    if mobius && levels > 0 {
        let mut vertices = 0;
        for k in 0..levels {
            vertices = vertices.max(p.sizes.get(k).ok_or(internal())?.vertices);
        }
        let spokes = super::mobius::workspace::spoke_u32s(p.star_valence, vertices)?;
        p.step_u32s = spokes.max(p.crease.u32s);
    }
    let candidates = if mobius { p.mobius_step_points()? } else { 0 };
    p.scratch = ScratchSizes {
        u32s: cadd(cadd(lay.total_u32()?, cmul(p.sharpness, 2)?)?, p.step_u32s)?,
        points: cadd(cadd(lay.points[0], lay.points[1])?, candidates)?,
    };
    if p.scratch.u32s > MAX_COUNT.saturating_mul(8) {
        return Err(Error::new(Status::SizeOverflow));
    }
    Ok((p, counts))
}
