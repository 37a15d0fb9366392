//! Cascaded feed drive for one axis (suzuki-best-kffp Fig. 11, Fig. 18,
//! Table 1; kato-cone-frustum-ballbar Fig. 2 and Eq. 1).
//!
//! Position P loop `kpp`, velocity PI loop (`kvp`, `kvi`), inertia `j` plus
//! load `j1`, viscous damping `c`, a ball screw of lead `lead` (linear axes)
//! or a direct drive / worm gear of ratio `gear_ratio` (rotary axes), and
//! FANUC-style Pre-Control feedforward (`kffp` %, smoothing `ts`, averaging
//! `ta`, preceding `tp`). Optional torque limit, backlash and worm-gear pitch
//! error `R = R_all + Σ W_i sin(N_i R_all θm + φ_i)` (kato Eq. 1).
//!
//! # Units
//! SI throughout the parameter set: kg·m², N·m·s/rad, 1/s, s, N·m, m (lead),
//! rad (backlash of a rotary axis) or mm (backlash of a linear axis).

pub mod axis;
pub mod discrete;
pub mod identify;
pub mod pid;
pub mod pitch_identify;
pub mod precontrol;
pub mod response;
pub mod simulate;
pub mod transmission;

pub use axis::{AxisKind, AxisParams, PitchReading, WormHarmonic};

/// Errors of the servo models.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ServoError {
    /// A parameter is outside its physical range.
    #[error("axis parameter `{field}` = {}: {expected}", crate::numeric::compact(*.value))]
    BadParameter {
        /// The camelCase field name, as in the JS API.
        field: &'static str,
        /// The offending value.
        value: f64,
        /// What was expected, e.g. "must be > 0".
        expected: &'static str,
    },
    /// A sample of a position command is unusable.
    #[error("position command, sample {index}: {why}")]
    BadCommand {
        /// 0-based sample index.
        index: usize,
        /// What is wrong and what was expected.
        why: &'static str,
    },
    /// The run is over its work budget.
    #[error(transparent)]
    Budget(#[from] crate::budget::BudgetError),
    /// A drive error (backlash, pitch error) of a machine is invalid.
    #[error("drives: `{}` {why}", crate::budget::clip(key, 40))]
    BadDriveError {
        /// Path of the offending key, e.g. `backlash.q`.
        key: String,
        /// What was expected.
        why: String,
    },
    /// The simulated loop diverges: its position runs away from a bounded
    /// command (gains too high for the time step, or an unstable loop).
    #[error("the axis loop is unstable: at dt = {} s its simulated position reaches {} while the command stays within ±{}; lower kpp, kvp or kvi (or the time step) until the loop is stable", crate::numeric::compact(*.dt), crate::numeric::compact(*.reached), crate::numeric::compact(*.command))]
    Unstable {
        /// The time step, s.
        dt: f64,
        /// The largest |position| reached (or NaN/∞), mm or rad.
        reached: f64,
        /// The largest |command|, mm or rad.
        command: f64,
    },
    /// A required parameter is missing for this kind of axis.
    #[error("axis parameter `{field}` is required: {why}")]
    MissingParameter {
        /// The camelCase field name.
        field: &'static str,
        /// Why it is needed.
        why: &'static str,
    },
}
