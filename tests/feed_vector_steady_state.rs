//! The simulated constant-feed-speed-vector test agrees at steady state with
//! the frequency-domain prediction: the mean α − β equals α_th of C minus
//! the mean lag of atan2(Y, X) built from G_X(jω) and G_Y(jω), and the
//! radius decrease equals the mean of R_W − |(X, Y)| built the same way.

use mtmotion::feed_vector::{feed_vector_test, Condition};
use mtmotion::machine;
use mtmotion::servo::response::{alpha_th, frequency_response};
use std::f64::consts::PI;

#[test]
fn mean_angle_difference_matches_the_frequency_response() {
    let mut m = machine::preset("nmv5000").unwrap();
    // a C axis whose integral action settles within the run, so that its
    // ramp lag reaches Eq. 17's limit
    m.axes.get_mut("c").unwrap().kvi = 40000.0;
    for omega in [0.5 * PI, PI, 1.5 * PI] {
        let cond = Condition {
            duration: Some(3.0 + 2.0 * 2.0 * PI / omega),
            ..Condition::paper(omega)
        };
        let r = feed_vector_test(&m, &cond).unwrap();
        assert!(!r.summary.saturated);
        let mut c = m.axes["c"].clone();
        c.j1 = cond.j1;
        let alpha = alpha_th(&c, omega).unwrap();
        let gx = frequency_response(&m.axes["x"], &[omega]).unwrap();
        let gy = frequency_response(&m.axes["y"], &[omega]).unwrap();
        // mean over one period of the angle and radius of the steady ellipse
        let k = 20000;
        let (mut lag, mut rad) = (0.0, 0.0);
        for i in 0..k {
            let th = 2.0 * PI * i as f64 / k as f64;
            let x = 8.0 * gx.magnitude[0] * (th + gx.phase[0]).cos();
            let y = 8.0 * gy.magnitude[0] * (th + gy.phase[0]).sin();
            let d = (th - y.atan2(x) + PI).rem_euclid(2.0 * PI) - PI;
            lag += d / k as f64;
            rad += (8.0 - x.hypot(y)) / k as f64;
        }
        let want = alpha - lag;
        let got = r.summary.mean_angle_diff;
        // the window averages whole samples, not whole periods: 2e-5 rad
        assert!((got - want).abs() < 2e-5, "ω={omega}: {got} vs {want}");
        assert!(
            (r.summary.radius_decrease - rad).abs() < 2e-4,
            "ω={omega}: ΔR {} vs {rad}",
            r.summary.radius_decrease
        );
    }
}

#[test]
fn paper_condition_series_are_consistent() {
    let m = machine::preset("nmv5000").unwrap();
    let r = feed_vector_test(&m, &Condition::paper(PI)).unwrap();
    let s = &r.series;
    let n = s.t.len();
    for v in [
        &s.x,
        &s.y,
        &s.c,
        &s.torque_c,
        &s.shape_error,
        &s.alpha,
        &s.beta,
        &s.angle_diff,
        &s.radius_error,
        &s.omega_c,
        &s.omega_l,
    ] {
        assert_eq!(v.len(), n);
    }
    // Eq. 10 = Eq. 8 − Eq. 9 sample by sample
    for i in (0..n).step_by(97) {
        assert!((s.angle_diff[i] - (s.alpha[i] - s.beta[i])).abs() < 1e-12);
    }
    // the C axis reaches the commanded angular velocity
    assert!((s.omega_c[n - 10] - PI).abs() < 1e-3);
    // default duration: steady start + two periods
    assert!((s.t[n - 1] - (r.summary.steady_from + 4.0)).abs() < 3e-3);
    assert_eq!(r.summary.periods, 2);
}

/// The whole test's work: samples × (1 + pitch-error harmonics) over X, Y
/// and C (each harmonic one `sin` per sample) is within one budget. With 64
/// harmonics on all three axes (X and Y declared rotary) 999 s at 1 ms is
/// refused before any step, naming the terms; 64 on C alone, or 64 on each
/// over a shorter test, are within it.
#[test]
fn pitch_harmonics_count_in_the_tests_work_budget() {
    let mut m = machine::preset("nmv5000").unwrap();
    // the count is what matters: 64 copies of one harmonic
    let one = mtmotion::servo::WormHarmonic {
        n: 3.0,
        w: 1e-6,
        phi: 0.2,
    };
    let harmonics = vec![one; 64];
    for k in ["x", "y", "c"] {
        let a = m.axes.get_mut(k).unwrap();
        a.kind = mtmotion::servo::AxisKind::Rotary;
        a.pitch_error = harmonics.clone();
    }
    let long = Condition {
        duration: Some(999.0),
        ..Condition::paper(PI)
    };
    let e = feed_vector_test(&m, &long).unwrap_err().to_string();
    assert_eq!(e, "feed-vector test: 194805195 terms (samples × (1 + pitch-error harmonics), over X, Y and C), more than the limit of 100000000; shorten it, raise dt or give fewer pitch-error harmonics");
    // 512,820 samples × 195 = 99,999,900 terms: within the budget; one more sample is not
    let samples = mtmotion::feed_vector::samples(
        &["x", "y", "c"].map(|k| m.axes[k].clone()),
        &Condition {
            duration: Some(512.819),
            ..Condition::paper(PI)
        },
    )
    .unwrap();
    assert_eq!(samples, 512_820);
    let over = Condition {
        duration: Some(512.820),
        ..Condition::paper(PI)
    };
    assert!(
        mtmotion::feed_vector::samples(&["x", "y", "c"].map(|k| m.axes[k].clone()), &over).is_err()
    );
}
