//! Benchmarks of the NC reader (criterion, native). Mirrors `src/nc/`:
//! parse alone, and parse + simulate (dt = 1 ms), of a generated
//! 200,000-line finishing program: short chords (0.05–0.15 mm) with every
//! seventh block a small arc (I/J), at F3000, as CAM posts write raster
//! finishing. Kept under a minute in all (10 samples each).

#[cfg(not(target_arch = "wasm32"))]
mod native {
    use criterion::{black_box, criterion_group, Criterion, Throughput};
    use mtmotion::nc::program::parse;
    use mtmotion::toolpath::{simulate_text, SimConfig};

    /// Lines of the generated program.
    pub const LINES: usize = 200_000;

    /// [`LINES`] lines: a header, then chords of 0.05–0.15 mm along a wavy
    /// line, every seventh an arc of radius 2 mm to the same kind of end
    /// point (centre on the chord's left normal).
    pub fn finishing_program() -> String {
        let mut s = String::with_capacity(LINES * 24);
        s.push_str("G90 G17 G21\nG0 X0 Y0 Z5\nG1 Z0 F3000\n");
        let (mut x, mut y) = (0.0f64, 0.0f64);
        for i in 0..LINES - 3 {
            let len = 0.05 + 0.05 * (i % 3) as f64;
            let ang = (i as f64 * 0.01).sin() * 0.8;
            let (dx, dy) = (len * ang.cos(), len * ang.sin());
            let (nx, ny) = (x + dx, y + dy);
            if i % 7 == 6 {
                // centre at distance h from the chord's midpoint on its
                // left, so that its radius is 2 mm
                let h = (4.0 - len * len / 4.0).sqrt();
                let (cx, cy) = (x + dx / 2.0 - h * dy / len, y + dy / 2.0 + h * dx / len);
                s.push_str(&format!(
                    "G3 X{nx:.4} Y{ny:.4} I{:.4} J{:.4}\n",
                    cx - x,
                    cy - y
                ));
            } else {
                s.push_str(&format!("G1 X{nx:.4} Y{ny:.4}\n"));
            }
            (x, y) = (nx, ny);
        }
        s
    }

    fn benches(c: &mut Criterion) {
        let text = finishing_program();
        let cfg = SimConfig::default();
        let mut g = c.benchmark_group("nc");
        g.sample_size(10);
        g.throughput(Throughput::Elements(LINES as u64));
        g.bench_function("parse_200k_lines", |b| {
            b.iter(|| parse(black_box(&text)).unwrap())
        });
        g.bench_function("parse_and_simulate_200k_lines_dt1ms", |b| {
            b.iter(|| simulate_text(black_box(&text), &cfg).unwrap())
        });
        g.finish();
    }

    criterion_group!(nc, benches);
}

#[cfg(not(target_arch = "wasm32"))]
criterion::criterion_main!(native::nc);

#[cfg(target_arch = "wasm32")]
fn main() {}
