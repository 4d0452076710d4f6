//! Surface-quality measures of seed 001 §4.3.
