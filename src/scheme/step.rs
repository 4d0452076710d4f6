//! One subdivision step on a built topology, over caller buffers: the sizes, the pattern's
//! connectivity, then the positions of the scheme's rules, linear ([`super::linear`]),
//! spherelike ([`super::spherelike`]) or canonical Möbius ([`super::mobius`]). [`step`] is
//! the one entry the level loop ([`super::levels`]) goes through.

use super::built::{self, not_built};
use super::mobius::{self, MobiusOptions, MobiusReport};
use super::size::step_size;
use super::tags::Sharpness;
use super::weights::{self, Blend, Uniform};
use super::{linear, linear_tagged, spherelike, Scheme};
use crate::error::{Error, Result, Status};
use crate::exec::{self, Executor};
use crate::mesh::refine::{write_pattern, write_pattern_with};
use crate::mesh::{internal, MeshOut, MeshSizes, Topology};
use crate::point::{self, Point};

/// One step of `scheme` on `topo` into `out`: the linear (or spherelike) rules with `mobius`
/// `None`, the canonical Möbius version with its options otherwise, `candidates` its scratch
/// ([`mobius::candidate_points`] and the star workspace,
/// [`mobius::workspace::workspace_points`]; unused by the other rules). Returns the sizes written and
/// the Möbius report (empty for the other rules). With `sharp` (the level's sharpness
/// values of a tagged mesh) the linear rules with sharp features ([`linear_tagged`]), or
/// the Möbius step on the mesh cut along its sharp edges ([`mobius::crease`]; `candidates`
/// then holds its points). `u32s` is the `u32` scratch of a Möbius step: the spoke workspace
/// ([`mobius::workspace::spoke_u32s`]) or, with sharp features, the cut step's
/// ([`mobius::crease::scratch`]); unused by the other rules.
///
/// # Errors
/// [`Status::SchemeNotBuilt`] for a scheme or Möbius version this build does not contain
/// ([`super::built`]; the plan refuses it first); those of [`linear`], [`mobius::step`] and
/// [`mobius::crease::step`].
#[allow(clippy::too_many_arguments)]
pub(crate) fn step(
    scheme: Scheme,
    mobius: Option<MobiusOptions>,
    sharp: Option<&Sharpness<'_>>,
    topo: &Topology<'_, '_>,
    out: &mut MeshOut<'_>,
    candidates: &mut [Point],
    u32s: &mut [u32],
    exec: &dyn Executor,
) -> Result<(MeshSizes, MobiusReport)> {
    // A constant `false` without the `mobius` feature: the optimiser then drops every Möbius
    // arm below, and with them the whole Möbius machinery.
    built::check(scheme, mobius.is_some())?;
    match (mobius, sharp) {
        (None, None) => linear_with(scheme, topo, out, exec).map(|s| (s, MobiusReport::default())),
        (None, Some(sh)) => tagged(scheme, topo, sh, out).map(|s| (s, MobiusReport::default())),
        (Some(opts), None) => mobius::step(scheme, topo, out, candidates, u32s, opts, exec),
        (Some(opts), Some(sh)) if opts.spectrum < 1.0 => {
            let blend = Blend::Global(opts.spectrum);
            mobius_tagged_spectrum(scheme, topo, sh, out, u32s, candidates, opts, blend, exec)
        }
        (Some(opts), Some(sh)) => {
            mobius::crease::step(scheme, topo, sh, out, u32s, candidates, opts, exec)
        }
    }
}

/// [`step`] of the Möbius version with per-vertex spectrum weights (seed 000 §7.2,
/// [`weights`]): `w` holds the weight of every output vertex of this step (of the linear
/// result with `of_linear`). All 0 is the
/// linear step and all 1 the Möbius step, exactly those (`mobius` with weight 1); otherwise
/// both are computed and blended per vertex, the linear positions in the last output-size
/// points of `candidates` (which holds the Möbius candidates and those points).
///
/// # Errors
/// Those of [`step`].
#[allow(clippy::too_many_arguments)]
pub(crate) fn step_weighted(
    scheme: Scheme,
    mobius: MobiusOptions,
    (w, of_linear): (&[f64], bool),
    sharp: Option<&Sharpness<'_>>,
    topo: &Topology<'_, '_>,
    out: &mut MeshOut<'_>,
    candidates: &mut [Point],
    u32s: &mut [u32],
    exec: &dyn Executor,
) -> Result<(MeshSizes, MobiusReport)> {
    let full = MobiusOptions {
        spectrum: 1.0,
        ..mobius
    };
    let w = w
        .get(..step_size(scheme, topo)?.vertices)
        .ok_or(internal())?;
    match weights::uniform(w, of_linear) {
        Uniform::Zero => step(scheme, None, sharp, topo, out, candidates, u32s, exec),
        Uniform::One => step(scheme, Some(full), sharp, topo, out, candidates, u32s, exec),
        Uniform::Mixed => match sharp {
            Some(sh) => {
                let blend = Blend::PerVertex(w, of_linear);
                mobius_tagged_spectrum(scheme, topo, sh, out, u32s, candidates, full, blend, exec)
            }
            None => {
                let n = w.len();
                let split = candidates.len().checked_sub(n).ok_or(internal())?;
                let (cand, lin) = candidates.split_at_mut_checked(split).ok_or(internal())?;
                let (sizes, report) = mobius::step(scheme, topo, out, cand, u32s, full, exec)?;
                linear::positions(scheme, topo, lin, exec)?;
                let pos = out.positions.get_mut(..n).ok_or(internal())?;
                Blend::PerVertex(w, of_linear).apply(pos, lin)?;
                if let Some(i) = exec::first_non_finite(exec, pos)? {
                    return Err(Error::at(Status::NumericalFailure, i as u32));
                }
                Ok((sizes, report))
            }
        },
    }
}

/// The Möbius–linear spectrum (seed 000 §7.2) with sharp features: the tagged Möbius step
/// ([`mobius::crease`]) blended with the tagged linear step by `blend` (`w · möbius + (1 − w)
/// · linear` per output vertex, one global `w` or one per vertex), as the untagged step blends
/// with the untagged linear rule. The linear positions take the last output-size points of
/// `candidates`.
#[allow(clippy::too_many_arguments)]
fn mobius_tagged_spectrum(
    scheme: Scheme,
    topo: &Topology<'_, '_>,
    sh: &Sharpness<'_>,
    out: &mut MeshOut<'_>,
    u32s: &mut [u32],
    candidates: &mut [Point],
    opts: MobiusOptions,
    blend: Blend<'_>,
    exec: &dyn Executor,
) -> Result<(MeshSizes, MobiusReport)> {
    let n = step_size(scheme, topo)?.vertices;
    let split = candidates.len().checked_sub(n).ok_or(internal())?;
    let (cand, lin) = candidates.split_at_mut_checked(split).ok_or(internal())?;
    tagged(scheme, topo, sh, out)?;
    for (l, p) in lin.iter_mut().zip(out.positions.iter()) {
        *l = *p;
    }
    let full = MobiusOptions {
        spectrum: 1.0,
        ..opts
    };
    let (sizes, report) = mobius::crease::step(scheme, topo, sh, out, u32s, cand, full, exec)?;
    let pos = out.positions.get_mut(..n).ok_or(internal())?;
    blend.apply(pos, lin)?;
    if let Some(i) = first_non_finite(pos) {
        return Err(Error::at(Status::NumericalFailure, i as u32));
    }
    Ok((sizes, report))
}

/// [`linear`] with sharp features (Loop, Catmull–Clark).
fn tagged(
    scheme: Scheme,
    topo: &Topology<'_, '_>,
    sharp: &Sharpness<'_>,
    out: &mut MeshOut<'_>,
) -> Result<MeshSizes> {
    let sizes = step_size(scheme, topo)?;
    out.check(&sizes)?;
    write_pattern(scheme.pattern(), topo, out.offsets, out.indices)?;
    let pos = out.positions.get_mut(..sizes.vertices).ok_or(internal())?;
    linear_tagged::positions(scheme, topo, sharp, pos)?;
    if let Some(i) = first_non_finite(pos) {
        return Err(Error::at(Status::NumericalFailure, i as u32));
    }
    Ok(sizes)
}

/// Writes one step of `scheme` on `topo` into `out` and returns the sizes written: the
/// linear rules, or for [`Scheme::Spherelike`] its circle-blend rules (seed 003 §3), which
/// share this step (and so the level loop). Differential-space subdivision steps its fields
/// with it too.
///
/// # Errors
/// Those of [`step_size`]; [`Status::BufferTooSmall`] (with the needed size) when an
/// output buffer is short, before any write; [`Status::NumericalFailure`] naming the first
/// output vertex that is not finite (overflow on huge coordinates); the statuses of
/// [`super::spherelike`].
///
/// The passes are run by `exec` ([`crate::exec`]): the same bits for every executor.
pub(crate) fn linear_with(
    scheme: Scheme,
    topo: &Topology<'_, '_>,
    out: &mut MeshOut<'_>,
    exec: &dyn Executor,
) -> Result<MeshSizes> {
    let sizes = step_size(scheme, topo)?;
    out.check(&sizes)?;
    write_pattern_with(scheme.pattern(), topo, out.offsets, out.indices, exec)?;
    let pos = out.positions.get_mut(..sizes.vertices).ok_or(internal())?;
    positions(scheme, topo, pos, exec)?;
    if let Some(i) = exec::first_non_finite(exec, pos)? {
        return Err(Error::at(Status::NumericalFailure, i as u32));
    }
    Ok(sizes)
}

/// The positions of one step of `scheme`'s linear rules ([`linear::positions`]) or, for
/// [`Scheme::Spherelike`], its circle-blend rules (seed 003 §3), when this build contains
/// the scheme ([`super::built`]); [`Status::SchemeNotBuilt`] otherwise. The one dispatch
/// of the non-Möbius rules on the scheme: each arm passes its scheme as a constant, so the
/// rules of the schemes left out are not reached from any call (`linear.rs` dispatches
/// again inside) and a build of a few schemes links the rules of those alone.
pub(super) fn positions(
    scheme: Scheme,
    topo: &Topology<'_, '_>,
    pos: &mut [Point],
    exec: &dyn Executor,
) -> Result<()> {
    // An arm of a scheme left out has a constant `false` guard: the optimiser removes it.
    match scheme {
        Scheme::Loop if cfg!(feature = "loop") => linear::positions(Scheme::Loop, topo, pos, exec),
        Scheme::CatmullClark if cfg!(feature = "catmull-clark") => {
            linear::positions(Scheme::CatmullClark, topo, pos, exec)
        }
        Scheme::ModifiedButterfly if cfg!(feature = "butterfly") => {
            linear::positions(Scheme::ModifiedButterfly, topo, pos, exec)
        }
        Scheme::Kobbelt if cfg!(feature = "kobbelt") => {
            linear::positions(Scheme::Kobbelt, topo, pos, exec)
        }
        Scheme::DooSabin if cfg!(feature = "doo-sabin") => {
            linear::positions(Scheme::DooSabin, topo, pos, exec)
        }
        Scheme::Simplest if cfg!(feature = "simplest") => {
            linear::positions(Scheme::Simplest, topo, pos, exec)
        }
        Scheme::Dual if cfg!(feature = "akleman") => {
            linear::positions(Scheme::Dual, topo, pos, exec)
        }
        Scheme::VertexInsertion if cfg!(feature = "akleman") => {
            linear::positions(Scheme::VertexInsertion, topo, pos, exec)
        }
        Scheme::DualTruncation if cfg!(feature = "akleman") => {
            linear::positions(Scheme::DualTruncation, topo, pos, exec)
        }
        Scheme::Spherelike if cfg!(feature = "spherelike") => {
            spherelike::positions(topo, pos, exec)
        }
        _ => Err(not_built()),
    }
}

/// The index of the first point with a NaN or infinite coordinate. A branch-free pass first
/// (`|x| ≤ f64::MAX` is false exactly for NaN and ±∞), the search only when it fails.
fn first_non_finite(pos: &[Point]) -> Option<usize> {
    let finite = pos
        .as_flattened()
        .iter()
        .fold(true, |ok, x| ok & (x.abs() <= f64::MAX));
    if finite {
        return None;
    }
    pos.iter().position(|p| !point::is_finite(p))
}
