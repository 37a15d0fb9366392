//! Closed-form inverse kinematics of a nominal (error-free) 5-axis chain,
//! every branch.
//!
//! The rotation of the chain is `R = F0·Rot(u1, θ1)·F1·Rot(u2, θ2)·F2`
//! (fixed rotations `F`, rotary joints in chain order). The tool axis fixes
//! `θ1, θ2` through Paden–Kahan subproblem 2 (two solutions, `γ = ±`), each
//! angle by subproblem 1. With the rotary angles known the tool tip is
//! affine in the linear axes, so a 3×3 linear solve gives `x, y, z` exactly.
//! Each rotary angle is then repeated every 360° inside the axis limits.
//!
//! Reading chosen at a singular pose (tool axis parallel to the first rotary
//! axis, e.g. B = 0 on a B–C table): the first rotary angle is free; the
//! branch keeps it at 0 and is marked `singular`.
//!
//! Units: mm, rad (limits in mm and rad here; the JS API converts degrees).

use std::f64::consts::TAU;

use nalgebra::{Matrix3, Vector3};
use serde::{Deserialize, Serialize};

use super::chain::{Chain, JointKind};
use super::errors::GeometricErrors;
use super::forward::{Model, Pose};
use super::htm::rot_xyz;
use super::KinematicsError;

/// Axis limits `[min, max]` per axis in [`super::AXES`] order (mm, rad).
pub type Limits = [[f64; 2]; 6];

/// No limits.
pub const NO_LIMITS: Limits = [[f64::NEG_INFINITY, f64::INFINITY]; 6];

/// One inverse-kinematics branch.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct Solution {
    /// `[x, y, z, a, b, c]`, mm and rad (axes the chain lacks are 0).
    pub q: [f64; 6],
    /// All axes inside their limits.
    pub within_limits: bool,
    /// The first rotary angle is undetermined (kept at 0).
    pub singular: bool,
}

/// Limits from a machine's `limits` map (mm, degrees) to mm/rad.
pub fn limits_from_degrees(map: &std::collections::BTreeMap<String, [f64; 2]>) -> Limits {
    let mut l = NO_LIMITS;
    for (i, a) in super::AXES.iter().enumerate() {
        if let Some(r) = map.get(*a) {
            l[i] = if i >= 3 {
                [r[0].to_radians(), r[1].to_radians()]
            } else {
                *r
            };
        }
    }
    l
}

fn sp1(w: &Vector3<f64>, a: &Vector3<f64>, b: &Vector3<f64>) -> f64 {
    let ap = a - w * w.dot(a);
    let bp = b - w * w.dot(b);
    w.dot(&ap.cross(&bp)).atan2(ap.dot(&bp))
}

use crate::numeric::wrap_angle as wrap;

/// Every inverse-kinematics branch of the nominal `chain` for `pose`.
///
/// # Units
/// Pose in mm and a unit vector (normalised here); `tool_length` in mm;
/// limits and result in mm and rad.
///
/// # Examples
/// ```
/// use mtmotion::kinematics::{forward, inverse, GeometricErrors, inverse::NO_LIMITS};
/// let chain = mtmotion::machine::preset("table-on-table-bc").unwrap().kinematics.unwrap();
/// let q = [12.0, -5.0, 30.0, 0.0, 0.4, -1.0];
/// let pose = forward(&chain, &q, &GeometricErrors::default(), 0.0).unwrap();
/// let sols = inverse(&chain, &pose, 0.0, &NO_LIMITS).unwrap();
/// assert!(sols.iter().any(|s| s.q.iter().zip(&q).all(|(a, b)| (a - b).abs() < 1e-9)));
/// ```
pub fn inverse(
    chain: &Chain,
    pose: &Pose,
    tool_length: f64,
    limits: &Limits,
) -> Result<Vec<Solution>, KinematicsError> {
    Inverse::new(chain, tool_length)?.solve(pose, limits)
}

/// A chain prepared for repeated inverse kinematics (the nominal model and
/// the rotation structure are built once).
#[derive(Debug, Clone)]
pub struct Inverse {
    model: Model,
    f: Vec<Matrix3<f64>>,
    rot: Vec<(usize, Vector3<f64>, f64)>,
    lin: Vec<usize>,
    t: Vector3<f64>,
}

impl Inverse {
    /// Prepares `chain` (errors are ignored: the nominal machine).
    pub fn new(chain: &Chain, tool_length: f64) -> Result<Self, KinematicsError> {
        let model = Model::new(chain, &GeometricErrors::default(), tool_length)?;
        let mut f = vec![Matrix3::identity()];
        let mut rot = Vec::new(); // (q index, unit dir, sign)
        let mut lin = Vec::new();
        for l in &chain.links {
            let last = f.len() - 1;
            f[last] *= rot_xyz(l.rotation);
            if let Some(j) = &l.joint {
                let qi = Chain::axis_index(&j.axis).unwrap_or(0);
                match j.kind {
                    JointKind::Rotary => {
                        rot.push((qi, j.dir.unit(), j.sign));
                        f.push(Matrix3::identity());
                    }
                    JointKind::Linear => lin.push(qi),
                }
            }
        }
        Ok(Self {
            model,
            f,
            rot,
            lin,
            t: Vector3::from(chain.tool_axis),
        })
    }

    /// Every branch for `pose` (see [`inverse`]).
    pub fn solve(&self, pose: &Pose, limits: &Limits) -> Result<Vec<Solution>, KinematicsError> {
        let k = Vector3::from(pose.orientation);
        let kn = k.norm();
        if !(kn.is_finite() && kn > 1e-12 && pose.position.iter().all(|v| v.is_finite())) {
            return Err(KinematicsError::BadInput {
                field: "pose".into(),
                why: "needs a finite position and a non-zero orientation vector".into(),
            });
        }
        let angle_sets = self.rotary_angles(&(k / kn))?;
        let target = Vector3::from(pose.position);
        let mut out = Vec::new();
        for (angles, singular) in angle_sets {
            let mut q = [0.0; 6];
            for ((qi, _, sign), th) in self.rot.iter().zip(&angles) {
                q[*qi] = wrap(th * sign);
            }
            let sol = self.linear_axes(&q, &target)?;
            for (col, qi) in self.lin.iter().enumerate().take(3) {
                q[*qi] = sol[col];
            }
            for c in periodic_copies(q, &self.rot, limits) {
                let within = c
                    .iter()
                    .zip(limits)
                    .all(|(v, l)| *v >= l[0] - 1e-12 && *v <= l[1] + 1e-12);
                out.push(Solution {
                    q: c,
                    within_limits: within,
                    singular,
                });
            }
        }
        // Keep principal copies outside limits only when no copy fits.
        let any_within = out.iter().any(|s| s.within_limits);
        if any_within {
            out.retain(|s| s.within_limits);
        }
        out.dedup_by(|a, b| a.q.iter().zip(&b.q).all(|(x, y)| (x - y).abs() < 1e-12));
        Ok(out)
    }

    /// The rotary-axis angle sets (before sign and wrap) that point the tool
    /// along the unit vector `k`, each with its singular flag.
    fn rotary_angles(&self, k: &Vector3<f64>) -> Result<Vec<(Vec<f64>, bool)>, KinematicsError> {
        let (f, rot, t, k) = (&self.f, &self.rot, self.t, *k);
        let mut angle_sets: Vec<(Vec<f64>, bool)> = Vec::new();
        let unreachable = || {
            KinematicsError::Unreachable(
                "this tool orientation is outside what the rotary axes can reach".into(),
            )
        };
        match rot.len() {
            0 => {
                if (f[0] * t - k).norm() > 1e-9 {
                    return Err(unreachable());
                }
                angle_sets.push((vec![], false));
            }
            1 => {
                let w = rot[0].1;
                let kp = f[0].transpose() * k;
                let p = f[1] * t;
                if (w.dot(&kp) - w.dot(&p)).abs() > 1e-9 {
                    return Err(unreachable());
                }
                let singular = w.cross(&p).norm() < 1e-12;
                angle_sets.push((
                    vec![if singular { 0.0 } else { sp1(&w, &p, &kp) }],
                    singular,
                ));
            }
            _ => {
                let w1 = rot[0].1;
                let w2 = f[1] * rot[1].1;
                let p = f[1] * f[2] * t;
                let kp = f[0].transpose() * k;
                let c12 = w1.dot(&w2);
                let cr = w1.cross(&w2);
                if cr.norm() < 1e-9 {
                    return Err(KinematicsError::BadChain {
                        field: "links".into(),
                        why: "the two rotary axes are parallel; inverse kinematics needs non-parallel axes".into(),
                    });
                }
                if w1.cross(&kp).norm() < 1e-12 {
                    // Tool axis along the first rotary axis: θ1 is free.
                    if (w2.dot(&p) - w2.dot(&kp)).abs() > 1e-9 {
                        return Err(unreachable());
                    }
                    angle_sets.push((vec![0.0, sp1(&w2, &p, &kp)], true));
                } else {
                    let den = c12 * c12 - 1.0;
                    let alpha = (c12 * w2.dot(&p) - w1.dot(&kp)) / den;
                    let beta = (c12 * w1.dot(&kp) - w2.dot(&p)) / den;
                    let g2 =
                        (p.norm_squared() - alpha * alpha - beta * beta - 2.0 * alpha * beta * c12)
                            / cr.norm_squared();
                    if g2 < -1e-12 {
                        return Err(unreachable());
                    }
                    let g = g2.max(0.0).sqrt();
                    let gammas: &[f64] = if g < 1e-12 { &[0.0] } else { &[g, -g] };
                    for gm in gammas {
                        let c = w1 * alpha + w2 * beta + cr * *gm;
                        angle_sets.push((vec![sp1(&w1, &c, &kp), sp1(&w2, &p, &c)], false));
                    }
                }
            }
        }
        Ok(angle_sets)
    }

    /// The linear-axis positions that put the tool tip on `target` with the
    /// rotary axes of `q` (the position is affine in the linear axes).
    fn linear_axes(
        &self,
        q: &[f64; 6],
        target: &Vector3<f64>,
    ) -> Result<Vector3<f64>, KinematicsError> {
        let (model, lin, q) = (&self.model, &self.lin, *q);
        let (p0, _) = model.eval(&q);
        let mut jac = Matrix3::zeros();
        for (col, qi) in lin.iter().enumerate().take(3) {
            let mut qe = q;
            qe[*qi] = 1.0;
            let (pe, _) = model.eval(&qe);
            jac.set_column(col, &(pe - p0));
        }
        let rhs = target - p0;
        let sol = if lin.len() == 3 {
            jac.lu()
                .solve(&rhs)
                .ok_or_else(|| KinematicsError::BadChain {
                    field: "links".into(),
                    why: "the linear axes are not independent".into(),
                })?
        } else {
            let svd = jac.svd(true, true);
            let s = svd
                .solve(&rhs, 1e-12)
                .map_err(|e| KinematicsError::Unreachable(e.to_string()))?;
            if (jac * s - rhs).norm() > 1e-9 {
                return Err(KinematicsError::Unreachable(
                    "the position needs a linear axis this machine does not have".into(),
                ));
            }
            s
        };
        Ok(sol)
    }
}

/// `q` and the copies of it whose rotary angles differ by whole turns and
/// stay inside `limits` (up to ±3 turns; the principal copy is always kept).
fn periodic_copies(
    q: [f64; 6],
    rot: &[(usize, Vector3<f64>, f64)],
    limits: &Limits,
) -> Vec<[f64; 6]> {
    let mut copies = vec![q];
    for (qi, _, _) in rot {
        let mut next = Vec::new();
        for base in &copies {
            for turn in -3..=3 {
                let mut c = *base;
                c[*qi] = base[*qi] + turn as f64 * TAU;
                if turn == 0 || (c[*qi] >= limits[*qi][0] && c[*qi] <= limits[*qi][1]) {
                    next.push(c);
                }
            }
        }
        copies = next;
    }
    copies
}
