//! Inversion of the full error model by Newton (Gauss–Newton) iteration
//! (thasana §II-D: "compensating [the NC data] based on the shape generation
//! motion"): find joint values `q` whose *actual* pose, through the error
//! model, is the nominal pose.
//!
//! Residual `r(q) = [p(q) − p*, L·(k(q) − k*)]` with `L = 100 mm`, so that an
//! orientation error of 1 µrad weighs like 0.1 µm of position. Jacobian by
//! central differences (step 1e-6 mm or rad; truncation ~1e-12). The step
//! solves the least-squares problem by SVD, so redundant or missing axes do
//! not break it. Converged when the step is below 1e-11 (mm, rad).
//!
//! Units: mm, rad.

use nalgebra::{DMatrix, DVector, Vector3};

use super::forward::{Model, Pose};
use super::KinematicsError;

const LEVER: f64 = 100.0;

/// Joint values (mm, rad) that make `model` reach `target`, starting at
/// `q0` (usually the nominal command). `axes` are the indices of the joints
/// that may move; `context` names the point in errors.
///
/// # Units
/// mm and rad.
///
/// # Examples
/// ```
/// use mtmotion::kinematics::{forward, newton::solve, GeometricErrors, Model};
/// let chain = mtmotion::machine::preset("trunnion-ac").unwrap().kinematics.unwrap();
/// let q = [10.0, 20.0, 5.0, 0.3, 0.0, 0.7];
/// let target = forward(&chain, &q, &GeometricErrors::default(), 0.0).unwrap();
/// let mut e = GeometricErrors::default();
/// e.location.insert("EY0A".into(), 0.02);
/// e.location.insert("EB0C".into(), 1e-4);
/// let m = Model::new(&chain, &e, 0.0).unwrap();
/// let qc = solve(&m, &target, &q, &[0, 1, 2, 3, 5], "test").unwrap();
/// let got = m.pose(&qc);
/// assert!((0..3).all(|i| (got.position[i] - target.position[i]).abs() < 1e-9));
/// assert!((0..3).all(|i| (got.orientation[i] - target.orientation[i]).abs() < 1e-11));
/// ```
pub fn solve(
    model: &Model,
    target: &Pose,
    q0: &[f64; 6],
    axes: &[usize],
    context: &str,
) -> Result<[f64; 6], KinematicsError> {
    iterate(model, target, q0, axes, context, true)
}

/// As [`solve`], but for a subset of axes that cannot reach the pose
/// exactly (thasana's X, Y, A, B only): returns the least-squares joint
/// values (weights as in the module header) once the Gauss–Newton step
/// is below 1e-8 (mm, rad), whatever the remaining residual.
///
/// # Units
/// mm and rad.
pub fn solve_least_squares(
    model: &Model,
    target: &Pose,
    q0: &[f64; 6],
    axes: &[usize],
    context: &str,
) -> Result<[f64; 6], KinematicsError> {
    iterate(model, target, q0, axes, context, false)
}

fn iterate(
    model: &Model,
    target: &Pose,
    q0: &[f64; 6],
    axes: &[usize],
    context: &str,
    exact: bool,
) -> Result<[f64; 6], KinematicsError> {
    let pt = Vector3::from(target.position);
    let kt = Vector3::from(target.orientation).normalize();
    let resid = |q: &[f64; 6]| {
        let (p, k) = model.eval(q);
        let mut r = DVector::zeros(6);
        r.fixed_rows_mut::<3>(0).copy_from(&(p - pt));
        r.fixed_rows_mut::<3>(3).copy_from(&((k - kt) * LEVER));
        r
    };
    let mut q = *q0;
    let mut r = resid(&q);
    const H: f64 = 1e-6;
    for it in 0..30 {
        let mut jac = DMatrix::zeros(6, axes.len());
        for (c, &i) in axes.iter().enumerate() {
            let mut qp = q;
            let mut qm = q;
            qp[i] += H;
            qm[i] -= H;
            jac.set_column(c, &((resid(&qp) - resid(&qm)) / (2.0 * H)));
        }
        let step = jac
            .svd(true, true)
            .solve(&(-&r), 1e-12)
            .map_err(|e| KinematicsError::Unreachable(format!("{context}: {e}")))?;
        for (c, &i) in axes.iter().enumerate() {
            q[i] += step[c];
        }
        r = resid(&q);
        // with a residual left (least squares) the finite-difference
        // Jacobian's noise keeps the step near 1e-9: stop at 1e-8, far
        // below the program's 4-decimal resolution
        if step.amax() < if exact { 1e-11 } else { 1e-8 } {
            if exact && r.norm() > 1e-6 {
                return Err(KinematicsError::NoConvergence {
                    context: context.to_string(),
                    residual: r.norm(),
                    iterations: it + 1,
                });
            }
            return Ok(q);
        }
    }
    if r.norm() < 1e-9 {
        return Ok(q);
    }
    Err(KinematicsError::NoConvergence {
        context: context.to_string(),
        residual: r.norm(),
        iterations: 30,
    })
}
