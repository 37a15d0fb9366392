//! The least-squares harmonic fit is orthogonal over a full revolution (a
//! single harmonic of order n leaks nothing into the others, and the
//! coefficients equal the DFT's), and — unlike a plain FFT — stays exact on
//! partial ranges such as the 180° and 90° travel of trunnion and universal
//! heads.

use mtmotion::ballbar::{fit_harmonics, harmonics::synthesize, Harmonic};

fn grid(from_deg: f64, span_deg: f64, n: usize, closed: bool) -> Vec<f64> {
    let d = if closed { n - 1 } else { n } as f64;
    (0..n)
        .map(|i| (from_deg + span_deg * i as f64 / d).to_radians())
        .collect()
}

#[test]
fn orthogonal_at_360_degrees() {
    let th = grid(0.0, 360.0, 1000, false);
    for n in 1..=12u32 {
        let h = Harmonic {
            order: n,
            amplitude: 0.005,
            phase: 0.7,
        };
        let dr: Vec<f64> = th.iter().map(|t| h.eval(*t)).collect();
        let fit = fit_harmonics(&th, &dr, 12).unwrap();
        for f in &fit {
            let want = if f.order == n { 0.005 } else { 0.0 };
            assert!(
                (f.amplitude.abs() - want).abs() < 1e-14,
                "order {n} leaks into {}: {}",
                f.order,
                f.amplitude
            );
        }
        assert!((fit[n as usize].phase - 0.7).abs() < 1e-9);
        // Orthogonality of the sampled basis itself: Σ sin(nθ)·sin(mθ) = 0.
        for m in 1..=12u32 {
            if m != n {
                let dot: f64 = th
                    .iter()
                    .map(|t| (f64::from(n) * t).sin() * (f64::from(m) * t).sin())
                    .sum();
                assert!(dot.abs() < 1e-9, "{n} {m}");
            }
        }
    }
}

#[test]
fn exact_on_partial_ranges_where_the_fft_is_not() {
    let set = vec![
        Harmonic {
            order: 2,
            amplitude: 0.005,
            phase: 0.0,
        },
        Harmonic {
            order: 3,
            amplitude: 0.003,
            phase: 1.0,
        },
        Harmonic {
            order: 5,
            amplitude: 0.0025,
            phase: -2.0,
        },
    ];
    for span in [90.0, 180.0, 270.0] {
        let th = grid(-span / 2.0, span, 721, true);
        let dr: Vec<f64> = th.iter().map(|t| synthesize(&set, *t)).collect();
        let fit = fit_harmonics(&th, &dr, 6).unwrap();
        for h in &set {
            let f = fit[h.order as usize];
            assert!((f.amplitude - h.amplitude).abs() < 1e-10, "{span}: {f:?}");
            assert!((f.phase - h.phase).abs() < 1e-6, "{span}: {f:?}");
        }
        // A plain DFT of the same samples, as if they were a revolution,
        // gets the order-2 amplitude wrong by far more.
        let n = th.len() as f64;
        let (a, b) = th
            .iter()
            .zip(&dr)
            .enumerate()
            .fold((0.0, 0.0), |(a, b), (i, (_, d))| {
                let p = std::f64::consts::TAU * 2.0 * i as f64 / n;
                (a + d * p.cos(), b + d * p.sin())
            });
        assert!(((2.0 / n) * a.hypot(b) - 0.005).abs() > 1e-4, "span {span}");
    }
}
