//! Shared numerical kernels, one definition each: Brent's root finder,
//! Levenberg–Marquardt least squares, angle wrapping, a deterministic
//! gaussian sequence for reproducible noise, and the compact
//! number format of error messages. The models call these
//! instead of carrying their own copies.

pub mod angle;
pub mod brent;
pub mod compact;
pub mod gaussian;
pub mod levenberg_marquardt;

pub use angle::wrap_angle;
pub use brent::brent;
pub use compact::compact;
pub use gaussian::gaussian;
pub use levenberg_marquardt::{
    levenberg_marquardt, levenberg_marquardt_lazy, LmOptions, LmResult, Normal,
};
