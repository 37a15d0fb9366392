//! Cutter radius compensation as modal state (Fanuc G40/G41/G42 with a D
//! word, LinuxCNC G41.1/G42.1 `D<diameter>`): which side of the programmed
//! contour the tool centre runs on, with which radius, over which stretch of
//! the program. The offset path itself is computed after the run, in
//! [`super::cutter_path`].
//!
//! Readings chosen:
//! - G41 (left of the contour, seen along the direction of travel from the
//!   positive plane normal, the view in which G3 is counter-clockwise) and
//!   G42 (right) take the radius of their `D` word from
//!   [`super::program::ParseOptions::tool_radii`] (the control's offset
//!   table, which the program does not hold), in program units (G20:
//!   inch), converted to mm when the G41/G42 is read. `D0` is a radius of
//!   0, as on a Fanuc control.
//! - G41.1/G42.1 (LinuxCNC) give the tool *diameter* in `D` on the block;
//!   the radius is half of it and no option is needed.
//! - When no radius is known (no entry for that D, or G41/G42 without a D
//!   word: the radius of the loaded tool on LinuxCNC, the modal D on
//!   Fanuc) the simulated path is the programmed path over that stretch,
//!   and ONE warning (kind `cutter compensation`) at the G41/G42 word says
//!   so and how to give the radius.
//! - A stretch runs from the G41/G42 to the G40 that ends it. G41/G42 again
//!   with the same side and radius while compensation is in force changes
//!   nothing; a change of side or radius without a G40 between, a change of
//!   plane, a canned cycle or a G28/G30/G53/G92 move during compensation are
//!   located errors (they are not simulated).
//!
//! Units: radii in mm inside; the `toolRadii` option in program units.

use std::collections::BTreeMap;

use serde::de::{self, MapAccess, Visitor};
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use super::block::length_scale;
use super::gcodes::code10;
use super::program::{err, Ctx, Modal, Warning};
use super::segment::Plane;
use super::{Block, NcError, Word};

/// The side of the contour the tool centre runs on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Side {
    /// G41: left of the contour, seen along the direction of travel.
    Left,
    /// G42: right of the contour.
    Right,
}

impl Side {
    /// +1 for left (G41), −1 for right (G42): the factor on the left normal.
    pub fn sign(self) -> f64 {
        match self {
            Side::Left => 1.0,
            Side::Right => -1.0,
        }
    }
}

/// Compensation in force (a field of [`Modal`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct Cutter {
    /// Side of the contour.
    pub side: Side,
    /// Tool radius, mm (`None`: not known, the path is the programmed one).
    pub radius: Option<f64>,
    /// Index of its stretch in [`super::program::Program::cutter`].
    pub stretch: usize,
}

/// One compensated stretch of the program: from a G41/G42 to its G40.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct CutterStretch {
    /// The code as written (`G41`, `G42`, `G41.1`, `G42.1`).
    pub code: String,
    /// Side of the contour.
    pub side: Side,
    /// The D word as written (`D08`), if any.
    pub d: Option<String>,
    /// Tool radius, mm; `None` when it is not known (the simulated path is
    /// then the programmed path).
    pub radius: Option<f64>,
    /// The plane the compensation works in.
    pub plane: Plane,
    /// 1-based line of the G41/G42 word.
    pub line: usize,
    /// 1-based column of the G41/G42 word.
    pub column: usize,
    /// The file, when the line is in one of the extra files.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub file: Option<String>,
}

/// Tool radii per D number, in program units (the control's offset table).
/// Deserialised from a map (`{ "1": 3, "D8": 0.25 }`) or a text
/// (`"D1=3, D8=0.25"`); every radius must be finite and ≥ 0.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ToolRadii(BTreeMap<u32, f64>);

impl ToolRadii {
    /// The radius for `D<d>`, program units.
    pub fn get(&self, d: u32) -> Option<f64> {
        self.0.get(&d).copied()
    }

    /// No radius given.
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }

    /// Adds `D<key>` = `radius` (key `"1"`, `"D1"` or `"d01"`).
    ///
    /// # Errors
    /// A key that is not a D number, a radius that is not finite or is
    /// negative; the message names the entry.
    pub fn insert(&mut self, key: &str, radius: f64) -> Result<(), String> {
        if self.0.len() >= crate::budget::MAX_TOOL_RADII {
            return Err(format!(
                "toolRadii: more than {} radii; give those the program's D words use",
                crate::budget::MAX_TOOL_RADII
            ));
        }
        let k = key.trim();
        let digits = k.strip_prefix(['D', 'd']).unwrap_or(k).trim();
        let d: u32 = digits.parse().map_err(|_| {
            format!(
                "toolRadii: '{}' is not a D number; expected e.g. D1 or 1",
                crate::budget::clip(k, 40)
            )
        })?;
        if !radius.is_finite() || radius < 0.0 {
            return Err(format!(
                "toolRadii D{d}: radius {radius} must be a finite number ≥ 0 (program units)"
            ));
        }
        self.0.insert(d, radius);
        Ok(())
    }

    /// Reads `"D1=3, D8=0.25"` (entries separated by `,`, `;` or line
    /// ends; an empty text gives no radii).
    ///
    /// # Errors
    /// An entry without `=`, a bad D number or radius, named.
    ///
    /// # Examples
    /// ```
    /// use mtmotion::nc::cutter::ToolRadii;
    /// let t = ToolRadii::parse("D1=3, d8 = 0.25").unwrap();
    /// assert_eq!((t.get(1), t.get(8), t.get(2)), (Some(3.0), Some(0.25), None));
    /// assert!(ToolRadii::parse("D1=-1").unwrap_err().contains("D1"));
    /// ```
    pub fn parse(text: &str) -> Result<Self, String> {
        let mut t = ToolRadii::default();
        for item in text.split([',', ';', '\n']).map(str::trim) {
            if item.is_empty() {
                continue;
            }
            let (k, v) = item
                .split_once('=')
                .ok_or_else(|| format!("toolRadii: '{item}' has no '='; expected e.g. D1=3"))?;
            let r: f64 = v.trim().parse().map_err(|_| {
                format!(
                    "toolRadii {}: '{}' is not a number; expected a radius in program units",
                    k.trim(),
                    v.trim()
                )
            })?;
            t.insert(k, r)?;
        }
        Ok(t)
    }
}

impl Serialize for ToolRadii {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_map(self.0.iter().map(|(d, r)| (format!("D{d}"), *r)))
    }
}

struct RadiiVisitor;

impl<'de> Visitor<'de> for RadiiVisitor {
    type Value = ToolRadii;
    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str("tool radii per D number: a map { D1: 3 } or a text 'D1=3, D8=0.25'")
    }
    fn visit_str<E: de::Error>(self, v: &str) -> Result<ToolRadii, E> {
        ToolRadii::parse(v).map_err(E::custom)
    }
    fn visit_map<A: MapAccess<'de>>(self, mut m: A) -> Result<ToolRadii, A::Error> {
        let mut t = ToolRadii::default();
        while let Some(k) = m.next_key::<String>()? {
            let r: f64 = m.next_value().map_err(|e| {
                de::Error::custom(format!(
                    "toolRadii {k}: {e}; expected a radius in program units"
                ))
            })?;
            t.insert(&k, r).map_err(de::Error::custom)?;
        }
        Ok(t)
    }
}

impl<'de> Deserialize<'de> for ToolRadii {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(RadiiVisitor)
    }
}

/// Applies the block's G40/G41/G42/G41.1/G42.1 word `w` (code ×10 `g`) to
/// `st`: a new stretch in `cx`, its warning when the radius is unknown.
///
/// # Errors
/// G41.1/G42.1 without a diameter, a D word that is not a whole number ≥ 0,
/// a change of side or radius while compensation is in force.
pub(super) fn cutter_word(
    b: &Block,
    st: &mut Modal,
    cx: &mut Ctx,
    w: &Word,
    g: i64,
) -> Result<(), NcError> {
    let side = match g {
        400 => {
            st.cutter = None;
            return Ok(());
        }
        410 | 411 => Side::Left,
        _ => Side::Right,
    };
    // A G41/G42 without D uses the modal D (an earlier block's D word).
    let modal_d = match (b.word('D'), st.d) {
        (None, Some(d)) if matches!(g, 410 | 420) => Some(Word {
            letter: 'D',
            value: d,
            text: format!("{d}").into(),
            column: w.column,
        }),
        _ => None,
    };
    let dw = b.word('D').or(modal_d.as_ref());
    let radius = radius_of(b, w, g, dw, st, cx)?;
    if let (Some(d), 410 | 420) = (dw, g) {
        st.d = Some(d.value);
    }
    if let Some(c) = st.cutter {
        if c.side == side && c.radius == radius {
            return Ok(());
        }
        return Err(err(
            b,
            w,
            format!(
                "G{} while {} is in force: a change of side or tool radius during compensation is not simulated; cancel with G40 (and a move) first",
                w.text, cx.stretches[c.stretch].code
            ),
        ));
    }
    let stretch = CutterStretch {
        code: format!("G{}", w.text),
        side,
        d: dw.map(|d| format!("D{}", d.text)),
        radius,
        plane: st.plane,
        line: b.line,
        column: w.column,
        file: None,
    };
    if radius.is_none() {
        cx.warnings
            .push(Warning::at(b.line, w.column, unknown_radius(&stretch)));
    }
    st.cutter = Some(Cutter {
        side,
        radius,
        stretch: cx.stretches.len(),
    });
    cx.stretches.push(stretch);
    Ok(())
}

/// The tool radius, mm, of a G41/G42 (from the option, by D) or a
/// G41.1/G42.1 (half its D diameter); `None` when it is not known.
fn radius_of(
    b: &Block,
    w: &Word,
    g: i64,
    dw: Option<&Word>,
    st: &Modal,
    cx: &Ctx,
) -> Result<Option<f64>, NcError> {
    let scale = length_scale(st);
    if matches!(g, 411 | 421) {
        return match dw {
            Some(d) if d.value.is_finite() && d.value >= 0.0 => Ok(Some(d.value / 2.0 * scale)),
            Some(d) => Err(err(
                b,
                d,
                format!("G{} D{}: expected the tool diameter ≥ 0", w.text, d.text),
            )),
            None => Err(err(
                b,
                w,
                format!("G{} needs D<tool diameter> on the same block", w.text),
            )),
        };
    }
    let Some(d) = dw else { return Ok(None) };
    if d.value < 0.0 || d.value.fract() != 0.0 || d.value > 9999.0 {
        return Err(err(
            b,
            d,
            format!(
                "D{}: expected a whole tool-offset number from 0 to 9999",
                d.text
            ),
        ));
    }
    let n = d.value as u32;
    if n == 0 {
        return Ok(Some(0.0));
    }
    Ok(cx.opt.tool_radii.get(n).map(|r| r * scale))
}

/// The warning of a stretch whose radius is not known.
fn unknown_radius(s: &CutterStretch) -> String {
    let (what, how) = match &s.d {
        Some(d) => (
            format!("no tool radius is given for {d}"),
            format!("give it with the option toolRadii (e.g. toolRadii: '{d}=3', in program units; on the page the 'tool radii per D' field)"),
        ),
        None => (
            "there is no D word (the control would use the loaded tool's radius or the modal D)".to_string(),
            "write the D word and give its radius with the option toolRadii (e.g. 'D1=3', in program units)".to_string(),
        ),
    };
    format!(
        "cutter compensation {}{}: {what}, so the simulated path is the programmed (un-offset) path and contour errors are those of the programmed path; {how}",
        s.code,
        s.d.as_deref().map(|d| format!(" {d}")).unwrap_or_default()
    )
}

/// The error for a block that moves in a way compensation does not
/// simulate (canned cycle, G28/G30/G53/G92) while it is in force, or that
/// changes the plane; `None` when compensation is off or the block is fine.
pub(super) fn refused_during(
    b: &Block,
    st: &Modal,
    cx: &Ctx,
    what: Option<&Word>,
) -> Option<NcError> {
    let c = st.cutter?;
    let s = &cx.stretches[c.stretch];
    if st.plane != s.plane {
        let column = b
            .words_of('G')
            .find(|w| matches!(code10(w), 170 | 180 | 190))
            .map_or(1, |w| w.column);
        return Some(NcError::new(
            b.line,
            column,
            format!(
                "plane change to G{} while cutter compensation {} (line {}) is in force in G{}; cancel it with G40 first",
                st.plane.code(),
                s.code,
                s.line,
                s.plane.code()
            ),
        ));
    }
    let w = what?;
    Some(err(
        b,
        w,
        format!(
            "{}{} during cutter compensation {} (line {}) is not simulated; cancel it with G40 (and a move) first",
            w.letter, w.text, s.code, s.line
        ),
    ))
}
