//! Proves IK(FK(q)) = q to 1e-9 (mm and degrees) on every 5-axis preset,
//! for joint vectors drawn over the preset's whole limits: one of the
//! branches `inverse` returns is the q we started from, every branch reaches
//! the pose, and every branch is inside the limits.
//! Singular poses (tool axis along the first rotary axis) are excluded by a
//! 0.05° band, where the first rotary angle is undetermined.
#![cfg(not(target_arch = "wasm32"))]

use mtmotion::kinematics::inverse::limits_from_degrees;
use mtmotion::kinematics::{forward, inverse, GeometricErrors, AXES};
use mtmotion::machine;
use proptest::prelude::*;

fn check(
    name: &str,
    unit: [f64; 6],
    tool_length: f64,
    singular: impl Fn(&[f64; 6]) -> bool,
) -> Result<(), TestCaseError> {
    let m = machine::preset(name).unwrap();
    let chain = m.kinematics.clone().unwrap();
    let lim = limits_from_degrees(&m.limits);
    let present = chain.axes();
    let mut q = [0.0; 6];
    for (i, a) in AXES.iter().enumerate() {
        if present.contains(a) {
            q[i] = lim[i][0] + unit[i] * (lim[i][1] - lim[i][0]);
        }
    }
    prop_assume!(!singular(&q));
    let none = GeometricErrors::default();
    let pose = forward(&chain, &q, &none, tool_length).unwrap();
    let sols = inverse(&chain, &pose, tool_length, &lim).unwrap();
    prop_assert!(!sols.is_empty());
    let close = |a: &[f64; 6]| {
        (0..6).all(|i| {
            let scale = if i >= 3 {
                180.0 / std::f64::consts::PI
            } else {
                1.0
            };
            ((a[i] - q[i]) * scale).abs() < 1e-9
        })
    };
    prop_assert!(
        sols.iter().any(|s| close(&s.q)),
        "{name}: q = {q:?} not among {sols:?}"
    );
    for s in &sols {
        prop_assert!(s.within_limits);
        let p = forward(&chain, &s.q, &none, tool_length).unwrap();
        for i in 0..3 {
            prop_assert!((p.position[i] - pose.position[i]).abs() < 1e-9);
            prop_assert!((p.orientation[i] - pose.orientation[i]).abs() < 1e-12);
        }
    }
    Ok(())
}

const BAND: f64 = 0.05 * std::f64::consts::PI / 180.0;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    #[test]
    fn pocketnc(u in prop::array::uniform6(0.0f64..=1.0), l in 0.0f64..80.0) {
        // Singular when the tool axis Ry(b)Rx(a)z is along y: a = ±90°.
        check("pocketnc-v2-10", u, l, |q| (q[3].abs() - std::f64::consts::FRAC_PI_2).abs() < BAND)?;
    }

    #[test]
    fn table_on_table_bc(u in prop::array::uniform6(0.0f64..=1.0), l in 0.0f64..150.0) {
        check("table-on-table-bc", u, l, |q| q[4].abs() < BAND)?;
    }

    #[test]
    fn trunnion_ac(u in prop::array::uniform6(0.0f64..=1.0), l in 0.0f64..150.0) {
        check("trunnion-ac", u, l, |q| q[3].abs() < BAND)?;
    }
}
