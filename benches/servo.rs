//! Benchmarks of the servo models (criterion, native). Mirrors `src/`:
//! `servo::simulate` (per step, with saturation and Pre-Control),
//! `servo::response`, `feed_vector` (3 axes, 2 s at 0.1 ms) and
//! `best_kffp` (simulated mode, saturating C axis).

#[cfg(not(target_arch = "wasm32"))]
mod native {
    use criterion::{black_box, criterion_group, Criterion, Throughput};
    use mtmotion::best_kffp::{best_kffp, Method, Options};
    use mtmotion::feed_vector::{feed_vector_test, Condition};
    use mtmotion::machine;
    use mtmotion::servo::response::frequency_response;
    use mtmotion::servo::simulate::simulate_axis;
    use std::f64::consts::PI;

    fn simulate(c: &mut Criterion) {
        let mut axis = machine::preset("nmv5000").unwrap().axes["c"].clone();
        axis.j1 = 1.7;
        // 4π rad/s ramp with 0.064 s acc/dec: the torque saturates at 725 N·m
        let dt = 1e-4;
        let n = 100_000;
        let cmd: Vec<f64> = (0..n)
            .map(|i| mtmotion::feed_vector::command::angle(i as f64 * dt, 4.0 * PI, 0.064))
            .collect();
        assert!(simulate_axis(&axis, dt, &cmd).unwrap().saturated);
        let mut g = c.benchmark_group("servo");
        g.throughput(Throughput::Elements(n as u64));
        g.bench_function("simulate_axis_saturating_precontrol_1e5_steps", |b| {
            b.iter(|| simulate_axis(black_box(&axis), dt, black_box(&cmd)).unwrap())
        });
        g.finish();
        let omegas: Vec<f64> = (0..1000).map(|i| 0.1 * 1.01f64.powi(i)).collect();
        c.bench_function("frequency_response_1000_points", |b| {
            b.iter(|| frequency_response(black_box(&axis), black_box(&omegas)).unwrap())
        });
    }

    fn feed_vector(c: &mut Criterion) {
        let m = machine::preset("nmv5000").unwrap();
        let cond = Condition {
            duration: Some(2.0),
            dt: Some(1e-4),
            ..Condition::paper(PI)
        };
        c.bench_function("feed_vector_test_3_axes_2s_at_0.1ms", |b| {
            b.iter(|| feed_vector_test(black_box(&m), black_box(&cond)).unwrap())
        });
    }

    fn best(c: &mut Criterion) {
        let m = machine::preset("nmv5000").unwrap();
        let cond = Condition::paper(3.2 * PI);
        let opts = Options {
            method: Method::Simulated,
            ..Options::default()
        };
        let mut g = c.benchmark_group("best_kffp");
        g.sample_size(10);
        g.bench_function("best_kffp_simulated_3.2pi", |b| {
            b.iter(|| best_kffp(black_box(&m), black_box(&cond), &opts).unwrap())
        });
        g.finish();
    }

    criterion_group!(benches, simulate, feed_vector, best);
}

#[cfg(not(target_arch = "wasm32"))]
criterion::criterion_main!(native::benches);

#[cfg(target_arch = "wasm32")]
fn main() {}
