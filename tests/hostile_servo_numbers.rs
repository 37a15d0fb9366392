//! The hostile numbers of the robustness probe, servo family: each is
//! refused with an error naming the field and its allowed range, where it
//! once trapped the wasm instance (an index out of bounds in the Pre-Control
//! from a NaN sample position, a Vec grown without end), looped, or
//! returned NaN/∞ as if it were an answer.
#![cfg(not(target_arch = "wasm32"))]

use mtmotion::best_kffp::saturation::{torque_saturation, SaturationQuery};
use mtmotion::feed_vector::{feed_vector_test, Condition};
use mtmotion::machine::preset;
use mtmotion::servo::response::frequency_response;
use mtmotion::servo::simulate::simulate_axis;

fn err<T: std::fmt::Debug, E: std::fmt::Display>(r: Result<T, E>) -> String {
    r.map(|v| format!("no error: {v:?}"))
        .unwrap_or_else(|e| e.to_string())
}

fn condition(json: &str) -> Condition {
    serde_json::from_str(json).unwrap()
}

#[test]
fn axis_parameters_outside_their_physical_range() {
    let m = preset("nmv5000").unwrap();
    let cmd: Vec<f64> = (0..100).map(|i| i as f64 * 1e-3).collect();
    for (field, value, want) in [
        ("ta", 1e6, "between 0 and 10 s"),
        ("tp", 2f64.powi(31), "between 0 and 10 s"),
        ("ts", 1e300, "between 0 and 10 s"),
        ("kffp", 1e308, "between −1000 and 1000 %"),
        ("j", 1e-320, "between 1e-9 and 1e4"),
    ] {
        let mut c = m.axes["c"].clone();
        match field {
            "ta" => c.ta = value,
            "tp" => c.tp = value,
            "ts" => c.ts = value,
            "kffp" => c.kffp = value,
            _ => c.j = value,
        }
        let e = err(simulate_axis(&c, 1e-3, &cmd));
        assert!(
            e.contains(field) && e.contains(want),
            "{field} = {value}: {e}"
        );
        let e = err(frequency_response(&c, &[1.0, 2.0]));
        assert!(
            e.contains(field),
            "frequencyResponse {field} = {value}: {e}"
        );
    }
    let mut x = m.axes["x"].clone();
    x.lead = Some(1e-320);
    let e = err(simulate_axis(&x, 1e-3, &cmd));
    assert!(
        e.contains("lead") && e.contains("between 1e-6 and 100 m"),
        "{e}"
    );
}

#[test]
fn time_steps_outside_their_range() {
    let c = preset("nmv5000").unwrap().axes["c"].clone();
    let cmd = vec![0.0; 10];
    for dt in [1e-320, 1e-9, 1e300, f64::NAN, 0.0] {
        let e = err(simulate_axis(&c, dt, &cmd));
        assert!(
            e.contains("dt") && e.contains("between 1e-7 and 1 s"),
            "dt = {dt}: {e}"
        );
    }
}

#[test]
fn feed_vector_conditions_outside_their_range() {
    let m = preset("nmv5000").unwrap();
    for (json, want) in [
        (
            r#"{"rc":5,"rw":8,"omega":1e18,"accelTime":0.064,"j1":1.7}"#,
            "between 0 and 1000 rad/s",
        ),
        (
            r#"{"rc":5,"rw":8,"omega":900,"accelTime":0.064,"j1":1.7,"dt":0.01}"#,
            "π/4 per time step",
        ),
        (
            r#"{"rc":5,"rw":8,"omega":3,"accelTime":0.064,"j1":1.7,"dt":1e-320}"#,
            "between 1e-7 and 0.01 s",
        ),
        (
            r#"{"rc":5,"rw":8,"omega":3,"accelTime":0.064,"j1":1.7,"dt":100}"#,
            "between 1e-7 and 0.01 s",
        ),
        (
            r#"{"rc":5,"rw":8,"omega":3,"accelTime":0.064,"j1":1.7,"kffp":{"x":100,"y":100,"c":1e308}}"#,
            "between −1000 and 1000 %",
        ),
        (
            r#"{"rc":1e-320,"rw":8,"omega":3,"accelTime":0.064,"j1":1.7}"#,
            "rc",
        ),
    ] {
        let e = err(feed_vector_test(&m, &condition(json)));
        assert!(e.contains(want), "{json}: {e}");
    }
}

#[test]
fn torque_saturation_needs_an_acc_dec_time_and_a_sane_step() {
    let m = preset("nmv5000").unwrap();
    let q = |accel_time: f64, dt: Option<f64>| SaturationQuery {
        j1: vec![1.7],
        torque_max: Some(725.0),
        accel_time,
        feed_at_cutting_point: 200.0,
        dt,
        reading: Default::default(),
    };
    // accelTime 0 is acc/dec once (Ts alone); with Ts 0 too the command is a
    // velocity step: no finite acceleration to report (it once gave ∞).
    let mut step = m.clone();
    step.axes.get_mut("c").unwrap().ts = 0.0;
    let e = err(torque_saturation(&step, &q(0.0, None)));
    assert!(
        e.contains("accelTime") && e.contains("velocity step"),
        "{e}"
    );
    let once = torque_saturation(&m, &q(0.0, None)).unwrap();
    assert!(
        once[0].accel_sat.is_finite() && once[0].accel_sat > 0.0,
        "{once:?}"
    );
    let e = err(torque_saturation(&m, &q(-1.0, None)));
    assert!(e.contains("between 0 and 100 s"), "{e}");
    let e = err(torque_saturation(&m, &q(0.064, Some(1e-320))));
    assert!(e.contains("dt"), "{e}");
    // A fine but legal step whose run would exceed the sample budget.
    let e = err(torque_saturation(&m, &q(100.0, Some(1e-7))));
    assert!(e.contains("1,000,000-sample budget"), "{e}");
    // The study counts loads × steps per load, not loads: 1000 loads of
    // 350,000 steps each (dt = 1 µs) are refused before any is simulated.
    let many = SaturationQuery {
        j1: vec![1.7; 1000],
        ..q(0.064, Some(1e-6))
    };
    let e = err(torque_saturation(&m, &many));
    assert!(
        e.starts_with("torque-saturation study: ") && e.contains("more than the limit of 50000000"),
        "{e}"
    );
    // And the normal case still answers with finite numbers.
    let ok = torque_saturation(&m, &q(0.064, None)).unwrap();
    assert!(ok
        .iter()
        .all(|p| p.accel_sat.is_finite() && p.omega_sat.is_finite()));
}

#[test]
fn cone_frustum_feed_outside_its_range() {
    use mtmotion::cone_frustum::{cone_frustum_test, ConeFrustumConfig};
    for feed in [1e308, 5e-324, 0.3, f64::NAN] {
        let cfg: ConeFrustumConfig = serde_json::from_value(serde_json::json!({
            "machine": "trunnion-ac", "halfApexDeg": 15.0, "inclinationDeg": 10.0, "feed": 1000.0, "idealServo": true
        }))
        .unwrap();
        let cfg = ConeFrustumConfig { feed, ..cfg };
        let e = err(cone_frustum_test(&cfg));
        assert!(
            e.contains("feed") && e.contains("between 1 and 100,000 mm/min"),
            "feed = {feed}: {e}"
        );
    }
}
