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
    match analyze_trace(text, &Condition::paper(1.0), &ColumnMap::default()) {
        Ok(r) => panic!("accepted, summary {:?}", r.summary),
        Err(e) => e.to_string(),
    }
}

#[test]
fn malformed_traces_name_line_and_column() {
    assert!(err("").contains("empty"));
    assert_eq!(
        err("time,x,y,c\n0,8,0,0\n0.001,8,0,zero\n0.002,8,0,0\n"),
        "line 3, column 4 ('c'): 'zero' is not a number"
    );
    let e = err("time,x,y,c\n0,8,0,0\n0.002,8,0,0\n0.001,8,0,0\n0.003,8,0,0\n");
    assert!(
        e.starts_with("line 4, column 1 ('time')") && e.contains("does not increase"),
        "{e}"
    );
    let e = err("time,x,y\n0,8,0\n0.001,8,0\n");
    assert!(e.contains("'c'") && e.contains("time, x, y"), "{e}");
    let e = err("time,x,y,c\n0,8,0,0\n0.001,8,0\n0.002,8,0,0\n");
    assert!(e.starts_with("line 3"), "{e}");
    let e = err("time,x,y,c\n0,8,0,0\n0.001,inf,0,0\n0.002,8,0,0\n");
    assert!(e.starts_with("line 3, column 2 ('x')"), "{e}");
}

/// A one-second trace at 1 ms of the test at ω = 1 rad/s (X, Y on the
/// circle of radius 8, C in degrees; a plausible trace), with `edit`
/// applied to the line of sample `k` (1-based line `k + 2`).
fn second_of_trace(k: usize, line: &str) -> String {
    let mut text = String::from("time,x,y,c\n");
    for i in 0..1000 {
        let t = i as f64 * 1e-3;
        if i == k {
            text += line;
            text.push('\n');
        } else {
            let (x, y, c) = (8.0 * t.cos(), 8.0 * t.sin(), t.to_degrees());
            writeln!(text, "{t},{x},{y},{c}").unwrap();
        }
    }
    text
}

/// Numbers outside a physical range are refused at their line and column
/// (the fuzz loop's 1e308 positions gave an infinite half amplitude).
#[test]
fn values_outside_their_physical_range_are_refused() {
    let e = err(&second_of_trace(7, "0.007,8,1e308,0"));
    assert_eq!(
        e,
        "line 9, column 3 ('y'): 1e308 mm (after scaling) is outside ±1e5 mm; check the column's unit and mapping.linearScale"
    );
    let e = err(&second_of_trace(9, "0.009,-2e5,0,0"));
    assert!(e.starts_with("line 11, column 2 ('x'): -200000 mm"), "{e}");
    let e = err(&second_of_trace(3, "0.003,8,0,1e8"));
    assert!(
        e.starts_with("line 5, column 4 ('c')") && e.contains("±1e6 rad"),
        "{e}"
    );
    let e = err(&second_of_trace(999, "2e7,8,0,0"));
    assert!(
        e.starts_with("line 1001, column 1 ('time')") && e.contains("±1e7 s"),
        "{e}"
    );
    // the unit factor counts: 99 m in µm is fine, 1 km is not
    let cond = Condition::paper(1.0);
    let um = ColumnMap {
        linear_scale: 1e-3,
        ..ColumnMap::default()
    };
    assert!(analyze_trace(&second_of_trace(5, "0.005,8,99e6,0"), &cond, &um).is_ok());
    let e = analyze_trace(&second_of_trace(5, "0.005,8,1e9,0"), &cond, &um).unwrap_err();
    assert!(
        e.to_string()
            .starts_with("line 7, column 3 ('y'): 1e6 mm (after scaling)"),
        "{e}"
    );
}

#[test]
fn a_sample_step_below_a_tenth_of_a_microsecond_is_refused() {
    let e = err(&second_of_trace(1, "1e-9,8,0,0"));
    assert_eq!(
        e,
        "line 3, column 1 ('time'): time 1e-9 s is 1e-9 s after the line before, less than the shortest sample interval of 1e-7 s; check the time unit (mapping.timeScale)"
    );
    // 1 µs steps are a fast oscilloscope's, and fine
    let mut text = String::from("time,x,y,c\n");
    for i in 0..2000 {
        writeln!(text, "{},8,0,0", i as f64 * 1e-6).unwrap();
    }
    let map = ColumnMap {
        steady_from: Some(0.0),
        ..ColumnMap::default()
    };
    if let Err(e) = analyze_trace(&text, &Condition::paper(1.0), &map) {
        panic!("{e}");
    }
}

/// A trace that ends before the steady window gave a summary of zeros.
#[test]
fn an_empty_steady_window_is_an_error_not_zeros() {
    let text = "time,x,y,c\n0,8,0,0\n0.001,8,0,0\n0.002,8,0,0\n";
    let e = err(text);
    assert!(
        e.starts_with("condition `mapping.steadyFrom` = 0.464: the steady window starts 0.464 s after the motion start (accel time + 0.4 s, the default of mapping.steadyFrom), but the trace ends 0.002 s after it"),
        "{e}"
    );
    let cond = Condition::paper(1.0);
    let late = ColumnMap {
        motion_start: Some(0.0015),
        steady_from: Some(0.0),
        ..ColumnMap::default()
    };
    let e = analyze_trace(text, &cond, &late).err().unwrap().to_string();
    assert!(e.contains("holds 1 sample(s), at least 2"), "{e}");
    let far = ColumnMap {
        motion_start: Some(1e300),
        ..ColumnMap::default()
    };
    let e = analyze_trace(text, &cond, &far).err().unwrap().to_string();
    assert_eq!(
        e,
        "condition `mapping.motionStart` = 1e300: must be a time in s within ±1e7 s"
    );
    let whole = ColumnMap {
        steady_from: Some(0.0),
        ..ColumnMap::default()
    };
    let r = analyze_trace(text, &cond, &whole).unwrap();
    assert_eq!(r.summary.radius_decrease, 0.0);
    assert_eq!(r.summary.periods, 0);
}
