//! The sharp-feature tags of a subdivided mesh's last level, for the OBJ output (`t crease`
//! and `t corner` lines) and for a fold count that leaves the creases out.
//!
//! The kernel carries the tags from level to level inside one tagged call and returns only
//! the positions and the connectivity. The values of the last level follow from the input's
//! tags by the same rule, OpenSubdiv's, which the kernel exports
//! (`stencil::crease::child_edge_sharpness`, `decrement`): per level, the two children of a
//! tagged edge take its decayed values, one per end, computed from the incident edges of
//! that end in star order (as the kernel computes them, so the values are the same bits);
//! an old vertex keeps its corner value decremented; new edges and vertices are smooth.
//! The connectivity of each level comes from one linear step of the same scheme (the
//! connectivity does not depend on the rules), with the kernel's numbering: old vertices
//! first, the edge point of edge `e` as vertex `V + e`.

use nlsubdiv::mesh::{topology_scratch_size, Mesh as CoreMesh, MeshOut, Topology};
use nlsubdiv::scheme::{self, CreaseMethod, Options, Scheme, Scratch};
use nlsubdiv::stencil::crease::{child_edge_sharpness, decrement, INFINITE};

use crate::error::{CliError, CliResult};
use crate::mesh::{FileTags, Mesh};

/// The tags of `input` after `levels` levels of `scheme` (one of the schemes that take tags)
/// with `method`: the creases and corners whose sharpness is still positive, with the last
/// level's vertex numbers. Infinite sharpness is written as 10.
///
/// # Errors
/// Internal errors only: the input and the tags were validated by the subdivision.
pub fn last_level(
    input: &Mesh,
    scheme: Scheme,
    levels: usize,
    tags: &FileTags,
    method: CreaseMethod,
) -> CliResult<FileTags> {
    let internal = |what: &str| CliError::internal(format!("tags of the last level: {what}"));
    let mut mesh = input.clone();
    let (mut edges, mut vertices) = {
        let mut scratch = topology_scratch(&mesh)?;
        let topo =
            Topology::build(core(&mesh), &mut scratch).map_err(|e| internal(&e.to_string()))?;
        let mut edges = vec![0.0f32; topo.num_edges()];
        let mut vertices = vec![0.0f32; topo.num_vertices()];
        for (&[a, b], &s) in tags.creases.iter().zip(&tags.crease_sharpness) {
            let e = edge_between(&topo, a, b).ok_or_else(|| internal("a crease is no edge"))?;
            edges[e as usize] = stored(s);
        }
        for (&v, &s) in tags.corners.iter().zip(&tags.corner_sharpness) {
            *vertices
                .get_mut(v as usize)
                .ok_or_else(|| internal("a corner out of range"))? = stored(s);
        }
        (edges, vertices)
    };
    for _ in 0..levels {
        let child = linear_step(&mesh, scheme)?;
        let mut ps = topology_scratch(&mesh)?;
        let parent = Topology::build(core(&mesh), &mut ps).map_err(|e| internal(&e.to_string()))?;
        let mut cs = topology_scratch(&child)?;
        let kid = Topology::build(core(&child), &mut cs).map_err(|e| internal(&e.to_string()))?;
        let nv = parent.num_vertices() as u32;
        let mut child_edges = vec![0.0f32; kid.num_edges()];
        let mut child_vertices = vec![0.0f32; kid.num_vertices()];
        let (mut pe, mut ce) = (Vec::new(), Vec::new());
        for v in 0..nv {
            child_vertices[v as usize] = decrement(vertices[v as usize]);
            pe.clear();
            for s in parent.star(v) {
                let boundary = parent
                    .is_boundary_edge(s.edge)
                    .map_err(|e| internal(&e.to_string()))?;
                pe.push(if boundary {
                    INFINITE
                } else {
                    edges[s.edge as usize]
                });
            }
            ce.clear();
            ce.resize(pe.len(), 0.0f32);
            child_edge_sharpness(method, &pe, &mut ce);
            for (s, &c) in parent.star(v).zip(&ce) {
                if c == 0.0 {
                    continue;
                }
                let e = edge_between(&kid, v, nv + s.edge)
                    .ok_or_else(|| internal("a child edge is missing"))?;
                child_edges[e as usize] = c;
            }
        }
        mesh = child;
        edges = child_edges;
        vertices = child_vertices;
    }
    let mut scratch = topology_scratch(&mesh)?;
    let topo = Topology::build(core(&mesh), &mut scratch).map_err(|e| internal(&e.to_string()))?;
    let mut out = FileTags::default();
    let written = |s: f32| if s >= INFINITE { 10.0 } else { f64::from(s) };
    for (e, &s) in edges.iter().enumerate() {
        let boundary = topo
            .is_boundary_edge(e as u32)
            .map_err(|e| internal(&e.to_string()))?;
        if s > 0.0 && !boundary {
            let (a, b) = topo
                .edge_vertices(e as u32)
                .map_err(|e| internal(&e.to_string()))?;
            out.creases.push([a.min(b), a.max(b)]);
            out.crease_sharpness.push(written(s));
        }
    }
    for (v, &s) in vertices.iter().enumerate() {
        if s > 0.0 {
            out.corners.push(v as u32);
            out.corner_sharpness.push(written(s));
        }
    }
    Ok(out)
}

fn core(m: &Mesh) -> CoreMesh<'_> {
    CoreMesh::new(&m.positions, &m.offsets, &m.indices)
}

fn topology_scratch(m: &Mesh) -> CliResult<Vec<u32>> {
    let len = topology_scratch_size(m.positions.len(), m.indices.len())
        .map_err(|e| CliError::internal(format!("tags of the last level: {e}")))?;
    Ok(vec![0u32; len])
}

/// The kernel's value of a validated sharpness (`Tags`: 10 or more is infinite).
fn stored(s: f64) -> f32 {
    let v = s as f32;
    if v >= INFINITE {
        INFINITE
    } else {
        v
    }
}

/// The edge of `topo` between `a` and `b`.
fn edge_between(topo: &Topology<'_, '_>, a: u32, b: u32) -> Option<u32> {
    topo.star(a).find(|s| s.neighbour == b).map(|s| s.edge)
}

/// One linear step of `scheme` (for its connectivity).
fn linear_step(m: &Mesh, scheme: Scheme) -> CliResult<Mesh> {
    let err = |e: nlsubdiv::Error| CliError::internal(format!("tags of the last level: {e}"));
    let opts = Options::new(scheme);
    let mut su = vec![0u32; scheme::plan_scratch_size(&core(m)).map_err(err)?];
    let plan = scheme::plan(core(m), &opts, &mut su).map_err(err)?;
    su.resize(plan.scratch.u32s.max(su.len()), 0);
    let mut sp = vec![[0.0f64; 3]; plan.scratch.points];
    let o = plan.output();
    let mut next = Mesh {
        positions: vec![[0.0; 3]; o.vertices],
        offsets: vec![0; o.faces + 1],
        indices: vec![0; o.indices],
    };
    scheme::subdivide(
        core(m),
        &opts,
        Scratch::new(&mut su, &mut sp),
        &mut MeshOut::new(&mut next.positions, &mut next.offsets, &mut next.indices),
    )
    .map_err(err)?;
    Ok(next)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A cube with one face's four edges tagged: after one Catmull–Clark level each tagged
    /// edge has two children at the edge point `V + e`, each still infinitely sharp, and a
    /// sharpness 1.5 edge's children 0.5 (uniform decay); nothing else is tagged.
    #[test]
    fn children_of_a_cube_face() {
        let p = (0..8)
            .map(|i| {
                [
                    f64::from(i & 1),
                    f64::from((i >> 1) & 1),
                    f64::from((i >> 2) & 1),
                ]
            })
            .collect();
        let faces: [[u32; 4]; 6] = [
            [0, 2, 3, 1],
            [4, 5, 7, 6],
            [0, 1, 5, 4],
            [2, 6, 7, 3],
            [0, 4, 6, 2],
            [1, 3, 7, 5],
        ];
        let cube = Mesh::from_faces(p, &faces);
        let tags = FileTags {
            creases: vec![[4, 5], [5, 7], [7, 6], [6, 4]],
            crease_sharpness: vec![10.0, 1.5, 10.0, 10.0],
            crease_lines: vec![0; 4],
            corners: vec![0],
            corner_sharpness: vec![2.0],
            corner_lines: vec![0],
        };
        let out = last_level(&cube, Scheme::CatmullClark, 1, &tags, CreaseMethod::Uniform).unwrap();
        assert_eq!(out.creases.len(), 8);
        let child = linear_step(&cube, Scheme::CatmullClark).unwrap();
        let mut s = vec![0u32; topology_scratch_size(8, 24).unwrap()];
        let topo = Topology::build(core(&cube), &mut s).unwrap();
        for (&[a, b], &want) in tags.creases.iter().zip(&[10.0, 0.5, 10.0, 10.0]) {
            let p = 8 + edge_between(&topo, a, b).unwrap();
            for end in [a, b] {
                let k = out
                    .creases
                    .iter()
                    .position(|&c| c == [end.min(p), end.max(p)])
                    .unwrap();
                assert_eq!(out.crease_sharpness[k], want);
            }
        }
        assert_eq!(out.corners, vec![0]);
        assert_eq!(out.corner_sharpness, vec![1.0]);
        assert_eq!(child.positions.len(), 8 + 12 + 6);
    }
}
