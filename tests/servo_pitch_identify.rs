//! kato §2.3, Fig. 3: pitch-error identification by Fourier analysis of a
//! measured rotary-axis error trace. A synthetic trace with known harmonics
//! (orders 1, 2, 90 = worm-wheel teeth, 180; phases given), sampled
//! unevenly over 2.3 revolutions from θ0 = 0.7 rad, must give back the
//! orders, amplitudes (0.1 %) and phases (1 mrad); mapped to Eq. 1's
//! worm harmonics, the transmission model must reproduce the trace
//! (independent path: `Transmission::gear_side`).

use mtmotion::servo::pitch_identify::{identify_pitch_error, PitchIdentifyOptions};
use mtmotion::servo::transmission::Transmission;

const TRUE: [(usize, f64, f64); 4] = [
    (1, 3e-5, 0.3),
    (2, 1e-5, 2.0),
    (90, 5e-6, 4.0),
    (180, 2e-6, 1.0),
];

fn e(t: f64) -> f64 {
    TRUE.iter()
        .map(|&(n, a, p)| a * (n as f64 * t + p).sin())
        .sum()
}

fn trace() -> (Vec<f64>, Vec<f64>) {
    let tau = std::f64::consts::TAU;
    let n = 230_000;
    let mut th = Vec::with_capacity(n);
    for i in 0..n {
        // uneven: ±30 % jitter of the step, deterministic
        let jitter = 0.3 * ((i as f64 * 12.9898).sin() * 43758.5453).fract();
        th.push(0.7 + (i as f64 + jitter) * 2.3 * tau / n as f64);
    }
    let err = th.iter().map(|&t| e(t) + 1e-6).collect();
    (th, err)
}

#[test]
fn recovers_known_harmonics() {
    let (th, err) = trace();
    let r = identify_pitch_error(&th, &err, &PitchIdentifyOptions::default()).unwrap();
    assert_eq!(r.revolutions, 2);
    assert_eq!(r.peaks.len(), 4, "{:?}", r.peaks);
    for (p, &(n, a, phi)) in r.peaks.iter().zip(&TRUE) {
        assert_eq!(p.order, n);
        assert!((p.amplitude / a - 1.0).abs() < 1e-3, "{p:?}");
        let d = (p.phase - phi + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU)
            - std::f64::consts::PI;
        assert!(d.abs() < 1e-3, "{p:?}");
    }
    // the mean (order 0) is the constant offset plus the window's mean of the harmonics (0)
    assert!((r.spectrum[0] - 1e-6).abs() < 1e-8);
    // no leakage: every other order is empty to the interpolation error
    for (n, a) in r.spectrum.iter().enumerate().skip(1) {
        if !TRUE.iter().any(|t| t.0 == n) {
            assert!(*a < 1e-9, "order {n}: {a}");
        }
    }
}

#[test]
fn identified_harmonics_drive_the_worm_gear_model() {
    let (th, err) = trace();
    let r = identify_pitch_error(&th, &err, &PitchIdentifyOptions::default()).unwrap();
    let mut c = mtmotion::machine::preset("nmv5000").unwrap().axes["c"].clone();
    c.gear_ratio = Some(90.0);
    c.pitch_error = r.peaks.iter().map(|p| p.worm_harmonic(90.0)).collect();
    let t = Transmission::new(&c).unwrap();
    for k in 0..500 {
        let x = k as f64 * 0.0123;
        // the gearRatio reading zeroes the error at x = 0
        let want = e(x) - e(0.0);
        assert!(
            (t.gear_side(x) - x - want).abs() < 5e-8,
            "x {x}: {} vs {want}",
            t.gear_side(x) - x
        );
    }
}

#[test]
fn bad_traces_are_named() {
    let o = PitchIdentifyOptions::default();
    let th: Vec<f64> = (0..100).map(|i| i as f64 * 0.01).collect();
    let msg = |r: Result<_, mtmotion::servo::pitch_identify::PitchIdentifyError>| {
        r.unwrap_err().to_string()
    };
    assert!(msg(identify_pitch_error(&th, &th[..50], &o)).contains("error"));
    assert!(msg(identify_pitch_error(&th, &th, &o)).contains("whole revolution"));
    let mut back = th.clone();
    back[40] = 0.0;
    assert!(msg(identify_pitch_error(&back, &th, &o)).contains("angle[40]"));
    let mut nan = th.clone();
    nan[7] = f64::NAN;
    assert!(msg(identify_pitch_error(&th, &nan, &o)).contains("error[7]"));
    let o2 = PitchIdentifyOptions {
        max_order: 5000,
        ..o
    };
    let full: Vec<f64> = (0..1000).map(|i| i as f64 * 0.01).collect();
    let small: Vec<f64> = full.iter().map(|v| v * 1e-5).collect();
    assert!(msg(identify_pitch_error(&full, &small, &o2)).contains("maxOrder"));
    // an error of 10 rad is no pitch error (at most 1 rad)
    assert!(msg(identify_pitch_error(&full, &full, &o)).contains("outside ±1 rad"));
}
