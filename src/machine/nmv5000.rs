//! DMG MORI NMV5000 feed drives, X, Y and C: suzuki-best-kffp Table 1.
//!
//! Values are copied from Table 1 as printed, in SI units:
//! - `kpp` = 60 1/s (the table; the text of §3 says the NC default was 30 —
//!   the table is the identified model, so it is used here; the text's 30
//!   is the `kppText` loop reading below).
//! - `kvi`: the table prints "Nms/rad" for Kvi as for Kvp, which cannot be
//!   right for an integral gain; it is read as N·m/rad in
//!   `τ = Kvp e + Kvi ∫e dt`, values as printed (see `servo::response`).
//! - X's loop (J, C, Kvp, Kvi) is read at the motor, the table moving one
//!   lead (16 mm) per motor turn.
//! - `kffp` is a set value (`*` in the table); the preset uses 100 %.
//! - `lead`: X has the 16 mm ball screw of the table. For Y the table lists
//!   no lead but `r = 1 m/rad` and `K_FF = 1`, i.e. the Y loop is already
//!   written in load units; `r = l/2π = 1` gives `lead = 2π m`. Apart
//!   from J the Y column repeats the C column (C, Kvp, Kvi, Ts, Ta, Tp); we
//!   suspect a copy, but use it as printed.
//! - `ts` is each axis's own smoothing, as printed: X 0.05 s, Y and C
//!   0.064 s. X therefore runs 7 ms ahead of Y and C in the feed-vector
//!   test (see `docs/servo.md`).
//! - `torqueMax` = 725 N·m for C (§5.2, Fig. 17); the paper gives no limit
//!   for X and Y.
//! - `j1` = 1.70 kg·m², the lightest of the paper's three work pieces.
//!
//! # Loop readings ([`LOOP_READINGS`], first = default)
//! Table 1 as printed gives X an underdamped velocity loop (Kvp/J ≈
//! 39 rad/s below Kpp = 60 1/s) and `|G_X(jω)| > 1` (Eq. 12: the radius
//! grows), against the paper's ΔR > 0 (§4.2). The paper leaves two things
//! open that shape the X loop, each a named reading:
//! - `table` (default): Table 1 as printed, J at the motor.
//! - `kppText`: Kpp = 30 1/s on every axis, as §3 states ("the default
//!   value of the position proportional gain K_pp was 30 in all axes").
//! - `inertiaAtLoad`: J is the load-side equivalent of each column, turned
//!   into motor units by the column's transformation coefficient
//!   `r = l/2π` (Table 1): `J_motor = J·r²`, i.e. X's 4.5 read as kg
//!   behind the 16 mm lead (2.918·10⁻⁵ kg·m² at the motor); Y and C have
//!   `r = 1` and are unchanged. C, Kvp, Kvi stay at the motor as printed.
//!   This goes against the printed unit kg·m² of X's J.
//!
//! `docs/readings.md` lists what each gives against the paper.

use std::collections::BTreeMap;

use super::paper_sweep::{PaperSaturationPoint, PaperSweep};
use super::{Machine, MachineError};
use crate::servo::{AxisKind, AxisParams};

/// The loop readings (module header), as `machinePreset('nmv5000')
/// .loopReadings` lists them; the first is the default.
pub const LOOP_READINGS: [&str; 3] = ["table", "kppText", "inertiaAtLoad"];

/// The position gain the text of §3 states for every axis, 1/s.
const KPP_TEXT: f64 = 30.0;

/// The position gain Table 1 prints for every axis, 1/s.
const KPP_TABLE: f64 = 60.0;

fn axis(kind: AxisKind, j: f64, c: f64, kvp: f64, kvi: f64, ts: f64, tp: f64) -> AxisParams {
    AxisParams {
        kind,
        j,
        j1: 0.0,
        c,
        kpp: KPP_TABLE,
        kvp,
        kvi,
        kffp: 100.0,
        ts,
        ta: 0.015,
        tp,
        torque_max: None,
        lead: None,
        gear_ratio: None,
        backlash: 0.0,
        pitch_error: Vec::new(),
        pitch_reading: Default::default(),
        friction: 0.0,
        gravity: 0.0,
    }
}

/// The preset.
pub fn machine() -> Machine {
    let mut x = axis(AxisKind::Linear, 4.5, 1.0, 177.5, 0.198, 0.05, 0.0155);
    x.lead = Some(0.016);
    let mut y = axis(AxisKind::Linear, 5.0, 5.0, 4700.0, 0.274, 0.064, 0.005);
    y.lead = Some(std::f64::consts::TAU);
    let mut c = axis(AxisKind::Rotary, 4.2, 5.0, 4700.0, 0.274, 0.064, 0.005);
    c.j1 = 1.70;
    c.torque_max = Some(725.0);
    Machine {
        name: "nmv5000".into(),
        description: "DMG MORI NMV5000 5-axis machining centre: X, Y ball-screw axes and the direct-drive C table".into(),
        source: "suzuki-best-kffp, Table 1 (feed-drive model parameters); 725 N·m C torque limit from §5.2, Fig. 17".into(),
        axes: BTreeMap::from([("x".into(), x), ("y".into(), y), ("c".into(), c)]),
        limits: BTreeMap::new(),
        kinematics: None,
        example_errors: None,
        example_drives: None,
        paper_sweep: Some(paper_sweep()),
        // The readings of best_kffp::saturation (data here: the preset may not
        // import the study above it; a test there checks the two agree).
        saturation_readings: ["preControlOff", "presetKffp", "inertiaOnly"]
            .iter()
            .map(|s| s.to_string())
            .collect(),
        loop_readings: LOOP_READINGS.iter().map(|s| s.to_string()).collect(),
    }
}

/// The paper's sweep (§3): R_C = 5 mm, R_W = 8 mm, ω = 0.5π … 4π rad/s,
/// J1 = 1.70, 3.24, 4.77 kg·m²; acc/dec 0.064 s (Figs. 12, 24:
/// dω/dt = ω/0.064 s); the required F_C = 200 mm/min (§2, Fig. 5); the
/// saturation points of §5.2 (dω/dt from Fig. 17, ω from Fig. 20, R_C at
/// F_C = 200 mm/min from Fig. 21).
fn paper_sweep() -> PaperSweep {
    let pi = std::f64::consts::PI;
    let point = |j_total, accel_sat, omega_sat, rc_min| PaperSaturationPoint {
        j_total,
        accel_sat,
        omega_sat,
        rc_min,
    };
    PaperSweep {
        source: "suzuki-best-kffp §3 (conditions); §5.2, Figs. 17, 20, 21 (saturation points)"
            .into(),
        rc: 5.0,
        rw: 8.0,
        omega: [0.5, 1.0, 1.5, 2.0, 3.0, 4.0]
            .iter()
            .map(|k| k * pi)
            .collect(),
        j1: vec![1.70, 3.24, 4.77],
        accel_time: 0.064,
        feed_at_cutting_point: 200.0,
        saturation: vec![
            point(5.9, 146.7, 9.39, 0.36),
            point(7.4, 118.5, 7.58, 0.44),
            point(8.9, 91.1, 5.83, 0.57),
        ],
    }
}

/// The preset under the loop reading `reading` (one of
/// [`LOOP_READINGS`]; module header).
pub fn with_loop_reading(reading: &str) -> Result<Machine, MachineError> {
    let mut m = machine();
    match reading {
        "table" => {}
        "kppText" => m.axes.values_mut().for_each(|a| a.kpp = KPP_TEXT),
        "inertiaAtLoad" => {
            for a in m.axes.values_mut() {
                if let Some(lead) = a.lead {
                    // r = l/2π m/rad: kg on the load side → kg·m² at the motor
                    a.j *= (lead / std::f64::consts::TAU).powi(2);
                }
            }
        }
        _ => {
            return Err(MachineError::UnknownReading {
                machine: m.name,
                reading: reading.to_string(),
                known: LOOP_READINGS.join(", "),
            })
        }
    }
    Ok(m)
}
