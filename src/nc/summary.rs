//! The summary a user checks first, before simulating: bounding box, path
//! length, counts of arcs, lines, rapids and dwells, units and planes used,
//! an estimated motion time, the warnings grouped by kind, and the
//! cutter-compensation stretches with the radius each used (or none: the
//! programmed path).
//!
//! Motion time (estimate, no acc/dec): Σ length/feed over cutting moves,
//! Σ length/rapid rate over rapids, plus the dwells. With the tool-path
//! model's acc/dec and servo lag off (tA = 0, T = 0) its simulated motion
//! time equals this sum; with them on it is longer by roughly tA + T per
//! stop. The bounding box covers arcs exactly: the start, the end and every
//! axis-extreme point (centre ± r along each plane axis) the sweep passes.
//!
//! Units: mm, s; `units` reports what the program was written in.

use serde::Serialize;

use super::program::{Arc, CutterStretch, Motion, Program, Segment, Warning};

/// Warnings of one kind.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct WarningGroup {
    /// The kind: the message's leading code or phrase (e.g. `G54`, `M6`,
    /// `block delete`, `unknown word`, `cutter compensation`).
    pub kind: String,
    /// How many warnings of this kind.
    pub count: usize,
    /// Their 1-based lines, in order.
    pub lines: Vec<usize>,
    /// Their indices in the program's warning list.
    pub indices: Vec<usize>,
}

/// Program summary.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct Summary {
    /// Lower corner of the XYZ bounding box of every move, mm (`None` for a
    /// program without motion).
    pub bbox_min: Option<[f64; 3]>,
    /// Upper corner, mm.
    pub bbox_max: Option<[f64; 3]>,
    /// XYZ length of all moves, mm.
    pub total_length: f64,
    /// XYZ length of cutting moves (G1–G3), mm.
    pub cutting_length: f64,
    /// Number of arcs, lines, rapids and dwells.
    pub arcs: usize,
    /// G1 lines.
    pub lines: usize,
    /// G0 rapids.
    pub rapids: usize,
    /// G4 dwells.
    pub dwells: usize,
    /// `"mm"`, `"inch"` or `"mm and inch"`.
    pub units: String,
    /// Planes of the arcs, e.g. `["XY", "ZX"]`.
    pub planes: Vec<String>,
    /// Estimated motion time without acc/dec, s.
    pub motion_time: f64,
    /// The rapid rate the estimate used, mm/min.
    pub rapid_feed: f64,
    /// Warnings grouped by kind, in order of first appearance.
    pub warnings: Vec<WarningGroup>,
    /// The cutter-compensation stretches (G41/G42 … G40): where each starts
    /// and the tool radius its offset path used (`None`: the simulated
    /// path is the programmed path, warned).
    pub cutter_compensation: Vec<CutterStretch>,
}

/// The kind of a warning message (see [`WarningGroup::kind`]).
pub fn warning_kind(message: &str) -> String {
    let phrases = [
        "block delete",
        "unknown word",
        "work offset",
        "blocks after the program end",
        "cutter compensation",
    ];
    if let Some(p) = phrases.iter().find(|p| message.starts_with(*p)) {
        return (*p).to_string();
    }
    let code: String = message
        .chars()
        .take_while(|c| c.is_ascii_alphanumeric() || *c == '.')
        .collect();
    let letter = code.chars().next().unwrap_or(' ');
    if matches!(letter, 'G' | 'M') && code.len() > 1 {
        code
    } else if matches!(letter, 'S' | 'T' | 'H' | 'D' | 'F') && code.len() > 1 {
        letter.to_string()
    } else {
        message.split(':').next().unwrap_or(message).to_string()
    }
}

/// Summarises `p`; `rapid_feed` is the machine's rapid rate, mm/min.
///
/// # Examples
/// ```
/// use mtmotion::nc::{program::parse, summary::summarize};
/// let p = parse("G0 X10 Y10\nG2 X10 Y-10 I0 J-10 F600\nG1 X0\nG4 P0.5").unwrap();
/// let s = summarize(&p, 6000.0);
/// assert_eq!((s.rapids, s.lines, s.arcs, s.dwells), (1, 1, 1, 1));
/// // The half circle bulges to X = 20 although no end point is there.
/// assert_eq!(s.bbox_max.unwrap()[0], 20.0);
/// assert_eq!(s.bbox_min.unwrap()[1], -10.0);
/// let t = 14.142135623730951 / 6000.0 * 60.0 + (10.0 * std::f64::consts::PI + 10.0) / 600.0 * 60.0 + 0.5;
/// assert!((s.motion_time - t).abs() < 1e-12);
/// ```
pub fn summarize(p: &Program, rapid_feed: f64) -> Summary {
    let mut t = Tally::new();
    for s in &p.segments {
        t.add(s, rapid_feed);
    }
    let has_box = t.lo[0].is_finite();
    Summary {
        bbox_min: has_box.then_some(t.lo),
        bbox_max: has_box.then_some(t.hi),
        total_length: t.total,
        cutting_length: t.cutting,
        arcs: t.arcs,
        lines: t.lines,
        rapids: t.rapids,
        dwells: t.dwells,
        units: units(p).into(),
        planes: t.planes,
        motion_time: t.time,
        rapid_feed,
        warnings: group_warnings(&p.warnings),
        cutter_compensation: p.cutter.clone(),
    }
}

/// The sums over a program's segments, in order.
struct Tally {
    /// Lower corner of the XYZ bounding box, mm (∞ while empty).
    lo: [f64; 3],
    /// Upper corner, mm (−∞ while empty).
    hi: [f64; 3],
    /// XYZ length of all moves, mm.
    total: f64,
    /// XYZ length of cutting moves, mm.
    cutting: f64,
    /// Motion time, s.
    time: f64,
    arcs: usize,
    lines: usize,
    rapids: usize,
    dwells: usize,
    /// Arc planes, in order of first use.
    planes: Vec<String>,
}

impl Tally {
    fn new() -> Self {
        Self {
            lo: [f64::INFINITY; 3],
            hi: [f64::NEG_INFINITY; 3],
            total: 0.0,
            cutting: 0.0,
            time: 0.0,
            arcs: 0,
            lines: 0,
            rapids: 0,
            dwells: 0,
            planes: Vec::new(),
        }
    }

    /// Widens the bounding box to hold `q`.
    fn grow(&mut self, q: [f64; 3]) {
        for (k, &x) in q.iter().enumerate() {
            self.lo[k] = self.lo[k].min(x);
            self.hi[k] = self.hi[k].max(x);
        }
    }

    /// Counts segment `s` (`rapid_feed`: mm/min).
    fn add(&mut self, s: &Segment, rapid_feed: f64) {
        let len = s.length();
        match s.motion {
            Motion::Dwell { seconds } => {
                self.dwells += 1;
                self.time += seconds;
                return;
            }
            Motion::Rapid => {
                self.rapids += 1;
                if rapid_feed > 0.0 {
                    self.time += len / rapid_feed * 60.0;
                }
            }
            Motion::Linear => self.lines += 1,
            Motion::Arc(a) => {
                self.arcs += 1;
                let name = format!("{:?}", a.plane);
                if !self.planes.contains(&name) {
                    self.planes.push(name);
                }
                self.arc_extremes(s, &a);
            }
        }
        if !matches!(s.motion, Motion::Rapid) {
            self.cutting += len;
            if s.feed > 0.0 {
                self.time += len / s.feed * 60.0;
            }
        }
        self.total += len;
        self.grow(s.start.p());
        self.grow(s.end.p());
    }

    /// Widens the box to the arc's axis-extreme points (centre ± r along
    /// each plane axis) that its sweep passes.
    fn arc_extremes(&mut self, s: &Segment, a: &Arc) {
        let (u, v, _) = a.plane.axes();
        let p0 = s.start.p();
        let a0 = (p0[v] - a.center[v]).atan2(p0[u] - a.center[u]);
        for q in 0..4 {
            let ang = q as f64 * std::f64::consts::FRAC_PI_2;
            // Is `ang` inside the sweep from a0?
            let rel = if a.sweep >= 0.0 {
                (ang - a0).rem_euclid(std::f64::consts::TAU)
            } else {
                (a0 - ang).rem_euclid(std::f64::consts::TAU)
            };
            if rel <= a.sweep.abs() {
                let mut pt = p0;
                pt[u] = a.center[u] + a.radius * ang.cos();
                pt[v] = a.center[v] + a.radius * ang.sin();
                self.grow(pt);
            }
        }
    }
}

/// The units the program was written in: "mm", "inch" or "mm and inch",
/// from the units in force where it moves (a G20 after the first block
/// does not make an inch program "mm and inch"); with no move, the units
/// at its end.
fn units(p: &Program) -> &'static str {
    let [mm, inch] = if p.moved_units.iter().any(|&u| u) {
        p.moved_units
    } else {
        let inch = p.modal.last().is_some_and(|m| m.inch);
        [!inch, inch]
    };
    match (mm, inch) {
        (true, true) => "mm and inch",
        (false, true) => "inch",
        _ => "mm",
    }
}

/// The warnings grouped by kind ([`warning_kind`]), in order of first
/// appearance.
fn group_warnings(warnings: &[Warning]) -> Vec<WarningGroup> {
    let mut groups: Vec<WarningGroup> = Vec::new();
    for (i, w) in warnings.iter().enumerate() {
        let kind = warning_kind(&w.message);
        match groups.iter_mut().find(|g| g.kind == kind) {
            Some(g) => {
                g.count += 1;
                g.lines.push(w.line);
                g.indices.push(i);
            }
            None => groups.push(WarningGroup {
                kind,
                count: 1,
                lines: vec![w.line],
                indices: vec![i],
            }),
        }
    }
    groups
}
