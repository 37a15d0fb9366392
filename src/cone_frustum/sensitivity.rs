//! Sensitivity coefficients of the ball-bar reading along the cone-frustum
//! path (kato §1, §3: "the sensitivity coefficient of each axis").
//!
//! Reading chosen: the sensitivity of the bar to axis `j` is the change of
//! the bar length per unit error of that axis' position,
//! `S_j = n·∂p/∂q_j` (mm/mm for linear, mm/rad for rotary axes), with `n`
//! the unit bar direction and `p` the spindle-ball centre relative to the
//! workpiece. The sensitivity to a geometric error `e` (an ISO 230 location
//! error) is `S_e = n·∂p/∂e` (mm/mm or mm/rad). Both are central differences
//! of the exact forward kinematics (step 1e-6 mm or rad; truncation below
//! 1e-9 relative), checked against the first-order propagation in the
//! tests.
//!
//! Units: mm per mm, mm per rad.

use nalgebra::Vector3;

use crate::kinematics::{Chain, GeometricErrors, KinematicsError, Model};

const H: f64 = 1e-6;

/// `n·∂p/∂q_j` for each index in `axes`.
pub fn axes(model: &Model, q: &[f64; 6], bar: &Vector3<f64>, axes: &[usize]) -> Vec<f64> {
    axes.iter()
        .map(|&j| {
            let mut qp = *q;
            let mut qm = *q;
            qp[j] += H;
            qm[j] -= H;
            bar.dot(&(model.eval(&qp).0 - model.eval(&qm).0)) / (2.0 * H)
        })
        .collect()
}

/// Models with `±1e-6` of the error `symbol` added to `base`.
pub fn perturbed(
    chain: &Chain,
    base: &GeometricErrors,
    tool_length: f64,
    symbol: &str,
) -> Result<(Model, Model), KinematicsError> {
    let mk = |h: f64| {
        let mut e = base.clone();
        *e.location.entry(symbol.to_string()).or_insert(0.0) += h;
        Model::new(chain, &e, tool_length)
    };
    Ok((mk(H)?, mk(-H)?))
}

/// `n·∂p/∂e` from the two perturbed models.
pub fn error(models: &(Model, Model), q: &[f64; 6], bar: &Vector3<f64>) -> f64 {
    bar.dot(&(models.0.eval(q).0 - models.1.eval(q).0)) / (2.0 * H)
}
