//! One driver per Möbius scheme: which rule the vertex pass evaluates in each star, and which
//! blends assemble the new points from the candidates (seed 000 §4.1 step 4, §4.3 for the
//! per-scheme choices). Each writes the output vertex layout of its linear scheme.

pub(super) mod akleman;
pub(super) mod butterfly;
pub(super) mod catmull_clark;
pub(super) mod doo_sabin;
pub(super) mod kobbelt;
pub(super) mod loop_scheme;
pub(super) mod simplest;
