//! Levenberg–Marquardt least squares (K. Levenberg 1944; D. W. Marquardt
//! 1963): the one damped Gauss–Newton driver of the crate, used by the
//! geometric circle fit (ball bar, ISO 230-4) and the identification of
//! tA and T from radius losses (qiu-toolpath-error-reverse-compensation
//! Eq. 3).
//!
//! The caller supplies the normal equations at a point, `JᵀJ`, `Jᵀr` and the
//! cost `Σ r²`, in one evaluation. A model with many residuals (a million
//! ball-bar points) accumulates them in one pass without storing `J`.
//!
//! Each step solves `(JᵀJ + λ·diag(JᵀJ)) δ = −Jᵀr` (Marquardt's scaling, so
//! the step does not depend on the parameters' units). A trial point whose
//! cost is not larger is accepted and λ divided by 10; otherwise it is
//! undone and λ multiplied by 10. It stops when the gradient, the step or
//! the cost drop falls below its tolerance, when λ exceeds `lambda_max`, or
//! after `max_iterations` trials.
//!
//! Units: whatever the model's parameters and residuals are.

use nalgebra::{SMatrix, SVector};

/// The normal equations of a least-squares model at one point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Normal<const N: usize> {
    /// `JᵀJ`.
    pub jtj: SMatrix<f64, N, N>,
    /// `Jᵀr`: half the gradient of the cost.
    pub jtr: SVector<f64, N>,
    /// `Σ r²`.
    pub cost: f64,
}

/// Tolerances and limits.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LmOptions {
    /// Initial damping λ.
    pub lambda: f64,
    /// Smallest damping after a success.
    pub lambda_min: f64,
    /// Give up when the damping grows past this (no descent direction left).
    pub lambda_max: f64,
    /// Most trial points evaluated.
    pub max_iterations: usize,
    /// Stop when `|Jᵀr| ≤ gradient_tol`.
    pub gradient_tol: f64,
    /// Stop when `|δ| < step_tol · (1 + |p|)`.
    pub step_tol: f64,
    /// Stop when an accepted step lowers the cost by at most this.
    pub cost_drop_tol: f64,
    /// … or by at most this fraction of the cost.
    pub cost_drop_rel: f64,
    /// Largest change of any one parameter in a step (a trust region for
    /// models that are far from linear, e.g. parameters on a log scale).
    pub max_step: f64,
    /// Damping floor: the diagonal is damped by `λ·max(JᵀJ_kk, floor)`, so
    /// a parameter the data does not see still gets a finite step.
    pub diag_floor: f64,
}

impl Default for LmOptions {
    /// λ from 1e-6 in [1e-12, 1e12], 200 trials, gradient and cost-drop
    /// tolerances 0 (off), a step tolerance of 1e-15 (rounding), no step
    /// limit and no damping floor.
    fn default() -> Self {
        LmOptions {
            lambda: 1e-6,
            lambda_min: 1e-12,
            lambda_max: 1e12,
            max_iterations: 200,
            gradient_tol: 0.0,
            step_tol: 1e-15,
            cost_drop_tol: 0.0,
            cost_drop_rel: 0.0,
            max_step: f64::INFINITY,
            diag_floor: 0.0,
        }
    }
}

/// The best point found and its normal equations.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LmResult<const N: usize> {
    /// Parameters.
    pub p: SVector<f64, N>,
    /// Normal equations at `p`.
    pub normal: Normal<N>,
    /// Accepted steps.
    pub steps: usize,
}

/// Minimises the cost of `normal` from `start`. `project` maps a trial
/// point into the feasible set (e.g. clamps a time constant at 0); pass
/// `|p| p` when the parameters are free.
///
/// # Examples
/// Fit `y = a·e^{b x}` to exact data; the answer is the generating (a, b).
/// ```
/// use mtmotion::numeric::{levenberg_marquardt, LmOptions, Normal};
/// use nalgebra::{SMatrix, SVector};
/// let xs: Vec<f64> = (0..20).map(|i| i as f64 * 0.1).collect();
/// let ys: Vec<f64> = xs.iter().map(|x| 2.0 * (-1.5 * x).exp()).collect();
/// let normal = |p: &SVector<f64, 2>| {
///     let (mut jtj, mut jtr, mut cost) = (SMatrix::<f64, 2, 2>::zeros(), SVector::<f64, 2>::zeros(), 0.0);
///     for (x, y) in xs.iter().zip(&ys) {
///         let e = (p[1] * x).exp();
///         let r = p[0] * e - y;
///         let j = SVector::<f64, 2>::new(e, p[0] * x * e);
///         jtj += j * j.transpose();
///         jtr += j * r;
///         cost += r * r;
///     }
///     Normal { jtj, jtr, cost }
/// };
/// let fit = levenberg_marquardt(SVector::<f64, 2>::new(1.0, 0.0), normal, |p| p, &LmOptions::default());
/// assert!((fit.p[0] - 2.0).abs() < 1e-10 && (fit.p[1] + 1.5).abs() < 1e-10);
/// ```
pub fn levenberg_marquardt<const N: usize>(
    start: SVector<f64, N>,
    mut normal: impl FnMut(&SVector<f64, N>) -> Normal<N>,
    project: impl Fn(SVector<f64, N>) -> SVector<f64, N>,
    opts: &LmOptions,
) -> LmResult<N> {
    let eval = |p: &SVector<f64, N>, _: bool| Ok::<_, std::convert::Infallible>((normal(p), true));
    match drive(start, eval, project, opts) {
        Ok(r) => r,
        Err(never) => match never {},
    }
}

/// As [`levenberg_marquardt`] for a model whose evaluation can fail and
/// whose normal equations cost much more than its cost (e.g. a Jacobian by
/// finite differences of a simulation): a trial point gets only `cost`;
/// `normal` is evaluated where a trial is accepted. A trial whose cost
/// fails is rejected like a worse one; a failure at `start` is returned.
pub fn levenberg_marquardt_lazy<const N: usize, E>(
    start: SVector<f64, N>,
    mut cost: impl FnMut(&SVector<f64, N>) -> Result<f64, E>,
    mut normal: impl FnMut(&SVector<f64, N>) -> Result<Normal<N>, E>,
    project: impl Fn(SVector<f64, N>) -> SVector<f64, N>,
    opts: &LmOptions,
) -> Result<LmResult<N>, E> {
    let eval = |p: &SVector<f64, N>, full: bool| {
        if full {
            normal(p).map(|n| (n, true))
        } else {
            cost(p).map(|c| {
                let n = Normal {
                    jtj: SMatrix::zeros(),
                    jtr: SVector::zeros(),
                    cost: c,
                };
                (n, false)
            })
        }
    };
    drive(start, eval, project, opts)
}

/// The one iteration, for both entry points. `eval(p, full)` returns the
/// normal equations at `p` (or only the cost when `full` is false) and
/// whether they are complete.
fn drive<const N: usize, E>(
    start: SVector<f64, N>,
    mut eval: impl FnMut(&SVector<f64, N>, bool) -> Result<(Normal<N>, bool), E>,
    project: impl Fn(SVector<f64, N>) -> SVector<f64, N>,
    opts: &LmOptions,
) -> Result<LmResult<N>, E> {
    let mut p = start;
    let mut at = eval(&p, true)?.0;
    let mut lambda = opts.lambda;
    let mut steps = 0;
    for _ in 0..opts.max_iterations {
        if at.jtr.norm() <= opts.gradient_tol {
            break;
        }
        let mut damped = at.jtj;
        for k in 0..N {
            let d = at.jtj[(k, k)];
            damped[(k, k)] = if d >= opts.diag_floor {
                d * (1.0 + lambda)
            } else {
                d + lambda * opts.diag_floor
            };
        }
        let Some(step) = damped.cholesky().map(|c| c.solve(&(-at.jtr))) else {
            lambda *= 10.0;
            if lambda > opts.lambda_max {
                break;
            }
            continue;
        };
        let step = step.map(|v| v.clamp(-opts.max_step, opts.max_step));
        if !step.iter().all(|v| v.is_finite()) || step.norm() < opts.step_tol * (1.0 + p.norm()) {
            break;
        }
        let q = project(p + step);
        let trial = match eval(&q, false) {
            Ok((n, complete)) if n.cost <= at.cost => Some((n, complete)),
            _ => None,
        };
        let Some((trial, complete)) = trial else {
            lambda *= 10.0;
            if lambda > opts.lambda_max {
                break;
            }
            continue;
        };
        let (before, drop) = (at.cost, at.cost - trial.cost);
        p = q;
        // A cost-only trial gets its normal equations once it is accepted.
        at = if complete { trial } else { eval(&p, true)?.0 };
        steps += 1;
        lambda = (lambda * 0.1).max(opts.lambda_min);
        if drop <= opts.cost_drop_tol || drop <= opts.cost_drop_rel * before {
            break;
        }
    }
    Ok(LmResult {
        p,
        normal: at,
        steps,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rosenbrock's valley as residuals (1 − x, 10 (y − x²)): minimum (1, 1).
    fn rosenbrock(p: &SVector<f64, 2>) -> Normal<2> {
        let r = SVector::<f64, 2>::new(1.0 - p[0], 10.0 * (p[1] - p[0] * p[0]));
        let j = SMatrix::<f64, 2, 2>::new(-1.0, 0.0, -20.0 * p[0], 10.0);
        Normal {
            jtj: j.transpose() * j,
            jtr: j.transpose() * r,
            cost: r.norm_squared(),
        }
    }

    #[test]
    fn finds_the_rosenbrock_minimum() {
        let fit = levenberg_marquardt(
            SVector::<f64, 2>::new(-1.2, 1.0),
            rosenbrock,
            |p| p,
            &LmOptions::default(),
        );
        assert!(
            (fit.p[0] - 1.0).abs() < 1e-9 && (fit.p[1] - 1.0).abs() < 1e-9,
            "{:?}",
            fit.p
        );
        assert!(fit.normal.cost < 1e-18);
    }

    #[test]
    fn projection_keeps_the_bound() {
        // Minimum of (p + 1)² over p ≥ 0 is at the bound 0.
        let normal = |p: &SVector<f64, 1>| Normal {
            jtj: SMatrix::<f64, 1, 1>::new(1.0),
            jtr: SVector::<f64, 1>::new(p[0] + 1.0),
            cost: (p[0] + 1.0).powi(2),
        };
        let fit = levenberg_marquardt(
            SVector::<f64, 1>::new(3.0),
            normal,
            |p| p.map(|v| v.max(0.0)),
            &LmOptions::default(),
        );
        assert_eq!(fit.p[0], 0.0);
    }

    #[test]
    fn never_accepts_a_worse_point() {
        // A cost that is NaN away from the start: the start is kept.
        let normal = |p: &SVector<f64, 1>| Normal {
            jtj: SMatrix::<f64, 1, 1>::new(1.0),
            jtr: SVector::<f64, 1>::new(1.0),
            cost: if p[0] == 0.0 { 1.0 } else { f64::NAN },
        };
        let fit = levenberg_marquardt(
            SVector::<f64, 1>::zeros(),
            normal,
            |p| p,
            &LmOptions::default(),
        );
        assert_eq!(fit.p[0], 0.0);
        assert_eq!(fit.normal.cost, 1.0);
    }
}
