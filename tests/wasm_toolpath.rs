//! Under Node: the tool-path bindings end to end — parseNc returns plain
//! segment objects with warnings, simulateToolPath returns Float64Arrays
//! whose maximum matches maxErrorUm, radiusReduction equals Eq. 3,
//! identifyAccDec recovers tA and T, reverseCompensate returns a corrected
//! program, and bad input throws an Error carrying the core's message.
#![cfg(target_arch = "wasm32")]

use js_sys::{Float64Array, Reflect};
use wasm_bindgen::{JsCast, JsValue};
use wasm_bindgen_test::wasm_bindgen_test;

use mtmotion::wasm::toolpath as tp;

fn get(v: &JsValue, path: &[&str]) -> JsValue {
    path.iter().fold(v.clone(), |acc, k| {
        Reflect::get(&acc, &JsValue::from_str(k)).unwrap()
    })
}

fn message(e: wasm_bindgen::JsError) -> String {
    let v: JsValue = e.into();
    v.dyn_into::<js_sys::Error>().unwrap().message().into()
}

fn cfg(json: &str) -> JsValue {
    js_sys::JSON::parse(json).unwrap()
}

#[wasm_bindgen_test]
fn parse_nc_crosses_as_plain_objects() {
    let p = tp::parse_nc(
        JsValue::from_str("N1 G0 X10 Y0 M3\nN2 G3 X-10 Y0 R10 F2000"),
        JsValue::UNDEFINED,
    )
    .unwrap();
    assert!(!p.is_instance_of::<js_sys::Map>());
    assert_eq!(
        get(&p, &["segments", "1", "motion", "type"])
            .as_string()
            .as_deref(),
        Some("arc")
    );
    assert_eq!(
        get(&p, &["segments", "1", "motion", "radius"]).as_f64(),
        Some(10.0)
    );
    assert_eq!(get(&p, &["segments", "1", "feed"]).as_f64(), Some(2000.0));
    assert_eq!(get(&p, &["warnings", "0", "column"]).as_f64(), Some(14.0));
}

#[wasm_bindgen_test]
fn simulate_returns_arrays_and_summary() {
    let r = tp::simulate_tool_path(
        JsValue::from_str("G0 X10 Y0\nG3 X10 Y0 I-10 J0 F2000"),
        cfg(r#"{"tA":0.04,"T":[0.015,0.015,0.015],"dt":0.001}"#),
        JsValue::UNDEFINED,
    )
    .unwrap();
    let err: Float64Array = get(&r, &["errorUm"]).dyn_into().unwrap();
    let max = err.to_vec().into_iter().fold(0.0, f64::max);
    let reported = get(&r, &["maxErrorUm"]).as_f64().unwrap();
    assert!(reported > 10.0 && (max - reported).abs() < 1e-9);
    let t: Float64Array = get(&r, &["t"]).dyn_into().unwrap();
    assert_eq!(t.length(), err.length());
    assert_eq!(
        get(&r, &["segments", "1", "kind"]).as_string().as_deref(),
        Some("arc")
    );
}

#[wasm_bindgen_test]
fn eq3_and_identification() {
    let dr = tp::radius_reduction(cfg(r#"{"feed":2000,"radius":10,"tA":0.04,"T":0.015}"#)).unwrap();
    let w: f64 = 2000.0 / 60.0 / 10.0;
    let x = 0.02 * w;
    let expect = (1.0 - x.sin() / x / (0.015f64.powi(2) * w * w + 1.0).sqrt()) * 10.0;
    assert!((dr - expect).abs() < 1e-15);
    let rows: Vec<String> = [(2000.0, 3.0), (5000.0, 5.0), (8000.0, 4.0), (3000.0, 20.0)]
        .iter()
        .map(|&(f, r)| {
            let loss = mtmotion::toolpath::identify::radius_reduction(f, r, 0.05, 0.02).unwrap();
            format!(r#"{{"feed":{f},"radius":{r},"radiusLoss":{loss}}}"#)
        })
        .collect();
    let id = tp::identify_acc_dec(cfg(&format!("[{}]", rows.join(",")))).unwrap();
    assert!((get(&id, &["tA"]).as_f64().unwrap() - 0.05).abs() < 1e-6);
    assert!((get(&id, &["T"]).as_f64().unwrap() - 0.02).abs() < 1e-6);
}

#[wasm_bindgen_test]
fn reverse_compensation_crosses() {
    let nc = tp::toolpath_example(JsValue::from_str("arcs")).unwrap();
    let r = tp::reverse_compensate_js(
        JsValue::from_str(&nc),
        JsValue::UNDEFINED,
        JsValue::UNDEFINED,
    )
    .unwrap();
    let text = get(&r, &["nc"]).as_string().unwrap();
    assert!(text.contains("N40 G3") && text.contains("(C)"));
    let before = get(&r, &["before", "maxErrorUm"]).as_f64().unwrap();
    let after = get(&r, &["after", "maxErrorUm"]).as_f64().unwrap();
    assert!(after < 0.5 * before);
    assert!(get(&r, &["afterSim", "errorUm"]).is_instance_of::<Float64Array>());
}

#[wasm_bindgen_test]
fn bad_input_throws_the_core_message() {
    let e = tp::parse_nc(
        JsValue::from_str("G0 X0 Y0\nG2 X10 Y0 F100"),
        JsValue::UNDEFINED,
    )
    .unwrap_err();
    assert_eq!(
        message(e),
        "line 2, column 4: arc (G2) without a centre in the G17 plane; expected I/J or R"
    );
    let e = tp::simulate_tool_path(
        JsValue::from_str("G1 X1 F100"),
        cfg(r#"{"dt":0}"#),
        JsValue::UNDEFINED,
    )
    .unwrap_err();
    assert!(message(e).starts_with("dt: expected a sampling interval"));
    let e =
        tp::radius_reduction(cfg(r#"{"feed":2000,"radius":-1,"tA":0.04,"T":0.01}"#)).unwrap_err();
    assert_eq!(
        message(e),
        "radius: expected a radius from 0.001 to 1e6 mm, got -1"
    );
    let e = tp::identify_acc_dec(cfg(r#"[{"feed":2000,"radius":10,"radiusLoss":0.01},{"feed":4000,"radius":20,"radiusLoss":0.01}]"#)).unwrap_err();
    assert!(message(e).contains("same angular velocity"));
    let e = tp::toolpath_example(JsValue::from_str("spiral")).unwrap_err();
    assert!(message(e).contains("expected 'arcs' or 'lines'"));
}
