//! The topology of a refined level derived from the topology of the level it was refined from
//! and the refinement pattern (the way OpenSubdiv's `Vtr::Refinement` builds a child level
//! from its parent), instead of validating and sorting the refined mesh again.
//!
//! A refined valid mesh is valid by construction, and every array of [`Topology::build`] on
//! it is a combinatorial function of the parent's arrays:
//!
//! * **twins**: each child half-edge lies on a half of a parent edge (its twin is in the
//!   child face of the neighbouring parent corner) or inside a parent face;
//! * **edge numbers**: the child's `(min, max)` key order puts first the edges from each old
//!   vertex `v` to the edge points of its edges, in vertex then parent-edge order (edge
//!   points are numbered after all old vertices, `V + e`), then the edges that start at an
//!   edge point `V + e`, in parent-edge order, each group sorted by its other end (a face
//!   point `V + E + f` for [`Pattern::Quads`], a later edge point for
//!   [`Pattern::Split1To4`]). A cursor per old vertex (the rank of `e` among `v`'s edges)
//!   gives the first group, a running counter the second: no sort;
//! * **stars**: an interior vertex's star starts at its lowest outgoing half-edge, a boundary
//!   vertex's at its outgoing boundary half-edge. Child half-edge numbers grow with the parent
//!   corner they come from, so an old vertex keeps the image of its parent start; an edge or
//!   face point takes the smallest of its (at most six) outgoing half-edges;
//! * **valences, boundary ranks, sums**: the pattern's counts (also used by the plan,
//!   [`crate::scheme::levels`]).
//!
//! The result is the same topology as [`Topology::build`] on the refined mesh, array for
//! array (tested below against `build` on meshes with boundaries, isolated vertices and mixed
//! faces, over several levels), so every scheme, linear and Möbius, reads the same
//! neighbourhoods in the same order and writes the same bits. The refined mesh is checked
//! against the pattern while deriving (every corner the derivation relies on): a mismatch
//! is an internal error, never a wrong topology.

use super::{internal, regions, Counts, Mesh, Regions, Result, Topology, NONE};
use crate::mesh::refine::Pattern;
use crate::mesh::{get, set, MAX_COUNT};
use crate::MAX_VALENCE;

/// Whether [`Topology::refined`] derives the child topology of `pattern`.
pub(crate) fn derivable(pattern: Pattern) -> bool {
    matches!(pattern, Pattern::Quads | Pattern::Split1To4)
}

/// `a == b`, or an internal error (the refined mesh is not the pattern's).
#[inline]
fn check_eq(a: u32, b: u32) -> Result<()> {
    if a == b {
        Ok(())
    } else {
        Err(internal())
    }
}

impl<'m, 's> Topology<'m, 's> {
    /// `next(h)` ([`super::Raw::next_prev_face`]: no lookup on an all-quad or all-triangle
    /// mesh).
    #[inline]
    fn next_fast(&self, h: u32) -> Result<u32> {
        Ok(self.raw().next_prev_face(h)?.0)
    }

    /// Writes the first group of child edges (module docs): for every parent edge `e`, the
    /// edges `(a, V + e)` and `(b, V + e)` from its ends to its edge point, numbered by a
    /// cursor per old vertex (kept in the first `V` entries of the child's boundary-rank
    /// region, which [`Topology::old_vertices`] overwrites afterwards). `image(h)` is the child
    /// half-edge from `origin(h)` to the edge point of `h`'s edge, `back(h)` the one from the
    /// edge point of `h`'s edge to `dest(h)`. Returns the number of edges written (`2E`).
    fn spoke_edges(
        &self,
        r: &mut Regions<'_>,
        image: impl Fn(u32) -> Result<u32>,
        back: impl Fn(u32) -> Result<u32>,
    ) -> Result<usize> {
        let nv = self.num_vertices();
        let cursor = r.bnd_rank.get_mut(..nv).ok_or(internal())?;
        let mut acc = 0u32;
        for (c, &n) in cursor.iter_mut().zip(self.valence) {
            *c = acc;
            acc += n;
        }
        let indices = self.mesh.indices;
        for &h in self.edge_he {
            let t = get(self.twin, h as usize)?;
            let a = get(indices, h as usize)?;
            let b = get(indices, self.next_fast(h)? as usize)?;
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
        if acc as usize != 2 * self.num_edges() {
            return Err(internal());
        }
        Ok(acc as usize)
    }

    /// The old vertices of the child: same valence and boundary rank, star start the image
    /// of the parent's (`image`, increasing in the parent half-edge).
    fn old_vertices(&self, r: &mut Regions<'_>, image: impl Fn(u32) -> Result<u32>) -> Result<()> {
        for v in 0..self.num_vertices() {
            let vh = get(self.vert_he, v)?;
            set(r.vert_he, v, if vh == NONE { NONE } else { image(vh)? })?;
            set(r.valence, v, get(self.valence, v)?)?;
            set(r.bnd_rank, v, get(self.bnd_rank, v)?)?;
        }
        Ok(())
    }

    /// The child topology of `pattern` ([`derivable`]) on `mesh`, the level that
    /// [`crate::mesh::refine::write_pattern`] wrote from this topology, in `scratch`
    /// ([`crate::mesh::topology_scratch_len`] of the child): the same arrays as [`Topology::build`] on
    /// `mesh` (module docs).
    ///
    /// # Errors
    /// [`crate::Status::BufferTooSmall`] with the needed length; an internal error when
    /// `mesh` is not this pattern's child or the pattern is not derivable.
    pub(crate) fn refined<'m2, 's2>(
        &self,
        pattern: Pattern,
        mesh: Mesh<'m2>,
        scratch: &'s2 mut [u32],
    ) -> Result<Topology<'m2, 's2>> {
        let counts = match pattern {
            Pattern::Quads => self.refine_quads(&mesh, scratch)?,
            Pattern::Split1To4 => self.refine_split(&mesh, scratch)?,
            _ => return Err(internal()),
        };
        Topology::from_parts(mesh, scratch, counts)
    }

    /// [`Pattern::Quads`]: corner `h` of face `f` becomes quad `h`, half-edges `4h..4h+4`:
    /// `v → E(h)`, `E(h) → F(f)`, `F(f) → E(prev h)`, `E(prev h) → v`.
    fn refine_quads(&self, mesh: &Mesh<'_>, scratch: &mut [u32]) -> Result<Counts> {
        let (nv, ne, nf, nh) = (
            self.num_vertices(),
            self.num_edges(),
            self.num_faces(),
            self.num_half_edges(),
        );
        let nv2 = nv + ne + nf;
        let nh2 = nh.checked_mul(4).ok_or(internal())?;
        if nv2 > MAX_COUNT
            || nh2 > MAX_COUNT
            || mesh.num_vertices() != nv2
            || mesh.num_corners() != nh2
            || mesh.num_faces() != nh
        {
            return Err(internal());
        }
        let mut r = regions(scratch, nv2, nh2)?;
        let (nv32, ne32) = (nv as u32, ne as u32);
        let offsets = self.mesh.offsets;
        let indices = self.mesh.indices;
        let (new_offsets, new_indices) = (mesh.offsets, mesh.indices);
        check_eq(get(new_offsets, 0)?, 0)?;
        for f in 0..nf {
            let a = get(offsets, f)?;
            let b = get(offsets, f + 1)?;
            let fp = nv32 + ne32 + f as u32;
            for h in a..b {
                let nx = if h + 1 == b { a } else { h + 1 };
                let p = if h == a { b - 1 } else { h - 1 };
                let t = get(self.twin, h as usize)?;
                let tp = get(self.twin, p as usize)?;
                let q = 4 * h as usize;
                let across = if t == NONE {
                    NONE
                } else {
                    4 * self.next_fast(t)? + 3
                };
                let back = if tp == NONE { NONE } else { 4 * tp };
                let Some([t0, t1, t2, t3]) = r.twin.get_mut(q..q + 4) else {
                    return Err(internal());
                };
                (*t0, *t1, *t2, *t3) = (across, 4 * nx + 2, 4 * p + 1, back);
                for s in r.face_of.get_mut(q..q + 4).ok_or(internal())? {
                    *s = h;
                }
                let Some(&[c0, c1, c2, c3]) = new_indices.get(q..q + 4) else {
                    return Err(internal());
                };
                check_eq(c0, get(indices, h as usize)?)?;
                check_eq(c1, nv32 + get(self.edge_of, h as usize)?)?;
                check_eq(c2, fp)?;
                check_eq(c3, nv32 + get(self.edge_of, p as usize)?)?;
                check_eq(get(new_offsets, h as usize + 1)?, 4 * h + 4)?;
            }
        }
        // Edges (v, E): v -> E is 4h, E -> dest(h) is 4 next(h) + 3.
        let mut id = self.spoke_edges(&mut r, |h| Ok(4 * h), |h| Ok(4 * self.next_fast(h)? + 3))?;
        // Edges (E, F) in parent-edge order, each pair by face id; edge points' stars.
        let mut rank = self.n_boundary_vertices as u32;
        for (e, &h) in self.edge_he.iter().enumerate() {
            let t = get(self.twin, h as usize)?;
            let nxh = self.next_fast(h)?;
            let v2 = nv + e;
            let mut put = |x: u32, id: usize| -> Result<()> {
                let x1 = 4 * x + 1;
                set(r.edge_of, x1 as usize, id as u32)?;
                set(r.edge_of, (4 * self.next_fast(x)? + 2) as usize, id as u32)?;
                set(r.edge_he, id, x1)
            };
            if t == NONE {
                put(h, id)?;
                id += 1;
                set(r.vert_he, v2, 4 * nxh + 3)?;
                set(r.valence, v2, 3)?;
                set(r.bnd_rank, v2, rank)?;
                rank += 1;
            } else {
                let (x, y) = if get(self.face_of, h as usize)? < get(self.face_of, t as usize)? {
                    (h, t)
                } else {
                    (t, h)
                };
                put(x, id)?;
                put(y, id + 1)?;
                id += 2;
                let nxt = self.next_fast(t)?;
                let start = (4 * h + 1).min(4 * nxh + 3).min(4 * t + 1).min(4 * nxt + 3);
                set(r.vert_he, v2, start)?;
                set(r.valence, v2, 4)?;
                set(r.bnd_rank, v2, NONE)?;
            }
        }
        if id != 2 * ne + nh {
            return Err(internal());
        }
        self.old_vertices(&mut r, |h| Ok(4 * h))?;
        for f in 0..nf {
            let a = get(offsets, f)?;
            let n = get(offsets, f + 1)? - a;
            let v2 = nv + ne + f;
            if n as usize > MAX_VALENCE {
                return Err(internal());
            }
            set(r.vert_he, v2, 4 * a + 2)?;
            set(r.valence, v2, n)?;
            set(r.bnd_rank, v2, NONE)?;
        }
        let eb = self.n_boundary_edges;
        let face = if nh > 0 { 4 } else { 0 };
        Ok(Counts {
            n_edges: id,
            n_boundary_edges: 2 * eb,
            n_boundary_vertices: self.n_boundary_vertices + eb,
            n_isolated: self.n_isolated,
            interior_spokes: self.interior_spokes + 4 * (ne - eb) + nh,
            boundary_spokes: self.boundary_spokes + 3 * eb,
            max_face: face,
            min_face: face,
        })
    }

    /// [`Pattern::Split1To4`]: corner `i` of triangle `f` (half-edge `h`) becomes triangle
    /// `4f + i`, half-edges `A(h) = 12f + 3i ..`: `v_i → e_i`, `e_i → e_{i−1}`,
    /// `e_{i−1} → v_i`; the middle triangle `4f + 3`, half-edges `C(f) + i = 12f + 9 + i`:
    /// `e_i → e_{i+1}`.
    fn refine_split(&self, mesh: &Mesh<'_>, scratch: &mut [u32]) -> Result<Counts> {
        let (nv, ne, nf, nh) = (
            self.num_vertices(),
            self.num_edges(),
            self.num_faces(),
            self.num_half_edges(),
        );
        let nv2 = nv + ne;
        let nh2 = nh.checked_mul(4).ok_or(internal())?;
        if nh != 3 * nf
            || nv2 > MAX_COUNT
            || nh2 > MAX_COUNT
            || mesh.num_vertices() != nv2
            || mesh.num_corners() != nh2
            || mesh.num_faces() != 4 * nf
        {
            return Err(internal());
        }
        // Triangles only (nh = 3 nf and every face ≥ 3 corners): offsets[f] = 3f, so the
        // face of h is h / 3 and its corner h % 3.
        let mut r = regions(scratch, nv2, nh2)?;
        let nv32 = nv as u32;
        let indices = self.mesh.indices;
        let (new_offsets, new_indices) = (mesh.offsets, mesh.indices);
        let big_a = |h: u32| 12 * (h / 3) + 3 * (h % 3);
        let big_c = |h: u32| 12 * (h / 3) + 9 + h % 3;
        let next = |h: u32| if h % 3 == 2 { h - 2 } else { h + 1 };
        let prev = |h: u32| if h % 3 == 0 { h + 2 } else { h - 1 };
        check_eq(get(new_offsets, 0)?, 0)?;
        for f in 0..nf as u32 {
            check_eq(get(self.mesh.offsets, f as usize + 1)?, 3 * f + 3)?;
            for i in 0..3u32 {
                let h = 3 * f + i;
                let (nx, p) = (next(h), prev(h));
                let t = get(self.twin, h as usize)?;
                let tp = get(self.twin, p as usize)?;
                let q = big_a(h) as usize;
                let c = big_c(h) as usize;
                let across = if t == NONE { NONE } else { big_a(next(t)) + 2 };
                let back = if tp == NONE { NONE } else { big_a(tp) };
                let Some([t0, t1, t2]) = r.twin.get_mut(q..q + 3) else {
                    return Err(internal());
                };
                (*t0, *t1, *t2) = (across, big_c(p), back);
                set(r.twin, c, big_a(nx) + 1)?;
                for s in r.face_of.get_mut(q..q + 3).ok_or(internal())? {
                    *s = 4 * f + i;
                }
                set(r.face_of, c, 4 * f + 3)?;
                let Some(&[c0, c1, c2]) = new_indices.get(q..q + 3) else {
                    return Err(internal());
                };
                let eh = nv32 + get(self.edge_of, h as usize)?;
                check_eq(c0, get(indices, h as usize)?)?;
                check_eq(c1, eh)?;
                check_eq(c2, nv32 + get(self.edge_of, p as usize)?)?;
                check_eq(get(new_indices, c)?, eh)?;
                check_eq(
                    get(new_offsets, (4 * f + i) as usize + 1)?,
                    12 * f + 3 * i + 3,
                )?;
            }
            check_eq(get(new_offsets, 4 * f as usize + 4)?, 12 * f + 12)?;
        }
        // Edges (v, E): v -> E is A(h), E -> dest(h) is A(next h) + 2.
        let mut id = self.spoke_edges(&mut r, |h| Ok(big_a(h)), |h| Ok(big_a(next(h)) + 2))?;
        // Edges (E(e), E(e')) with e < e' in parent-edge order, sorted by e' (at most four:
        // two per face of e; two faces never share two edges of a valid triangle mesh).
        let mut rank = self.n_boundary_vertices as u32;
        for (e, &h) in self.edge_he.iter().enumerate() {
            let e32 = e as u32;
            let t = get(self.twin, h as usize)?;
            let v2 = nv + e;
            // (other edge, representative e -> e', its twin).
            let mut cand = [(NONE, NONE, NONE); 4];
            let mut n = 0usize;
            for x in [h, t] {
                if x == NONE {
                    continue;
                }
                let en = get(self.edge_of, next(x) as usize)?;
                if en > e32 {
                    set(&mut cand, n, (en, big_c(x), big_a(next(x)) + 1))?;
                    n += 1;
                }
                let ep = get(self.edge_of, prev(x) as usize)?;
                if ep > e32 {
                    set(&mut cand, n, (ep, big_a(x) + 1, big_c(prev(x))))?;
                    n += 1;
                }
            }
            let cand = cand.get_mut(..n).ok_or(internal())?;
            // Insertion sort of at most four distinct keys.
            for i in 1..cand.len() {
                let mut j = i;
                while j > 0 {
                    let (Some(&lo), Some(&hi)) = (cand.get(j - 1), cand.get(j)) else {
                        return Err(internal());
                    };
                    if lo.0 <= hi.0 {
                        break;
                    }
                    cand.swap(j - 1, j);
                    j -= 1;
                }
            }
            for &(_, rep, other) in cand.iter() {
                set(r.edge_of, rep as usize, id as u32)?;
                set(r.edge_of, other as usize, id as u32)?;
                set(r.edge_he, id, rep)?;
                id += 1;
            }
            let nxh = next(h);
            if t == NONE {
                set(r.vert_he, v2, big_a(nxh) + 2)?;
                set(r.valence, v2, 4)?;
                set(r.bnd_rank, v2, rank)?;
                rank += 1;
            } else {
                // Outgoing: A(next h) + 2, A(next t) + 2 (to the ends), A(h) + 1, C(h),
                // A(t) + 1, C(t) (to edge points); C(x) > A(x) + 1 (the middle triangle's
                // half-edges follow the corner triangles' of the same face).
                let start = (big_a(nxh) + 2)
                    .min(big_a(next(t)) + 2)
                    .min(big_a(h) + 1)
                    .min(big_a(t) + 1);
                set(r.vert_he, v2, start)?;
                set(r.valence, v2, 6)?;
                set(r.bnd_rank, v2, NONE)?;
            }
        }
        if id != 2 * ne + 3 * nf {
            return Err(internal());
        }
        self.old_vertices(&mut r, |h| Ok(big_a(h)))?;
        let eb = self.n_boundary_edges;
        let face = if nf > 0 { 3 } else { 0 };
        Ok(Counts {
            n_edges: id,
            n_boundary_edges: 2 * eb,
            n_boundary_vertices: self.n_boundary_vertices + eb,
            n_isolated: self.n_isolated,
            interior_spokes: self.interior_spokes + 6 * (ne - eb),
            boundary_spokes: self.boundary_spokes + 4 * eb,
            max_face: face,
            min_face: face,
        })
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::indexing_slicing)]
mod tests {
    use super::*;
    use crate::error::Error;
    use crate::mesh::refine::{pattern_size, write_pattern};
    use crate::mesh::topology_scratch_len;
    use crate::point::Point;
    use arrayvec::ArrayVec;

    /// `u32` and point arenas the levels of one test are carved from (no allocation in the
    /// core, not even in its tests): every level keeps its buffers while the next is built.
    const ARENA_U32: usize = 1 << 16;
    const ARENA_POINTS: usize = 1 << 12;

    /// Takes the first `n` elements of `*arena`, leaving the rest there.
    fn take<'a, T>(arena: &mut &'a mut [T], n: usize) -> &'a mut [T] {
        let (head, rest) = core::mem::take(arena).split_at_mut(n);
        *arena = rest;
        head
    }

    /// Every array and count of two topologies of the same mesh.
    fn assert_same(a: &Topology<'_, '_>, b: &Topology<'_, '_>, what: (Pattern, usize)) {
        assert_eq!(a.face_of, b.face_of, "{what:?}: faces of half-edges");
        assert_eq!(a.twin, b.twin, "{what:?}: twins");
        assert_eq!(a.edge_of, b.edge_of, "{what:?}: edge numbers");
        assert_eq!(a.edge_he, b.edge_he, "{what:?}: edge representatives");
        assert_eq!(a.vert_he, b.vert_he, "{what:?}: star starts");
        assert_eq!(a.valence, b.valence, "{what:?}: valences");
        assert_eq!(a.bnd_rank, b.bnd_rank, "{what:?}: boundary ranks");
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
        let need = topology_scratch_len(mesh.num_vertices(), mesh.num_corners()).unwrap();
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
            let need = topology_scratch_len(sz.vertices, sz.indices).unwrap();
            // Garbage in the derived scratch: every entry the topology uses must be written.
            let sd = take(&mut arena_u32, need);
            sd.fill(0xdead_beef);
            let sb = take(&mut arena_u32, need);
            assert_eq!(
                topo.refined(pattern, child, &mut short[..need - 1])
                    .unwrap_err(),
                Error::too_small(need)
            );
            let derived = topo.refined(pattern, child, sd).unwrap();
            let built = Topology::build(child, sb).unwrap();
            assert_same(&derived, &built, (pattern, k));
            topo = derived;
        }
    }

    fn grid_positions<const N: usize>() -> [Point; N] {
        core::array::from_fn(|v| [(v % 4) as f64, (v / 4) as f64, 0.0])
    }

    #[test]
    fn quads_cube() {
        let pos: [Point; 8] =
            core::array::from_fn(|v| [(v & 1) as f64, ((v >> 1) & 1) as f64, (v >> 2) as f64]);
        let idx = [
            0, 2, 3, 1, 4, 5, 7, 6, 0, 1, 5, 4, 2, 6, 7, 3, 0, 4, 6, 2, 1, 3, 7, 5,
        ];
        let offs = [0, 4, 8, 12, 16, 20, 24];
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

    /// A child that is not the pattern's is refused, never described wrongly.
    #[test]
    fn wrong_child_is_an_error() {
        let pos = grid_positions::<4>();
        let (offs, idx) = ([0u32, 3, 6], [0u32, 1, 2, 0, 2, 3]);
        let mesh = Mesh::new(&pos, &offs, &idx);
        let mut sc = [0u32; 64];
        let need = topology_scratch_len(4, 6).unwrap();
        let topo = Topology::build(mesh, &mut sc[..need]).unwrap();
        let sz = pattern_size(Pattern::Split1To4, &topo).unwrap();
        let (mut o, mut i) = ([0u32; 64], [0u32; 64]);
        let (o, i) = (&mut o[..sz.faces + 1], &mut i[..sz.indices]);
        write_pattern(Pattern::Split1To4, &topo, o, i).unwrap();
        i.swap(0, 1);
        let p = [[0.0; 3]; 64];
        let child = Mesh::new(&p[..sz.vertices], o, i);
        let mut s2 = [0u32; 512];
        let s2 = &mut s2[..topology_scratch_len(sz.vertices, sz.indices).unwrap()];
        assert!(topo.refined(Pattern::Split1To4, child, s2).is_err());
        assert!(topo.refined(Pattern::Quads, child, s2).is_err());
        assert!(topo.refined(Pattern::Dual, child, s2).is_err());
        assert!(!derivable(Pattern::CornerCut) && derivable(Pattern::Quads));
    }
}
