//! A worm-gear rotary axis (kato Eq. 1, Fig. 2) in `simulate_axis`: the
//! semi-closed loop is unchanged by backlash and pitch error; the table
//! angle is the motor angle over `R_all` plus the integrated Eq. 1 ripple
//! `−(W g/N)[cos(N θm/g + φ) − cos φ]`, minus half the backlash while
//! driving forward and plus half of it after a reversal.

use mtmotion::machine;
use mtmotion::servo::simulate::simulate_axis;
use mtmotion::servo::WormHarmonic;

#[test]
fn backlash_and_pitch_error_reach_the_table() {
    let mut a = machine::preset("nmv5000").unwrap().axes["c"].clone();
    a.gear_ratio = Some(90.0);
    a.j = 0.004; // motor-side inertia of a small worm-gear axis
    a.j1 = 0.0;
    a.kvp = 5.0;
    a.kvi = 0.0; // no integral, no feedforward: no overshoot at the stops
    a.kffp = 0.0;
    a.c = 0.001;
    a.torque_max = None;
    let dt = 1e-3;
    // forward 1 rad over 2 s, hold, back to 0.4 rad
    let cmd: Vec<f64> = (0..6000)
        .map(|i| {
            let t = i as f64 * dt;
            if t < 2.0 {
                0.5 * t
            } else if t < 3.0 {
                1.0
            } else if t < 4.2 {
                1.0 - 0.5 * (t - 3.0)
            } else {
                0.4
            }
        })
        .collect();
    let rigid = simulate_axis(&a, dt, &cmd).unwrap();
    let (w, n, phi, b) = (2e-5, 3.0, 0.4, 0.001);
    a.backlash = b;
    a.pitch_error = vec![WormHarmonic { w, n, phi }];
    let worm = simulate_axis(&a, dt, &cmd).unwrap();
    let g = 90.0;
    let pitch = |th: f64| -(w * g / n) * ((n * th + phi).cos() - phi.cos());
    // forward, after the gap is taken up
    for i in [1000, 1999, 2800] {
        let th = rigid.position[i];
        let want = th + pitch(th) - 0.5 * b;
        assert!(
            (worm.position[i] - want).abs() < 1e-12,
            "{i}: {} vs {want}",
            worm.position[i]
        );
    }
    // after the reversal
    for i in [4500, 5999] {
        let th = rigid.position[i];
        let want = th + pitch(th) + 0.5 * b;
        assert!((worm.position[i] - want).abs() < 1e-12, "{i}");
    }
    // the loop itself (velocity, torque) does not see the transmission
    assert_eq!(rigid.velocity, worm.velocity);
    assert_eq!(rigid.torque, worm.torque);
    // pitch error amplitude W·g/N = 0.6 mrad is visible
    assert!(w * g / n > 5e-4);
}

#[test]
fn pitch_error_on_a_linear_axis_is_rejected() {
    let mut x = machine::preset("nmv5000").unwrap().axes["x"].clone();
    x.pitch_error = vec![WormHarmonic {
        w: 1e-5,
        n: 1.0,
        phi: 0.0,
    }];
    let e = simulate_axis(&x, 1e-3, &[0.0, 1.0])
        .unwrap_err()
        .to_string();
    assert!(e.contains("pitchError"), "{e}");
}
