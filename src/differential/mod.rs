//! Differential-space subdivision of triangle meshes (seed 001 §3, "Differential space
//! subdivision"; Zhu, Wang et al. 2011).
//!
//! Instead of the positions, the *differential coordinates* (discrete mean-curvature
//! normals) are subdivided, and the surface is reconstructed from them once, at the last
//! level (§4.1 "Computation in the reconstruction": one linear system, not `k`):
//!
//! 1. `Δ⁰ = L₀ V⁰` with the combinatorial Laplacian, Eq. (2)–(3), and the curve form Eq. (8)
//!    on the boundary ([`laplacian`]); optionally edited (§4.4, [`DifferentialOptions`]).
//! 2. `Δ⁰` is subdivided `k` times with Loop or Modified Butterfly — the crate's own linear
//!    drivers ([`crate::scheme::subdivide`]) run on a mesh whose "positions" are the
//!    differential coordinates — or with DirMag (§3.4, [`dirmag`]) for the first
//!    [`DifferentialOptions::dirmag_levels`] levels ("we only perform the DirMag subdivision
//!    in the first one or two iterations").
//! 3. The geometry of level `k` is the least-squares solution of `4ᵏ L_k Ṽᵏ = Δᵏ` with anchor
//!    rows (§3.5 step 4), solved by [`solve`]: the boundary loops exactly (tridiagonal), the
//!    rest as the equivalent Dirichlet graph-Laplacian problem by multigrid-preconditioned CG,
//!    warm-started from the spatial subdivision of the same stencil; the tolerance is checked
//!    on the residual of the normal equations.
//!
//! # Placement (decision)
//!
//! The paper fixes the translation with one handle, `v₀ = (0, 0, 0)`. That moves the result
//! away from the control mesh, and one handle does not fix a mesh with several components or
//! boundary loops (each boundary loop is a closed differential curve with its own free
//! translation: `L` has one null vector per closed component and per boundary loop). We
//! anchor the lowest-index vertex of every closed component and of every boundary loop (and
//! every isolated vertex) at its position in the spatial subdivision, then translate each
//! connected component so that its centroid (the mean of its vertices) equals the centroid of
//! the same component of the spatial subdivision. Translations do not change the
//! least-squares residual of the Laplacian rows, so this is one of the paper's solutions; for
//! a closed connected mesh it is the paper's solution translated by a constant vector.
//! Consequences: `k = 0` returns the control mesh (up to the solver tolerance); translating
//! the input translates the output.
//!
//! # Buffers
//!
//! Output order and faces are those of the spatial Loop/Butterfly subdivision
//! ([`crate::scheme`]). Scratch sizes come from [`plan`]; contents of every buffer are
//! unspecified on error. [`Status::NotConverged`] is returned when the solver stops at its
//! iteration cap; the report still says how far it got.

pub mod dirmag;
pub mod laplacian;
pub mod metrics;
pub mod solve;

use arrayvec::ArrayVec;

use crate::error::{Error, Result, Status};
use crate::mesh::{
    cadd, cmul, get, internal, set, topology_scratch_len, Mesh, MeshOut, MeshSizes, Topology, NONE,
};
use crate::point::Point;
use crate::scheme::{Scheme, MAX_LEVELS};
use laplacian::Laplacian;
use solve::{SolveLevel, SolveOptions, SolveReport, System};

/// The linear stencil used on the differential mesh (and for the warm start).
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Stencil {
    /// Loop (approximating).
    Loop = 0,
    /// Modified Butterfly (interpolating; the paper's preferred choice, §4.2).
    ModifiedButterfly = 1,
}

impl Stencil {
    /// The stencil of a code.
    pub fn from_code(c: u32) -> Option<Stencil> {
        match c {
            0 => Some(Stencil::Loop),
            1 => Some(Stencil::ModifiedButterfly),
            _ => None,
        }
    }

    const fn scheme(self) -> Scheme {
        match self {
            Stencil::Loop => Scheme::Loop,
            Stencil::ModifiedButterfly => Scheme::ModifiedButterfly,
        }
    }
}

/// Options of [`plan`] and [`subdivide`].
#[derive(Clone, Copy, Debug)]
pub struct DifferentialOptions<'a> {
    /// The stencil on the differential mesh.
    pub stencil: Stencil,
    /// Subdivision levels `k` (at most [`MAX_LEVELS`]).
    pub levels: usize,
    /// The first this many levels use DirMag (§3.4) with `stencil`; 0 for plain linear
    /// subdivision of `Δ`. Values above `levels` act as `levels`.
    pub dirmag_levels: usize,
    /// Solver tolerance and caps.
    pub solve: SolveOptions,
    /// §4.4 editing: per control vertex, a factor on its mean curvature `H_i` (length = the
    /// control vertex count).
    pub curvature_scale: Option<&'a [f64]>,
    /// §4.4 editing: per control vertex, a replacement normal direction (normalised here);
    /// a zero vector keeps the vertex's own normal. Length = the control vertex count.
    pub normals: Option<&'a [Point]>,
}

impl Default for DifferentialOptions<'_> {
    fn default() -> Self {
        DifferentialOptions {
            stencil: Stencil::Loop,
            levels: 1,
            dirmag_levels: 0,
            solve: SolveOptions::default(),
            curvature_scale: None,
            normals: None,
        }
    }
}

/// What [`subdivide`] did (also written when it returns [`Status::NotConverged`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct DifferentialReport {
    /// The reconstruction's solver report.
    pub solve: SolveReport,
    /// DirMag outputs whose subdivided normal was too short to normalise.
    pub dirmag_degenerate: u32,
    /// Number of anchor rows (closed components + boundary loops + isolated vertices).
    pub anchors: u32,
}

/// Sizes of every level and the scratch of [`subdivide`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DifferentialPlan {
    /// Levels `k`.
    pub levels: usize,
    /// `sizes[j]` of level `j`.
    pub sizes: [MeshSizes; MAX_LEVELS + 1],
    /// `u32` scratch entries.
    pub scratch_u32: usize,
    /// Point scratch entries.
    pub scratch_points: usize,
}

impl DifferentialPlan {
    /// The output sizes.
    pub fn output(&self) -> MeshSizes {
        self.sizes.get(self.levels).copied().unwrap_or_default()
    }

    fn size(&self, j: usize) -> Result<MeshSizes> {
        self.sizes.get(j).copied().ok_or(internal())
    }

    fn layout(&self) -> Result<Layout> {
        let k = self.levels;
        let top = self.size(k)?;
        let n0 = self.size(0)?.vertices;
        let mut u = Layout {
            topo: topology_scratch_len(top.vertices, top.indices)?,
            ..Layout::default()
        };
        for j in 0..=k {
            let s = self.size(j)?;
            if j >= 1 && j < k {
                u.faces = cadd(u.faces, cadd(s.offsets()?, s.indices)?)?;
            }
            u.lap = cadd(
                u.lap,
                cadd(cadd(cmul(s.vertices, 2)?, 1)?, cadd(s.indices, s.vertices)?)?,
            )?;
            if j < k {
                let e = self.size(j + 1)?.vertices - s.vertices;
                u.edges = cadd(u.edges, cmul(e, 2)?)?;
            }
        }
        u.marks = cadd(cadd(top.vertices, n0)?, cadd(n0, self.size(0)?.indices)?)?;
        let nk = top.vertices;
        let mut counts = ArrayVec::<usize, { MAX_LEVELS + 1 }>::new();
        for j in 0..=k {
            counts
                .try_push(self.size(j)?.vertices)
                .map_err(|_| internal())?;
        }
        let fields = cadd(cmul(nk, 7)?, n0)?;
        u.work = solve::solve_scratch_len(&counts)?.max(fields);
        u.points = cadd(cadd(u.work, nk)?, cmul(n0, 3)?)?;
        u.u32s = cadd(
            cadd(cadd(u.topo, u.faces)?, cadd(u.lap, u.edges)?)?,
            u.marks,
        )?;
        Ok(u)
    }
}

#[derive(Clone, Copy, Debug, Default)]
struct Layout {
    topo: usize,
    faces: usize,
    lap: usize,
    edges: usize,
    marks: usize,
    work: usize,
    points: usize,
    u32s: usize,
}

/// `u32` scratch [`plan`] needs (the input topology).
///
/// # Errors
/// [`Status::SizeOverflow`].
pub fn plan_scratch_len(mesh: &Mesh<'_>) -> Result<usize> {
    crate::scheme::scratch_len(mesh)
}

/// Validates `mesh` (triangles only) and `opts` and plans the call.
///
/// # Errors
/// Validation errors of [`Topology::build`]; [`Status::UnsupportedFaceType`] naming the first
/// face that is not a triangle; [`Status::InvalidArgument`] for more than [`MAX_LEVELS`]
/// levels, a bad tolerance, or an edit slice whose length is not the vertex count;
/// [`Status::NonFiniteInput`] for a non-finite edit value (naming the vertex);
/// [`Status::SizeOverflow`]; [`Status::ValenceTooHigh`].
pub fn plan(
    mesh: Mesh<'_>,
    opts: &DifferentialOptions<'_>,
    scratch: &mut [u32],
) -> Result<DifferentialPlan> {
    let ok = |t: f64| t.is_finite() && t >= 0.0;
    if opts.levels > MAX_LEVELS || !ok(opts.solve.tolerance) || !ok(opts.solve.coarse_tolerance) {
        return Err(Error::new(Status::InvalidArgument));
    }
    let n = mesh.num_vertices();
    if let Some(s) = opts.curvature_scale {
        if s.len() != n {
            return Err(Error::new(Status::InvalidArgument));
        }
        if let Some(i) = s.iter().position(|x| !x.is_finite()) {
            return Err(Error::at(Status::NonFiniteInput, i as u32));
        }
    }
    if let Some(s) = opts.normals {
        if s.len() != n {
            return Err(Error::new(Status::InvalidArgument));
        }
        if let Some(i) = s.iter().position(|x| !crate::point::is_finite(x)) {
            return Err(Error::at(Status::NonFiniteInput, i as u32));
        }
    }
    {
        let topo = Topology::build(mesh, scratch)?;
        for f in 0..topo.num_faces() as u32 {
            if topo.face_size(f)? != 3 {
                return Err(Error::at(Status::UnsupportedFaceType, f));
            }
        }
    }
    let lp = crate::scheme::plan(opts.stencil.scheme(), mesh, opts.levels, scratch)?;
    let mut p = DifferentialPlan {
        levels: opts.levels,
        sizes: lp.sizes,
        scratch_u32: 0,
        scratch_points: 0,
    };
    let l = p.layout()?;
    p.scratch_u32 = l.u32s;
    p.scratch_points = l.points;
    Ok(p)
}

fn take<'a, T>(s: &mut &'a mut [T], n: usize) -> Result<&'a mut [T]> {
    let whole = core::mem::take(s);
    if whole.len() < n {
        return Err(internal());
    }
    let (a, b) = whole.split_at_mut_checked(n).ok_or(internal())?;
    *s = b;
    Ok(a)
}

/// Union–find root with path halving (deterministic).
fn find(parent: &mut [u32], mut v: u32) -> Result<u32> {
    for _ in 0..parent.len() + 1 {
        let p = get(parent, v as usize)?;
        if p == v {
            return Ok(v);
        }
        let gp = get(parent, p as usize)?;
        set(parent, v as usize, gp)?;
        v = gp;
    }
    Err(internal())
}

/// Differential-space subdivision of `mesh` (see the [module docs](self)) into `out`
/// (≥ [`DifferentialPlan::output`]); `scratch_u32` and `scratch_points` hold at least the
/// plan's sizes. `report` is written on success and on [`Status::NotConverged`].
///
/// # Errors
/// Those of [`plan`]; [`Status::BufferTooSmall`] (needed size) for a short output or scratch;
/// [`Status::NotConverged`] when the solver stops at [`SolveOptions::max_iterations`];
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
    let scheme = opts.stencil.scheme();
    let n0 = mesh.num_vertices();
    let nk = out_sizes.vertices;

    // ---- carve the scratch ----
    let mut us: &mut [u32] = scratch_u32;
    let topo_buf = take(&mut us, lay.topo)?;
    let mut faces = ArrayVec::<(&mut [u32], &mut [u32]), MAX_LEVELS>::new();
    for j in 1..k {
        let s = plan.size(j)?;
        let o = take(&mut us, s.offsets()?)?;
        let i = take(&mut us, s.indices)?;
        faces.try_push((o, i)).map_err(|_| internal())?;
    }
    let mut laps = ArrayVec::<(&mut [u32], &mut [u32], &mut [u32]), { MAX_LEVELS + 1 }>::new();
    let mut edges = ArrayVec::<&mut [u32], { MAX_LEVELS + 1 }>::new();
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
    let labels = take(&mut us, nk)?;
    let aux = take(&mut us, n0)?;
    let anchors_buf = take(&mut us, n0)?;
    let loop_mark = take(&mut us, plan.size(0)?.indices)?;

    let mut ps: &mut [Point] = scratch_points;
    let work = take(&mut ps, lay.work)?;
    let rhs = take(&mut ps, nk)?;
    let sums_x = take(&mut ps, n0)?;
    let sums_s = take(&mut ps, n0)?;
    let counts = take(&mut ps, n0)?;

    // Field buffers inside `work` (the solver reuses it afterwards).
    let field = work.get_mut(..cadd(cmul(nk, 7)?, n0)?).ok_or(internal())?;
    let mut fr: &mut [Point] = field;
    let mut da = take(&mut fr, nk)?;
    let mut db = take(&mut fr, nk)?;
    let mut na = take(&mut fr, nk)?;
    let mut nb = take(&mut fr, nk)?;
    let mut ha = take(&mut fr, nk)?;
    let mut hb = take(&mut fr, nk)?;
    let spatial_tmp = take(&mut fr, nk)?;
    let nbar = take(&mut fr, n0)?;

    // ---- level 0: Δ⁰, separation, anchors, components ----
    let mut anchors_n;
    let loops_n;
    let mut degenerate = 0u32;
    {
        let topo = Topology::build(mesh, topo_buf)?;
        let (r, c, bf) = laps.get_mut(0).ok_or(internal())?;
        laplacian::build(&topo, r, c, bf)?;
        let lap = Laplacian {
            rows: r,
            cols: c,
            boundary: bf,
        };
        let pos0 = spatial_tmp.get_mut(..n0).ok_or(internal())?;
        for (v, p) in mesh.positions().enumerate() {
            set(pos0, v, p)?;
        }
        lap.apply(pos0, 1.0, da)?;
        if dm > 0 || opts.normals.is_some() {
            dirmag::angle_weighted_normals(&topo, nbar)?;
        }
        for i in 0..n0 {
            let d = get(da, i)?;
            let s = match opts.curvature_scale {
                Some(sc) => get(sc, i)?,
                None => 1.0,
            };
            let (mut h, mut nrm) = dirmag::separate(d, get(nbar, i)?);
            if let Some(nn) = opts.normals {
                if let Some(u) = dirmag::normalized(get(nn, i)?) {
                    nrm = u;
                    if h == 0.0 {
                        h = 0.0;
                    }
                }
            }
            h *= s;
            let edited = if opts.normals.is_some() {
                [h * nrm[0], h * nrm[1], h * nrm[2]]
            } else {
                [s * d[0], s * d[1], s * d[2]]
            };
            set(da, i, edited)?;
            set(ha, i, [h, 0.0, 0.0])?;
            set(na, i, nrm)?;
        }
        // Components (union–find over edges) and anchors.
        let parent = labels.get_mut(..n0).ok_or(internal())?;
        for (v, p) in parent.iter_mut().enumerate() {
            *p = v as u32;
        }
        for e in 0..topo.num_edges() as u32 {
            let (a, b) = topo.edge_vertices(e)?;
            let (ra, rb) = (find(parent, a)?, find(parent, b)?);
            if ra != rb {
                let (lo, hi) = if ra < rb { (ra, rb) } else { (rb, ra) };
                set(parent, hi as usize, lo)?;
            }
        }
        for v in 0..n0 as u32 {
            let r = find(parent, v)?;
            set(parent, v as usize, r)?;
        }
        for a in aux.iter_mut() {
            *a = 0;
        }
        let loops = topo.boundary_loops(loop_mark)?;
        for a in anchors_buf.iter_mut().take(loops) {
            *a = NONE;
        }
        for (h, &m) in loop_mark.iter().enumerate() {
            if m == NONE {
                continue;
            }
            let v = topo.origin(h as u32)?;
            let slot = anchors_buf.get_mut(m as usize).ok_or(internal())?;
            *slot = (*slot).min(v);
            set(aux, get(parent, v as usize)? as usize, 1)?;
        }
        anchors_n = loops;
        loops_n = loops;
        for v in 0..n0 {
            let r = get(parent, v)? as usize;
            if get(aux, r)? == 0 {
                set(aux, r, 2)?;
                set(anchors_buf, anchors_n, v as u32)?;
                anchors_n += 1;
            }
        }
        // From here on `aux[root] ≠ 0` means "this component has a boundary".
        for a in aux.iter_mut() {
            *a = u32::from(*a == 1);
        }
    }

    // ---- levels 1..k: subdivide the fields and the warm start ----
    // The spatial level j lives in `out.positions` when k − j is even, else in spatial_tmp.
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
        let nf = faces.len();
        let (lo, hi) = faces.split_at_mut_checked(j.min(nf)).ok_or(internal())?;
        let (src_o, src_i): (&[u32], &[u32]) = if j == 0 {
            (mesh.offsets, mesh.indices)
        } else {
            let f = lo.last().ok_or(internal())?;
            (&*f.0, &*f.1)
        };
        // Destination faces of level j + 1.
        let run = |field: &[Point],
                   dst: &mut [Point],
                   offs: &mut [u32],
                   idx: &mut [u32],
                   topo_buf: &mut [u32]|
         -> Result<()> {
            let m = Mesh::new(field.get(..sj.vertices).ok_or(internal())?, src_o, src_i);
            let topo = Topology::build(m, topo_buf).map_err(non_finite_intermediate)?;
            let mut o = MeshOut::new(dst, offs, idx);
            crate::scheme::subdivide(scheme, &topo, &mut o)?;
            Ok(())
        };
        let dst_faces: (&mut [u32], &mut [u32]) = if j + 1 == k {
            (&mut *out_offs, &mut *out_idx)
        } else {
            let f = hi.first_mut().ok_or(internal())?;
            (&mut *f.0, &mut *f.1)
        };
        let (doffs, didx) = dst_faces;
        // Spatial warm start.
        let (src_sp, dst_sp): (&[Point], &mut [Point]) = if (k - j) % 2 == 0 {
            (&*out_pos, &mut *spatial_tmp)
        } else {
            (&*spatial_tmp, &mut *out_pos)
        };
        run(src_sp, dst_sp, doffs, didx, topo_buf)?;
        if j < dm {
            run(ha, hb, doffs, didx, topo_buf)?;
            run(na, nb, doffs, didx, topo_buf)?;
            for p in nb.iter_mut().take(sn.vertices) {
                match dirmag::normalized(*p) {
                    Some(u) => *p = u,
                    None => degenerate += 1,
                }
            }
            core::mem::swap(&mut ha, &mut hb);
            core::mem::swap(&mut na, &mut nb);
            if j + 1 == dm {
                for i in 0..sn.vertices {
                    let h = get(ha, i)?[0];
                    let u = get(na, i)?;
                    set(da, i, [h * u[0], h * u[1], h * u[2]])?;
                }
            }
        } else {
            run(da, db, doffs, didx, topo_buf)?;
            core::mem::swap(&mut da, &mut db);
        }
    }
    if k == 0 {
        set_faces(mesh, out.offsets, out.indices)?;
    }
    report.dirmag_degenerate = degenerate;
    report.anchors = anchors_n as u32;

    // ---- the hierarchy: Laplacian and edges of every level, component labels ----
    let dummy = rhs;
    for d in dummy.iter_mut() {
        *d = [0.0; 3];
    }
    for j in 0..=k {
        let sj = plan.size(j)?;
        let (o, i): (&[u32], &[u32]) = if j == 0 {
            (mesh.offsets, mesh.indices)
        } else if j == k {
            (
                out.offsets.get(..sj.offsets()?).ok_or(internal())?,
                out.indices.get(..sj.indices).ok_or(internal())?,
            )
        } else {
            let f = faces.get(j - 1).ok_or(internal())?;
            (&*f.0, &*f.1)
        };
        let m = Mesh::new(dummy.get(..sj.vertices).ok_or(internal())?, o, i);
        let topo = Topology::build(m, topo_buf)?;
        if j > 0 {
            let (r, c, bf) = laps.get_mut(j).ok_or(internal())?;
            laplacian::build(&topo, r, c, bf)?;
        }
        if j < k {
            let e = edges.get_mut(j).ok_or(internal())?;
            for id in 0..topo.num_edges() {
                let (a, b) = topo.edge_vertices(id as u32)?;
                set(e, 2 * id, a)?;
                set(e, 2 * id + 1, b)?;
                let la = get(labels, a as usize)?;
                set(labels, sj.vertices + id, la)?;
            }
        }
    }
    let anchors = anchors_buf.get(..anchors_n).ok_or(internal())?;
    for (_, _, bf) in laps.iter_mut() {
        for &a in anchors {
            let f = bf.get_mut(a as usize).ok_or(internal())?;
            *f |= laplacian::PINNED;
        }
    }
    let mut levels = ArrayVec::<SolveLevel<'_>, { MAX_LEVELS + 1 }>::new();
    for j in 0..=k {
        let (r, c, bf) = laps.get(j).ok_or(internal())?;
        levels
            .try_push(SolveLevel {
                lap: Laplacian {
                    rows: r,
                    cols: c,
                    boundary: bf,
                },
                edges: edges.get(j).ok_or(internal())?,
            })
            .map_err(|_| internal())?;
    }

    // ---- δ = 4⁻ᵏ Δᵏ (Δᵏ is in `da`, inside the solver's scratch: copy it out) ----
    let mut c = 1.0;
    for _ in 0..k {
        c *= 0.25;
    }
    let delta = dummy;
    for (d, dk) in delta.iter_mut().zip(da.iter()).take(nk) {
        *d = [c * dk[0], c * dk[1], c * dk[2]];
    }
    // Component centroids of the warm start.
    for ((a, b), c) in sums_x
        .iter_mut()
        .zip(sums_s.iter_mut())
        .zip(counts.iter_mut())
    {
        *a = [0.0; 3];
        *b = [0.0; 3];
        *c = [0.0; 3];
    }
    for (v, p) in out_pos.iter().enumerate() {
        let l = get(labels, v)? as usize;
        let s = sums_s.get_mut(l).ok_or(internal())?;
        *s = [s[0] + p[0], s[1] + p[1], s[2] + p[2]];
        counts.get_mut(l).ok_or(internal())?[0] += 1.0;
    }

    // ---- solve ----
    let sys = System {
        levels: &levels,
        anchors,
        loop_anchors: loops_n,
        anchor_weight: 1.0,
        components: labels,
        open: aux,
    };
    let r = solve::solve(&sys, delta, out_pos, work, &opts.solve)?;
    report.solve = r;
    if !r.converged {
        return Err(Error::new(Status::NotConverged));
    }

    // ---- placement: match every component's centroid to the spatial subdivision ----
    for (v, p) in out_pos.iter().enumerate() {
        let l = get(labels, v)? as usize;
        let s = sums_x.get_mut(l).ok_or(internal())?;
        *s = [s[0] + p[0], s[1] + p[1], s[2] + p[2]];
    }
    for (v, p) in out_pos.iter_mut().enumerate() {
        let l = get(labels, v)? as usize;
        let n = get(counts, l)?[0];
        let (a, b) = (get(sums_s, l)?, get(sums_x, l)?);
        let q = [
            p[0] + (a[0] - b[0]) / n,
            p[1] + (a[1] - b[1]) / n,
            p[2] + (a[2] - b[2]) / n,
        ];
        if !crate::point::is_finite(&q) {
            return Err(Error::at(Status::NumericalFailure, v as u32));
        }
        *p = q;
    }
    Ok(out_sizes)
}

/// The fields subdivided here (`Δ`, `H`, `n`, the warm start) are intermediates: the input
/// was validated by [`plan`], so a non-finite value met while building their topology is an
/// overflow of the computation (`Δ` of a vertex near `1e231` overflows), reported as
/// [`Status::NumericalFailure`] naming the vertex (docs/bad-input-catalogue.md row 15), not
/// as bad input. Found by the `differential` fuzz target
/// (`fuzz/regressions/differential/laplacian-overflow`).
fn non_finite_intermediate(e: Error) -> Error {
    if e.status == Status::NonFiniteInput {
        Error::at(Status::NumericalFailure, e.element)
    } else {
        e
    }
}

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
