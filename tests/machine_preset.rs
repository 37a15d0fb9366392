//! The `nmv5000` preset carries suzuki-best-kffp Table 1 in SI units, and
//! serialises to the JS contract (camelCase, `kind`, `torqueMax`, `lead`).

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
