//! Native timing of the servo step for `node bench/node/run.mjs servo`, which
//! runs it (`cargo bench --bench servo_step`) and prints the wasm/native
//! ratio. The same case as bench/node/servo.bench.mjs: the nmv5000 C axis
//! with J1 = 1.7 kg·m², a 4π rad/s ramp with 0.064 s acc/dec (the torque
//! saturates), 1e5 steps at 0.1 ms, Pre-Control on. Prints one JSON line:
//! the median over rounds of each round's fastest call, in ns per step.

#[cfg(not(target_arch = "wasm32"))]
fn main() {
    use mtmotion::feed_vector::command::angle;
    use mtmotion::servo::simulate::simulate_axis;
    use std::hint::black_box;
    use std::time::Instant;

    let mut axis = mtmotion::machine::preset("nmv5000").unwrap().axes["c"].clone();
    axis.j1 = 1.7;
    let (dt, n) = (1e-4, 100_000);
    let cmd: Vec<f64> = (0..n)
        .map(|i| angle(i as f64 * dt, 4.0 * std::f64::consts::PI, 0.064))
        .collect();
    assert!(simulate_axis(&axis, dt, &cmd).unwrap().saturated);
    let mut rounds: Vec<f64> = (0..15)
        .map(|_| {
            (0..10)
                .map(|_| {
                    let t0 = Instant::now();
                    black_box(simulate_axis(black_box(&axis), dt, black_box(&cmd)).unwrap());
                    t0.elapsed().as_secs_f64()
                })
                .fold(f64::INFINITY, f64::min)
        })
        .collect();
    rounds.sort_by(f64::total_cmp);
    println!(
        "{{\"nsPerStep\": {}}}",
        rounds[rounds.len() / 2] * 1e9 / n as f64
    );
}

#[cfg(target_arch = "wasm32")]
fn main() {}
