//! Distances between triangle meshes for the seed 001 Fig. 4 examples: exact point–triangle
//! distance, a bounding-volume hierarchy, the vertex-sampled symmetric Hausdorff distance and
//! the bounding-box diagonal.

use crate::common::OwnedMesh;
use nlsubdiv::Point;

pub fn sub(a: Point, b: Point) -> Point {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
pub fn dot(a: Point, b: Point) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn add_s(a: Point, s: f64, b: Point) -> Point {
    [a[0] + s * b[0], a[1] + s * b[1], a[2] + s * b[2]]
}

/// Squared distance from `p` to the triangle `abc` (closest point by Voronoi regions,
/// Ericson, Real-Time Collision Detection §5.1.5).
fn point_triangle_d2(p: Point, a: Point, b: Point, c: Point) -> f64 {
    let (ab, ac, ap) = (sub(b, a), sub(c, a), sub(p, a));
    let (d1, d2) = (dot(ab, ap), dot(ac, ap));
    let q = if d1 <= 0.0 && d2 <= 0.0 {
        a
    } else {
        let bp = sub(p, b);
        let (d3, d4) = (dot(ab, bp), dot(ac, bp));
        if d3 >= 0.0 && d4 <= d3 {
            b
        } else {
            let vc = d1 * d4 - d3 * d2;
            if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
                add_s(a, d1 / (d1 - d3), ab)
            } else {
                let cp = sub(p, c);
                let (d5, d6) = (dot(ab, cp), dot(ac, cp));
                if d6 >= 0.0 && d5 <= d6 {
                    c
                } else {
                    let vb = d5 * d2 - d1 * d6;
                    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
                        add_s(a, d2 / (d2 - d6), ac)
                    } else {
                        let va = d3 * d6 - d5 * d4;
                        if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
                            add_s(b, (d4 - d3) / ((d4 - d3) + (d5 - d6)), sub(c, b))
                        } else {
                            let den = 1.0 / (va + vb + vc);
                            add_s(add_s(a, vb * den, ab), vc * den, ac)
                        }
                    }
                }
            }
        }
    };
    let d = sub(p, q);
    dot(d, d)
}

/// A bounding-volume hierarchy of a triangle mesh's faces for nearest-surface queries
/// (median split on the longest axis; best-first descent pruned by box distance).
struct Bvh<'a> {
    pos: &'a [Point],
    faces: Vec<[u32; 3]>,
    /// Per node: box (lo, hi), and either children (left, right) or a leaf range.
    nodes: Vec<Node>,
}

#[derive(Clone, Copy)]
struct Node {
    lo: Point,
    hi: Point,
    /// Leaf: `first..first + count` of `faces`; inner: `count == 0`, children `first`,
    /// `first + 1`.
    first: usize,
    count: usize,
}

impl<'a> Bvh<'a> {
    fn new(m: &'a OwnedMesh) -> Self {
        let pos = &m.positions[..];
        let mut faces: Vec<[u32; 3]> = m.indices.chunks(3).map(|f| [f[0], f[1], f[2]]).collect();
        let mut nodes = vec![Node {
            lo: [0.0; 3],
            hi: [0.0; 3],
            first: 0,
            count: faces.len(),
        }];
        let centroid = |f: &[u32; 3], a: usize| {
            (pos[f[0] as usize][a] + pos[f[1] as usize][a] + pos[f[2] as usize][a]) / 3.0
        };
        let mut stack = vec![0usize];
        while let Some(ni) = stack.pop() {
            let (first, count) = (nodes[ni].first, nodes[ni].count);
            let mut lo = [f64::INFINITY; 3];
            let mut hi = [f64::NEG_INFINITY; 3];
            for f in &faces[first..first + count] {
                for &v in f {
                    for c in 0..3 {
                        lo[c] = lo[c].min(pos[v as usize][c]);
                        hi[c] = hi[c].max(pos[v as usize][c]);
                    }
                }
            }
            nodes[ni].lo = lo;
            nodes[ni].hi = hi;
            if count <= 4 {
                continue;
            }
            let ext = sub(hi, lo);
            let axis = if ext[0] >= ext[1] && ext[0] >= ext[2] {
                0
            } else if ext[1] >= ext[2] {
                1
            } else {
                2
            };
            let half = count / 2;
            faces[first..first + count].select_nth_unstable_by(half, |x, y| {
                centroid(x, axis).total_cmp(&centroid(y, axis))
            });
            let left = nodes.len();
            nodes.push(Node {
                lo,
                hi,
                first,
                count: half,
            });
            nodes.push(Node {
                lo,
                hi,
                first: first + half,
                count: count - half,
            });
            nodes[ni].first = left;
            nodes[ni].count = 0;
            stack.push(left);
            stack.push(left + 1);
        }
        Bvh { pos, faces, nodes }
    }

    fn box_d2(n: &Node, p: Point) -> f64 {
        let mut d = 0.0;
        for ((lo, hi), x) in n.lo.iter().zip(&n.hi).zip(&p) {
            let e = (lo - x).max(x - hi).max(0.0);
            d += e * e;
        }
        d
    }

    /// Distance from `p` to the surface.
    fn distance(&self, p: Point) -> f64 {
        let mut best = f64::INFINITY;
        let mut stack = vec![0usize];
        while let Some(ni) = stack.pop() {
            let n = self.nodes[ni];
            if Self::box_d2(&n, p) >= best {
                continue;
            }
            if n.count > 0 {
                for f in &self.faces[n.first..n.first + n.count] {
                    let q = |v: u32| self.pos[v as usize];
                    best = best.min(point_triangle_d2(p, q(f[0]), q(f[1]), q(f[2])));
                }
            } else {
                // Nearer child last, so that it is searched first.
                let (a, b) = (n.first, n.first + 1);
                let (da, db) = (
                    Self::box_d2(&self.nodes[a], p),
                    Self::box_d2(&self.nodes[b], p),
                );
                if da < db {
                    stack.push(b);
                    stack.push(a);
                } else {
                    stack.push(a);
                    stack.push(b);
                }
            }
        }
        best.sqrt()
    }
}

/// Vertex-sampled symmetric Hausdorff distance, over the vertices `va` of `a` and `vb` of `b`.
pub fn hausdorff(a: &OwnedMesh, va: &[usize], b: &OwnedMesh, vb: &[usize]) -> f64 {
    let (ga, gb) = (Bvh::new(a), Bvh::new(b));
    let ab = va
        .iter()
        .map(|&v| gb.distance(a.positions[v]))
        .fold(0.0, f64::max);
    let ba = vb
        .iter()
        .map(|&v| ga.distance(b.positions[v]))
        .fold(0.0, f64::max);
    ab.max(ba)
}

pub fn diagonal(m: &OwnedMesh) -> f64 {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in &m.positions {
        for c in 0..3 {
            lo[c] = lo[c].min(p[c]);
            hi[c] = hi[c].max(p[c]);
        }
    }
    dot(sub(hi, lo), sub(hi, lo)).sqrt()
}
