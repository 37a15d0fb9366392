//! Benchmarks of the ball-bar and alignment models (criterion, native).
//! Mirrors `src/ballbar` and `src/alignment`. Issue targets (for the wasm
//! build, see `bench/node/ballbar.bench.mjs`): fitting 1e6 points < 50 ms;
//! a 10-range sweep at 1000 samples < 10 ms.

#[cfg(not(target_arch = "wasm32"))]
mod native {
    use criterion::{black_box, criterion_group, Criterion};
    use mtmotion::alignment::{travel_range_sweep, Locus, Offset, SweepConfig};
    use mtmotion::ballbar::{
        circular_test, fit_circle, fit_harmonics, synthetic_trace, Harmonic, SyntheticConfig,
    };

    fn noisy_arc(n: usize) -> (Vec<f64>, Vec<f64>) {
        let mut s = 1u64;
        (0..n)
            .map(|i| {
                s = s
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                let e = 0.001 * ((s >> 11) as f64 / (1u64 << 53) as f64 - 0.5);
                let t = (200.0 * i as f64 / n as f64).to_radians();
                (3.0 + (100.0 + e) * t.cos(), -1.0 + (100.0 + e) * t.sin())
            })
            .unzip()
    }

    fn sweep_cfg() -> SweepConfig {
        let h = |order, a: f64| Harmonic {
            order,
            amplitude: a * 1e-3,
            phase: 0.0,
        };
        SweepConfig {
            offset: Offset { z: 0.0, x: 0.01 },
            ranges: (0..10).map(|k| 90.0 + 30.0 * k as f64).collect(),
            locus: Locus {
                harmonics: vec![h(2, 5.0), h(3, 3.0), h(5, 2.5)],
                radius: 100.0,
                samples: 1000,
                centre_deg: 0.0,
            },
        }
    }

    fn benches_fn(c: &mut Criterion) {
        let (x, y) = noisy_arc(1_000_000);
        let mut g = c.benchmark_group("ballbar");
        g.sample_size(20);
        g.bench_function("fit_circle_1e6_points_200deg", |b| {
            b.iter(|| fit_circle(black_box(&x), black_box(&y)).unwrap())
        });
        let cfg = sweep_cfg();
        g.bench_function("travel_range_sweep_10_ranges_1000_samples", |b| {
            b.iter(|| travel_range_sweep(black_box(&cfg)).unwrap())
        });
        let th: Vec<f64> = (0..3600).map(|i| (i as f64 * 0.05).to_radians()).collect();
        let dr: Vec<f64> = th.iter().map(|t| 0.005 * (2.0 * t).sin()).collect();
        g.bench_function("harmonics_3600_samples_order_20_180deg", |b| {
            b.iter(|| fit_harmonics(black_box(&th), black_box(&dr), 20).unwrap())
        });
        let t = synthetic_trace(&SyntheticConfig {
            backlash_x: 0.004,
            cyclic_amplitude: 0.001,
            ..Default::default()
        })
        .unwrap();
        g.bench_function("circular_test_2x3600_points_with_diagnostics", |b| {
            b.iter(|| circular_test(black_box(&t)).unwrap())
        });
        g.finish();
    }

    criterion_group!(benches, benches_fn);
}

#[cfg(not(target_arch = "wasm32"))]
criterion::criterion_main!(native::benches);

#[cfg(target_arch = "wasm32")]
fn main() {}
