//! The Best K_FFP method (Eq. 20): the analytic K_FFP makes
//! α_th − β_th zero to 1e-9 rad for each linear axis, and the simulated
//! check shrinks the mean α − β; when C saturates the simulated search
//! (Fig. 18) nulls the simulated mean α − β.

use mtmotion::best_kffp::{best_kffp, Method, Options};
use mtmotion::feed_vector::{feed_vector_test, Condition};
use mtmotion::machine;
use mtmotion::servo::response::{alpha_th, beta_th};
use std::f64::consts::PI;

#[test]
fn analytic_zeroes_the_theoretical_angle_difference() {
    let m = machine::preset("nmv5000").unwrap();
    for omega in [0.5 * PI, PI, 1.5 * PI] {
        let cond = Condition::paper(omega);
        let r = best_kffp(&m, &cond, &Options::default()).unwrap();
        assert_eq!(r.method, Method::Analytic);
        let mut c = m.axes["c"].clone();
        c.j1 = cond.j1;
        let alpha = alpha_th(&c, omega).unwrap();
        for (name, k) in [("x", r.kffp.x), ("y", r.kffp.y)] {
            let mut a = m.axes[name].clone();
            a.kffp = k;
            let d = alpha - beta_th(&a, omega).unwrap();
            assert!(d.abs() < 1e-9, "{name} ω={omega}: α_th − β_th = {d}");
        }
        assert_eq!(r.kffp.c, 100.0);
        // the simulated check: the rest is the C axis's ω·C/(Kvp·Kpp), which
        // Kvi = 0.274 N·m/rad cannot integrate away within seconds
        let slow = omega * c.c / (c.kvp * c.kpp);
        assert!(
            (r.after.mean_angle_diff - slow).abs() < 0.1 * slow,
            "{} vs {slow}",
            r.after.mean_angle_diff
        );
        assert!(r.after.half_amplitude < r.before.half_amplitude);
    }
}

#[test]
fn simulated_mode_when_the_rotary_axis_saturates() {
    let m = machine::preset("nmv5000").unwrap();
    let cond = Condition::paper(3.2 * PI);
    assert!(feed_vector_test(&m, &cond).unwrap().summary.saturated);
    let r = best_kffp(&m, &cond, &Options::default()).unwrap();
    assert_eq!(r.method, Method::Simulated);
    assert!(r.after.saturated);
    assert!(
        r.after.mean_angle_diff.abs() < 1e-6,
        "{}",
        r.after.mean_angle_diff
    );
    assert!(r.before.mean_angle_diff > 0.02);
}

#[test]
fn forced_simulated_mode_agrees_with_analytic_without_saturation() {
    let m = machine::preset("nmv5000").unwrap();
    let cond = Condition::paper(PI);
    let opts = Options {
        method: Method::Simulated,
        ..Options::default()
    };
    let s = best_kffp(&m, &cond, &opts).unwrap();
    let a = best_kffp(&m, &cond, &Options::default()).unwrap();
    assert!(s.after.mean_angle_diff.abs() < 1e-6);
    // the shift only absorbs the slow ω·C/(Kvp·Kpp) rest: well under 1 %
    assert!((s.kffp.x - a.kffp.x).abs() < 1.0 && (s.kffp.y - a.kffp.y).abs() < 1.0);
}

#[test]
fn bad_options_are_named() {
    let m = machine::preset("nmv5000").unwrap();
    let opts = Options {
        k_min: 50.0,
        k_max: 10.0,
        ..Options::default()
    };
    let e = best_kffp(&m, &Condition::paper(PI), &opts)
        .unwrap_err()
        .to_string();
    assert!(e.contains("kMin"), "{e}");
    let narrow = Options {
        k_min: 90.0,
        k_max: 110.0,
        ..Options::default()
    };
    let e = best_kffp(&m, &Condition::paper(PI), &narrow)
        .unwrap_err()
        .to_string();
    assert!(e.contains("axis x") && e.contains("no K_FFP"), "{e}");
}

/// The search and the `after` check reuse the one C response of `before`
/// (C keeps its K_FFP): `before` and `after` are bit for bit the
/// feed-vector tests of the set and of the returned K_FFP, each simulated
/// on its own (with pitch error on C, whose harmonics made each C run the
/// costly part; and with the simulated method's search).
#[test]
fn before_and_after_equal_their_own_feed_vector_tests() {
    let mut m = machine::preset("nmv5000").unwrap();
    m.axes.get_mut("c").unwrap().pitch_error = (1..=3)
        .map(|n| mtmotion::servo::WormHarmonic {
            n: n as f64,
            w: 2e-6,
            phi: 0.1 * n as f64,
        })
        .collect();
    for (omega, method) in [(PI, Method::Analytic), (3.2 * PI, Method::Simulated)] {
        let cond = Condition::paper(omega);
        let opts = Options {
            method,
            ..Options::default()
        };
        let r = best_kffp(&m, &cond, &opts).unwrap();
        assert_eq!(r.before, feed_vector_test(&m, &cond).unwrap().summary);
        let after = Condition {
            kffp: Some(r.kffp),
            ..cond.clone()
        };
        assert_eq!(r.after, feed_vector_test(&m, &after).unwrap().summary);
        assert_ne!(r.after, r.before);
    }
}
