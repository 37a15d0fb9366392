//! The ball-bar bindings: results cross the JS boundary with the contract's
//! field names, Float64Arrays go in and out, and bad input throws an Error
//! carrying the core's message.
#![cfg(target_arch = "wasm32")]

use js_sys::{Array, Float64Array, Reflect};
use mtmotion::wasm::ballbar::*;
use wasm_bindgen::prelude::*;
use wasm_bindgen_test::*;

fn get(v: &JsValue, k: &str) -> JsValue {
    Reflect::get(v, &JsValue::from_str(k)).unwrap()
}
fn num(v: &JsValue, k: &str) -> f64 {
    get(v, k).as_f64().unwrap()
}
fn message(e: JsError) -> String {
    js_sys::Error::from(JsValue::from(e)).message().into()
}
fn arr(v: &[f64]) -> JsValue {
    Float64Array::from(v).into()
}
fn json(s: &str) -> JsValue {
    js_sys::JSON::parse(s).unwrap()
}

#[wasm_bindgen_test]
fn fit_circle_crosses_and_throws() {
    let (x, y): (Vec<f64>, Vec<f64>) = (0..30)
        .map(|i| {
            let t = (i as f64).to_radians();
            (1.0 + 50.0 * t.cos(), 2.0 + 50.0 * t.sin())
        })
        .unzip();
    let c = fit_circle(arr(&x), arr(&y)).unwrap();
    assert!((num(&c, "cx") - 1.0).abs() < 1e-9 && (num(&c, "r") - 50.0).abs() < 1e-9);
    assert!(num(&c, "rmsResidual") < 1e-9);
    let e = message(fit_circle(arr(&[0.0, 1.0]), arr(&[0.0, 1.0])).unwrap_err());
    assert_eq!(e, "a circle needs at least 3 points, got 2");
}

#[wasm_bindgen_test]
fn harmonics_and_sweeps_cross() {
    let th: Vec<f64> = (0..360).map(|i| (i as f64).to_radians()).collect();
    let dr: Vec<f64> = th.iter().map(|t| 0.005 * (2.0 * t).sin()).collect();
    let h = Array::from(&harmonics(arr(&th), arr(&dr), JsValue::from_f64(3.0)).unwrap());
    assert_eq!(h.length(), 4);
    assert!((num(&h.get(2), "amplitude") - 0.005).abs() < 1e-12);
    let s = Array::from(&travel_range_sweep(json(r#"{"offset":{"z":0,"x":0.01},"harmonics":[{"order":2,"amplitude":0.005,"phase":0}],"ranges":[180,360],"radius":100,"samples":1000}"#)).unwrap());
    assert_eq!(num(&s.get(0), "rangeDeg"), 180.0);
    assert!(num(&s.get(0), "errorX") > 0.004 && num(&s.get(1), "errorX").abs() < 1e-9);
    let e = message(travel_range_sweep(json(r#"{"ranges":[500]}"#)).unwrap_err());
    assert!(e.starts_with("ranges[0]:"), "{e}");
    let e = message(travel_range_sweep(json(r#"{"ranges":"x"}"#)).unwrap_err());
    assert!(e.starts_with("config.ranges: expected an array"), "{e}");
    let a = Array::from(&angle_sweep(json(r#"{"sections":[{"y":350,"offset":{"z":0.02,"x":0}},{"y":-350,"offset":{"z":0,"x":0}}],"ranges":[90]}"#)).unwrap());
    assert!((num(&a.get(0), "deltaBz") - 0.02 / 700.0).abs() < 1e-12);
}

#[wasm_bindgen_test]
fn estimate_alignment_takes_float64_arrays() {
    let sec = |y: f64, cz: f64| {
        let a: Vec<f64> = (0..=90).map(|i| i as f64 - 45.0).collect();
        let d: Vec<f64> = a
            .iter()
            .map(|t| {
                let t = t.to_radians();
                (cz + 100.0 * t.cos()).hypot(100.0 * t.sin()) - 100.0
            })
            .collect();
        let o = js_sys::Object::new();
        Reflect::set(&o, &"y".into(), &y.into()).unwrap();
        Reflect::set(&o, &"angleDeg".into(), &Float64Array::from(&a[..])).unwrap();
        Reflect::set(&o, &"deviation".into(), &Float64Array::from(&d[..])).unwrap();
        o
    };
    let input = js_sys::Object::new();
    let list = Array::of2(&sec(350.0, 0.02), &sec(-350.0, 0.0));
    Reflect::set(&input, &"sections".into(), &list).unwrap();
    let r = estimate_alignment(input.clone().into()).unwrap();
    assert!((num(&r, "deltaBz") - 0.02 / 700.0).abs() < 2e-8);
    Reflect::set(
        &input,
        &"sections".into(),
        &Array::of1(&js_sys::Object::new()),
    )
    .unwrap();
    let e = message(estimate_alignment(input.into()).unwrap_err());
    assert_eq!(e, "sections[0].y: expected a number");
}

#[wasm_bindgen_test]
fn trace_round_trip_and_circular_test() {
    let t = synthetic_ballbar_trace(json(r#"{"backlashX":0.004,"feed":2000}"#)).unwrap();
    let runs = Array::from(&get(&t, "runs"));
    assert_eq!(runs.length(), 2);
    assert!(get(&runs.get(0), "angleRad").is_instance_of::<Float64Array>());
    let r = circular_test(t).unwrap();
    let d = get(&r, "diagnostics");
    assert!((num(&d, "backlashXUm") - 4.0).abs() < 0.05);
    assert!(num(&r, "hUm") > 3.9);
    let p = parse_ballbar_trace(
        JsValue::from_str("angle,deviation\n0,1\n1,x\n"),
        JsValue::UNDEFINED,
    )
    .unwrap_err();
    assert_eq!(
        message(p),
        "line 3, column 2 ('deviation'): 'x' is not a number"
    );
    let e = message(
        circular_test(json(r#"{"nominalRadius":100,"runs":[{"direction":"up"}]}"#)).unwrap_err(),
    );
    assert_eq!(e, "trace.runs[0].direction: expected 'ccw' or 'cw'");
}

#[wasm_bindgen_test]
fn paper_examples_cross() {
    let e = ballbar_example(JsValue::from_str("fig7"), JsValue::UNDEFINED).unwrap();
    assert_eq!(Array::from(&get(&e, "curves")).length(), 2);
    let e = message(ballbar_example(JsValue::from_str("fig99"), JsValue::UNDEFINED).unwrap_err());
    assert!(e.contains("unknown example"), "{e}");
}
