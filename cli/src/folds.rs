//! Folded edges of a mesh: interior edges whose two faces have (Newell) normals more than 90°
//! apart, the fold measure of `docs/folds.md`, reported by `metrics` and after `subdivide`.

use std::collections::{BTreeSet, HashMap};

use crate::mesh::{area_vector, dot, norm, Mesh};

/// The folds of a mesh.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Folds {
    /// Interior edges (two faces, opposite directions) whose faces' normals are more than 90°
    /// apart.
    pub folded: usize,
    /// The largest angle between the normals of the two faces of an interior edge, in
    /// degrees (0 for a flat mesh; NaN when no interior edge has two faces with a normal).
    pub worst_degrees: f64,
    /// Where: the end vertices of that edge.
    pub worst_edge: Option<(u32, u32)>,
}

/// The folds of `m`. An edge used by other than exactly two faces in opposite directions,
/// or whose faces have no normal (zero area), is not measured.
pub fn measure(m: &Mesh) -> Folds {
    measure_except(m, &BTreeSet::new())
}

/// [`measure`] leaving out the edges in `creases` (`(min, max)` vertex pairs): the sharp
/// edges of a tagged mesh, whose faces may meet at any angle by design.
pub fn measure_except(m: &Mesh, creases: &BTreeSet<[u32; 2]>) -> Folds {
    let normals: Vec<[f64; 3]> = m.faces().map(|f| area_vector(m, f)).collect();
    let mut half: HashMap<(u32, u32), usize> = HashMap::new();
    let mut repeated: HashMap<(u32, u32), ()> = HashMap::new();
    for (k, f) in m.faces().enumerate() {
        for i in 0..f.len() {
            let key = (f[i], f[(i + 1) % f.len()]);
            if half.insert(key, k).is_some() {
                repeated.insert(key, ());
            }
        }
    }
    let mut out = Folds {
        folded: 0,
        worst_degrees: f64::NAN,
        worst_edge: None,
    };
    // Sorted, so that ties of the worst angle name the same edge on every run.
    let mut keys: Vec<&(u32, u32)> = half.keys().filter(|(a, b)| a < b).collect();
    keys.sort_unstable();
    for &(a, b) in keys {
        if repeated.contains_key(&(a, b))
            || repeated.contains_key(&(b, a))
            || creases.contains(&[a, b])
        {
            continue;
        }
        let (Some(&fa), Some(&fb)) = (half.get(&(a, b)), half.get(&(b, a))) else {
            continue;
        };
        let (na, nb) = (normals[fa], normals[fb]);
        let len = norm(na) * norm(nb);
        if !(len > 0.0 && len.is_finite()) {
            continue;
        }
        let d = dot(na, nb);
        if d < 0.0 {
            out.folded += 1;
        }
        let deg = (d / len).clamp(-1.0, 1.0).acos().to_degrees();
        if out.worst_degrees.is_nan() || deg > out.worst_degrees {
            out.worst_degrees = deg;
            out.worst_edge = Some((a, b));
        }
    }
    out
}

impl Folds {
    /// `N folded edges (worst normal angle D° at edge a–b)`.
    pub fn describe(&self) -> String {
        let worst = match self.worst_edge {
            Some((a, b)) => format!(
                " (worst normal angle {:.1}° at edge {a}–{b})",
                self.worst_degrees
            ),
            None => String::new(),
        };
        format!(
            "{} folded edge{}{worst}",
            self.folded,
            if self.folded == 1 { "" } else { "s" }
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two triangles on the edge 0–1: flat (0°), then the apex of the second folded over
    /// the first (180°).
    #[test]
    fn a_hinge() {
        let flat = Mesh::from_faces(
            vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [0.5, 1.0, 0.0],
                [0.5, -1.0, 0.0],
            ],
            &[vec![0u32, 1, 2], vec![1, 0, 3]],
        );
        let f = measure(&flat);
        assert_eq!((f.folded, f.worst_edge), (0, Some((0, 1))));
        assert!(f.worst_degrees.abs() < 1e-9);
        let folded = Mesh::from_faces(
            vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [0.5, 1.0, 0.0],
                [0.5, 1.0, 1e-3],
            ],
            &[vec![0u32, 1, 2], vec![1, 0, 3]],
        );
        let f = measure(&folded);
        assert_eq!(f.folded, 1);
        assert!(f.worst_degrees > 179.0, "{}", f.worst_degrees);
        assert!(f.describe().starts_with("1 folded edge (worst"));
    }
}
