//! Which schemes and forms this build of the crate contains: its Cargo features (`loop`,
//! `catmull-clark`, `butterfly`, `kobbelt`, `doo-sabin`, `simplest`, `akleman`, `spherelike`,
//! and `mobius` for the canonical Möbius forms; all on by default).
//!
//! The scheme is a run-time argument of [`plan`](super::plan()) and
//! [`subdivide`](super::subdivide), so a linker cannot tell which rules a call will take and
//! keeps every rule the dispatch reaches. A feature that is off removes its arms from the few
//! places that dispatch on the scheme (`step.rs` for the linear and spherelike rules,
//! `mobius/mod.rs` for the Möbius drivers, `linear_tagged.rs` for the rules with sharp
//! features) and the modules only those arms use, so a firmware that calls one scheme links
//! only that one (`docs/firmware.md`, "Link only what you use"). A scheme or form left out
//! is [`Status::SchemeNotBuilt`]: refused by the plan before the mesh is read, and by every
//! step as well, never a panic.

use super::Scheme;
use crate::error::{Error, Result, Status};

impl Scheme {
    /// Whether this build contains the scheme's linear rules (or, for
    /// [`Scheme::Spherelike`], its circle-blend rules): its Cargo feature is on.
    pub const fn is_built(self) -> bool {
        narrow(self).is_ok()
    }

    /// Whether this build contains the scheme's canonical Möbius version: the scheme has one
    /// ([`Scheme::has_mobius_form`]), it is built, and so is the `mobius` feature.
    pub const fn is_mobius_built(self) -> bool {
        self.has_mobius_form() && self.is_built() && cfg!(feature = "mobius")
    }
}

/// [`Status::SchemeNotBuilt`] unless this build contains `scheme`, in its Möbius version
/// with `mobius`.
pub(crate) fn check(scheme: Scheme, mobius: bool) -> Result<()> {
    let built = if mobius {
        scheme.is_mobius_built()
    } else {
        scheme.is_built()
    };
    if built {
        Ok(())
    } else {
        Err(Error::new(Status::SchemeNotBuilt))
    }
}

/// `scheme` itself when this build contains it (its Cargo feature is on),
/// [`Status::SchemeNotBuilt`] otherwise: the table of which feature holds which scheme.
/// Every arm returns a constant: in a build of one scheme the optimiser then knows the
/// scheme wherever the result flows (its refinement pattern, its sizes, the dispatch of each
/// step) and drops what the other schemes would need. The plan and the level loop take
/// their scheme from here.
pub(crate) const fn narrow(scheme: Scheme) -> Result<Scheme> {
    match scheme {
        Scheme::Loop if cfg!(feature = "loop") => Ok(Scheme::Loop),
        Scheme::CatmullClark if cfg!(feature = "catmull-clark") => Ok(Scheme::CatmullClark),
        Scheme::ModifiedButterfly if cfg!(feature = "butterfly") => Ok(Scheme::ModifiedButterfly),
        Scheme::Kobbelt if cfg!(feature = "kobbelt") => Ok(Scheme::Kobbelt),
        Scheme::DooSabin if cfg!(feature = "doo-sabin") => Ok(Scheme::DooSabin),
        Scheme::Simplest if cfg!(feature = "simplest") => Ok(Scheme::Simplest),
        Scheme::Dual if cfg!(feature = "akleman") => Ok(Scheme::Dual),
        Scheme::VertexInsertion if cfg!(feature = "akleman") => Ok(Scheme::VertexInsertion),
        Scheme::DualTruncation if cfg!(feature = "akleman") => Ok(Scheme::DualTruncation),
        Scheme::Spherelike if cfg!(feature = "spherelike") => Ok(Scheme::Spherelike),
        _ => Err(not_built()),
    }
}

/// The error of a dispatch arm left out of this build.
pub(crate) const fn not_built() -> Error {
    Error::new(Status::SchemeNotBuilt)
}
