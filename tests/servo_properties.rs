#![cfg(not(target_arch = "wasm32"))]
//! Invariants of the servo models over random stable parameter sets:
//! the simulation is linear (scaling the command scales the response) and
//! shift-invariant in the command offset without saturation; its steady
//! state equals the frequency response; |G(j0⁺)| → 1.

use mtmotion::servo::response::frequency_response;
use mtmotion::servo::simulate::simulate_axis;
use mtmotion::servo::{AxisKind, AxisParams};
use proptest::prelude::*;

fn axis() -> impl Strategy<Value = AxisParams> {
    (
        0.5f64..10.0,
        0.0f64..10.0,
        10.0f64..80.0,
        0.0f64..0.08,
        0.0f64..0.03,
        0.0f64..0.02,
        0.0f64..120.0,
    )
        .prop_map(|(j, c, kpp, ts, ta, tp, kffp)| AxisParams {
            kind: AxisKind::Rotary,
            j,
            j1: 0.0,
            c,
            kpp,
            // a velocity loop 10–20× faster than the position loop
            kvp: 15.0 * kpp * j,
            kvi: 0.0,
            kffp,
            ts,
            ta,
            tp,
            torque_max: None,
            lead: None,
            gear_ratio: None,
            backlash: 0.0,
            pitch_error: Vec::new(),
            pitch_reading: Default::default(),
            friction: 0.0,
            gravity: 0.0,
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    #[test]
    fn response_is_linear_in_the_command(a in axis(), gain in -5.0f64..5.0, offset in -100.0f64..100.0) {
        let dt = 1e-3;
        let cmd: Vec<f64> = (0..800).map(|i| (i as f64 * dt * 7.0).sin() + 0.3 * i as f64 * dt).collect();
        let base = simulate_axis(&a, dt, &cmd).unwrap();
        let scaled: Vec<f64> = cmd.iter().map(|v| gain * v + offset).collect();
        let r = simulate_axis(&a, dt, &scaled).unwrap();
        for i in (0..800).step_by(37) {
            let want = gain * base.position[i] + offset;
            prop_assert!((r.position[i] - want).abs() < 1e-8 * (1.0 + want.abs()));
        }
    }

    #[test]
    fn steady_state_is_the_frequency_response(a in axis(), w in 1.0f64..30.0) {
        let dt = 1e-3;
        let n = 3000 + (2.0 * std::f64::consts::TAU / w / dt) as usize;
        // 300 samples more than compared: the read-ahead must not see the end
        let cmd: Vec<f64> = (0..n + 300).map(|i| (w * i as f64 * dt).sin()).collect();
        let r = simulate_axis(&a, dt, &cmd).unwrap();
        let fr = frequency_response(&a, &[w]).unwrap();
        // compare at the last 200 samples with the predicted steady sine
        for i in (n - 200..n).step_by(13) {
            let want = fr.magnitude[0] * (w * i as f64 * dt + fr.phase[0]).sin();
            prop_assert!((r.position[i] - want).abs() < 5e-3 * fr.magnitude[0] + 1e-6,
                "i={} {} vs {}", i, r.position[i], want);
        }
        let low = frequency_response(&a, &[1e-6]).unwrap();
        prop_assert!((low.magnitude[0] - 1.0).abs() < 1e-6);
    }
}
