//! Several levels in one call, with a plan of the exact sizes of every level computed before
//! anything is written.
//!
//! [`plan`] validates the input, then follows a handful of counts from level to level
//! (vertices, faces, corners, edges, boundary edges, isolated vertices, valence sums and
//! maxima): for every pattern these counts of level `k + 1` are exact functions of the counts
//! of level `k` (each pattern's own, in [`crate::mesh::refine`]), so no intermediate level
//! has to be built to know its size. The plan's sizes are checked against what each step
//! really writes.
//!
//! The level loop runs every level through the one-step function of the one-level calls
//! (linear or Möbius), and for the patterns that allow it derives each level's topology from
//! the previous one instead of validating the refined mesh again.
//!
//! Limits: at most [`MAX_LEVELS`] levels; a later level whose valence or face size would
//! exceed the capacity is [`Status::ValenceTooHigh`] (no element: it does not exist yet).

use super::mobius::MobiusOptions;
use super::size::subdivide_size;
use super::step::step;
use super::Scheme;
use crate::error::{Error, Result, Status};
use crate::mesh::refine::{child_topology, derivable, LevelCounts, Pattern};
use crate::mesh::topology::Counts;
use crate::mesh::{
    cadd, internal, topology_scratch_len, Mesh, MeshOut, MeshSizes, Topology, MAX_COUNT,
};
use crate::point::Point;

/// The largest number of levels of one [`subdivide_levels`] call.
pub const MAX_LEVELS: usize = 16;

/// Sizes of every level of a multi-level call and the scratch it needs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LevelPlan {
    /// Number of levels.
    pub levels: usize,
    /// `sizes[0]` is the input, `sizes[k]` level `k` (entries above `levels` are zero).
    pub sizes: [MeshSizes; MAX_LEVELS + 1],
    /// `u32` scratch of [`subdivide_levels`]: the topologies of the input levels plus the
    /// offsets and indices of the intermediate levels (two alternating buffers). The
    /// topology buffer is one (the largest input level) for most patterns; for the patterns
    /// whose child topology is derived from the parent's (Catmull–Clark, Kobbelt, Spherelike,
    /// Loop, Modified Butterfly) two alternate (the two largest input levels: a derivation reads
    /// one while writing the other). With zero levels it is the input's topology: the call
    /// still validates the input ([`plan_scratch_len`]).
    pub scratch_u32: usize,
    /// Point scratch of [`subdivide_levels`]: the positions of the intermediate levels (two
    /// alternating buffers).
    pub scratch_points: usize,
}

impl LevelPlan {
    /// The sizes of the last level (what the caller's output buffers must hold).
    pub fn output(&self) -> MeshSizes {
        self.sizes.get(self.levels).copied().unwrap_or_default()
    }

    /// Point scratch of [`subdivide_levels_mobius`]: [`LevelPlan::scratch_points`] plus the
    /// candidate scratch of one Möbius step ([`super::mobius::scratch_len`]) for the largest
    /// input level.
    ///
    /// # Errors
    /// [`Status::SizeOverflow`].
    pub fn mobius_scratch_points(&self) -> Result<usize> {
        cadd(self.scratch_points, self.mobius_step_points()?)
    }

    /// The candidate scratch of the largest Möbius step (0 for zero levels).
    fn mobius_step_points(&self) -> Result<usize> {
        let mut corners = 0usize;
        for k in 0..self.levels {
            corners = corners.max(self.sizes.get(k).ok_or(internal())?.indices);
        }
        if self.levels == 0 {
            return Ok(0);
        }
        super::mobius::scratch_len_for(corners)
    }
}

/// What the Möbius steps of [`subdivide_levels_mobius`] had to do besides the paper's rules.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LevelsReport {
    /// Output vertices that took their linear rule, summed over all levels.
    pub fallbacks: u32,
    /// The first such vertex of the first level that had one (an index into that level), or
    /// [`crate::NO_ELEMENT`].
    pub first_fallback: u32,
    /// That level (1 for the first step), or 0 when there was no fallback.
    pub first_fallback_level: u32,
}

impl Default for LevelsReport {
    fn default() -> Self {
        LevelsReport {
            fallbacks: 0,
            first_fallback: crate::NO_ELEMENT,
            first_fallback_level: 0,
        }
    }
}

/// Validates `mesh` (topology in `scratch`, [`super::scratch_len`] entries) and plans
/// `levels` steps of `scheme`: the exact sizes of every level and the scratch that
/// [`subdivide_levels`] needs.
///
/// # Errors
/// Validation errors; those of [`subdivide_size`] for the first level;
/// [`Status::InvalidArgument`] for more than [`MAX_LEVELS`] levels; [`Status::SizeOverflow`];
/// [`Status::ValenceTooHigh`] (no element) when a later level would exceed [`crate::MAX_VALENCE`].
pub fn plan(
    scheme: Scheme,
    mesh: Mesh<'_>,
    levels: usize,
    scratch: &mut [u32],
) -> Result<LevelPlan> {
    plan_with_topology(scheme, mesh, levels, scratch).map(|(p, _)| p)
}

/// [`plan`], also returning the counts of the input's topology, which stays in
/// `scratch[..topology_scratch_len(input)]` for the first step of [`run_levels`].
fn plan_with_topology(
    scheme: Scheme,
    mesh: Mesh<'_>,
    levels: usize,
    scratch: &mut [u32],
) -> Result<(LevelPlan, Counts)> {
    if levels > MAX_LEVELS {
        return Err(Error::new(Status::InvalidArgument));
    }
    let topo = Topology::build(mesh, scratch)?;
    let counts = topo.counts();
    let mut stats = LevelCounts::of(&topo)?;
    let mut p = LevelPlan {
        levels,
        sizes: [MeshSizes::default(); MAX_LEVELS + 1],
        scratch_u32: 0,
        scratch_points: 0,
    };
    *p.sizes.get_mut(0).ok_or(internal())? = stats.sizes();
    let pattern = scheme.pattern();
    if levels > 0 {
        // Level 1 exactly as the single step computes it (face types, per-vertex valences).
        let first = subdivide_size(scheme, &topo)?;
        for k in 1..=levels {
            stats = stats.next(pattern)?;
            let sz = stats.sizes();
            if k == 1 && sz != first {
                return Err(internal());
            }
            *p.sizes.get_mut(k).ok_or(internal())? = sz;
        }
    }
    let lay = Layout::of(&p, pattern)?;
    p.scratch_points = cadd(lay.points[0], lay.points[1])?;
    p.scratch_u32 = lay.total_u32()?;
    if p.scratch_u32 > MAX_COUNT.saturating_mul(8) {
        return Err(Error::new(Status::SizeOverflow));
    }
    Ok((p, counts))
}

/// Where [`run_levels`] keeps what it needs, computed from the plan's sizes by [`plan`] (for
/// the sizes it reports) and by [`run_levels`] (for the split), so the two always agree.
///
/// `u32` scratch: `[topology A | topology B | level slot 0 | level slot 1]`. Level `k`'s
/// topology is needed by step `k` (`k < levels`); level 0's is the one [`plan`] built at the
/// start of the scratch (in A). When the pattern's child topology is derived from its parent
/// ([`derivable`]), level `k`'s lives in A for even `k` and in B for odd `k` (a derivation
/// reads the parent while writing the child); otherwise every level is built in A and B is
/// empty. Intermediate level `k` (`1 ≤ k < levels`: offsets, indices, positions) lives in
/// slot `k % 2`. With no levels, A holds the input's topology (the validation).
#[derive(Clone, Copy, Debug)]
struct Layout {
    topo: [usize; 2],
    levels_u32: [usize; 2],
    points: [usize; 2],
}

impl Layout {
    fn of(p: &LevelPlan, pattern: Pattern) -> Result<Layout> {
        let two = derivable(pattern);
        let mut l = Layout {
            topo: [0; 2],
            levels_u32: [0; 2],
            points: [0; 2],
        };
        for k in 0..p.levels.max(1) {
            let sz = p.sizes.get(k).copied().ok_or(internal())?;
            let t = l
                .topo
                .get_mut(if two { k % 2 } else { 0 })
                .ok_or(internal())?;
            *t = (*t).max(topology_scratch_len(sz.vertices, sz.indices)?);
            if k >= 1 {
                let slot = k % 2;
                let pts = l.points.get_mut(slot).ok_or(internal())?;
                *pts = (*pts).max(sz.vertices);
                let u = l.levels_u32.get_mut(slot).ok_or(internal())?;
                *u = (*u).max(cadd(sz.offsets()?, sz.indices)?);
            }
        }
        Ok(l)
    }

    fn total_u32(&self) -> Result<usize> {
        cadd(
            cadd(self.topo[0], self.topo[1])?,
            cadd(self.levels_u32[0], self.levels_u32[1])?,
        )
    }
}

/// The `u32` scratch that [`plan`] needs (the input topology).
///
/// # Errors
/// [`Status::SizeOverflow`].
pub fn plan_scratch_len(mesh: &Mesh<'_>) -> Result<usize> {
    super::scratch_len(mesh)
}

/// Runs `levels` steps of `scheme` on `mesh`, intermediate levels in caller scratch
/// (`scratch_u32` ≥ [`LevelPlan::scratch_u32`], `scratch_points` ≥
/// [`LevelPlan::scratch_points`]), the last level in `out` (≥ [`LevelPlan::output`]). Level 0
/// copies the input. Returns the output sizes.
///
/// # Errors
/// Those of [`plan`] and [`super::subdivide`]; [`Status::BufferTooSmall`] with the needed
/// size.
pub fn subdivide_levels(
    scheme: Scheme,
    mesh: Mesh<'_>,
    levels: usize,
    scratch_u32: &mut [u32],
    scratch_points: &mut [Point],
    out: &mut MeshOut<'_>,
) -> Result<MeshSizes> {
    run_levels(scheme, None, mesh, levels, scratch_u32, scratch_points, out).map(|(s, _)| s)
}

/// [`subdivide_levels`] with the canonical Möbius version of `scheme`
/// ([`super::mobius::subdivide`]) at every level: `scratch_points` must hold
/// [`LevelPlan::mobius_scratch_points`]. Returns the output sizes and the fallbacks of all
/// levels. With [`MobiusOptions::strict`] a fallback is an error naming the output vertex
/// of the level being computed.
///
/// # Errors
/// Those of [`plan`] and [`super::mobius::subdivide`]; [`Status::BufferTooSmall`] with the
/// needed size.
pub fn subdivide_levels_mobius(
    scheme: Scheme,
    mesh: Mesh<'_>,
    levels: usize,
    scratch_u32: &mut [u32],
    scratch_points: &mut [Point],
    out: &mut MeshOut<'_>,
    opts: MobiusOptions,
) -> Result<(MeshSizes, LevelsReport)> {
    run_levels(
        scheme,
        Some(opts),
        mesh,
        levels,
        scratch_u32,
        scratch_points,
        out,
    )
}

/// The level loop shared by [`subdivide_levels`] (`mobius` `None`) and
/// [`subdivide_levels_mobius`]: every level is one [`step`]; with `mobius`, the candidate
/// scratch of the largest step ([`LevelPlan::mobius_step_points`], after the intermediate
/// levels) is handed to every step and the steps' reports are gathered.
fn run_levels(
    scheme: Scheme,
    mobius: Option<MobiusOptions>,
    mesh: Mesh<'_>,
    levels: usize,
    scratch_u32: &mut [u32],
    scratch_points: &mut [Point],
    out: &mut MeshOut<'_>,
) -> Result<(MeshSizes, LevelsReport)> {
    let mut report = LevelsReport::default();
    let need_plan = plan_scratch_len(&mesh)?;
    if scratch_u32.len() < need_plan {
        return Err(Error::too_small(need_plan));
    }
    let (p, input_counts) = plan_with_topology(scheme, mesh, levels, scratch_u32)?;
    let final_sizes = p.output();
    out.check(&final_sizes)?;
    if scratch_u32.len() < p.scratch_u32 {
        return Err(Error::too_small(p.scratch_u32));
    }
    let extra = match mobius {
        Some(_) => p.mobius_step_points()?,
        None => 0,
    };
    let need_points = cadd(p.scratch_points, extra)?;
    if scratch_points.len() < need_points {
        return Err(Error::too_small(need_points));
    }
    if levels == 0 {
        copy_mesh(mesh, out)?;
        return Ok((final_sizes, report));
    }
    let pattern = scheme.pattern();
    let derive = derivable(pattern);
    let lay = Layout::of(&p, pattern)?;
    let (t_a, rest) = scratch_u32
        .split_at_mut_checked(lay.topo[0])
        .ok_or(internal())?;
    let (t_b, rest) = rest.split_at_mut_checked(lay.topo[1]).ok_or(internal())?;
    let (u_a, rest) = rest
        .split_at_mut_checked(lay.levels_u32[0])
        .ok_or(internal())?;
    let (u_b, _) = rest
        .split_at_mut_checked(lay.levels_u32[1])
        .ok_or(internal())?;
    let (p_a, rest) = scratch_points
        .split_at_mut_checked(lay.points[0])
        .ok_or(internal())?;
    let (p_b, rest) = rest.split_at_mut_checked(lay.points[1]).ok_or(internal())?;
    let step_scratch = rest.get_mut(..extra).ok_or(internal())?;
    // Slot 0 holds even levels, slot 1 odd levels; topology A even (or all), B odd.
    let mut bufs_t: [&mut [u32]; 2] = [t_a, t_b];
    let mut bufs_u: [&mut [u32]; 2] = [u_a, u_b];
    let mut bufs_p: [&mut [Point]; 2] = [p_a, p_b];
    // The counts of level k's topology when it is already in its buffer (level 0: built by
    // the plan; later levels: derived by the previous step).
    let mut ready = Some(input_counts);
    for k in 0..levels {
        let out_sizes = p.sizes.get(k + 1).copied().ok_or(internal())?;
        let [ua, ub] = &mut bufs_u;
        let [pa, pb] = &mut bufs_p;
        let [ta, tb] = &mut bufs_t;
        // Input of step k: the mesh (k = 0) or level k in slot k % 2; output: level k + 1
        // in the other slot, or `out` for the last step.
        let (in_u, out_u, in_p, out_p): (&[u32], &mut [u32], &[Point], &mut [Point]) = if k % 2 == 0
        {
            (&**ua, &mut **ub, &**pa, &mut **pb)
        } else {
            (&**ub, &mut **ua, &**pb, &mut **pa)
        };
        let (in_t, out_t): (&mut [u32], &mut [u32]) = if derive && k % 2 == 1 {
            (&mut **tb, &mut **ta)
        } else {
            (&mut **ta, &mut **tb)
        };
        let input = if k == 0 {
            mesh
        } else {
            let sz = p.sizes.get(k).copied().ok_or(internal())?;
            let no = sz.offsets()?;
            let offs = in_u.get(..no).ok_or(internal())?;
            let idx = in_u.get(no..no + sz.indices).ok_or(internal())?;
            Mesh::new(in_p.get(..sz.vertices).ok_or(internal())?, offs, idx)
        };
        let topo = match ready.take() {
            Some(c) => Topology::from_parts(input, in_t, c)?,
            None => Topology::build(input, in_t)?,
        };
        let (written, r) = if k + 1 == levels {
            step(scheme, mobius, &topo, out, step_scratch)?
        } else {
            let no = out_sizes.offsets()?;
            let (o, rest) = out_u.split_at_mut_checked(no).ok_or(internal())?;
            let mut step_out = MeshOut::new(&mut *out_p, o, rest);
            step(scheme, mobius, &topo, &mut step_out, step_scratch)?
        };
        report.fallbacks = report.fallbacks.saturating_add(r.fallbacks);
        if report.first_fallback_level == 0 && r.fallbacks > 0 {
            report.first_fallback = r.first_fallback;
            report.first_fallback_level = (k + 1) as u32;
        }
        if written != out_sizes {
            return Err(internal());
        }
        if derive && k + 1 < levels {
            // Level k + 1 as the step wrote it, and its topology derived from level k's.
            let no = out_sizes.offsets()?;
            let out_u: &[u32] = out_u;
            let offs = out_u.get(..no).ok_or(internal())?;
            let idx = out_u.get(no..no + out_sizes.indices).ok_or(internal())?;
            let pts: &[Point] = out_p;
            let child = Mesh::new(pts.get(..out_sizes.vertices).ok_or(internal())?, offs, idx);
            ready = Some(child_topology(&topo, pattern, child, out_t)?.counts());
        }
    }
    Ok((final_sizes, report))
}

fn copy_mesh(mesh: Mesh<'_>, out: &mut MeshOut<'_>) -> Result<()> {
    for (d, s) in out.positions.iter_mut().zip(mesh.positions()) {
        *d = s;
    }
    for (d, s) in out.offsets.iter_mut().zip(mesh.offsets) {
        *d = *s;
    }
    for (d, s) in out.indices.iter_mut().zip(mesh.indices) {
        *d = *s;
    }
    Ok(())
}
