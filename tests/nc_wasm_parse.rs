//! Under Node: parseNc takes reading options (an unknown key throws naming
//! it), returns the program summary, and lists every error with its line.
#![cfg(target_arch = "wasm32")]

use js_sys::Reflect;
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

fn obj(json: &str) -> JsValue {
    js_sys::JSON::parse(json).unwrap()
}

#[wasm_bindgen_test]
fn options_and_summary() {
    let p = tp::parse_nc(
        JsValue::from_str("G4 P3\nG1 X10 F600"),
        obj(r#"{"dwellP":"seconds"}"#),
    )
    .unwrap();
    assert_eq!(
        get(&p, &["segments", "0", "motion", "seconds"]).as_f64(),
        Some(3.0)
    );
    // 3 s dwell + 10 mm at 600 mm/min = 4 s.
    let t = get(&p, &["summary", "motionTime"]).as_f64().unwrap();
    assert!((t - 4.0).abs() < 1e-12, "{t}");
    assert_eq!(get(&p, &["summary", "lines"]).as_f64(), Some(1.0));
    assert_eq!(get(&p, &["summary", "bboxMax", "0"]).as_f64(), Some(10.0));
    let e = tp::parse_nc(JsValue::from_str("G0 X1"), obj(r#"{"dwelP":"seconds"}"#)).unwrap_err();
    assert!(message(e).contains("dwelP"));
}

#[wasm_bindgen_test]
fn every_error_is_listed_with_its_line() {
    let e = tp::parse_nc(
        JsValue::from_str("G1 X1\nG0 X2\nG1 Y(open"),
        JsValue::UNDEFINED,
    )
    .unwrap_err();
    let m = message(e);
    assert!(m.starts_with("2 errors in the program:"), "{m}");
    assert!(
        m.contains("\nline 1, column 4: cutting move without a feed"),
        "{m}"
    );
    assert!(m.contains("\nline 3, column 4:"), "{m}");
}

#[wasm_bindgen_test]
fn check_nc_returns_errors_as_data() {
    let c = tp::check_nc(
        JsValue::from_str("G1 X1\nG0 X2\nG1 Y(open"),
        JsValue::UNDEFINED,
    )
    .unwrap();
    assert_eq!(get(&c, &["errors", "length"]).as_f64(), Some(2.0));
    assert_eq!(get(&c, &["errors", "1", "line"]).as_f64(), Some(3.0));
    assert_eq!(get(&c, &["errors", "1", "column"]).as_f64(), Some(4.0));
    assert!(get(&c, &["summary"]).is_null());
    let c = tp::check_nc(JsValue::from_str("G55 G0 X2"), JsValue::UNDEFINED).unwrap();
    assert_eq!(get(&c, &["errors", "length"]).as_f64(), Some(0.0));
    assert_eq!(get(&c, &["warnings", "0", "line"]).as_f64(), Some(1.0));
    assert_eq!(get(&c, &["summary", "rapids"]).as_f64(), Some(1.0));
}
