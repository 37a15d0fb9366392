//! The per-segment statistics of a tool-path simulation (qiu §4-2) as
//! columns, one array per field, for programs of millions of segments: a
//! [`super::SegmentStats`] is 176 B in wasm memory (its reverse-compensation
//! halves included) and one JS object each once returned, which for the
//! 2 M-segment finishing program of `bench/node/large-program.bench.mjs`
//! was several hundred MB and seconds of conversion. The columns hold the
//! same numbers as the serialised fields of [`super::SegmentStats`], bit for
//! bit (`tests/toolpath_columns.rs`), in 45 B per segment; the halves that
//! only reverse compensation reads are not gathered.
//!
//! Units: mm; `max_error_um` in µm.

use super::contour::Element;
use crate::nc::program::{Motion, Segment};

/// Kind code of a line in [`SegmentColumns::kind`].
pub const KIND_LINE: u8 = 0;
/// Kind code of an arc.
pub const KIND_ARC: u8 = 1;
/// Kind code of a rapid.
pub const KIND_RAPID: u8 = 2;

/// The statistics of every reference segment with a length, in path
/// order, one column per field of [`super::SegmentStats`] (its
/// `segment`, `line`, `kind`, `length`, `radius`, `max_error_um`,
/// `mean_deviation`, `samples`).
#[derive(Debug, Clone, Default)]
pub struct SegmentColumns {
    /// Index into the reference program's segments.
    pub segment: Vec<u32>,
    /// Source line.
    pub line: Vec<u32>,
    /// [`KIND_LINE`], [`KIND_ARC`] or [`KIND_RAPID`].
    pub kind: Vec<u8>,
    /// Length, mm.
    pub length: Vec<f64>,
    /// Arc radius, mm (0 for lines and rapids).
    pub radius: Vec<f64>,
    /// Largest contour error of the samples nearest to the segment, µm.
    pub max_error_um: Vec<f64>,
    /// Mean signed normal deviation, mm; NaN where no sample had one
    /// (`SegmentStats::mean_deviation` is `None` there).
    pub mean_deviation: Vec<f64>,
    /// Number of samples nearest to the segment.
    pub samples: Vec<u32>,
}

/// The `kind` and `radius` of reference segment `seg` (mm), as
/// [`super::SegmentStats`] gives them.
pub(super) fn kind_radius(seg: &Segment) -> (&'static str, f64) {
    match seg.motion {
        Motion::Arc(a) => ("arc", a.radius),
        Motion::Rapid => ("rapid", 0.0),
        _ => ("line", 0.0),
    }
}

impl SegmentColumns {
    /// Empty columns with room for `n` segments' segment, line, kind,
    /// length and radius, and none yet for their statistics (which
    /// [`SegmentColumns::reserve_stats`] makes once the program's segments
    /// are freed: 38 MB less at the peak of a 2 M-segment simulation in
    /// wasm).
    pub(super) fn for_segments(n: usize) -> Self {
        Self {
            segment: Vec::with_capacity(n),
            line: Vec::with_capacity(n),
            kind: Vec::with_capacity(n),
            length: Vec::with_capacity(n),
            radius: Vec::with_capacity(n),
            ..Self::default()
        }
    }

    /// Room for the statistics of every segment pushed.
    pub(super) fn reserve_stats(&mut self) {
        let n = self.segment.len();
        self.max_error_um.reserve_exact(n);
        self.mean_deviation.reserve_exact(n);
        self.samples.reserve_exact(n);
    }

    /// Number of segments.
    pub fn len(&self) -> usize {
        self.segment.len()
    }

    /// True with no segment.
    pub fn is_empty(&self) -> bool {
        self.segment.is_empty()
    }

    /// Appends element `el` of the reference path, whose segment is `seg`:
    /// its segment, line, kind, length and radius (the statistics follow
    /// with [`SegmentColumns::push_stats`], once the run is done).
    pub(super) fn push_segment(&mut self, el: &Element, seg: &Segment) {
        let (kind, radius) = kind_radius(seg);
        // Segments, lines and samples are within the budgets
        // (`budget::MAX_TOOLPATH_SEGMENTS`, `MAX_NC_LINES`,
        // `MAX_TOOLPATH_SAMPLES`), far below `u32::MAX`.
        self.segment.push(u32_of(el.segment));
        self.line.push(u32_of(seg.line));
        self.kind.push(match kind {
            "arc" => KIND_ARC,
            "rapid" => KIND_RAPID,
            _ => KIND_LINE,
        });
        self.length.push(el.len);
        self.radius.push(radius);
    }

    /// Appends the statistics of the next element: its largest error
    /// `max_error` (mm), its mean normal deviation (mm) and its sample
    /// count.
    pub(super) fn push_stats(
        &mut self,
        max_error: f64,
        mean_deviation: Option<f64>,
        samples: usize,
    ) {
        self.max_error_um.push(max_error * 1e3);
        self.mean_deviation.push(mean_deviation.unwrap_or(f64::NAN));
        self.samples.push(u32_of(samples));
    }
}

/// `v` as u32 (saturating; every count here is far below `u32::MAX`).
fn u32_of(v: usize) -> u32 {
    u32::try_from(v).unwrap_or(u32::MAX)
}
