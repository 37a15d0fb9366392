//! The hostile numbers of the robustness probe outside the servo family:
//! a subnormal radius (ω = F/R overflows to ∞ and Eq. 3 returns NaN), NaN
//! in a bulk forward-kinematics array (the single-pose call refused it, the
//! bulk one returned NaN), and an S-shape feed the program cannot write
//! ("F0." or an F word of 309 digits). Each is refused with an error that
//! names the field, the value in at most 6 significant digits and the range.
#![cfg(not(target_arch = "wasm32"))]

use mtmotion::ballbar::{synthetic_trace, SyntheticConfig};
use mtmotion::compensate::nc5::s_shape::{s_shape, SShapeOptions};
use mtmotion::kinematics::{GeometricErrors, Model};
use mtmotion::machine::preset;
use mtmotion::toolpath::identify::radius_reduction;

fn err<T: std::fmt::Debug, E: std::fmt::Display>(r: Result<T, E>) -> String {
    r.map(|v| format!("no error: {v:?}"))
        .unwrap_or_else(|e| e.to_string())
}

#[test]
fn radius_reduction_refuses_a_subnormal_radius_and_extreme_values() {
    for (args, want) in [
        (
            (1000.0, 1e-320, 0.04, 0.01),
            "radius: expected a radius from 0.001 to 1e6 mm, got 9.99989e-321",
        ),
        (
            (1e300, 10.0, 0.04, 0.01),
            "feed: expected a feed above 0 and at most 1e6 mm/min, got 1e300",
        ),
        (
            (1000.0, 10.0, 1e9, 0.01),
            "tA: expected tA from 0 to 100 s, got 1e9",
        ),
    ] {
        let (f, r, ta, t) = args;
        assert_eq!(err(radius_reduction(f, r, ta, t)), want);
    }
    // The edges of the ranges still give finite answers.
    for (f, r) in [(1e-300, 1e-3), (1e6, 1e-3), (1e6, 1e6), (1e-300, 1e6)] {
        let dr = radius_reduction(f, r, 100.0, 100.0).unwrap();
        assert!(
            dr.is_finite() && (0.0..=2.0 * r).contains(&dr),
            "{f} {r}: {dr}"
        );
    }
}

#[test]
fn synthetic_trace_refuses_a_subnormal_radius_and_overflowing_errors() {
    let c = SyntheticConfig {
        radius: 1e-320,
        ..Default::default()
    };
    assert_eq!(
        err(synthetic_trace(&c)),
        "radius: expected a bar length from 0.001 to 1e6 mm, got 9.99989e-321"
    );
    let c = SyntheticConfig {
        scale_x: 1e308,
        ..Default::default()
    };
    assert!(err(synthetic_trace(&c)).contains("overflows"));
    let c = SyntheticConfig {
        radius: 1e-3,
        feed: 1e6,
        ..Default::default()
    };
    let t = synthetic_trace(&c).unwrap();
    assert!(t
        .runs
        .iter()
        .all(|r| r.deviation.iter().all(|d| d.is_finite())));
}

#[test]
fn bulk_forward_kinematics_refuses_nan_like_the_single_pose() {
    let chain = preset("pocketnc-v2-10").unwrap().kinematics.unwrap();
    let m = Model::new(&chain, &GeometricErrors::default(), 0.0).unwrap();
    let mut q = vec![0.0; 12];
    q[10] = f64::NAN;
    assert_eq!(
        err(m.eval_bulk_degrees(&q)),
        "`q[10]` axis b of point 1 is NaN: must be a finite number"
    );
    q[10] = f64::INFINITY;
    assert!(err(m.eval_bulk_degrees(&q)).contains("axis b of point 1 is inf"));
}

#[test]
fn s_shape_feed_must_be_writable() {
    for (feed, shown) in [(1e-300, "1e-300"), (1e308, "1e308"), (0.0, "0")] {
        let o = SShapeOptions {
            feed,
            ..serde_json::from_str(r#"{"machine":"pocketnc-v2-10"}"#).unwrap()
        };
        assert_eq!(
            err(s_shape(&o)),
            format!("`feed` must be from 0.001 to 1e6 mm/min, got {shown}")
        );
    }
}

#[test]
fn an_nc_number_of_309_digits_is_refused_not_read_as_infinity() {
    let text = format!("G1 X1 F{}", "9".repeat(309));
    let e = mtmotion::nc::program::parse(&text).unwrap_err();
    assert_eq!((e.line, e.column), (1, 8));
    assert_eq!(
        e.message,
        "'99999999999999999999999…' after address 'F' has 309 characters; an NC number has at most 24"
    );
    // Twelve digits and a point are still an NC number.
    assert!(mtmotion::nc::program::parse("G1 X123456.789012 F100").is_ok());
}

#[test]
fn trace_unit_factors_outside_their_range_are_refused() {
    use mtmotion::feed_vector::trace_analysis::{analyze_trace, ColumnMap};
    use mtmotion::feed_vector::Condition;
    let text = "time,x,y,c\n0,8,0,0\n0.001,8,0.001,0.0573\n0.002,8,0.002,0.1146\n";
    let map = ColumnMap {
        time_scale: 1e300,
        ..ColumnMap::default()
    };
    let e = analyze_trace(text, &Condition::paper(1.0), &map).unwrap_err();
    assert_eq!(
        e.to_string(),
        "condition `mapping.timeScale` = 1e300: must be a unit factor of magnitude 1e-9 to 1e6 (e.g. 0.001 for ms, 25.4 for inch)"
    );
}

#[test]
fn trace_times_must_be_finite() {
    use mtmotion::feed_vector::trace_analysis::{analyze_trace, ColumnMap};
    use mtmotion::feed_vector::Condition;
    let text = "time,x,y,c\n0,8,0,0\n0.001,8,0.001,0.0573\n0.002,8,0.002,0.1146\n";
    for (map, field) in [
        (
            ColumnMap {
                motion_start: Some(f64::NAN),
                ..ColumnMap::default()
            },
            "motionStart",
        ),
        (
            ColumnMap {
                steady_from: Some(f64::INFINITY),
                ..ColumnMap::default()
            },
            "steadyFrom",
        ),
    ] {
        let e = analyze_trace(text, &Condition::paper(1.0), &map).unwrap_err();
        assert!(
            e.to_string()
                .starts_with(&format!("condition `mapping.{field}` = ")),
            "{e}"
        );
    }
}
