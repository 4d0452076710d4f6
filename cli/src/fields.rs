//! Per-vertex scalar fields: the core's star measures and a mean-curvature estimate, plus
//! their statistics and a colour map.

use clap::ValueEnum;

use crate::mesh::{add, area_vector, cross, dot, norm, normalize, sub, Mesh, P3};
use crate::progress::Progress;
use crate::topology::Topology;

/// A per-vertex quantity to show or measure.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Field {
    /// Discrete Willmore energy of each vertex star (tangent-polygon planarity, seed 000
    /// Fig. 9): 0 where the star is cospherical.
    Willmore,
    /// Mean curvature (cotangent Laplacian over the faces, fanned into triangles; positive
    /// where the surface is convex seen from outside). Interior vertices only.
    MeanCurvature,
    /// Möbius-regularity defect of each vertex star (seed 000 Fig. 15): 0 for a star that is
    /// a Möbius image of a regular one.
    MobiusRegularity,
}

impl Field {
    /// The name used on the command line and in output.
    pub fn name(self) -> &'static str {
        match self {
            Field::Willmore => "willmore",
            Field::MeanCurvature => "mean-curvature",
            Field::MobiusRegularity => "mobius-regularity",
        }
    }

    /// Whether the values have a sign that matters (a diverging colour map).
    pub fn signed(self) -> bool {
        self == Field::MeanCurvature
    }
}

/// Computes `field` at every vertex; `None` where it is not defined (isolated or
/// non-manifold vertices, degenerate stars, boundary vertices for mean curvature).
pub fn compute(
    field: Field,
    mesh: &Mesh,
    topo: &Topology,
    progress: &mut Progress,
) -> Vec<Option<f64>> {
    match field {
        Field::Willmore | Field::MobiusRegularity => {
            let mut out = Vec::with_capacity(mesh.num_vertices());
            let mut ring_pos: Vec<P3> = Vec::new();
            for v in 0..mesh.num_vertices() as u32 {
                progress.inc(1);
                let Some((ring, closed)) = topo.star(v) else {
                    out.push(None);
                    continue;
                };
                ring_pos.clear();
                ring_pos.extend(ring.iter().map(|&u| mesh.pos(u)));
                let p = mesh.pos(v);
                let r = match field {
                    Field::Willmore => nlsubdiv::metrics::willmore_energy(p, &ring_pos, closed),
                    _ => nlsubdiv::metrics::mobius_regularity(p, &ring_pos, closed),
                };
                out.push(r.ok().filter(|x| x.is_finite()));
            }
            out
        }
        Field::MeanCurvature => {
            let h = mean_curvature(mesh, topo);
            progress.inc(mesh.num_vertices() as u64);
            h
        }
    }
}

/// Mean curvature `H = −(L x · n) / (2 A)` with the cotangent Laplacian `L`, barycentric
/// vertex areas `A` and area-weighted vertex normals `n`; faces are fanned into triangles
/// from their first corner. `None` on the boundary and where the area vanishes.
pub fn mean_curvature(mesh: &Mesh, topo: &Topology) -> Vec<Option<f64>> {
    let nv = mesh.num_vertices();
    let mut lap = vec![[0.0; 3]; nv];
    let mut area = vec![0.0; nv];
    let mut normal = vec![[0.0; 3]; nv];
    for face in mesh.faces() {
        let an = area_vector(mesh, face);
        for &v in face {
            normal[v as usize] = add(normal[v as usize], an);
        }
        for i in 1..face.len().saturating_sub(1) {
            let t = [face[0], face[i], face[i + 1]];
            let p = t.map(|v| mesh.pos(v));
            let a2 = norm(cross(sub(p[1], p[0]), sub(p[2], p[0])));
            if a2 <= 0.0 {
                continue;
            }
            for k in 0..3 {
                let (i0, i1, i2) = (k, (k + 1) % 3, (k + 2) % 3);
                let e1 = sub(p[i1], p[i0]);
                let e2 = sub(p[i2], p[i0]);
                let cot = dot(e1, e2) / norm(cross(e1, e2)).max(f64::MIN_POSITIVE);
                let w = 0.5 * cot;
                let (a, b) = (t[i1] as usize, t[i2] as usize);
                let d = sub(p[i2], p[i1]);
                lap[a] = add(lap[a], [w * d[0], w * d[1], w * d[2]]);
                lap[b] = add(lap[b], [-w * d[0], -w * d[1], -w * d[2]]);
                area[t[i0] as usize] += a2 / 6.0;
            }
        }
    }
    (0..nv)
        .map(|v| {
            let (_, closed) = topo.star(v as u32)?;
            if !closed || area[v] <= 0.0 {
                return None;
            }
            let n = normalize(normal[v]);
            let h = -dot(lap[v], n) / (2.0 * area[v]);
            h.is_finite().then_some(h)
        })
        .collect()
}

/// Mean, maximum (with its vertex), root mean square and count of the defined values.
#[derive(Clone, Copy, Debug, Default)]
pub struct Stats {
    /// Number of vertices with a value.
    pub count: usize,
    /// Number of vertices without one (not counting isolated vertices).
    pub undefined: usize,
    /// Mean.
    pub mean: f64,
    /// Root mean square.
    pub rms: f64,
    /// Minimum.
    pub min: f64,
    /// Maximum.
    pub max: f64,
    /// A vertex where the maximum is reached (the first).
    pub argmax: usize,
}

impl Stats {
    /// Statistics of `values` over the vertices used by faces.
    pub fn of(values: &[Option<f64>], topo: &Topology) -> Stats {
        let mut s = Stats {
            min: f64::INFINITY,
            max: f64::NEG_INFINITY,
            ..Stats::default()
        };
        let (mut sum, mut sq) = (0.0, 0.0);
        for (v, x) in values.iter().enumerate() {
            match x {
                Some(x) => {
                    s.count += 1;
                    sum += x;
                    sq += x * x;
                    s.min = s.min.min(*x);
                    if *x > s.max {
                        s.max = *x;
                        s.argmax = v;
                    }
                }
                None if topo.face_count(v as u32) > 0 => s.undefined += 1,
                None => {}
            }
        }
        if s.count > 0 {
            s.mean = sum / s.count as f64;
            s.rms = (sq / s.count as f64).sqrt();
        } else {
            s.min = 0.0;
            s.max = 0.0;
        }
        s
    }
}

/// The value range a colour map spans: the 2nd to 98th percentile of the defined values
/// (symmetric about 0 for signed fields), so that a few extreme vertices do not wash out
/// the picture.
pub fn color_range(values: &[Option<f64>], signed: bool) -> (f64, f64) {
    let mut v: Vec<f64> = values.iter().flatten().copied().collect();
    if v.is_empty() {
        return (0.0, 1.0);
    }
    v.sort_by(f64::total_cmp);
    let q = |p: f64| v[((v.len() - 1) as f64 * p).round() as usize];
    let (mut lo, mut hi) = (q(0.02), q(0.98));
    if signed {
        let m = lo.abs().max(hi.abs());
        lo = -m;
        hi = m;
    }
    if hi - lo <= 0.0 || !(hi - lo).is_finite() {
        let m = if hi.abs() > 0.0 { hi.abs() } else { 1.0 };
        (lo - 0.5 * m, hi + 0.5 * m)
    } else {
        (lo, hi)
    }
}

/// Colour of `t` in 0…1: viridis for unsigned fields, a blue–white–red diverging map for
/// signed ones.
pub fn colormap(t: f64, signed: bool) -> [f64; 3] {
    let t = if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.5
    };
    let stops: &[[f64; 3]] = if signed {
        &[
            [0.23, 0.30, 0.75],
            [0.55, 0.69, 0.99],
            [0.87, 0.87, 0.87],
            [0.96, 0.60, 0.48],
            [0.71, 0.02, 0.15],
        ]
    } else {
        // viridis at 0, 1/6, …, 1
        &[
            [0.267, 0.005, 0.329],
            [0.255, 0.267, 0.529],
            [0.163, 0.471, 0.558],
            [0.134, 0.658, 0.518],
            [0.478, 0.821, 0.319],
            [0.741, 0.873, 0.150],
            [0.993, 0.906, 0.144],
        ]
    };
    let x = t * (stops.len() - 1) as f64;
    let i = (x.floor() as usize).min(stops.len() - 2);
    let f = x - i as f64;
    let (a, b) = (stops[i], stops[i + 1]);
    [
        a[0] + (b[0] - a[0]) * f,
        a[1] + (b[1] - a[1]) * f,
        a[2] + (b[2] - a[2]) * f,
    ]
}

/// The grey of vertices without a value.
pub const UNDEFINED_COLOR: [f64; 3] = [0.55, 0.55, 0.55];

/// 8-bit colours of `values` over `range`.
pub fn colors_u8(values: &[Option<f64>], range: (f64, f64), signed: bool) -> Vec<[u8; 3]> {
    values
        .iter()
        .map(|x| {
            let c = match x {
                Some(x) => colormap((x - range.0) / (range.1 - range.0), signed),
                None => UNDEFINED_COLOR,
            };
            c.map(|k| (k * 255.0).round().clamp(0.0, 255.0) as u8)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::Instant;

    fn icosahedron() -> Mesh {
        let t = (1.0 + 5f64.sqrt()) / 2.0;
        let p = vec![
            [-1.0, t, 0.0],
            [1.0, t, 0.0],
            [-1.0, -t, 0.0],
            [1.0, -t, 0.0],
            [0.0, -1.0, t],
            [0.0, 1.0, t],
            [0.0, -1.0, -t],
            [0.0, 1.0, -t],
            [t, 0.0, -1.0],
            [t, 0.0, 1.0],
            [-t, 0.0, -1.0],
            [-t, 0.0, 1.0],
        ];
        let f: [[u32; 3]; 20] = [
            [0, 11, 5],
            [0, 5, 1],
            [0, 1, 7],
            [0, 7, 10],
            [0, 10, 11],
            [1, 5, 9],
            [5, 11, 4],
            [11, 10, 2],
            [10, 7, 6],
            [7, 1, 8],
            [3, 9, 4],
            [3, 4, 2],
            [3, 2, 6],
            [3, 6, 8],
            [3, 8, 9],
            [4, 9, 5],
            [2, 4, 11],
            [6, 2, 10],
            [8, 6, 7],
            [9, 8, 1],
        ];
        Mesh::from_faces(p, &f)
    }

    #[test]
    fn icosahedron_fields() {
        let m = icosahedron();
        let t = Topology::build(&m);
        let mut p = Progress::new(false, Instant::now(), 0, "");
        let w = compute(Field::Willmore, &m, &t, &mut p);
        assert!(w.iter().all(|x| x.unwrap() < 1e-12), "{w:?}");
        let mr = compute(Field::MobiusRegularity, &m, &t, &mut p);
        assert!(mr.iter().all(|x| x.unwrap() < 1e-20), "{mr:?}");
        let h = compute(Field::MeanCurvature, &m, &t, &mut p);
        // Circumradius of this icosahedron: sqrt(1 + t²) ≈ 1.902; H ≈ 1/R, positive.
        let r = (1.0 + ((1.0 + 5f64.sqrt()) / 2.0).powi(2)).sqrt();
        for x in &h {
            let x = x.unwrap();
            assert!(x > 0.0 && (x * r - 1.0).abs() < 0.35, "{x}");
        }
    }
}
