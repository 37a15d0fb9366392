//! Torque-saturation onset (Figs. 17, 21): `torqueSaturation` gives ω_sat
//! such that `feedVectorTest` does not saturate at 0.97·ω_sat and does at
//! 1.03·ω_sat, for each of the paper's loads; accelSat = ω_sat/accelTime,
//! rcMin = F_C/ω_sat, and accelSat lies below the naive τ_max/J.

use mtmotion::best_kffp::saturation::{torque_saturation, SaturationQuery};
use mtmotion::feed_vector::{feed_vector_test, Condition};
use mtmotion::machine;

#[test]
fn onset_is_consistent_with_the_feed_vector_test() {
    let m = machine::preset("nmv5000").unwrap();
    let j1 = vec![1.70, 3.24, 4.77];
    let q = SaturationQuery {
        j1: j1.clone(),
        torque_max: 725.0,
        accel_time: 0.064,
        feed_at_cutting_point: 200.0,
        dt: None,
    };
    let pts = torque_saturation(&m, &q).unwrap();
    for (p, &j1) in pts.iter().zip(&j1) {
        assert!((p.j_total - (4.2 + j1)).abs() < 1e-12);
        assert!((p.accel_sat * 0.064 - p.omega_sat).abs() < 1e-9);
        assert!((p.rc_min - 200.0 / 60.0 / p.omega_sat).abs() < 1e-12);
        assert!(p.accel_sat < 725.0 / p.j_total);
        for (f, sat) in [(0.97, false), (1.03, true)] {
            let cond = Condition {
                j1,
                torque_max: Some(725.0),
                ..Condition::paper(f * p.omega_sat)
            };
            let r = feed_vector_test(&m, &cond).unwrap();
            assert_eq!(r.summary.saturated, sat, "J1={j1} at {f}·ω_sat");
            if !sat {
                // the linear model: peak torque ∝ ω
                assert!((r.summary.peak_torque - f * 725.0).abs() < 1e-6 * 725.0);
            }
        }
    }
    // heavier load saturates earlier
    assert!(pts[0].omega_sat > pts[1].omega_sat && pts[1].omega_sat > pts[2].omega_sat);
}

#[test]
fn bad_query_is_named() {
    let m = machine::preset("nmv5000").unwrap();
    let q = SaturationQuery {
        j1: vec![1.7],
        torque_max: 725.0,
        accel_time: 0.064,
        feed_at_cutting_point: 0.0,
        dt: None,
    };
    assert!(torque_saturation(&m, &q)
        .unwrap_err()
        .to_string()
        .contains("feedAtCuttingPoint"));
    let q = SaturationQuery {
        j1: vec![-1.0],
        feed_at_cutting_point: 200.0,
        ..q
    };
    assert!(torque_saturation(&m, &q)
        .unwrap_err()
        .to_string()
        .contains("j1"));
}
