//! Benchmarks of the kinematics models (criterion, native). Mirrors `src/`:
//! forward kinematics (nominal and with errors), inverse kinematics, the
//! 3600-point cone-frustum test with servo models, and the S-shape
//! compensation.

#[cfg(not(target_arch = "wasm32"))]
mod native {
    use criterion::{black_box, criterion_group, Criterion};
    use mtmotion::compensate::nc5::{compensate_nc5, s_shape, Nc5Config};
    use mtmotion::cone_frustum::{cone_frustum_test, ConeFrustumConfig, Method};
    use mtmotion::kinematics::inverse::NO_LIMITS;
    use mtmotion::kinematics::{inverse, GeometricErrors, Model};
    use mtmotion::machine::MachineRef;

    fn kinematics(c: &mut Criterion) {
        let chain = mtmotion::machine::preset("trunnion-ac")
            .unwrap()
            .kinematics
            .unwrap();
        let nominal = Model::new(&chain, &GeometricErrors::default(), 50.0).unwrap();
        let mut e = GeometricErrors::default();
        for (k, v) in [
            ("EX0C", 0.01),
            ("EY0C", -0.005),
            ("EA0C", 2e-5),
            ("EB0C", -1e-5),
            ("EY0A", 0.02),
            ("EC0Y", 1e-5),
        ] {
            e.location.insert(k.into(), v);
        }
        let with_errors = Model::new(&chain, &e, 50.0).unwrap();
        let q = [10.0, 20.0, 30.0, 0.3, 0.0, 0.7];
        c.bench_function("fk_trunnion_ac_nominal", |b| {
            b.iter(|| nominal.eval(black_box(&q)))
        });
        c.bench_function("fk_trunnion_ac_errors", |b| {
            b.iter(|| with_errors.eval(black_box(&q)))
        });
        let pose = nominal.pose(&q);
        c.bench_function("ik_trunnion_ac_all_branches", |b| {
            b.iter(|| inverse(&chain, black_box(&pose), 50.0, &NO_LIMITS).unwrap())
        });
        let mut cfg = ConeFrustumConfig {
            machine: MachineRef::Name("trunnion-ac".into()),
            half_apex_deg: 45.0,
            inclination_deg: 10.0,
            method: Method::Perpendicular,
            bar_length: 100.0,
            feed: 1000.0,
            radius: None,
            centre: Some([60.0, 40.0, 20.0]),
            errors: GeometricErrors::default(),
            drives: Default::default(),
            ideal_servo: false,
            tool_length: 0.0,
            points: 3600,
            clockwise: false,
            lead_in_deg: 0.0,
            sensitivities: true,
        };
        cfg.drives.backlash.insert("c".into(), 1.745e-4);
        let mut g = c.benchmark_group("cone_frustum");
        g.sample_size(10);
        g.bench_function("cone_frustum_3600_servo", |b| {
            b.iter(|| cone_frustum_test(black_box(&cfg)).unwrap())
        });
        let program = s_shape::s_shape(&s_shape::SShapeOptions::paper(MachineRef::Name(
            "pocketnc-v2-10".into(),
        )))
        .unwrap()
        .nc;
        let nc_cfg = Nc5Config {
            machine: MachineRef::Name("pocketnc-v2-10".into()),
            errors: GeometricErrors::default(),
            tool_length: 0.0,
            monte_carlo: Some(Default::default()),
            cutting: None,
            compensate_axes: None,
            feed_drive: None,
        };
        g.bench_function("compensate_nc5_s_shape_64", |b| {
            b.iter(|| compensate_nc5(black_box(&program), &nc_cfg).unwrap())
        });
        g.finish();
    }

    criterion_group!(benches, kinematics);
}

#[cfg(not(target_arch = "wasm32"))]
criterion::criterion_main!(native::benches);

#[cfg(target_arch = "wasm32")]
fn main() {}
