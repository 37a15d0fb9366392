//! 5-axis machine kinematics with geometric errors: 4×4 homogeneous-transform
//! chains with error matrices (thasana-htm-nc-compensation §II-B, Eqs. 1–3,
//! Eq. 8), errors named as in ISO 230-1 / ISO 230-7, forward kinematics,
//! every inverse-kinematics branch, Newton inversion of the full error model,
//! and first-order error propagation.
//!
//! - [`htm`]: elementary transforms and the error matrix `E` (Eq. 3);
//! - [`chain`]: machine chains as data (links, joints);
//! - [`errors`]: ISO-named geometric errors and how they enter the chain;
//! - [`forward`](mod@forward): compiled forward kinematics;
//! - [`inverse`](mod@inverse): closed-form inverse kinematics of the nominal chain;
//! - [`newton`]: inverse of the full error model (thasana §II-D);
//! - [`propagation`]: first-order error propagation and sensitivities.
//!
//! Units: mm and rad in the core (rotary joint values in rad); the JS
//! binding converts rotary axis positions from and to degrees.

pub mod chain;
pub mod errors;
pub mod forward;
pub mod htm;
pub mod inverse;
pub mod newton;
pub mod propagation;

pub use chain::{Chain, Joint, JointKind, Link, AXES};
pub use errors::GeometricErrors;
pub use forward::{forward, Model, Pose};
pub use inverse::{inverse, Limits, Solution};

/// Errors of the kinematics models.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum KinematicsError {
    /// The chain description is invalid.
    #[error("machine chain: `{field}` {why}")]
    BadChain {
        /// Path of the offending field, e.g. `links[2].joint.axis`.
        field: String,
        /// What was expected.
        why: String,
    },
    /// An error parameter is invalid.
    #[error("errors: `{}` {why}", crate::budget::clip(.key, 60))]
    BadError {
        /// Path of the offending key, e.g. `location.XOQ`.
        key: String,
        /// What was expected.
        why: String,
    },
    /// An input value is invalid.
    #[error("`{field}` {why}")]
    BadInput {
        /// The field, e.g. `pose.orientation`.
        field: String,
        /// What was expected.
        why: String,
    },
    /// The pose cannot be reached.
    #[error("pose unreachable: {0}")]
    Unreachable(String),
    /// Newton iteration did not converge.
    #[error("Newton inversion of the error model did not converge at {context}: residual {residual:.3e} after {iterations} iterations")]
    NoConvergence {
        /// Where (e.g. `line 12`).
        context: String,
        /// Final residual norm (mm).
        residual: f64,
        /// Iterations done.
        iterations: usize,
    },
}

/// Converts a joint vector with rotary axes in degrees to mm/rad.
pub fn q_from_degrees(q: &[f64; 6]) -> [f64; 6] {
    let mut r = *q;
    for v in &mut r[3..] {
        *v = v.to_radians();
    }
    r
}

/// Converts a joint vector with rotary axes in rad to mm/degrees.
pub fn q_to_degrees(q: &[f64; 6]) -> [f64; 6] {
    let mut r = *q;
    for v in &mut r[3..] {
        *v = v.to_degrees();
    }
    r
}
