//! A Renishaw `.b5r` report's features beside ours: each feature the file
//! reports ([`crate::trace::b5r`]) paired with the value our circular test
//! ([`super::circular_test`]) gives for the same feature, where we compute
//! one.
//!
//! Pairing (readings chosen; the names are those of the `.b5r` layout the
//! reader's header cites; `A`/`B` are the plane's first and second axis,
//! ours X and Y, the trace's first and second column):
//! - `AF_CIRCULARITY` of an analysis ↔ the largest ISO 230-4 G of our
//!   runs; of a `BALLBAR_RUN` ↔ G of our first run in the same direction
//!   (`CW`/`CCW`);
//! - `AF_SQUARENESS` ↔ squareness (µrad = µm/m); `AF_SERVO_MISMATCH` ↔
//!   servo mismatch (ms); `AF_SCALE_MISMATCH` ↔ scale mismatch (ppm);
//! - `AF_BACKLASH_A_*`/`_B_*` ↔ backlash X/Y (both the POS and the NEG
//!   feature face our one value per axis); `AF_CYCLIC_ERROR_A*`/`_B*` ↔
//!   cyclic amplitude X/Y;
//! - any other feature (straightness, lateral play, reversal spikes,
//!   measured feed, …) has no value of ours.
//!
//! The file's value is converted to our unit only where the units are the
//! same quantity (mm → µm, µm/m → µrad, ms, ppm, µm); otherwise
//! [`Beside::theirs_in_ours`] is None and both stay as written. Signs are
//! each side's own convention: no sign is changed, and the two are shown,
//! not asserted to agree.
//!
//! # Units
//! `theirs` in the file's unit; `ours` and `theirs_in_ours` in `ours_unit`.

use serde::{Deserialize, Serialize};

use super::iso230_4::CircularTest;
use super::trace_import::Direction;
use crate::trace::b5r::{B5rFeature, B5rReport};

/// One feature of the file beside ours.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct Beside {
    /// Where the file reports it: the analysis's name, or `run CW` (`run`
    /// for a run without a direction).
    pub source: String,
    /// The feature's `NAME`, e.g. `AF_SQUARENESS`.
    pub feature: String,
    /// The file's value as written.
    pub theirs: f64,
    /// Its unit (None for an unknown unit code).
    pub theirs_unit: Option<String>,
    /// Our value, None where we compute none (or not for this trace).
    pub ours: Option<f64>,
    /// Our unit ("" where we compute none).
    pub ours_unit: String,
    /// The file's value in our unit, where the units are the same quantity.
    pub theirs_in_ours: Option<f64>,
    /// 1-based line of the feature in the file.
    pub line: usize,
}

/// The factor from the file's unit to ours, for units of one quantity.
fn factor(theirs: Option<&str>, ours: &str) -> Option<f64> {
    match (theirs?, ours) {
        ("mm", "µm") => Some(1000.0),
        ("µm", "µm") | ("µm/m", "µrad") | ("ms", "ms") | ("ppm", "ppm") => Some(1.0),
        _ => None,
    }
}

/// Our value and unit for feature `name`; `run`: the direction of the
/// file's run holding it, None for an analysis's feature.
fn ours(name: &str, run: Option<Direction>, t: &CircularTest) -> (Option<f64>, &'static str) {
    let n = name.to_ascii_uppercase();
    let d = t.diagnostics.as_ref();
    let axis = |x: f64, y: f64| {
        if n.contains("_A_") || n.ends_with("_A") {
            Some(x)
        } else if n.contains("_B_") || n.ends_with("_B") {
            Some(y)
        } else {
            None
        }
    };
    if n == "AF_CIRCULARITY" {
        let g = match run {
            Some(dir) => t.runs.iter().find(|r| r.direction == dir).map(|r| r.g_um),
            None => t.runs.iter().map(|r| r.g_um).reduce(f64::max),
        };
        return (g, "µm");
    }
    if n == "AF_SQUARENESS" {
        return (d.map(|d| d.squareness_urad), "µrad");
    }
    if n == "AF_SERVO_MISMATCH" {
        return (d.and_then(|d| d.servo_mismatch_ms), "ms");
    }
    if n == "AF_SCALE_MISMATCH" {
        return (d.map(|d| d.scale_mismatch_ppm), "ppm");
    }
    if n.starts_with("AF_BACKLASH_") {
        return (d.and_then(|d| axis(d.backlash_x_um, d.backlash_y_um)), "µm");
    }
    if n.starts_with("AF_CYCLIC_ERROR_") {
        let c = d.and_then(|d| d.cyclic);
        return (
            c.and_then(|c| axis(c.amplitude_x_um, c.amplitude_y_um)),
            "µm",
        );
    }
    (None, "")
}

fn row(source: &str, f: &B5rFeature, run: Option<Direction>, t: &CircularTest) -> Beside {
    let (ours, unit) = ours(&f.name, run, t);
    let theirs_in_ours = (!unit.is_empty())
        .then(|| factor(f.unit.as_deref(), unit))
        .flatten()
        .map(|k| f.value * k);
    Beside {
        source: source.to_string(),
        feature: f.name.clone(),
        theirs: f.value,
        theirs_unit: f.unit.clone(),
        ours,
        ours_unit: unit.to_string(),
        theirs_in_ours,
        line: f.line,
    }
}

/// Every feature of `report`, runs first then analyses, in file order,
/// beside our value from `ours` (see the module's pairing).
///
/// # Examples
/// ```
/// use mtmotion::ballbar::{b5r_beside::beside, circular_test, synthetic_trace, SyntheticConfig};
/// use mtmotion::trace::b5r::read;
/// let t = circular_test(&synthetic_trace(&SyntheticConfig::default()).unwrap()).unwrap();
/// let r = read(r#"<TEST_DOCUMENT><ANALYSIS NAME="RENISHAW_DIAGNOSTICS">
/// <FEATURE NAME="AF_SQUARENESS" DT="UT_SQUARENESS">-12</FEATURE></ANALYSIS></TEST_DOCUMENT>"#).unwrap();
/// let b = beside(&r, &t);
/// assert_eq!((b[0].theirs_in_ours, b[0].ours_unit.as_str()), (Some(-12.0), "µrad"));
/// assert_eq!(b[0].ours, Some(t.diagnostics.unwrap().squareness_urad));
/// ```
pub fn beside(report: &B5rReport, ours: &CircularTest) -> Vec<Beside> {
    let mut rows = Vec::new();
    for r in &report.runs {
        let dir = match r.direction.trim().to_ascii_uppercase().as_str() {
            "CW" => Some(Direction::Cw),
            "CCW" => Some(Direction::Ccw),
            _ => None,
        };
        let source = format!("run {}", r.direction.trim()).trim_end().to_string();
        for f in &r.features {
            // a run of unknown direction pairs with none of ours
            let row = match dir {
                Some(d) => row(&source, f, Some(d), ours),
                None => Beside {
                    ours: None,
                    ..row(&source, f, None, ours)
                },
            };
            rows.push(row);
        }
    }
    for a in &report.analyses {
        for f in &a.features {
            rows.push(row(&a.name, f, None, ours));
        }
    }
    rows
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ballbar::{circular_test, synthetic_trace, SyntheticConfig};
    use crate::trace::b5r::read;

    #[test]
    fn a_run_of_unknown_direction_pairs_with_none_and_ppm_stays_ppm() {
        let ours = circular_test(&synthetic_trace(&SyntheticConfig::default()).unwrap()).unwrap();
        let r = read(
            r#"<TEST_DOCUMENT><RUN_RESULTS>
<BALLBAR_RUN><RUN_DIRECTION>UP</RUN_DIRECTION><FEATURE NAME="AF_CIRCULARITY" DT="UT_LENGTH_MM">0.01</FEATURE></BALLBAR_RUN>
<BALLBAR_RUN><FEATURE NAME="AF_CIRCULARITY" DT="UT_LENGTH_UM">12</FEATURE></BALLBAR_RUN>
</RUN_RESULTS><ANALYSIS NAME="X">
<FEATURE NAME="af_scale_mismatch" DT="UT_SCALE_ERROR">-3</FEATURE>
<FEATURE NAME="AF_BACKLASH_B" DT="UT_LENGTH_UM">2</FEATURE>
</ANALYSIS></TEST_DOCUMENT>"#,
        )
        .unwrap();
        let b = beside(&r, &ours);
        let d = ours.diagnostics.unwrap();
        // a run of no known direction: the file's value in our unit, ours none
        assert_eq!((b[0].source.as_str(), b[0].ours), ("run UP", None));
        assert_eq!(
            (b[0].theirs_in_ours, b[0].ours_unit.as_str()),
            (Some(10.0), "µm")
        );
        assert_eq!((b[1].source.as_str(), b[1].ours), ("run", None));
        // names in any case; ppm to ppm; a name ending in the axis letter
        assert_eq!(
            (b[2].ours, b[2].theirs_in_ours),
            (Some(d.scale_mismatch_ppm), Some(-3.0))
        );
        assert_eq!((b[3].ours, b[3].line), (Some(d.backlash_y_um), 6));
    }
}
