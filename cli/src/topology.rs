//! Connectivity of a [`Mesh`] for the command: edges, twins, vertex stars, boundary loops,
//! components, and the checks behind `nlsubdiv check` (std code; the core has its own
//! allocation-free topology for the schemes).
//!
//! Conventions are the core's: corner `h` is the half-edge from `indices[h]` to the next
//! corner of its face; stars run counter-clockwise (`h → twin(prev(h))`), a boundary star
//! from the end of the vertex's outgoing boundary half-edge to the start of its incoming
//! one. Edges are numbered in ascending `(min, max)` order. Nothing depends on hashing order.
//!
//! [`Topology::build`] never fails: defects are recorded, the half-edges involved get no
//! twin, and the vertices whose star is not one fan are marked, so that lenient commands
//! can go on and skip them.

use std::collections::HashMap;

use crate::mesh::{area_vector, norm, sub, Mesh, Source};

/// "No such element".
pub const NONE: u32 = u32::MAX;

/// The core's limits (`nlsubdiv::MAX_VALENCE`, `nlsubdiv::MAX_FACE_SIZE`).
const MAX_VALENCE: usize = nlsubdiv::MAX_VALENCE;
const MAX_FACE_SIZE: usize = nlsubdiv::MAX_FACE_SIZE;

/// Half-edge connectivity built from the face list.
#[derive(Debug)]
pub struct Topology {
    /// Corner → face.
    pub face_of: Vec<u32>,
    /// Corner → twin corner (the opposite half-edge of a manifold, consistently oriented
    /// edge), or [`NONE`].
    pub twin: Vec<u32>,
    /// Corner → edge id.
    pub edge_of: Vec<u32>,
    /// Edges `(min, max)`, ascending.
    pub edges: Vec<(u32, u32)>,
    /// Number of corners (half-edges) on each edge.
    pub edge_uses: Vec<u32>,
    /// For each vertex, its corners (outgoing half-edges): `vc_idx[vc_off[v]..vc_off[v+1]]`.
    vc_off: Vec<u32>,
    vc_idx: Vec<u32>,
    offsets: Vec<u32>,
    indices: Vec<u32>,
    /// Vertices whose star is not a single fan or touches a defective edge.
    pub bad_vertex: Vec<bool>,
    /// Defects found while building.
    defects: Defects,
}

#[derive(Debug, Default)]
struct Defects {
    repeated: Vec<u32>,                   // faces with a repeated vertex
    nonmanifold_edges: Vec<u32>,          // edge ids with 3+ uses
    same_direction: Vec<(u32, u32, u32)>, // (edge, face, face) used twice the same way
    nonmanifold_vertices: Vec<u32>,
}

impl Topology {
    /// Builds the connectivity of `mesh` (indices must be in range, as the readers ensure).
    pub fn build(mesh: &Mesh) -> Topology {
        let nv = mesh.num_vertices();
        let nc = mesh.indices.len();
        let offsets = mesh.offsets.clone();
        let indices = mesh.indices.clone();
        let mut face_of = vec![0u32; nc];
        for f in 0..mesh.num_faces() {
            for h in offsets[f]..offsets[f + 1] {
                face_of[h as usize] = f as u32;
            }
        }
        let mut t = Topology {
            face_of,
            twin: vec![NONE; nc],
            edge_of: vec![NONE; nc],
            edges: Vec::new(),
            edge_uses: Vec::new(),
            vc_off: Vec::new(),
            vc_idx: Vec::new(),
            offsets,
            indices,
            bad_vertex: vec![false; nv],
            defects: Defects::default(),
        };
        // Faces with a repeated vertex: their half-edges stay unpaired.
        let mut bad_face = vec![false; mesh.num_faces()];
        for (f, face) in mesh.faces().enumerate() {
            let mut s = face.to_vec();
            s.sort_unstable();
            if s.windows(2).any(|w| w[0] == w[1]) {
                bad_face[f] = true;
                t.defects.repeated.push(f as u32);
                for &v in face {
                    t.bad_vertex[v as usize] = true;
                }
            }
        }
        // Directed half-edges sorted by undirected key, then corner.
        let mut keyed: Vec<(u32, u32, u32)> = (0..nc as u32)
            .map(|h| {
                let (a, b) = (t.from(h), t.to(h));
                (a.min(b), a.max(b), h)
            })
            .collect();
        keyed.sort_unstable();
        let mut i = 0;
        while i < keyed.len() {
            let (a, b, _) = keyed[i];
            let mut j = i;
            while j < keyed.len() && keyed[j].0 == a && keyed[j].1 == b {
                j += 1;
            }
            let e = t.edges.len() as u32;
            t.edges.push((a, b));
            t.edge_uses.push((j - i) as u32);
            for k in &keyed[i..j] {
                t.edge_of[k.2 as usize] = e;
            }
            let group: Vec<u32> = keyed[i..j].iter().map(|k| k.2).collect();
            let any_bad_face = group
                .iter()
                .any(|&h| bad_face[t.face_of[h as usize] as usize]);
            if group.len() > 2 {
                t.defects.nonmanifold_edges.push(e);
                t.bad_vertex[a as usize] = true;
                t.bad_vertex[b as usize] = true;
            } else if group.len() == 2 && !any_bad_face {
                let (h, g) = (group[0], group[1]);
                if t.from(h) == t.from(g) {
                    let (fh, fg) = (t.face_of[h as usize], t.face_of[g as usize]);
                    t.defects.same_direction.push((e, fh.min(fg), fh.max(fg)));
                    t.bad_vertex[a as usize] = true;
                    t.bad_vertex[b as usize] = true;
                } else {
                    t.twin[h as usize] = g;
                    t.twin[g as usize] = h;
                }
            }
            i = j;
        }
        // Corners of each vertex (CSR), in corner order.
        let mut count = vec![0u32; nv + 1];
        for &v in &t.indices {
            count[v as usize + 1] += 1;
        }
        for v in 0..nv {
            count[v + 1] += count[v];
        }
        let mut fill = count.clone();
        let mut vc_idx = vec![0u32; nc];
        for (h, &v) in t.indices.iter().enumerate() {
            vc_idx[fill[v as usize] as usize] = h as u32;
            fill[v as usize] += 1;
        }
        t.vc_off = count;
        t.vc_idx = vc_idx;
        // Stars: every vertex must be one fan.
        for v in 0..nv as u32 {
            let corners = t.corners(v).len();
            if corners == 0 || t.bad_vertex[v as usize] {
                continue;
            }
            match t.walk(v) {
                Some((hs, _)) if hs.len() == corners => {}
                _ => {
                    t.bad_vertex[v as usize] = true;
                    t.defects.nonmanifold_vertices.push(v);
                }
            }
        }
        t
    }

    /// Start vertex of half-edge `h`.
    pub fn from(&self, h: u32) -> u32 {
        self.indices[h as usize]
    }

    /// End vertex of half-edge `h`.
    pub fn to(&self, h: u32) -> u32 {
        self.indices[self.next(h) as usize]
    }

    /// Next corner in the face of `h`.
    pub fn next(&self, h: u32) -> u32 {
        let f = self.face_of[h as usize] as usize;
        let (a, b) = (self.offsets[f], self.offsets[f + 1]);
        if h + 1 == b {
            a
        } else {
            h + 1
        }
    }

    /// Previous corner in the face of `h`.
    pub fn prev(&self, h: u32) -> u32 {
        let f = self.face_of[h as usize] as usize;
        let (a, b) = (self.offsets[f], self.offsets[f + 1]);
        if h == a {
            b - 1
        } else {
            h - 1
        }
    }

    /// The corners (outgoing half-edges) of vertex `v`.
    pub fn corners(&self, v: u32) -> &[u32] {
        let (a, b) = (self.vc_off[v as usize], self.vc_off[v as usize + 1]);
        &self.vc_idx[a as usize..b as usize]
    }

    /// Number of faces at vertex `v`.
    pub fn face_count(&self, v: u32) -> usize {
        self.corners(v).len()
    }

    /// The counter-clockwise walk of `v`'s star: its outgoing half-edges in order and whether
    /// it is closed. `None` for a vertex with two or more outgoing boundary half-edges.
    fn walk(&self, v: u32) -> Option<(Vec<u32>, bool)> {
        let corners = self.corners(v);
        let starts: Vec<u32> = corners
            .iter()
            .copied()
            .filter(|&h| self.twin[h as usize] == NONE)
            .collect();
        let (start, closed) = match starts.as_slice() {
            [] => (*corners.first()?, true),
            [h] => (*h, false),
            _ => return None,
        };
        let mut out = vec![start];
        let mut h = start;
        loop {
            let p = self.prev(h);
            let t = self.twin[p as usize];
            if t == NONE {
                break;
            }
            if t == start {
                break;
            }
            if out.len() > corners.len() {
                return None;
            }
            out.push(t);
            h = t;
        }
        Some((out, closed))
    }

    /// The star of `v`: its edge neighbours counter-clockwise and whether the star is closed
    /// (interior vertex). `None` for isolated vertices and vertices marked bad.
    pub fn star(&self, v: u32) -> Option<(Vec<u32>, bool)> {
        if self.bad_vertex[v as usize] {
            return None;
        }
        let (hs, closed) = self.walk(v)?;
        let mut ring: Vec<u32> = hs.iter().map(|&h| self.to(h)).collect();
        if !closed {
            let last = *hs.last()?;
            ring.push(self.from(self.prev(last)));
        }
        Some((ring, closed))
    }

    /// Whether edge `e` is a boundary edge (used by one face).
    pub fn is_boundary_edge(&self, e: usize) -> bool {
        self.edge_uses[e] == 1
    }

    /// The first half-edge of every boundary loop (cycles of half-edges on edges used once).
    pub fn boundary_loop_starts(&self) -> Vec<u32> {
        let nc = self.indices.len();
        let is_b = |h: u32| self.edge_uses[self.edge_of[h as usize] as usize] == 1;
        let mut seen = vec![false; nc];
        let mut loops = Vec::new();
        for h0 in 0..nc as u32 {
            if seen[h0 as usize] || !is_b(h0) {
                continue;
            }
            loops.push(h0);
            let mut h = h0;
            loop {
                seen[h as usize] = true;
                let w = self.to(h);
                // The next boundary half-edge starts at w (the first unseen one at a
                // non-manifold vertex).
                let next = self
                    .corners(w)
                    .iter()
                    .copied()
                    .find(|&g| is_b(g) && !seen[g as usize]);
                match next {
                    Some(g) => h = g,
                    None => break,
                }
            }
        }
        loops
    }

    /// Connected components (through shared vertices): `(component of each face, count)`.
    pub fn components(&self, mesh: &Mesh) -> (Vec<u32>, usize) {
        let nv = mesh.num_vertices();
        let mut parent: Vec<u32> = (0..nv as u32).collect();
        fn find(p: &mut [u32], mut x: u32) -> u32 {
            while p[x as usize] != x {
                p[x as usize] = p[p[x as usize] as usize];
                x = p[x as usize];
            }
            x
        }
        for face in mesh.faces() {
            for &v in &face[1..] {
                let a = find(&mut parent, face[0]);
                let b = find(&mut parent, v);
                if a != b {
                    parent[a.max(b) as usize] = a.min(b);
                }
            }
        }
        let mut id = vec![NONE; nv];
        let mut n = 0;
        let mut comp = Vec::with_capacity(mesh.num_faces());
        for face in mesh.faces() {
            let r = find(&mut parent, face[0]) as usize;
            if id[r] == NONE {
                id[r] = n;
                n += 1;
            }
            comp.push(id[r]);
        }
        (comp, n as usize)
    }

    /// Number of vertices used by at least one face.
    pub fn referenced_vertices(&self) -> usize {
        self.vc_off.windows(2).filter(|w| w[1] > w[0]).count()
    }

    /// The checks of `nlsubdiv check`, in a fixed order, each with up to
    /// [`Finding::EXAMPLES`] located examples.
    pub fn findings(&self, mesh: &Mesh, src: &Source) -> Vec<Finding> {
        let mut out = Vec::new();
        fn add(
            out: &mut Vec<Finding>,
            severity: Severity,
            kind: &'static str,
            examples: Vec<String>,
            count: usize,
        ) {
            if count > 0 {
                out.push(Finding {
                    severity,
                    kind,
                    count,
                    examples,
                    hint: None,
                });
            }
        }
        let ex = Finding::EXAMPLES;
        use Severity::{Error, Warning};

        let d = &self.defects;
        add(
            &mut out,
            Error,
            "repeated-vertex",
            d.repeated
                .iter()
                .take(ex)
                .map(|&f| {
                    format!(
                        "{}: a vertex appears twice in the face ({})",
                        src.at_face(f as usize),
                        list(mesh.face(f as usize))
                    )
                })
                .collect(),
            d.repeated.len(),
        );
        // Duplicate faces: same vertex set.
        let mut keys: Vec<(Vec<u32>, u32)> = mesh
            .faces()
            .enumerate()
            .map(|(f, face)| {
                let mut k = face.to_vec();
                k.sort_unstable();
                (k, f as u32)
            })
            .collect();
        keys.sort_unstable();
        let dups: Vec<(u32, u32)> = keys
            .windows(2)
            .filter(|w| w[0].0 == w[1].0)
            .map(|w| (w[0].1, w[1].1))
            .collect();
        add(
            &mut out,
            Error,
            "duplicate-face",
            dups.iter()
                .take(ex)
                .map(|&(a, b)| {
                    format!(
                        "{}: the face has the same vertices as face {a} ({})",
                        src.at_face(b as usize),
                        list(mesh.face(b as usize))
                    )
                })
                .collect(),
            dups.len(),
        );
        add(
            &mut out,
            Error,
            "non-manifold-edge",
            d.nonmanifold_edges
                .iter()
                .take(ex)
                .map(|&e| {
                    let faces: Vec<u32> = (0..self.indices.len())
                        .filter(|&h| self.edge_of[h] == e)
                        .map(|h| self.face_of[h])
                        .collect();
                    let (a, b) = self.edges[e as usize];
                    format!(
                        "{}: edge ({a}, {b}) is shared by {} faces ({}): non-manifold edge",
                        src.at_face(*faces.last().unwrap_or(&0) as usize),
                        faces.len(),
                        list(&faces)
                    )
                })
                .collect(),
            d.nonmanifold_edges.len(),
        );
        if !d.same_direction.is_empty() {
            let (orientable, flips) = self.orientability(mesh);
            let items = d
                .same_direction
                .iter()
                .take(ex)
                .map(|&(e, f, g)| {
                    let (a, b) = self.edges[e as usize];
                    format!(
                        "{}: faces {f} and {g} both run along edge ({a}, {b}) in the same \
                         direction",
                        src.at_face(g as usize)
                    )
                })
                .collect();
            if orientable {
                add(
                    &mut out,
                    Error,
                    "inconsistent-orientation",
                    items,
                    d.same_direction.len(),
                );
                if let Some(last) = out.last_mut() {
                    last.hint = Some(format!(
                        "reversing {} face(s) would orient the mesh consistently (first: {})",
                        flips.len(),
                        list(&flips[..flips.len().min(8)])
                    ));
                }
            } else {
                add(
                    &mut out,
                    Error,
                    "non-orientable",
                    items,
                    d.same_direction.len(),
                );
                if let Some(last) = out.last_mut() {
                    last.hint = Some(
                        "no choice of face orientations is consistent: the surface is \
                         non-orientable (like a Möbius strip)"
                            .to_string(),
                    );
                }
            }
        }
        add(
            &mut out,
            Error,
            "non-manifold-vertex",
            d.nonmanifold_vertices
                .iter()
                .take(ex)
                .map(|&v| {
                    format!(
                        "{}: the faces around the vertex do not form one disk or half-disk \
                         ({} faces): non-manifold vertex",
                        src.at_vertex(v as usize),
                        self.face_count(v)
                    )
                })
                .collect(),
            d.nonmanifold_vertices.len(),
        );

        // Warnings: what the core accepts but is most likely a mistake.
        let unref: Vec<usize> = (0..mesh.num_vertices())
            .filter(|&v| self.corners(v as u32).is_empty())
            .collect();
        add(
            &mut out,
            Warning,
            "unreferenced-vertex",
            unref
                .iter()
                .take(ex)
                .map(|&v| format!("{}: no face uses the vertex", src.at_vertex(v)))
                .collect(),
            unref.len(),
        );
        let degenerate: Vec<usize> = mesh
            .faces()
            .enumerate()
            .filter(|(_, face)| is_degenerate(mesh, face))
            .map(|(f, _)| f)
            .collect();
        add(
            &mut out,
            Warning,
            "degenerate-face",
            degenerate
                .iter()
                .take(ex)
                .map(|&f| {
                    format!(
                        "{}: the face has zero area (its corners {} are collinear or coincide)",
                        src.at_face(f),
                        list(mesh.face(f))
                    )
                })
                .collect(),
            degenerate.len(),
        );
        let cracks = self.cracks(mesh);
        add(
            &mut out,
            Warning,
            "open-crack",
            cracks
                .iter()
                .take(ex)
                .map(|&(h, g)| {
                    format!(
                        "{}: boundary edge ({}, {}) lies exactly on boundary edge ({}, {}) of \
                         face {}: duplicated vertices leave the surface open there",
                        src.at_face(self.face_of[h as usize] as usize),
                        self.from(h),
                        self.to(h),
                        self.from(g),
                        self.to(g),
                        self.face_of[g as usize]
                    )
                })
                .collect(),
            cracks.len(),
        );
        let big_faces: Vec<usize> = mesh
            .faces()
            .enumerate()
            .filter(|(_, f)| f.len() > MAX_FACE_SIZE)
            .map(|(f, _)| f)
            .collect();
        add(
            &mut out,
            Warning,
            "face-too-large",
            big_faces
                .iter()
                .take(ex)
                .map(|&f| {
                    format!(
                        "{}: {} corners, more than the kernel's limit of {MAX_FACE_SIZE}",
                        src.at_face(f),
                        mesh.face(f).len()
                    )
                })
                .collect(),
            big_faces.len(),
        );
        let high: Vec<u32> = (0..mesh.num_vertices() as u32)
            .filter(|&v| self.valence(v) > MAX_VALENCE)
            .collect();
        add(
            &mut out,
            Warning,
            "valence-too-high",
            high.iter()
                .take(ex)
                .map(|&v| {
                    format!(
                        "{}: {} neighbours, more than the kernel's limit of {MAX_VALENCE}",
                        src.at_vertex(v as usize),
                        self.valence(v)
                    )
                })
                .collect(),
            high.len(),
        );
        out
    }

    /// Number of distinct edge neighbours of `v`.
    pub fn valence(&self, v: u32) -> usize {
        let mut n: Vec<u32> = Vec::new();
        for &h in self.corners(v) {
            n.push(self.to(h));
            n.push(self.from(self.prev(h)));
        }
        n.sort_unstable();
        n.dedup();
        n.len()
    }

    /// Whether faces can be oriented consistently, and if so, the faces to reverse (the
    /// smaller side in every component).
    fn orientability(&self, mesh: &Mesh) -> (bool, Vec<u32>) {
        let nf = mesh.num_faces();
        // Face adjacency through edges used exactly twice: (other face, same direction?).
        let mut by_edge: Vec<Vec<u32>> = vec![Vec::new(); self.edges.len()];
        for h in 0..self.indices.len() {
            by_edge[self.edge_of[h] as usize].push(h as u32);
        }
        let mut adj: Vec<Vec<(u32, bool)>> = vec![Vec::new(); nf];
        for hs in &by_edge {
            if let [h, g] = hs.as_slice() {
                let (fh, fg) = (self.face_of[*h as usize], self.face_of[*g as usize]);
                let same = self.from(*h) == self.from(*g);
                adj[fh as usize].push((fg, same));
                adj[fg as usize].push((fh, same));
            }
        }
        let mut flip: Vec<Option<bool>> = vec![None; nf];
        let mut flips = Vec::new();
        for f0 in 0..nf {
            if flip[f0].is_some() {
                continue;
            }
            let mut comp = vec![f0 as u32];
            flip[f0] = Some(false);
            let mut k = 0;
            while k < comp.len() {
                let f = comp[k] as usize;
                k += 1;
                let ff = flip[f].unwrap_or(false);
                for &(g, same) in &adj[f] {
                    let want = ff ^ same;
                    match flip[g as usize] {
                        None => {
                            flip[g as usize] = Some(want);
                            comp.push(g);
                        }
                        Some(x) if x != want => return (false, Vec::new()),
                        Some(_) => {}
                    }
                }
            }
            let flipped: Vec<u32> = comp
                .iter()
                .copied()
                .filter(|&f| flip[f as usize] == Some(true))
                .collect();
            if flipped.len() * 2 <= comp.len() {
                flips.extend(flipped);
            } else {
                flips.extend(
                    comp.iter()
                        .copied()
                        .filter(|&f| flip[f as usize] == Some(false)),
                );
            }
        }
        flips.sort_unstable();
        (true, flips)
    }

    /// Pairs of boundary half-edges that lie exactly on each other in opposite directions
    /// but have different vertices: a seam that was never welded.
    fn cracks(&self, mesh: &Mesh) -> Vec<(u32, u32)> {
        let bits = |v: u32| {
            let p = mesh.pos(v);
            [p[0].to_bits(), p[1].to_bits(), p[2].to_bits()]
        };
        let boundary: Vec<u32> = (0..self.indices.len() as u32)
            .filter(|&h| self.edge_uses[self.edge_of[h as usize] as usize] == 1)
            .collect();
        let mut map: HashMap<([u64; 3], [u64; 3]), u32> = HashMap::new();
        for &h in &boundary {
            map.entry((bits(self.from(h)), bits(self.to(h))))
                .or_insert(h);
        }
        let mut out = Vec::new();
        for &h in &boundary {
            if let Some(&g) = map.get(&(bits(self.to(h)), bits(self.from(h)))) {
                if g > h && (self.from(g), self.to(g)) != (self.to(h), self.from(h)) {
                    out.push((h, g));
                }
            }
        }
        out
    }
}

/// Whether a face has zero area relative to its size (collinear or coincident corners).
pub fn is_degenerate(mesh: &Mesh, face: &[u32]) -> bool {
    let mut longest: f64 = 0.0;
    for i in 0..face.len() {
        let a = mesh.pos(face[i]);
        let b = mesh.pos(face[(i + 1) % face.len()]);
        longest = longest.max(norm(sub(b, a)));
    }
    norm(area_vector(mesh, face)) <= 1e-14 * longest * longest
}

fn list(v: &[u32]) -> String {
    v.iter().map(u32::to_string).collect::<Vec<_>>().join(", ")
}

/// How bad a finding is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Severity {
    /// The mesh cannot be used as it is (the kernel refuses it).
    Error,
    /// The kernel accepts the mesh, but this is most likely a mistake.
    Warning,
}

/// One class of defect found in a mesh.
#[derive(Clone, Debug)]
pub struct Finding {
    /// Error or warning.
    pub severity: Severity,
    /// Stable identifier (`non-manifold-edge`, …), used in `--json` output.
    pub kind: &'static str,
    /// How many elements have it.
    pub count: usize,
    /// Messages naming the first elements (file, line, element).
    pub examples: Vec<String>,
    /// What would fix it, where that is known.
    pub hint: Option<String>,
}

impl Finding {
    /// How many elements each finding names.
    pub const EXAMPLES: usize = 3;
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    fn cube() -> Mesh {
        let p = (0..8)
            .map(|i| [(i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64])
            .collect();
        Mesh::from_faces(
            p,
            &[
                [0, 2, 3, 1],
                [4, 5, 7, 6],
                [0, 1, 5, 4],
                [2, 6, 7, 3],
                [0, 4, 6, 2],
                [1, 3, 7, 5],
            ],
        )
    }

    fn kinds(m: &Mesh) -> Vec<&'static str> {
        let t = Topology::build(m);
        t.findings(m, &Source::new(Path::new("t")))
            .iter()
            .map(|f| f.kind)
            .collect()
    }

    #[test]
    fn cube_is_clean_with_ccw_stars() {
        let m = cube();
        assert!(kinds(&m).is_empty());
        let t = Topology::build(&m);
        assert_eq!(t.edges.len(), 12);
        assert_eq!(t.boundary_loop_starts().len(), 0);
        let (ring, closed) = t.star(0).unwrap();
        assert!(closed);
        assert_eq!(ring.len(), 3);
        // Seen from outside (from (-1,-1,-1)), the neighbours 1 (x), 2 (y), 4 (z) of the
        // corner at the origin run counter-clockwise as 1 → 4 → 2 (or a rotation of it).
        let s: String = ring.iter().map(|v| v.to_string()).collect();
        assert!(["142", "421", "214"].contains(&s.as_str()), "{s}");
    }

    #[test]
    fn open_grid_boundary_star() {
        // 2x2 quads, vertices 0..9 row-major, CCW seen from +z.
        let p = (0..9)
            .map(|i| [(i % 3) as f64, (i / 3) as f64, 0.0])
            .collect();
        let m = Mesh::from_faces(p, &[[0, 1, 4, 3], [1, 2, 5, 4], [3, 4, 7, 6], [4, 5, 8, 7]]);
        let t = Topology::build(&m);
        assert_eq!(t.boundary_loop_starts().len(), 1);
        // Interior: from the lowest corner, counter-clockwise seen from +z.
        assert_eq!(t.star(4).unwrap(), (vec![3, 1, 5, 7], true));
        // Boundary: from the end of 1's outgoing boundary half-edge (1 → 2) to the start of
        // its incoming one (0 → 1), counter-clockwise: 2, 4, 0.
        assert_eq!(t.star(1).unwrap(), (vec![2, 4, 0], false));
        assert_eq!(t.star(0).unwrap(), (vec![1, 3], false));
    }

    #[test]
    fn defects() {
        let mut m = cube();
        // Reverse face 5.
        let f5: Vec<u32> = m.face(5).iter().rev().copied().collect();
        let n = m.indices.len();
        m.indices[n - 4..].copy_from_slice(&f5);
        assert_eq!(kinds(&m), vec!["inconsistent-orientation"]);
        let mut m = cube();
        m.positions.push([9.0, 9.0, 9.0]);
        assert_eq!(kinds(&m), vec!["unreferenced-vertex"]);
        let m = Mesh::from_faces(
            vec![
                [0.0; 3],
                [1.0, 0.0, 0.0],
                [0.0, 1.0, 0.0],
                [0.0, 0.0, 1.0],
                [1.0; 3],
            ],
            &[[0, 1, 2], [1, 0, 3], [0, 1, 4]],
        );
        assert!(kinds(&m).contains(&"non-manifold-edge"));
    }
}
