//! The half-edge topology of a validated [`Mesh`], held in caller scratch: what OpenSubdiv's
//! `Vtr::Level` is to its refiner. Every scheme reads its neighbourhoods through it.
//!
//! # Half-edges, edges, stars
//!
//! * Half-edge `h` **is corner `h`**: it starts at `indices[h]` and ends at the next corner of
//!   its face. `next`, `prev` and `face` follow from the CSR offsets; `twin` is stored.
//! * **Edges** are numbered in ascending `(min, max)` vertex-key order: the directed-edge table
//!   is sorted by `(min, max, half-edge)` — two stable counting sorts, by `max` then by
//!   `min` — so numbering never depends on input order beyond the vertex indices (no
//!   hashing, whose order is the hasher's, and no `sort_unstable`, which keeps a panic
//!   path). Each edge's representative half-edge runs from `min` to `max` when that direction
//!   exists (always, for interior edges), else it is the only half-edge.
//! * **Stars** ([`Topology::star`]) are walked counter-clockwise (faces are CCW seen from
//!   outside): `h → twin(prev(h))`. An interior vertex's star starts at its lowest-numbered
//!   outgoing half-edge; a boundary vertex's star runs from one boundary neighbour `b0`
//!   (the end of its outgoing boundary half-edge) to the other, `b1` (the start of its incoming
//!   boundary half-edge), so it has `faces + 1` spokes.
//! * **Boundary loops** follow the boundary half-edges (face on their left):
//!   [`Topology::next_boundary`].
//!
//! # Validation order and the element named by each error
//!
//! Topology first, all before any write to caller output, so that bad input never leaves
//! partial output behind. Each class is checked over the whole mesh before the next class:
//!
//! | order | status | element |
//! |---|---|---|
//! | 0 | `SizeOverflow`: a count above [`MAX_COUNT`] | none |
//! | 1 | `BadOffsets`: `offsets` empty, `offsets[0] ≠ 0`, decreasing, or last ≠ `indices.len()` | face |
//! | 2 | `FaceTooSmall`: fewer than 3 corners | face |
//! | 3 | `ValenceTooHigh`: more than [`MAX_FACE_SIZE`] corners | face |
//! | 4 | `IndexOutOfRange` | face |
//! | 5 | `RepeatedVertex` | face |
//! | 6 | `BufferTooSmall`: scratch below [`topology_scratch_size`] | none |
//! | 7 | `DuplicateFace`: two faces on one edge with the same vertex set | the later face |
//! | 7 | `InconsistentOrientation`: two half-edges of one edge in the same direction | the later face |
//! | 7 | `NonManifoldEdge`: three or more faces on one edge | the last face on it |
//! | 8 | `DuplicateFace`: pillow (every edge of a face shared with one other face) | the later face |
//! | 9 | `NonManifoldVertex`: the faces at a vertex are not one disk or half-disk | vertex (lowest) |
//! | 10 | `ValenceTooHigh`: more than [`MAX_VALENCE`] neighbours | vertex |
//! | 11 | `NonFiniteInput`: NaN or ±∞ in any vertex, referenced or not | vertex |
//!
//! Class 7 is reported for the first offending edge in `(min, max)` key order. A duplicate is
//! recognised among the first four faces of an edge; beyond that `NonManifoldEdge` is
//! reported (bounded work on hostile input).
//!
//! # Where things are
//!
//! * `build.rs`: validation (the order of the checks and the element each status names) and
//!   the construction of the arrays;
//! * `arrays.rs`: the layout of the arrays in scratch, their raw view for hot loops, and the
//!   scalar counts that rebuild a view of a derived topology;
//! * `queries.rs`: counts and element queries (faces, half-edges, edges, vertices);
//! * `star.rs`: vertex stars (spokes, counter-clockwise);
//! * `boundary.rs`: boundary neighbours and boundary loops.

mod arrays;
mod boundary;
mod build;
mod queries;
mod star;

pub(crate) use arrays::{regions, Counts, Raw, Regions};
pub use star::{Spoke, Star};

use crate::error::{Error, Result, Status};
use crate::mesh::Mesh;
#[cfg(doc)]
use crate::mesh::MAX_COUNT;
#[cfg(doc)]
use crate::{MAX_FACE_SIZE, MAX_VALENCE};

/// The exact scratch (`u32` entries) that [`Topology::build`] needs for a mesh with
/// `num_vertices` vertices and `num_corners` corners: `4·corners + 3·vertices`.
///
/// # Errors
/// [`Status::SizeOverflow`] when the size does not fit `usize`.
pub fn topology_scratch_size(num_vertices: usize, num_corners: usize) -> Result<usize> {
    let a = num_corners
        .checked_mul(4)
        .ok_or(Error::new(Status::SizeOverflow))?;
    let b = num_vertices
        .checked_mul(3)
        .ok_or(Error::new(Status::SizeOverflow))?;
    a.checked_add(b).ok_or(Error::new(Status::SizeOverflow))
}

/// A validated mesh with its half-edge topology, held in caller scratch.
///
/// Built by [`Topology::build`] (validating) or derived from a parent level's by
/// `refine::child_topology` (multi-level calls); every query is `O(1)` except star walks
/// (`O(valence)`). Queries return `Result` only to stay panic-free: on a built topology they cannot
/// fail for indices in range.
#[derive(Clone, Copy, Debug)]
pub struct Topology<'m, 's> {
    mesh: Mesh<'m>,
    face_of: &'s [u32],
    twin: &'s [u32],
    edge_of: &'s [u32],
    edge_he: &'s [u32],
    vert_he: &'s [u32],
    valence: &'s [u32],
    bnd_rank: &'s [u32],
    n_boundary_edges: usize,
    n_boundary_vertices: usize,
    n_isolated: usize,
    interior_spokes: usize,
    boundary_spokes: usize,
    max_face: usize,
    min_face: usize,
}
