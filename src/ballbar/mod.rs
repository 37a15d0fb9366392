//! Ball-bar analysis: circle fit, harmonics, ISO 230-4 circular test
//! (takayama-alignment-travel-range; ISO 230-4).
//!
//! | file | what it models |
//! |---|---|
//! | [`circle_fit`] | geometric least-squares circle (algebraic seed + Levenberg–Marquardt) |
//! | [`harmonics`] | least-squares harmonic fit of a radial deviation, valid on partial ranges |

pub mod circle_fit;
pub mod harmonics;

pub use circle_fit::{fit_circle, Circle, FitError};
pub use harmonics::{fit_harmonics, Harmonic, HarmonicsError};
