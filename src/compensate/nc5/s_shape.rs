//! Parametric ISO 10791-7 S-shape test piece (thasana §II-C, Figs. 3–4)
//! and its 5-axis flank-milling program with 64 evaluation points.
//!
//! The S part is a ruled surface between an upper and a lower S curve.
//! Readings chosen (the paper gives only the 15 % scaling and the two
//! measuring planes): full-size length 300 mm, S amplitude 60 mm and
//! height 80 mm, so at 15 % the part is 45 mm long and the measuring planes
//! are Z = 0 and Z = −12 mm. Upper curve `y = A·sin(2π s)`, lower curve
//! `y = A·sin(2π s + τ)` with a 20° twist `τ`, shifted in x by
//! `H/4·cos(2π s)` (so the rules lean both ways: the "open–close angle
//! conversion and twist" of the test piece, with A and B both moving),
//! `x = L(s − ½)`. The tool axis
//! is the rule line from the lower to the upper curve. The 64 evaluation
//! points are 32 equally spaced in `s` on each plane; the program visits
//! them with the tool tip (32 at Z = 0, then 32 at Z = −12).
//!
//! Units: mm, degrees in the program.

use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

use crate::kinematics::inverse::limits_from_degrees;
use crate::kinematics::{inverse, q_to_degrees, KinematicsError, Pose, Solution};
use crate::machine::MachineRef;
use crate::nc::writer::fmt_num;

fn scale_default() -> f64 {
    0.15
}
fn feed_default() -> f64 {
    200.0
}

/// S-shape options.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase", deny_unknown_fields)]
pub struct SShapeOptions {
    /// Machine for the program.
    pub machine: MachineRef,
    /// Scale of the full-size part (paper: 0.15).
    #[serde(default = "scale_default")]
    pub scale: f64,
    /// Tool length, mm.
    #[serde(default)]
    pub tool_length: f64,
    /// Part origin in the workpiece frame, mm.
    #[serde(default)]
    pub origin: [f64; 3],
    /// Feed, mm/min (paper: 200).
    #[serde(default = "feed_default")]
    pub feed: f64,
}

impl SShapeOptions {
    /// thasana §II-D's test piece: 15 % scale, F200, no tool length, part
    /// origin at the workpiece origin.
    pub fn paper(machine: MachineRef) -> Self {
        Self {
            machine,
            scale: scale_default(),
            tool_length: 0.0,
            origin: [0.0; 3],
            feed: feed_default(),
        }
    }
}

/// The test piece's evaluation points and program.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct SShape {
    /// Tool-tip targets `[x, y, z]`, mm (64).
    pub points: Vec<[f64; 3]>,
    /// Tool axes (64).
    pub axes: Vec<[f64; 3]>,
    /// The NC program.
    pub nc: String,
}

/// Lowest feed of the program, mm/min: it is written with 4 decimals.
pub const MIN_FEED: f64 = 1e-3;
/// Highest feed, mm/min (1 km/min).
pub const MAX_FEED: f64 = 1e6;
/// Largest |origin| or tool length, mm (100 m: beyond any machine).
pub const MAX_LENGTH: f64 = 1e5;

/// Builds the S part and its program.
///
/// # Units
/// mm; program in mm and degrees.
///
/// # Examples
/// ```
/// use mtmotion::compensate::nc5::s_shape::{s_shape, SShapeOptions};
/// use mtmotion::machine::MachineRef;
/// let s = s_shape(&SShapeOptions::paper(MachineRef::Name("pocketnc-v2-10".into()))).unwrap();
/// assert_eq!(s.points.len(), 64);
/// assert_eq!(s.points.iter().filter(|p| p[2].abs() < 1e-12).count(), 32);
/// assert_eq!(s.points.iter().filter(|p| (p[2] + 12.0).abs() < 1e-12).count(), 32);
/// assert_eq!(s.nc.lines().filter(|l| l.starts_with("G1") || l.starts_with("G0 X")).count(), 64);
/// ```
pub fn s_shape(o: &SShapeOptions) -> Result<SShape, KinematicsError> {
    validate(o)?;
    let (machine, chain) = o.machine.resolve().map_err(|e| KinematicsError::BadInput {
        field: "machine".into(),
        why: e.to_string(),
    })?;
    let (points, axes) = targets(o);
    let limits = limits_from_degrees(&machine.limits);
    let present = chain.axes();
    let mut nc =
        String::from("%\n(ISO 10791-7 S-shape, 64 evaluation points, mtmotion)\nG90 G21 G17\n");
    let mut prev: Option<[f64; 6]> = None;
    for (n, (p, k)) in points.iter().zip(&axes).enumerate() {
        let sols = inverse(
            &chain,
            &Pose {
                position: *p,
                orientation: *k,
            },
            o.tool_length,
            &limits,
        )?;
        let best = nearest_solution(&sols, prev).ok_or_else(|| {
            KinematicsError::Unreachable(format!(
                "S-shape point {} is outside the limits of {}; move `origin`",
                n + 1,
                machine.name
            ))
        })?;
        prev = Some(best.q);
        nc.push_str(&block(n, &best.q, &present, o.feed));
        nc.push('\n');
    }
    nc.push_str("M30\n%\n");
    Ok(SShape { points, axes, nc })
}

/// Checks the scale, the feed, the tool length and the origin.
fn validate(o: &SShapeOptions) -> Result<(), KinematicsError> {
    if !(o.scale.is_finite() && o.scale > 0.0 && o.scale <= 2.0) {
        return Err(KinematicsError::BadInput {
            field: "scale".into(),
            why: "must be in (0, 2]".into(),
        });
    }
    // The program writes F with 4 decimals: a feed below 0.001 would read
    // "F0." and one of 1e308 would be written with 309 digits.
    if !(o.feed.is_finite() && (MIN_FEED..=MAX_FEED).contains(&o.feed)) {
        return Err(KinematicsError::BadInput {
            field: "feed".into(),
            why: format!(
                "must be from 0.001 to 1e6 mm/min, got {}",
                crate::numeric::compact(o.feed)
            ),
        });
    }
    for (field, v) in [
        ("toolLength", o.tool_length),
        ("origin[0]", o.origin[0]),
        ("origin[1]", o.origin[1]),
        ("origin[2]", o.origin[2]),
    ] {
        if !(v.is_finite() && v.abs() <= MAX_LENGTH) {
            return Err(KinematicsError::BadInput {
                field: field.into(),
                why: format!(
                    "must be a length within ±1e5 mm, got {}",
                    crate::numeric::compact(v)
                ),
            });
        }
    }
    Ok(())
}

/// The within-limits solution whose rotary axes (A, B, C) move least from
/// `prev` (the previous point's joints), or lie nearest zero for the first
/// point; the first of equals wins.
fn nearest_solution(sols: &[Solution], prev: Option<[f64; 6]>) -> Option<&Solution> {
    sols.iter().filter(|s| s.within_limits).min_by(|a, b| {
        let d = |s: &Solution| match prev {
            Some(q) => (3..6).map(|i| (s.q[i] - q[i]).abs()).sum::<f64>(),
            None => (3..6).map(|i| s.q[i].abs()).sum::<f64>(),
        };
        d(a).total_cmp(&d(b))
    })
}

/// The block (without newline) moving to joints `q` for point `n`
/// (0-based): a G0 to the first, G1 to the others, the words of the
/// `present` axes only, and the feed on the first G1.
fn block(n: usize, q: &[f64; 6], present: &[&str], feed: f64) -> String {
    let qd = q_to_degrees(q);
    let mut line = if n == 0 {
        "G0".to_string()
    } else {
        "G1".to_string()
    };
    for (i, a) in ["X", "Y", "Z", "A", "B", "C"].iter().enumerate() {
        if present.contains(&crate::kinematics::AXES[i]) {
            line.push_str(&format!(" {a}{}", fmt_num(qd[i])));
        }
    }
    if n == 1 {
        line.push_str(&format!(" F{}", fmt_num(feed)));
    }
    line
}

/// The 64 tool-tip targets (32 on the upper S curve, then 32 on the lower,
/// mm) and the tool axis of each (the ruling from the lower to the upper
/// curve): a 300 × 60 × 80 mm part at `scale`, the lower curve twisted 20°.
fn targets(o: &SShapeOptions) -> (Vec<[f64; 3]>, Vec<[f64; 3]>) {
    let (len, amp, height) = (300.0 * o.scale, 60.0 * o.scale, 80.0 * o.scale);
    let twist = 20f64.to_radians();
    let org = Vector3::from(o.origin);
    let upper = |s: f64| {
        org + Vector3::new(
            len * (s - 0.5),
            amp * (std::f64::consts::TAU * s).sin(),
            0.0,
        )
    };
    let lower = |s: f64| {
        org + Vector3::new(
            len * (s - 0.5) + 0.25 * height * (std::f64::consts::TAU * s).cos(),
            amp * (std::f64::consts::TAU * s + twist).sin(),
            -height,
        )
    };
    let mut points = Vec::with_capacity(64);
    let mut axes = Vec::with_capacity(64);
    for level in 0..2 {
        for i in 0..32 {
            let s = (i as f64 + 0.5) / 32.0;
            let (u, l) = (upper(s), lower(s));
            let axis = (u - l).normalize();
            points.push(if level == 0 { u } else { l }.into());
            axes.push(axis.into());
        }
    }
    (points, axes)
}
