//! Trace analysis of the feed-vector test: a simulated test written as a
//! SERVO GUIDE-style CSV (C in degrees) and read back gives the same series
//! and summary; malformed traces give errors naming the line and column.

use mtmotion::feed_vector::trace_analysis::{analyze_trace, ColumnMap};
use mtmotion::feed_vector::{feed_vector_test, Condition};
use mtmotion::machine;
use std::f64::consts::PI;
use std::fmt::Write;

#[test]
fn simulated_trace_round_trips() {
    let m = machine::preset("nmv5000").unwrap();
    let cond = Condition::paper(PI);
    let sim = feed_vector_test(&m, &cond).unwrap();
    let s = &sim.series;
    let mut text = String::from("# SERVO GUIDE export\ntime\tX [um]\tY [um]\tC [deg]\tTCMD\n");
    for i in 0..s.t.len() {
        writeln!(
            text,
            "{:.1}\t{:.17e}\t{:.17e}\t{:.17e}\t{:.17e}",
            s.t[i] * 1e3,
            (s.x[i] - cond.rw) * 1e3,
            s.y[i] * 1e3,
            s.c[i].to_degrees(),
            s.torque_c[i]
        )
        .unwrap();
    }
    let map = ColumnMap {
        time_scale: 1e-3,
        linear_scale: 1e-3,
        torque: Some("TCMD".into()),
        relative: true,
        steady_from: Some(sim.summary.steady_from),
        ..ColumnMap::default()
    };
    let tr = analyze_trace(&text, &cond, &map).unwrap();
    assert_eq!(tr.series.t.len(), s.t.len());
    let a = &tr.summary;
    let b = &sim.summary;
    assert!((a.mean_angle_diff - b.mean_angle_diff).abs() < 1e-10);
    assert!((a.half_amplitude - b.half_amplitude).abs() < 1e-10);
    assert!((a.radius_decrease - b.radius_decrease).abs() < 1e-10);
    assert!((a.peak_torque - b.peak_torque).abs() < 1e-9);
    assert_eq!(a.periods, b.periods);
}

fn err(text: &str) -> String {
    analyze_trace(text, &Condition::paper(1.0), &ColumnMap::default())
        .unwrap_err()
        .to_string()
}

#[test]
fn malformed_traces_name_line_and_column() {
    assert!(err("").contains("empty"));
    assert_eq!(
        err("time,x,y,c\n0,8,0,0\n0.001,8,0,zero\n"),
        "line 3, column 4 ('c'): 'zero' is not a number"
    );
    let e = err("time,x,y,c\n0,8,0,0\n0.002,8,0,0\n0.001,8,0,0\n");
    assert!(
        e.starts_with("line 4, column 1 ('time')") && e.contains("does not increase"),
        "{e}"
    );
    let e = err("time,x,y\n0,8,0\n0.001,8,0\n");
    assert!(e.contains("'c'") && e.contains("time, x, y"), "{e}");
    let e = err("time,x,y,c\n0,8,0,0\n0.001,8,0\n");
    assert!(e.starts_with("line 3"), "{e}");
    let e = err("time,x,y,c\n0,8,0,0\n0.001,inf,0,0\n");
    assert!(e.starts_with("line 3, column 2 ('x')"), "{e}");
}
