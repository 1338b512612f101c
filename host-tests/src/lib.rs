//! Independent std, f64 reference implementation (filled in by the reference work).
