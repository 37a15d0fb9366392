//! Machine chains as data (thasana-htm-nc-compensation §II-B, Eqs. 1–2, 8).
//!
//! A chain is the list of links from the workpiece (first) to the tool
//! (last), so that `r_w = T(q)·r_e` (Eq. 1): a point given in the tool frame
//! is mapped into the workpiece frame. Link `i` is
//! `Fixed_i · Joint_i(q) · E_i`: a fixed transform (translation in mm, then a
//! rotation `A⁴A⁵A⁶` in rad; the `A¹(d)…A³(d)` of Eq. 8), an optional joint
//! (linear along, or rotary about, a principal direction), and the error
//! matrix `E_i` of Eq. 3 built from the geometric errors
//! ([`super::errors`]).
//!
//! Reading chosen for the joint sign: every NC axis value is the motion of
//! the tool *relative to the workpiece* (ISO 841), so in a workpiece→tool
//! chain a joint enters with `sign = +1` whether the axis moves the table or
//! the spindle. `sign = -1` describes a machine whose control uses the
//! opposite convention.
//!
//! Units: mm, rad inside the chain; joint values of rotary axes are rad in
//! the core and degrees at the JS API.

use serde::{Deserialize, Serialize};

use super::htm::Dir;
use super::KinematicsError;

/// Linear or rotary joint.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum JointKind {
    /// Translation along `dir`, mm.
    Linear,
    /// Rotation about `dir`, rad.
    Rotary,
}

/// A joint: which NC axis drives it and how it moves.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct Joint {
    /// NC axis letter, lower case: `x`, `y`, `z`, `a`, `b` or `c`.
    pub axis: String,
    /// Linear or rotary.
    pub kind: JointKind,
    /// Direction of the translation or of the rotation axis.
    pub dir: Dir,
    /// `+1` or `-1` (see the module header).
    #[serde(default = "one")]
    pub sign: f64,
}

fn one() -> f64 {
    1.0
}

/// One link of the chain.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct Link {
    /// Name, e.g. `B table` (for reports).
    pub name: String,
    /// Fixed translation before the joint, mm.
    #[serde(default)]
    pub translation: [f64; 3],
    /// Fixed rotation `A⁴(rx)·A⁵(ry)·A⁶(rz)` after the translation, rad.
    #[serde(default, skip_serializing_if = "is_zero3")]
    pub rotation: [f64; 3],
    /// The joint, if the link moves.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub joint: Option<Joint>,
}

fn is_zero3(v: &[f64; 3]) -> bool {
    v.iter().all(|x| *x == 0.0)
}

/// A machine chain from the workpiece to the tool.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct Chain {
    /// Links, workpiece first.
    pub links: Vec<Link>,
    /// Tool tip (or spindle-ball centre) in the last frame, mm, with no
    /// tool length.
    #[serde(default)]
    pub tool_point: [f64; 3],
    /// Tool axis in the last frame, from the tip towards the spindle
    /// (unit vector).
    pub tool_axis: [f64; 3],
}

/// Axis letters in the order of the joint vector `q`.
pub use crate::axes::AXES;

impl Chain {
    /// The joints in chain order: `(link index, joint)`.
    pub fn joints(&self) -> impl Iterator<Item = (usize, &Joint)> {
        self.links
            .iter()
            .enumerate()
            .filter_map(|(i, l)| l.joint.as_ref().map(|j| (i, j)))
    }

    /// Index of `axis` in [`AXES`].
    pub fn axis_index(axis: &str) -> Option<usize> {
        AXES.iter().position(|a| *a == axis)
    }

    /// The axis letters this chain moves, in [`AXES`] order.
    pub fn axes(&self) -> Vec<&'static str> {
        AXES.iter()
            .copied()
            .filter(|a| self.joints().any(|(_, j)| j.axis == *a))
            .collect()
    }

    /// Checks the chain: known axis letters, each at most once, linear
    /// joints on x/y/z and rotary on a/b/c, signs ±1, finite numbers, a
    /// unit tool axis.
    ///
    /// # Examples
    /// ```
    /// let m = mtmotion::machine::preset("trunnion-ac").unwrap();
    /// let mut chain = m.kinematics.unwrap();
    /// assert!(chain.validate().is_ok());
    /// chain.tool_axis = [0.0, 0.0, 0.0];
    /// assert!(chain.validate().unwrap_err().to_string().contains("toolAxis"));
    /// ```
    pub fn validate(&self) -> Result<(), KinematicsError> {
        let bad = |field: String, why: &str| KinematicsError::BadChain {
            field,
            why: why.to_string(),
        };
        let mut seen = [false; 6];
        for (i, l) in self.links.iter().enumerate() {
            if !l
                .translation
                .iter()
                .chain(&l.rotation)
                .all(|v| v.is_finite())
            {
                return Err(bad(
                    format!("links[{i}]"),
                    "translation and rotation must be finite numbers",
                ));
            }
            if let Some(j) = &l.joint {
                let k = Self::axis_index(&j.axis).ok_or_else(|| {
                    bad(
                        format!("links[{i}].joint.axis"),
                        "must be one of x, y, z, a, b, c",
                    )
                })?;
                if seen[k] {
                    return Err(bad(
                        format!("links[{i}].joint.axis"),
                        "this axis already drives another link",
                    ));
                }
                seen[k] = true;
                let linear = k < 3;
                if linear != (j.kind == JointKind::Linear) {
                    return Err(bad(
                        format!("links[{i}].joint.kind"),
                        "x, y, z must be linear joints and a, b, c rotary joints",
                    ));
                }
                if j.sign != 1.0 && j.sign != -1.0 {
                    return Err(bad(format!("links[{i}].joint.sign"), "must be +1 or -1"));
                }
            }
        }
        let n: f64 = self.tool_axis.iter().map(|v| v * v).sum::<f64>().sqrt();
        if (n - 1.0).abs() >= 1e-9 || !n.is_finite() {
            return Err(bad("toolAxis".into(), "must be a unit vector"));
        }
        if !self.tool_point.iter().all(|v| v.is_finite()) {
            return Err(bad("toolPoint".into(), "must be finite numbers"));
        }
        let rotary = seen[3..].iter().filter(|s| **s).count();
        if rotary > 2 {
            return Err(bad(
                "links".into(),
                "at most two rotary axes (a 5-axis machine) are supported",
            ));
        }
        Ok(())
    }
}

impl Link {
    /// A link with no joint.
    pub fn fixed(name: &str, translation: [f64; 3]) -> Self {
        Self {
            name: name.into(),
            translation,
            rotation: [0.0; 3],
            joint: None,
        }
    }
    /// A link with a linear joint along `dir` driven by `axis`.
    pub fn linear(name: &str, translation: [f64; 3], axis: &str, dir: Dir) -> Self {
        Self {
            joint: Some(Joint {
                axis: axis.into(),
                kind: JointKind::Linear,
                dir,
                sign: 1.0,
            }),
            ..Self::fixed(name, translation)
        }
    }
    /// A link with a rotary joint about `dir` driven by `axis`.
    pub fn rotary(name: &str, translation: [f64; 3], axis: &str, dir: Dir) -> Self {
        Self {
            joint: Some(Joint {
                axis: axis.into(),
                kind: JointKind::Rotary,
                dir,
                sign: 1.0,
            }),
            ..Self::fixed(name, translation)
        }
    }
}
