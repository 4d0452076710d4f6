//! Sharp features of Loop and Catmull–Clark: the rules that decide, from sharpness values
//! alone, which mask a vertex or an edge point takes and how semi-sharp features decay from
//! level to level. They are OpenSubdiv's (`Sdc::Crease`, `Sdc::Scheme`), with its
//! conventions, so that tagged meshes refine exactly as in OpenSubdiv:
//!
//! * Sharpness `0` is smooth, `≥ 10` ([`INFINITE`]) infinitely sharp, anything between
//!   semi-sharp. Boundary edges count as infinitely sharp (boundary interpolation "edge
//!   only": every boundary loop is a cubic B-spline crease).
//! * Sharpness is evaluated in single precision, as OpenSubdiv stores it: values that are
//!   sums of powers of two (`1.5`, `2.25`) are exact, others are rounded once to `f32`.
//! * Each level a semi-sharp value `s` becomes `s − 1` ([`CreaseMethod::Uniform`]), or for an
//!   edge with [`CreaseMethod::Chaikin`] `3/4 s + 1/4 s̄ − 1` with `s̄` the average of the
//!   other semi-sharp edges at the vertex the child edge touches (Chaikin's curve rule
//!   applied to the sharpness along a crease, so a crease whose sharpness varies decays
//!   smoothly); a value that drops to zero or below becomes smooth.
//! * A vertex takes the *smooth* rule with no sharp incident edge or one (a *dart*), the
//!   *crease* rule (`3/4 v + 1/8 (q_a + q_b)`, the cubic B-spline along the two sharp edges)
//!   with two, the *corner* rule (`v` stays) with three or more or a positive vertex
//!   sharpness. When the rule of the child (from the decremented sharpness values) differs
//!   from the parent's, the vertex point is `w P + (1 − w) C`: the parent rule `P` and the
//!   child rule `C` blended by the average of the sharpness values that decay to zero in
//!   this step, clamped to 1 ([`fractional_weight`]).
//! * An edge whose two child edges stay sharp takes the crease rule (its midpoint), another
//!   sharp edge the blend `s · midpoint + (1 − s) · smooth` ([`edge_weight`]).

use crate::point::{lin2, Point};

/// Infinitely sharp: this value and anything above it never decays.
pub const INFINITE: f32 = 10.0;

/// How semi-sharp edge values decay from level to level.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum CreaseMethod {
    /// Every value decreases by one per level.
    #[default]
    Uniform,
    /// Chaikin's rule: an edge's child takes `3/4` of its value and `1/4` of the average of
    /// the other semi-sharp edges at the shared vertex, minus one.
    Chaikin,
}

/// The rule of a vertex point.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VertexRule {
    /// No sharp incident edge: the scheme's smooth rule.
    Smooth,
    /// One sharp incident edge: the smooth rule (the crease ends in the surface).
    Dart,
    /// Two sharp incident edges: the curve rule along them.
    Crease,
    /// Three or more sharp incident edges, or a sharp vertex: the vertex stays.
    Corner,
}

/// Sharp: positive.
#[inline]
pub fn is_sharp(s: f32) -> bool {
    s > 0.0
}

/// Infinitely sharp: at least [`INFINITE`].
#[inline]
pub fn is_infinite(s: f32) -> bool {
    s >= INFINITE
}

/// Semi-sharp: positive and finite in OpenSubdiv's sense (below [`INFINITE`]).
#[inline]
pub fn is_semi_sharp(s: f32) -> bool {
    s > 0.0 && s < INFINITE
}

/// The value one level later with the uniform rule: `s − 1`, smooth at or below zero,
/// infinite stays infinite.
#[inline]
pub fn decrement(s: f32) -> f32 {
    if !is_sharp(s) {
        0.0
    } else if is_infinite(s) {
        INFINITE
    } else if s > 1.0 {
        s - 1.0
    } else {
        0.0
    }
}

/// The rule of a vertex of sharpness `vertex` whose incident edges have the sharpness values
/// `edges`.
pub fn vertex_rule(vertex: f32, edges: &[f32]) -> VertexRule {
    if is_sharp(vertex) {
        return VertexRule::Corner;
    }
    match edges.iter().filter(|&&s| is_sharp(s)).count() {
        0 => VertexRule::Smooth,
        1 => VertexRule::Dart,
        2 => VertexRule::Crease,
        _ => VertexRule::Corner,
    }
}

/// The values of the child edges at a vertex, one per incident edge: `parent` are the
/// incident edges' values (in any order), `child` receives theirs in the same order (both of
/// the same length; a shorter `child` receives a prefix).
pub fn child_edge_sharpness(method: CreaseMethod, parent: &[f32], child: &mut [f32]) {
    let (mut sum, mut count) = (0.0f32, 0u32);
    for &s in parent {
        if is_semi_sharp(s) {
            sum += s;
            count += 1;
        }
    }
    // Chaikin needs at least two incident edges (OpenSubdiv: the uniform rule otherwise).
    let chaikin = method == CreaseMethod::Chaikin && parent.len() >= 2;
    for (c, &s) in child.iter_mut().zip(parent) {
        *c = if !chaikin || !is_semi_sharp(s) || count < 2 {
            decrement(s)
        } else {
            let others = (sum - s) / (count - 1) as f32;
            let v = (0.75f32 * s + 0.25f32 * others) - 1.0;
            if is_sharp(v) {
                v
            } else {
                0.0
            }
        };
    }
}

/// The weight `w` of the parent rule when a vertex changes rule in this step: the average of
/// the values that decay to zero in this step (the vertex's own and its incident edges'),
/// clamped to 1; 0 when none does.
pub fn fractional_weight(
    method: CreaseMethod,
    parent_vertex: f32,
    child_vertex: f32,
    parent_edges: &[f32],
    child_edges: &[f32],
) -> f32 {
    let (mut sum, mut count) = (0.0f32, 0u32);
    if is_sharp(parent_vertex) && !is_sharp(child_vertex) {
        sum = parent_vertex;
        count = 1;
    }
    for (&p, &c) in parent_edges.iter().zip(child_edges) {
        // Uniform: a value decays to zero in this step exactly when it is at most 1.
        let decays = match method {
            CreaseMethod::Uniform => p <= 1.0,
            CreaseMethod::Chaikin => !is_sharp(c),
        };
        if is_sharp(p) && decays {
            sum += p;
            count += 1;
        }
    }
    if count == 0 {
        return 0.0;
    }
    let w = sum / count as f32;
    if w > 1.0 {
        1.0
    } else {
        w
    }
}

/// The weight of the crease rule (the midpoint) in the edge point of an edge of sharpness
/// `s` whose two child edges have the values `ends`: 0 for a smooth edge, 1 when both
/// children stay sharp (the new vertex is a crease vertex), `s` itself otherwise. With the
/// uniform method that is `min(s, 1)`; with Chaikin's, an edge above 1 with a child that
/// decays to zero gets `s > 1`, an extrapolation past the midpoint that OpenSubdiv makes
/// too (its edge mask takes the parent sharpness unclamped), kept for equality with it.
pub fn edge_weight(s: f32, ends: [f32; 2]) -> f64 {
    if !is_sharp(s) {
        0.0
    } else if is_sharp(ends[0]) && is_sharp(ends[1]) {
        1.0
    } else {
        f64::from(s)
    }
}

/// `w · sharp + (1 − w) · smooth`, the blend of a rule with its sharper parent rule (exact
/// at `w = 0` and `w = 1`, so untouched features keep their bits).
#[inline]
pub fn blend(w: f64, sharp: Point, smooth: Point) -> Point {
    if w <= 0.0 {
        smooth
    } else if w == 1.0 {
        sharp
    } else {
        lin2(w, sharp, 1.0 - w, smooth)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rules_from_counts() {
        assert_eq!(vertex_rule(0.0, &[0.0, 0.0, 0.0]), VertexRule::Smooth);
        assert_eq!(vertex_rule(0.0, &[0.5, 0.0, 0.0]), VertexRule::Dart);
        assert_eq!(vertex_rule(0.0, &[0.5, 10.0, 0.0]), VertexRule::Crease);
        assert_eq!(vertex_rule(0.0, &[0.5, 10.0, 2.0]), VertexRule::Corner);
        assert_eq!(vertex_rule(0.25, &[0.0; 4]), VertexRule::Corner);
    }

    #[test]
    fn decay() {
        assert_eq!(decrement(2.5), 1.5);
        assert_eq!(decrement(1.0), 0.0);
        assert_eq!(decrement(12.0), INFINITE);
        let mut c = [0.0f32; 3];
        // Chaikin: 3/4 · 2 + 1/4 · 1 − 1 = 0.75 and 3/4 · 1 + 1/4 · 2 − 1 = 0.25.
        child_edge_sharpness(CreaseMethod::Chaikin, &[2.0, 1.0, 0.0], &mut c);
        assert_eq!(c, [0.75, 0.25, 0.0]);
        child_edge_sharpness(CreaseMethod::Uniform, &[2.0, 1.0, 10.0], &mut c);
        assert_eq!(c, [1.0, 0.0, INFINITE]);
        // Infinite edges are not averaged in.
        child_edge_sharpness(CreaseMethod::Chaikin, &[2.0, 10.0], &mut c);
        assert_eq!(&c[..2], &[1.0, INFINITE]);
    }

    #[test]
    fn weights() {
        assert_eq!(
            fractional_weight(CreaseMethod::Uniform, 0.0, 0.0, &[0.5, 0.25], &[0.0, 0.0]),
            0.375
        );
        assert_eq!(
            fractional_weight(CreaseMethod::Uniform, 3.0, 2.0, &[2.0], &[1.0]),
            0.0
        );
        assert_eq!(edge_weight(0.25, [0.0; 2]), 0.25);
        assert_eq!(edge_weight(1.5, [0.5; 2]), 1.0);
        assert_eq!(edge_weight(1.0, [0.0; 2]), 1.0);
        assert_eq!(edge_weight(0.5, [0.125; 2]), 1.0);
        assert_eq!(edge_weight(1.25, [0.5, 0.0]), 1.25);
    }
}
