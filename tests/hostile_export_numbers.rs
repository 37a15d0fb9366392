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

/// The export-by-export probe of this session (every numeric leaf of each
/// export's good call set to NaN, ±∞, ±1e308, subnormals, 2⁵³, 1e18 …):
/// each finding below returned NaN/∞ or trapped, and is now refused naming
/// the field, the value and the range.
#[test]
fn tool_path_time_constants_below_a_microsecond_are_refused() {
    use mtmotion::toolpath::{simulate_text, Lag, SimConfig};
    let text = "G1 X10 F600\nG1 Y10\n";
    // tA = 1e-15 s gave a 312 mm contour error; 5e-324 gave NaN positions
    for (cfg, want) in [
        (
            SimConfig { t_a: 1e-15, ..SimConfig::default() },
            "tA: expected 0 (no acc/dec) or an acc/dec time constant from 1e-6 to 10 s, got 1e-15",
        ),
        (
            SimConfig { t_a: 5e-324, ..SimConfig::default() },
            "tA: expected 0 (no acc/dec) or an acc/dec time constant from 1e-6 to 10 s, got 4.94066e-324",
        ),
        (
            SimConfig { t: Lag::PerAxis([0.015, 1e-300, 0.015]), ..SimConfig::default() },
            "T: expected 0 (no lag) or servo time constants from 1e-6 to 10 s, got 1e-300",
        ),
    ] {
        assert_eq!(err(simulate_text(text, &cfg).map(|s| s.max_error)), want);
    }
    // 0 (none) and the edges are still simulated, with finite numbers
    for (t_a, t) in [(0.0, 0.0), (1e-6, 1e-6), (10.0, 10.0)] {
        let cfg = SimConfig {
            t_a,
            t: Lag::All(t),
            ..SimConfig::default()
        };
        let s = simulate_text(text, &cfg).unwrap();
        assert!(s.max_error.is_finite() && s.sim.iter().all(|p| p.iter().all(|v| v.is_finite())));
    }
}

#[test]
fn servo_traces_and_frequencies_beyond_their_range_are_refused() {
    use mtmotion::servo::identify::{identify_axis, MeasuredTrace};
    use mtmotion::servo::response::frequency_response;
    use mtmotion::servo::simulate::simulate_axis;
    let axis = preset("nmv5000").unwrap().axes["c"].clone();
    // identifyAxis: a 1e308 sample gave an infinite RMS
    let command: Vec<f64> = (0..50).map(|i| i as f64 * 1e-3).collect();
    let mut position = command.clone();
    position[7] = 1e308;
    let trace = MeasuredTrace {
        dt: 1e-3,
        command: command.clone(),
        position,
        torque: None,
    };
    assert_eq!(
        err(identify_axis(&axis, &trace).map(|r| r.rms_position)),
        "`position[7]`: 1e308 is outside ±1e6 mm or rad; check the trace's units"
    );
    // simulateAxis: a 1e308 command gave positions of NaN
    let mut cmd = command.clone();
    cmd[3] = -1e308;
    let e = err(simulate_axis(&axis, 1e-3, &cmd).map(|r| r.position.len()));
    assert!(
        e.contains("sample 3") && e.contains("within ±1e6 mm or rad"),
        "{e}"
    );
    // frequencyResponse: ω = 1e308 gave NaN magnitude and phase
    let e = err(frequency_response(&axis, &[1.0, 1e308]).map(|r| r.magnitude));
    assert!(
        e.contains("1e308") && e.contains("from 0 to 1e7 rad/s"),
        "{e}"
    );
    let r = frequency_response(&axis, &[1e7]).unwrap();
    assert!(r.magnitude[0].is_finite() && r.phase[0].is_finite());
}

#[test]
fn pitch_error_identification_refuses_huge_angles_instead_of_trapping() {
    use mtmotion::servo::pitch_identify::{identify_pitch_error, PitchIdentifyOptions};
    let th: Vec<f64> = (0..720).map(|i| (i as f64).to_radians()).collect();
    let e: Vec<f64> = th.iter().map(|t| 2e-5 * (3.0 * t).sin()).collect();
    let opts = PitchIdentifyOptions::default();
    // the last angle at 1e308 rad: 1e307 revolutions, a capacity overflow
    // panic (a trap in wasm)
    let mut far = th.clone();
    far[719] = 1e308;
    assert_eq!(
        err(identify_pitch_error(&far, &e, &opts).map(|r| r.revolutions)),
        "`angle[719]`: 1e308 rad is outside ±1e6 rad; check the trace's units"
    );
    // within the range but past the work budget
    let long: Vec<f64> = (0..720).map(|i| i as f64 * 1e3).collect();
    let err_long = err(identify_pitch_error(&long, &e, &opts).map(|r| r.revolutions));
    assert!(
        err_long.contains("more than the limit of 1000000000"),
        "{err_long}"
    );
    let mut big = e.clone();
    big[5] = 1e308;
    assert_eq!(
        err(identify_pitch_error(&th, &big, &opts).map(|r| r.revolutions)),
        "`error[5]`: 1e308 rad is outside ±1 rad; check the trace's units"
    );
    assert!(identify_pitch_error(&th, &e, &opts).is_ok());
}

#[test]
fn harmonic_fits_and_circular_tests_refuse_out_of_range_numbers() {
    use mtmotion::ballbar::{circular_test, fit_harmonics, synthetic_trace, SyntheticConfig};
    let th: Vec<f64> = (0..360).map(|i| (i as f64).to_radians()).collect();
    let dr: Vec<f64> = th.iter().map(|t| 0.005 * (2.0 * t).sin()).collect();
    let mut far = th.clone();
    far[0] = 1e308;
    assert_eq!(
        err(fit_harmonics(&far, &dr, 4).map(|h| h.len())),
        "sample 0: angle 1e308 is outside ±1e6 rad; check the trace's units"
    );
    let mut big = dr.clone();
    big[9] = -1e308;
    assert_eq!(
        err(fit_harmonics(&th, &big, 4).map(|h| h.len())),
        "sample 9: deviation -1e308 is outside ±1e9; check the trace's units"
    );
    // a subnormal nominal radius gave an infinite scale mismatch
    let mut t = synthetic_trace(&SyntheticConfig::default()).unwrap();
    t.nominal_radius = 5e-324;
    assert_eq!(
        err(circular_test(&t).map(|r| r.runs.len())),
        "nominalRadius: expected a bar length from 0.001 to 1e6 mm, got 4.94066e-324"
    );
}

#[test]
fn circular_tests_refuse_huge_angles_deviations_and_feeds() {
    use mtmotion::ballbar::{circular_test, synthetic_trace, SyntheticConfig};
    let good = synthetic_trace(&SyntheticConfig::default()).unwrap();
    let run = |f: &dyn Fn(&mut mtmotion::ballbar::BallbarTrace)| {
        let mut t = good.clone();
        f(&mut t);
        err(circular_test(&t).map(|r| r.runs.len()))
    };
    // 2⁵³ rad: a capacity overflow (a trap in wasm); 1e308: an infinite span
    for v in [2f64.powi(53), 1e308] {
        let e = run(&|t| t.runs[0].angle[0] = v);
        assert!(
            e.starts_with("runs[0].angleRad[0]: ") && e.contains("outside ±1e6 rad"),
            "{e}"
        );
    }
    let e = run(&|t| t.runs[0].deviation[3] = -100.0);
    assert_eq!(
        e,
        "runs[0].deviation[3]: -100 is outside ±100 mm (the bar length); check the trace's units"
    );
    // a subnormal feed made the servo-mismatch time infinite
    let e = run(&|t| t.feed = Some(5e-324));
    assert_eq!(
        e,
        "feed: expected a feed from 0.001 to 1e6 mm/min, got 4.94066e-324"
    );
    assert!(circular_test(&good).is_ok());
}
