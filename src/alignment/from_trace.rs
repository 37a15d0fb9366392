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
    // bytes and lines over every trace together, not each on its own
    crate::budget::check_trace_texts("alignment traces", traces.iter().map(|t| t.text.as_str()))?;
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
            let t = parse_ballbar_trace(&ts.text, opts.clone())
                .map_err(|e| bad(&what, e.to_string()))?;
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

#[cfg(test)]
mod tests {
    use super::*;

    /// An X/Y arc (mm) about `(cx, cy)` + offset, R 80.004 mm (a bar
    /// 4 µm longer than its nominal 80), 200° from 40°, CCW then back CW
    /// (two runs).
    fn xy(cx: f64, cy: f64, dx: f64, dy: f64) -> String {
        let mut s = String::from("X [mm];Y [mm]\n");
        let pts = (0..=200).chain((0..200).rev());
        for i in pts {
            let a = (40.0 + i as f64).to_radians();
            s += &format!(
                "{:.7};{:.7}\n",
                cx + dx + 80.004 * a.cos(),
                cy + dy + 80.004 * a.sin()
            );
        }
        s
    }

    #[test]
    fn xy_sections_keep_their_offsets_about_the_common_centre() {
        let ts = [
            TraceSection {
                y: 60.0,
                text: xy(-20.0, 7.5, 0.012, -0.003),
                run: 0,
            },
            TraceSection {
                y: 260.0,
                text: xy(-20.0, 7.5, 0.002, 0.005),
                run: 1,
            },
        ];
        let c = Some(PlanePoint { x: -20.0, y: 7.5 });
        let s = sections_from_traces(&ts, 80.0, c).unwrap();
        assert_eq!((s.len(), s[0].y, s[1].y), (2, 60.0, 260.0));
        // Degrees, about the centre, from the first plane axis.
        assert!(
            (s[0].angle_deg[0] - 40.0).abs() < 0.01,
            "{}",
            s[0].angle_deg[0]
        );
        // Run 1 is the CW run: its angles fall.
        assert!(s[1].angle_deg[0] > s[1].angle_deg[5]);
        // The deviation about the given centre from the given bar length:
        // Δ(θ) ≈ 4 µm + e·u(θ) (second order 1.6 nm).
        let d_at = |k: usize, i: usize, (ex, ey): (f64, f64)| {
            let t = s[k].angle_deg[i].to_radians();
            (s[k].deviation[i] - 0.004 - ex * t.cos() - ey * t.sin()).abs()
        };
        for i in [0, 50, 150, 199] {
            assert!(
                d_at(0, i, (0.012, -0.003)) < 5e-6,
                "run 0 sample {i}: {} at {}",
                s[0].deviation[i],
                s[0].angle_deg[i]
            );
            assert!(d_at(1, i, (0.002, 0.005)) < 5e-6, "run 1 sample {i}");
        }
    }

    #[test]
    fn bad_sections_are_named() {
        let t = TraceSection {
            y: 1.0,
            text: xy(0.0, 0.0, 0.0, 0.0),
            run: 2,
        };
        let c = Some(PlanePoint { x: 0.0, y: 0.0 });
        let e = sections_from_traces(std::slice::from_ref(&t), 80.0, c).unwrap_err();
        assert_eq!(
            e.to_string(),
            "sections[0].run: the file has 2 run(s) (0 … 1), not run 2"
        );
        let bad = TraceSection {
            y: 1.0,
            text: "x,y\n1,2\n3,oops\n".into(),
            run: 0,
        };
        let good = TraceSection {
            run: 1,
            ..t.clone()
        };
        let e = sections_from_traces(&[good, bad], 80.0, c)
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("sections[1]: line 3"), "{e}");
        let e = sections_from_traces(&[t], 80.0, None)
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("sections[0]: an X/Y trace needs the common centre"),
            "{e}"
        );
    }
}
