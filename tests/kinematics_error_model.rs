//! Proves the error model behaves: zero errors change nothing; the exact
//! HTM forward kinematics and the independent first-order propagation
//! (Eq. 3 as printed, 4×4 matrices) agree to second order for small errors;
//! the Newton inversion of the full model hits the nominal pose.
#![cfg(not(target_arch = "wasm32"))]

use mtmotion::kinematics::errors::Coeffs;
use mtmotion::kinematics::newton::solve;
use mtmotion::kinematics::propagation::first_order;
use mtmotion::kinematics::{forward, GeometricErrors, Model};
use mtmotion::machine;

const PRESETS: [&str; 3] = ["pocketnc-v2-10", "table-on-table-bc", "trunnion-ac"];

fn q_for(name: &str) -> [f64; 6] {
    match name {
        "pocketnc-v2-10" => [-60.0, -70.0, -40.0, 0.6, 0.9, 0.0],
        "table-on-table-bc" => [40.0, -30.0, 60.0, 0.0, 0.7, 2.1],
        _ => [40.0, -30.0, 60.0, 0.5, 0.0, -1.3],
    }
}

/// A set of every kind of error, scaled by `s` (s = 1: 10 µm, 20 µrad).
fn all_errors(name: &str, s: f64) -> GeometricErrors {
    let chain = machine::preset(name).unwrap().kinematics.unwrap();
    let mut e = GeometricErrors::default();
    let mut k = 1.0;
    for a in chain.axes() {
        let up = a.to_uppercase();
        for d in ["X", "Y", "Z"] {
            k += 0.37;
            e.location
                .insert(format!("E{d}0{up}"), s * 0.01 * (k % 1.0 - 0.5));
            e.component.insert(
                format!("E{d}{up}"),
                Coeffs::Polynomial(vec![s * 0.01 * (k % 0.7 - 0.3), s * 1e-5]),
            );
        }
        for d in ["A", "B", "C"] {
            k += 0.53;
            e.location
                .insert(format!("E{d}0{up}"), s * 2e-5 * (k % 1.0 - 0.5));
            e.component.insert(
                format!("E{d}{up}"),
                Coeffs::Constant(s * 2e-5 * (k % 0.9 - 0.4)),
            );
        }
    }
    e.tool = [0.003 * s, -0.002 * s, 0.001 * s, 1e-5 * s, -2e-5 * s, 0.0];
    e
}

#[test]
fn zero_errors_change_nothing() {
    for name in PRESETS {
        let chain = machine::preset(name).unwrap().kinematics.unwrap();
        let q = q_for(name);
        let nominal = forward(&chain, &q, &GeometricErrors::default(), 30.0).unwrap();
        let zero = all_errors(name, 0.0);
        let same = forward(&chain, &q, &zero, 30.0).unwrap();
        assert_eq!(nominal, same, "{name}");
        let lin = first_order(&chain, &q, &zero, 30.0).unwrap();
        for i in 0..3 {
            assert!((lin.position[i] - nominal.position[i]).abs() < 1e-12);
        }
    }
}

#[test]
fn first_order_propagation_matches_exact_htm() {
    for name in PRESETS {
        let chain = machine::preset(name).unwrap().kinematics.unwrap();
        let q = q_for(name);
        let nominal = forward(&chain, &q, &GeometricErrors::default(), 30.0).unwrap();
        let mut rel = Vec::new();
        for s in [1.0, 0.1] {
            let e = all_errors(name, s);
            let exact = forward(&chain, &q, &e, 30.0).unwrap();
            let lin = first_order(&chain, &q, &e, 30.0).unwrap();
            let dev: f64 = (0..3)
                .map(|i| (exact.position[i] - nominal.position[i]).powi(2))
                .sum::<f64>()
                .sqrt();
            let diff: f64 = (0..3)
                .map(|i| (exact.position[i] - lin.position[i]).powi(2))
                .sum::<f64>()
                .sqrt();
            // The error itself is tens of µm; first order is good to < 0.1 % of it.
            assert!(dev > 1e-3 * s, "{name}: deviation {dev} too small to test");
            assert!(
                diff < 1e-3 * dev,
                "{name} s={s}: exact−first-order {diff} vs deviation {dev}"
            );
            rel.push(diff);
        }
        // Second order: 10× smaller errors give ~100× smaller disagreement.
        let ratio = rel[0] / rel[1];
        assert!((60.0..160.0).contains(&ratio), "{name}: ratio {ratio}");
    }
}

#[test]
fn newton_inverts_the_full_model() {
    for name in PRESETS {
        let chain = machine::preset(name).unwrap().kinematics.unwrap();
        let q = q_for(name);
        let target = forward(&chain, &q, &GeometricErrors::default(), 30.0).unwrap();
        let e = all_errors(name, 3.0);
        let m = Model::new(&chain, &e, 30.0).unwrap();
        let before = m.pose(&q);
        let axes: Vec<usize> = (0..6)
            .filter(|i| chain.axes().contains(&mtmotion::kinematics::AXES[*i]))
            .collect();
        let qc = solve(&m, &target, &q, &axes, name).unwrap();
        let after = m.pose(&qc);
        let err = |p: &mtmotion::kinematics::Pose| {
            (0..3)
                .map(|i| (p.position[i] - target.position[i]).abs())
                .fold(0.0, f64::max)
        };
        assert!(err(&before) > 1e-2, "{name}: {}", err(&before));
        assert!(err(&after) < 1e-9, "{name}: {}", err(&after));
    }
}
