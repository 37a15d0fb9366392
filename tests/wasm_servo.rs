#![cfg(target_arch = "wasm32")]
//! The servo bindings cross correctly (Float64Arrays out, camelCase
//! summaries, preset names or objects in) and bad input throws an `Error`
//! carrying the core's message.

use js_sys::{Float64Array, Object, Reflect};
use mtmotion::wasm::machine::machine_preset;
use mtmotion::wasm::servo::*;
use wasm_bindgen::prelude::*;
use wasm_bindgen_test::*;

fn get(v: &JsValue, k: &str) -> JsValue {
    Reflect::get(v, &JsValue::from_str(k)).unwrap()
}

fn message(e: JsError) -> String {
    let v: JsValue = e.into();
    get(&v, "message").as_string().unwrap()
}

fn c_axis() -> JsValue {
    get(
        &get(
            &machine_preset("nmv5000".into(), JsValue::UNDEFINED).unwrap(),
            "axes",
        ),
        "c",
    )
}

#[wasm_bindgen_test]
fn frequency_response_crosses_as_float64_arrays() {
    let r = frequency_response(
        c_axis(),
        js_sys::Float64Array::from(&[1.0, 10.0][..]).into(),
    )
    .unwrap();
    let mag = Float64Array::from(get(&r, "magnitude")).to_vec();
    let ph = Float64Array::from(get(&r, "phase")).to_vec();
    let core = mtmotion::servo::response::frequency_response(
        &mtmotion::machine::preset("nmv5000").unwrap().axes["c"],
        &[1.0, 10.0],
    )
    .unwrap();
    assert_eq!(mag, core.magnitude);
    assert_eq!(ph, core.phase);
}

#[wasm_bindgen_test]
fn simulate_axis_round_trip_and_errors() {
    let input = Object::new();
    let cmd: Vec<f64> = (0..500).map(|i| i as f64 * 1e-3).collect();
    Reflect::set(&input, &"dt".into(), &1e-3.into()).unwrap();
    Reflect::set(
        &input,
        &"position".into(),
        &Float64Array::from(&cmd[..]).into(),
    )
    .unwrap();
    let r = simulate_axis(c_axis(), input.clone().into()).unwrap();
    assert_eq!(Float64Array::from(get(&r, "position")).length(), 500);
    assert_eq!(get(&r, "saturated").as_bool(), Some(false));
    Reflect::set(&input, &"dt".into(), &(-1.0).into()).unwrap();
    let e = message(simulate_axis(c_axis(), input.into()).unwrap_err());
    assert!(e.contains("`dt`"), "{e}");
    let e = message(simulate_axis(JsValue::from_str("nope"), Object::new().into()).unwrap_err());
    assert!(e.starts_with("axis:"), "{e}");
}

fn condition(omega: f64) -> JsValue {
    let o = Object::new();
    for (k, v) in [
        ("rc", 5.0),
        ("rw", 8.0),
        ("omega", omega),
        ("accelTime", 0.064),
        ("j1", 1.7),
    ] {
        Reflect::set(&o, &k.into(), &v.into()).unwrap();
    }
    o.into()
}

#[wasm_bindgen_test]
fn feed_vector_best_kffp_and_saturation() {
    let r = feed_vector_test("nmv5000".into(), condition(std::f64::consts::PI)).unwrap();
    let s = get(&r, "summary");
    assert!(get(&s, "meanAngleDiff").as_f64().unwrap() > 0.0);
    assert_eq!(get(&s, "saturated").as_bool(), Some(false));
    assert!(Float64Array::from(get(&get(&r, "series"), "angleDiff")).length() > 1000);
    let b = best_kffp(
        "nmv5000".into(),
        condition(std::f64::consts::PI),
        JsValue::UNDEFINED,
    )
    .unwrap();
    assert_eq!(get(&b, "method").as_string().as_deref(), Some("analytic"));
    assert!(get(&b, "residualX").as_f64().unwrap().abs() < 1e-9);
    let q = Object::new();
    Reflect::set(&q, &"j1".into(), &js_sys::Array::of1(&1.7.into())).unwrap();
    for (k, v) in [
        ("torqueMax", 725.0),
        ("accelTime", 0.064),
        ("feedAtCuttingPoint", 200.0),
    ] {
        Reflect::set(&q, &k.into(), &v.into()).unwrap();
    }
    let p = torque_saturation("nmv5000".into(), q.into()).unwrap();
    let first = js_sys::Array::from(&p).get(0);
    assert!(get(&first, "omegaSat").as_f64().unwrap() > 5.0);
    let e = message(feed_vector_test("nope".into(), condition(1.0)).unwrap_err());
    assert!(e.contains("unknown machine preset"), "{e}");
    let e = message(feed_vector_test("nmv5000".into(), condition(-1.0)).unwrap_err());
    // In the user's words: the page's label and unit, not the code name.
    assert!(e.starts_with("ω [rad/s] = -1: "), "{e}");
}

#[wasm_bindgen_test]
fn trace_errors_name_line_and_column() {
    let e = analyze_feed_vector_trace(
        JsValue::from_str("time,x,y,c\n0,8,0,0\n0.001,8,?,0\n"),
        condition(1.0),
        JsValue::UNDEFINED,
    )
    .unwrap_err();
    assert_eq!(message(e), "line 3, column 3 ('y'): '?' is not a number");
}
