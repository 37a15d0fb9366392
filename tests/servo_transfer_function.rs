//! With `Ts = Ta = Tp = 0` and no saturation the closed loop is exactly the
//! issue's `G = T_v (Kpp + k s)/(s + Kpp T_v)`: checked against an
//! independent state-space evaluation `G = c (sI − A)⁻¹ b` (complex LU
//! solve) to 1e-9, and the delays/averages against their exact exponentials.

use mtmotion::machine;
use mtmotion::servo::response::{closed_loop, frequency_response};
use mtmotion::servo::AxisParams;
use nalgebra::{Complex, Matrix3, Vector3};

type C64 = Complex<f64>;

/// State `[θ, ω, I]`, input the command x (with v_ff = s·x):
/// θ' = ω; J ω' = Kvp(Kpp(x − θ) + k x' − ω) + Kvi I − C ω; I' = Kpp(x − θ) + k x' − ω.
/// The k·x' term enters as `s·k·x`, i.e. the input vector is `b0 + s·b1`.
fn g_state_space(a: &AxisParams, w: f64) -> C64 {
    let (j, kpp, kvp, kvi, c) = (a.inertia(), a.kpp, a.kvp, a.kvi, a.c);
    let k = a.kffp / 100.0;
    let am = Matrix3::new(
        0.0,
        1.0,
        0.0,
        -kvp * kpp / j,
        -(kvp + c) / j,
        kvi / j,
        -kpp,
        -1.0,
        0.0,
    );
    let s = C64::new(0.0, w);
    let b = Vector3::new(C64::new(0.0, 0.0), (s * k + kpp) * (kvp / j), s * k + kpp);
    let m = Matrix3::<C64>::identity() * s - am.map(|v| C64::new(v, 0.0));
    let z = m.lu().solve(&b).expect("regular for ω > 0");
    z[0]
}

fn axes() -> Vec<(String, AxisParams)> {
    machine::preset("nmv5000")
        .unwrap()
        .axes
        .into_iter()
        .collect()
}

#[test]
fn no_delays_matches_the_state_space_form() {
    for (name, mut a) in axes() {
        a.ts = 0.0;
        a.ta = 0.0;
        a.tp = 0.0;
        for kffp in [0.0, 50.0, 100.0, 120.0] {
            a.kffp = kffp;
            for kvi in [0.0, a.kvi, 5000.0] {
                a.kvi = kvi;
                for w in [0.01, 0.5, 3.0, 12.566, 60.0, 400.0, 5000.0] {
                    let g = closed_loop(&a, w).unwrap();
                    let h = g_state_space(&a, w);
                    assert!(
                        (g - h).norm() < 1e-9 * h.norm().max(1e-3),
                        "{name} k={kffp} kvi={kvi} ω={w}: {g} vs {h}"
                    );
                }
            }
        }
    }
}

#[test]
fn issue_formula_literally() {
    // G = T_v (Kpp + k s)/(s + Kpp T_v), T_v = PV/(1+PV)
    let mut c = machine::preset("nmv5000").unwrap().axes["c"].clone();
    c.ts = 0.0;
    c.ta = 0.0;
    c.tp = 0.0;
    c.kffp = 90.0;
    for w in [1.0, 10.0, 100.0] {
        let s = C64::new(0.0, w);
        let p = C64::new(1.0, 0.0) / (s * c.inertia() + c.c);
        let v = C64::new(c.kvp, 0.0) + C64::new(c.kvi, 0.0) / s;
        let tv = p * v / (p * v + 1.0);
        let g = tv * (s * 0.9 + c.kpp) / (s + tv * c.kpp);
        assert!((closed_loop(&c, w).unwrap() - g).norm() < 1e-12);
    }
}

#[test]
fn delays_enter_as_exact_exponentials() {
    let base = machine::preset("nmv5000").unwrap().axes["x"].clone();
    let mut a = base.clone();
    a.ts = 0.0;
    a.ta = 0.0;
    a.tp = 0.0;
    for w in [0.7, 9.0, 40.0] {
        let s = C64::new(0.0, w);
        let tv = {
            let num = s * a.kvp + a.kvi;
            num / (s * (s * a.inertia() + a.c) + num)
        };
        let avg = |t: f64| (C64::new(1.0, 0.0) - (-s * t).exp()) / (s * t);
        let k = base.kffp / 100.0;
        let want = avg(base.ts) * tv * (s * k * (s * base.tp).exp() * avg(base.ta) + base.kpp)
            / (s + tv * base.kpp);
        let got = closed_loop(&base, w).unwrap();
        assert!((got - want).norm() < 1e-12, "ω={w}");
        let fr = frequency_response(&base, &[w]).unwrap();
        assert!((C64::from_polar(fr.magnitude[0], fr.phase[0]) - want).norm() < 1e-12);
    }
}
