//! The fixed-step simulation agrees with the exact frequency response at
//! steady state (|G| to 0.5 %, phase to 0.5 mrad) for every nmv5000 axis
//! with Pre-Control and smoothing, and the steady ramp error is
//! `α = ω (1 − K_FFP/100)/Kpp` when the velocity loop has integral action.

use mtmotion::machine;
use mtmotion::servo::response::{alpha_th, frequency_response};
use mtmotion::servo::simulate::simulate_axis;
use mtmotion::servo::AxisParams;

/// Least-squares fit of y ≈ a sin ωt + b cos ωt over samples `from..`:
/// returns (amplitude, phase) of y relative to sin ωt.
fn fit(dt: f64, y: &[f64], w: f64, from: usize) -> (f64, f64) {
    let (mut ss, mut sc, mut cc, mut ys, mut yc) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for (i, v) in y.iter().enumerate().skip(from) {
        let (s, c) = (w * i as f64 * dt).sin_cos();
        ss += s * s;
        sc += s * c;
        cc += c * c;
        ys += v * s;
        yc += v * c;
    }
    let det = ss * cc - sc * sc;
    let a = (ys * cc - yc * sc) / det;
    let b = (yc * ss - ys * sc) / det;
    ((a * a + b * b).sqrt(), b.atan2(a))
}

fn check_sine(a: &AxisParams, w: f64, dt: f64, what: &str) {
    // the linear regime: no torque limit
    let a = &AxisParams {
        torque_max: None,
        ..a.clone()
    };
    let period = std::f64::consts::TAU / w;
    // settle ≥ 1.5 s, then fit over whole periods
    let settle = (1.5 / dt) as usize;
    let fit_n = ((3.0 * period / dt).round()) as usize;
    let n = settle + fit_n;
    let cmd: Vec<f64> = (0..n).map(|i| 5.0 * (w * i as f64 * dt).sin()).collect();
    let r = simulate_axis(a, dt, &cmd).unwrap();
    let (mag, ph) = fit(dt, &r.position, w, settle);
    let fr = frequency_response(a, &[w]).unwrap();
    let rel = mag / (5.0 * fr.magnitude[0]) - 1.0;
    let dph = (ph - fr.phase[0] + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU)
        - std::f64::consts::PI;
    assert!(rel.abs() < 5e-3, "{what} ω={w} dt={dt}: |G| off by {rel}");
    assert!(
        dph.abs() < 5e-4,
        "{what} ω={w} dt={dt}: phase off by {dph} rad"
    );
}

#[test]
fn time_simulation_matches_frequency_response() {
    let m = machine::preset("nmv5000").unwrap();
    for (name, a) in &m.axes {
        for w in [0.5 * std::f64::consts::PI, 4.0 * std::f64::consts::PI, 40.0] {
            check_sine(a, w, 1e-3, name);
        }
        check_sine(a, 4.0 * std::f64::consts::PI, 1e-4, name);
    }
}

#[test]
fn time_simulation_matches_with_odd_times_and_gains() {
    // Times that are not multiples of dt, low feedforward, strong integral.
    let mut a = machine::preset("nmv5000").unwrap().axes["c"].clone();
    a.ts = 0.0371;
    a.ta = 0.0123;
    a.tp = 0.0047;
    a.kffp = 63.0;
    a.kvi = 30000.0;
    for w in [2.0, 25.0] {
        check_sine(&a, w, 1e-3, "c-odd");
    }
}

#[test]
fn ramp_error_with_integral_action() {
    let mut a = machine::preset("nmv5000").unwrap().axes["c"].clone();
    a.ts = 0.0;
    a.kvi = 40000.0; // integral corner Kvi/Kvp ≈ 8.5 rad/s: settles within the run
    let omega = 3.0;
    let dt = 1e-3;
    let cmd: Vec<f64> = (0..4000).map(|i| omega * i as f64 * dt).collect();
    for kffp in [0.0, 50.0, 90.0, 100.0] {
        a.kffp = kffp;
        let r = simulate_axis(&a, dt, &cmd).unwrap();
        let lag = cmd[3500] - r.position[3500];
        let want = omega * (1.0 - kffp / 100.0) / a.kpp;
        assert!((lag - want).abs() < 1e-7, "K_FFP {kffp}: {lag} vs {want}");
        assert!((alpha_th(&a, omega).unwrap() - want).abs() < 1e-15);
    }
}

#[test]
fn ramp_error_without_integral_action_keeps_the_damping_term() {
    // Kvi = 0: T_v(0) = Kvp/(Kvp + C), α = ω((Kvp + C)/Kvp − k)/Kpp
    let mut a = machine::preset("nmv5000").unwrap().axes["x"].clone();
    a.ts = 0.0;
    a.kvi = 0.0;
    a.kffp = 100.0;
    let omega = 20.0; // mm/s
    let dt = 1e-3;
    let cmd: Vec<f64> = (0..3000).map(|i| omega * i as f64 * dt).collect();
    let r = simulate_axis(&a, dt, &cmd).unwrap();
    let want = omega * ((a.kvp + a.c) / a.kvp - 1.0) / a.kpp;
    let lag = cmd[2900] - r.position[2900];
    assert!((lag - want).abs() < 1e-9 + 1e-6 * want, "{lag} vs {want}");
}
