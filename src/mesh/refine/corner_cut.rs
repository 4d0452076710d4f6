//! [`Pattern::CornerCut`](super::Pattern::CornerCut) (Doo–Sabin): one new point per corner (corner
//! `h` → point `h`), then the isolated vertices. Faces: the `F` F-faces (a face's corner points in
//! face order), the E-faces of the interior edges in edge order `(c(next h), c(h), c(next t),
//! c(t))` with `h` the `min → max` half-edge and `t` its twin, the V-faces of the interior vertices
//! in vertex order (the corners of the star, counter-clockwise). No faces around boundary edges and
//! vertices (CGAL's `DQQ_1step`), so the new boundary runs through the corner points of the
//! boundary faces.

use arrayvec::ArrayVec;

use super::counts::{some, LevelCounts};
use super::dual_checks::dual_face_sizes;
use crate::error::Result;
use crate::exec::{self, Executor, MAX_CHUNKS};
use crate::mesh::{cadd, cmul, get, idx, internal, set, MeshSizes, Topology, NONE};

/// The output sizes: `H + I` vertices; `F + E_i + V_i` faces.
pub(super) fn size(topo: &Topology<'_, '_>) -> Result<MeshSizes> {
    dual_face_sizes(topo, 0)?;
    let (f, h, iso) = (
        topo.num_faces(),
        topo.num_half_edges(),
        topo.num_isolated_vertices(),
    );
    Ok(MeshSizes {
        vertices: cadd(h, iso)?,
        faces: cadd(
            cadd(f, topo.num_interior_edges())?,
            topo.num_interior_vertices(),
        )?,
        indices: cadd(
            cadd(h, cmul(topo.num_interior_edges(), 4)?)?,
            topo.interior_valence_sum(),
        )?,
    })
}

/// The faces (module docs), the closing offset excepted (the caller's), in the chunks of
/// `exec`: chunk `i` writes the F-faces of its parent-face range, the E-faces of its edge
/// range and the V-faces of its vertex range (the same ranges of [`exec::chunk_range`] over
/// each), each group into its own disjoint part of `offsets` and `indices`. An F-face
/// starts at its parent face's offset; the E-faces and V-faces of a range start after the
/// interior edges and the interior valences of the ranges before it, counted per chunk first
/// ([`count_range`]; on a closed mesh from the valences alone) and summed in chunk order, so
/// every executor and chunking writes the same bits. One chunk: inline, with the totals of
/// `topo` and without a counting pass.
pub(super) fn write(
    topo: &Topology<'_, '_>,
    sizes: &MeshSizes,
    offsets: &mut [u32],
    indices: &mut [u32],
    exec: &dyn Executor,
) -> Result<()> {
    // Chunked by parent faces as Split1To4 and Quads are (about 16 output corners each): an
    // output corner costs a nanosecond or two, far less than the executor's unit of work.
    let k = exec::chunk_count(exec, topo.num_faces());
    if k <= 1 {
        let all = RangeCounts {
            edges: (0, topo.num_edges()),
            vertices: (0, topo.num_vertices()),
            interior_edges: topo.num_interior_edges(),
            interior_vertices: topo.num_interior_vertices(),
            valence_sum: topo.interior_valence_sum(),
        };
        return exec::own_frame(|| {
            let mut out = Outputs::new(topo, sizes, offsets, indices)?;
            let mut part = out.part(topo, (0, topo.num_faces()), &all)?;
            out.finish()?;
            write_part(topo, &mut part)
        });
    }
    split(topo, sizes, offsets, indices, exec, k)
}

/// An edge range and a vertex range of the parent with what they contribute to the E-faces
/// and V-faces: their interior edges, interior vertices and the sum of those vertices'
/// valences.
#[derive(Clone, Copy, Debug, Default)]
struct RangeCounts {
    edges: (usize, usize),
    vertices: (usize, usize),
    interior_edges: usize,
    interior_vertices: usize,
    valence_sum: usize,
}

/// Counts the interior edges and vertices of `c`'s ranges into `c`.
fn count_range(topo: &Topology<'_, '_>, c: &mut RangeCounts) -> Result<()> {
    let r = topo.raw();
    let (e0, e1) = c.edges;
    let mut ei = 0;
    for &h in r.edge_he.get(e0..e1).ok_or(internal())? {
        ei += usize::from(get(r.twin, h as usize)? != NONE);
    }
    let (v0, v1) = c.vertices;
    let starts = r.vert_he.get(v0..v1).ok_or(internal())?;
    let valences = r.valence.get(v0..v1).ok_or(internal())?;
    let (mut vi, mut sum) = (0, 0);
    for (&h, &n) in starts.iter().zip(valences) {
        // Interior: referenced (a star) and its first spoke has a twin (a boundary star starts
        // at the outgoing boundary half-edge).
        if h != NONE && get(r.twin, h as usize)? != NONE {
            vi += 1;
            sum += n as usize;
        }
    }
    (c.interior_edges, c.interior_vertices, c.valence_sum) = (ei, vi, sum);
    Ok(())
}

/// What one chunk writes: its parent ranges, the first output corner of its E-faces and of
/// its V-faces, and its share of the output's offsets and indices for each of the three
/// groups (from the group's first face and corner in the range on).
#[derive(Debug)]
struct Part<'a> {
    faces: (usize, usize),
    edges: (usize, usize),
    vertices: (usize, usize),
    e_corner: usize,
    v_corner: usize,
    f_out: (&'a mut [u32], &'a mut [u32]),
    e_out: (&'a mut [u32], &'a mut [u32]),
    v_out: (&'a mut [u32], &'a mut [u32]),
}

/// The output's offsets (the closing one left out) and indices not yet handed to a part,
/// each split at the starts of the E-faces and V-faces, and the first corner of the next
/// part's E-faces and V-faces.
struct Outputs<'a> {
    f: (&'a mut [u32], &'a mut [u32]),
    e: (&'a mut [u32], &'a mut [u32]),
    v: (&'a mut [u32], &'a mut [u32]),
    e_corner: usize,
    v_corner: usize,
}

impl<'a> Outputs<'a> {
    fn new(
        topo: &Topology<'_, '_>,
        sizes: &MeshSizes,
        offsets: &'a mut [u32],
        indices: &'a mut [u32],
    ) -> Result<Self> {
        let (nf, nh, ei) = (
            topo.num_faces(),
            topo.num_half_edges(),
            topo.num_interior_edges(),
        );
        let mut offsets = offsets.get_mut(..sizes.faces).ok_or(internal())?;
        let mut indices = indices.get_mut(..sizes.indices).ok_or(internal())?;
        let f = (
            exec::take_front(&mut offsets, nf)?,
            exec::take_front(&mut indices, nh)?,
        );
        let e = (
            exec::take_front(&mut offsets, ei)?,
            exec::take_front(&mut indices, cmul(ei, 4)?)?,
        );
        let e_corner = nh;
        let v_corner = cadd(nh, cmul(ei, 4)?)?;
        Ok(Outputs {
            f,
            e,
            v: (offsets, indices),
            e_corner,
            v_corner,
        })
    }

    /// The next part: parent faces `faces` and the ranges of `c`.
    fn part(
        &mut self,
        topo: &Topology<'_, '_>,
        faces: (usize, usize),
        c: &RangeCounts,
    ) -> Result<Part<'a>> {
        let r = topo.raw();
        let corners = get(r.offsets, faces.1)?
            .checked_sub(get(r.offsets, faces.0)?)
            .ok_or(internal())?;
        let ei4 = cmul(c.interior_edges, 4)?;
        let part = Part {
            faces,
            edges: c.edges,
            vertices: c.vertices,
            e_corner: self.e_corner,
            v_corner: self.v_corner,
            f_out: (
                exec::take_front(&mut self.f.0, faces.1 - faces.0)?,
                exec::take_front(&mut self.f.1, corners as usize)?,
            ),
            e_out: (
                exec::take_front(&mut self.e.0, c.interior_edges)?,
                exec::take_front(&mut self.e.1, ei4)?,
            ),
            v_out: (
                exec::take_front(&mut self.v.0, c.interior_vertices)?,
                exec::take_front(&mut self.v.1, c.valence_sum)?,
            ),
        };
        self.e_corner = cadd(self.e_corner, ei4)?;
        self.v_corner = cadd(self.v_corner, c.valence_sum)?;
        Ok(part)
    }

    /// An internal error unless the parts took the whole output.
    fn finish(&self) -> Result<()> {
        let left = [&self.f, &self.e, &self.v]
            .iter()
            .any(|(o, i)| !o.is_empty() || !i.is_empty());
        if left {
            Err(internal())
        } else {
            Ok(())
        }
    }
}

/// [`write`] in `k ≥ 2` chunks (out of line: the one-chunk path keeps a small stack frame):
/// the counting pass, the parts in chunk order, the writing pass.
#[inline(never)]
fn split(
    topo: &Topology<'_, '_>,
    sizes: &MeshSizes,
    offsets: &mut [u32],
    indices: &mut [u32],
    exec: &dyn Executor,
    k: usize,
) -> Result<()> {
    let (nf, ne, nv) = (topo.num_faces(), topo.num_edges(), topo.num_vertices());
    let mut counts = ArrayVec::<RangeCounts, MAX_CHUNKS>::new();
    for i in 0..k {
        counts
            .try_push(RangeCounts {
                edges: exec::chunk_range(ne, k, i),
                vertices: exec::chunk_range(nv, k, i),
                ..RangeCounts::default()
            })
            .map_err(|_| internal())?;
    }
    if topo.num_boundary_edges() == 0 && topo.num_isolated_vertices() == 0 {
        // Closed, nothing isolated: every edge and vertex is interior, and a range's valence
        // sum is one vectorised pass, cheaper than a pass of the executor (a spawn or a
        // wake-up per chunk).
        for c in &mut counts {
            let (v0, v1) = c.vertices;
            let valences = topo.raw().valence.get(v0..v1).ok_or(internal())?;
            c.interior_edges = c.edges.1 - c.edges.0;
            c.interior_vertices = v1 - v0;
            c.valence_sum = valences.iter().map(|&n| n as usize).sum();
        }
    } else {
        exec::parts(
            exec,
            &mut counts,
            |c| (c.edges.1 - c.edges.0) + (c.vertices.1 - c.vertices.0),
            |c, _| count_range(topo, c),
        )?;
    }
    let mut out = Outputs::new(topo, sizes, offsets, indices)?;
    let mut parts = ArrayVec::<Part<'_>, MAX_CHUNKS>::new();
    for (i, c) in counts.iter().enumerate() {
        let part = out.part(topo, exec::chunk_range(nf, k, i), c)?;
        parts.try_push(part).map_err(|_| internal())?;
    }
    // The chunk counts must add up to the topology's (each part took exactly its share).
    out.finish()?;
    exec::parts(
        exec,
        &mut parts,
        |p| (p.faces.1 - p.faces.0) + (p.edges.1 - p.edges.0) + (p.vertices.1 - p.vertices.0),
        |p, _| write_part(topo, p),
    )
    .map(|_| ())
}

/// The F-, E- and V-faces of one [`Part`].
fn write_part(topo: &Topology<'_, '_>, p: &mut Part<'_>) -> Result<()> {
    write_f_faces(topo, p.faces, &mut p.f_out)?;
    write_e_faces(topo, p.edges, p.e_corner, &mut p.e_out)?;
    write_v_faces(topo, p.vertices, p.v_corner, &mut p.v_out)
}

/// The F-faces of the parent faces `faces`: face `f` is the parent's corners, at the
/// parent's offsets (corner `h` → point `h`).
fn write_f_faces(
    topo: &Topology<'_, '_>,
    faces: (usize, usize),
    out: &mut (&mut [u32], &mut [u32]),
) -> Result<()> {
    let (offsets, indices) = out;
    let parent = topo.raw().offsets.get(faces.0..faces.1).ok_or(internal())?;
    if parent.len() != offsets.len() {
        return Err(internal());
    }
    offsets.copy_from_slice(parent);
    let h0 = get(topo.raw().offsets, faces.0)?;
    for (h, i) in (h0..).zip(indices.iter_mut()) {
        *i = h;
    }
    Ok(())
}

/// The E-faces of the interior edges among `edges`, from output corner `corner` on.
fn write_e_faces(
    topo: &Topology<'_, '_>,
    edges: (usize, usize),
    corner: usize,
    out: &mut (&mut [u32], &mut [u32]),
) -> Result<()> {
    let (offsets, indices) = out;
    let mut faces = offsets.iter_mut();
    let mut quads = indices.chunks_exact_mut(4);
    let mut c = corner;
    for e in edges.0..edges.1 {
        let h = topo.edge_half_edge(idx(e)?)?;
        let t = topo.twin(h)?;
        if t == NONE {
            continue;
        }
        let (o, q) = (faces.next(), quads.next());
        let (Some(o), Some([q0, q1, q2, q3])) = (o, q) else {
            return Err(internal());
        };
        *o = idx(c)?;
        (*q0, *q1, *q2, *q3) = (topo.next(h)?, h, topo.next(t)?, t);
        c += 4;
    }
    // Exactly the counted faces (and no remainder of a partial quad).
    if faces.next().is_some() || quads.next().is_some() || !quads.into_remainder().is_empty() {
        return Err(internal());
    }
    Ok(())
}

/// The V-faces of the interior vertices among `vertices`, from output corner `corner` on.
fn write_v_faces(
    topo: &Topology<'_, '_>,
    vertices: (usize, usize),
    corner: usize,
    out: &mut (&mut [u32], &mut [u32]),
) -> Result<()> {
    let (offsets, indices) = out;
    let mut faces = offsets.iter_mut();
    let mut c = 0;
    for v in vertices.0..vertices.1 {
        let v = idx(v)?;
        if topo.is_isolated(v)? || topo.is_boundary_vertex(v)? {
            continue;
        }
        *faces.next().ok_or(internal())? = idx(cadd(corner, c)?)?;
        for s in topo.star(v) {
            set(indices, c, s.half_edge)?;
            c += 1;
        }
    }
    if faces.next().is_some() || c != indices.len() {
        return Err(internal());
    }
    Ok(())
}

/// The counts of the next level. Corner points at interior vertices: interior, valence 4.
/// At a boundary vertex with k faces: valence 2 + (interior edges of the face at the
/// vertex), which sums to 2k + 2(k − 1). New boundary edges: the old ones plus one per
/// interior edge at a boundary vertex (Σ_b (valence − 2)).
pub(super) fn next(s: &LevelCounts) -> Result<LevelCounts> {
    let (ei, vi) = (s.ei(), s.vi());
    let sb4 = cmul(s.sb, 4)?;
    let eb6 = cmul(s.eb, 6)?;
    Ok(LevelCounts {
        v: cadd(s.h, s.iso)?,
        f: cadd(cadd(s.f, ei)?, vi)?,
        h: cadd(cadd(s.h, cmul(ei, 4)?)?, s.si)?,
        e: cadd(s.h, cmul(ei, 2)?)?,
        eb: s.sb.checked_sub(s.eb).ok_or(internal())?,
        iso: s.iso,
        si: cmul(s.si, 4)?,
        sb: sb4.checked_sub(eb6).ok_or(internal())?,
        max_vi: some(s.si > 0, 4),
        max_vb: some(s.eb > 0, 4),
        max_face: s.max_face.max(some(ei > 0, 4)).max(some(vi > 0, s.max_vi)),
        max_dt: 0,
    })
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::indexing_slicing)]
mod tests {
    use super::super::face_writer::FaceWriter;
    use crate::exec::testing::{take, Reverse};
    use crate::exec::MAX_CHUNKS;
    use crate::mesh::refine::fixtures::{cube, mixed_open_dual};
    use crate::mesh::refine::{pattern_size, write_pattern, write_pattern_with, Pattern};
    use crate::mesh::{topology_scratch_size, Mesh, MeshSizes, Topology, NONE};
    use crate::point::Point;

    /// `u32` and point arenas the levels of one test are carved from (no allocation in the
    /// core, not even in its tests).
    const ARENA_U32: usize = 1 << 17;
    const ARENA_POINTS: usize = 1 << 12;

    /// The faces as written with a running cursor, one after the other (the serial writer
    /// the chunked one replaced): the reference.
    fn reference(topo: &Topology<'_, '_>, sizes: &MeshSizes, o: &mut [u32], i: &mut [u32]) {
        let mut w = FaceWriter::new(o, i).unwrap();
        for f in 0..topo.num_faces() as u32 {
            for h in topo.face_half_edges(f).unwrap() {
                w.push(h).unwrap();
            }
            w.end_face().unwrap();
        }
        for e in 0..topo.num_edges() as u32 {
            let h = topo.edge_half_edge(e).unwrap();
            let t = topo.twin(h).unwrap();
            if t != NONE {
                let (nh, nt) = (topo.next(h).unwrap(), topo.next(t).unwrap());
                w.face(&[nh, h, nt, t]).unwrap();
            }
        }
        for v in 0..topo.num_vertices() as u32 {
            if topo.is_isolated(v).unwrap() || topo.is_boundary_vertex(v).unwrap() {
                continue;
            }
            for s in topo.star(v) {
                w.push(s.half_edge).unwrap();
            }
            w.end_face().unwrap();
        }
        w.finish(sizes).unwrap();
    }

    /// `levels` Doo–Sabin steps: each level written serially must equal the reference, and
    /// written in 2, 3, 5, 7 and [`MAX_CHUNKS`] chunks run in reverse order (chunk boundaries
    /// in every group, ranges with no interior edge or vertex, empty ranges) must equal the
    /// serial one, every entry (the buffers start as garbage).
    fn chunked_equals_serial(pos: &[Point], offs: &[u32], idx: &[u32], levels: usize) {
        let mut store_u32 = [0u32; ARENA_U32];
        let mut store_points = [[0.0f64; 3]; ARENA_POINTS];
        let mut arena_u32: &mut [u32] = &mut store_u32;
        let mut arena_points: &mut [Point] = &mut store_points;
        let mesh = Mesh::new(pos, offs, idx);
        let need = topology_scratch_size(mesh.num_vertices(), mesh.num_corners()).unwrap();
        let mut topo = Topology::build(mesh, take(&mut arena_u32, need)).unwrap();
        for level in 1..=levels {
            let sz = pattern_size(Pattern::CornerCut, &topo).unwrap();
            let o = take(&mut arena_u32, sz.faces + 1);
            let i = take(&mut arena_u32, sz.indices);
            o.fill(0xdead_beef);
            i.fill(0xdead_beef);
            write_pattern(Pattern::CornerCut, &topo, o, i).unwrap();
            let (ro, ri) = ([0u32; 4096], [0u32; 16384]);
            let (mut ro, mut ri) = (ro, ri);
            let (ro, ri) = (&mut ro[..sz.faces + 1], &mut ri[..sz.indices]);
            reference(&topo, &sz, ro, ri);
            assert_eq!((&*o, &*i), (&*ro, &*ri), "level {level}: serial");
            for chunks in [2, 3, 5, 7, MAX_CHUNKS] {
                let (mut o2, mut i2) = ([0xdead_beef_u32; 4096], [0xdead_beef_u32; 16384]);
                let (o2, i2) = (&mut o2[..sz.faces + 1], &mut i2[..sz.indices]);
                write_pattern_with(Pattern::CornerCut, &topo, o2, i2, &Reverse(chunks)).unwrap();
                assert_eq!((&*o2, &*i2), (&*o, &*i), "level {level}, {chunks} chunks");
            }
            let (o, i): (&[u32], &[u32]) = (o, i);
            // Any finite positions: the connectivity does not read them.
            let p = take(&mut arena_points, sz.vertices);
            for (v, q) in p.iter_mut().enumerate() {
                *q = [v as f64, 0.5, -1.0];
            }
            let child = Mesh::new(p, o, i);
            let need = topology_scratch_size(sz.vertices, sz.indices).unwrap();
            topo = Topology::build(child, take(&mut arena_u32, need)).unwrap();
        }
    }

    #[test]
    fn chunked_cube() {
        let (pos, offs, idx) = cube();
        chunked_equals_serial(&pos, &offs, &idx, 3);
    }

    /// Quads, triangles and a pentagon with a boundary, three interior vertices (5, 6, 9) and
    /// two isolated ones (3, 15).
    #[test]
    fn chunked_mixed_open_with_isolated_vertices() {
        let (pos, offs, idx) = mixed_open_dual();
        chunked_equals_serial(&pos, &offs, &idx, 3);
    }
}
