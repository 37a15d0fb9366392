//! Identification of the feed-drive parameters J, C, Kvp and Kpp of
//! suzuki-best-kffp Table 1 from a measured trace ("these parameters were
//! identified using simulation software", §4.5): the least-squares match of
//! [`super::simulate::simulate_axis`] to a measured position (and torque)
//! response to a known command — a step, a ramp or the circle of the
//! feed-vector test.
//!
//! Method: Levenberg–Marquardt on `ln J, ln C, ln Kvp, ln Kpp` (all stay
//! positive), forward-difference Jacobian (relative step 1e-6), residuals
//! `(p_sim − p_meas)/s_p` and `(τ_sim − τ_meas)/s_τ` with `s_p` the RMS of
//! the measured following error `p_meas − command` and `s_τ` the RMS of the
//! measured torque, so both signals weigh alike whatever their units. The
//! other parameters (Kvi, K_FFP, Ts, Ta, Tp, J1, lead, gear) are the NC's
//! set values and are taken from the `initial` axis.
//!
//! # Reading: what a position-only trace can identify
//! The velocity loop `T_v = (Kvp s + Kvi)/(J s² + (C + Kvp) s + Kvi)` is
//! unchanged when J, C, Kvp and Kvi are scaled together, and Kvi is
//! negligible in Table 1 (`Kvi/Kvp ≈ 6·10⁻⁵ rad/s`), so a position trace
//! fixes only the ratios. With a torque trace all four are identified; with
//! none, J is held at its initial value and C, Kvp, Kpp are identified
//! (the result then scales with the J given).
//!
//! # Units
//! As [`super::AxisParams`]; `dt` in s; command and position in mm
//! (linear) or rad (rotary); torque in N·m at the motor.

use nalgebra::{Matrix4, Vector4};
use serde::{Deserialize, Serialize};

use super::simulate::simulate_axis;
use super::{AxisParams, ServoError};
use crate::numeric::{levenberg_marquardt_lazy, LmOptions, Normal};

/// Errors of the identification.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum IdentifyError {
    /// The trace is unusable.
    #[error("`{field}`: {message}")]
    BadTrace {
        /// The field, e.g. `position[3]`.
        field: String,
        /// What is wrong and what was expected.
        message: String,
    },
    /// The initial axis is not a valid axis.
    #[error(transparent)]
    Servo(#[from] ServoError),
    /// The fit's simulations would pass the work budget
    /// ([`crate::budget::MAX_IDENTIFY_SAMPLES`]).
    #[error("axis identification: {0}")]
    Budget(#[from] crate::budget::BudgetError),
    /// The fit's own trial left the physical range (the caller's values
    /// were valid): said as the fit's doing, with the initial guess, not
    /// as a bad parameter the caller never set.
    #[error("the fit left the physical range from this initial guess (j = {}, c = {}, kvp = {}, kpp = {}): a trial step {why}; start from values nearer the axis", crate::numeric::compact(.initial[0]), crate::numeric::compact(.initial[1]), crate::numeric::compact(.initial[2]), crate::numeric::compact(.initial[3]))]
    FitDiverged {
        /// The initial j, c, kvp, kpp.
        initial: [f64; 4],
        /// What the trial step did, e.g. "took `kpp` out of its range (…)".
        why: String,
    },
}

fn bad(field: impl Into<String>, message: impl Into<String>) -> IdentifyError {
    IdentifyError::BadTrace {
        field: field.into(),
        message: message.into(),
    }
}

/// A measured response of one axis.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct MeasuredTrace {
    /// Sampling interval, s.
    pub dt: f64,
    /// The command (interpolator output), one sample per `dt`.
    pub command: Vec<f64>,
    /// The measured position, same length.
    pub position: Vec<f64>,
    /// The measured motor torque, same length (optional; needed for J).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub torque: Option<Vec<f64>>,
}

/// The identified parameters.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct Identified {
    /// The axis with J, C, Kvp and Kpp replaced.
    pub axis: AxisParams,
    /// Whether J was identified (a torque trace was given) or held.
    pub j_identified: bool,
    /// RMS position residual, mm or rad.
    pub rms_position: f64,
    /// RMS torque residual, N·m (0 without a torque trace).
    pub rms_torque: f64,
    /// Levenberg–Marquardt iterations.
    pub iterations: usize,
}

fn with(initial: &AxisParams, p: &[f64; 4]) -> AxisParams {
    AxisParams {
        j: p[0].exp(),
        c: p[1].exp(),
        kvp: p[2].exp(),
        kpp: p[3].exp(),
        ..initial.clone()
    }
}

fn rms(v: impl Iterator<Item = f64>) -> f64 {
    let (mut s, mut n) = (0.0, 0usize);
    for x in v {
        s += x * x;
        n += 1;
    }
    (s / n.max(1) as f64).sqrt()
}

/// Largest |command| or |position| of a trace, mm or rad: beyond it the
/// squared residuals overflow (a 1e308 sample gave an infinite RMS).
pub const MAX_POSITION: f64 = 1e6;
/// Largest |torque| of a trace, N·m.
pub const MAX_TORQUE: f64 = 1e7;

fn check(tr: &MeasuredTrace) -> Result<(), IdentifyError> {
    if !(tr.dt.is_finite() && tr.dt > 0.0) {
        return Err(bad("dt", format!("{}: expected a time step > 0 s", tr.dt)));
    }
    let n = tr.command.len();
    if n < 10 {
        return Err(bad("command", format!("{n} samples; give at least 10")));
    }
    let mut arrays = vec![("command", &tr.command), ("position", &tr.position)];
    if let Some(t) = &tr.torque {
        arrays.push(("torque", t));
    }
    for (name, v) in arrays {
        if v.len() != n {
            return Err(bad(
                name,
                format!("{} samples, but the command has {n}", v.len()),
            ));
        }
        if let Some(i) = v.iter().position(|x| !x.is_finite()) {
            return Err(bad(
                format!("{name}[{i}]"),
                format!("{} is not a finite number", v[i]),
            ));
        }
        let (limit, unit) = if name == "torque" {
            (MAX_TORQUE, "N·m")
        } else {
            (MAX_POSITION, "mm or rad")
        };
        if let Some(i) = v.iter().position(|x| x.abs() > limit) {
            return Err(bad(
                format!("{name}[{i}]"),
                format!(
                    "{} is outside ±{} {unit}; check the trace's units",
                    crate::numeric::compact(v[i]),
                    crate::numeric::compact(limit)
                ),
            ));
        }
    }
    Ok(())
}

/// Identifies J, C, Kvp and Kpp of `initial` from `trace` (module header).
///
/// # Errors
/// A trace with mismatched or non-finite samples, a bad `dt`, or an initial
/// axis whose J, C, Kvp or Kpp is not > 0.
pub fn identify_axis(
    initial: &AxisParams,
    trace: &MeasuredTrace,
) -> Result<Identified, IdentifyError> {
    check(trace)?;
    check_initial(initial)?;
    let lag = rms(trace
        .position
        .iter()
        .zip(&trace.command)
        .map(|(p, c)| p - c));
    if lag <= 0.0 {
        return Err(bad(
            "position",
            "equals the command: a trace without following error identifies nothing",
        ));
    }
    let tq = trace.torque.as_ref().map(|t| (t, rms(t.iter().copied())));
    if let Some((_, s)) = tq {
        if s <= 0.0 {
            return Err(bad(
                "torque",
                "is zero throughout: give the measured torque or omit it",
            ));
        }
    }
    let fit_problem = Problem {
        initial,
        trace,
        lag,
        tq,
        free: if tq.is_some() {
            vec![0, 1, 2, 3]
        } else {
            vec![1, 2, 3]
        },
        simulated: std::cell::Cell::new(0),
    };
    // refused before any work when not even the first trial and one
    // Jacobian (a simulation per free parameter) fit in the budget
    work(fit_problem.per_simulation() * (fit_problem.free.len() as u64 + 2))?;
    // Levenberg–Marquardt ([`crate::numeric::levenberg_marquardt_lazy`]):
    // a trial costs one simulation, the Jacobian (forward differences, one
    // simulation per free parameter) only where a trial is accepted. J is
    // held (its row of the normal equations is the identity) when no
    // torque is given; steps are limited to ±1 in the logarithm.
    let normal = |v: &Vector4<f64>| fit_problem.normal(v);
    let cost = |v: &Vector4<f64>| fit_problem.residuals(&(*v).into()).map(|r| sq(&r));
    let opts = LmOptions {
        lambda: 1e-3,
        max_iterations: 600,
        step_tol: 1e-12,
        cost_drop_rel: 1e-15,
        max_step: 1.0,
        diag_floor: 1e-12,
        ..LmOptions::default()
    };
    let start = Vector4::new(
        initial.j.ln(),
        initial.c.ln(),
        initial.kvp.ln(),
        initial.kpp.ln(),
    );
    let fit = levenberg_marquardt_lazy(start, cost, normal, |v| v, &opts).map_err(|e| match e {
        IdentifyError::Servo(s) => IdentifyError::FitDiverged {
            initial: [initial.j, initial.c, initial.kvp, initial.kpp],
            why: trial_error(&s),
        },
        e => e,
    })?;
    let p: [f64; 4] = fit.p.into();
    let iterations = fit.steps;
    let r = fit_problem.residuals(&p)?;
    let axis = with(initial, &p);
    let n = trace.command.len();
    let rms_position = rms(r[..n].iter().map(|x| x * lag));
    let rms_torque = tq.map_or(0.0, |(_, s)| rms(r[n..].iter().map(|x| x * s)));
    Ok(Identified {
        axis,
        j_identified: tq.is_some(),
        rms_position,
        rms_torque,
        iterations,
    })
}

/// What a trial step of the fit ran into, in words. A trial past a
/// parameter's range is said as such: its value printed with 6 digits
/// (1e4 + 1e-9 as "10000") looked inside the range it was refused for.
fn trial_error(e: &ServoError) -> String {
    match e {
        ServoError::BadParameter {
            field, expected, ..
        } => format!("took `{field}` out of its range ({expected})"),
        other => format!("gave {other}"),
    }
}

/// The initial guess' J, C, Kvp and Kpp must be > 0: the fit works on their logarithms.
fn check_initial(initial: &AxisParams) -> Result<(), IdentifyError> {
    initial.validate()?;
    for (f, v) in [
        ("j", initial.j),
        ("c", initial.c),
        ("kvp", initial.kvp),
        ("kpp", initial.kpp),
    ] {
        if !(v.is_finite() && v > 0.0) {
            return Err(bad(
                format!("initial.{f}"),
                format!("{v}: the initial guess must be > 0 (the fit works on its logarithm)"),
            ));
        }
    }
    Ok(())
}

/// `Ok` while `simulated` samples are within the identification's work
/// budget.
fn work(simulated: u64) -> Result<(), crate::budget::BudgetError> {
    crate::budget::check(
        "the fit's simulations",
        simulated,
        crate::budget::MAX_IDENTIFY_SAMPLES,
        "samples (trace samples × simulations, twice with a torque trace)",
        "give a shorter trace (a few seconds of a step or a ramp identify the axis) or an initial guess nearer the axis",
    )
}

/// Sum of squares.
fn sq(r: &[f64]) -> f64 {
    r.iter().map(|x| x * x).sum::<f64>()
}

/// The least-squares problem: parameters are ln J, ln C, ln Kvp, ln Kpp;
/// residuals are the position error scaled by the RMS following error
/// `lag`, then (with a torque trace) the torque error scaled by its RMS.
struct Problem<'a> {
    initial: &'a AxisParams,
    trace: &'a MeasuredTrace,
    lag: f64,
    tq: Option<(&'a Vec<f64>, f64)>,
    /// The parameters fitted (J only with a torque trace).
    free: Vec<usize>,
    /// Samples simulated so far ([`crate::budget::MAX_IDENTIFY_SAMPLES`]).
    simulated: std::cell::Cell<u64>,
}

impl Problem<'_> {
    /// What one simulation costs against the budget: the trace's samples,
    /// twice with a torque trace (its residuals and Jacobian columns are
    /// twice as long: a 2.67 M-sample trace with torque took 10.5 s to
    /// reach 30 M samples counted once, one without torque 5.8 s).
    fn per_simulation(&self) -> u64 {
        self.trace.command.len() as u64 * if self.tq.is_some() { 2 } else { 1 }
    }

    fn residuals(&self, p: &[f64; 4]) -> Result<Vec<f64>, IdentifyError> {
        let total = self.simulated.get() + self.per_simulation();
        work(total)?;
        self.simulated.set(total);
        let a = with(self.initial, p);
        let r = simulate_axis(&a, self.trace.dt, &self.trace.command)?;
        let mut out: Vec<f64> = r
            .position
            .iter()
            .zip(&self.trace.position)
            .map(|(s, m)| (s - m) / self.lag)
            .collect();
        if let Some((t, s)) = self.tq {
            out.extend(r.torque.iter().zip(t).map(|(a, b)| (a - b) / s));
        }
        Ok(out)
    }

    /// Normal equations JᵀJ, Jᵀr at `v` (forward differences, step 1e-6 in
    /// the logarithm); a held parameter's row is the identity.
    fn normal(&self, v: &Vector4<f64>) -> Result<Normal<4>, IdentifyError> {
        let p: [f64; 4] = (*v).into();
        let r = self.residuals(&p)?;
        let h = 1e-6;
        let mut cols: Vec<(usize, Vec<f64>)> = Vec::with_capacity(self.free.len());
        for &i in &self.free {
            let mut q = p;
            q[i] += h;
            let rq = self.residuals(&q)?;
            cols.push((i, rq.iter().zip(&r).map(|(a, b)| (a - b) / h).collect()));
        }
        let (mut jtj, mut jtr) = (Matrix4::zeros(), Vector4::zeros());
        for i in 0..4 {
            if !self.free.contains(&i) {
                jtj[(i, i)] = 1.0;
            }
        }
        for (i, ci) in &cols {
            for (k, ck) in &cols {
                jtj[(*i, *k)] = ci.iter().zip(ck).map(|(x, y)| x * y).sum();
            }
            jtr[*i] = ci.iter().zip(&r).map(|(x, y)| x * y).sum();
        }
        Ok(Normal {
            jtj,
            jtr,
            cost: sq(&r),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The running budget: each simulation of the fit adds the trace's
    /// samples, and the one that would pass the limit is refused by name.
    #[test]
    fn the_fits_simulations_are_counted_against_the_budget() {
        let a = crate::machine::preset("nmv5000").unwrap().axes["x"].clone();
        let command: Vec<f64> = (0..20).map(|i| i as f64 * 1e-3).collect();
        let position = command.iter().map(|c| c - 1e-4).collect();
        let trace = MeasuredTrace {
            dt: 1e-3,
            command,
            position,
            torque: None,
        };
        let limit = crate::budget::MAX_IDENTIFY_SAMPLES as u64;
        let p = [a.j.ln(), a.c.ln(), a.kvp.ln(), a.kpp.ln()];
        let torque = vec![1.0; 20];
        // a torque trace counts each simulation twice (40 here)
        for (tq, per) in [(None, 20), (Some((&torque, 1.0)), 40)] {
            let problem = |done: u64| Problem {
                initial: &a,
                trace: &trace,
                lag: 1e-4,
                tq,
                free: vec![1, 2, 3],
                simulated: std::cell::Cell::new(done),
            };
            let at = problem(limit - per);
            assert_eq!(at.residuals(&p).unwrap().len() as u64, per);
            assert_eq!(at.simulated.get(), limit);
            let over = problem(limit - per + 1);
            match over.residuals(&p) {
                Err(IdentifyError::Budget(b)) => assert_eq!(b.amount, limit + 1),
                other => panic!("{other:?}"),
            }
            assert_eq!(over.simulated.get(), limit - per + 1);
        }
    }
}
