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
use super::plan::{plan, plan_scratch_size, DifferentialPlan, Layout};
use super::solve::{self, SolveLevel, SolveReport, System};
use super::{dirmag, edit, folds, normal_edit};
use crate::error::{Error, Result, Status, NO_ELEMENT};
use crate::exec::{Executor, Serial};
use crate::mesh::{cadd, cmul, get, internal, set, Mesh, MeshOut, MeshSizes, Topology};
use crate::point::{add, sub, Point};
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
    subdivide_with(
        mesh,
        opts,
        scratch_u32,
        scratch_points,
        out,
        report,
        &Serial,
    )
}

/// [`subdivide`] with the passes over all vertices split into disjoint output ranges run by
/// `exec` ([`crate::exec`]): the linear subdivision steps of `Δ` and of the warm start, and
/// in the reconstruction the row-wise sparse products and vector updates
/// ([`solve::solve_with`]). Every output element is computed as in [`subdivide`] and the
/// reductions stay serial, so the output, the report and the errors are those of
/// [`subdivide`], bit for bit, for every executor and chunking. The core stays
/// single-threaded; `nlsubdiv-threads` brings the threads.
///
/// # Errors
/// Those of [`subdivide`].
pub fn subdivide_with(
    mesh: Mesh<'_>,
    opts: &DifferentialOptions<'_>,
    scratch_u32: &mut [u32],
    scratch_points: &mut [Point],
    out: &mut MeshOut<'_>,
    report: &mut DifferentialReport,
    exec: &dyn Executor,
) -> Result<MeshSizes> {
    // First, and a constant without the feature: the optimiser then drops the method.
    opts.stencil.check_built()?;
    let plan = {
        let need = plan_scratch_size(&mesh)?;
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
    let scheme = opts.stencil.scheme();

    let mut u = U32Buffers::carve(&plan, &lay, scratch_u32, n0, nk)?;
    let p = PointBuffers::carve(&lay, scratch_points, n0, nk)?;
    // The fields live in the solver's scratch, which the solve reuses once `δ` is copied out.
    let mut f = Fields::carve(&mut *p.work, n0, nk)?;

    // The unedited reconstruction (with edits: the reference they are measured against).
    let anchors = level_zero(mesh, dm, &mut u, &mut f)?;
    let degenerate = subdivide_fields(mesh, &plan, scheme, dm, &mut u, out, &mut f, exec)?;
    if k == 0 {
        set_faces(mesh, out.offsets, out.indices)?;
    }
    report.dirmag_degenerate = degenerate;
    report.anchors = anchors.count as u32;
    report.reference_solve = SolveReport::default();
    report.folded_faces = 0;
    report.first_folded_face = NO_ELEMENT;
    report.folded_edges = 0;
    report.first_folded_edge = [NO_ELEMENT; 2];

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
    scaled_delta(k, f.da, p.rhs, nk);
    {
        let out_pos = out.positions.get_mut(..nk).ok_or(internal())?;
        placement::spatial_centroid_sums(u.labels, out_pos, p.sums_x, p.sums_s, p.counts)?;
    }
    let r = reconstruct(&u, k, anchors, p.rhs, out, p.work, &opts.solve, exec)?;
    report.solve = r;
    if !r.converged {
        return Err(Error::new(Status::NotConverged));
    }

    let edited = opts.curvature_scale.is_some() || opts.normals.is_some();
    if edited {
        report.reference_solve = r;
        let out_pos = out.positions.get(..nk).ok_or(internal())?;
        copy_points(out_pos, p.reference)?;
    }
    // A scale of 1 everywhere changes nothing (`1 · δ = δ`): no second solve.
    if let Some(sc) = opts.curvature_scale.filter(|s| s.iter().any(|&x| x != 1.0)) {
        // §4.4 curvature edit: `Δ⁰` scaled, subdivided again and solved from the unedited
        // result (the anchors keep their values).
        let mut f = Fields::carve(&mut *p.work, n0, nk)?;
        {
            let topo = Topology::build(mesh, u.topo)?;
            let (r, c, bf) = u.laps.first().ok_or(internal())?;
            let lap = Laplacian {
                rows: r,
                cols: c,
                boundary: bf,
            };
            delta_level_zero(mesh, &topo, lap, Some(sc), dm, &mut f)?;
        }
        report.dirmag_degenerate =
            subdivide_delta(mesh, &plan, scheme, dm, &mut u, out, &mut f, exec)?;
        scaled_delta(k, f.da, p.rhs, nk);
        let r = reconstruct(&u, k, anchors, p.rhs, out, p.work, &opts.solve, exec)?;
        report.solve = r;
        if !r.converged {
            return Err(Error::new(Status::NotConverged));
        }
    }
    if let Some(normals) = opts.normals {
        // §4.4 normal edit (`normal_edit.rs`): `δ ← δ + L_k D`, solved from `X + D`.
        if turn_normals(mesh, &plan, normals, &mut u, out, p.rhs, p.work)? > 0 {
            let r = reconstruct(&u, k, anchors, p.rhs, out, p.work, &opts.solve, exec)?;
            report.solve = r;
            if !r.converged {
                return Err(Error::new(Status::NotConverged));
            }
        }
    }
    {
        let out_pos = out.positions.get_mut(..nk).ok_or(internal())?;
        placement::place(u.labels, out_pos, p.sums_x, p.sums_s, p.counts)?;
    }
    if edited {
        let pos = out.positions.get(..nk).ok_or(internal())?;
        let m = Mesh::new(
            pos,
            out.offsets.get(..out_sizes.offsets()?).ok_or(internal())?,
            out.indices.get(..out_sizes.indices).ok_or(internal())?,
        );
        let topo = Topology::build(m, u.topo)?;
        let fo = folds::census(&topo, pos, p.reference)?;
        report.folded_faces = fo.faces;
        report.first_folded_face = fo.first_face;
        report.folded_edges = fo.edges;
        report.first_folded_edge = fo.first_edge;
        if let (true, Some(face)) = (opts.strict, fo.culprit()) {
            return Err(Error::at(Status::FoldedSurface, face));
        }
    }
    Ok(out_sizes)
}

/// `dst[..src.len()] = src`.
fn copy_points(src: &[Point], dst: &mut [Point]) -> Result<()> {
    let d = dst.get_mut(..src.len()).ok_or(internal())?;
    d.copy_from_slice(src);
    Ok(())
}

/// One reconstruction (§3.5 step 4) of `δ` (in `rhs`) from the warm start in
/// `out.positions`, overwritten with the solution; the anchors keep their warm-start values.
#[allow(clippy::too_many_arguments)]
fn reconstruct(
    u: &U32Buffers<'_>,
    k: usize,
    anchors: Anchors,
    rhs: &[Point],
    out: &mut MeshOut<'_>,
    work: &mut [Point],
    opts: &solve::SolveOptions,
    exec: &dyn Executor,
) -> Result<solve::SolveReport> {
    let levels = solve_levels(u, k)?;
    let sys = System {
        levels: &levels,
        anchors: u.anchors.get(..anchors.count).ok_or(internal())?,
        loop_anchors: anchors.loops,
        anchor_weight: 1.0,
        components: u.labels,
        open: u.open,
    };
    let n = rhs.len();
    let x = out.positions.get_mut(..n).ok_or(internal())?;
    solve::solve_with(&sys, rhs, x, work, opts, exec)
}

/// The normal edit of `normal_edit.rs` on the solved positions in `out.positions` (`nk`
/// vertices, not yet placed): the rotation field seeded at each edited vertex's seed level and
/// subdivided with Loop over the stored faces of every level, the displacement `D`,
/// `rhs += L_k D` and
/// `out.positions += D`. `work` is the solver's scratch (free between solves). Returns the
/// number of edited vertices (0: nothing changed).
fn turn_normals(
    mesh: Mesh<'_>,
    plan: &DifferentialPlan,
    normals: &[Point],
    u: &mut U32Buffers<'_>,
    out: &mut MeshOut<'_>,
    rhs: &mut [Point],
    work: &mut [Point],
) -> Result<usize> {
    let k = plan.levels;
    let nk = plan.output().vertices;
    let mut w: &mut [Point] = work;
    let star = take(&mut w, nk)?;
    let mut wa = take(&mut w, nk)?;
    let mut wb = take(&mut w, nk)?;
    let mut ca = take(&mut w, nk)?;
    let mut cb = take(&mut w, nk)?;
    let d = take(&mut w, nk)?;
    let ld = take(&mut w, nk)?;
    let top = plan.output();
    {
        let x = out.positions.get(..nk).ok_or(internal())?;
        let m = Mesh::new(
            x,
            out.offsets.get(..top.offsets()?).ok_or(internal())?,
            out.indices.get(..top.indices).ok_or(internal())?,
        );
        let topo = Topology::build(m, u.topo)?;
        normal_edit::star_normals(&topo, star)?;
    }
    // Per control vertex: its rotation vector (in `d`) and seed level (in `ld`), until `d`
    // and `ld` receive `D` and `L_k D`.
    let (omegas, levels) = (&mut *d, &mut *ld);
    let edited = {
        let topo0 = Topology::build(mesh, u.topo)?;
        normal_edit::rotations(&topo0, normals, star, k, omegas, levels)?
    };
    if edited == 0 {
        return Ok(0);
    }
    {
        let x = out.positions.get(..nk).ok_or(internal())?;
        for (i, (w, c)) in wa
            .iter_mut()
            .zip(ca.iter_mut())
            .enumerate()
            .take(mesh.num_vertices())
        {
            *w = [0.0; 3];
            *c = get(x, i)?;
        }
    }
    {
        let x: &[Point] = out.positions.get(..nk).ok_or(internal())?;
        let seeds = normal_edit::Seeds {
            normals,
            omegas,
            levels,
            x,
        };
        for_each_level(
            mesh,
            plan,
            u,
            out.offsets,
            out.indices,
            |j, src, offs, idx, topo| {
                {
                    // The topology of level j (its positions are not read by the seeding).
                    let (o, i, n) = src;
                    let m = Mesh::new(x.get(..n).ok_or(internal())?, o, i);
                    let t = Topology::build(m, &mut *topo)?;
                    seeds.seed(&t, j, wa, ca)?;
                }
                subdivide_field(Scheme::Loop, src, wa, wb, (offs, idx), topo, &Serial)?;
                subdivide_field(Scheme::Loop, src, ca, cb, (offs, idx), topo, &Serial)?;
                core::mem::swap(&mut wa, &mut wb);
                core::mem::swap(&mut ca, &mut cb);
                Ok(())
            },
        )?;
        // Seeds of level k (edited vertices that k does not leave room for).
        let m = Mesh::new(
            x,
            out.offsets.get(..top.offsets()?).ok_or(internal())?,
            out.indices.get(..top.indices).ok_or(internal())?,
        );
        let t = Topology::build(m, u.topo)?;
        seeds.seed(&t, k, wa, ca)?;
    }
    let x = out.positions.get_mut(..nk).ok_or(internal())?;
    for i in 0..nk {
        let v = sub(get(x, i)?, get(ca, i)?);
        set(d, i, normal_edit::rotation_displacement(get(wa, i)?, v))?;
    }
    let (r, c, bf) = u.laps.get(k).ok_or(internal())?;
    let lap = Laplacian {
        rows: r,
        cols: c,
        boundary: bf,
    };
    lap.apply(d, 1.0, ld)?;
    for (i, (xi, ri)) in x.iter_mut().zip(rhs.iter_mut()).enumerate().take(nk) {
        *xi = add(*xi, get(d, i)?);
        *ri = add(*ri, get(ld, i)?);
    }
    Ok(edited)
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
    /// With edits: the unedited result, the reference of the fold census.
    reference: &'a mut [Point],
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
            reference: take(&mut ps, lay.reference)?,
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

/// Level 0: the Laplacian `L₀` (into `u.laps[0]`), the unedited `Δ⁰` ([`delta_level_zero`])
/// and the components and anchors of the control mesh (`placement.rs`).
fn level_zero(
    mesh: Mesh<'_>,
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
    delta_level_zero(mesh, &topo, lap, None, dm, f)?;
    placement::components_and_anchors(&topo, n0, u.labels, u.open, u.anchors, u.loop_mark)
}

/// `Δ⁰ = L₀ V⁰` (Eq. (2)–(3), Eq. (8) on the boundary) of the control mesh `mesh` (topology
/// `topo`, Laplacian `lap`) into `f.da`, scaled by the curvature edit `scale` and split into
/// `H` and `n` (§4.4, `edit.rs`).
fn delta_level_zero(
    mesh: Mesh<'_>,
    topo: &Topology<'_, '_>,
    lap: Laplacian<'_>,
    scale: Option<&[f64]>,
    dm: usize,
    f: &mut Fields<'_>,
) -> Result<()> {
    let n0 = mesh.num_vertices();
    let pos0 = f.spatial_tmp.get_mut(..n0).ok_or(internal())?;
    for (v, p) in mesh.positions().enumerate() {
        set(pos0, v, p)?;
    }
    lap.apply(pos0, 1.0, f.da)?;
    if dm > 0 {
        dirmag::angle_weighted_normals(topo, f.nbar)?;
    }
    edit::edit_differentials(scale, n0, f.da, f.ha, f.na, f.nbar)
}

/// Runs `step(j, source, offsets, indices, topology scratch)` for every level `j` in
/// `0..k`: `source` is level `j`'s faces and vertex count, `offsets` and `indices` receive
/// level `j + 1`'s faces (those of levels `1..k−1` in `u.faces`, level `k`'s in `out`). A
/// step that subdivides writes them; rewriting them gives the same values.
fn for_each_level(
    mesh: Mesh<'_>,
    plan: &DifferentialPlan,
    u: &mut U32Buffers<'_>,
    out_offs: &mut [u32],
    out_idx: &mut [u32],
    mut step: impl FnMut(
        usize,
        (&[u32], &[u32], usize),
        &mut [u32],
        &mut [u32],
        &mut [u32],
    ) -> Result<()>,
) -> Result<()> {
    let k = plan.levels;
    for j in 0..k {
        let sj = plan.size(j)?;
        let nf = u.faces.len();
        let (lo, hi) = u.faces.split_at_mut_checked(j.min(nf)).ok_or(internal())?;
        let (src_o, src_i): (&[u32], &[u32]) = if j == 0 {
            (mesh.offsets, mesh.indices)
        } else {
            let prev = lo.last().ok_or(internal())?;
            (&*prev.0, &*prev.1)
        };
        let (doffs, didx): (&mut [u32], &mut [u32]) = if j + 1 == k {
            (&mut *out_offs, &mut *out_idx)
        } else {
            let next = hi.first_mut().ok_or(internal())?;
            (&mut *next.0, &mut *next.1)
        };
        step(j, (src_o, src_i, sj.vertices), doffs, didx, u.topo)?;
    }
    Ok(())
}

/// Levels `1..k`: the spatial subdivision (the solver's warm start, ending in `out.positions`)
/// and `Δ` ([`delta_step`]), each subdivided with the linear `scheme`; the faces of levels
/// `1..k−1` go to `u.faces`, those of level `k` to `out`. Returns the number of DirMag normals
/// too short to normalise.
#[allow(clippy::too_many_arguments)]
fn subdivide_fields(
    mesh: Mesh<'_>,
    plan: &DifferentialPlan,
    scheme: Scheme,
    dm: usize,
    u: &mut U32Buffers<'_>,
    out: &mut MeshOut<'_>,
    f: &mut Fields<'_>,
    exec: &dyn Executor,
) -> Result<u32> {
    let k = plan.levels;
    let nk = plan.output().vertices;
    let mut degenerate = 0u32;
    // The spatial level j lives in `out.positions` when k − j is even, else in `f.spatial_tmp`.
    let op = out.positions.get_mut(..nk).ok_or(internal())?;
    if k % 2 == 0 {
        for (v, p) in mesh.positions().enumerate() {
            set(op, v, p)?;
        }
    }
    for_each_level(
        mesh,
        plan,
        u,
        out.offsets,
        out.indices,
        |j, src, doffs, didx, topo| {
            // Spatial warm start.
            let (src_sp, dst_sp): (&[Point], &mut [Point]) = if (k - j) % 2 == 0 {
                (&*op, &mut *f.spatial_tmp)
            } else {
                (&*f.spatial_tmp, &mut *op)
            };
            subdivide_field(scheme, src, src_sp, dst_sp, (doffs, didx), topo, exec)?;
            let sn = plan.size(j + 1)?.vertices;
            degenerate += delta_step(scheme, j, dm, sn, src, doffs, didx, topo, f, exec)?;
            Ok(())
        },
    )?;
    Ok(degenerate)
}

/// Levels `1..k` of `Δ` alone ([`delta_step`]) over the faces already in `u.faces` and `out`.
/// Returns the number of DirMag normals too short to normalise.
#[allow(clippy::too_many_arguments)]
fn subdivide_delta(
    mesh: Mesh<'_>,
    plan: &DifferentialPlan,
    scheme: Scheme,
    dm: usize,
    u: &mut U32Buffers<'_>,
    out: &mut MeshOut<'_>,
    f: &mut Fields<'_>,
    exec: &dyn Executor,
) -> Result<u32> {
    let mut degenerate = 0u32;
    for_each_level(
        mesh,
        plan,
        u,
        out.offsets,
        out.indices,
        |j, src, doffs, didx, topo| {
            let sn = plan.size(j + 1)?.vertices;
            degenerate += delta_step(scheme, j, dm, sn, src, doffs, didx, topo, f, exec)?;
            Ok(())
        },
    )?;
    Ok(degenerate)
}

/// Step `j → j + 1` of `Δ` with the linear `scheme` — or, for the first `dm` levels, of
/// DirMag's `H` and `n` (§3.4), recombined into `Δ` after level `dm`. `sn` is the vertex count
/// of level `j + 1`. Returns the number of DirMag normals too short to normalise.
#[allow(clippy::too_many_arguments)]
fn delta_step(
    scheme: Scheme,
    j: usize,
    dm: usize,
    sn: usize,
    src: (&[u32], &[u32], usize),
    doffs: &mut [u32],
    didx: &mut [u32],
    topo: &mut [u32],
    f: &mut Fields<'_>,
    exec: &dyn Executor,
) -> Result<u32> {
    let mut degenerate = 0u32;
    if j < dm {
        subdivide_field(scheme, src, f.ha, f.hb, (doffs, didx), topo, exec)?;
        subdivide_field(scheme, src, f.na, f.nb, (doffs, didx), topo, exec)?;
        for p in f.nb.iter_mut().take(sn) {
            match dirmag::normalized(*p) {
                Some(u) => *p = u,
                None => degenerate += 1,
            }
        }
        core::mem::swap(&mut f.ha, &mut f.hb);
        core::mem::swap(&mut f.na, &mut f.nb);
        if j + 1 == dm {
            for i in 0..sn {
                let h = get(f.ha, i)?[0];
                let u = get(f.na, i)?;
                set(f.da, i, [h * u[0], h * u[1], h * u[2]])?;
            }
        }
    } else {
        subdivide_field(scheme, src, f.da, f.db, (doffs, didx), topo, exec)?;
        core::mem::swap(&mut f.da, &mut f.db);
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
    (offs, idx): (&mut [u32], &mut [u32]),
    topo_buf: &mut [u32],
    exec: &dyn Executor,
) -> Result<()> {
    let m = Mesh::new(field.get(..n).ok_or(internal())?, offsets, indices);
    let topo = Topology::build(m, topo_buf).map_err(non_finite_intermediate)?;
    let mut o = MeshOut::new(dst, offs, idx);
    crate::scheme::step_linear_with(scheme, &topo, &mut o, exec)?;
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
