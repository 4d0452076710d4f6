//! Editing the differential coordinates before they are subdivided (seed 001 §4.4).
//!
//! Each `δ_i` of the control mesh is split into a mean curvature `H_i` and a normal direction
//! `n_i` ([`dirmag::separate`]); the caller may scale `H_i` and replace `n_i`, and the edited
//! `Δ⁰` is what the subdivision and the reconstruction see. The same split feeds DirMag
//! (§3.4), which subdivides `H` and `n` separately.

use super::dirmag;
use super::options::DifferentialOptions;
use crate::error::Result;
use crate::mesh::{get, set};
use crate::point::Point;

/// Splits `Δ⁰` (in `delta`) of the `n0` control vertices into `H` (`h[i][0]`) and `n` (`n[i]`)
/// along the angle-weighted normals `nbar`, applies the edits of `opts`, and writes the edited
/// `Δ⁰` back into `delta`. Without edits `delta` is unchanged (`1 · δ = δ`).
pub(super) fn edit_differentials(
    opts: &DifferentialOptions<'_>,
    n0: usize,
    delta: &mut [Point],
    h: &mut [Point],
    n: &mut [Point],
    nbar: &[Point],
) -> Result<()> {
    for i in 0..n0 {
        let d = get(delta, i)?;
        let s = match opts.curvature_scale {
            Some(sc) => get(sc, i)?,
            None => 1.0,
        };
        let (mut hi, mut nrm) = dirmag::separate(d, get(nbar, i)?);
        if let Some(nn) = opts.normals {
            if let Some(u) = dirmag::normalized(get(nn, i)?) {
                nrm = u;
                // A −0 curvature becomes +0, so that the edited `Δ = H n` of a flat vertex has
                // no sign that depends on how `separate` rounded to zero.
                if hi == 0.0 {
                    hi = 0.0;
                }
            }
        }
        hi *= s;
        let edited = if opts.normals.is_some() {
            [hi * nrm[0], hi * nrm[1], hi * nrm[2]]
        } else {
            [s * d[0], s * d[1], s * d[2]]
        };
        set(delta, i, edited)?;
        set(h, i, [hi, 0.0, 0.0])?;
        set(n, i, nrm)?;
    }
    Ok(())
}
