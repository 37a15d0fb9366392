//! 4×4 homogeneous transforms of a machine chain (thasana-htm-nc-compensation
//! §II-B, Eqs. 1–3).
//!
//! - `A¹(d)`, `A²(d)`, `A³(d)`: translation by `d` along x, y, z; `A⁴(α)`,
//!   `A⁵(β)`, `A⁶(γ)`: rotation by an angle about x, y, z (Eq. 2's
//!   elementary matrices, right-handed).
//! - Eq. 3 is the *first-order* (infinitesimal) error matrix `E` with
//!   `δx, δy, δz, εx, εy, εz`. [`error_matrix_linear`] is Eq. 3 as printed;
//!   [`error_matrix_exact`] is the exact rigid transform
//!   `Trans(δ)·A⁴(εx)·A⁵(εy)·A⁶(εz)` that Eq. 3 linearises. The
//!   forward kinematics uses the exact form (so the error model stays a
//!   rigid-body motion for any size of error); the first-order propagation
//!   ([`super::propagation`]) is the independent small-error check.
//!
//! For speed the chain is evaluated with [`Affine`], a 3×3 rotation plus a
//! translation (the top three rows of the HTM); [`Affine::to_matrix4`]
//! gives the 4×4 HTM.
//!
//! Units: mm, rad.

use nalgebra::{Matrix3, Matrix4, Vector3};

/// Principal direction of a joint or elementary transform.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Dir {
    /// x.
    X,
    /// y.
    Y,
    /// z.
    Z,
}

impl Dir {
    /// Index 0, 1, 2.
    pub fn index(self) -> usize {
        match self {
            Dir::X => 0,
            Dir::Y => 1,
            Dir::Z => 2,
        }
    }
    /// Unit vector.
    pub fn unit(self) -> Vector3<f64> {
        let mut v = Vector3::zeros();
        v[self.index()] = 1.0;
        v
    }
}

/// Six error parameters of Eq. 3: `[δx, δy, δz, εx, εy, εz]`, mm and rad.
pub type Six = [f64; 6];

/// A rigid transform `p ↦ r·p + t` (the top three rows of an HTM).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Affine {
    /// Rotation.
    pub r: Matrix3<f64>,
    /// Translation, mm.
    pub t: Vector3<f64>,
}

impl Default for Affine {
    fn default() -> Self {
        Self::identity()
    }
}

impl Affine {
    /// The identity.
    pub fn identity() -> Self {
        Self {
            r: Matrix3::identity(),
            t: Vector3::zeros(),
        }
    }
    /// Pure translation (`A¹A²A³`).
    pub fn translation(t: Vector3<f64>) -> Self {
        Self {
            r: Matrix3::identity(),
            t,
        }
    }
    /// Pure rotation.
    pub fn rotation(r: Matrix3<f64>) -> Self {
        Self {
            r,
            t: Vector3::zeros(),
        }
    }
    /// `self · other`.
    pub fn then(&self, other: &Affine) -> Affine {
        Affine {
            r: self.r * other.r,
            t: self.r * other.t + self.t,
        }
    }
    /// Applies to a point.
    pub fn point(&self, p: &Vector3<f64>) -> Vector3<f64> {
        self.r * p + self.t
    }
    /// The inverse transform.
    pub fn inverse(&self) -> Affine {
        let rt = self.r.transpose();
        Affine {
            r: rt,
            t: -(rt * self.t),
        }
    }
    /// The 4×4 HTM.
    pub fn to_matrix4(&self) -> Matrix4<f64> {
        let mut m = Matrix4::identity();
        m.fixed_view_mut::<3, 3>(0, 0).copy_from(&self.r);
        m.fixed_view_mut::<3, 1>(0, 3).copy_from(&self.t);
        m
    }
    /// True when the rotation is exactly the identity.
    pub fn is_translation(&self) -> bool {
        self.r == Matrix3::identity()
    }
}

/// Rotation by `angle` (rad) about a principal axis: `A⁴`, `A⁵` or `A⁶`.
///
/// # Units
/// `angle` in rad.
///
/// # Examples
/// ```
/// use mtmotion::kinematics::htm::{rot, Dir};
/// let r = rot(Dir::Z, std::f64::consts::FRAC_PI_2);
/// let p = r * nalgebra::Vector3::new(1.0, 0.0, 0.0);
/// assert!((p.y - 1.0).abs() < 1e-15 && p.x.abs() < 1e-15);
/// ```
pub fn rot(dir: Dir, angle: f64) -> Matrix3<f64> {
    let (s, c) = angle.sin_cos();
    match dir {
        Dir::X => Matrix3::new(1.0, 0.0, 0.0, 0.0, c, -s, 0.0, s, c),
        Dir::Y => Matrix3::new(c, 0.0, s, 0.0, 1.0, 0.0, -s, 0.0, c),
        Dir::Z => Matrix3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0),
    }
}

/// Rotation `A⁴(rx)·A⁵(ry)·A⁶(rz)` (rad).
pub fn rot_xyz(r: [f64; 3]) -> Matrix3<f64> {
    rot(Dir::X, r[0]) * rot(Dir::Y, r[1]) * rot(Dir::Z, r[2])
}

/// Eq. 3 exactly as printed: the first-order error matrix.
///
/// # Units
/// `e = [δx, δy, δz, εx, εy, εz]` in mm and rad.
///
/// # Examples
/// ```
/// use mtmotion::kinematics::htm::error_matrix_linear;
/// let m = error_matrix_linear(&[0.01, 0.0, 0.0, 0.0, 0.0, 1e-4]);
/// assert_eq!(m[(0, 1)], -1e-4);
/// assert_eq!(m[(1, 0)], 1e-4);
/// assert_eq!(m[(0, 3)], 0.01);
/// ```
pub fn error_matrix_linear(e: &Six) -> Matrix4<f64> {
    Matrix4::new(
        1.0, -e[5], e[4], e[0], //
        e[5], 1.0, -e[3], e[1], //
        -e[4], e[3], 1.0, e[2], //
        0.0, 0.0, 0.0, 1.0,
    )
}

/// The exact rigid transform that Eq. 3 linearises:
/// `Trans(δx, δy, δz)·A⁴(εx)·A⁵(εy)·A⁶(εz)`.
///
/// # Units
/// `e = [δx, δy, δz, εx, εy, εz]` in mm and rad.
///
/// # Examples
/// ```
/// use mtmotion::kinematics::htm::{error_matrix_exact, error_matrix_linear};
/// let e = [1e-3, -2e-3, 5e-4, 1e-5, -2e-5, 3e-5];
/// let d = error_matrix_exact(&e).to_matrix4() - error_matrix_linear(&e);
/// assert!(d.abs().max() < 1e-9); // they differ at second order only
/// ```
pub fn error_matrix_exact(e: &Six) -> Affine {
    if e[3] == 0.0 && e[4] == 0.0 && e[5] == 0.0 {
        return Affine::translation(Vector3::new(e[0], e[1], e[2]));
    }
    Affine {
        r: rot_xyz([e[3], e[4], e[5]]),
        t: Vector3::new(e[0], e[1], e[2]),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn elementary_rotations_are_right_handed() {
        let q = std::f64::consts::FRAC_PI_2;
        // x→y about z, y→z about x, z→x about y.
        assert!((rot(Dir::Z, q) * Dir::X.unit() - Dir::Y.unit()).norm() < 1e-15);
        assert!((rot(Dir::X, q) * Dir::Y.unit() - Dir::Z.unit()).norm() < 1e-15);
        assert!((rot(Dir::Y, q) * Dir::Z.unit() - Dir::X.unit()).norm() < 1e-15);
    }

    #[test]
    fn affine_inverse_and_matrix4_agree() {
        let a = Affine {
            r: rot_xyz([0.1, -0.2, 0.3]),
            t: Vector3::new(1.0, 2.0, 3.0),
        };
        let i = a.then(&a.inverse());
        assert!((i.r - Matrix3::identity()).abs().max() < 1e-15);
        assert!(i.t.norm() < 1e-14);
        let m = a.to_matrix4() * a.inverse().to_matrix4();
        assert!((m - Matrix4::identity()).abs().max() < 1e-14);
    }

    #[test]
    fn exact_error_matrix_is_second_order_close_to_eq3() {
        // Difference scales with ε²: halve ε → quarter the difference.
        let e1 = [0.0, 0.0, 0.0, 1e-3, 2e-3, -1e-3];
        let e2 = e1.map(|v| v / 2.0);
        let d1 = (error_matrix_exact(&e1).to_matrix4() - error_matrix_linear(&e1))
            .abs()
            .max();
        let d2 = (error_matrix_exact(&e2).to_matrix4() - error_matrix_linear(&e2))
            .abs()
            .max();
        assert!((d1 / d2 - 4.0).abs() < 0.01, "{d1} {d2}");
    }
}
