//! The mesh as the command holds it: the layout of the core's mesh API (positions, faces as
//! CSR offsets and indices), plus where each element came from, for messages.

use std::path::{Path, PathBuf};

/// A point or vector.
pub type P3 = nlsubdiv::Point;

/// A polygon mesh in the layout of the core's mesh API: `positions[V]`, `offsets[F + 1]`
/// (`offsets[0] = 0`), `indices[offsets[F]]`; face `f` is `indices[offsets[f]..offsets[f+1]]`,
/// counter-clockwise seen from outside.
///
/// Every mesh the readers return has `offsets` well formed and every index below `V`.
#[derive(Clone, Debug, PartialEq)]
pub struct Mesh {
    /// Vertex positions.
    pub positions: Vec<P3>,
    /// Face offsets, `F + 1` entries.
    pub offsets: Vec<u32>,
    /// Corner vertex indices, face after face.
    pub indices: Vec<u32>,
}

impl Default for Mesh {
    fn default() -> Self {
        Mesh {
            positions: Vec::new(),
            offsets: vec![0],
            indices: Vec::new(),
        }
    }
}

impl Mesh {
    /// A mesh from positions and a list of faces (tests build meshes with it).
    pub fn from_faces<F: AsRef<[u32]>>(positions: Vec<P3>, faces: &[F]) -> Mesh {
        let mut m = Mesh {
            positions,
            ..Mesh::default()
        };
        for f in faces {
            m.indices.extend_from_slice(f.as_ref());
            m.offsets.push(m.indices.len() as u32);
        }
        m
    }

    /// Number of vertices (referenced or not).
    pub fn num_vertices(&self) -> usize {
        self.positions.len()
    }

    /// Number of faces.
    pub fn num_faces(&self) -> usize {
        self.offsets.len().saturating_sub(1)
    }

    /// The vertex indices of face `f` (`f < num_faces()`).
    pub fn face(&self, f: usize) -> &[u32] {
        &self.indices[self.offsets[f] as usize..self.offsets[f + 1] as usize]
    }

    /// All faces in order.
    pub fn faces(&self) -> impl Iterator<Item = &[u32]> + '_ {
        self.offsets
            .windows(2)
            .map(|w| &self.indices[w[0] as usize..w[1] as usize])
    }

    /// Position of vertex `v`.
    pub fn pos(&self, v: u32) -> P3 {
        self.positions[v as usize]
    }

    /// Axis-aligned bounding box of all vertices, `None` without vertices.
    pub fn bbox(&self) -> Option<(P3, P3)> {
        bbox(&self.positions)
    }
}

/// Axis-aligned bounding box of points, `None` for none.
pub fn bbox(points: &[P3]) -> Option<(P3, P3)> {
    let first = *points.first()?;
    let mut lo = first;
    let mut hi = first;
    for p in points {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    Some((lo, hi))
}

// Vector arithmetic is the kernel's (`nlsubdiv::point`): the same operations, in the same
// order, as the rules that produced the meshes this command measures. `norm` is the scaled
// one, which neither overflows nor underflows at the ends of the double range.
pub use nlsubdiv::point::{add, cross, dot, norm, scale, sub};

/// `a / |a|`, or zero for a zero vector.
pub fn normalize(a: P3) -> P3 {
    let n = norm(a);
    if n > 0.0 {
        scale(a, 1.0 / n)
    } else {
        [0.0; 3]
    }
}

/// The area vector of a polygon (Newell's method): its length is the area of a planar
/// polygon, its direction the normal (counter-clockwise orientation).
pub fn area_vector(m: &Mesh, face: &[u32]) -> P3 {
    let n = face.len();
    let mut s = [0.0; 3];
    if n < 3 {
        return s;
    }
    // Relative to the first corner, for accuracy far from the origin.
    let o = m.pos(face[0]);
    for i in 1..n - 1 {
        let a = sub(m.pos(face[i]), o);
        let b = sub(m.pos(face[i + 1]), o);
        s = add(s, cross(a, b));
    }
    scale(s, 0.5)
}

/// Sharp-feature tags read from a file (OBJ `t crease` and `t corner` statements), each
/// with the line it came from, in the layout of the kernel's `Tags`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FileTags {
    /// Tagged edges as vertex pairs (0-based).
    pub creases: Vec<[u32; 2]>,
    /// Their sharpness.
    pub crease_sharpness: Vec<f64>,
    /// The line of each tagged edge.
    pub crease_lines: Vec<u32>,
    /// Tagged vertices (0-based).
    pub corners: Vec<u32>,
    /// Their sharpness.
    pub corner_sharpness: Vec<f64>,
    /// The line of each tagged vertex.
    pub corner_lines: Vec<u32>,
}

impl FileTags {
    /// Whether there is no tag.
    pub fn is_empty(&self) -> bool {
        self.creases.is_empty() && self.corners.is_empty()
    }

    /// The line of tag `element` as the kernel numbers tags (creases, then corners).
    pub fn line_of(&self, element: usize) -> Option<u32> {
        match element.checked_sub(self.creases.len()) {
            None => self.crease_lines.get(element).copied(),
            Some(j) => self.corner_lines.get(j).copied(),
        }
    }
}

/// Where a mesh came from: the file, its format, and the line of each element where the
/// format has lines. Used to name the line and element at fault in messages.
#[derive(Clone, Debug)]
pub struct Source {
    /// The file read.
    pub path: PathBuf,
    lines: Lines,
    /// Sharp-feature tags the file carries (OBJ only; empty otherwise).
    pub tags: FileTags,
}

#[derive(Clone, Debug)]
enum Lines {
    /// No line numbers (binary PLY, generated meshes).
    None,
    /// The line where each vertex and face starts (OFF, OBJ, ASCII PLY).
    PerElement { vertex: Vec<u32>, face: Vec<u32> },
}

impl Source {
    /// A source without line information.
    pub fn new(path: &Path) -> Source {
        Source {
            path: path.to_path_buf(),
            lines: Lines::None,
            tags: FileTags::default(),
        }
    }

    /// A source with the starting line of every vertex and face.
    pub fn with_lines(path: &Path, vertex: Vec<u32>, face: Vec<u32>) -> Source {
        Source {
            path: path.to_path_buf(),
            lines: Lines::PerElement { vertex, face },
            tags: FileTags::default(),
        }
    }

    /// The line of vertex `v`, when known.
    pub fn vertex_line(&self, v: usize) -> Option<u32> {
        match &self.lines {
            Lines::None => None,
            Lines::PerElement { vertex, .. } => vertex.get(v).copied(),
        }
    }

    /// The line of face `f`, when known.
    pub fn face_line(&self, f: usize) -> Option<u32> {
        match &self.lines {
            Lines::None => None,
            Lines::PerElement { face, .. } => face.get(f).copied(),
        }
    }

    /// `path:line: vertex v` (or `path: vertex v` without a line).
    pub fn at_vertex(&self, v: usize) -> String {
        self.at(self.vertex_line(v), &format!("vertex {v}"))
    }

    /// `path:line: face f` (or `path: face f` without a line).
    pub fn at_face(&self, f: usize) -> String {
        self.at(self.face_line(f), &format!("face {f}"))
    }

    /// `path:line: what`.
    pub fn at(&self, line: Option<u32>, what: &str) -> String {
        match line {
            Some(l) => format!("{}:{l}: {what}", self.path.display()),
            None => format!("{}: {what}", self.path.display()),
        }
    }
}
