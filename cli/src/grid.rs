//! A uniform grid over points for nearest-neighbour queries (about one point per cell).

use crate::mesh::{bbox, P3};

/// Points bucketed in a uniform grid.
#[derive(Debug)]
pub struct Grid {
    lo: P3,
    cell: f64,
    dims: [usize; 3],
    /// Cell `c` holds `items[start[c]..start[c + 1]]`, point indices ascending.
    start: Vec<u32>,
    items: Vec<u32>,
}

impl Grid {
    /// Buckets `points` (finite coordinates).
    pub fn new(points: &[P3]) -> Grid {
        let (lo, hi) = bbox(points).unwrap_or(([0.0; 3], [0.0; 3]));
        let ext = [hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]];
        let max_ext = ext[0].max(ext[1]).max(ext[2]);
        let n = points.len().max(1) as u64;
        let mut cell = if max_ext > 0.0 { max_ext } else { 1.0 };
        let dims_for = |cell: f64| ext.map(|e| ((e / cell).floor() as usize).saturating_add(1));
        // Halve the cell until there are about as many cells as points.
        for _ in 0..64 {
            let d = dims_for(cell * 0.5);
            let cells = d.iter().fold(1u64, |a, &x| a.saturating_mul(x as u64));
            if cells > 2 * n {
                break;
            }
            cell *= 0.5;
        }
        let dims = dims_for(cell);
        let ncells = dims[0] * dims[1] * dims[2];
        let mut g = Grid {
            lo,
            cell,
            dims,
            start: vec![0; ncells + 1],
            items: vec![0; points.len()],
        };
        let ids: Vec<usize> = points.iter().map(|p| g.cell_index(g.coords(*p))).collect();
        for &c in &ids {
            g.start[c + 1] += 1;
        }
        for c in 0..ncells {
            g.start[c + 1] += g.start[c];
        }
        let mut fill = g.start.clone();
        for (i, &c) in ids.iter().enumerate() {
            g.items[fill[c] as usize] = i as u32;
            fill[c] += 1;
        }
        g
    }

    fn coords(&self, p: P3) -> [usize; 3] {
        let mut c = [0usize; 3];
        for k in 0..3 {
            let x = ((p[k] - self.lo[k]) / self.cell).floor();
            c[k] = if x.is_nan() || x < 0.0 {
                0
            } else {
                (x as usize).min(self.dims[k] - 1)
            };
        }
        c
    }

    fn cell_index(&self, c: [usize; 3]) -> usize {
        (c[2] * self.dims[1] + c[1]) * self.dims[0] + c[0]
    }

    /// The squared distance from `q` to its nearest points and all points at exactly that
    /// distance, ascending; `None` without points.
    pub fn nearest(&self, points: &[P3], q: P3) -> Option<(f64, Vec<u32>)> {
        if points.is_empty() {
            return None;
        }
        let c = self.coords(q);
        let mut best = f64::INFINITY;
        let mut found: Vec<u32> = Vec::new();
        let max_r = self.dims.iter().copied().max().unwrap_or(1);
        for r in 0..=max_r {
            // Points in shells beyond r are at least r·cell away.
            let bound = (r as f64 - 1.0).max(0.0) * self.cell;
            if !found.is_empty() && best < bound * bound {
                break;
            }
            let lo = c.map(|x| x.saturating_sub(r));
            let hi = [0, 1, 2].map(|k| (c[k] + r).min(self.dims[k] - 1));
            for z in lo[2]..=hi[2] {
                for y in lo[1]..=hi[1] {
                    for x in lo[0]..=hi[0] {
                        let shell = x.abs_diff(c[0]).max(y.abs_diff(c[1])).max(z.abs_diff(c[2]));
                        if shell != r {
                            continue;
                        }
                        let ci = self.cell_index([x, y, z]);
                        let (a, b) = (self.start[ci] as usize, self.start[ci + 1] as usize);
                        for &i in &self.items[a..b] {
                            let p = points[i as usize];
                            let d = (p[0] - q[0]) * (p[0] - q[0])
                                + (p[1] - q[1]) * (p[1] - q[1])
                                + (p[2] - q[2]) * (p[2] - q[2]);
                            if d < best {
                                best = d;
                                found.clear();
                                found.push(i);
                            } else if d == best {
                                found.push(i);
                            }
                        }
                    }
                }
            }
        }
        found.sort_unstable();
        Some((best, found))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matches_brute_force() {
        let mut s = 12345u64;
        let mut rnd = || {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (s >> 11) as f64 / (1u64 << 53) as f64
        };
        for flat in [false, true] {
            let pts: Vec<P3> = (0..2000)
                .map(|_| [rnd(), rnd() * 3.0, if flat { 0.5 } else { rnd() }])
                .collect();
            let g = Grid::new(&pts);
            for _ in 0..300 {
                let q = [rnd() * 1.4 - 0.2, rnd() * 3.4 - 0.2, rnd() * 1.4 - 0.2];
                let (d, ids) = g.nearest(&pts, q).unwrap();
                let bf = pts
                    .iter()
                    .map(|p| (p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2))
                    .fold(f64::INFINITY, f64::min);
                assert!((d - bf).abs() <= 1e-15, "{d} {bf}");
                assert!(!ids.is_empty());
            }
        }
        let same = vec![[1.0, 2.0, 3.0]; 5];
        let g = Grid::new(&same);
        assert_eq!(g.nearest(&same, [0.0; 3]).unwrap().1, vec![0, 1, 2, 3, 4]);
    }
}
