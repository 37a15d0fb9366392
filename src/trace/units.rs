//! Units stated in trace headers, and their factors to core units.
//!
//! Instruments write a column's unit into its name: `Time [ms]`, `t(s)`,
//! `X_mm`, `x_um`, `POS X(um)`, `C deg`, `TCMD C(%)`. [`name_unit`] splits a
//! name into its bare name and the unit; [`unit()`] gives the unit's quantity
//! and its factor to the core's units (mm, s, rad, N·m).
//!
//! Reading chosen: `nm` in a header is N·m (servo tuning software writes
//! torque as `Nm`; no trace of a machine tool is written in nanometres),
//! `m` is metres and `in` inches. A `%` column is a torque in per cent of
//! the motor's rated torque (FANUC's `TCMD` is written so): it has no
//! factor until the rated torque is given.
//!
//! # Units
//! Factors are core units per stated unit: s/ms = 1e-3, mm/in = 25.4,
//! rad/deg = π/180.

use serde::Serialize;

/// What a unit measures.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "camelCase")]
pub enum Quantity {
    /// Time, core unit s.
    Time,
    /// Length, core unit mm.
    Length,
    /// Angle, core unit rad.
    Angle,
    /// Torque, core unit N·m.
    Torque,
    /// Per cent of a rated value (torque): no factor without the rating.
    Percent,
}

impl Quantity {
    /// The core unit of the quantity (`%` for [`Quantity::Percent`]).
    pub fn core_unit(self) -> &'static str {
        match self {
            Self::Time => "s",
            Self::Length => "mm",
            Self::Angle => "rad",
            Self::Torque => "N·m",
            Self::Percent => "%",
        }
    }
}

/// A unit a header may state.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Unit {
    /// Its code as [`name_unit`] returns it (`ms`, `um`, `deg`, `n·m`, `%`).
    pub code: &'static str,
    /// What it measures.
    pub quantity: Quantity,
    /// Core units per this unit (0.01 for `%`: a fraction of the rating).
    pub factor: f64,
}

/// Every unit a header may state, by quantity, core unit first.
pub const UNITS: [Unit; 11] = [
    Unit {
        code: "s",
        quantity: Quantity::Time,
        factor: 1.0,
    },
    Unit {
        code: "ms",
        quantity: Quantity::Time,
        factor: 1e-3,
    },
    Unit {
        code: "us",
        quantity: Quantity::Time,
        factor: 1e-6,
    },
    Unit {
        code: "mm",
        quantity: Quantity::Length,
        factor: 1.0,
    },
    Unit {
        code: "um",
        quantity: Quantity::Length,
        factor: 1e-3,
    },
    Unit {
        code: "m",
        quantity: Quantity::Length,
        factor: 1e3,
    },
    Unit {
        code: "in",
        quantity: Quantity::Length,
        factor: 25.4,
    },
    Unit {
        code: "rad",
        quantity: Quantity::Angle,
        factor: 1.0,
    },
    Unit {
        code: "deg",
        quantity: Quantity::Angle,
        factor: std::f64::consts::PI / 180.0,
    },
    Unit {
        code: "n·m",
        quantity: Quantity::Torque,
        factor: 1.0,
    },
    Unit {
        code: "%",
        quantity: Quantity::Percent,
        factor: 0.01,
    },
];

/// The unit of a code from [`name_unit`] (`None` for an unknown code).
///
/// # Examples
/// ```
/// use mtmotion::trace::units::{unit, Quantity};
/// let ms = unit("ms").unwrap();
/// assert_eq!((ms.quantity, ms.factor), (Quantity::Time, 1e-3));
/// assert!((unit("deg").unwrap().factor - 0.017453292519943295).abs() < 1e-18);
/// assert!(unit("furlong").is_none());
/// ```
pub fn unit(code: &str) -> Option<Unit> {
    UNITS.iter().copied().find(|u| u.code == code)
}

/// The code of a unit as written (`[ms]`, `µm`, `Nm`, `°`), lower-case.
fn code(u: &str) -> Option<&'static str> {
    match u.trim().to_lowercase().replace('μ', "µ").as_str() {
        "s" | "sec" => Some("s"),
        "ms" | "msec" => Some("ms"),
        "us" | "µs" => Some("us"),
        "mm" => Some("mm"),
        "um" | "µm" => Some("um"),
        "m" => Some("m"),
        "in" | "inch" => Some("in"),
        "deg" | "°" | "degree" | "degrees" => Some("deg"),
        "rad" => Some("rad"),
        "nm" | "n·m" | "n.m" | "n*m" => Some("n·m"),
        "%" => Some("%"),
        _ => None,
    }
}

/// A column name split into its bare name and the unit it states, as
/// instruments write it: `Time(ms)`, `Time [ms]`, `t(s)`, `X_mm`, `x_um`,
/// `C deg`, `C[deg]`, `POS X(um)`, `TCMD C(%)`. Units recognised
/// (lower-case on return): `s`, `ms`, `us`, `mm`, `um` (also `µm`, `μm`),
/// `m`, `in`, `deg`, `rad`, `n·m` (`Nm`, `N.m`, `N·m`), `%`; anything else
/// is `None`.
///
/// # Examples
/// ```
/// use mtmotion::trace::name_unit;
/// assert_eq!(name_unit("Time [ms]"), ("Time".to_string(), Some("ms")));
/// assert_eq!(name_unit("t(s)"), ("t".to_string(), Some("s")));
/// assert_eq!(name_unit("pos_x_mm"), ("pos_x".to_string(), Some("mm")));
/// assert_eq!(name_unit("C deg"), ("C".to_string(), Some("deg")));
/// assert_eq!(name_unit("TCMD C(%)"), ("TCMD C".to_string(), Some("%")));
/// assert_eq!(name_unit("X"), ("X".to_string(), None));
/// ```
pub fn name_unit(name: &str) -> (String, Option<&'static str>) {
    let n = name.trim();
    // Bracketed suffix: "Time [ms]", "Time(ms)".
    if let Some(open) = n.rfind(['[', '(']) {
        let close = if n[open..].starts_with('[') { ']' } else { ')' };
        if n.ends_with(close) && open > 0 {
            if let Some(u) = code(&n[open + 1..n.len() - 1]) {
                return (n[..open].trim().to_string(), Some(u));
            }
        }
    }
    // Separated suffix: "x_mm", "C deg", "t-s".
    if let Some(sep) = n.rfind(['_', ' ', '-']) {
        if sep > 0 {
            if let Some(u) = code(&n[sep + 1..]) {
                return (n[..sep].trim().to_string(), Some(u));
            }
        }
    }
    (n.to_string(), None)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::trace::Table;

    #[test]
    fn unit_suffixes_name_the_column_and_its_unit() {
        for (n, bare, u) in [
            ("Time(ms)", "Time", Some("ms")),
            ("Time [ms]", "Time", Some("ms")),
            ("t(s)", "t", Some("s")),
            ("X_mm", "X", Some("mm")),
            ("Y [µm]", "Y", Some("um")),
            ("C deg", "C", Some("deg")),
            ("Torque (Nm)", "Torque", Some("n·m")),
            ("pos_x", "pos_x", None),
            ("(ms)", "(ms)", None),
            // a name that is only a unit keeps it as its name
            ("_mm", "_mm", None),
            ("-s", "-s", None),
        ] {
            assert_eq!(name_unit(n), (bare.to_string(), u), "{n}");
        }
        // A column chosen by its full name with the unit is found.
        let t = Table::parse("Time(ms),X [mm]\n0,1\n1,2\n").unwrap();
        assert_eq!(t.column(&["Time(ms)"], 1e-3).unwrap(), vec![0.0, 1e-3]);
        assert_eq!(t.column(&["x"], 1.0).unwrap(), vec![1.0, 2.0]);
    }

    #[test]
    fn every_unit_has_its_code_and_a_factor_to_core_units() {
        for u in UNITS {
            assert_eq!(unit(u.code), Some(u));
            assert_eq!(name_unit(&format!("v [{}]", u.code)).1, Some(u.code));
        }
        for (written, code, factor) in [
            ("POS X(um)", "um", 1e-3),
            ("X [in]", "in", 25.4),
            ("x_m", "m", 1e3),
            ("t_us", "us", 1e-6),
            ("Torque [N·m]", "n·m", 1.0),
            ("C (rad)", "rad", 1.0),
        ] {
            let c = name_unit(written).1.unwrap();
            assert_eq!((c, unit(c).unwrap().factor), (code, factor), "{written}");
        }
        assert_eq!(Quantity::Percent.core_unit(), "%");
        assert_eq!(Quantity::Torque.core_unit(), "N·m");
        assert_eq!(Quantity::Time.core_unit(), "s");
        assert_eq!(Quantity::Length.core_unit(), "mm");
        assert_eq!(Quantity::Angle.core_unit(), "rad");
    }
}
