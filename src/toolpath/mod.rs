//! Tool-path motion error from NC linear acc/dec and servo lag
//! (qiu-toolpath-error-reverse-compensation §4-1, §4-2, Eqs. 1–3).
//!
//! The model: every segment of the NC program gives each axis a commanded
//! velocity `f_b(t)` at the programmed feed ([`timeline`]); the NC's linear
//! acc/dec is the moving average of length `tA` (Eq. 1) and each axis servo
//! a first-order lag `T` (Eq. 2) ([`filter`]); the per-segment responses are
//! superposed as the paper does ([`superpose`]), which equals filtering the
//! whole command directly (tested; [`sampler`] is that filter's fast
//! evaluation of the command); the contour error is the exact distance
//! from the simulated point to the commanded lines and arcs ([`contour`]).
//! [`mod@simulate`] ties them together (its per-segment statistics also as
//! [`columns`] for programs of millions of segments); [`locality`] re-simulates only
//! around changed segments (the reach of Eqs. 1–2); [`identify`] is Eq. 3 and the
//! identification of `tA` and `T`; [`example`] holds the built-in test paths
//! that resemble the paper's Fig. 2.
//!
//! Readings: only X, Y, Z are simulated (A/B/C are carried by the
//! interpreter but do not enter the contour error); rapids move at
//! [`SimConfig::rapid_feed`] through the same filters but are excluded from
//! the maximum error; the paper's unpublished special treatment of arcs
//! shorter than `tA` is not reproduced — the moving average handles every
//! segment length uniformly.
//!
//! Units: mm, s, mm/min for feeds.

#![allow(clippy::needless_range_loop)] // per-axis loops index several arrays at once

pub mod bvh;
pub mod columns;
pub mod contour;
pub mod example;
pub mod filter;
pub mod identify;
pub mod locality;
pub mod sampler;
pub mod simulate;
pub mod superpose;
pub mod timeline;

use serde::{Deserialize, Serialize};

pub use columns::SegmentColumns;
pub use simulate::{
    sample_estimate, simulate, simulate_columns, simulate_columns_owned, simulate_program,
    simulate_stats, simulate_text, simulate_thinned, simulate_with_progress, SegmentStats,
    Simulation, WindowStats, PROGRESS_EVERY,
};

/// The servo time constant: one for all axes or one per axis X, Y, Z.
/// Read from a number or an array of three (anything else is refused in
/// those words, not serde's "untagged enum").
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(untagged)]
pub enum Lag {
    /// The same `T` for X, Y, Z, s.
    All(f64),
    /// `[Tx, Ty, Tz]`, s.
    PerAxis([f64; 3]),
}

impl<'de> Deserialize<'de> for Lag {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Either;
        impl<'de> serde::de::Visitor<'de> for Either {
            type Value = Lag;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a time constant in s, or [Tx, Ty, Tz]")
            }
            fn visit_f64<E: serde::de::Error>(self, t: f64) -> Result<Lag, E> {
                Ok(Lag::All(t))
            }
            fn visit_i64<E: serde::de::Error>(self, t: i64) -> Result<Lag, E> {
                Ok(Lag::All(t as f64))
            }
            fn visit_u64<E: serde::de::Error>(self, t: u64) -> Result<Lag, E> {
                Ok(Lag::All(t as f64))
            }
            fn visit_seq<A: serde::de::SeqAccess<'de>>(self, seq: A) -> Result<Lag, A::Error> {
                let t = <[f64; 3]>::deserialize(serde::de::value::SeqAccessDeserializer::new(seq))?;
                Ok(Lag::PerAxis(t))
            }
        }
        d.deserialize_any(Either)
    }
}

impl Lag {
    /// `[Tx, Ty, Tz]`, s.
    pub fn per_axis(self) -> [f64; 3] {
        match self {
            Lag::All(t) => [t; 3],
            Lag::PerAxis(t) => t,
        }
    }
}

/// Simulation settings.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct SimConfig {
    /// Linear acc/dec time constant `tA` (moving-average length), s.
    #[serde(rename = "tA")]
    pub t_a: f64,
    /// Position-loop time constant `T`, s.
    #[serde(rename = "T")]
    pub t: Lag,
    /// Sampling interval, s.
    pub dt: f64,
    /// Rapid traverse rate for G0, mm/min.
    #[serde(rename = "rapidFeed")]
    pub rapid_feed: f64,
    /// Feed override as a fraction (1 = 100 %), applied to cutting feeds.
    #[serde(rename = "feedOverride")]
    pub feed_override: f64,
    /// A G4 dwell starts with an exact stop: the tool waits `tA + 5·max T`
    /// (the command's acc/dec, then the lag decayed to e⁻⁵ ≈ 0.7 %, an
    /// in-position check) before the dwell's own time. Default off: the
    /// dwell adds only its own time (see [`mod@simulate`]).
    #[serde(rename = "dwellExactStop")]
    pub dwell_exact_stop: bool,
}

impl Default for SimConfig {
    fn default() -> Self {
        Self {
            t_a: 0.04,
            t: Lag::All(0.015),
            dt: 0.001,
            rapid_feed: 20_000.0,
            feed_override: 1.0,
            dwell_exact_stop: false,
        }
    }
}

/// Errors of the tool-path model.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ToolpathError {
    /// The NC program could not be read.
    #[error(transparent)]
    Nc(#[from] crate::nc::NcError),
    /// A setting is out of range.
    #[error("{field}: {message}")]
    Config {
        /// The field, e.g. `tA`.
        field: &'static str,
        /// What was expected.
        message: String,
    },
    /// Nothing to simulate.
    #[error("the program has no cutting or rapid move with a non-zero length")]
    Empty,
    /// The caller stopped the run (a progress callback returned false).
    #[error("cancelled")]
    Cancelled,
    /// Over a work budget ([`crate::budget`]).
    #[error(transparent)]
    Budget(#[from] crate::budget::BudgetError),
    /// The run would need too many samples.
    /// More segments than [`crate::budget::MAX_TOOLPATH_SEGMENTS`]: each
    /// holds memory while the simulation runs.
    #[error("the simulation would hold {segments} segments, more than the limit of {limit} (each holds about 0.4 to 0.7 KB of memory while it runs); segment {next} is line {line}: split the program there or earlier and simulate each part")]
    TooManySegments {
        /// Segments of the program.
        segments: usize,
        /// The budget.
        limit: usize,
        /// The first segment over it (1-based).
        next: usize,
        /// Its source line.
        line: usize,
    },
    #[error("the simulation would need {samples:.3e} samples (limit {limit}){slowest}; increase dt or shorten the program, or check a very low feed")]
    TooLong {
        /// Samples needed (a float: a feed of 1e-21 mm/min asks for more
        /// than any integer type holds, which a cast would saturate).
        samples: f64,
        /// The limit.
        limit: usize,
        /// `"; the longest move is line N (… s at F mm/min)"`, or empty.
        slowest: String,
    },
}

/// At most this many samples per simulation (the work budget
/// [`crate::budget::MAX_TOOLPATH_SAMPLES`]).
pub const MAX_SAMPLES: usize = crate::budget::MAX_TOOLPATH_SAMPLES;

/// At most this many samples in a simulation's series (the budget
/// [`crate::budget::MAX_TOOLPATH_SERIES`]); a longer run keeps, of each
/// group of consecutive samples, the one with the largest error.
pub const MAX_SERIES: usize = crate::budget::MAX_TOOLPATH_SERIES;

/// Smallest positive `tA` or `T`, s: below 1 µs the acc/dec's accelerations
/// lose every digit of the path.
pub const MIN_TIME_CONSTANT: f64 = 1e-6;

impl SimConfig {
    /// Checks every field.
    ///
    /// # Errors
    /// [`ToolpathError::Config`] naming the field.
    pub fn validate(&self) -> Result<(), ToolpathError> {
        let bad = |field, message: &str| {
            Err(ToolpathError::Config {
                field,
                message: message.to_string(),
            })
        };
        // 0 is "none"; a positive time constant below 1 µs is no machine's
        // and its huge accelerations lose every digit of the path (tA = 1e-15 s
        // gave a 312 mm contour error).
        let time_constant = |v: f64| v == 0.0 || (MIN_TIME_CONSTANT..=10.0).contains(&v);
        if !time_constant(self.t_a) {
            return bad(
                "tA",
                &format!(
                    "expected 0 (no acc/dec) or an acc/dec time constant from 1e-6 to 10 s, got {}",
                    crate::numeric::compact(self.t_a)
                ),
            );
        }
        if let Some(t) = self.t.per_axis().into_iter().find(|t| !time_constant(*t)) {
            return bad(
                "T",
                &format!(
                    "expected 0 (no lag) or servo time constants from 1e-6 to 10 s, got {}",
                    crate::numeric::compact(t)
                ),
            );
        }
        if !(self.dt.is_finite() && self.dt > 0.0 && self.dt <= 0.1) {
            return bad(
                "dt",
                "expected a sampling interval above 0 and at most 0.1 s",
            );
        }
        if !(self.rapid_feed.is_finite() && self.rapid_feed > 0.0) {
            return bad("rapidFeed", "expected a positive rapid rate in mm/min");
        }
        if !(self.feed_override.is_finite()
            && self.feed_override > 0.0
            && self.feed_override <= 10.0)
        {
            return bad(
                "feedOverride",
                "expected a feed override above 0 and at most 10 (1 = 100 %)",
            );
        }
        Ok(())
    }
}
