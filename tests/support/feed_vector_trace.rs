//! The simulated constant-feed-speed-vector trace the trace-reader tests
//! write in each layout and read back (shared by tests/trace_reader.rs,
//! trace_layouts.rs and trace_mat.rs).
#![allow(dead_code)] // each test uses its share

use mtmotion::feed_vector::{feed_vector_test, Condition, FeedVectorResult};
use mtmotion::machine;
use std::f64::consts::PI;

/// The simulated test at ω = π rad/s (one period 2 s) over 3 s.
pub fn sim() -> (Condition, FeedVectorResult) {
    let m = machine::preset("nmv5000").unwrap();
    let cond = Condition {
        duration: Some(3.0),
        ..Condition::paper(PI)
    };
    let r = feed_vector_test(&m, &cond).unwrap();
    (cond, r)
}

/// The trace's rows: time (s), X, Y (mm), C (deg), torque (N·m).
pub fn rows(r: &FeedVectorResult) -> Vec<[f64; 5]> {
    let s = &r.series;
    (0..s.t.len())
        .map(|i| [s.t[i], s.x[i], s.y[i], s.c[i].to_degrees(), s.torque_c[i]])
        .collect()
}

/// `a` equals `b` within 1e-9 relative (1e-12 absolute near zero).
pub fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * b.abs().max(1e-3)
}
