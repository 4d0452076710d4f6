//! The level loop of [`super::subdivide`]: every level is one step ([`super::step`], linear,
//! spherelike or Möbius) from the previous level, the intermediate levels in caller scratch,
//! the last one in the caller's output. For the patterns that allow it, each level's topology
//! is derived from the previous one ([`crate::mesh::refine`]) instead of validating the
//! refined mesh again.
//!
//! Limits: at most [`MAX_LEVELS`] levels; a later level whose valence or face size would
//! exceed the capacity is [`Status::ValenceTooHigh`] (no element: it does not exist yet),
//! found by the plan ([`super::plan`]) before anything is written.

use super::mobius::MobiusOptions;
use super::plan::{plan_with_topology, Plan};
use super::step::{step, step_weighted};
use super::tags::{self, Sharpness, Tags};
use super::weights::{self, VertexWeights};
use super::{Options, Report, Scratch};
#[cfg(doc)]
use crate::error::Status;
use crate::error::{Error, Result};
use crate::exec::Executor;
use crate::mesh::refine::{child_topology, derivable, Pattern};
use crate::mesh::topology::Counts;
use crate::mesh::{cadd, internal, topology_scratch_size, Mesh, MeshOut, Topology};
use crate::point::Point;

/// The largest number of levels of one [`subdivide`](super::subdivide) call.
pub const MAX_LEVELS: usize = 16;

/// Where [`run`] keeps what it needs, computed from the plan's sizes by [`super::plan`] (for
/// the sizes it reports) and by [`run`] (for the split), so the two always agree.
///
/// `u32` scratch: `[topology A | topology B | level slot 0 | level slot 1]`. Level `k`'s
/// topology is needed by step `k` (`k < levels`); level 0's is the one the plan built at the
/// start of the scratch (in A). When the pattern's child topology is derived from its parent
/// ([`derivable`]), level `k`'s lives in A for even `k` and in B for odd `k` (a derivation
/// reads the parent while writing the child); otherwise every level is built in A and B is
/// empty. Intermediate level `k` (`1 ≤ k < levels`: offsets, indices, positions) lives in
/// slot `k % 2`. With no levels, A holds the input's topology (the validation).
#[derive(Clone, Copy, Debug)]
pub(super) struct Layout {
    topo: [usize; 2],
    levels_u32: [usize; 2],
    pub(super) points: [usize; 2],
}

impl Layout {
    pub(super) fn of(p: &Plan, pattern: Pattern) -> Result<Layout> {
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
            *t = (*t).max(topology_scratch_size(sz.vertices, sz.indices)?);
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

    pub(super) fn total_u32(&self) -> Result<usize> {
        cadd(
            cadd(self.topo[0], self.topo[1])?,
            cadd(self.levels_u32[0], self.levels_u32[1])?,
        )
    }
}

/// The work of [`super::subdivide`]: the plan (validation, sizes), the buffer checks, then
/// every level as one [`step`] into the scratch or, for the last, into `out`. With
/// [`Options::mobius`], the candidate scratch of the largest step (after the intermediate
/// levels) is handed to every step and the steps' fallbacks are gathered. With `tags`, the
/// sharpness values of the level stepped from and of the next alternate in two buffers after
/// the levels' `u32` scratch ([`tags`]). With per-vertex spectrum `weights` and
/// [`Options::mobius`], the weights of each level written alternate in two buffers after the
/// step scratch ([`weights`]: level `k + 1`'s carried from level `k`'s before step `k`,
/// which blends with them).
#[allow(clippy::too_many_arguments)]
pub(super) fn run(
    mesh: Mesh<'_>,
    opts: &Options,
    tags: &Tags<'_>,
    weights: Option<VertexWeights<'_>>,
    scratch: Scratch<'_>,
    out: &mut MeshOut<'_>,
    exec: &dyn Executor,
) -> Result<Report> {
    let Scratch {
        u32s: scratch_u32,
        points: scratch_points,
    } = scratch;
    // The plan read in place in the returned `Result` (moving it out would keep a second copy
    // of its level sizes in this frame, below which every level runs: docs/firmware.md).
    let planned = plan_with_topology(mesh, opts, tags, weights, scratch_u32);
    let (p, input_counts): (&Plan, _) = match &planned {
        Ok((p, counts)) => (p, *counts),
        Err(e) => return Err(*e),
    };
    let final_sizes = p.output();
    let mut report = Report::empty(final_sizes);
    out.check(&final_sizes)?;
    if scratch_u32.len() < p.scratch.u32s {
        return Err(Error::too_small(p.scratch.u32s));
    }
    if scratch_points.len() < p.scratch.points {
        return Err(Error::too_small(p.scratch.points));
    }
    // The scheme as this build knows it (a constant in a build of one scheme).
    let (scheme, levels) = (super::built::narrow(opts.scheme)?, opts.levels);
    // A spectrum weight of 0 is the linear scheme (bit for bit: its steps are the linear
    // ones); between 0 and 1 each Möbius step blends with the linear positions.
    // Per-vertex weights (Möbius only) replace the global one: each step then sees its
    // level's weights (`step_weighted`).
    let weights = weights.filter(|_| opts.mobius);
    let mobius =
        (opts.mobius && (opts.spectrum > 0.0 || weights.is_some())).then_some(MobiusOptions {
            strict: opts.strict,
            guard: !opts.literal,
            spectrum: if weights.is_some() {
                1.0
            } else {
                opts.spectrum
            },
        });
    let extra = match mobius {
        Some(_) if opts.spectrum < 1.0 || weights.is_some() => {
            cadd(p.mobius_step_points()?, p.spectrum_points()?)?
        }
        Some(_) => p.mobius_step_points()?,
        None => 0,
    };
    let weight_points = match weights {
        Some(_) => weights::points_for(p.spectrum_points()?),
        None => 0,
    };
    if levels == 0 {
        copy_mesh(mesh, out)?;
        return Ok(report);
    }
    let pattern = scheme.pattern();
    let derive = derivable(pattern);
    let lay = Layout::of(p, pattern)?;
    let (t_a, rest) = scratch_u32
        .split_at_mut_checked(lay.topo[0])
        .ok_or(internal())?;
    let (t_b, rest) = rest.split_at_mut_checked(lay.topo[1]).ok_or(internal())?;
    let (u_a, rest) = rest
        .split_at_mut_checked(lay.levels_u32[0])
        .ok_or(internal())?;
    let (u_b, rest) = rest
        .split_at_mut_checked(lay.levels_u32[1])
        .ok_or(internal())?;
    let (s_a, rest) = rest.split_at_mut_checked(p.sharpness).ok_or(internal())?;
    let (s_b, rest) = rest.split_at_mut_checked(p.sharpness).ok_or(internal())?;
    let step_u32s = rest.get_mut(..p.step_u32s).ok_or(internal())?;
    let mut bufs_s: [&mut [u32]; 2] = [s_a, s_b];
    let tagged = p.sharpness > 0;
    let (p_a, rest) = scratch_points
        .split_at_mut_checked(lay.points[0])
        .ok_or(internal())?;
    let (p_b, rest) = rest.split_at_mut_checked(lay.points[1]).ok_or(internal())?;
    let (step_scratch, rest) = rest.split_at_mut_checked(extra).ok_or(internal())?;
    let (w_a, rest) = rest.split_at_mut_checked(weight_points).ok_or(internal())?;
    let w_b = rest.get_mut(..weight_points).ok_or(internal())?;
    let mut bufs_w: [&mut [f64]; 2] = [w_a.as_flattened_mut(), w_b.as_flattened_mut()];
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
        // Sharpness of level k in buffer k % 2, of level k + 1 in the other.
        let [sa, sb] = &mut bufs_s;
        let (in_s, out_s): (&mut [u32], &mut [u32]) = if k % 2 == 0 {
            (&mut **sa, &mut **sb)
        } else {
            (&mut **sb, &mut **sa)
        };
        if tagged && k == 0 {
            tags::initial(tags, &topo, in_s)?;
        }
        let (ne, nv) = (topo.num_edges(), topo.num_vertices());
        let in_s: &[u32] = in_s;
        let sharp = Sharpness {
            edges: in_s.get(..ne).unwrap_or(&[]),
            vertices: in_s.get(ne..ne + nv).unwrap_or(&[]),
            method: tags.method,
            whole: false,
        };
        let sharp = tagged.then_some(&sharp);
        // Weights of level k + 1 in buffer k % 2, carried from level k's (the caller's for
        // k = 0, else the other buffer).
        let [wa, wb] = &mut bufs_w;
        let (w_in, w_out): (&[f64], &mut [f64]) = match (k, weights) {
            (0, Some(w)) => (w.values(), &mut **wa),
            (_, _) if k % 2 == 0 => (&**wb, &mut **wa),
            _ => (&**wa, &mut **wb),
        };
        let mut one = |o: &mut MeshOut<'_>| match (mobius, weights) {
            (Some(m), Some(given)) => {
                weights::carry(scheme, &topo, w_in, w_out)?;
                let w: &[f64] = w_out;
                let w = w.get(..out_sizes.vertices).ok_or(internal())?;
                let w = (w, given.of_linear());
                step_weighted(scheme, m, w, sharp, &topo, o, step_scratch, step_u32s, exec)
            }
            _ => step(
                scheme,
                mobius,
                sharp,
                &topo,
                o,
                step_scratch,
                step_u32s,
                exec,
            ),
        };
        let (written, r) = if k + 1 == levels {
            one(out)?
        } else {
            let no = out_sizes.offsets()?;
            let (o, rest) = out_u.split_at_mut_checked(no).ok_or(internal())?;
            let mut step_out = MeshOut::new(&mut *out_p, o, rest);
            one(&mut step_out)?
        };
        report.fallbacks = report.fallbacks.saturating_add(r.fallbacks);
        if report.first_fallback_level == 0 && r.fallbacks > 0 {
            report.first_fallback = r.first_fallback;
            report.first_fallback_level = (k + 1) as u32;
        }
        report.guarded = report.guarded.saturating_add(r.guarded);
        if report.first_guarded_level == 0 && r.guarded > 0 {
            report.first_guarded = r.first_guarded;
            report.first_guarded_level = (k + 1) as u32;
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
            ready = Some(derive_child(
                &topo,
                pattern,
                child,
                out_t,
                (sharp, out_s),
                exec,
            )?);
        }
    }
    Ok(report)
}

/// The topology of level `k + 1` (`child`, as the step wrote it) derived from level `k`'s
/// (`topo`) into `out_t`, with the sharpness of its edges and vertices carried into `out_s`
/// when the level is tagged; its counts. Out of line: its topologies are not in the frame of
/// [`run`], below which every step runs (`docs/firmware.md`, "Stack").
#[inline(never)]
fn derive_child(
    topo: &Topology<'_, '_>,
    pattern: Pattern,
    child: Mesh<'_>,
    out_t: &mut [u32],
    (sharp, out_s): (Option<&Sharpness<'_>>, &mut [u32]),
    exec: &dyn Executor,
) -> Result<Counts> {
    let child = child_topology(topo, pattern, child, out_t, exec)?;
    if let Some(sh) = sharp {
        tags::carry(topo, sh, &child, out_s)?;
    }
    Ok(child.counts())
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
