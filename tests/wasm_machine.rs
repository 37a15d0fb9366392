//! Under Node: the binding pattern end to end — a preset crosses as a plain
//! object, an unknown name throws a JS `Error` carrying the core's message.
#![cfg(target_arch = "wasm32")]

use js_sys::Reflect;
use wasm_bindgen::{JsCast, JsValue};
use wasm_bindgen_test::wasm_bindgen_test;

fn get(v: &JsValue, path: &[&str]) -> JsValue {
    path.iter().fold(v.clone(), |acc, k| {
        Reflect::get(&acc, &JsValue::from_str(k)).unwrap()
    })
}

#[wasm_bindgen_test]
fn machine_preset_returns_plain_objects() {
    let m = mtmotion::wasm::machine::machine_preset("nmv5000".into(), JsValue::UNDEFINED).unwrap();
    assert!(!m.is_instance_of::<js_sys::Map>());
    assert_eq!(get(&m, &["axes", "c", "torqueMax"]).as_f64(), Some(725.0));
    assert_eq!(
        get(&m, &["axes", "x", "kind"]).as_string().as_deref(),
        Some("linear")
    );
    assert_eq!(get(&m, &["axes", "x", "lead"]).as_f64(), Some(0.016));
    // the paper's sweep crosses as data the page reads
    let sweep = get(&m, &["paperSweep"]);
    assert!(!sweep.is_instance_of::<js_sys::Map>());
    assert_eq!(get(&sweep, &["feedAtCuttingPoint"]).as_f64(), Some(200.0));
    assert_eq!(get(&sweep, &["j1", "2"]).as_f64(), Some(4.77));
    assert_eq!(
        get(&sweep, &["saturation", "0", "accelSat"]).as_f64(),
        Some(146.7)
    );
}

#[wasm_bindgen_test]
fn unknown_preset_throws_error_listing_names() {
    let err: JsValue = mtmotion::wasm::machine::machine_preset("dmu50".into(), JsValue::UNDEFINED)
        .unwrap_err()
        .into();
    let err: js_sys::Error = err.dyn_into().expect("a JS Error");
    let msg: String = err.message().into();
    assert!(msg.contains("dmu50") && msg.contains("nmv5000"), "{msg}");
}

#[wasm_bindgen_test]
fn a_non_string_name_throws_instead_of_trapping() {
    let err: JsValue =
        mtmotion::wasm::machine::machine_preset(JsValue::from_f64(3.0), JsValue::UNDEFINED)
            .unwrap_err()
            .into();
    let err: js_sys::Error = err.dyn_into().expect("a JS Error");
    let msg: String = err.message().into();
    assert_eq!(msg, "name: expected a string, got number");
}

#[wasm_bindgen_test]
fn a_loop_reading_is_applied_and_an_unknown_one_is_named() {
    let m = mtmotion::wasm::machine::machine_preset("nmv5000".into(), "kppText".into()).unwrap();
    assert_eq!(get(&m, &["axes", "x", "kpp"]).as_f64(), Some(30.0));
    let d = mtmotion::wasm::machine::machine_preset("nmv5000".into(), JsValue::UNDEFINED).unwrap();
    assert_eq!(get(&d, &["axes", "x", "kpp"]).as_f64(), Some(60.0));
    assert_eq!(
        get(&d, &["loopReadings", "0"]).as_string().as_deref(),
        Some("table")
    );
    let err: JsValue = mtmotion::wasm::machine::machine_preset("nmv5000".into(), "kpp".into())
        .unwrap_err()
        .into();
    let msg: String = err.dyn_into::<js_sys::Error>().unwrap().message().into();
    assert!(
        msg.contains("'kpp'") && msg.contains("inertiaAtLoad"),
        "{msg}"
    );
    let err: JsValue =
        mtmotion::wasm::machine::machine_preset("nmv5000".into(), JsValue::from_f64(1.0))
            .unwrap_err()
            .into();
    let msg: String = err.dyn_into::<js_sys::Error>().unwrap().message().into();
    assert_eq!(msg, "reading: expected a string, got number");
}
