//! The demo's bundled input: a coarse dome-like control cage in the spirit of the
//! architectural cage of seed 000, Fig. 1 (a metro-station cover designed on a coarse
//! polygonal cage, then subdivided).
//!
//! A spherical cap (y up) of five rings of vertices — 6, 12, 12, 24 and 24 — joined by a
//! hexagon at the crown, a ring of 6 pentagons (6 → 12 segments), 12 quads, 12 pentagons
//! (12 → 24) and 24 quads down to the boundary ring: 78 vertices, 55 faces (1 hexagon,
//! 18 pentagons, 36 quads), one boundary loop. Valence-3 vertices and the pentagons and
//! hexagon give the extraordinary points a mixed-face cage has. With `arches`, the lower
//! rings are lifted between six supports into arched openings, so the surface is no
//! longer a sphere; without, every vertex lies on the unit sphere.

use crate::mesh::{area_vector, dot, Mesh};

/// Polar angles (degrees from the crown) and vertex counts of the rings.
const RINGS: [(f64, u32); 5] = [(15.0, 6), (32.0, 12), (50.0, 12), (68.0, 24), (84.0, 24)];

/// Height of the arches at the boundary (the unit sphere's radius is 1).
const ARCH: f64 = 0.3;

/// The cage; see the module docs.
pub fn cage(arches: bool) -> Mesh {
    let mut positions = Vec::new();
    let mut start = Vec::new();
    let theta_max = RINGS[RINGS.len() - 1].0.to_radians();
    for &(theta_deg, count) in &RINGS {
        start.push(positions.len() as u32);
        let theta = theta_deg.to_radians();
        for j in 0..count {
            let phi = std::f64::consts::TAU * f64::from(j) / f64::from(count);
            let mut p = [
                theta.sin() * phi.cos(),
                theta.cos(),
                -theta.sin() * phi.sin(),
            ];
            if arches {
                // Six supports at φ = 0°, 60°, …; the arches rise between them, more and more
                // towards the boundary.
                let t = theta / theta_max;
                p[1] += ARCH * t.powi(4) * 0.5 * (1.0 - (6.0 * phi).cos());
            }
            positions.push(p);
        }
    }
    let v = |ring: usize, j: u32| start[ring] + j % RINGS[ring].1;
    let mut faces: Vec<Vec<u32>> = vec![(0..RINGS[0].1).map(|j| v(0, j)).collect()];
    for ring in 0..RINGS.len() - 1 {
        let (n, m) = (RINGS[ring].1, RINGS[ring + 1].1);
        for j in 0..n {
            if m == n {
                faces.push(vec![
                    v(ring, j),
                    v(ring + 1, j),
                    v(ring + 1, j + 1),
                    v(ring, j + 1),
                ]);
            } else {
                faces.push(vec![
                    v(ring, j),
                    v(ring + 1, 2 * j),
                    v(ring + 1, 2 * j + 1),
                    v(ring + 1, 2 * j + 2),
                    v(ring, j + 1),
                ]);
            }
        }
    }
    let mut m = Mesh {
        positions,
        ..Mesh::default()
    };
    for f in &faces {
        m.indices.extend_from_slice(f);
        m.offsets.push(m.indices.len() as u32);
    }
    // Counter-clockwise seen from outside (from above at the crown).
    if dot(area_vector(&m, m.face(0)), [0.0, 1.0, 0.0]) < 0.0 {
        for f in 0..m.num_faces() {
            let (a, b) = (m.offsets[f] as usize, m.offsets[f + 1] as usize);
            m.indices[a..b].reverse();
        }
    }
    m
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{norm, Source};
    use crate::topology::Topology;

    #[test]
    fn the_cage_is_a_clean_disk_facing_outwards() {
        for arches in [false, true] {
            let m = cage(arches);
            assert_eq!((m.num_vertices(), m.num_faces()), (78, 55));
            let topo = Topology::build(&m);
            let findings = topo.findings(&m, &Source::new(std::path::Path::new("cage")));
            assert!(findings.is_empty(), "{findings:?}");
            assert_eq!(topo.boundary_loop_starts().len(), 1);
            for f in m.faces() {
                let c = f.iter().fold([0.0; 3], |s, &i| {
                    let p = m.pos(i);
                    [s[0] + p[0], s[1] + p[1], s[2] + p[2]]
                });
                assert!(dot(area_vector(&m, f), c) > 0.0, "face {f:?} faces inwards");
            }
            if !arches {
                for p in &m.positions {
                    assert!((norm(*p) - 1.0).abs() < 1e-15);
                }
            }
        }
    }
}
