//! The differential-space subdivision driver (seed 001 §3.5): the three steps of the
//! [module documentation](super) on caller buffers.
//!
//! [`subdivide`] carves its two scratch arrays into named buffers ([`U32Buffers`],
//! [`PointBuffers`], [`Fields`]) and then runs, in order: [`level_zero`] (`Δ⁰`, its edits, the
//! anchors), [`subdivide_fields`] (levels `1..k` of `Δ` and of the spatial warm start),
//! [`build_hierarchy`] (the Laplacians and edges of every level, for the multigrid solve),
//! [`scaled_delta`] (`δ = 4⁻ᵏ Δᵏ`), the solve, and the placement.

use arrayvec::ArrayVec;

use super::laplacian::{self, Laplacian};
use super::options::{DifferentialOptions, DifferentialReport};
use super::placement::{self, Anchors};
use super::plan::{plan, plan_scratch_len, DifferentialPlan, Layout};
use super::solve::{self, SolveLevel, System};
use super::{dirmag, edit};
use crate::error::{Error, Result, Status};
use crate::mesh::{cadd, cmul, get, internal, set, Mesh, MeshOut, MeshSizes, Topology};
use crate::point::Point;
use crate::scheme::{Scheme, MAX_LEVELS};

/// Differential-space subdivision of `mesh` (see the [module docs](super)) into `out`
/// (≥ [`DifferentialPlan::output`]); `scratch_u32` and `scratch_points` hold at least the
/// plan's sizes. `report` is written on success and on [`Status::NotConverged`].
///
/// # Errors
/// Those of [`plan`]; [`Status::BufferTooSmall`] (needed size) for a short output or scratch;
/// [`Status::NotConverged`] when the solver stops at
/// [`SolveOptions::max_iterations`](super::solve::SolveOptions::max_iterations);
/// [`Status::NumericalFailure`] on overflow.
pub fn subdivide(
    mesh: Mesh<'_>,
    opts: &DifferentialOptions<'_>,
    scratch_u32: &mut [u32],
    scratch_points: &mut [Point],
    out: &mut MeshOut<'_>,
    report: &mut DifferentialReport,
) -> Result<MeshSizes> {
    let plan = {
        let need = plan_scratch_len(&mesh)?;
        let s = scratch_u32.get_mut(..need).ok_or(Error::too_small(need))?;
        plan(mesh, opts, s)?
    };
    let lay = plan.layout()?;
    if scratch_u32.len() < lay.u32s {
        return Err(Error::too_small(lay.u32s));
    }
    if scratch_points.len() < lay.points {
        return Err(Error::too_small(lay.points));
    }
    let out_sizes = plan.output();
    out.check(&out_sizes)?;
    let k = plan.levels;
    let dm = opts.dirmag_levels.min(k);
    let n0 = mesh.num_vertices();
    let nk = out_sizes.vertices;

    let mut u = U32Buffers::carve(&plan, &lay, scratch_u32, n0, nk)?;
    let p = PointBuffers::carve(&lay, scratch_points, n0, nk)?;
    // The fields live in the solver's scratch, which the solve reuses once `δ` is copied out.
    let mut f = Fields::carve(&mut *p.work, n0, nk)?;

    let anchors = level_zero(mesh, opts, dm, &mut u, &mut f)?;
    let degenerate = subdivide_fields(mesh, &plan, opts.stencil.scheme(), dm, &mut u, out, &mut f)?;
    let out_pos = out.positions.get_mut(..nk).ok_or(internal())?;
    if k == 0 {
        set_faces(mesh, out.offsets, out.indices)?;
    }
    report.dirmag_degenerate = degenerate;
    report.anchors = anchors.count as u32;

    // The positions of the meshes `build_hierarchy` builds topologies of: `p.rhs`, zeroed
    // (only the connectivity is read), which then receives `δ`.
    build_hierarchy(
        mesh,
        &plan,
        out.offsets,
        out.indices,
        p.rhs,
        &mut u,
        anchors,
    )?;
    let levels = solve_levels(&u, k)?;
    scaled_delta(k, f.da, p.rhs, nk);
    placement::spatial_centroid_sums(u.labels, out_pos, p.sums_x, p.sums_s, p.counts)?;

    let sys = System {
        levels: &levels,
        anchors: u.anchors.get(..anchors.count).ok_or(internal())?,
        loop_anchors: anchors.loops,
        anchor_weight: 1.0,
        components: u.labels,
        open: u.open,
    };
    let r = solve::solve(&sys, p.rhs, out_pos, p.work, &opts.solve)?;
    report.solve = r;
    if !r.converged {
        return Err(Error::new(Status::NotConverged));
    }
    placement::place(u.labels, out_pos, p.sums_x, p.sums_s, p.counts)?;
    Ok(out_sizes)
}

/// The `u32` scratch of [`subdivide`], carved in the order of [`Layout`].
struct U32Buffers<'a> {
    /// The topology of the level at hand.
    topo: &'a mut [u32],
    /// Faces (offsets, indices) of levels `1..k−1`.
    faces: ArrayVec<(&'a mut [u32], &'a mut [u32]), MAX_LEVELS>,
    /// Laplacian (rows, columns, vertex flags) of levels `0..=k`.
    laps: ArrayVec<(&'a mut [u32], &'a mut [u32], &'a mut [u32]), { MAX_LEVELS + 1 }>,
    /// Edges of levels `0..=k` as vertex pairs (the last one empty).
    edges: ArrayVec<&'a mut [u32], { MAX_LEVELS + 1 }>,
    /// Per finest-level vertex, its component (the lowest control vertex in it).
    labels: &'a mut [u32],
    /// Per component root: non-zero when the component has a boundary.
    open: &'a mut [u32],
    /// The anchors ([`Anchors`]).
    anchors: &'a mut [u32],
    /// The boundary-loop marks of level 0's half-edges.
    loop_mark: &'a mut [u32],
}

impl<'a> U32Buffers<'a> {
    fn carve(
        plan: &DifferentialPlan,
        lay: &Layout,
        scratch: &'a mut [u32],
        n0: usize,
        nk: usize,
    ) -> Result<U32Buffers<'a>> {
        let k = plan.levels;
        let mut us: &mut [u32] = scratch;
        let topo = take(&mut us, lay.topo)?;
        let mut faces = ArrayVec::new();
        for j in 1..k {
            let s = plan.size(j)?;
            let o = take(&mut us, s.offsets()?)?;
            let i = take(&mut us, s.indices)?;
            faces.try_push((o, i)).map_err(|_| internal())?;
        }
        let mut laps = ArrayVec::new();
        let mut edges = ArrayVec::new();
        for j in 0..=k {
            let s = plan.size(j)?;
            let r = take(&mut us, s.vertices + 1)?;
            let c = take(&mut us, s.indices + s.vertices)?;
            let bf = take(&mut us, s.vertices)?;
            laps.try_push((r, c, bf)).map_err(|_| internal())?;
            let e = if j < k {
                2 * (plan.size(j + 1)?.vertices - s.vertices)
            } else {
                0
            };
            edges.try_push(take(&mut us, e)?).map_err(|_| internal())?;
        }
        Ok(U32Buffers {
            topo,
            faces,
            laps,
            edges,
            labels: take(&mut us, nk)?,
            open: take(&mut us, n0)?,
            anchors: take(&mut us, n0)?,
            loop_mark: take(&mut us, plan.size(0)?.indices)?,
        })
    }
}

/// The point scratch of [`subdivide`], carved in the order of [`Layout`].
struct PointBuffers<'a> {
    /// The solver's scratch; first the [`Fields`].
    work: &'a mut [Point],
    /// The positions of the hierarchy's meshes, then `δ = 4⁻ᵏ Δᵏ`.
    rhs: &'a mut [Point],
    /// Per component: the sum of the solved positions.
    sums_x: &'a mut [Point],
    /// Per component: the sum of the spatial subdivision's positions.
    sums_s: &'a mut [Point],
    /// Per component: its vertex count (`[n, 0, 0]`).
    counts: &'a mut [Point],
}

impl<'a> PointBuffers<'a> {
    fn carve(
        lay: &Layout,
        scratch: &'a mut [Point],
        n0: usize,
        nk: usize,
    ) -> Result<PointBuffers<'a>> {
        let mut ps: &mut [Point] = scratch;
        Ok(PointBuffers {
            work: take(&mut ps, lay.work)?,
            rhs: take(&mut ps, nk)?,
            sums_x: take(&mut ps, n0)?,
            sums_s: take(&mut ps, n0)?,
            counts: take(&mut ps, n0)?,
        })
    }
}

/// The fields subdivided level by level, inside the solver's scratch: each has a current
/// (`a`) and a next (`b`) buffer, swapped after every level.
struct Fields<'a> {
    /// `Δ`.
    da: &'a mut [Point],
    db: &'a mut [Point],
    /// DirMag's unit normals `n`.
    na: &'a mut [Point],
    nb: &'a mut [Point],
    /// DirMag's magnitudes `H` (`[H, 0, 0]`).
    ha: &'a mut [Point],
    hb: &'a mut [Point],
    /// The spatial level that is not in the output (the warm start ping-pongs with it).
    spatial_tmp: &'a mut [Point],
    /// The angle-weighted normals of the control mesh.
    nbar: &'a mut [Point],
}

impl<'a> Fields<'a> {
    fn carve(work: &'a mut [Point], n0: usize, nk: usize) -> Result<Fields<'a>> {
        let field = work.get_mut(..cadd(cmul(nk, 7)?, n0)?).ok_or(internal())?;
        let mut fr: &mut [Point] = field;
        Ok(Fields {
            da: take(&mut fr, nk)?,
            db: take(&mut fr, nk)?,
            na: take(&mut fr, nk)?,
            nb: take(&mut fr, nk)?,
            ha: take(&mut fr, nk)?,
            hb: take(&mut fr, nk)?,
            spatial_tmp: take(&mut fr, nk)?,
            nbar: take(&mut fr, n0)?,
        })
    }
}

/// The first `n` entries of `*s`, leaving the rest in `*s`.
fn take<'a, T>(s: &mut &'a mut [T], n: usize) -> Result<&'a mut [T]> {
    let whole = core::mem::take(s);
    if whole.len() < n {
        return Err(internal());
    }
    let (a, b) = whole.split_at_mut_checked(n).ok_or(internal())?;
    *s = b;
    Ok(a)
}

/// Level 0: the Laplacian `L₀` (into `u.laps[0]`), `Δ⁰ = L₀ V⁰` (Eq. (2)–(3), Eq. (8) on the
/// boundary) into `f.da`, edited and split into `H` and `n` (§4.4, `edit.rs`), and the
/// components and anchors of the control mesh (`placement.rs`).
fn level_zero(
    mesh: Mesh<'_>,
    opts: &DifferentialOptions<'_>,
    dm: usize,
    u: &mut U32Buffers<'_>,
    f: &mut Fields<'_>,
) -> Result<Anchors> {
    let n0 = mesh.num_vertices();
    let topo = Topology::build(mesh, u.topo)?;
    let (r, c, bf) = u.laps.get_mut(0).ok_or(internal())?;
    laplacian::build(&topo, r, c, bf)?;
    let lap = Laplacian {
        rows: r,
        cols: c,
        boundary: bf,
    };
    let pos0 = f.spatial_tmp.get_mut(..n0).ok_or(internal())?;
    for (v, p) in mesh.positions().enumerate() {
        set(pos0, v, p)?;
    }
    lap.apply(pos0, 1.0, f.da)?;
    if dm > 0 || opts.normals.is_some() {
        dirmag::angle_weighted_normals(&topo, f.nbar)?;
    }
    edit::edit_differentials(opts, n0, f.da, f.ha, f.na, f.nbar)?;
    placement::components_and_anchors(&topo, n0, u.labels, u.open, u.anchors, u.loop_mark)
}

/// Levels `1..k`: the spatial subdivision (the solver's warm start, ending in `out_pos`) and
/// `Δ` — or, for the first `dm` levels, DirMag's `H` and `n` (§3.4), recombined into `Δ` after
/// level `dm` — each subdivided with the linear `scheme`. The faces of levels `1..k−1` go to
/// `u.faces`, those of level `k` to `out`. Returns the number of DirMag normals too short to
/// normalise.
fn subdivide_fields(
    mesh: Mesh<'_>,
    plan: &DifferentialPlan,
    scheme: Scheme,
    dm: usize,
    u: &mut U32Buffers<'_>,
    out: &mut MeshOut<'_>,
    f: &mut Fields<'_>,
) -> Result<u32> {
    let k = plan.levels;
    let nk = plan.output().vertices;
    let mut degenerate = 0u32;
    // The spatial level j lives in `out.positions` when k − j is even, else in `f.spatial_tmp`.
    let out_pos = out.positions.get_mut(..nk).ok_or(internal())?;
    if k % 2 == 0 {
        for (v, p) in mesh.positions().enumerate() {
            set(out_pos, v, p)?;
        }
    }
    let (out_offs, out_idx) = (&mut *out.offsets, &mut *out.indices);
    for j in 0..k {
        let sj = plan.size(j)?;
        let sn = plan.size(j + 1)?;
        let nf = u.faces.len();
        let (lo, hi) = u.faces.split_at_mut_checked(j.min(nf)).ok_or(internal())?;
        let (src_o, src_i): (&[u32], &[u32]) = if j == 0 {
            (mesh.offsets, mesh.indices)
        } else {
            let prev = lo.last().ok_or(internal())?;
            (&*prev.0, &*prev.1)
        };
        let src = (src_o, src_i, sj.vertices);
        // Destination faces of level j + 1.
        let dst_faces: (&mut [u32], &mut [u32]) = if j + 1 == k {
            (&mut *out_offs, &mut *out_idx)
        } else {
            let next = hi.first_mut().ok_or(internal())?;
            (&mut *next.0, &mut *next.1)
        };
        let (doffs, didx) = dst_faces;
        // Spatial warm start.
        let (src_sp, dst_sp): (&[Point], &mut [Point]) = if (k - j) % 2 == 0 {
            (&*out_pos, &mut *f.spatial_tmp)
        } else {
            (&*f.spatial_tmp, &mut *out_pos)
        };
        subdivide_field(scheme, src, src_sp, dst_sp, doffs, didx, u.topo)?;
        if j < dm {
            subdivide_field(scheme, src, f.ha, f.hb, doffs, didx, u.topo)?;
            subdivide_field(scheme, src, f.na, f.nb, doffs, didx, u.topo)?;
            for p in f.nb.iter_mut().take(sn.vertices) {
                match dirmag::normalized(*p) {
                    Some(u) => *p = u,
                    None => degenerate += 1,
                }
            }
            core::mem::swap(&mut f.ha, &mut f.hb);
            core::mem::swap(&mut f.na, &mut f.nb);
            if j + 1 == dm {
                for i in 0..sn.vertices {
                    let h = get(f.ha, i)?[0];
                    let u = get(f.na, i)?;
                    set(f.da, i, [h * u[0], h * u[1], h * u[2]])?;
                }
            }
        } else {
            subdivide_field(scheme, src, f.da, f.db, doffs, didx, u.topo)?;
            core::mem::swap(&mut f.da, &mut f.db);
        }
    }
    Ok(degenerate)
}

/// One linear subdivision step of the field `field` (the "positions" of the first `n`
/// vertices of the mesh with faces `offsets`, `indices`, given as `(offsets, indices, n)`)
/// into `dst`, writing the next level's faces into `offs` and `idx`.
fn subdivide_field(
    scheme: Scheme,
    (offsets, indices, n): (&[u32], &[u32], usize),
    field: &[Point],
    dst: &mut [Point],
    offs: &mut [u32],
    idx: &mut [u32],
    topo_buf: &mut [u32],
) -> Result<()> {
    let m = Mesh::new(field.get(..n).ok_or(internal())?, offsets, indices);
    let topo = Topology::build(m, topo_buf).map_err(non_finite_intermediate)?;
    let mut o = MeshOut::new(dst, offs, idx);
    crate::scheme::step_linear(scheme, &topo, &mut o)?;
    Ok(())
}

/// The fields subdivided here (`Δ`, `H`, `n`, the warm start) are intermediates: the input
/// was validated by [`plan`], so a non-finite value met while building their topology is an
/// overflow of the computation (`Δ` of a vertex near `1e231` overflows), reported as
/// [`Status::NumericalFailure`] naming the vertex (docs/bad-input-catalogue.md row 15), not
/// as bad input (pinned by `fuzz/regressions/differential/laplacian-overflow`).
fn non_finite_intermediate(e: Error) -> Error {
    if e.status == Status::NonFiniteInput {
        Error::at(Status::NumericalFailure, e.element)
    } else {
        e
    }
}

/// The output faces of `k = 0`: the control mesh's own.
fn set_faces(mesh: Mesh<'_>, offs: &mut [u32], idx: &mut [u32]) -> Result<()> {
    let o = offs.get_mut(..mesh.offsets.len()).ok_or(internal())?;
    for (d, s) in o.iter_mut().zip(mesh.offsets) {
        *d = *s;
    }
    let i = idx.get_mut(..mesh.indices.len()).ok_or(internal())?;
    for (d, s) in i.iter_mut().zip(mesh.indices) {
        *d = *s;
    }
    Ok(())
}

/// The hierarchy of the solve: the Laplacian of levels `1..=k` (level 0's is built by
/// [`level_zero`]), the edges of levels `0..k−1` (the parents of the next level's edge points)
/// with the component label of every edge point, and the anchors pinned at every level. The
/// topologies are built on `dummy` positions (zeroed here; only connectivity is read); the
/// faces of level `k` are `out_offs`, `out_idx`.
fn build_hierarchy(
    mesh: Mesh<'_>,
    plan: &DifferentialPlan,
    out_offs: &[u32],
    out_idx: &[u32],
    dummy: &mut [Point],
    u: &mut U32Buffers<'_>,
    anchors: Anchors,
) -> Result<()> {
    let k = plan.levels;
    for d in dummy.iter_mut() {
        *d = [0.0; 3];
    }
    for j in 0..=k {
        let sj = plan.size(j)?;
        let (o, i): (&[u32], &[u32]) = if j == 0 {
            (mesh.offsets, mesh.indices)
        } else if j == k {
            (
                out_offs.get(..sj.offsets()?).ok_or(internal())?,
                out_idx.get(..sj.indices).ok_or(internal())?,
            )
        } else {
            let faces = u.faces.get(j - 1).ok_or(internal())?;
            (&*faces.0, &*faces.1)
        };
        let m = Mesh::new(dummy.get(..sj.vertices).ok_or(internal())?, o, i);
        let topo = Topology::build(m, u.topo)?;
        if j > 0 {
            let (r, c, bf) = u.laps.get_mut(j).ok_or(internal())?;
            laplacian::build(&topo, r, c, bf)?;
        }
        if j < k {
            let e = u.edges.get_mut(j).ok_or(internal())?;
            for id in 0..topo.num_edges() {
                let (a, b) = topo.edge_vertices(id as u32)?;
                set(e, 2 * id, a)?;
                set(e, 2 * id + 1, b)?;
                let la = get(u.labels, a as usize)?;
                set(u.labels, sj.vertices + id, la)?;
            }
        }
    }
    let pinned = u.anchors.get(..anchors.count).ok_or(internal())?;
    for (_, _, bf) in u.laps.iter_mut() {
        for &a in pinned {
            let f = bf.get_mut(a as usize).ok_or(internal())?;
            *f |= laplacian::PINNED;
        }
    }
    Ok(())
}

/// The levels of the solve's hierarchy, coarsest first, from the buffers [`build_hierarchy`]
/// filled.
fn solve_levels<'b>(
    u: &'b U32Buffers<'_>,
    k: usize,
) -> Result<ArrayVec<SolveLevel<'b>, { MAX_LEVELS + 1 }>> {
    let mut levels = ArrayVec::new();
    for j in 0..=k {
        let (r, c, bf) = u.laps.get(j).ok_or(internal())?;
        levels
            .try_push(SolveLevel {
                lap: Laplacian {
                    rows: r,
                    cols: c,
                    boundary: bf,
                },
                edges: u.edges.get(j).ok_or(internal())?,
            })
            .map_err(|_| internal())?;
    }
    Ok(levels)
}

/// `δ = 4⁻ᵏ Δᵏ` of the `nk` finest vertices into `delta` (`Δᵏ` is in `da`, inside the
/// solver's scratch: it is copied out before the solve). `4⁻ᵏ` is an exact power of two.
fn scaled_delta(k: usize, da: &[Point], delta: &mut [Point], nk: usize) {
    let mut c = 1.0;
    for _ in 0..k {
        c *= 0.25;
    }
    for (d, dk) in delta.iter_mut().zip(da.iter()).take(nk) {
        *d = [c * dk[0], c * dk[1], c * dk[2]];
    }
}
