//! Alignment sections from the user's own ball-bar trace files
//! (takayama-alignment-travel-range §2.2, Fig. 2: one trace per section).
//!
//! Reading chosen: the method exists to find the offset of the rotary
//! axis's centre, so every section's deviation must be taken about one
//! common, stated centre. An angle/deviation trace is already about the
//! bar's pivot. An X/Y trace is read about the centre the user gives (the
//! pivot, or the programmed circle centre), never about its own fitted
//! circle, which would remove exactly the offset sought: an X/Y trace
//! without a centre is refused, saying so. The trace's first plane axis is
//! the section's first axis (Z for a B axis), its angle measured from it.
//!
//! Units: mm (heights, centre, radius), the trace's own units at the input
//! (converted by [`crate::ballbar::parse_ballbar_trace`]).

use serde::{Deserialize, Serialize};

use super::angle::Section;
use super::travel_range::{bad, AlignmentError};
use crate::ballbar::{parse_ballbar_trace, ParseOptions, PlanePoint};

/// One section given as a trace file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TraceSection {
    /// Section position (height along the axis), mm.
    pub y: f64,
    /// The trace file's text (CSV/TSV: angle + deviation, or X/Y).
    pub text: String,
    /// Which run of the file (0-based; a file may hold CCW and CW runs).
    #[serde(default)]
    pub run: usize,
}

/// Reads every section's trace about the common `centre` (needed for X/Y
/// traces) with the bar length `radius`.
///
/// # Units
/// mm; angles come out in degrees, deviations in mm.
///
/// # Errors
/// [`AlignmentError::BadField`] naming `sections[k]` with the trace's own
/// message (line and column), an X/Y trace without `centre`, or a `run`
/// the file does not have.
///
/// # Examples
/// ```
/// use mtmotion::alignment::from_trace::{sections_from_traces, TraceSection};
/// use mtmotion::ballbar::PlanePoint;
/// // An X/Y arc about (300.004, 50) read about the programmed centre (300, 50).
/// let mut text = String::from("x,y\n");
/// for i in 0..=180 {
///     let a = (i as f64 - 90.0).to_radians();
///     text += &format!("{},{}\n", 300.004 + 100.0 * a.cos(), 50.0 + 100.0 * a.sin());
/// }
/// let s = vec![TraceSection { y: 120.0, text: text.clone(), run: 0 }];
/// let c = Some(PlanePoint { x: 300.0, y: 50.0 });
/// let secs = sections_from_traces(&s, 100.0, c).unwrap();
/// assert!((secs[0].deviation[90] - 0.004).abs() < 1e-9); // the offset stays
/// let e = sections_from_traces(&s, 100.0, None).unwrap_err().to_string();
/// assert!(e.starts_with("sections[0]: an X/Y trace needs the common centre"));
/// ```
pub fn sections_from_traces(
    traces: &[TraceSection],
    radius: f64,
    centre: Option<PlanePoint>,
) -> Result<Vec<Section>, AlignmentError> {
    let total: u64 = traces.iter().map(|t| t.text.len() as u64).sum();
    crate::budget::check_bytes("alignment traces", total)?;
    let opts = ParseOptions {
        nominal_radius: Some(radius),
        centre,
        ..ParseOptions::default()
    };
    traces
        .iter()
        .enumerate()
        .map(|(k, ts)| {
            let what = format!("sections[{k}]");
            let t = parse_ballbar_trace(&ts.text, opts).map_err(|e| bad(&what, e.to_string()))?;
            if t.centre.is_some_and(|c| !c.given) {
                return Err(bad(
                    what,
                    "an X/Y trace needs the common centre (the bar's pivot or the programmed \
                     circle centre, in the trace's X/Y coordinates): fitting each section's own \
                     circle would remove the very offset being estimated",
                ));
            }
            let n = t.runs.len();
            let run = t.runs.get(ts.run).ok_or_else(|| {
                bad(
                    format!("{what}.run"),
                    format!(
                        "the file has {n} run(s) (0 … {}), not run {}",
                        n - 1,
                        ts.run
                    ),
                )
            })?;
            Ok(Section {
                y: ts.y,
                angle_deg: run.angle.iter().map(|a| a.to_degrees()).collect(),
                deviation: run.deviation.clone(),
            })
        })
        .collect()
}
