//! A program that cuts the same path twice (the CAMotics botomata pocket
//! cuts its part a second time after a `G10 L2` work offset this model
//! does not apply, so both copies lie on one path) has each copy's samples
//! counted on that copy's own segments: the nearest-point search breaks
//! ties towards the commanded point.
//!
//! The trap this checks: a retract that rises through an upper layer's
//! line, so for a moment that line is strictly nearer than the retract;
//! after it, the second copy's retract and the first copy's tie, and the
//! first copy's is nearer along the path to that line. Before the
//! tie-break towards the command, the search then stayed on the first
//! copy, and the second copy's last cut had no sample of its own.
#![cfg(not(target_arch = "wasm32"))]

use mtmotion::nc::program::parse;
use mtmotion::toolpath::{simulate, Lag, SimConfig};

/// One copy: a line through (40, 20) at Z-1, retracting at its end; a
/// rectangle at Z-2 ending at (40, 20) and retracting there, through the
/// first line; a last cut elsewhere. Copy 2's second retract ties with
/// copy 1's, which is nearer along the path to copy 2's first line, where
/// the tracker was a moment before.
const COPY: &str = "G0 Z2
G0 X40 Y0
G0 Z0
G1 Z-1 F600
G1 Y30 F1200
G0 Z2
G0 X0 Y0
G0 Z-1
G1 Z-2 F600
G1 X40 F1200
G1 Y20
G1 X0
G1 Y0.5
G1 X40 Y20
G0 Z2
G0 X60 Y0
G0 Z-1
G1 Z-2 F600
G1 X80 F1200
G1 Y10
G0 Z2
";

#[test]
fn each_copy_of_a_repeated_path_keeps_its_own_samples() {
    let text = format!("G21 G90 G17\n{COPY}{COPY}");
    let p = parse(&text).unwrap();
    let cfg = SimConfig {
        t_a: 0.04,
        t: Lag::All(0.015),
        dt: 0.000_25,
        ..SimConfig::default()
    };
    let sim = simulate(&p.segments, &p.segments, &cfg).unwrap();
    let n = p.segments.len();
    assert_eq!(n % 2, 0);
    let half = n / 2;
    let mut samples = vec![0usize; n];
    let mut err = vec![0.0f64; n];
    for st in &sim.segments {
        samples[st.segment] = st.samples;
        err[st.segment] = st.max_error_um;
    }
    for i in 0..half {
        let (a, b) = (i, i + half);
        let s = &p.segments[a];
        if !s.is_cutting() || s.length() < 1.0 {
            continue;
        }
        // Each copy starts from rest after a rapid's exact stop, so its
        // twin sees the same motion, up to the phase of the sample grid
        // (a sampled peak moves by up to the tool's travel in one step;
        // where a cut exits into a rapid, seen 2.5 % at dt 0.25 ms).
        assert!(
            samples[b] > 0 && samples[a].abs_diff(samples[b]) <= samples[a] / 100 + 2,
            "line {} / {}: {} vs {} samples",
            s.line,
            p.segments[b].line,
            samples[a],
            samples[b]
        );
        assert!(
            (err[a] - err[b]).abs() <= 0.05 * err[a],
            "line {}: {} vs {} µm (within the sampling phase at dt 0.25 ms)",
            s.line,
            err[a],
            err[b]
        );
    }
}
