//! Ball-bar analysis: circle fit, harmonics, ISO 230-4 circular test
//! (takayama-alignment-travel-range; ISO 230-4).
//!
//! | file | what it models |
//! |---|---|
//! | [`circle_fit`] | geometric least-squares circle (algebraic seed + Levenberg–Marquardt) |
//! | [`harmonics`] | least-squares harmonic fit of a radial deviation, valid on partial ranges |
//! | [`trace_import`] | CSV/TSV ball-bar traces (angle + deviation or X/Y), split into CCW/CW runs |
//! | [`trim`] | the constant-feed part of a trace: lead-in, lead-out, standstill and overshoot left out |
//! | [`iso230_4`] | ISO 230-4 circular deviation G, hysteresis H, radial deviation F |
//! | [`diagnostics`] | backlash, reversal spikes, servo and scale mismatch, squareness, cyclic error |
//! | [`cyclic`] | the cyclic-error pitch search and amplitudes of the diagnostics |
//! | [`synthetic`] | synthetic traces with known machine errors (the diagnostics' forward model) |
//! | [`b5r_beside`] | a Renishaw `.b5r` report's features beside ours |

pub mod b5r_beside;
pub mod circle_fit;
pub mod cyclic;
pub mod diagnostics;
pub mod harmonics;
pub mod iso230_4;
pub mod synthetic;
pub mod trace_import;
pub mod trim;

pub use circle_fit::{fit_circle, Circle, FitError};
pub use cyclic::CyclicTest;
pub use diagnostics::{Centre, Cyclic, Diagnostics, Spike};
pub use harmonics::{fit_harmonics, Harmonic, HarmonicsError};
pub use iso230_4::{
    circular_deviation, circular_test, CircularDeviation, CircularTest, CircularTestError,
    RunResult,
};
pub use synthetic::{synthetic_trace, SyntheticConfig, SyntheticError};
pub use trace_import::{
    parse_ballbar_trace, parse_ballbar_trace_bytes, BallbarColumns, BallbarTrace,
    BallbarTraceError, Direction, ParseOptions, PlanePoint, Run, TraceCentre,
};
pub use trim::{TimeBase, TrimReason, Trimmed, Trimming};
