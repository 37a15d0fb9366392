//! kato Fig. 2: gravity G and Coulomb friction F in the feed-drive loop,
//! and the additive reading of Eq. 1. Oracles: the closed-form steady
//! states of the cascaded loop with Kvi = 0 (the velocity error must carry
//! the load torque: `e = G/Kvp`, so the position lag grows by
//! `G/(Kvp·Kpp)` motor rad), and the additive pitch map written out.

use mtmotion::machine;
use mtmotion::servo::simulate::simulate_axis;
use mtmotion::servo::transmission::{motor_scale, Transmission};
use mtmotion::servo::{AxisParams, PitchReading, WormHarmonic};

fn x_axis() -> AxisParams {
    let mut x = machine::preset("nmv5000").unwrap().axes["x"].clone();
    x.kvi = 0.0;
    x.ts = 0.0;
    x.ta = 0.0;
    x.tp = 0.0;
    x
}

#[test]
fn gravity_shifts_the_holding_position_by_g_over_kvp_kpp() {
    let x = x_axis();
    let sm = motor_scale(&x).unwrap();
    for g in [5.0, -12.0] {
        let a = AxisParams {
            gravity: g,
            ..x.clone()
        };
        let r = simulate_axis(&a, 1e-3, &vec![10.0; 3000]).unwrap();
        let want = 10.0 - g / (a.kvp * a.kpp) / sm;
        assert!(
            (r.position[2999] - want).abs() < 1e-9,
            "G {g}: {} vs {want}",
            r.position[2999]
        );
        // the motor holds the load: applied torque = G
        assert!((r.torque[2999] - g).abs() < 1e-6);
    }
}

#[test]
fn friction_adds_f_over_kvp_kpp_to_the_following_error_against_the_motion() {
    let x = x_axis();
    let sm = motor_scale(&x).unwrap();
    let f = 8.0;
    for dir in [1.0, -1.0] {
        let cmd: Vec<f64> = (0..3000).map(|i| dir * 20.0 * i as f64 * 1e-3).collect();
        let plain = simulate_axis(&x, 1e-3, &cmd).unwrap();
        let fr = simulate_axis(
            &AxisParams {
                friction: f,
                ..x.clone()
            },
            1e-3,
            &cmd,
        )
        .unwrap();
        let extra = fr.position[2999] - plain.position[2999];
        let want = -dir * f / (x.kvp * x.kpp) / sm;
        assert!(
            (extra - want).abs() < 1e-9 * want.abs().max(1e-6) + 1e-12,
            "dir {dir}: {extra} vs {want}"
        );
    }
    // no load: identical to the plain loop, bit for bit
    let cmd: Vec<f64> = (0..500).map(|i| (i as f64 * 0.01).sin()).collect();
    let a = simulate_axis(&x, 1e-3, &cmd).unwrap();
    let b = simulate_axis(
        &AxisParams {
            friction: 0.0,
            gravity: 0.0,
            ..x.clone()
        },
        1e-3,
        &cmd,
    )
    .unwrap();
    assert_eq!(a.position, b.position);
}

#[test]
fn additive_reading_of_eq_1_is_the_angle_amplitude() {
    let mut c = machine::preset("nmv5000").unwrap().axes["c"].clone();
    c.gear_ratio = Some(90.0);
    c.pitch_error = vec![WormHarmonic {
        w: 2e-5,
        n: 3.0,
        phi: 0.4,
    }];
    c.pitch_reading = PitchReading::Additive;
    let t = Transmission::new(&c).unwrap();
    for k in 0..50 {
        let x = k as f64 * 0.137;
        let want = 2e-5 * ((3.0 * x + 0.4).sin() - 0.4f64.sin());
        // (to the rounding of x + error − x)
        assert!((t.gear_side(x) - x - want).abs() < 4e-15, "{x}");
    }
    // the default reading scales the same W by g/N = 30
    c.pitch_reading = PitchReading::GearRatio;
    let g = Transmission::new(&c).unwrap();
    let peak = (0..2000)
        .map(|k| {
            (g.gear_side(k as f64 * 0.001 * std::f64::consts::TAU)
                - k as f64 * 0.001 * std::f64::consts::TAU)
                .abs()
        })
        .fold(0.0, f64::max);
    assert!((peak / (2.0 * 2e-5 * 30.0) - 1.0).abs() < 0.05, "{peak}");
}

#[test]
fn bad_load_torques_are_named() {
    let x = x_axis();
    let e = simulate_axis(
        &AxisParams {
            friction: -1.0,
            ..x.clone()
        },
        1e-3,
        &[0.0, 1.0],
    )
    .unwrap_err();
    assert!(e.to_string().contains("friction"), "{e}");
    let e = simulate_axis(
        &AxisParams {
            gravity: f64::NAN,
            ..x
        },
        1e-3,
        &[0.0, 1.0],
    )
    .unwrap_err();
    assert!(e.to_string().contains("gravity"), "{e}");
}
