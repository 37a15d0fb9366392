//! MATLAB v5 `.mat` captures (issue 26, item 2): a simulated
//! constant-feed-speed-vector trace written by this test as dSPACE
//! ControlDesk writes a capture (a struct with `X` = time and `Y(i)` with
//! `Name`, `Data`, `Unit`; compressed with zlib, and uncompressed in
//! big-endian byte order), as a Simulink structure with time, and as plain
//! vectors, reads back to the same numbers within 1e-9 relative and gives
//! the simulation's summary; every refusal names its byte offset and cause
//! (complex, sparse, v7.3, a cut-short file, damaged zlib, unequal lengths).
#![cfg(not(target_arch = "wasm32"))]

use mtmotion::feed_vector::trace_analysis::{analyze_trace_bytes, ColumnMap};
use mtmotion::feed_vector::FeedVectorResult;
use mtmotion::trace::{mat, read_bytes, read_table, ReadOptions};
#[path = "support/feed_vector_trace.rs"]
mod feed_vector_trace;
use feed_vector_trace::{close, sim};
#[path = "support/mat_writer.rs"]
mod mat_writer;
use mat_writer::Mat;

/// The simulation's columns: time (s), X, Y (mm), C (deg), torque (N·m).
fn signals(r: &FeedVectorResult) -> [Vec<f64>; 5] {
    let s = &r.series;
    [
        s.t.clone(),
        s.x.clone(),
        s.y.clone(),
        s.c.iter().map(|c| c.to_degrees()).collect(),
        s.torque_c.clone(),
    ]
}

const NAMES: [&str; 4] = ["X", "Y", "C", "Torque"];
const UNITS: [&str; 4] = ["mm", "mm", "deg", "Nm"];

fn dspace(r: &FeedVectorResult, big: bool, compress: bool) -> Vec<u8> {
    let w = Mat { big };
    let s = signals(r);
    let x = w.structure(
        "",
        &["Name", "Type", "Data", "Unit"],
        &[vec![
            w.chars("", "Time"),
            w.chars("", "Time"),
            w.doubles("", &s[0]),
            w.chars("", "s"),
        ]],
    );
    let ys: Vec<Vec<Vec<u8>>> = (0..4)
        .map(|k| {
            vec![
                w.chars("", &format!("Model Root/Axes/{}", NAMES[k])),
                w.chars("", "Y"),
                w.doubles("", &s[k + 1]),
                w.chars("", UNITS[k]),
            ]
        })
        .collect();
    let y = w.structure("", &["Name", "Type", "Data", "Unit"], &ys);
    let top = w.structure(
        "feedvector_001",
        &["X", "Y", "Description"],
        &[vec![x, y, w.chars("", "feed-vector test")]],
    );
    let mut out = w.header();
    out.extend(if compress { w.compressed(&top) } else { top });
    out
}

fn simulink(r: &FeedVectorResult) -> Vec<u8> {
    let w = Mat { big: false };
    let s = signals(r);
    let sig: Vec<Vec<Vec<u8>>> = (0..4)
        .map(|k| {
            let v = &s[k + 1];
            let data: Vec<u8> = v.iter().flat_map(|x| x.to_le_bytes()).collect();
            vec![
                w.matrix(6, 0, &[v.len(), 1], "", &w.el(9, &data)),
                w.chars("", NAMES[k]),
            ]
        })
        .collect();
    let signals = w.structure("", &["values", "label"], &sig);
    let top = w.structure(
        "ScopeData",
        &["time", "signals", "blockName"],
        &[vec![
            w.doubles("", &s[0]),
            signals,
            w.chars("", "model/Scope"),
        ]],
    );
    let mut out = w.header();
    out.extend(w.compressed(&top));
    out
}

fn vectors(r: &FeedVectorResult) -> Vec<u8> {
    let w = Mat { big: false };
    let s = signals(r);
    let mut out = w.header();
    for (k, n) in ["t", "x", "y", "c", "torque"].iter().enumerate() {
        out.extend(w.doubles(n, &s[k]));
    }
    out.extend(w.chars("note", "a text variable"));
    out
}

#[test]
fn captures_read_back_to_the_same_numbers() {
    let (_, r) = sim();
    let want = signals(&r);
    for (what, bytes, names) in [
        (
            "dSPACE compressed",
            dspace(&r, false, true),
            [
                "time [s]",
                "Model Root/Axes/X [mm]",
                "Model Root/Axes/Y [mm]",
                "Model Root/Axes/C [deg]",
                "Model Root/Axes/Torque [Nm]",
            ],
        ),
        (
            "dSPACE big-endian",
            dspace(&r, true, false),
            [
                "time [s]",
                "Model Root/Axes/X [mm]",
                "Model Root/Axes/Y [mm]",
                "Model Root/Axes/C [deg]",
                "Model Root/Axes/Torque [Nm]",
            ],
        ),
        (
            "Simulink",
            simulink(&r),
            ["time [s]", "X", "Y", "C", "Torque"],
        ),
        ("vectors", vectors(&r), ["t", "x", "y", "c", "torque"]),
    ] {
        let got =
            read_bytes(&bytes, &ReadOptions::default()).unwrap_or_else(|e| panic!("{what}: {e}"));
        assert_eq!(got.layout.format, "matV5", "{what}");
        assert_eq!(got.table.names, names, "{what}");
        for (k, col) in got.table.columns.iter().enumerate() {
            assert_eq!(col.len(), want[k].len(), "{what}");
            for (i, (a, b)) in col.iter().zip(&want[k]).enumerate() {
                assert!(close(*a, *b), "{what}: {} row {i}: {a} vs {b}", names[k]);
            }
        }
        assert_eq!(
            got.table.lines[..3],
            [1, 2, 3],
            "{what}: rows numbered by sample"
        );
        let notes = got.layout.notes.join(" | ");
        match what {
            "vectors" => assert!(
                notes.contains("variable 'note' is not a real vector: ignored"),
                "{notes}"
            ),
            "Simulink" => assert!(
                notes.contains("Simulink structure with time 'ScopeData': 4 signals"),
                "{notes}"
            ),
            _ => assert!(
                notes.contains("dSPACE capture 'feedvector_001': X (time) and 4 signals Y"),
                "{notes}"
            ),
        }
    }
}

#[test]
fn a_capture_gives_the_simulations_summary() {
    let (cond, r) = sim();
    let bytes = dspace(&r, false, true);
    let map = ColumnMap {
        steady_from: Some(r.summary.steady_from),
        x: Some("Model Root/Axes/X [mm]".into()),
        y: Some("Model Root/Axes/Y [mm]".into()),
        c: Some("Model Root/Axes/C [deg]".into()),
        torque: Some("Model Root/Axes/Torque [Nm]".into()),
        ..ColumnMap::default()
    };
    let tr = analyze_trace_bytes(&bytes, &cond, &map).unwrap();
    let d = (tr.summary.mean_angle_diff - r.summary.mean_angle_diff).abs();
    assert!(d < 1e-9, "{d} rad");
    assert_eq!(tr.summary.periods, r.summary.periods);
    // the same file read as text by mistake says what it is
    let e = read_table(&String::from_utf8_lossy(&bytes), &ReadOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("a MATLAB .mat file, which is read from its bytes"),
        "{e}"
    );
}

#[test]
fn every_refusal_names_its_byte_and_cause() {
    let w = Mat { big: false };
    let with = |body: Vec<u8>| [w.header(), body].concat();
    let data: Vec<u8> = [1.0f64, 2.0].iter().flat_map(|x| x.to_le_bytes()).collect();
    let complex = w.matrix(
        6,
        0x800,
        &[1, 2],
        "z",
        &[w.el(9, &data), w.el(9, &data)].concat(),
    );
    let sparse = w.matrix(5, 0, &[2, 2], "s", &[]);
    let mut v73 = w.header();
    v73[124] = 0;
    v73[125] = 2;
    let good = w.doubles("x", &[1.0, 2.0]);
    let cut = with(good[..good.len() - 9].to_vec());
    let mut bad_zlib = w.compressed(&good);
    let n = bad_zlib.len();
    bad_zlib[n - 6] ^= 0xff;
    let unequal = with(
        [
            w.doubles("t", &[0.0, 1.0, 2.0]),
            w.doubles("x", &[1.0, 2.0]),
        ]
        .concat(),
    );
    let text_only = with(w.chars("note", "hello"));
    let nan = with(
        [
            w.doubles("t", &[0.0, 1.0]),
            w.doubles("x", &[1.0, f64::NAN]),
        ]
        .concat(),
    );
    for (what, bytes, offset, cause) in [
        ("complex", with(complex), 136, "'z' is complex"),
        (
            "sparse",
            with(sparse),
            136,
            "'s' is mxSPARSE (a sparse matrix), which is not read",
        ),
        ("v7.3", v73, 124, "v7.3 (HDF5)"),
        ("cut", cut, 128, "the file is cut short"),
        (
            "zlib",
            with(bad_zlib),
            136,
            "miCOMPRESSED data do not inflate",
        ),
        ("unequal", unequal, 0, "'x' has 2 samples, 't' has 3"),
        ("text", text_only, 128, "no capture found"),
        ("nan", nan, 0, "'x' sample 2 is NaN"),
        (
            "endian",
            [&w.header()[..126], b"XX"].concat(),
            126,
            "endian mark",
        ),
        (
            "huge struct",
            with(w.matrix(
                2,
                0,
                &[1, 4_000_000],
                "s",
                &[w.small(5, &w.u32(32)), w.el(1, &[0u8; 32])].concat(),
            )),
            232,
            "a data element's tag needs 8 bytes, 0 left",
        ),
    ] {
        let e = read_bytes(&bytes, &ReadOptions::default())
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with(&format!("byte {offset}: MATLAB .mat: ")),
            "{what}: {e}"
        );
        assert!(e.contains(cause), "{what}: {e}");
    }
}

/// The bytes of `v` as data type `ty`, in the writer's byte order.
fn typed(w: &Mat, ty: u32, v: &[f64]) -> Vec<u8> {
    let b = |le: Vec<u8>| -> Vec<u8> {
        if w.big {
            le.into_iter().rev().collect()
        } else {
            le
        }
    };
    v.iter()
        .flat_map(|&x| match ty {
            1 => b((x as i8).to_le_bytes().to_vec()),
            2 | 16 => b((x as u8).to_le_bytes().to_vec()),
            3 => b((x as i16).to_le_bytes().to_vec()),
            4 => b((x as u16).to_le_bytes().to_vec()),
            5 => b((x as i32).to_le_bytes().to_vec()),
            6 => b((x as u32).to_le_bytes().to_vec()),
            7 => b((x as f32).to_le_bytes().to_vec()),
            9 => b(x.to_le_bytes().to_vec()),
            12 => b((x as i64).to_le_bytes().to_vec()),
            _ => b((x as u64).to_le_bytes().to_vec()),
        })
        .collect()
}

/// MATLAB stores a double array in the smallest type that holds its
/// values (miINT8 … miUINT64, miSINGLE): each reads back as the same
/// numbers, with its sign, in both byte orders.
#[test]
fn every_numeric_data_type_reads_back_in_both_byte_orders() {
    let cases: [(u32, &str, [f64; 3]); 11] = [
        (1, "int8", [-3.0, 100.0, -128.0]),
        (2, "uint8", [200.0, 1.0, 255.0]),
        (3, "int16", [-300.0, 7.0, -32768.0]),
        (4, "uint16", [60000.0, 2.0, 65535.0]),
        (5, "int32", [-70000.0, 3.0, -2147483648.0]),
        (6, "uint32", [3e9, 4.0, 4294967295.0]),
        (7, "single", [1.5, -2.25, 3.0e38]),
        (9, "double", [0.1, -2.0, 1e300]),
        (12, "int64", [-5e12, 6.0, -9.0e18]),
        (13, "uint64", [1e19, 8.0, 1.8e19]),
        (16, "utf8", [65.0, 66.0, 200.0]),
    ];
    for big in [false, true] {
        let w = Mat { big };
        let mut bytes = w.header();
        for (ty, name, v) in &cases {
            // dims 3×1: a column vector
            bytes.extend(w.matrix(6, 0, &[3, 1], name, &w.el(*ty, &typed(&w, *ty, v))));
        }
        let got = read_bytes(&bytes, &ReadOptions::default())
            .unwrap_or_else(|e| panic!("big {big}: {e}"));
        let names: Vec<&str> = cases.iter().map(|c| c.1).collect();
        assert_eq!(got.table.names, names, "big {big}");
        for (k, (_, name, v)) in cases.iter().enumerate() {
            let want: Vec<f64> = if *name == "single" {
                v.iter().map(|&x| x as f32 as f64).collect()
            } else {
                v.to_vec()
            };
            assert_eq!(got.table.columns[k], want, "{name}, big {big}");
        }
    }
}

/// A Simulink signal of two columns reads as two named columns, one
/// without a label is named by its place; a dSPACE signal without a Name
/// is `Y(i)`, and a name written as a 2-row char array reads row by row.
#[test]
fn signals_without_labels_and_of_two_columns_are_named() {
    let w = Mat { big: false };
    let t = [0.0, 0.5, 1.0];
    let two: Vec<u8> = [1.0f64, 2.0, 3.0, 10.0, 20.0, 30.0]
        .iter()
        .flat_map(|x| x.to_le_bytes())
        .collect();
    // Simulink's values are samples × columns (column-major)
    let col: Vec<u8> = [4.0f64, 5.0, 6.0]
        .iter()
        .flat_map(|x| x.to_le_bytes())
        .collect();
    let sig = vec![
        vec![
            w.matrix(6, 0, &[3, 2], "", &w.el(9, &two)),
            w.chars("", "pos"),
        ],
        vec![w.matrix(6, 0, &[3, 1], "", &w.el(9, &col)), w.chars("", "")],
    ];
    let top = w.structure(
        "ScopeData",
        &["time", "signals"],
        &[vec![
            w.doubles("", &t),
            w.structure("", &["values", "label"], &sig),
        ]],
    );
    let got = read_bytes(&[w.header(), top].concat(), &ReadOptions::default()).unwrap();
    assert_eq!(
        got.table.names,
        ["time [s]", "pos(1)", "pos(2)", "signals(2)"]
    );
    assert_eq!(got.table.columns[1], [1.0, 2.0, 3.0]);
    assert_eq!(got.table.columns[2], [10.0, 20.0, 30.0]);
    assert_eq!(got.table.columns[3], [4.0, 5.0, 6.0]);
    // dSPACE: Y(2) has no Name; Y(1)'s name is a 2×3 char array ("abc", "de")
    let rows2: Vec<u8> = "adbec "
        .encode_utf16()
        .flat_map(|c| c.to_le_bytes())
        .collect();
    let name2 = w.matrix(4, 0, &[2, 3], "", &w.el(4, &rows2));
    // Y(3)'s name is a cell holding its text, as some exports write it
    let in_cell = w.matrix(1, 0, &[1, 1], "", &w.chars("", "Z"));
    // Units: none (an empty array: a tag alone, the last one ending the
    // struct's data exactly), and one the core does not know
    let none = w.el(14, &[]);
    let ys = vec![
        vec![name2, w.doubles("", &[1.0, 2.0, 3.0]), none.clone()],
        vec![
            w.matrix(6, 0, &[0, 0], "", &w.el(9, &[])),
            w.doubles("", &[4.0, 5.0, 6.0]),
            w.chars("", "V"),
        ],
        vec![in_cell, w.doubles("", &[7.0, 8.0, 9.0]), none],
    ];
    let x = w.structure("", &["Data"], &[vec![w.doubles("", &t)]]);
    let top = w.structure(
        "cap",
        &["X", "Y"],
        &[vec![x, w.structure("", &["Name", "Data", "Unit"], &ys)]],
    );
    let file = [w.header(), top].concat();
    let got = read_bytes(&file, &ReadOptions::default()).unwrap();
    assert_eq!(got.table.names, ["time [s]", "abc\nde", "Y(2)", "Z"]);
    assert_eq!(got.table.columns[2], [4.0, 5.0, 6.0]);
    assert_eq!(got.table.columns[3], [7.0, 8.0, 9.0]);
    // a struct array's length; anything else has none
    let vars = mat::variables(&file).unwrap();
    let (name, v) = &vars[0];
    assert_eq!((name.as_str(), v.len(), v.is_empty()), ("cap", 1, false));
    let y = v.field(0, "Y").unwrap();
    assert_eq!((y.len(), y.is_empty()), (3, false));
    let data = y.field(2, "Data").unwrap();
    assert_eq!((data.len(), data.is_empty()), (0, true));
    assert!(
        v.field(1, "Y").is_none() && v.field(0, "Q").is_none() && data.field(0, "Data").is_none()
    );
}

/// Small data elements (at most 4 bytes packed into the tag): a 2-byte
/// name reads; one that claims 5 bytes, or 3 bytes of miINT32 dimensions,
/// is refused at its own byte.
#[test]
fn small_data_elements_read_and_are_refused_at_their_byte() {
    let w = Mat { big: false };
    let flags = w.el(6, &[w.u32(6), w.u32(0)].concat()); // bytes 136–151
    let dims = w.el(5, &[w.u32(1), w.u32(2)].concat()); // bytes 152–167
    let data: Vec<u8> = [1.5f64, -2.0]
        .iter()
        .flat_map(|x| x.to_le_bytes())
        .collect();
    let file = |inner: Vec<u8>| [w.header(), w.el(14, &inner)].concat();
    let good = file(
        [
            flags.clone(),
            dims.clone(),
            w.small(1, b"ab"),
            w.el(9, &data),
        ]
        .concat(),
    );
    let r = read_bytes(&good, &ReadOptions::default()).unwrap();
    assert_eq!(
        (r.table.names[0].as_str(), r.table.columns[0].as_slice()),
        ("ab", [1.5, -2.0].as_slice())
    );
    let five = [w.u32((5 << 16) | 1).to_vec(), b"abcd".to_vec()].concat();
    let bad_name = file([flags.clone(), dims, five, w.el(9, &data)].concat());
    let short_dims = file(
        [
            flags,
            w.small(5, &[1, 0, 0]),
            w.small(1, b"ab"),
            w.el(9, &data),
        ]
        .concat(),
    );
    for (bytes, want) in [
        (
            bad_name,
            "byte 168: MATLAB .mat: a small data element of 5 bytes (at most 4)",
        ),
        (
            short_dims,
            "byte 156: MATLAB .mat: 3 bytes of miINT32 (a multiple of 4 expected)",
        ),
    ] {
        let e = read_bytes(&bytes, &ReadOptions::default()).unwrap_err();
        assert_eq!(e.to_string(), want);
    }
}

/// Broken arrays inside a well-formed file: each refusal names the byte
/// where the fault is and what was expected there.
#[test]
fn broken_arrays_are_refused_at_their_byte() {
    let w = Mat { big: false };
    let file = |body: Vec<u8>| [w.header(), body].concat();
    let two: Vec<u8> = [1.0f64, 2.0].iter().flat_map(|x| x.to_le_bytes()).collect();
    let flags = |class: u32| w.el(6, &[w.u32(class), w.u32(0)].concat()); // 136–151
    let dims = |d: &[u32]| w.el(5, &d.iter().flat_map(|&x| w.u32(x)).collect::<Vec<u8>>());
    let raw = |parts: &[Vec<u8>]| file(w.el(14, &parts.concat()));
    // a vector inside 16 nested cells is read (and is no capture); 17 are too deep
    let nested = |k: usize| {
        let mut v = w.doubles("", &[1.0]);
        for _ in 0..k {
            v = w.matrix(1, 0, &[1, 1], "", &v);
        }
        file(v)
    };
    let deep = nested(17);
    let e = read_bytes(&nested(16), &ReadOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("byte 128: MATLAB .mat: no capture found"),
        "{e}"
    );
    let cases: Vec<(&str, Vec<u8>, String)> = vec![
        (
            "flags of another type",
            raw(&[w.el(5, &[w.u32(6), w.u32(0)].concat()), dims(&[1, 2]), w.el(1, b"x"), w.el(9, &two)]),
            "byte 144: MATLAB .mat: an array's flags (miUINT32, 8 bytes) were expected".into(),
        ),
        (
            "dimensions too large",
            raw(&[flags(6), dims(&[100_000, 100_000]), w.el(1, b"x"), w.el(9, &two)]),
            "byte 160: MATLAB .mat: dimensions [100000, 100000] are too large".into(),
        ),
        (
            "one value more than 64 MiB of doubles",
            raw(&[flags(6), dims(&[4097, 2048]), w.el(1, b"x"), w.el(9, &two)]),
            "byte 160: MATLAB .mat: dimensions [4097, 2048] are too large".into(),
        ),
        (
            // 2048 × 4096 doubles are 64 MiB: the largest array reserved
            "the largest array",
            raw(&[flags(6), dims(&[2048, 4096]), w.el(1, b"x"), w.el(9, &two)]),
            "byte 192: MATLAB .mat: 'x' has 2 values for dimensions [2048, 4096]".into(),
        ),
        ("the header alone", w.header(), "no capture found: no struct with X and Y (dSPACE) or time and signals (Simulink), and no real vector (variables: )".into()),
        (
            "fewer values than the dimensions",
            raw(&[flags(6), dims(&[1, 3]), w.el(1, b"x"), w.el(9, &two)]),
            "byte 192: MATLAB .mat: 'x' has 2 values for dimensions [1, 3]".into(),
        ),
        (
            "an object",
            raw(&[flags(3), dims(&[1, 1]), w.el(1, b"o")]),
            "byte 136: MATLAB .mat: 'o' is mxOBJECT (a MATLAB object), which is not read; a trace is real numbers, text, structs and cells".into(),
        ),
        (
            "a field name length of 0",
            raw(&[flags(2), dims(&[1, 1]), w.el(1, b"s"), w.small(5, &w.u32(0)), w.el(1, b"abcd")]),
            "byte 200: MATLAB .mat: 's': field names of 4 bytes with a name length of 0".into(),
        ),
        (
            "a number where a struct field's array belongs",
            file(w.structure("s", &["a"], &[vec![w.el(9, &two)]])),
            "byte 240: MATLAB .mat: data type 9 inside a struct or cell (miMATRIX expected)".into(),
        ),
        ("nested too deep", deep, "structs or cells nested deeper than 16 levels".into()),
        (
            "short flags",
            raw(&[w.el(6, &w.u32(6)), dims(&[1, 2]), w.el(1, b"x"), w.el(9, &two)]),
            "byte 144: MATLAB .mat: an array's flags (miUINT32, 8 bytes) were expected".into(),
        ),
        (
            "a function handle",
            raw(&[flags(16), dims(&[1, 1]), w.el(1, b"f")]),
            "byte 136: MATLAB .mat: 'f' is mxFUNCTION (a function handle), which is not read; a trace is real numbers, text, structs and cells".into(),
        ),
        (
            "an opaque object",
            raw(&[flags(17), dims(&[1, 1]), w.el(1, b"o")]),
            "byte 136: MATLAB .mat: 'o' is mxOPAQUE (a MATLAB object), which is not read; a trace is real numbers, text, structs and cells".into(),
        ),
        (
            "an unknown class",
            raw(&[flags(40), dims(&[1, 1]), w.el(1, b"u")]),
            "byte 136: MATLAB .mat: 'u' is array class 40, which is not read; a trace is real numbers, text, structs and cells".into(),
        ),
        (
            "a number at the top level",
            file(w.el(9, &two)),
            "byte 136: MATLAB .mat: data type 9 at the top level (miMATRIX expected)".into(),
        ),
    ];
    for (what, bytes, want) in cases {
        let e = read_bytes(&bytes, &ReadOptions::default())
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("byte ") && e.ends_with(&want), "{what}: {e}");
    }
    // dSPACE and Simulink structs without their data say which is missing
    let st = |name: &str, field: &str, value: Vec<u8>| w.structure(name, &[field], &[vec![value]]);
    let two_fields = |name: &str, f: [&str; 2], a: Vec<u8>, b: Vec<u8>| {
        file(w.structure(name, &f, &[vec![a, b]]))
    };
    for (bytes, want) in [
        (
            two_fields(
                "cap",
                ["X", "Y"],
                st("", "Name", w.chars("", "Time")),
                st("", "Data", w.doubles("", &[1.0])),
            ),
            "'cap.X' has no Data vector (the time)",
        ),
        (
            two_fields(
                "cap",
                ["X", "Y"],
                st("", "Data", w.doubles("", &[0.0])),
                st("", "Name", w.chars("", "pos")),
            ),
            "'cap.Y(1)' ('pos') has no Data vector",
        ),
        (
            two_fields(
                "sd",
                ["time", "signals"],
                w.doubles("", &[0.0]),
                st("", "label", w.chars("", "pos")),
            ),
            "'sd.signals(1)' has no values",
        ),
        (
            two_fields(
                "sd",
                ["time", "signals"],
                w.chars("", "t"),
                st("", "values", w.doubles("", &[1.0])),
            ),
            "'sd.time' is not a vector",
        ),
    ] {
        let e = read_bytes(&bytes, &ReadOptions::default())
            .unwrap_err()
            .to_string();
        assert_eq!(e, format!("byte 0: MATLAB .mat: {want}"));
    }
    // text stored as miUTF8 reads as its characters
    let utf8 = file(w.structure(
        "cap",
        &["X", "Y"],
        &[vec![
            w.structure("", &["Data"], &[vec![w.doubles("", &[0.0, 1.0])]]),
            w.structure(
                "",
                &["Name", "Data"],
                &[vec![
                    w.matrix(4, 0, &[1, 3], "", &w.el(16, "Xµm".as_bytes())),
                    w.doubles("", &[5.0, 6.0]),
                ]],
            ),
        ]],
    ));
    let r = read_bytes(&utf8, &ReadOptions::default()).unwrap();
    assert_eq!(r.table.names[1], "Xµm");
}

/// Compressed elements follow each other unpadded; plain ones are padded
/// to 8 bytes. A matrix or an empty vector among the vectors is named and
/// left out. A big-endian v7.3 file is refused as the little-endian one is.
#[test]
fn compressed_elements_in_a_row_and_what_is_left_out() {
    let w = Mat { big: false };
    let t = w.compressed(&w.doubles("t", &[0.0, 1.0, 2.0]));
    let x = w.compressed(&w.doubles("x", &[5.0, 6.0, 7.0]));
    assert!(
        t.len() % 8 != 0,
        "the case needs an unpadded length: {}",
        t.len()
    );
    let m = w.matrix(6, 0, &[2, 2], "m", &w.el(9, &[0u8; 32]));
    let e = w.doubles("e", &[]);
    let file = [w.header(), t, m, x, e].concat();
    let r = read_bytes(&file, &ReadOptions::default()).unwrap();
    assert_eq!(r.table.names, ["t", "x"]);
    assert_eq!(r.table.columns[1], [5.0, 6.0, 7.0]);
    let notes = r.layout.notes.join(" | ");
    for v in ["m", "e"] {
        assert!(
            notes.contains(&format!("variable '{v}' is not a real vector: ignored")),
            "{notes}"
        );
    }
    let big = Mat { big: true };
    let mut v73 = big.header();
    v73[124..126].copy_from_slice(&0x0200u16.to_be_bytes());
    let e = read_bytes(&v73, &ReadOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("byte 124: MATLAB .mat: a v7.3 (HDF5) MAT-file"),
        "{e}"
    );
    let e = mat::variables(b"hello").unwrap_err().to_string();
    assert_eq!(
        e,
        "byte 0: MATLAB .mat: not a MATLAB 5.0 MAT-file (its header text is missing)"
    );
}
