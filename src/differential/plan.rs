//! Planning a differential-space subdivision: validation of the mesh and the options, the
//! sizes of every level, and the scratch the call needs, all before any point is computed, so
//! a caller can allocate once (the crate allocates nothing).

use arrayvec::ArrayVec;

use super::options::DifferentialOptions;
use super::solve;
use crate::error::{Error, Result, Status};
use crate::mesh::{cadd, cmul, internal, topology_scratch_len, Mesh, MeshSizes, Topology};
use crate::scheme::MAX_LEVELS;

/// Sizes of every level and the scratch of [`subdivide`](super::subdivide).
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
    /// Whether edits are planned (they need the unedited result kept as the reference).
    edited: bool,
}

impl DifferentialPlan {
    /// The output sizes.
    pub fn output(&self) -> MeshSizes {
        self.sizes.get(self.levels).copied().unwrap_or_default()
    }

    /// The sizes of level `j`.
    pub(super) fn size(&self, j: usize) -> Result<MeshSizes> {
        self.sizes.get(j).copied().ok_or(internal())
    }

    /// Where every buffer of [`subdivide`](super::subdivide) lives in the two scratch arrays.
    pub(super) fn layout(&self) -> Result<Layout> {
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
        u.work = solve::solve_scratch_size(&counts)?.max(fields);
        u.reference = if self.edited { nk } else { 0 };
        u.points = cadd(cadd(cadd(u.work, nk)?, cmul(n0, 3)?)?, u.reference)?;
        u.u32s = cadd(
            cadd(cadd(u.topo, u.faces)?, cadd(u.lap, u.edges)?)?,
            u.marks,
        )?;
        Ok(u)
    }
}

/// The sizes of the buffers [`subdivide`](super::subdivide) carves from its scratch, in the
/// order it carves them.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Layout {
    /// `u32`: the topology of one level (the finest is the largest).
    pub(super) topo: usize,
    /// `u32`: the faces (offsets and indices) of levels `1..k−1` (level `k`'s go to the output).
    pub(super) faces: usize,
    /// `u32`: the Laplacian of every level `0..=k` (rows, columns and vertex flags).
    pub(super) lap: usize,
    /// `u32`: the edges of levels `0..k−1` as vertex pairs, the parents of the next level's
    /// edge points.
    pub(super) edges: usize,
    /// `u32`: component labels of the finest level, the per-component boundary marks, the
    /// anchors and the boundary-loop marks of level 0.
    pub(super) marks: usize,
    /// Points: the solver's scratch, which first holds the subdivided fields.
    pub(super) work: usize,
    /// Points: the unedited result, kept as the reference of the edits (`nk` when the call
    /// has edits, else 0).
    pub(super) reference: usize,
    /// Points in all: `work`, the right-hand side, three per-component sums and the
    /// reference.
    pub(super) points: usize,
    /// `u32` in all.
    pub(super) u32s: usize,
}

/// `u32` scratch [`plan`] needs (the input topology).
///
/// # Errors
/// [`Status::SizeOverflow`].
pub fn plan_scratch_size(mesh: &Mesh<'_>) -> Result<usize> {
    crate::scheme::scratch_size(mesh)
}

/// Validates `mesh` (triangles only) and `opts` and plans the call.
///
/// # Errors
/// [`Status::SchemeNotBuilt`] first, when this build does not contain differential-space
/// subdivision with the stencil ([`Stencil::is_built`](super::Stencil::is_built));
/// validation errors of [`Topology::build`]; [`Status::UnsupportedFaceType`] naming the first
/// face that is not a triangle; [`Status::InvalidArgument`] for more than [`MAX_LEVELS`]
/// levels or a bad tolerance, and for an edit slice whose length is not the vertex count
/// (naming the first index without a partner);
/// [`Status::NonFiniteInput`] for a non-finite edit value (naming the vertex);
/// [`Status::SizeOverflow`]; [`Status::ValenceTooHigh`]; [`Status::NumericalFailure`] for a
/// mesh outside the sizes the normal equations can represent
/// ([`crate::mesh::check_extent`]).
pub fn plan(
    mesh: Mesh<'_>,
    opts: &DifferentialOptions<'_>,
    scratch: &mut [u32],
) -> Result<DifferentialPlan> {
    opts.stencil.check_built()?;
    let ok = |t: f64| t.is_finite() && t >= 0.0;
    if opts.levels > MAX_LEVELS || !ok(opts.solve.tolerance) || !ok(opts.solve.coarse_tolerance) {
        return Err(Error::new(Status::InvalidArgument));
    }
    let n = mesh.num_vertices();
    if let Some(s) = opts.curvature_scale {
        check_len(s.len(), n)?;
        if let Some(i) = s.iter().position(|x| !x.is_finite()) {
            return Err(Error::at(Status::NonFiniteInput, i as u32));
        }
    }
    if let Some(s) = opts.normals {
        check_len(s.len(), n)?;
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
    // The normal equations hold squared lengths: outside this range they underflow or
    // overflow and the shape is lost (mesh/extent.rs).
    crate::mesh::check_extent(&mesh)?;
    let lp = crate::scheme::plan_levels(opts.stencil.scheme(), mesh, opts.levels, scratch)?;
    let mut p = DifferentialPlan {
        levels: opts.levels,
        sizes: lp.sizes,
        scratch_u32: 0,
        scratch_points: 0,
        edited: false,
    };
    p.edited = opts.curvature_scale.is_some() || opts.normals.is_some();
    let l = p.layout()?;
    p.scratch_u32 = l.u32s;
    p.scratch_points = l.points;
    Ok(p)
}

/// An edit slice must have one entry per control vertex; otherwise
/// [`Status::InvalidArgument`] naming the first index that has no partner: the first vertex
/// without a value (a short slice) or the first value without a vertex (a long one).
fn check_len(len: usize, n: usize) -> Result<()> {
    if len == n {
        Ok(())
    } else {
        Err(Error::at(Status::InvalidArgument, len.min(n) as u32))
    }
}
