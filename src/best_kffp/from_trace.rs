//! Best K_FFP from a measured constant-feed-speed-vector trace
//! (suzuki-best-kffp §4.1 Fig. 7 for the trace, §4.7 Eq. 20 and §5.2–5.3
//! for the K_FFP that makes α − β zero).
//!
//! The paper measures α − β on the machine, then computes the Best K_FFP on
//! its identified model. A user's model (a preset, edited to their axis, or
//! identified) is never exact, so the trace anchors it:
//! 1. the trace is analysed as in [`crate::feed_vector::trace_analysis`]:
//!    the measured steady mean of α − β, its shape error and torque;
//! 2. optionally (`identify`), X and Y are first identified from the trace
//!    ([`crate::servo::identify::identify_axis`]: C, Kvp, Kpp with J held,
//!    from the measured X and Y against the command rebuilt from the
//!    condition), so the model's slope dβ/dK_FFP is the machine's too;
//! 3. the model runs the same test with the K_FFP set used during the
//!    measurement (`cond.kffp`, required); δ = measured − simulated mean
//!    α − β is the model's mismatch at that set;
//! 4. each linear axis gets the K_FFP whose phase lag on the model equals
//!    the C lag plus the mismatch: −∠G_X(jω; K_X) = α_th + δ (and Y), by
//!    [`super::analytic::match_lag`]. Reading chosen: δ is taken as
//!    independent of K_FFP over the correction (the model's slope
//!    dβ/dK_FFP is trusted, its level is corrected by the measurement);
//!    whether the error sits in α or in β does not matter, only the
//!    difference enters;
//! 5. when the C torque saturates (in the trace, or on the model) the
//!    linear model does not hold; the common shift of X and Y is then
//!    searched on the saturating simulation so that simulated mean + δ = 0
//!    (the paper's Fig. 18 mode);
//! 6. the result carries the prediction after (the model's simulation with
//!    the new set, its mean α − β shifted by δ, its shape-error half
//!    amplitude shifted by the measured − model difference) next to the
//!    measurement, so the user sees what changes.
//!
//! Units: K_FFP in %, angles in rad, lengths in mm, torque in N·m.

use serde::{Deserialize, Serialize};

use super::{matched_set, Baseline, BestKffpError, Method, Options};
use crate::feed_vector::{self, Condition, FeedVectorResult, KffpSet, Summary};
use crate::machine::Machine;
use crate::servo::identify::{identify_axis, MeasuredTrace};
use crate::servo::AxisParams;

/// Options of [`best_kffp_from_trace`]: the search of [`super::best_kffp`]
/// and whether to identify X and Y first (fields, not a flattened
/// [`Options`], so that the JS reader can name every key).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase", default)]
pub struct TraceOptions {
    /// Method; default `auto`.
    pub method: Method,
    /// Lower bound of the K_FFP search, %.
    pub k_min: f64,
    /// Upper bound of the K_FFP search, %.
    pub k_max: f64,
    /// Identify X and Y (C, Kvp, Kpp) from the trace first.
    pub identify: bool,
}

impl Default for TraceOptions {
    fn default() -> Self {
        let o = Options::default();
        Self {
            method: o.method,
            k_min: o.k_min,
            k_max: o.k_max,
            identify: false,
        }
    }
}

impl TraceOptions {
    /// The search options.
    pub fn search(&self) -> Options {
        Options {
            method: self.method,
            k_min: self.k_min,
            k_max: self.k_max,
        }
    }
}

/// An axis identified from the trace.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct IdentifiedAxis {
    /// The axis letter.
    pub axis: String,
    /// The identified parameters (J held at the model's).
    pub params: AxisParams,
    /// RMS of the position residual, mm.
    pub rms_position: f64,
}

/// The recommendation from a measured trace.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct TraceKffp {
    /// The K_FFP set used during the measurement, %.
    pub measured_with: KffpSet,
    /// The recommended K_FFP per axis, %.
    pub kffp: KffpSet,
    /// The trace's own summary (the measurement).
    pub measured: Summary,
    /// The model's simulated summary with the measurement's K_FFP set.
    pub model_before: Summary,
    /// δ: measured − simulated mean α − β, rad (the model's mismatch).
    pub mismatch: f64,
    /// The model's simulated summary with the recommended set.
    pub model_after: Summary,
    /// Predicted mean α − β after: the model's after + δ, rad.
    pub predicted_mean_angle_diff: f64,
    /// Predicted shape-error half amplitude after: the model's after plus
    /// the measured − model difference before (as δ for the mean; not
    /// below 0), mm.
    pub predicted_half_amplitude: f64,
    /// `analytic` or `simulated` (when C saturates).
    pub method: Method,
    /// X and Y as identified from the trace (empty unless asked).
    pub identified: Vec<IdentifiedAxis>,
}

/// Recommends the K_FFP set from `trace`, the analysis of a trace taken
/// with the set `cond.kffp`, on the user's model `machine`.
///
/// # Units
/// See the module header.
///
/// # Errors
/// [`BestKffpError::BadQuery`] without `cond.kffp` or with a measured mean
/// that is not finite; the errors of the feed-vector test and of the
/// Best K_FFP search.
///
/// # Examples
/// ```
/// use mtmotion::best_kffp::{best_kffp_from_trace, TraceOptions};
/// use mtmotion::feed_vector::{feed_vector_test, Condition, KffpSet};
/// let m = mtmotion::machine::preset("nmv5000").unwrap();
/// let mut cond = Condition::paper(std::f64::consts::PI);
/// cond.kffp = Some(KffpSet { x: 90.0, y: 90.0, c: m.axes["c"].kffp });
/// // The "measurement" is the model itself here: no mismatch.
/// let measured = feed_vector_test(&m, &cond).unwrap();
/// let r = best_kffp_from_trace(&m, &cond, &measured, &TraceOptions::default()).unwrap();
/// assert!(r.mismatch.abs() < 1e-12);
/// let before = measured.summary.mean_angle_diff;
/// assert!(r.predicted_mean_angle_diff.abs() < 0.05 * before.abs());
/// ```
pub fn best_kffp_from_trace(
    machine: &Machine,
    cond: &Condition,
    trace: &FeedVectorResult,
    options: &TraceOptions,
) -> Result<TraceKffp, BestKffpError> {
    let measured = &trace.summary;
    let opts = &options.search();
    let Some(measured_with) = cond.kffp else {
        return Err(BestKffpError::BadQuery {
            field: "condition.kffp",
            value: f64::NAN,
            expected: "give the K_FFP set (x, y, c in %) the trace was measured with",
        });
    };
    if !measured.mean_angle_diff.is_finite() {
        return Err(BestKffpError::BadQuery {
            field: "measured.meanAngleDiff",
            value: measured.mean_angle_diff,
            expected: "the trace's mean α − β must be a finite angle in rad",
        });
    }
    super::check_options(opts)?;
    cond.validate()?;
    let identified = if options.identify {
        identify_xy(machine, cond, trace)?
    } else {
        Vec::new()
    };
    let mut model = machine.clone();
    for a in &identified {
        model.axes.insert(a.axis.clone(), a.params.clone());
    }
    let machine = &model;
    let axes = feed_vector::axes_for(machine, cond)?;
    let base = Baseline::simulate(&axes, cond)?;
    let model_before = base.summary;
    let mismatch = measured.mean_angle_diff - model_before.mean_angle_diff;
    let c = &axes[2];
    let alpha = crate::servo::response::alpha_th(c, cond.omega)
        .map_err(|source| BestKffpError::Servo { axis: "c", source })?;
    let method = match opts.method {
        Method::Auto if measured.saturated || model_before.saturated => Method::Simulated,
        Method::Auto => Method::Analytic,
        m => m,
    };
    let (kffp, model_after) = matched_set(
        &base,
        cond,
        &axes,
        alpha + mismatch,
        -mismatch,
        method,
        opts,
    )?;
    let amplitude_mismatch = measured.half_amplitude - model_before.half_amplitude;
    Ok(TraceKffp {
        measured_with,
        kffp,
        measured: *measured,
        predicted_mean_angle_diff: model_after.mean_angle_diff + mismatch,
        predicted_half_amplitude: (model_after.half_amplitude + amplitude_mismatch).max(0.0),
        model_before,
        mismatch,
        model_after,
        method,
        identified,
    })
}

/// X and Y identified from the trace's measured positions against the
/// command rebuilt from the condition (uniform sampling required).
fn identify_xy(
    machine: &Machine,
    cond: &Condition,
    trace: &FeedVectorResult,
) -> Result<Vec<IdentifiedAxis>, BestKffpError> {
    let s = &trace.series;
    let dt = match s.t.as_slice() {
        [a, b, ..] => b - a,
        _ => f64::NAN,
    };
    let uniform =
        s.t.windows(2)
            .all(|w| ((w[1] - w[0]) - dt).abs() <= 1e-6 * dt.abs());
    if !(dt > 0.0 && uniform) {
        return Err(BestKffpError::BadQuery {
            field: "options.identify",
            value: dt,
            expected: "identification needs a trace sampled at a constant interval",
        });
    }
    let axes = feed_vector::axes_for(machine, cond)?;
    [
        ("x", &axes[0], &s.x_cmd, &s.x),
        ("y", &axes[1], &s.y_cmd, &s.y),
    ]
    .into_iter()
    .map(|(name, initial, command, position)| {
        let m = MeasuredTrace {
            dt,
            command: command.clone(),
            position: position.clone(),
            torque: None,
        };
        let r = identify_axis(initial, &m).map_err(|e| BestKffpError::Identify {
            axis: name,
            message: e.to_string(),
        })?;
        Ok(IdentifiedAxis {
            axis: name.to_string(),
            params: r.axis,
            rms_position: r.rms_position,
        })
    })
    .collect()
}
