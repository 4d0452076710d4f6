//! The topology of a refined level derived from the topology of the level it was refined from
//! and the refinement pattern (the way OpenSubdiv's `Vtr::Refinement` builds a child level
//! from its parent), instead of validating and sorting the refined mesh again.
//!
//! A refined valid mesh is valid by construction, and every array of [`Topology::build`] on
//! it is a combinatorial function of the parent's arrays. For the primal patterns
//! ([`super::Pattern::Quads`], [`super::Pattern::Split1To4`]), which keep the old vertices
//! and add edge points (Doo–Sabin's corner cut, whose points are the parent's corners, is
//! described in `corner_cut_topology.rs`):
//!
//! * **twins**: each child half-edge lies on a half of a parent edge (its twin is in the
//!   child face of the neighbouring parent corner) or inside a parent face;
//! * **edge numbers**: the child's `(min, max)` key order puts first the edges from each old
//!   vertex `v` to the edge points of its edges, in vertex then parent-edge order (edge
//!   points are numbered after all old vertices, `V + e`), then the edges that start at an
//!   edge point `V + e`, in parent-edge order, each group sorted by its other end (a face
//!   point `V + E + f` for [`super::Pattern::Quads`], a later edge point for
//!   [`super::Pattern::Split1To4`]). A cursor per old vertex (the rank of `e` among `v`'s edges)
//!   gives the first group, a running counter the second: no sort;
//! * **stars**: an interior vertex's star starts at its lowest outgoing half-edge, a boundary
//!   vertex's at its outgoing boundary half-edge. Child half-edge numbers grow with the parent
//!   corner they come from, so an old vertex keeps the image of its parent start; an edge or
//!   face point takes the smallest of its (at most six) outgoing half-edges;
//! * **valences, boundary ranks, sums**: the pattern's counts (also used by the plan,
//!   `LevelCounts`).
//!
//! The result is the same topology as [`Topology::build`] on the refined mesh, array for
//! array (tested below against `build` on meshes with boundaries, isolated vertices and mixed
//! faces, over several levels), so every scheme, linear and Möbius, reads the same
//! neighbourhoods in the same order and writes the same bits. The refined mesh is checked
//! against the pattern while deriving (every corner the derivation relies on): a mismatch
//! is an internal error, never a wrong topology.

//!
//! This file holds what the derivations of `Quads` and `Split1To4` share (the edges from old
//! vertices to edge points, the old vertices' arrays) and the tests of all three; each
//! derivation lives with its pattern (Doo–Sabin's [`super::Pattern::CornerCut`], whose
//! vertices are the parent's corners and whose edges are numbered by a prefix sum, in
//! `corner_cut_topology.rs`), and [`super::child_topology`] dispatches.

use arrayvec::ArrayVec;

use crate::error::Result;
use crate::exec::{self, Executor, MAX_CHUNKS};
use crate::mesh::topology::{Raw, Regions};
use crate::mesh::{get, internal, set, Topology, NONE};

/// `a == b`, or an internal error (the refined mesh is not the pattern's).
#[inline]
pub(super) fn check_eq(a: u32, b: u32) -> Result<()> {
    if a == b {
        Ok(())
    } else {
        Err(internal())
    }
}

/// `next(h)` of the parent ([`Raw::next_prev_face`]: no lookup on an all-quad or
/// all-triangle mesh).
#[inline]
pub(super) fn next_fast(par: &Raw<'_, '_>, h: u32) -> Result<u32> {
    Ok(par.next_prev_face(h)?.0)
}

/// A range of parent faces `[faces.0, faces.1)` and the child's `twin` and `face_of`
/// entries of the child half-edges made from those faces, from child half-edge `first` on
/// (what one chunk of [`face_spans`] writes).
#[derive(Debug)]
pub(super) struct FaceSpan<'a> {
    pub(super) faces: (usize, usize),
    pub(super) first: usize,
    pub(super) twin: &'a mut [u32],
    pub(super) face_of: &'a mut [u32],
}

/// Runs `f` on the parent faces in the chunks of `exec`. A child half-edge's twin and face
/// depend only on the parent face it comes from, and the child half-edges of parent face
/// `f` start at `child_he(f)` (increasing in `f`), so the chunks write disjoint ranges of
/// `r.twin` and `r.face_of` and the arrays are the same for every executor. One chunk runs
/// inline, without building the chunk list.
pub(super) fn face_spans<F>(
    nf: usize,
    r: &mut Regions<'_>,
    child_he: impl Fn(usize) -> Result<usize>,
    exec: &dyn Executor,
    f: F,
) -> Result<()>
where
    F: Fn(&mut FaceSpan<'_>) -> Result<()> + Sync,
{
    let k = exec::chunk_count(exec, nf);
    if k <= 1 {
        return exec::own_frame(|| {
            f(&mut FaceSpan {
                faces: (0, nf),
                first: 0,
                twin: &mut *r.twin,
                face_of: &mut *r.face_of,
            })
        });
    }
    split_face_spans(nf, r, &child_he, exec, k, &f)
}

/// [`face_spans`] in `k ≥ 2` chunks (out of line: the one-chunk path keeps a small stack
/// frame).
#[inline(never)]
fn split_face_spans(
    nf: usize,
    r: &mut Regions<'_>,
    child_he: &dyn Fn(usize) -> Result<usize>,
    exec: &dyn Executor,
    k: usize,
    f: &(dyn Fn(&mut FaceSpan<'_>) -> Result<()> + Sync),
) -> Result<()> {
    let (mut twin, mut face_of): (&mut [u32], &mut [u32]) = (&mut *r.twin, &mut *r.face_of);
    let mut spans = ArrayVec::<FaceSpan<'_>, MAX_CHUNKS>::new();
    for i in 0..k {
        let (f0, f1) = exec::chunk_range(nf, k, i);
        let (h0, h1) = (child_he(f0)?, child_he(f1)?);
        let len = h1.checked_sub(h0).ok_or(internal())?;
        spans
            .try_push(FaceSpan {
                faces: (f0, f1),
                first: h0,
                twin: exec::take_front(&mut twin, len)?,
                face_of: exec::take_front(&mut face_of, len)?,
            })
            .map_err(|_| internal())?;
    }
    exec::parts(exec, &mut spans, |s| s.faces.1 - s.faces.0, |s, _| f(s)).map(|_| ())
}

/// Writes the first group of child edges (module docs): for every parent edge `e`, the
/// edges `(a, V + e)` and `(b, V + e)` from its ends to its edge point, numbered by a
/// cursor per old vertex (kept in the first `V` entries of the child's boundary-rank
/// region, which [`old_vertices`] overwrites afterwards). `image(h)` is the child
/// half-edge from `origin(h)` to the edge point of `h`'s edge, `back(h)` the one from the
/// edge point of `h`'s edge to `dest(h)`. Returns the number of edges written (`2E`).
pub(super) fn spoke_edges(
    parent: &Topology<'_, '_>,
    r: &mut Regions<'_>,
    image: impl Fn(u32) -> Result<u32>,
    back: impl Fn(u32) -> Result<u32>,
) -> Result<usize> {
    let par = parent.raw();
    let nv = parent.num_vertices();
    let cursor = r.bnd_rank.get_mut(..nv).ok_or(internal())?;
    let mut acc = 0u32;
    for (c, &n) in cursor.iter_mut().zip(par.valence) {
        *c = acc;
        acc += n;
    }
    let indices = par.indices;
    for &h in par.edge_he {
        let t = get(par.twin, h as usize)?;
        let a = get(indices, h as usize)?;
        let b = get(indices, next_fast(&par, h)? as usize)?;
        // (a, V + e): a -> E is image(h), E -> a is back(t).
        let ia = get(cursor, a as usize)?;
        set(cursor, a as usize, ia + 1)?;
        let fwd = image(h)?;
        set(r.edge_of, fwd as usize, ia)?;
        set(r.edge_he, ia as usize, fwd)?;
        // (b, V + e): b -> E is image(t), E -> b is back(h).
        let ib = get(cursor, b as usize)?;
        set(cursor, b as usize, ib + 1)?;
        let bk = back(h)?;
        set(r.edge_of, bk as usize, ib)?;
        if t == NONE {
            set(r.edge_he, ib as usize, bk)?;
        } else {
            set(r.edge_of, back(t)? as usize, ia)?;
            let it = image(t)?;
            set(r.edge_of, it as usize, ib)?;
            set(r.edge_he, ib as usize, it)?;
        }
    }
    if acc as usize != 2 * parent.num_edges() {
        return Err(internal());
    }
    Ok(acc as usize)
}

/// The old vertices of the child: same valence and boundary rank, star start the image
/// of the parent's (`image`, increasing in the parent half-edge).
pub(super) fn old_vertices(
    parent: &Topology<'_, '_>,
    r: &mut Regions<'_>,
    image: impl Fn(u32) -> Result<u32>,
) -> Result<()> {
    let par = parent.raw();
    for v in 0..parent.num_vertices() {
        let vh = get(par.vert_he, v)?;
        set(r.vert_he, v, if vh == NONE { NONE } else { image(vh)? })?;
        set(r.valence, v, get(par.valence, v)?)?;
        set(r.bnd_rank, v, get(par.bnd_rank, v)?)?;
    }
    Ok(())
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::indexing_slicing)]
mod tests {
    use crate::error::Error;
    use crate::exec::testing::{take, Reverse};
    use crate::exec::Serial;
    use crate::mesh::refine::fixtures::{cube, grid_positions, mixed_open_dual};
    use crate::mesh::refine::{
        child_topology, derivable, pattern_size, write_pattern, write_pattern_with, Pattern,
    };
    use crate::mesh::{topology_scratch_size, Mesh, Topology};
    use crate::point::Point;
    use arrayvec::ArrayVec;

    /// `u32` and point arenas the levels of one test are carved from (no allocation in the
    /// core, not even in its tests): every level keeps its buffers while the next is built.
    const ARENA_U32: usize = 1 << 17;
    const ARENA_POINTS: usize = 1 << 12;

    /// Every array and count of two topologies of the same mesh.
    fn assert_same(a: &Topology<'_, '_>, b: &Topology<'_, '_>, what: (Pattern, usize)) {
        let (ra, rb) = (a.raw(), b.raw());
        assert_eq!(ra.face_of, rb.face_of, "{what:?}: faces of half-edges");
        assert_eq!(ra.twin, rb.twin, "{what:?}: twins");
        assert_eq!(ra.edge_of, rb.edge_of, "{what:?}: edge numbers");
        assert_eq!(ra.edge_he, rb.edge_he, "{what:?}: edge representatives");
        assert_eq!(ra.vert_he, rb.vert_he, "{what:?}: star starts");
        assert_eq!(ra.valence, rb.valence, "{what:?}: valences");
        assert_eq!(ra.bnd_rank, rb.bnd_rank, "{what:?}: boundary ranks");
        assert_eq!(a.counts(), b.counts(), "{what:?}: counts (pattern, level)");
    }

    /// `levels` refinements of `pattern`, each level's topology derived from the previous
    /// derived one and compared with [`Topology::build`] on the refined mesh.
    /// Every face's corners start at each of its corners in turn (`rot` + the face index):
    /// the faces' first corners decide which half-edge starts a star and which child
    /// half-edges come first, so every case of the derivation is met.
    fn derive_equals_build(
        pattern: Pattern,
        pos: &[Point],
        offs: &[u32],
        idx: &[u32],
        levels: usize,
    ) {
        for rot in 0..4 {
            let mut rotated: ArrayVec<u32, 64> = ArrayVec::new();
            for (f, w) in offs.windows(2).enumerate() {
                let face = &idx[w[0] as usize..w[1] as usize];
                let r = (rot + f) % face.len();
                rotated
                    .try_extend_from_slice(&face[r..])
                    .and_then(|()| rotated.try_extend_from_slice(&face[..r]))
                    .unwrap();
            }
            derive_levels(pattern, pos, offs, &rotated, levels);
        }
    }

    fn derive_levels(pattern: Pattern, pos: &[Point], offs: &[u32], idx: &[u32], levels: usize) {
        let mut store_u32 = [0u32; ARENA_U32];
        let mut store_points = [[0.0f64; 3]; ARENA_POINTS];
        let mut arena_u32: &mut [u32] = &mut store_u32;
        let mut arena_points: &mut [Point] = &mut store_points;
        let mesh = Mesh::new(pos, offs, idx);
        let need = topology_scratch_size(mesh.num_vertices(), mesh.num_corners()).unwrap();
        let mut topo = Topology::build(mesh, take(&mut arena_u32, need)).unwrap();
        let mut short = [0u32; 1 << 14];
        for k in 1..=levels {
            let sz = pattern_size(pattern, &topo).unwrap();
            let o = take(&mut arena_u32, sz.faces + 1);
            let i = take(&mut arena_u32, sz.indices);
            write_pattern(pattern, &topo, o, i).unwrap();
            let (o, i): (&[u32], &[u32]) = (o, i);
            // Any finite positions: the topology does not read them.
            let p = take(&mut arena_points, sz.vertices);
            for (v, q) in p.iter_mut().enumerate() {
                *q = [v as f64, 0.5, -1.0];
            }
            let child = Mesh::new(p, o, i);
            let need = topology_scratch_size(sz.vertices, sz.indices).unwrap();
            // Garbage in the derived scratch: every entry the topology uses must be written.
            let sd = take(&mut arena_u32, need);
            sd.fill(0xdead_beef);
            let sb = take(&mut arena_u32, need);
            assert_eq!(
                child_topology(&topo, pattern, child, &mut short[..need - 1], &Serial).unwrap_err(),
                Error::too_small(need)
            );
            let derived = child_topology(&topo, pattern, child, sd, &Serial).unwrap();
            let built = Topology::build(child, sb).unwrap();
            assert_same(&derived, &built, (pattern, k));
            // In 3 and 7 chunks run in reverse order: the same faces and arrays.
            for chunks in [3, 7] {
                let exec = Reverse(chunks);
                let (o2, i2) = (take(&mut arena_u32, o.len()), take(&mut arena_u32, i.len()));
                o2.fill(0xdead_beef);
                i2.fill(0xdead_beef);
                write_pattern_with(pattern, &topo, o2, i2, &exec).unwrap();
                assert_eq!(
                    (&*o2, &*i2),
                    (o, i),
                    "{pattern:?} level {k}, {chunks} chunks"
                );
                let sc = take(&mut arena_u32, need);
                sc.fill(0xdead_beef);
                let chunked = child_topology(&topo, pattern, child, sc, &exec).unwrap();
                assert_same(&chunked, &built, (pattern, k));
            }
            topo = derived;
        }
    }

    #[test]
    fn quads_cube() {
        let (pos, offs, idx) = cube();
        derive_equals_build(Pattern::Quads, &pos, &offs, &idx, 3);
    }

    /// Quads, triangles and a pentagon with a boundary and an isolated vertex.
    #[test]
    fn quads_mixed_open_with_isolated_vertex() {
        let pos = grid_positions::<16>();
        let idx = [
            0, 1, 5, 4, 1, 2, 6, 5, 2, 3, 7, 2, 7, 6, 4, 5, 9, 8, 5, 6, 10, 9, 6, 7, 11, 10, 9, 10,
            14, 13, 12,
        ];
        let offs = [0, 4, 8, 11, 14, 18, 22, 26, 31];
        derive_equals_build(Pattern::Quads, &pos, &offs, &idx, 3);
    }

    #[test]
    fn split_octahedron() {
        let pos: [Point; 6] = [
            [1.0, 0.0, 0.0],
            [-1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, -1.0, 0.0],
            [0.0, 0.0, 1.0],
            [0.0, 0.0, -1.0],
        ];
        let idx = [
            0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5,
        ];
        let offs: [u32; 9] = core::array::from_fn(|f| 3 * f as u32);
        derive_equals_build(Pattern::Split1To4, &pos, &offs, &idx, 3);
    }

    /// A triangulated open grid, a second component and an isolated vertex.
    #[test]
    fn split_open_two_components_with_isolated_vertex() {
        let pos = grid_positions::<16>();
        let mut idx: ArrayVec<u32, 64> = ArrayVec::new();
        for j in 0..2u32 {
            for i in 0..3u32 {
                let a = 4 * j + i;
                let (b, c, d) = (a + 1, a + 5, a + 4);
                if (i + j) % 2 == 0 {
                    idx.try_extend_from_slice(&[a, b, c, a, c, d]).unwrap();
                } else {
                    idx.try_extend_from_slice(&[a, b, d, b, c, d]).unwrap();
                }
            }
        }
        idx.try_extend_from_slice(&[13, 12, 14]).unwrap();
        let offs: ArrayVec<u32, 32> = (0..=idx.len() as u32 / 3).map(|f| 3 * f).collect();
        derive_equals_build(Pattern::Split1To4, &pos, &offs, &idx, 3);
    }

    #[test]
    fn corner_cut_cube() {
        let (pos, offs, idx) = cube();
        derive_equals_build(Pattern::CornerCut, &pos, &offs, &idx, 3);
    }

    /// Quads, triangles and a pentagon with a boundary, three interior vertices (5, 6, 9) and
    /// two isolated ones (3, 15): boundary points of every valence, E-faces with one or two
    /// ends on the boundary, isolated vertices after the points.
    #[test]
    fn corner_cut_mixed_open_with_isolated_vertices() {
        let (pos, offs, idx) = mixed_open_dual();
        derive_equals_build(Pattern::CornerCut, &pos, &offs, &idx, 3);
    }

    /// An open fan of three triangles and a quad around boundary vertex 0: corners whose
    /// two edges are both interior at a boundary vertex (their outgoing boundary half-edge
    /// is in an E-face), and a second boundary loop through the quad.
    #[test]
    fn corner_cut_open_fan() {
        let pos = grid_positions::<8>();
        let idx = [0, 1, 2, 0, 2, 3, 0, 3, 4, 0, 4, 6, 5];
        let offs = [0, 3, 6, 9, 13];
        derive_equals_build(Pattern::CornerCut, &pos, &offs, &idx, 3);
    }

    /// A Doo–Sabin child whose faces are not the pattern's (two corners of an F-face, of an
    /// E-face or of a V-face swapped, or an offset moved) is refused, never described wrongly.
    #[test]
    fn corner_cut_wrong_child_is_an_error() {
        let (pos, offs, idx) = cube();
        let mesh = Mesh::new(&pos, &offs, &idx);
        let mut sc = [0u32; 256];
        let need = topology_scratch_size(8, 24).unwrap();
        let topo = Topology::build(mesh, &mut sc[..need]).unwrap();
        let sz = pattern_size(Pattern::CornerCut, &topo).unwrap();
        let (mut o, mut i) = ([0u32; 64], [0u32; 128]);
        let (o, i) = (&mut o[..sz.faces + 1], &mut i[..sz.indices]);
        write_pattern(Pattern::CornerCut, &topo, o, i).unwrap();
        let p = [[0.0; 3]; 64];
        let mut s2 = [0u32; 1024];
        let s2 = &mut s2[..topology_scratch_size(sz.vertices, sz.indices).unwrap()];
        let child = Mesh::new(&p[..sz.vertices], o, i);
        assert!(child_topology(&topo, Pattern::CornerCut, child, s2, &Serial).is_ok());
        // F-face 0 (corners 0..4), E-face 0 (24..28), V-face 0 (the first after the 12 E-faces).
        let v0 = o[6 + 12] as usize;
        for (a, b) in [(0, 1), (24, 25), (v0, v0 + 1)] {
            let mut bad = [0u32; 128];
            let bad = &mut bad[..sz.indices];
            bad.copy_from_slice(i);
            bad.swap(a, b);
            let child = Mesh::new(&p[..sz.vertices], o, bad);
            assert!(
                child_topology(&topo, Pattern::CornerCut, child, s2, &Serial).is_err(),
                "corners {a} and {b} swapped"
            );
        }
        let mut moved = [0u32; 64];
        let moved = &mut moved[..sz.faces + 1];
        moved.copy_from_slice(o);
        moved[7] += 1;
        let child = Mesh::new(&p[..sz.vertices], moved, i);
        assert!(child_topology(&topo, Pattern::CornerCut, child, s2, &Serial).is_err());
    }

    /// A child that is not the pattern's is refused, never described wrongly.
    #[test]
    fn wrong_child_is_an_error() {
        let pos = grid_positions::<4>();
        let (offs, idx) = ([0u32, 3, 6], [0u32, 1, 2, 0, 2, 3]);
        let mesh = Mesh::new(&pos, &offs, &idx);
        let mut sc = [0u32; 64];
        let need = topology_scratch_size(4, 6).unwrap();
        let topo = Topology::build(mesh, &mut sc[..need]).unwrap();
        let sz = pattern_size(Pattern::Split1To4, &topo).unwrap();
        let (mut o, mut i) = ([0u32; 64], [0u32; 64]);
        let (o, i) = (&mut o[..sz.faces + 1], &mut i[..sz.indices]);
        write_pattern(Pattern::Split1To4, &topo, o, i).unwrap();
        i.swap(0, 1);
        let p = [[0.0; 3]; 64];
        let child = Mesh::new(&p[..sz.vertices], o, i);
        let mut s2 = [0u32; 512];
        let s2 = &mut s2[..topology_scratch_size(sz.vertices, sz.indices).unwrap()];
        assert!(child_topology(&topo, Pattern::Split1To4, child, s2, &Serial).is_err());
        assert!(child_topology(&topo, Pattern::Quads, child, s2, &Serial).is_err());
        assert!(child_topology(&topo, Pattern::Dual, child, s2, &Serial).is_err());
        assert!(!derivable(Pattern::Dual) && derivable(Pattern::CornerCut));
    }
}
