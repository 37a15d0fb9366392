//! Benchmarks of the toolpath models (criterion, native). Mirrors `src/`:
//! simulation throughput on the built-in arc example, a 10,000-segment
//! program at dt = 1 ms (target < 1 s), and the reverse compensation of the
//! arc example (target < 500 ms).

#[cfg(not(target_arch = "wasm32"))]
mod native {
    use criterion::{black_box, criterion_group, Criterion, Throughput};
    use mtmotion::compensate::reverse::{reverse_compensate, ReverseConfig};
    use mtmotion::toolpath::{example, simulate_text, SimConfig};

    /// 10,000 segments: a wavy line of 1–3 mm chords with every fifth
    /// segment an arc, at F3000.
    pub fn long_program() -> String {
        let mut s = String::from("G90 G17 G21\nG0 X0 Y0\nG1 X1 Y0 F3000\n");
        let (mut x, mut y) = (1.0f64, 0.0f64);
        for i in 0..9_999 {
            let len = 1.0 + (i % 3) as f64;
            let ang = (i as f64 * 0.05).sin() * 0.6;
            let (nx, ny) = (x + len * ang.cos(), y + len * ang.sin());
            if i % 5 == 4 {
                s.push_str(&format!("G3 X{nx:.4} Y{ny:.4} R{:.4}\n", 5.0 * len));
            } else {
                s.push_str(&format!("G1 X{nx:.4} Y{ny:.4}\n"));
            }
            (x, y) = (nx, ny);
        }
        s
    }

    fn benches(c: &mut Criterion) {
        let arcs = example::arc_example();
        let cfg = SimConfig::default();
        let n = simulate_text(&arcs, &cfg).unwrap().t.len() as u64;
        let mut g = c.benchmark_group("toolpath");
        g.throughput(Throughput::Elements(n));
        g.bench_function("simulate_arc_example_dt1ms", |b| {
            b.iter(|| simulate_text(black_box(&arcs), &cfg).unwrap())
        });
        let fine = SimConfig { dt: 1e-4, ..cfg };
        let n = simulate_text(&arcs, &fine).unwrap().t.len() as u64;
        g.throughput(Throughput::Elements(n));
        g.bench_function("simulate_arc_example_dt0.1ms", |b| {
            b.iter(|| simulate_text(black_box(&arcs), &fine).unwrap())
        });
        let long = long_program();
        let n = simulate_text(&long, &cfg).unwrap().t.len() as u64;
        g.throughput(Throughput::Elements(n));
        g.sample_size(10);
        g.bench_function("simulate_10000_segments_dt1ms", |b| {
            b.iter(|| simulate_text(black_box(&long), &cfg).unwrap())
        });
        g.throughput(Throughput::Elements(1));
        g.bench_function("reverse_compensate_arc_example", |b| {
            b.iter(|| reverse_compensate(black_box(&arcs), &ReverseConfig::default()).unwrap())
        });
        g.finish();
    }

    criterion_group!(toolpath, benches);
}

#[cfg(not(target_arch = "wasm32"))]
criterion::criterion_main!(native::toolpath);

#[cfg(target_arch = "wasm32")]
fn main() {}
