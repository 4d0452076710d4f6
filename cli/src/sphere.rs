//! Least-squares sphere fit: an algebraic fit refined by Gauss–Newton on the geometric
//! distances `|p − c| − r`.

use crate::mesh::{norm, sub, P3};

/// A fitted sphere and the distances of the points from it.
#[derive(Clone, Copy, Debug)]
pub struct SphereFit {
    /// Centre.
    pub center: P3,
    /// Radius.
    pub radius: f64,
    /// Root mean square of `|p − c| − r`, divided by `r`.
    pub rms_relative: f64,
    /// Maximum of `||p − c| − r|`, divided by `r`.
    pub max_relative: f64,
    /// A point where the maximum is reached.
    pub argmax: usize,
}

/// Solves the 4×4 system `a x = b` by Gaussian elimination with partial pivoting; `None`
/// when it is (numerically) singular.
fn solve4(mut a: [[f64; 4]; 4], mut b: [f64; 4]) -> Option<[f64; 4]> {
    let scale = a.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
    if scale == 0.0 || !scale.is_finite() {
        return None;
    }
    for col in 0..4 {
        let piv = (col..4).max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))?;
        if a[piv][col].abs() <= 1e-13 * scale {
            return None;
        }
        a.swap(col, piv);
        b.swap(col, piv);
        for r in col + 1..4 {
            let f = a[r][col] / a[col][col];
            let pivot_row = a[col];
            for (x, p) in a[r].iter_mut().zip(pivot_row).skip(col) {
                *x -= f * p;
            }
            b[r] -= f * b[col];
        }
    }
    let mut x = [0.0; 4];
    for r in (0..4).rev() {
        let mut s = b[r];
        for k in r + 1..4 {
            s -= a[r][k] * x[k];
        }
        x[r] = s / a[r][r];
    }
    Some(x)
}

/// Fits a sphere to `points`; `None` for fewer than 4 points or (nearly) coplanar ones.
pub fn fit(points: &[P3]) -> Option<SphereFit> {
    if points.len() < 4 {
        return None;
    }
    // Centre and scale for conditioning.
    let n = points.len() as f64;
    let mut m = [0.0; 3];
    for p in points {
        for k in 0..3 {
            m[k] += p[k] / n;
        }
    }
    let s = (points.iter().map(|p| norm(sub(*p, m)).powi(2)).sum::<f64>() / n).sqrt();
    if s == 0.0 || !s.is_finite() {
        return None;
    }
    let q: Vec<P3> = points.iter().map(|p| sub(*p, m).map(|x| x / s)).collect();
    // Algebraic fit: |q|² = 2 c·q + d, linear in (c, d).
    let mut ata = [[0.0; 4]; 4];
    let mut atb = [0.0; 4];
    for p in &q {
        let row = [2.0 * p[0], 2.0 * p[1], 2.0 * p[2], 1.0];
        let rhs = p[0] * p[0] + p[1] * p[1] + p[2] * p[2];
        for i in 0..4 {
            for j in 0..4 {
                ata[i][j] += row[i] * row[j];
            }
            atb[i] += row[i] * rhs;
        }
    }
    let x = solve4(ata, atb)?;
    let mut c = [x[0], x[1], x[2]];
    let r2 = x[3] + c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
    if r2.is_nan() || r2 <= 0.0 {
        return None;
    }
    let mut r = r2.sqrt();
    if r > 1e6 {
        return None; // a plane, as far as a sphere can tell
    }
    // Gauss–Newton on the geometric residuals.
    for _ in 0..20 {
        let mut jtj = [[0.0; 4]; 4];
        let mut jtr = [0.0; 4];
        for p in &q {
            let d = sub(*p, c);
            let l = norm(d);
            if l == 0.0 {
                continue;
            }
            let row = [-d[0] / l, -d[1] / l, -d[2] / l, -1.0];
            let res = l - r;
            for i in 0..4 {
                for j in 0..4 {
                    jtj[i][j] += row[i] * row[j];
                }
                jtr[i] -= row[i] * res;
            }
        }
        let Some(step) = solve4(jtj, jtr) else { break };
        c = [c[0] + step[0], c[1] + step[1], c[2] + step[2]];
        r += step[3];
        if step.iter().map(|x| x.abs()).fold(0.0, f64::max) < 1e-15 {
            break;
        }
    }
    if !r.is_finite() || r <= 0.0 {
        return None;
    }
    let (mut sq, mut mx, mut arg) = (0.0, 0.0, 0);
    for (i, p) in q.iter().enumerate() {
        let e = (norm(sub(*p, c)) - r).abs();
        sq += e * e;
        if e > mx {
            mx = e;
            arg = i;
        }
    }
    Some(SphereFit {
        center: [m[0] + s * c[0], m[1] + s * c[1], m[2] + s * c[2]],
        radius: s * r,
        rms_relative: (sq / n).sqrt() / r,
        max_relative: mx / r,
        argmax: arg,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn recovers_a_sphere() {
        let mut pts = Vec::new();
        for i in 0..20 {
            for j in 0..10 {
                let (th, ph) = (0.3 + i as f64 * 0.29, 0.2 + j as f64 * 0.3);
                pts.push([
                    5.0 + 2.5 * ph.sin() * th.cos(),
                    -1.0 + 2.5 * ph.sin() * th.sin(),
                    7.0 + 2.5 * ph.cos(),
                ]);
            }
        }
        let f = fit(&pts).unwrap();
        assert!((f.radius - 2.5).abs() < 1e-12, "{f:?}");
        assert!((f.center[0] - 5.0).abs() < 1e-12 && (f.center[2] - 7.0).abs() < 1e-12);
        assert!(f.max_relative < 1e-13);
        let plane: Vec<P3> = (0..50)
            .map(|i| [i as f64, (i * i % 7) as f64, 0.0])
            .collect();
        assert!(fit(&plane).is_none());
    }
}
