//! Under Node: the kinematics bindings cross correctly — degrees in and
//! out, Float64Arrays for bulk data, every IK branch, the cone-frustum
//! result shape, NC compensation — and bad input throws an `Error` with the
//! core's message.
#![cfg(target_arch = "wasm32")]

use js_sys::{Float64Array, Reflect};
use mtmotion::wasm::kinematics as k;
use wasm_bindgen::{JsCast, JsValue};
use wasm_bindgen_test::wasm_bindgen_test;

fn get(v: &JsValue, path: &[&str]) -> JsValue {
    path.iter().fold(v.clone(), |acc, key| {
        Reflect::get(&acc, &JsValue::from_str(key)).unwrap()
    })
}

fn js(s: &str) -> JsValue {
    js_sys::JSON::parse(s).unwrap()
}

fn message(e: wasm_bindgen::JsError) -> String {
    let v: JsValue = e.into();
    let e: js_sys::Error = v.dyn_into().expect("a JS Error");
    e.message().into()
}

#[wasm_bindgen_test]
fn forward_takes_degrees_and_errors() {
    // C = 90°: a point at x = 10 on the table is seen at y = 10... the tool at
    // x = 10 sits at workpiece y = 10 after the table turned.
    let p = k::forward_kinematics(
        js("\"trunnion-ac\""),
        js("[10, 0, 0, 0, 0, 90]"),
        JsValue::UNDEFINED,
        JsValue::UNDEFINED,
    )
    .unwrap();
    let pos: Vec<f64> = serde_wasm_bindgen::from_value(get(&p, &["position"])).unwrap();
    assert!((pos[1] - 10.0).abs() < 1e-12 && pos[0].abs() < 1e-12);
    let e = js(r#"{"location": {"EC0C": 0.001}}"#);
    let p = k::forward_kinematics(
        js("\"trunnion-ac\""),
        js(r#"{"x": 10}"#),
        e,
        JsValue::UNDEFINED,
    )
    .unwrap();
    let pos: Vec<f64> = serde_wasm_bindgen::from_value(get(&p, &["position"])).unwrap();
    assert!((pos[1] - 10.0 * 0.001f64.sin()).abs() < 1e-12);
}

#[wasm_bindgen_test]
fn bulk_forward_matches_single_calls() {
    let q = [
        10.0, 20.0, 30.0, 15.0, 0.0, 40.0, -5.0, 0.0, 3.0, 60.0, 0.0, -170.0,
    ];
    let r = k::forward_kinematics_bulk(
        js("\"trunnion-ac\""),
        Float64Array::from(&q[..]).into(),
        JsValue::UNDEFINED,
        JsValue::from_f64(25.0),
    )
    .unwrap();
    let pos = get(&r, &["position"])
        .dyn_into::<Float64Array>()
        .unwrap()
        .to_vec();
    assert_eq!(pos.len(), 6);
    let one = k::forward_kinematics(
        js("\"trunnion-ac\""),
        js("[-5, 0, 3, 60, 0, -170]"),
        JsValue::UNDEFINED,
        JsValue::from_f64(25.0),
    )
    .unwrap();
    let p1: Vec<f64> = serde_wasm_bindgen::from_value(get(&one, &["position"])).unwrap();
    for i in 0..3 {
        assert!((pos[3 + i] - p1[i]).abs() < 1e-12);
    }
    let err = message(
        k::forward_kinematics_bulk(
            js("\"trunnion-ac\""),
            Float64Array::from(&q[..7]).into(),
            JsValue::UNDEFINED,
            JsValue::UNDEFINED,
        )
        .unwrap_err(),
    );
    assert!(err.contains("6 values"), "{err}");
}

#[wasm_bindgen_test]
fn inverse_returns_every_branch_in_degrees() {
    let pose = k::forward_kinematics(
        js("\"table-on-table-bc\""),
        js("[10, 20, 30, 0, 40, 30]"),
        JsValue::UNDEFINED,
        JsValue::UNDEFINED,
    )
    .unwrap();
    let sols =
        k::inverse_kinematics(js("\"table-on-table-bc\""), pose, JsValue::UNDEFINED).unwrap();
    let arr: js_sys::Array = sols.dyn_into().unwrap();
    assert!(arr.length() >= 2, "C ±360° copies");
    let found = arr.iter().any(|s| {
        let b = get(&s, &["q", "b"]).as_f64().unwrap();
        let c = get(&s, &["q", "c"]).as_f64().unwrap();
        (b - 40.0).abs() < 1e-9 && (c - 30.0).abs() < 1e-9
    });
    assert!(found);
}

#[wasm_bindgen_test]
fn cone_frustum_crosses_and_validates() {
    let opts = js(
        r#"{"machine": "trunnion-ac", "halfApexDeg": 45, "inclinationDeg": 10, "feed": 1000,
        "centre": [60, 40, 20], "idealServo": true, "points": 360, "errors": {"location": {"EX0C": 0.01}}}"#,
    );
    let r = k::cone_frustum_test(opts, JsValue::UNDEFINED).unwrap();
    let dev = get(&r, &["deviation"])
        .dyn_into::<Float64Array>()
        .unwrap()
        .to_vec();
    assert_eq!(dev.len(), 360);
    assert!(dev.iter().any(|d| d.abs() > 1e-3));
    let s = get(&r, &["sensitivity", "errors", "EX0C"])
        .dyn_into::<Float64Array>()
        .unwrap()
        .to_vec();
    // First order: deviation ≈ S·0.01 mm.
    for (d, s) in dev.iter().zip(&s) {
        assert!((d - 0.01 * s).abs() < 1e-5);
    }
    let c = get(&r, &["axes", "c", "command"])
        .dyn_into::<Float64Array>()
        .unwrap()
        .to_vec();
    assert!(c.iter().any(|v| v.abs() > 10.0), "C in degrees");
    let bad =
        js(r#"{"machine": "trunnion-ac", "halfApexDeg": 95, "inclinationDeg": 10, "feed": 1000}"#);
    let err = message(k::cone_frustum_test(bad, JsValue::UNDEFINED).unwrap_err());
    assert!(err.contains("halfApexDeg"), "{err}");
}

#[wasm_bindgen_test]
fn compensate_nc5_crosses_and_names_lines() {
    let opts = js(r#"{"machine": "trunnion-ac", "errors": {"location": {"EY0A": 0.03}}}"#);
    let r = k::compensate_nc5(
        JsValue::from_str("G90 G21\nG0 X10 Y0 Z5 A10 C0\nG1 X20 Y5 Z5 A20 C30 F500\n"),
        opts.clone(),
    )
    .unwrap();
    assert!(get(&r, &["nc"]).as_string().unwrap().contains("G1"));
    let x = get(&r, &["beforePoints", "y"])
        .dyn_into::<Float64Array>()
        .unwrap()
        .to_vec();
    assert_eq!(x.len(), 2);
    let err = message(
        k::compensate_nc5(JsValue::from_str("G90\nG1 X1 F100\nG2 X2 Y1 R1\n"), opts).unwrap_err(),
    );
    assert!(err.contains("line 3"), "{err}");
    let err = message(
        k::compensate_nc5(JsValue::from_str("G1 X1 F1"), js(r#"{"machine": "nope"}"#)).unwrap_err(),
    );
    assert!(err.contains("nope") && err.contains("trunnion-ac"), "{err}");
}

#[wasm_bindgen_test]
fn example_errors_cross_with_the_preset_and_feed_the_cone_frustum_test() {
    let m =
        mtmotion::wasm::machine::machine_preset(js("\"trunnion-ac\""), JsValue::UNDEFINED).unwrap();
    let ex = get(&m, &["exampleErrors"]);
    assert!((get(&ex, &["location", "EX0C"]).as_f64().unwrap() - 0.015).abs() < 1e-15);
    let drives = get(&m, &["exampleDrives"]);
    let c = get(&drives, &["backlash", "c"]).as_f64().unwrap();
    assert!((c - 0.01_f64.to_radians()).abs() < 1e-15);
    let opts = js(
        r#"{"machine":"trunnion-ac","halfApexDeg":45,"inclinationDeg":10,"feed":1000,"centre":[60,40,20],"idealServo":true,"points":360}"#,
    );
    Reflect::set(&opts, &JsValue::from_str("errors"), &ex).unwrap();
    Reflect::set(&opts, &JsValue::from_str("drives"), &drives).unwrap();
    let r = k::cone_frustum_test(opts, JsValue::UNDEFINED).unwrap();
    let max = get(&r, &["maxDeviation"]).as_f64().unwrap();
    let min = get(&r, &["minDeviation"]).as_f64().unwrap();
    assert!(max.max(-min) > 1e-3, "example errors read {min}..{max} mm");
}
