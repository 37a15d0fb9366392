//! Geometric errors as data, named as in ISO 230-1 and ISO 230-7, and how
//! they enter the chain as error matrices `E` (thasana Eq. 3).
//!
//! - **Location errors** (`location`), symbol `E<d>0<axis>`: the position
//!   and orientation of an axis. For a rotary axis these are the ISO 230-7
//!   offsets and squareness of its axis average line, e.g. `EX0C`, `EY0C`
//!   (mm) and `EA0C`, `EB0C` (rad) for C; `EC0C` is its zero-position
//!   error. For a linear axis they are the ISO 230-1 squareness errors,
//!   e.g. `EC0Y` (Y to X, about Z), `EA0Z` (Z to Y) and `EB0Z` (Z to X).
//!   The older spellings `XOC`, `X0C`, `EXOC` are accepted.
//! - **Component errors** (`component`), symbol `E<d><axis>`: the six error
//!   motions of an axis as polynomials in its position (mm for linear axes,
//!   rad for rotary axes), e.g. `EXX` (positioning error of X), `EYX`, `EZX`
//!   (straightness), `EAX`, `EBX`, `ECX` (roll, pitch, yaw); `EXC`, `EYC`
//!   (radial), `EZC` (axial), `EAC`, `EBC` (tilt), `ECC` (angular
//!   positioning) for C. A single number is a constant.
//! - `tool`: the six parameters of `E_ST` of thasana Eq. 8 (tool deflection
//!   in the tool frame, `[δx, δy, δz, εx, εy, εz]`).
//!
//! Backlash and worm-gear pitch error are the drives' errors
//! (`servo::transmission::DriveErrors`), not part of this model.
//!
//! Reading chosen: a location error of an axis acts as `E·J(q)·E⁻¹` around
//! its joint `J` (the axis line is displaced and tilted, the parts it
//! carries are not moved at the axis' zero), except for the component along
//! or about the axis itself (`EX0X`, `EC0C`…), which is a zero-position
//! offset added to `q`. Component errors act as `E(q)` after the joint.
//!
//! Units: mm and rad.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use super::chain::Chain;
use super::htm::Six;
use super::KinematicsError;

/// A constant or a polynomial `c0 + c1·q + c2·q² …`: read from a number
/// or an array of numbers.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(untagged)]
pub enum Coeffs {
    /// A constant.
    Constant(f64),
    /// Polynomial coefficients, lowest order first.
    Polynomial(Vec<f64>),
}

impl<'de> Deserialize<'de> for Coeffs {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Either;
        impl<'de> serde::de::Visitor<'de> for Either {
            type Value = Coeffs;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a number or an array of polynomial coefficients")
            }
            fn visit_f64<E: serde::de::Error>(self, c: f64) -> Result<Coeffs, E> {
                Ok(Coeffs::Constant(c))
            }
            fn visit_i64<E: serde::de::Error>(self, c: i64) -> Result<Coeffs, E> {
                Ok(Coeffs::Constant(c as f64))
            }
            fn visit_u64<E: serde::de::Error>(self, c: u64) -> Result<Coeffs, E> {
                Ok(Coeffs::Constant(c as f64))
            }
            fn visit_seq<A: serde::de::SeqAccess<'de>>(self, seq: A) -> Result<Coeffs, A::Error> {
                let v = Vec::<f64>::deserialize(serde::de::value::SeqAccessDeserializer::new(seq))?;
                Ok(Coeffs::Polynomial(v))
            }
        }
        d.deserialize_any(Either)
    }
}

impl Coeffs {
    /// Coefficients as a vector.
    pub fn to_vec(&self) -> Vec<f64> {
        match self {
            Coeffs::Constant(c) => vec![*c],
            Coeffs::Polynomial(v) => v.clone(),
        }
    }
}

/// The geometric errors of a machine.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(rename_all = "camelCase", deny_unknown_fields)]
pub struct GeometricErrors {
    /// Location errors by ISO symbol (mm, rad).
    #[serde(default)]
    pub location: BTreeMap<String, f64>,
    /// Component errors by ISO symbol (mm, rad; polynomial in mm or rad).
    #[serde(default)]
    pub component: BTreeMap<String, Coeffs>,
    /// `E_ST` of Eq. 8, `[δx, δy, δz, εx, εy, εz]` in the tool frame.
    #[serde(default)]
    pub tool: Six,
}

/// One parsed error symbol: error direction `d` (0..6 = x,y,z,a,b,c) of
/// axis `axis` (0..6).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Symbol {
    /// Direction of the error: 0..3 translation x, y, z; 3..6 rotation.
    pub d: usize,
    /// The axis it belongs to, index into [`crate::axes::AXES`].
    pub axis: usize,
    /// Location (`true`) or component error.
    pub location: bool,
}

fn letter(c: char) -> Option<usize> {
    "XYZABC".find(c.to_ascii_uppercase())
}

/// Parses an ISO symbol: `EX0C`, `XOC`, `X0C`, `EXOC` (location) or `EXC`
/// (component).
///
/// # Examples
/// ```
/// use mtmotion::kinematics::errors::parse_symbol;
/// let s = parse_symbol("XOC").unwrap();
/// assert_eq!((s.d, s.axis, s.location), (0, 5, true));
/// let s = parse_symbol("ebx").unwrap();
/// assert_eq!((s.d, s.axis, s.location), (4, 0, false));
/// assert!(parse_symbol("EQX").is_none());
/// ```
pub fn parse_symbol(sym: &str) -> Option<Symbol> {
    let s: Vec<char> = sym.trim().to_ascii_uppercase().chars().collect();
    let body: &[char] = if s.first() == Some(&'E') && s.len() >= 3 {
        &s[1..]
    } else {
        &s
    };
    match body {
        [d, o, a] if *o == '0' || *o == 'O' => Some(Symbol {
            d: letter(*d)?,
            axis: letter(*a)?,
            location: true,
        }),
        [d, a] if s.len() == 3 => Some(Symbol {
            d: letter(*d)?,
            axis: letter(*a)?,
            location: false,
        }),
        _ => None,
    }
}

/// Canonical symbol, e.g. `EX0C` or `EXC`.
pub fn symbol_name(s: Symbol) -> String {
    let l = |i: usize| "XYZABC".chars().nth(i).unwrap_or('?');
    if s.location {
        format!("E{}0{}", l(s.d), l(s.axis))
    } else {
        format!("E{}{}", l(s.d), l(s.axis))
    }
}

/// The errors of one axis, ready for the chain.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct AxisErrors {
    /// Location error `E` (the own-axis component removed).
    pub location: Six,
    /// Zero-position offset added to `q` (mm or rad).
    pub zero: f64,
    /// Component error polynomials, one per direction.
    pub component: [Vec<f64>; 6],
}

impl AxisErrors {
    /// True when the component errors do not depend on the position.
    pub fn component_is_constant(&self) -> bool {
        self.component.iter().all(|c| c.len() <= 1)
    }
    /// The component errors at position `q`.
    pub fn component_at(&self, q: f64) -> Six {
        let mut e = [0.0; 6];
        for (slot, c) in e.iter_mut().zip(&self.component) {
            *slot = c.iter().rev().fold(0.0, |acc, k| acc * q + k);
        }
        e
    }
}

/// The own direction of axis `axis` (0..6): x→0, … c→5.
fn own(axis: usize) -> usize {
    axis
}

impl GeometricErrors {
    /// True when nothing is set.
    pub fn is_zero(&self) -> bool {
        self.location.values().all(|v| *v == 0.0)
            && self
                .component
                .values()
                .all(|c| c.to_vec().iter().all(|v| *v == 0.0))
            && self.tool.iter().all(|v| *v == 0.0)
    }

    /// Resolves the symbols against `chain`: per axis (index into
    /// [`crate::axes::AXES`]) the errors that enter its link. Errors name the offending
    /// key.
    pub fn resolve(&self, chain: &Chain) -> Result<[AxisErrors; 6], KinematicsError> {
        let mut out: [AxisErrors; 6] = Default::default();
        let present = chain.axes();
        for (key, v) in &self.location {
            let s = parse_symbol(key).filter(|s| s.location).ok_or_else(|| {
                KinematicsError::BadError {
                    key: format!("location.{key}"),
                    why:
                        "expected an ISO 230 location-error symbol such as EX0C, EA0C, EC0Y or XOC"
                            .into(),
                }
            })?;
            check_axis(&present, &format!("location.{key}"), s.axis)?;
            finite(&format!("location.{key}"), *v)?;
            if s.d == own(s.axis) {
                out[s.axis].zero += v;
            } else {
                out[s.axis].location[s.d] += v;
            }
        }
        for (key, c) in &self.component {
            let s = parse_symbol(key).filter(|s| !s.location).ok_or_else(|| {
                KinematicsError::BadError {
                    key: format!("component.{key}"),
                    why: "expected an ISO 230 component-error symbol such as EXX, EBX or ECC"
                        .into(),
                }
            })?;
            check_axis(&present, &format!("component.{key}"), s.axis)?;
            let coeffs = c.to_vec();
            for v in &coeffs {
                finite(&format!("component.{key}"), *v)?;
            }
            let slot = &mut out[s.axis].component[s.d];
            if slot.len() < coeffs.len() {
                slot.resize(coeffs.len(), 0.0);
            }
            for (a, b) in slot.iter_mut().zip(&coeffs) {
                *a += b;
            }
        }
        for (i, v) in self.tool.iter().enumerate() {
            finite(&format!("tool[{i}]"), *v)?;
        }
        Ok(out)
    }
}

/// An error on an axis the machine does not have is refused, naming the key.
fn check_axis(present: &[&str], key: &str, axis: usize) -> Result<(), KinematicsError> {
    crate::axes::require(present, axis).map_err(|why| KinematicsError::BadError {
        key: key.to_string(),
        why,
    })
}

/// An error value must be a finite number.
fn finite(key: &str, v: f64) -> Result<(), KinematicsError> {
    if v.is_finite() {
        Ok(())
    } else {
        Err(KinematicsError::BadError {
            key: key.to_string(),
            why: "must be a finite number (mm or rad)".into(),
        })
    }
}

/// The location errors a machine's motions can reveal (and so the errors a
/// cone-frustum test or a compensation can see): for each rotary axis
/// its two radial offsets and three angular errors (the own-axis angle is
/// the zero-position error); for the linear axes the squareness errors
/// `EC0Y`, `EB0Z`, `EA0Z`.
///
/// # Examples
/// ```
/// let chain = mtmotion::machine::preset("trunnion-ac").unwrap().kinematics.unwrap();
/// let s = mtmotion::kinematics::errors::error_symbols(&chain);
/// assert!(s.contains(&"EX0C".to_string()) && s.contains(&"EY0A".to_string()));
/// assert!(!s.contains(&"EZ0C".to_string()) && !s.contains(&"EX0A".to_string()));
/// ```
pub fn error_symbols(chain: &Chain) -> Vec<String> {
    let mut out = Vec::new();
    for (_, j) in chain.joints() {
        if j.kind != super::JointKind::Rotary {
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn symbols_round_trip() {
        for name in [
            "EX0C", "EY0C", "EA0C", "EB0C", "EC0Y", "EB0Z", "EXX", "ECC", "EZB",
        ] {
            let s = parse_symbol(name).unwrap();
            assert_eq!(symbol_name(s), name);
        }
        assert_eq!(symbol_name(parse_symbol("yoa").unwrap()), "EY0A");
        assert!(parse_symbol("E").is_none());
        assert!(parse_symbol("EXYZ").is_none());
    }

    #[test]
    fn polynomial_component_error() {
        let a = AxisErrors {
            component: [vec![1.0, 2.0, 3.0], vec![], vec![], vec![], vec![], vec![]],
            ..Default::default()
        };
        assert_eq!(a.component_at(2.0)[0], 1.0 + 4.0 + 12.0);
    }
}
