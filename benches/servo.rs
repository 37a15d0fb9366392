//! Benchmarks of the servo models (criterion, native). Mirrors `src/`.
//! Filled in under the issue that implements the models.

#[cfg(not(target_arch = "wasm32"))]
mod native {
    use criterion::{black_box, criterion_group, Criterion};

    fn placeholder(c: &mut Criterion) {
        c.bench_function("machine_preset_nmv5000", |b| {
            b.iter(|| mtmotion::machine::preset(black_box("nmv5000")))
        });
    }

    criterion_group!(benches, placeholder);
}

#[cfg(not(target_arch = "wasm32"))]
criterion::criterion_main!(native::benches);

#[cfg(target_arch = "wasm32")]
fn main() {}
