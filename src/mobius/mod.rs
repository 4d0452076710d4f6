//! Möbius maps and the canonical forms of vertex stars (seed 000 §3.2 Eq. (1) and §4.2).
//!
//! * [`MobiusMap`] (`map.rs`): the maps `q ↦ (aq + b)(cq + d)⁻¹` themselves, composed and
//!   inverted as quaternionic 2×2 matrices;
//! * [`CanonicalForm`], [`StarKind`] (`canonical_form.rs`): the Möbius normalisation of a
//!   vertex star in which the Möbius schemes evaluate their linear stencils.

mod canonical_form;
mod map;

pub use canonical_form::{CanonicalForm, StarKind};
pub use map::MobiusMap;
