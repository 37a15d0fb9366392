//! Forward kinematics of a chain with geometric errors (thasana Eqs. 1, 2,
//! 8): `r_w = T(q)·r_e`, and the tool axis `k_w = R(q)·k_e`.
//!
//! [`Model::new`] compiles a [`Chain`] and its [`GeometricErrors`] once:
//! every constant factor (fixed transforms, location errors `E`, `E⁻¹`,
//! constant component errors) between two joints is multiplied out, so an
//! evaluation is one rigid transform per joint plus one rotation or
//! translation about a principal direction per joint. Position-dependent
//! component errors stay as factors evaluated at `q`.
//!
//! The tool tip is the chain's `toolPoint` moved by `toolLength` against the
//! tool axis (from the spindle towards the tip).
//!
//! Units: joint vector `q = [x, y, z, a, b, c]` in mm and rad; pose in mm and
//! a unit vector.

use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

use super::chain::{Chain, JointKind};
use super::errors::{AxisErrors, GeometricErrors};
use super::htm::{error_matrix_exact, rot_xyz, Affine, Dir};
use super::KinematicsError;

/// Tool tip and tool axis relative to the workpiece.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Pose {
    /// Tool tip, mm.
    pub position: [f64; 3],
    /// Tool axis `[i, j, k]`, unit, from the tip towards the spindle.
    pub orientation: [f64; 3],
}

#[derive(Debug, Clone)]
enum Op {
    Const(Affine),
    Shift(Vector3<f64>),
    Linear {
        q: usize,
        dir: Dir,
        sign: f64,
        zero: f64,
    },
    Rotary {
        q: usize,
        dir: Dir,
        sign: f64,
        zero: f64,
    },
    Component {
        q: usize,
        errors: Box<AxisErrors>,
    },
}

/// A compiled chain with its errors, ready for fast evaluation.
#[derive(Debug, Clone)]
pub struct Model {
    ops: Vec<Op>,
    tip: Vector3<f64>,
    axis: Vector3<f64>,
}

fn push_const(ops: &mut Vec<Op>, a: Affine) {
    if a.is_translation() {
        if a.t != Vector3::zeros() {
            ops.push(Op::Shift(a.t));
        }
    } else {
        ops.push(Op::Const(a));
    }
}

impl Model {
    /// Compiles `chain` with `errors` and a tool length (mm).
    ///
    /// # Units
    /// `tool_length` in mm; errors in mm and rad.
    ///
    /// # Examples
    /// ```
    /// use mtmotion::kinematics::{Model, GeometricErrors};
    /// let chain = mtmotion::machine::preset("table-on-table-bc").unwrap().kinematics.unwrap();
    /// let m = Model::new(&chain, &GeometricErrors::default(), 0.0).unwrap();
    /// let p = m.pose(&[10.0, 20.0, 30.0, 0.0, 0.0, 0.0]);
    /// assert!((p.position[0] - 10.0).abs() < 1e-12 && (p.orientation[2] - 1.0).abs() < 1e-15);
    /// ```
    pub fn new(
        chain: &Chain,
        errors: &GeometricErrors,
        tool_length: f64,
    ) -> Result<Self, KinematicsError> {
        chain.validate()?;
        if !tool_length.is_finite() {
            return Err(KinematicsError::BadInput {
                field: "toolLength".into(),
                why: "must be a finite length in mm".into(),
            });
        }
        let per_axis = errors.resolve(chain)?;
        let mut ops = Vec::new();
        let mut cur = Affine::identity();
        for link in &chain.links {
            let fixed = Affine {
                r: rot_xyz(link.rotation),
                t: Vector3::from(link.translation),
            };
            cur = cur.then(&fixed);
            let Some(j) = &link.joint else { continue };
            let q = Chain::axis_index(&j.axis).unwrap_or(0);
            let ae = &per_axis[q];
            let e = error_matrix_exact(&ae.location);
            cur = cur.then(&e);
            push_const(&mut ops, cur);
            ops.push(match j.kind {
                JointKind::Linear => Op::Linear {
                    q,
                    dir: j.dir,
                    sign: j.sign,
                    zero: ae.zero,
                },
                JointKind::Rotary => Op::Rotary {
                    q,
                    dir: j.dir,
                    sign: j.sign,
                    zero: ae.zero,
                },
            });
            cur = e.inverse();
            if ae.component_is_constant() {
                cur = cur.then(&error_matrix_exact(&ae.component_at(0.0)));
            } else {
                push_const(&mut ops, cur);
                ops.push(Op::Component {
                    q,
                    errors: Box::new(ae.clone()),
                });
                cur = Affine::identity();
            }
        }
        cur = cur.then(&error_matrix_exact(&errors.tool));
        let axis = Vector3::from(chain.tool_axis);
        let tip = Vector3::from(chain.tool_point) - axis * tool_length;
        Ok(Self {
            tip: cur.point(&tip),
            axis: cur.r * axis,
            ops,
        })
    }

    /// The pose at joint vector `q = [x, y, z, a, b, c]` (mm, rad); axes
    /// the chain does not have are ignored.
    ///
    /// # Units
    /// `q`: mm and rad. Result: mm and a unit vector.
    pub fn pose(&self, q: &[f64; 6]) -> Pose {
        let (p, k) = self.eval(q);
        Pose {
            position: [p.x, p.y, p.z],
            orientation: [k.x, k.y, k.z],
        }
    }

    /// Tip and axis as vectors.
    #[inline]
    pub fn eval(&self, q: &[f64; 6]) -> (Vector3<f64>, Vector3<f64>) {
        let mut p = self.tip;
        let mut k = self.axis;
        for op in self.ops.iter().rev() {
            match op {
                Op::Shift(t) => p += t,
                Op::Const(a) => {
                    p = a.r * p + a.t;
                    k = a.r * k;
                }
                Op::Linear {
                    q: i,
                    dir,
                    sign,
                    zero,
                } => p[dir.index()] += sign * (q[*i] + zero),
                Op::Rotary {
                    q: i,
                    dir,
                    sign,
                    zero,
                } => {
                    let (s, c) = (sign * (q[*i] + zero)).sin_cos();
                    rotate(&mut p, *dir, s, c);
                    rotate(&mut k, *dir, s, c);
                }
                Op::Component { q: i, errors } => {
                    let a = error_matrix_exact(&errors.component_at(q[*i]));
                    p = a.r * p + a.t;
                    k = a.r * k;
                }
            }
        }
        (p, k)
    }
}

impl Model {
    /// Bulk evaluation: `q` holds `n × 6` axis values with the rotary axes
    /// in **degrees** (the JS convention); returns flat `n × 3` positions
    /// and orientations.
    ///
    /// # Units
    /// mm and degrees in, mm and unit vectors out.
    ///
    /// # Examples
    /// ```
    /// use mtmotion::kinematics::{Model, GeometricErrors};
    /// let chain = mtmotion::machine::preset("trunnion-ac").unwrap().kinematics.unwrap();
    /// let m = Model::new(&chain, &GeometricErrors::default(), 0.0).unwrap();
    /// let (p, k) = m.eval_bulk_degrees(&[10.0, 0.0, 0.0, 0.0, 0.0, 90.0]).unwrap();
    /// assert!((p[1] - 10.0).abs() < 1e-12 && (k[2] - 1.0).abs() < 1e-15);
    /// assert!(m.eval_bulk_degrees(&[1.0; 7]).is_err());
    /// ```
    pub fn eval_bulk_degrees(&self, q: &[f64]) -> Result<(Vec<f64>, Vec<f64>), KinematicsError> {
        if q.len() % 6 != 0 {
            return Err(KinematicsError::BadInput {
                field: "q".into(),
                why: format!(
                    "must hold 6 values (x, y, z, a, b, c) per point; got {} values",
                    q.len()
                ),
            });
        }
        if let Some(i) = q.iter().position(|v| !v.is_finite()) {
            return Err(KinematicsError::BadInput {
                field: format!("q[{i}]"),
                why: format!(
                    "axis {} of point {} is {}: must be a finite number",
                    super::AXES[i % 6],
                    i / 6,
                    crate::numeric::compact(q[i])
                ),
            });
        }
        let n = q.len() / 6;
        let mut pos = Vec::with_capacity(3 * n);
        let mut ori = Vec::with_capacity(3 * n);
        let k = std::f64::consts::PI / 180.0;
        for c in q.chunks_exact(6) {
            let qq = [c[0], c[1], c[2], c[3] * k, c[4] * k, c[5] * k];
            let (p, o) = self.eval(&qq);
            pos.extend_from_slice(p.as_slice());
            ori.extend_from_slice(o.as_slice());
        }
        if let Some(i) = pos.iter().chain(&ori).position(|v| !v.is_finite()) {
            return Err(KinematicsError::BadInput {
                field: "q".into(),
                why: format!(
                    "point {} gives a non-finite pose: the axis values are too large for the error model",
                    (i % (3 * n)) / 3
                ),
            });
        }
        Ok((pos, ori))
    }
}

#[inline(always)]
fn rotate(v: &mut Vector3<f64>, dir: Dir, s: f64, c: f64) {
    let (x, y, z) = (v.x, v.y, v.z);
    match dir {
        Dir::X => {
            v.y = c * y - s * z;
            v.z = s * y + c * z;
        }
        Dir::Y => {
            v.x = c * x + s * z;
            v.z = -s * x + c * z;
        }
        Dir::Z => {
            v.x = c * x - s * y;
            v.y = s * x + c * y;
        }
    }
}

/// Forward kinematics in one call: the pose of `chain` at `q` with `errors`.
///
/// # Units
/// `q = [x, y, z, a, b, c]` in mm and rad; `tool_length` mm.
///
/// # Examples
/// ```
/// use mtmotion::kinematics::{forward, GeometricErrors};
/// let chain = mtmotion::machine::preset("trunnion-ac").unwrap().kinematics.unwrap();
/// let mut e = GeometricErrors::default();
/// e.location.insert("EC0C".into(), 1e-3); // zero-position error of C
/// let p0 = forward(&chain, &[50.0, 0.0, 0.0, 0.0, 0.0, 0.0], &GeometricErrors::default(), 0.0).unwrap();
/// let p1 = forward(&chain, &[50.0, 0.0, 0.0, 0.0, 0.0, 0.0], &e, 0.0).unwrap();
/// // a C rotation of 1 mrad moves a point 50 mm from the C axis by 50 µm in y
/// assert!((p1.position[1] - p0.position[1] - 50.0 * 1e-3f64.sin()).abs() < 1e-12);
/// ```
pub fn forward(
    chain: &Chain,
    q: &[f64; 6],
    errors: &GeometricErrors,
    tool_length: f64,
) -> Result<Pose, KinematicsError> {
    Ok(Model::new(chain, errors, tool_length)?.pose(q))
}
