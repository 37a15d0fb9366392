//! Rotary-axis alignment from partial-range ball-bar traces
//! (takayama-alignment-travel-range §2–4).
//!
//! | file | what it models |
//! |---|---|
//! | [`travel_range`] | §2.1: centre-estimate error against travel range (Figs. 6–8) |
//! | [`angle`] | §2.2: offset per section, ΔBz/ΔBx from two sections, angle sweep (Fig. 12) |
//! | [`section_fit`] | one section's centre with its bias (selected harmonics) and standard error |
//! | [`from_trace`] | sections from trace files, about one common centre |
//! | [`band`] | an estimate from measured sections with its travel-range bias band |
//! | [`examples`] | the paper's Figs. 6, 7, 8, 12 as built-in examples, with its numbers |

pub mod angle;
pub mod band;
pub mod examples;
pub mod from_trace;
pub mod section_fit;
pub mod travel_range;

pub use angle::{
    angle_sweep, estimate_alignment, AlignmentEstimate, AngleSweepConfig, AngleSweepPoint, Section,
    SectionEstimate, SectionOffset,
};
pub use band::{estimate_alignment_band, AlignmentBand, AngleBand, BandConfig, SectionBand};
pub use travel_range::{
    travel_range_sweep, AlignmentError, Locus, Offset, SweepConfig, SweepPoint,
};
