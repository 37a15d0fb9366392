//! The test conditions a paper ran on a preset machine, as data, so that
//! the page and the tests read them from the core instead of carrying
//! them: the constant-feed-speed-vector sweep of suzuki-best-kffp §3
//! (Figs. 14, 15, 20, 22) and the torque-saturation points it quotes
//! (§5.2, Fig. 17, Fig. 21).
//!
//! Units: mm, rad/s, s, kg·m², mm/min, rad/s² (named per field).

use serde::{Deserialize, Serialize};

/// One torque-saturation point as the paper quotes it (§5.2).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct PaperSaturationPoint {
    /// J + J1, kg·m².
    pub j_total: f64,
    /// Saturating angular acceleration dω/dt, rad/s².
    pub accel_sat: f64,
    /// Saturating angular velocity ω, rad/s.
    pub omega_sat: f64,
    /// Smallest R_C at the paper's F_C, mm.
    pub rc_min: f64,
}

/// The paper's sweep of the constant-feed-speed-vector test and its
/// quoted saturation points.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct PaperSweep {
    /// Where the numbers come from (paper, section, figures).
    pub source: String,
    /// Radius R_C of the circle at the cutting point, mm.
    pub rc: f64,
    /// Offset R_W of the linear axes' circle, mm.
    pub rw: f64,
    /// Angular velocities ω of the sweep, rad/s.
    pub omega: Vec<f64>,
    /// Load inertias J1 on the rotary axis, kg·m² (the work pieces).
    pub j1: Vec<f64>,
    /// Acc/dec time of the rotary axis, s.
    pub accel_time: f64,
    /// The required feed speed at the cutting point F_C, mm/min.
    pub feed_at_cutting_point: f64,
    /// The saturation points the paper quotes, one per `j1`.
    pub saturation: Vec<PaperSaturationPoint>,
}
