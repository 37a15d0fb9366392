//! Torque-saturation limits of the rotary axis (suzuki-best-kffp §5.2,
//! Figs. 17 and 21).
//!
//! For each load `J1` the C axis of the feed-vector test is simulated
//! without a torque limit at a reference ω; the loop is linear and starts
//! from rest, so its torque command is proportional to ω and the largest ω
//! that keeps `max |τ| ≤ τ_max` is `ω_sat = ω_ref·τ_max/max|τ_ref|`, exactly
//! on the same sample grid as [`crate::feed_vector::feed_vector_test`]
//! (which therefore does not saturate at 0.97·ω_sat and does at 1.03·ω_sat).
//! Then `accelSat = ω_sat/accelTime` (the command's acceleration) and
//! `rcMin = F_C/ω_sat` (Eq. 1).
//!
//! # Readings (`query.reading`, names in [`READINGS`])
//! The paper (§5.2, Fig. 17) gives the saturating `dω/dt` = 146.7, 118.5,
//! 91.1 rad/s² and ω = 9.39, 7.58, 5.83 rad/s for J + J1 = 5.9, 7.4,
//! 8.9 kg·m²; `dω/dt = ω/0.064 s` in every case, so its α is the
//! *commanded* acceleration. It does not state the K_FFP of Fig. 17.
//! - `preControlOff` (default): the commanded acceleration, the C loop with
//!   K_FFP = 0 (Pre-Control off). A loop that lags its command accelerates
//!   the axis less, so it saturates later: 143.5 / 114.6 / 95.2 rad/s²
//!   (dt 1 ms), within 2.2 / 3.3 / 4.5 % of the paper, and ω_sat·(J + J1)
//!   within 0.6 % of the paper's mean. It is the default because it is the
//!   reading that reproduces the paper's stated numbers.
//! - `presetKffp`: the commanded acceleration with the machine's own K_FFP
//!   (the preset's 100 %): 120.3 / 96.1 / 79.9 rad/s², 18–12 % low.
//! - `inertiaOnly`: the bound `J·α = τ_max` alone (no viscous torque, no
//!   loop): α = τ_max/(J + J1), ω = α·accelTime: 122.9 / 98.0 / 81.5.
//!
//! The paper's three points are not consistent with one another under any
//! model whose torque per rad/s grows with J: its ω_sat·(J + J1) is 55.4,
//! 56.1 and 51.9 (rising, then falling by 7.5 %), so no reading can be within
//! 2 % at all three; `docs/readings.md` lists each reading's distances.
//!
//! # Units
//! J in kg·m²; τ in N·m; accelTime in s; `feedAtCuttingPoint` in mm/min
//! (the paper's F_C = 200 mm/min); ω in rad/s; α in rad/s²; R_C in mm.

use serde::{Deserialize, Serialize};

use super::BestKffpError;
use crate::feed_vector::{self, Condition, FeedVectorError};
use crate::machine::Machine;

/// The JS `torqueSaturation` query.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct SaturationQuery {
    /// Load inertias J1 to evaluate, kg·m².
    pub j1: Vec<f64>,
    /// C torque limit, N·m; absent: the machine's (`axes.c.torqueMax`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub torque_max: Option<f64>,
    /// Acc/dec time, s.
    pub accel_time: f64,
    /// Feed speed at the cutting point F_C, mm/min.
    pub feed_at_cutting_point: f64,
    /// Time step, s (default 1 ms as in `feedVectorTest`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dt: Option<f64>,
    /// The reading (module header); default `preControlOff`.
    #[serde(default)]
    pub reading: SaturationReading,
}

/// How the paper's saturation point is read (module header).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub enum SaturationReading {
    /// Commanded acceleration, C loop with K_FFP = 0 (reproduces the paper).
    #[default]
    PreControlOff,
    /// Commanded acceleration, the machine's own K_FFP.
    PresetKffp,
    /// `J·α = τ_max` alone.
    InertiaOnly,
}

/// The names of the readings, as `machinePreset(..).saturationReadings`
/// lists them; the first is the default.
pub const READINGS: [&str; 3] = ["preControlOff", "presetKffp", "inertiaOnly"];

/// One saturation limit (Fig. 21 point).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct SaturationPoint {
    /// J + J1, kg·m².
    pub j_total: f64,
    /// Largest commanded C acceleration without saturation, rad/s².
    pub accel_sat: f64,
    /// Largest ω without saturation, rad/s.
    pub omega_sat: f64,
    /// Smallest R_C at the given F_C, mm.
    pub rc_min: f64,
    /// Peak torque command per rad/s of ω, N·m·s/rad.
    pub torque_per_omega: f64,
}

/// The saturation limit for each load (the JS `torqueSaturation`).
///
/// # Units
/// See the module header.
///
/// # Examples
/// ```
/// use mtmotion::best_kffp::saturation::{torque_saturation, SaturationQuery};
/// let m = mtmotion::machine::preset("nmv5000").unwrap();
/// let q = SaturationQuery { j1: vec![1.70], torque_max: None, accel_time: 0.064,
///                           feed_at_cutting_point: 200.0, dt: None,
///                           reading: Default::default() };
/// let p = torque_saturation(&m, &q).unwrap()[0];
/// assert!((p.j_total - 5.9).abs() < 1e-12);
/// assert!((p.rc_min * p.omega_sat - 200.0 / 60.0).abs() < 1e-12);
/// // a lagging loop (K_FFP = 0) saturates above the naive 725/5.9 rad/s²
/// assert!(p.accel_sat > 725.0 / 5.9);
/// // the limit is the preset's C torqueMax (725 N·m) unless the query gives one
/// let half = SaturationQuery { torque_max: Some(362.5), ..q.clone() };
/// let h = torque_saturation(&m, &half).unwrap()[0];
/// assert!((h.omega_sat - p.omega_sat / 2.0).abs() < 1e-9 * p.omega_sat);
/// ```
pub fn torque_saturation(
    machine: &Machine,
    q: &SaturationQuery,
) -> Result<Vec<SaturationPoint>, BestKffpError> {
    check_query(q)?;
    let torque_max = q
        .torque_max
        .or_else(|| machine.axes.get("c").and_then(|c| c.torque_max))
        .ok_or(BestKffpError::NoTorqueLimit)?;
    let runs =
        q.j1.iter()
            .map(|&j1| load_run(machine, q, torque_max, j1))
            .collect::<Result<Vec<_>, _>>()?;
    // the whole study: every load's run, counted before any is simulated
    let steps: u64 = runs.iter().map(|r| r.steps() as u64).sum();
    crate::budget::check(
        "torque-saturation study",
        steps,
        crate::budget::MAX_SATURATION_STEPS,
        "servo steps (loads × steps of each load's C-axis run)",
        "give fewer loads or raise dt",
    )
    .map_err(FeedVectorError::from)?;
    runs.iter()
        .map(|r| saturation_point(r, q, torque_max))
        .collect()
}

/// A feed at the cutting point > 0, at least one load, acc/dec time in 0…100 s.
fn check_query(q: &SaturationQuery) -> Result<(), BestKffpError> {
    if !(q.feed_at_cutting_point.is_finite() && q.feed_at_cutting_point > 0.0) {
        return Err(BestKffpError::BadQuery {
            field: "feedAtCuttingPoint",
            value: q.feed_at_cutting_point,
            expected: "must be > 0 mm/min",
        });
    }
    if q.j1.len() > crate::budget::MAX_SATURATION_LOADS {
        return Err(BestKffpError::BadQuery {
            field: "j1",
            value: q.j1.len() as f64,
            expected: "at most 1000 load inertias (each runs a simulation of the C axis)",
        });
    }
    if q.j1.is_empty() {
        return Err(BestKffpError::BadQuery {
            field: "j1",
            value: 0.0,
            expected: "give at least one load inertia in kg·m²",
        });
    }
    if !(q.accel_time.is_finite()
        && (0.0..=100.0).contains(&q.accel_time)
        && (q.accel_time == 0.0 || q.accel_time.is_normal()))
    {
        return Err(BestKffpError::BadQuery {
            field: "accelTime",
            value: q.accel_time,
            expected: "the acc/dec time must be between 0 and 100 s",
        });
    }
    Ok(())
}

/// One load's C-axis run, set up and sized but not simulated.
struct LoadRun {
    /// The X, Y, C axes of the test with this load (C without a torque limit).
    axes: [crate::servo::AxisParams; 3],
    /// The time step, s.
    dt: f64,
    /// Samples of the run (0 for the `inertiaOnly` reading, which runs none).
    n: usize,
    /// The acceleration time of the command, s.
    t_acc: f64,
}

impl LoadRun {
    /// Servo steps the run takes (its samples and the read-ahead pad).
    fn steps(&self) -> usize {
        if self.n == 0 {
            0
        } else {
            self.n + feed_vector::read_ahead_pad(&self.axes, self.dt)
        }
    }
}

/// Reference ω of the runs, rad/s (the loop is linear: the torque scales).
const OMEGA_REF: f64 = 1.0;

/// Sets up the run of the C axis with load inertia `j1` (kg·m²) and torque
/// limit `torque_max` (N·m).
fn load_run(
    machine: &Machine,
    q: &SaturationQuery,
    torque_max: f64,
    j1: f64,
) -> Result<LoadRun, BestKffpError> {
    let cond = Condition {
        rc: 1.0,
        rw: 1.0,
        omega: OMEGA_REF,
        accel_time: q.accel_time,
        j1,
        torque_max: Some(torque_max),
        duration: None,
        dt: q.dt,
        kffp: None,
    };
    cond.validate()?;
    let mut axes = feed_vector::axes_for(machine, &cond)?;
    axes[2].torque_max = None;
    // The saturating acceleration is ω_sat over the command's
    // acceleration time: the acc/dec ramp, or with accelTime 0 (acc/dec
    // once) the Ts smoothing that then shapes the velocity step alone.
    let t_acc = if q.accel_time > 0.0 {
        q.accel_time
    } else {
        axes[2].ts
    };
    if t_acc <= 0.0 {
        return Err(BestKffpError::BadQuery {
            field: "accelTime",
            value: q.accel_time,
            expected: "with accelTime 0 and no Ts on the C axis the command is a velocity step with no finite acceleration; give accelTime > 0 s",
        });
    }
    let dt = cond.step();
    if q.reading == SaturationReading::InertiaOnly {
        return Ok(LoadRun {
            axes,
            dt,
            n: 0,
            t_acc,
        });
    }
    if q.reading == SaturationReading::PreControlOff {
        axes[2].kffp = 0.0;
    }
    // through the acc/dec, the smoothing and the settling of the loop
    let n_f = (feed_vector::steady_from(&axes, &cond) / dt).ceil() + 1.0;
    if n_f > feed_vector::MAX_SAMPLES as f64 {
        return Err(BestKffpError::BadQuery {
            field: "dt",
            value: dt,
            expected: "too fine for this acc/dec time: one load's run would exceed the 1,000,000-sample budget of the feed-vector test; raise dt or shorten accelTime",
        });
    }
    Ok(LoadRun {
        axes,
        dt,
        n: n_f as usize,
        t_acc,
    })
}

/// The saturation point of run `r` with torque limit `torque_max` (N·m).
fn saturation_point(
    r: &LoadRun,
    q: &SaturationQuery,
    torque_max: f64,
) -> Result<SaturationPoint, BestKffpError> {
    let c = &r.axes[2];
    if r.n == 0 {
        // the inertiaOnly reading: J·α = τ_max alone
        let j = c.inertia();
        let accel_sat = torque_max / j;
        let omega_sat = accel_sat * r.t_acc;
        return Ok(SaturationPoint {
            j_total: j,
            accel_sat,
            omega_sat,
            rc_min: q.feed_at_cutting_point / 60.0 / omega_sat,
            torque_per_omega: torque_max / omega_sat,
        });
    }
    let cmd: Vec<f64> = (0..r.steps())
        .map(|i| feed_vector::command::angle(i as f64 * r.dt, OMEGA_REF, q.accel_time))
        .collect();
    let run = feed_vector::run_axis("c", c, r.dt, &cmd, r.n)?;
    let peak = run.torque.iter().fold(0.0_f64, |m, t| m.max(t.abs()));
    let per_omega = peak / OMEGA_REF;
    let omega_sat = torque_max / per_omega;
    let accel_sat = omega_sat / r.t_acc;
    Ok(SaturationPoint {
        j_total: c.inertia(),
        accel_sat,
        omega_sat,
        rc_min: q.feed_at_cutting_point / 60.0 / omega_sat,
        torque_per_omega: per_omega,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_nmv5000_preset_lists_these_readings_default_first() {
        let m = crate::machine::preset("nmv5000").unwrap();
        assert_eq!(m.saturation_readings, READINGS.map(String::from).to_vec());
    }
}
