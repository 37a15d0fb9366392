//! ISO 10791-6 cone-frustum ball-bar test, simulated
//! (kato-cone-frustum-ballbar §2–3): the 3D circular five-axis motion
//! equivalent to cone-frustum cutting, the per-axis feed drives of Fig. 2
//! (ball screw, worm gear with reduction ratio, backlash, pitch error of
//! Eq. 1), the geometric errors of the machine, and the sensitivity
//! coefficients of the bar reading to each axis and each error.
//!
//! - [`path`]: the path for half-apex θ (15°, 45°), inclination β (10°,
//!   30°) and the perpendicular or parallel bar of Fig. 1;
//! - [`drive`]: servo model or ideal servo per axis;
//! - [`test`](mod@test): the simulation and its result;
//! - [`sensitivity`]: sensitivity coefficients along the path.
//!
//! Units: mm, rad, s inside; the configuration takes degrees for the cone
//! angles and mm/min for the feed, as in kato.

pub mod drive;
pub mod path;
pub mod sensitivity;
pub mod test;

pub use path::Method;
pub use test::{cone_frustum_test, ConeFrustumConfig, ConeFrustumResult};

/// Errors of the cone-frustum test.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ConeFrustumError {
    /// A configuration value is out of range.
    #[error("cone-frustum test: `{field}` = {}: {why}", crate::numeric::compact(*.value))]
    BadConfig {
        /// The camelCase field.
        field: &'static str,
        /// The value given.
        value: f64,
        /// What was expected.
        why: &'static str,
    },
    /// The servo simulation would be over its work budget.
    #[error("cone-frustum test: {0}")]
    Budget(#[from] crate::budget::BudgetError),
    /// The machine preset or description is unusable.
    #[error(transparent)]
    Machine(#[from] crate::machine::MachineError),
    /// The chain or errors are invalid, or the path is unreachable.
    #[error("cone-frustum test: {0}")]
    Kinematics(#[from] crate::kinematics::KinematicsError),
    /// The drive errors (backlash, pitch error) are invalid.
    #[error("cone-frustum test: {0}")]
    Drives(crate::servo::ServoError),
    /// The path leaves an axis' travel.
    #[error("cone-frustum test: the path needs {axis} = {value:.3} at {angle_deg:.1}°, outside its limits [{min}, {max}] (mm or degrees); move `centre` or change the angles")]
    OutOfLimits {
        /// Axis letter.
        axis: String,
        /// Needed value (mm or degrees).
        value: f64,
        /// Path angle, degrees.
        angle_deg: f64,
        /// Lower limit.
        min: f64,
        /// Upper limit.
        max: f64,
    },
    /// No inverse-kinematics branch follows the whole path continuously
    /// inside the limits: some axis would have to jump.
    #[error("cone-frustum test: no continuous axis motion inside the limits follows this path; {axis} would have to jump by {jump_deg:.1}° at {angle_deg:.1}° (a branch change the drives cannot make); move `centre`, change the angles or widen the {axis} limits")]
    BranchJump {
        /// Axis letter of the largest jump.
        axis: String,
        /// Size of the jump, degrees.
        jump_deg: f64,
        /// Path angle, degrees.
        angle_deg: f64,
    },
    /// A servo axis is missing or invalid.
    #[error("cone-frustum test, axis {axis}: {why}")]
    Servo {
        /// Axis letter.
        axis: String,
        /// What went wrong.
        why: String,
    },
}
