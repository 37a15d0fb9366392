//! Geometry types of an interpreted NC program: [`Pose`] (X Y Z in mm,
//! A B C in degrees), [`Plane`], [`MotionCode`], [`Arc`], [`Motion`] and
//! [`Segment`], with the segment's length and its point at a fraction of
//! its length. Re-exported by [`crate::nc::program`]; see there for how
//! they are produced.
//!
//! Arc reading: the sweep is signed about the plane normal (G17 +Z, G18 +Y,
//! G19 +X; CCW positive, as seen from the positive normal); a helical arc
//! moves the normal axis linearly with the angle.
//!
//! Units: mm, degrees (A/B/C), rad (sweep), mm/min (feed).

use serde::{Deserialize, Serialize};

/// Axis letters in [`Pose::get`] order.
pub const AXES: [char; 6] = ['X', 'Y', 'Z', 'A', 'B', 'C'];

/// Tool position: X, Y, Z in mm, A, B, C in degrees.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct Pose {
    /// X, mm.
    pub x: f64,
    /// Y, mm.
    pub y: f64,
    /// Z, mm.
    pub z: f64,
    /// A, degrees.
    pub a: f64,
    /// B, degrees.
    pub b: f64,
    /// C, degrees.
    pub c: f64,
}

impl Pose {
    /// A pose at `x`, `y`, `z` with the rotary axes at zero.
    pub fn xyz(x: f64, y: f64, z: f64) -> Self {
        Self {
            x,
            y,
            z,
            ..Self::default()
        }
    }
    /// Axis `i` in [`AXES`] order (0 = X … 5 = C); out-of-range gives C.
    pub fn get(&self, i: usize) -> f64 {
        self.to_array()[i.min(5)]
    }
    /// Sets axis `i` in [`AXES`] order; out-of-range indices are ignored.
    pub fn set(&mut self, i: usize, v: f64) {
        let mut a = self.to_array();
        if let Some(slot) = a.get_mut(i) {
            *slot = v;
        }
        *self = Self::from_array(a);
    }
    /// `[x, y, z, a, b, c]`.
    pub fn to_array(&self) -> [f64; 6] {
        [self.x, self.y, self.z, self.a, self.b, self.c]
    }
    /// From `[x, y, z, a, b, c]`.
    pub fn from_array(a: [f64; 6]) -> Self {
        Self {
            x: a[0],
            y: a[1],
            z: a[2],
            a: a[3],
            b: a[4],
            c: a[5],
        }
    }
    /// `[x, y, z]`, mm.
    pub fn p(&self) -> [f64; 3] {
        [self.x, self.y, self.z]
    }
}

/// Arc plane.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum Plane {
    /// G17: XY, normal +Z.
    #[default]
    XY,
    /// G18: ZX, normal +Y.
    ZX,
    /// G19: YZ, normal +X.
    YZ,
}

impl Plane {
    /// Indices (u, v, normal) into `[x, y, z]`; u → v is counter-clockwise
    /// seen from the positive normal.
    pub fn axes(self) -> (usize, usize, usize) {
        match self {
            Plane::XY => (0, 1, 2),
            Plane::ZX => (2, 0, 1),
            Plane::YZ => (1, 2, 0),
        }
    }
    /// The G code number (17, 18, 19).
    pub fn code(self) -> u32 {
        match self {
            Plane::XY => 17,
            Plane::ZX => 18,
            Plane::YZ => 19,
        }
    }
}

/// Modal motion code.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum MotionCode {
    /// G0.
    Rapid,
    /// G1.
    Linear,
    /// G2.
    Cw,
    /// G3.
    Ccw,
}

impl MotionCode {
    /// The G code number (0–3).
    pub fn code(self) -> u32 {
        match self {
            MotionCode::Rapid => 0,
            MotionCode::Linear => 1,
            MotionCode::Cw => 2,
            MotionCode::Ccw => 3,
        }
    }
}

/// A circular (or helical) arc.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct Arc {
    /// Centre `[x, y, z]`, mm; its normal coordinate is the start's.
    pub center: [f64; 3],
    /// Radius, mm.
    pub radius: f64,
    /// Plane.
    pub plane: Plane,
    /// Signed sweep, rad: positive counter-clockwise (G3) about the plane
    /// normal, negative clockwise (G2); ±2π for a full circle.
    pub sweep: f64,
    /// The program gave the centre as R (written back as R).
    pub r_form: bool,
}

/// What a segment does.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "camelCase")]
pub enum Motion {
    /// G0 at the machine's rapid rate.
    Rapid,
    /// G1 straight line.
    Linear,
    /// G2/G3.
    Arc(Arc),
    /// G4: stand still.
    Dwell {
        /// Duration, s.
        seconds: f64,
    },
}

/// One motion segment.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct Segment {
    /// Index into [`crate::nc::program::Program::blocks`]; `None` for a segment a tool inserted.
    pub block: Option<usize>,
    /// 1-based source line (0 for an inserted segment).
    pub line: usize,
    /// What the segment does.
    pub motion: Motion,
    /// Start pose.
    pub start: Pose,
    /// End pose.
    pub end: Pose,
    /// Programmed feed, mm/min (0 for rapids and dwells).
    pub feed: f64,
    /// True when the segment's end point is not written literally, once, in
    /// its source block: a canned-cycle expansion, a subprogram body, a
    /// macro-computed word. A compensation must not move it (its source
    /// words cannot be edited for this one execution only).
    #[serde(default)]
    pub fixed: bool,
}

impl Segment {
    /// The length a feed is read over: the path [`length`](Self::length),
    /// or for a move of the rotary axes only its largest rotary move in
    /// degrees (F is deg/min there; under G93 the block still takes 1/F
    /// minutes).
    pub fn timed_length(&self) -> f64 {
        let l = self.length();
        if l > 0.0 {
            l
        } else {
            (3..6)
                .map(|i| (self.end.get(i) - self.start.get(i)).abs())
                .fold(0.0, f64::max)
        }
    }

    /// XYZ path length, mm (helix length for helical arcs; 0 for dwells).
    ///
    /// # Units
    /// mm.
    ///
    /// # Examples
    /// ```
    /// let p = mtmotion::nc::program::parse("G1 X3 Y4 F100").unwrap();
    /// assert!((p.segments[0].length() - 5.0).abs() < 1e-12);
    /// ```
    pub fn length(&self) -> f64 {
        match self.motion {
            Motion::Dwell { .. } => 0.0,
            Motion::Arc(a) => {
                let (_, _, n) = a.plane.axes();
                let h = self.end.p()[n] - self.start.p()[n];
                (a.radius * a.sweep).hypot(h)
            }
            _ => dist(self.start.p(), self.end.p()),
        }
    }

    /// The XYZ point at fraction `s` ∈ [0, 1] of the segment, mm.
    pub fn point_at(&self, s: f64) -> [f64; 3] {
        let p0 = self.start.p();
        let p1 = self.end.p();
        match self.motion {
            Motion::Arc(a) => {
                let (u, v, n) = a.plane.axes();
                let th0 = (p0[v] - a.center[v]).atan2(p0[u] - a.center[u]);
                let th = th0 + a.sweep * s;
                let mut q = [0.0; 3];
                q[u] = a.center[u] + a.radius * th.cos();
                q[v] = a.center[v] + a.radius * th.sin();
                q[n] = p0[n] + (p1[n] - p0[n]) * s;
                q
            }
            _ => [
                p0[0] + (p1[0] - p0[0]) * s,
                p0[1] + (p1[1] - p0[1]) * s,
                p0[2] + (p1[2] - p0[2]) * s,
            ],
        }
    }

    /// True for G1/G2/G3 (cutting moves).
    pub fn is_cutting(&self) -> bool {
        matches!(self.motion, Motion::Linear | Motion::Arc(_))
    }
}

/// Euclidean distance of two points.
pub fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// Largest |coordinate| of a segment's poses and arc centre: 1e9 mm for
/// X/Y/Z (1,000 km), 1e9° for A/B/C (2.8 million turns). Beyond it a
/// position is no machine's, and written back in mm it needs more
/// characters than an NC number has (an inch X of 2e22 was 5e23 mm).
pub const MAX_COORDINATE: f64 = 1e9;

/// Largest feed, mm/min (1,000 km/min): far above the implausible-feed
/// warning, the limit of what is still a number to write.
pub const MAX_FEED: f64 = 1e9;

impl Segment {
    /// The first of the segment's numbers beyond [`MAX_COORDINATE`] or
    /// [`MAX_FEED`], said in words ("end point X 5.08e23 mm is beyond
    /// ±1e9"), or `None`. Checked for every segment the interpreter
    /// makes, so the words are only formatted for a number out of range.
    pub fn out_of_range(&self) -> Option<String> {
        let beyond = |v: f64, limit: f64| v.is_nan() || v.abs() > limit;
        let say = |what: &str, v: f64, limit: f64| {
            format!(
                "{what} {} is beyond ±{}",
                crate::numeric::compact(v),
                crate::numeric::compact(limit)
            )
        };
        for (pose, which) in [(&self.start, "start"), (&self.end, "end point")] {
            if let Some(i) = (0..AXES.len()).find(|&i| beyond(pose.get(i), MAX_COORDINATE)) {
                let unit = if i < 3 { "mm" } else { "°" };
                let what = format!("{which} {} ({unit})", AXES[i]);
                return Some(say(&what, pose.get(i), MAX_COORDINATE));
            }
        }
        if let Motion::Arc(a) = &self.motion {
            if let Some(&c) = a.center.iter().find(|&&c| beyond(c, MAX_COORDINATE)) {
                return Some(say("arc centre (mm)", c, MAX_COORDINATE));
            }
        }
        beyond(self.feed, MAX_FEED).then(|| say("feed (mm/min)", self.feed, MAX_FEED))
    }
}
