//! thasana Eq. 9 / Fig. 8 PID feed drive: the exact discretisation against
//! the closed-loop transfer function `C·P/(1 + C·P)` evaluated
//! independently in complex arithmetic (steady sinusoid: amplitude and
//! phase within (ω dt)²/4, the input's sampling), and a ramp followed without steady error (two
//! integrators in the loop).

use mtmotion::servo::pid::{simulate_pid, PidDrive};

fn fit_sine(t: &[f64], y: &[f64], w: f64) -> (f64, f64) {
    // least squares y ≈ A sin wt + B cos wt over whole periods
    let (mut ss, mut cc, mut sc, mut ys, mut yc) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for (&t, &y) in t.iter().zip(y) {
        let (s, c) = (w * t).sin_cos();
        ss += s * s;
        cc += c * c;
        sc += s * c;
        ys += y * s;
        yc += y * c;
    }
    let det = ss * cc - sc * sc;
    let a = (ys * cc - yc * sc) / det;
    let b = (yc * ss - ys * sc) / det;
    (a.hypot(b), b.atan2(a))
}

#[test]
fn steady_sinusoid_matches_the_transfer_function() {
    for drive in [
        PidDrive::paper(),
        PidDrive {
            k: 50.0,
            a: 5.0,
            ..PidDrive::paper()
        },
    ] {
        for w in [0.3, 1.0, 4.0] {
            let dt = 1e-3;
            let period = std::f64::consts::TAU / w;
            let settle = 200.0;
            let n = ((settle + 4.0 * period) / dt) as usize + 10;
            let t: Vec<f64> = (0..n).map(|i| i as f64 * dt).collect();
            let cmd: Vec<f64> = t.iter().map(|t| (w * t).sin()).collect();
            let x = simulate_pid(&drive, dt, &cmd).unwrap();
            let k0 = (settle / dt) as usize;
            let k1 = k0 + (4.0 * period / dt).round() as usize;
            let (amp, ph) = fit_sine(&t[k0..k1], &x[k0..k1], w);
            let g = drive.response(w);
            // the simulation is exact for the piecewise-linear interpolant
            // of the sampled sine, which differs from the sine by at most
            // (ω dt)²/8 of its amplitude: allow twice that
            let tol = 1e-8 + (w * dt).powi(2) / 4.0;
            assert!(
                (amp - g.norm()).abs() < tol,
                "{drive:?} ω {w}: {amp} vs {}",
                g.norm()
            );
            assert!(
                (ph - g.arg()).abs() < tol,
                "{drive:?} ω {w}: {ph} vs {}",
                g.arg()
            );
        }
    }
}

#[test]
fn ramp_is_followed_without_steady_error() {
    let dt = 1e-3;
    let cmd: Vec<f64> = (0..200_000).map(|i| 3.0 * i as f64 * dt).collect();
    let x = simulate_pid(&PidDrive::paper(), dt, &cmd).unwrap();
    assert!(
        (x[199_999] - cmd[199_999]).abs() < 1e-6,
        "{}",
        x[199_999] - cmd[199_999]
    );
    // but not instantly: the lag is large on the way
    assert!((x[2000] - cmd[2000]).abs() > 0.1);
}

#[test]
fn bad_parameters_are_named() {
    let e = simulate_pid(
        &PidDrive {
            n: 0.0,
            ..PidDrive::paper()
        },
        1e-3,
        &[0.0, 1.0],
    )
    .unwrap_err();
    assert!(e.to_string().contains("pid.n"), "{e}");
    let e = simulate_pid(&PidDrive::paper(), 0.0, &[0.0, 1.0]).unwrap_err();
    assert!(e.to_string().contains("dt"), "{e}");
}
