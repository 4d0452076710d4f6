//! The curvature edit of seed 001 §4.4 ("editing result by adjusting the mean curvatures",
//! Figs. 11(c), 12), applied to the differential coordinates before they are subdivided.
//!
//! Each `δ_i` of the control mesh is split into a mean curvature `H_i` and a normal direction
//! `n_i` ([`dirmag::separate`]); the caller's factor scales `H_i`, so `δ_i ← s_i δ_i`, and the
//! edited `Δ⁰` is what the subdivision and the reconstruction see. The same split feeds DirMag
//! (§3.4), which subdivides `H` and `n` separately. The normal edit of §4.4 is not a change of
//! `Δ⁰`'s directions (see `normal_edit.rs` for why and what it is instead).

use super::dirmag;
use crate::error::Result;
use crate::mesh::{get, set};
use crate::point::Point;

/// Splits `Δ⁰` (in `delta`) of the `n0` control vertices into `H` (`h[i][0]`) and `n` (`n[i]`)
/// along the angle-weighted normals `nbar`, scales `H` and `δ` by `scale`, and writes the
/// edited `Δ⁰` back into `delta`. Without a scale `delta` is unchanged (`1 · δ = δ` bit for
/// bit).
pub(super) fn edit_differentials(
    scale: Option<&[f64]>,
    n0: usize,
    delta: &mut [Point],
    h: &mut [Point],
    n: &mut [Point],
    nbar: &[Point],
) -> Result<()> {
    for i in 0..n0 {
        let d = get(delta, i)?;
        let s = match scale {
            Some(sc) => get(sc, i)?,
            None => 1.0,
        };
        let (hi, nrm) = dirmag::separate(d, get(nbar, i)?);
        set(delta, i, [s * d[0], s * d[1], s * d[2]])?;
        set(h, i, [s * hi, 0.0, 0.0])?;
        set(n, i, nrm)?;
    }
    Ok(())
}
