//! The ISO 10791-6 cone-frustum ball-bar path (kato-cone-frustum-ballbar
//! §2.1, Fig. 1): a 3D circle equivalent to cutting a cone frustum with
//! simultaneous five-axis motion.
//!
//! Readings chosen (Fig. 1 is missing from the text):
//! - the cone axis `a` is the workpiece z axis inclined by `β` about the
//!   workpiece x axis: `a = A⁴(−β)·z = (0, sin β, cos β)`; `e1 = x`,
//!   `e2 = a × e1`, `r(φ) = cos φ·e1 + sin φ·e2`;
//! - the tool axis is the generator of the cone through the cutting point,
//!   `g = cos θ·a − sin θ·r` (the frustum narrows upward; half-apex `θ`);
//! - the table ball `O_T` is fixed at `centre` on the cone axis; the
//!   spindle ball `O_S` is the tool tip, at distance `L` from `O_T`:
//!   *perpendicular* method (Fig. 1(a)): the bar is along the outward
//!   surface normal `n = cos θ·r + sin θ·a`, so `O_S` runs on a circle of
//!   radius `L cos θ`, `L sin θ` above `O_T`; *parallel* method (Fig. 1(b)):
//!   the bar is along `r`, parallel to the frustum bottom, radius `L`.
//!
//! Units: mm, rad.

use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

/// Sensitive direction of the ball bar (kato Fig. 1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Method {
    /// Bar perpendicular to the conical surface (Fig. 1(a)).
    Perpendicular,
    /// Bar parallel to the cone-frustum bottom (Fig. 1(b)).
    Parallel,
}

/// The geometry of one test.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Geometry {
    /// Half-apex angle θ, rad.
    pub half_apex: f64,
    /// Inclination β of the cone axis, rad.
    pub inclination: f64,
    /// Bar direction.
    pub method: Method,
    /// Bar length L, mm.
    pub bar_length: f64,
    /// Table-ball centre `O_T`, mm (workpiece frame).
    pub centre: Vector3<f64>,
}

/// One point of the path.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PathPoint {
    /// Spindle-ball centre (tool tip), mm.
    pub tip: Vector3<f64>,
    /// Tool axis (unit).
    pub axis: Vector3<f64>,
    /// Unit bar direction from `O_T` to `O_S`.
    pub bar: Vector3<f64>,
}

impl Geometry {
    /// Cone axis.
    pub fn cone_axis(&self) -> Vector3<f64> {
        Vector3::new(0.0, self.inclination.sin(), self.inclination.cos())
    }

    /// Radius of the spindle-ball circle, mm.
    pub fn circle_radius(&self) -> f64 {
        match self.method {
            Method::Perpendicular => self.bar_length * self.half_apex.cos(),
            Method::Parallel => self.bar_length,
        }
    }

    /// The path point at angle `phi` (rad) around the cone axis.
    ///
    /// # Units
    /// `phi` in rad; result in mm.
    ///
    /// # Examples
    /// ```
    /// use mtmotion::cone_frustum::path::{Geometry, Method};
    /// let g = Geometry { half_apex: 45f64.to_radians(), inclination: 0.0,
    ///     method: Method::Perpendicular, bar_length: 100.0, centre: nalgebra::Vector3::zeros() };
    /// let p = g.point(0.0);
    /// assert!(((p.tip - g.centre).norm() - 100.0).abs() < 1e-12);
    /// assert!(p.bar.dot(&p.axis).abs() < 1e-15); // bar ⟂ tool axis (⟂ surface)
    /// assert!((p.tip.x - 100.0 * 45f64.to_radians().cos()).abs() < 1e-12);
    /// ```
    pub fn point(&self, phi: f64) -> PathPoint {
        let a = self.cone_axis();
        let e1 = Vector3::x();
        let e2 = a.cross(&e1);
        let r = e1 * phi.cos() + e2 * phi.sin();
        let (st, ct) = self.half_apex.sin_cos();
        let axis = a * ct - r * st;
        let bar = match self.method {
            Method::Perpendicular => r * ct + a * st,
            Method::Parallel => r,
        };
        PathPoint {
            tip: self.centre + bar * self.bar_length,
            axis,
            bar,
        }
    }
}
