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

#[wasm_bindgen_test]
fn extra_files_hold_the_subprograms() {
    let files = r#"{"files":[{"name":"O2000.nc","text":"O2000\nG91 G1 X5 F100\nG90\nM99"},{"name":"bad.nc","text":"O3000\nG1 X\nM99"}]}"#;
    let good = r#"{"files":[{"name":"O2000.nc","text":"O2000\nG91 G1 X5 F100\nG90\nM99"}]}"#;
    let p = tp::parse_nc(JsValue::from_str("G0 X0\nM98 P2000\nM30"), obj(good)).unwrap();
    // An error in any file is reported, called or not.
    let e = tp::parse_nc(JsValue::from_str("G0 X0\nM98 P2000\nM30"), obj(files)).unwrap_err();
    assert!(message(e).contains("file bad.nc, line 2, column 4"));
    assert_eq!(get(&p, &["segments", "1", "end", "x"]).as_f64(), Some(5.0));
    let c = tp::check_nc(JsValue::from_str("M98 P3000\nM30"), obj(files)).unwrap();
    assert_eq!(
        get(&c, &["errors", "0", "file"]).as_string().as_deref(),
        Some("bad.nc")
    );
    assert_eq!(get(&c, &["errors", "0", "line"]).as_f64(), Some(2.0));
    let cfg =
        r#"{"files":[{"name":"O2000.nc","text":"O2000\nG91 G1 X5 F100\nG90\nM99"}],"tA":0,"T":0}"#;
    let s = tp::simulate_tool_path(
        JsValue::from_str("G0 X0\nM98 P2000\nM30"),
        obj(cfg),
        JsValue::UNDEFINED,
    )
    .unwrap();
    let t = get(&s, &["nominalTime"]).as_f64().unwrap();
    assert!((t - 3.0).abs() < 1e-9, "5 mm at 100 mm/min: {t}");
    let texts = js_sys::JSON::parse(r#"["O2000\nM99","G0 X0\nM30"]"#).unwrap();
    assert_eq!(tp::nc_main_file(texts).unwrap(), 1);
}

#[wasm_bindgen_test]
fn tool_radii_offset_the_compensated_path_and_are_validated() {
    let text = "G0 X0 Y0\nG41 D1 G1 X20 F400\nG3 X20 Y0 I-20 J0\nG40 G1 X0 Y0\nM30";
    // The G3 circle of radius 20 with G41 (tool inside): radius 20 − 2.
    for opts in [r#"{"toolRadii":{"D1":2}}"#, r#"{"toolRadii":"D1=2"}"#] {
        let p = tp::parse_nc(JsValue::from_str(text), obj(opts)).unwrap();
        let r = get(&p, &["segments", "2", "motion", "radius"])
            .as_f64()
            .unwrap();
        assert!((r - 18.0).abs() < 1e-9, "{opts}: {r}");
        let c = get(&p, &["summary", "cutterCompensation", "0"]);
        assert_eq!(get(&c, &["radius"]).as_f64(), Some(2.0));
        assert_eq!(get(&c, &["d"]).as_string().as_deref(), Some("D1"));
    }
    let p = tp::parse_nc(JsValue::from_str(text), JsValue::UNDEFINED).unwrap();
    assert!(get(&p, &["summary", "cutterCompensation", "0", "radius"]).is_null());
    assert_eq!(
        get(&p, &["summary", "warnings", "0", "kind"])
            .as_string()
            .as_deref(),
        Some("cutter compensation")
    );
    let e = tp::parse_nc(JsValue::from_str(text), obj(r#"{"toolRadii":{"D1":-2}}"#)).unwrap_err();
    assert!(message(e).contains("toolRadii D1"));
    let cfg = r#"{"toolRadii":"D1=2","tA":0,"T":0}"#;
    let s = tp::simulate_tool_path(JsValue::from_str(text), obj(cfg), JsValue::UNDEFINED).unwrap();
    let t = get(&s, &["nominalTime"]).as_f64().unwrap();
    // 18 mm start-up and 18 mm cancel at 400 mm/min, the circle of 18 mm.
    let want = (18.0 + 2.0 * std::f64::consts::PI * 18.0 + 18.0) / 400.0 * 60.0;
    assert!((t - want).abs() < 1e-9, "{t} vs {want}");
}
