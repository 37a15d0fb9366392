//! The nmv5000 loop readings (suzuki-best-kffp Table 1, §3, Eq. 12): which
//! of them gives X the paper's radius decrease ΔR > 0, each checked by two
//! independent methods.
//!
//! - `|G(jω)|` from the exact frequency response against the steady-state
//!   amplitude of the fixed-step simulation on a sine command (least
//!   squares over whole periods, with an offset and a drift term for the
//!   slow integral mode), to [`GAIN_TOL`];
//! - the sign of `|G| − 1` of the bare loop (K_FFP = 0, no Ts/Ta/Tp, no
//!   Kvi) against the closed-form damping ratio of
//!   `J s² + (C + Kvp) s + Kvp Kpp`: `|G| > 1` at low ω exactly when
//!   `ζ < 1/√2`.
//!
//! Table 1 as printed (`table`) and the text's Kpp = 30 (`kppText`) give X
//! `|G| > 1` (the radius grows); `inertiaAtLoad` gives `|G| < 1`, ΔR > 0.

use std::f64::consts::{PI, TAU};

use mtmotion::machine::{self, preset_with_reading};
use mtmotion::servo::response::frequency_response;
use mtmotion::servo::simulate::simulate_axis;
use mtmotion::servo::AxisParams;

/// Agreement of the simulated steady-state amplitude ratio with `|G(jω)|`:
/// the piecewise-linear sampled sine (dt 0.5 ms) loses up to
/// `(ω dt)²/12 ≈ 2·10⁻⁶` of its fundamental at 3.2π, the fit's leftover
/// transient less (1·10⁻⁷ seen for X at 0.5π); the smallest `|G| − 1` it
/// must resolve is 4.5·10⁻⁴ (X at 0.5π), 90 times larger.
const GAIN_TOL: f64 = 5e-6;

/// The paper's test frequencies, in units of π rad/s.
const OMEGAS_PI: [f64; 4] = [0.5, 1.0, 2.0, 3.2];

/// R_W of the paper's test, mm (Eq. 12).
const RW_MM: f64 = 8.0;

/// Least squares `y ≈ a sin ωt + b cos ωt + c + d t` over samples `from..`:
/// the amplitude `√(a² + b²)`.
fn amplitude(dt: f64, y: &[f64], w: f64, from: usize) -> f64 {
    let mut n = nalgebra::Matrix4::<f64>::zeros();
    let mut r = nalgebra::Vector4::<f64>::zeros();
    for (i, v) in y.iter().enumerate().skip(from) {
        let t = i as f64 * dt;
        let (s, c) = (w * t).sin_cos();
        let row = nalgebra::Vector4::new(s, c, 1.0, t);
        n += row * row.transpose();
        r += row * *v;
    }
    let p = n.lu().solve(&r).expect("regular normal equations");
    p[0].hypot(p[1])
}

/// Steady-state amplitude ratio of the simulation on `RW_MM · sin ωt`.
fn simulated_gain(a: &AxisParams, w: f64) -> f64 {
    let dt = 5e-4;
    let settle = (3.0 / dt) as usize;
    let fit_n = ((8.0 * TAU / w / dt).round()) as usize;
    let cmd: Vec<f64> = (0..settle + fit_n)
        .map(|i| RW_MM * (w * i as f64 * dt).sin())
        .collect();
    let r = simulate_axis(a, dt, &cmd).unwrap();
    amplitude(dt, &r.position, w, settle) / RW_MM
}

fn gains(a: &AxisParams) -> Vec<f64> {
    let ws: Vec<f64> = OMEGAS_PI.iter().map(|k| k * PI).collect();
    frequency_response(a, &ws).unwrap().magnitude
}

#[test]
fn frequency_response_and_simulation_agree_on_the_sign_of_delta_r() {
    let m = machine::preset("nmv5000").unwrap();
    for reading in &m.loop_readings {
        let m = preset_with_reading("nmv5000", reading).unwrap();
        for axis in ["x", "y"] {
            let a = &m.axes[axis];
            for (k, g) in OMEGAS_PI.iter().zip(gains(a)) {
                let sim = simulated_gain(a, k * PI);
                assert!(
                    (sim - g).abs() < GAIN_TOL,
                    "{reading} {axis} {k}π: |G| {g}, simulated {sim}"
                );
                // Eq. 12: ΔR_th = (1 − |G|)·R_W; the paper has ΔR > 0
                let dr_um = (1.0 - g) * RW_MM * 1e3;
                let shrinks = axis == "y" || reading == "inertiaAtLoad";
                assert_eq!(
                    dr_um > 0.0,
                    shrinks,
                    "{reading} {axis} {k}π: ΔR_th {dr_um} µm"
                );
            }
        }
    }
}

/// `ζ` of `J s² + (C + Kvp) s + Kvp Kpp` (bare loop, Kvi neglected).
fn damping_ratio(a: &AxisParams) -> f64 {
    (a.c + a.kvp) / (2.0 * (a.inertia() * a.kvp * a.kpp).sqrt())
}

#[test]
fn the_bare_x_loop_peaks_exactly_when_its_damping_ratio_is_below_one_over_root_two() {
    let m = machine::preset("nmv5000").unwrap();
    let mut zetas = Vec::new();
    for reading in &m.loop_readings {
        let mut x = preset_with_reading("nmv5000", reading).unwrap().axes["x"].clone();
        (x.kffp, x.ts, x.ta, x.tp, x.kvi) = (0.0, 0.0, 0.0, 0.0, 0.0);
        let zeta = damping_ratio(&x);
        // well below the loop's natural frequency √(Kvp Kpp/J)
        let wn = (x.kvp * x.kpp / x.inertia()).sqrt();
        let g = frequency_response(&x, &[0.05 * wn]).unwrap().magnitude[0];
        assert_eq!(
            g > 1.0,
            zeta < std::f64::consts::FRAC_1_SQRT_2,
            "{reading}: ζ {zeta}, |G| {g}"
        );
        zetas.push(zeta);
    }
    // table 0.41, kppText 0.58 (both underdamped), inertiaAtLoad 160
    assert!(zetas[0] < zetas[1] && zetas[1] < std::f64::consts::FRAC_1_SQRT_2);
    assert!(zetas[2] > 1.0);
}

#[test]
fn readings_change_only_what_they_name() {
    let t = preset_with_reading("nmv5000", "table").unwrap();
    let k = preset_with_reading("nmv5000", "kppText").unwrap();
    let j = preset_with_reading("nmv5000", "inertiaAtLoad").unwrap();
    for (name, a) in &t.axes {
        assert_eq!(k.axes[name].kpp, 30.0);
        let rest = AxisParams {
            kpp: a.kpp,
            ..k.axes[name].clone()
        };
        assert_eq!(&rest, a, "kppText changes only Kpp of {name}");
        let r = a.lead.map_or(1.0, |l| l / TAU);
        assert!((j.axes[name].j - a.j * r * r).abs() <= 1e-15 * a.j);
    }
    // Y's r = lead/2π = 1 m/rad: unchanged; X's 4.5 behind 16 mm
    assert_eq!(j.axes["y"], t.axes["y"]);
    assert!((j.axes["x"].j - 2.918e-5).abs() < 1e-8);
}
