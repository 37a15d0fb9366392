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

use crate::kinematics::errors::{symbol_name, Symbol};
use crate::kinematics::{Chain, GeometricErrors, JointKind, KinematicsError, Model};

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

/// The location errors a cone-frustum test can see: for each rotary axis
/// its two radial offsets and three angular errors (the own-axis angle is
/// the zero-position error); for the linear axes the squareness errors
/// `EC0Y`, `EB0Z`, `EA0Z`.
///
/// # Examples
/// ```
/// let chain = mtmotion::machine::preset("trunnion-ac").unwrap().kinematics.unwrap();
/// let s = mtmotion::cone_frustum::sensitivity::error_symbols(&chain);
/// assert!(s.contains(&"EX0C".to_string()) && s.contains(&"EY0A".to_string()));
/// assert!(!s.contains(&"EZ0C".to_string()) && !s.contains(&"EX0A".to_string()));
/// ```
pub fn error_symbols(chain: &Chain) -> Vec<String> {
    let mut out = Vec::new();
    for (_, j) in chain.joints() {
        if j.kind != JointKind::Rotary {
            continue;
        }
        let Some(axis) = Chain::axis_index(&j.axis) else {
            continue;
        };
        for d in 0..6 {
            if d == j.dir.index() {
                continue; // translation along its own axis: no effect
            }
            out.push(symbol_name(Symbol {
                d,
                axis,
                location: true,
            }));
        }
    }
    let present = chain.axes();
    for (sym, need) in [
        ("EC0Y", ["x", "y"]),
        ("EB0Z", ["x", "z"]),
        ("EA0Z", ["y", "z"]),
    ] {
        if need.iter().all(|a| present.contains(a)) {
            out.push(sym.to_string());
        }
    }
    out
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
