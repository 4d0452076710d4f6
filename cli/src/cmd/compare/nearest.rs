//! Nearest points for `compare`: a k-d tree over the *distinct* positions of a mesh, each
//! holding the vertices at that position.
//!
//! Why not a uniform grid: a grid sized for evenly spread points degenerates when they are
//! not (all but one point in a tiny cluster, or thousands of vertices at one position —
//! both valid meshes), and every query then scans the crowded cell: quadratic time. A k-d
//! tree of the distinct positions is built in O(n log n) and answers a query in O(log n) for
//! any spread; coincident vertices are one entry, so they cost one distance, not thousands.
//!
//! Distances are computed on the caller's (scaled) coordinates exactly as
//! `dx² + dy² + dz²`; every position at exactly the smallest distance is returned, so the
//! result does not depend on the shape of the tree.

use crate::mesh::P3;

/// The vertices at one distinct position, ascending, and how many have been matched.
#[derive(Debug)]
pub struct Group {
    /// The position.
    pub p: P3,
    /// Vertex ids at this position, ascending.
    pub members: Vec<u32>,
    /// `members[..used]` are matched (the matching takes them in ascending order).
    pub used: usize,
}

/// A k-d tree over groups of coincident points.
#[derive(Debug)]
pub struct Nearest {
    /// The groups, in tree order: the node of `groups[lo..hi]` is its middle element.
    pub groups: Vec<Group>,
    /// The split axis of every node (by the index of its middle element).
    axis: Vec<u8>,
}

fn key(p: P3) -> [u64; 3] {
    // +0.0 merges the two zeros: -0.0 and 0.0 are the same position.
    p.map(|x| (x + 0.0).to_bits())
}

fn d2(a: P3, b: P3) -> f64 {
    let (x, y, z) = (a[0] - b[0], a[1] - b[1], a[2] - b[2]);
    x * x + y * y + z * z
}

impl Nearest {
    /// Groups `points` by position and builds the tree.
    pub fn new(points: &[P3]) -> Nearest {
        let mut order: Vec<u32> = (0..points.len() as u32).collect();
        order.sort_unstable_by_key(|&i| (key(points[i as usize]), i));
        let mut groups: Vec<Group> = Vec::new();
        for &i in &order {
            let p = points[i as usize];
            match groups.last_mut() {
                Some(g) if key(g.p) == key(p) => g.members.push(i),
                _ => groups.push(Group {
                    p,
                    members: vec![i],
                    used: 0,
                }),
            }
        }
        let mut axis = vec![0u8; groups.len()];
        build(&mut groups, &mut axis);
        Nearest { groups, axis }
    }

    /// The squared distance from `q` to the nearest positions and the groups at exactly that
    /// distance (indices into [`Nearest::groups`]); `None` without points.
    pub fn query(&self, q: P3) -> Option<(f64, Vec<usize>)> {
        if self.groups.is_empty() {
            return None;
        }
        let mut best = f64::INFINITY;
        let mut found = Vec::new();
        self.search(0, self.groups.len(), q, &mut best, &mut found);
        Some((best, found))
    }

    fn search(&self, lo: usize, hi: usize, q: P3, best: &mut f64, found: &mut Vec<usize>) {
        if lo >= hi {
            return;
        }
        let mid = lo + (hi - lo) / 2;
        let g = &self.groups[mid];
        let d = d2(g.p, q);
        if d < *best {
            *best = d;
            found.clear();
            found.push(mid);
        } else if d == *best {
            found.push(mid);
        }
        let a = usize::from(self.axis[mid]);
        let delta = q[a] - g.p[a];
        let (near, far) = if delta < 0.0 {
            ((lo, mid), (mid + 1, hi))
        } else {
            ((mid + 1, hi), (lo, mid))
        };
        self.search(near.0, near.1, q, best, found);
        // Points at exactly the best distance are wanted too: `<=`.
        if delta * delta <= *best {
            self.search(far.0, far.1, q, best, found);
        }
    }
}

/// Arranges `g` as an implicit k-d tree: the middle element splits the rest along the axis
/// of largest extent; smaller coordinates go left. Ties are ordered by vertex id, so the
/// tree is deterministic.
fn build(g: &mut [Group], axis: &mut [u8]) {
    if g.len() <= 1 {
        return;
    }
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for x in g.iter() {
        for k in 0..3 {
            lo[k] = lo[k].min(x.p[k]);
            hi[k] = hi[k].max(x.p[k]);
        }
    }
    let ext = [hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]];
    let a = if ext[0] >= ext[1] && ext[0] >= ext[2] {
        0
    } else if ext[1] >= ext[2] {
        1
    } else {
        2
    };
    let mid = g.len() / 2;
    g.select_nth_unstable_by(mid, |x, y| {
        x.p[a]
            .total_cmp(&y.p[a])
            .then_with(|| x.members[0].cmp(&y.members[0]))
    });
    axis[mid] = a as u8;
    let (left, right) = g.split_at_mut(mid);
    let (al, ar) = axis.split_at_mut(mid);
    build(left, al);
    if let (Some((_, rest)), Some((_, arest))) = (right.split_first_mut(), ar.split_first_mut()) {
        build(rest, arest);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matches_brute_force_with_ties_and_clusters() {
        let mut s = 12345u64;
        let mut rnd = || {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (s >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut pts: Vec<P3> = (0..1500).map(|_| [rnd(), rnd(), rnd() * 1e-9]).collect();
        pts.extend(std::iter::repeat_n([0.5, 0.5, 0.0], 300));
        pts.push([1e3, 0.0, 0.0]);
        // Lattice points: many exact ties.
        for i in 0..5 {
            for j in 0..5 {
                pts.push([2.0 + i as f64, 2.0 + j as f64, 0.0]);
            }
        }
        let t = Nearest::new(&pts);
        for qi in 0..400 {
            let q = if qi % 4 == 0 {
                [4.0, 4.0, 0.0]
            } else {
                [rnd() * 8.0 - 1.0, rnd() * 8.0 - 1.0, rnd() - 0.5]
            };
            let (d, gs) = t.query(q).unwrap();
            let bf = pts.iter().map(|p| d2(*p, q)).fold(f64::INFINITY, f64::min);
            assert_eq!(d, bf);
            let mut got: Vec<u32> = gs
                .iter()
                .flat_map(|&g| t.groups[g].members.iter().copied())
                .collect();
            got.sort_unstable();
            let want: Vec<u32> = (0..pts.len() as u32)
                .filter(|&i| d2(pts[i as usize], q) == bf)
                .collect();
            assert_eq!(got, want);
        }
    }
}
