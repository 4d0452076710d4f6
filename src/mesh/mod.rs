//! Polygon meshes in caller buffers: the view, validation, half-edge topology built in caller
//! scratch, and the refinement patterns of the schemes.
//!
//! # Buffers
//!
//! * **Positions**: `&[[f64; 3]]`, one point per vertex ([`Mesh::new`]); the C ABI's
//!   `double[3*V]` has exactly this layout (`[f64; 3]` has the alignment of `f64`). Strided
//!   host arrays (`x y z` followed by other attributes) are read in place with
//!   [`Mesh::with_stride`], without copying. Output positions are always packed.
//! * **Faces** in CSR form: `offsets[F + 1]` (`offsets[0] = 0`, non-decreasing,
//!   `offsets[F] = indices.len()`) and `indices[offsets[F]]`; face `f` is
//!   `indices[offsets[f]..offsets[f + 1]]`, counter-clockwise seen from outside.
//!
//! Every count (vertices, faces, corners, output sizes) must be at most [`MAX_COUNT`] so that
//! every index fits a `u32` and `u32::MAX` stays free as the "none" marker [`NONE`].
//!
//! # Policies (decisions where the papers are silent)
//!
//! * **Empty mesh** (no faces, any number of vertices, `offsets = [0]`) is valid: every scheme
//!   returns it with its vertices carried through and no faces. `offsets = []` is
//!   [`Status::BadOffsets`] (the CSR needs `F + 1 ≥ 1` entries).
//! * **Isolated (unreferenced) vertices** are valid and carried through unchanged: primal
//!   schemes keep every old vertex at its index; dual schemes append the isolated vertices, in
//!   index order, after their own points.
//! * **Duplicate faces**: two faces with the same vertex set are
//!   [`Status::DuplicateFace`], whatever their orientation. The
//!   *pillow* (a face and its reverse, a closed two-face component that passes the edge test)
//!   is rejected too: it has no interior, and its vertices are valence-2 spikes for every rule.
//! * The kernel never repairs: the first error found is returned, naming its element.
//!
//! See [`topology`] for the order of the checks and the element each status names.

mod extent;
pub(crate) mod gather;
pub mod refine;
mod sort;
pub mod topology;

pub use extent::{check_extent, MAX_EXTENT, MIN_EXTENT};
pub use topology::{topology_scratch_size, Spoke, Star, Topology};
// The name differential-space subdivision imports.
pub(crate) use topology::topology_scratch_size as topology_scratch_len;

use crate::error::{Error, Result, Status};
use crate::point::Point;

/// The "none" marker in `u32` index arrays (no twin, no face, no half-edge).
pub const NONE: u32 = u32::MAX;

/// The largest vertex, face, corner or output count: every index is below `u32::MAX`, which
/// stays reserved as [`NONE`].
pub const MAX_COUNT: usize = (u32::MAX - 1) as usize;

/// A polygon mesh over caller slices (not validated; see [`Topology::build`]).
#[derive(Clone, Copy, Debug)]
pub struct Mesh<'a> {
    coords: &'a [f64],
    stride: usize,
    num_vertices: usize,
    /// Face offsets into `indices`, `F + 1` entries.
    pub offsets: &'a [u32],
    /// Vertex indices of all faces, face after face.
    pub indices: &'a [u32],
}

impl<'a> Mesh<'a> {
    /// A view of packed positions and the CSR faces; nothing is checked here.
    pub fn new(positions: &'a [Point], offsets: &'a [u32], indices: &'a [u32]) -> Self {
        Mesh {
            coords: positions.as_flattened(),
            stride: 3,
            num_vertices: positions.len(),
            offsets,
            indices,
        }
    }

    /// A view of `num_vertices` positions stored with `stride` `f64`s between consecutive
    /// vertices (`x, y, z` first): vertex `v` is `coords[v·stride .. v·stride + 3]`.
    ///
    /// # Errors
    /// [`Status::InvalidArgument`] for `stride < 3`; [`Status::SizeOverflow`] when the extent
    /// overflows; [`Status::BufferTooSmall`] (with the needed length) when `coords` is shorter
    /// than `(num_vertices − 1)·stride + 3`.
    pub fn with_stride(
        coords: &'a [f64],
        stride: usize,
        num_vertices: usize,
        offsets: &'a [u32],
        indices: &'a [u32],
    ) -> Result<Self> {
        if stride < 3 {
            return Err(Error::new(Status::InvalidArgument));
        }
        if num_vertices > 0 {
            let need = cadd(cmul(num_vertices - 1, stride)?, 3)?;
            if coords.len() < need {
                return Err(Error::too_small(need));
            }
        }
        Ok(Mesh {
            coords,
            stride,
            num_vertices,
            offsets,
            indices,
        })
    }

    /// The number of vertices (referenced or not).
    pub const fn num_vertices(&self) -> usize {
        self.num_vertices
    }

    /// The number of faces, `offsets.len() − 1` (0 for an empty offsets slice).
    pub const fn num_faces(&self) -> usize {
        self.offsets.len().saturating_sub(1)
    }

    /// The number of corners (= half-edges), `indices.len()`.
    pub const fn num_corners(&self) -> usize {
        self.indices.len()
    }

    /// The vertex indices of face `f`, or `None` when `f` or its offsets are out of range.
    pub fn face(&self, f: usize) -> Option<&'a [u32]> {
        let a = *self.offsets.get(f)? as usize;
        let b = *self.offsets.get(f.checked_add(1)?)? as usize;
        self.indices.get(a..b)
    }

    /// The position of vertex `v`.
    #[inline]
    pub fn position(&self, v: u32) -> Option<Point> {
        let v = v as usize;
        if v >= self.num_vertices {
            return None;
        }
        // No overflow: v ≤ num_vertices − 1 and (num_vertices − 1)·stride + 3 ≤ coords.len()
        // (checked by `with_stride`; `new` has stride 3 over the flattened points).
        let a = v * self.stride;
        match self.coords.get(a..a + 3)? {
            &[x, y, z] => Some([x, y, z]),
            _ => None,
        }
    }

    /// The positions of all vertices, in order.
    pub fn positions(&self) -> impl Iterator<Item = Point> + 'a {
        let m = *self;
        (0..self.num_vertices as u32).map(move |v| m.position(v).unwrap_or([f64::NAN; 3]))
    }
}

/// Exact sizes of a mesh: what a subdivision step writes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct MeshSizes {
    /// Number of vertices (points in the positions buffer).
    pub vertices: usize,
    /// Number of faces; the offsets buffer holds `faces + 1` entries.
    pub faces: usize,
    /// Number of corners (entries of the indices buffer).
    pub indices: usize,
}

impl MeshSizes {
    /// Entries of the offsets buffer, `faces + 1`.
    pub fn offsets(&self) -> Result<usize> {
        cadd(self.faces, 1)
    }

    /// Checks that every count is at most [`MAX_COUNT`].
    pub fn check(self) -> Result<MeshSizes> {
        if self.vertices > MAX_COUNT || self.faces > MAX_COUNT || self.indices > MAX_COUNT {
            Err(Error::new(Status::SizeOverflow))
        } else {
            Ok(self)
        }
    }
}

/// Output buffers of one subdivision step. Their contents are unspecified on error.
#[derive(Debug)]
pub struct MeshOut<'a> {
    /// At least [`MeshSizes::vertices`] points.
    pub positions: &'a mut [Point],
    /// At least [`MeshSizes::faces`]` + 1` entries.
    pub offsets: &'a mut [u32],
    /// At least [`MeshSizes::indices`] entries.
    pub indices: &'a mut [u32],
}

impl<'a> MeshOut<'a> {
    /// Bundles three output slices.
    pub fn new(positions: &'a mut [Point], offsets: &'a mut [u32], indices: &'a mut [u32]) -> Self {
        MeshOut {
            positions,
            offsets,
            indices,
        }
    }

    /// [`Status::BufferTooSmall`] (with the needed size of the first short buffer, checked in
    /// the order positions, offsets, indices) unless every buffer holds `sizes`.
    pub fn check(&self, sizes: &MeshSizes) -> Result<()> {
        if self.positions.len() < sizes.vertices {
            return Err(Error::too_small(sizes.vertices));
        }
        let no = sizes.offsets()?;
        if self.offsets.len() < no {
            return Err(Error::too_small(no));
        }
        if self.indices.len() < sizes.indices {
            return Err(Error::too_small(sizes.indices));
        }
        Ok(())
    }
}

// ---- small panic-free helpers shared by the mesh code and the drivers ----

// The internal-error constructor lives in `crate::error` (so that `exec`, which the mesh
// refinement imports, needs nothing from `mesh`); re-exported here for the mesh code and the
// drivers, which take it with `get` and `set`.
pub(crate) use crate::error::internal;

/// `s[i]`, or an internal error.
#[inline]
pub(crate) fn get<T: Copy>(s: &[T], i: usize) -> Result<T> {
    s.get(i).copied().ok_or(internal())
}

/// `s[i] = v`, or an internal error.
#[inline]
pub(crate) fn set<T>(s: &mut [T], i: usize, v: T) -> Result<()> {
    *s.get_mut(i).ok_or(internal())? = v;
    Ok(())
}

/// Checked `a + b` ([`Status::SizeOverflow`]).
#[inline]
pub(crate) fn cadd(a: usize, b: usize) -> Result<usize> {
    a.checked_add(b).ok_or(Error::new(Status::SizeOverflow))
}

/// Checked `a * b` ([`Status::SizeOverflow`]).
#[inline]
pub(crate) fn cmul(a: usize, b: usize) -> Result<usize> {
    a.checked_mul(b).ok_or(Error::new(Status::SizeOverflow))
}

/// `i as u32`, or [`Status::SizeOverflow`] when it does not fit below [`NONE`].
#[inline]
pub(crate) fn idx(i: usize) -> Result<u32> {
    if i > MAX_COUNT {
        Err(Error::new(Status::SizeOverflow))
    } else {
        Ok(i as u32)
    }
}
