//! What a mesh subdivision is asked to do: the scheme, its linear or canonical Möbius version
//! (seed 000 §4), strictness about Möbius fallbacks, and the number of levels. One value
//! drives both [`super::plan`] and [`super::subdivide`], so the sizes planned are the sizes
//! written.

use super::{Scheme, MAX_LEVELS};
#[cfg(doc)]
use crate::error::Status;

/// Options of [`plan`](super::plan()) and [`subdivide`](super::subdivide): start from
/// [`Options::new`] and chain the builder methods (all `const`):
///
/// ```
/// use nlsubdiv::{Options, Scheme};
/// const OPTS: Options = Options::new(Scheme::Loop).mobius(true).levels(3);
/// assert!(OPTS.mobius && !OPTS.strict && OPTS.levels == 3);
/// ```
///
/// `#[non_exhaustive]`: a later version may add a field (with a default that keeps today's
/// behaviour) without breaking callers, which is why the struct is built through
/// [`Options::new`] rather than a struct literal. Only `PartialEq` for the same reason: a
/// later field may be a weight (`f64`).
#[non_exhaustive]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Options {
    /// The scheme.
    pub scheme: Scheme,
    /// The canonical Möbius version of the scheme (seed 000 §4; [`super::mobius`]).
    /// [`Status::InvalidArgument`] for a scheme without one ([`Scheme::has_mobius_form`]).
    pub mobius: bool,
    /// A Möbius fallback (a degenerate neighbourhood taking its linear rule) is
    /// [`Status::FallbackInStrictMode`] naming the output vertex instead of a count in the
    /// [`Report`](super::Report). Accepted and without effect for the linear schemes, which
    /// never fall back.
    pub strict: bool,
    /// Levels, `0..=`[`MAX_LEVELS`]; 0 validates the input and copies it.
    pub levels: usize,
    /// With [`Options::mobius`]: the paper's algorithm exactly as printed (seed 000 §4),
    /// without the fold guard. By default (`false`) a Möbius step guards the stars whose
    /// canonical form is ill-conditioned (Loop, Modified Butterfly, Catmull–Clark; seed 000
    /// §7.1, §7.2; `docs/folds.md`): they are evaluated in a form interpolated toward the
    /// linear rule, and the elements this changes are counted in the
    /// [`Report`](super::Report) (`guarded`) or, with [`Options::strict`], refused with
    /// [`Status::FallbackInStrictMode`]. Named for what it gives rather than for the guard,
    /// so that `true` always means "the published rules, bit for bit". Accepted and without
    /// effect for the linear schemes.
    pub literal: bool,
    /// With [`Options::mobius`]: the global weight `w ∈ [0, 1]` of the Möbius–linear
    /// spectrum (seed 000 §7.2): every output vertex of every level is
    /// `w · (Möbius point) + (1 − w) · (linear point)` of that level's input. 1 (the default)
    /// is the Möbius result bit for bit (guarded or [`Options::literal`]), 0 the linear
    /// result bit for bit; continuous in `w` between. NaN or outside `[0, 1]` is
    /// [`Status::InvalidArgument`]. Checked, and without effect, for the linear schemes. A
    /// weight per input vertex instead: [`subdivide_weighted`](super::subdivide_weighted).
    pub spectrum: f64,
}

impl Options {
    /// The linear version of `scheme`, not strict, one level.
    pub const fn new(scheme: Scheme) -> Options {
        Options {
            scheme,
            mobius: false,
            strict: false,
            levels: 1,
            literal: false,
            spectrum: 1.0,
        }
    }

    /// The canonical Möbius version (`true`) or the linear one (`false`).
    #[must_use]
    pub const fn mobius(self, on: bool) -> Options {
        Options { mobius: on, ..self }
    }

    /// Fallbacks are errors (`true`) or counted (`false`).
    #[must_use]
    pub const fn strict(self, on: bool) -> Options {
        Options { strict: on, ..self }
    }

    /// The paper's literal Möbius rules (`true`) or the guarded ones (`false`, the default;
    /// [`Options::literal`]).
    #[must_use]
    pub const fn literal(self, on: bool) -> Options {
        Options {
            literal: on,
            ..self
        }
    }

    /// The weight of the Möbius–linear spectrum ([`Options::spectrum`]; checked by the calls).
    #[must_use]
    pub const fn spectrum(self, w: f64) -> Options {
        Options {
            spectrum: w,
            ..self
        }
    }

    /// The number of levels (checked against [`MAX_LEVELS`] by the calls).
    #[must_use]
    pub const fn levels(self, levels: usize) -> Options {
        Options { levels, ..self }
    }

    /// [`Status::InvalidArgument`] for more than [`MAX_LEVELS`] levels, the Möbius version
    /// of a scheme without one, or a spectrum weight that is NaN or outside `[0, 1]`; then
    /// [`Status::SchemeNotBuilt`] for a scheme or Möbius version this build does not contain
    /// ([`Scheme::is_built`], [`Scheme::is_mobius_built`]); checked before the mesh is read.
    pub(crate) fn check(&self) -> crate::Result<()> {
        let w_ok = self.spectrum >= 0.0 && self.spectrum <= 1.0;
        if self.levels > MAX_LEVELS || (self.mobius && !self.scheme.has_mobius_form()) || !w_ok {
            return Err(crate::Error::new(crate::Status::InvalidArgument));
        }
        super::built::check(self.scheme, self.mobius)
    }
}
