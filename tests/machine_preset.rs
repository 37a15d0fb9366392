//! The `nmv5000` preset carries suzuki-best-kffp Table 1 in SI units and
//! the paper's test conditions (`paperSweep`), and serialises to the JS
//! contract (camelCase, `kind`, `torqueMax`, `lead`).

use mtmotion::machine;
use mtmotion::servo::AxisKind;

#[test]
fn nmv5000_matches_table_1() {
    let m = machine::preset("nmv5000").unwrap();
    let (x, y, c) = (&m.axes["x"], &m.axes["y"], &m.axes["c"]);
    assert_eq!(x.kind, AxisKind::Linear);
    assert_eq!(c.kind, AxisKind::Rotary);
    // Table 1 row by row: J, C, Kpp, Kvp, Kvi, Ts, Ta, Tp.
    let rows = [
        ([x.j, y.j, c.j], [4.5, 5.0, 4.2]),
        ([x.c, y.c, c.c], [1.0, 5.0, 5.0]),
        ([x.kpp, y.kpp, c.kpp], [60.0, 60.0, 60.0]),
        ([x.kvp, y.kvp, c.kvp], [177.5, 4700.0, 4700.0]),
        ([x.kvi, y.kvi, c.kvi], [0.198, 0.274, 0.274]),
        ([x.ts, y.ts, c.ts], [0.05, 0.064, 0.064]),
        ([x.ta, y.ta, c.ta], [0.015, 0.015, 0.015]),
        ([x.tp, y.tp, c.tp], [0.0155, 0.005, 0.005]),
    ];
    for (got, want) in rows {
        for (g, w) in got.iter().zip(want) {
            assert!((g - w).abs() < 1e-12, "{got:?} != {want:?}");
        }
    }
    assert_eq!(x.lead, Some(0.016));
    assert_eq!(c.torque_max, Some(725.0));
    assert!(m.source.contains("Table 1"));
}

#[test]
fn preset_serialises_to_the_js_contract() {
    let m = machine::preset("nmv5000").unwrap();
    let v = serde_json::to_value(&m).unwrap();
    let c = &v["axes"]["c"];
    assert_eq!(c["kind"], "rotary");
    assert_eq!(c["torqueMax"], 725.0);
    assert_eq!(v["axes"]["x"]["lead"], 0.016);
    for f in [
        "j", "j1", "c", "kpp", "kvp", "kvi", "kffp", "ts", "ta", "tp",
    ] {
        assert!(c[f].is_number(), "field {f} missing: {c}");
    }
}

/// The paper's test conditions (suzuki §3) and quoted saturation points
/// (§5.2, Figs. 17, 20, 21) are preset data, consistent with the preset:
/// each quoted J + J1 is the C axis' J plus a sweep load, and each quoted
/// R_C is F_C/ω at the quoted ω, within one unit of the last printed digit
/// (the paper prints 4.2 + 4.77 = 8.97 as 8.9, and 0.36 for 200/60/9.39 =
/// 0.355).
#[test]
fn nmv5000_carries_the_papers_sweep() {
    let m = machine::preset("nmv5000").unwrap();
    let s = m
        .paper_sweep
        .as_ref()
        .expect("nmv5000 has the paper's sweep");
    assert_eq!((s.rc, s.rw, s.accel_time), (5.0, 8.0, 0.064));
    assert_eq!(s.feed_at_cutting_point, 200.0);
    assert_eq!(s.j1, [1.70, 3.24, 4.77]);
    let pi = std::f64::consts::PI;
    let want: Vec<f64> = [0.5, 1.0, 1.5, 2.0, 3.0, 4.0]
        .iter()
        .map(|k| k * pi)
        .collect();
    assert_eq!(s.omega, want);
    let quoted: Vec<_> = s
        .saturation
        .iter()
        .map(|p| (p.j_total, p.accel_sat, p.omega_sat, p.rc_min))
        .collect();
    assert_eq!(
        quoted,
        [
            (5.9, 146.7, 9.39, 0.36),
            (7.4, 118.5, 7.58, 0.44),
            (8.9, 91.1, 5.83, 0.57)
        ]
    );
    // within one unit of the last printed digit: J + J1 to 0.1 kg·m² (8.97
    // prints as 8.9), R_C to 0.01 mm
    for (p, j1) in s.saturation.iter().zip(&s.j1) {
        assert!((p.j_total - (m.axes["c"].j + j1)).abs() < 0.1);
        let rc = s.feed_at_cutting_point / 60.0 / p.omega_sat;
        assert!((p.rc_min - rc).abs() <= 0.01, "{rc} vs {}", p.rc_min);
    }
    let v = serde_json::to_value(&m).unwrap();
    assert_eq!(v["paperSweep"]["feedAtCuttingPoint"], 200.0);
    assert_eq!(v["paperSweep"]["saturation"][0]["accelSat"], 146.7);
    assert!(machine::preset("trunnion-ac")
        .unwrap()
        .paper_sweep
        .is_none());
}
