//! Controls' and instruments' own trace layouts (issue 26, item 2): a
//! simulated constant-feed-speed-vector trace of known content, written
//! by this test in each layout (SINUMERIK Operate trace XML, TwinCAT
//! Scope View export in its tab and comma dialects, halsampler with and
//! without `-t`, halscope's log, a CSV with header rows before the data
//! as SERVO GUIDE exports, `;` with decimal commas), is recognised as that
//! layout and reads back to the same numbers within 1e-9 relative; the
//! feed-vector analysis of each gives the simulation's own summary. Every
//! refusal names its cause and its line.
#![cfg(not(target_arch = "wasm32"))]

use mtmotion::feed_vector::trace_analysis::{analyze_trace, ColumnMap};
use mtmotion::feed_vector::FeedVectorResult;
use mtmotion::trace::{read_table, ColumnKind, ReadOptions, TableRead};
use std::f64::consts::PI;

#[path = "support/feed_vector_trace.rs"]
mod feed_vector_trace;
use feed_vector_trace::{close, rows, sim};

const NAMES: [&str; 5] = ["time", "X", "Y", "C", "Torque"];

/// The file in `layout`, and per written quantity (time, X, Y, C,
/// torque) the factor from the simulation's value to the file's.
fn written(r: &FeedVectorResult, layout: &str) -> String {
    let rows = rows(r);
    let comma = |v: f64| v.to_string().replace('.', ",");
    let mut s = String::new();
    match layout {
        "sinumerik" => {
            s += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<traceCaptureFile version=\"1.0\">\n<traceHeader><!-- trigger, sample rate --></traceHeader>\n<traceData>\n<dataFrame name=\"Frame1\">\n";
            for (k, n) in [
                "/Nck/MachineAxis/aaIm[X1]",
                "/Nck/MachineAxis/aaIm[Y1]",
                "/Nck/MachineAxis/aaIm[C1]",
                "/Nck/MachineAxis/aaLoad[C1]",
            ]
            .iter()
            .enumerate()
            {
                s += &format!(
                    "<dataSignal id=\"{}\" name=\"{n}\" description=\"{}\"/>\n",
                    k + 1,
                    NAMES[k + 1]
                );
            }
            // the first record has no value yet, as the control writes it
            s += "<rec time=\"-0.001\" f1=\"9.2233720368547758E+18\" f2=\"9.2233720368547758E+18\" f3=\"9.2233720368547758E+18\" f4=\"9.2233720368547758E+18\"/>\n";
            for [t, x, y, c, tq] in &rows {
                s += &format!("<rec time=\"{t}\" f1=\"{x}\" f2=\"{y}\" f3=\"{c}\" f4=\"{tq}\"/>\n");
            }
            s += "</dataFrame>\n</traceData>\n</traceCaptureFile>\n";
        }
        "twincat-tab" | "twincat-comma" => {
            let d = if layout == "twincat-tab" { '\t' } else { ',' };
            let num = |v: f64| if d == '\t' { comma(v) } else { v.to_string() };
            s += &format!("Name{d}feedvector\nFile{d}C:\\TwinCAT\\Scope\\feedvector.svdx\nStarttime of export{d}133000000000000000{d}Freitag, 27. November 2026{d}10:00:00.000\nEndtime of export{d}133000000030000000{d}Freitag, 27. November 2026{d}10:00:03.000\n\n\n");
            let units = [
                "mm (Millimeter)",
                "mm (Millimeter)",
                "deg (Degree)",
                "(None)",
            ];
            let rows_of = |key: &str, f: &dyn Fn(usize) -> String| -> String {
                let cells: Vec<String> = (0..4).map(|k| format!("{key}{d}{}", f(k))).collect();
                cells.join(&d.to_string()) + "\n"
            };
            s += &rows_of("Name", &|k| format!("MAIN.{}", NAMES[k + 1]));
            s += &rows_of("SymbolComment", &|_| String::new());
            s += &rows_of("Data-Type", &|_| "REAL64".into());
            s += &rows_of("SampleTime[ms]", &|_| "1".into());
            s += &rows_of("VariableSize", &|_| "8".into());
            s += &rows_of("SymbolName", &|k| format!("MAIN.{}", NAMES[k + 1]));
            s += &rows_of("NetID", &|_| "5.1.2.3.1.1".into());
            s += &rows_of("Port", &|_| "851".into());
            s += &rows_of("Offset", &|_| "0".into());
            s += &rows_of("ScaleFactor", &|_| "1".into());
            s += &rows_of("BitMask", &|_| "0xffffffffffffffff".into());
            s += &rows_of("Unit", &|k| units[k].into());
            s += &rows_of("Unit ScaleFactor", &|_| "1".into());
            s += &rows_of("Unit Offset", &|_| "0".into());
            s += "\n";
            for [t, x, y, c, tq] in &rows {
                let t = num(t * 1e3);
                let cells = [x, y, c, tq].map(|v| format!("{t}{d}{}", num(*v)));
                s += &(cells.join(&d.to_string()) + "\n");
            }
        }
        "halsampler" => {
            for [_, x, y, c, tq] in &rows {
                s += &format!("{x} {y} {c} {tq} \n");
            }
        }
        "halsampler-t" => {
            for (i, [_, x, y, c, tq]) in rows.iter().enumerate() {
                s += &format!("{i} {x} {y} {c} {tq} \n");
            }
        }
        "halscope" => {
            s += "Sampling period is 1000000 ns \n";
            for [_, x, y, c, tq] in &rows {
                s += &format!("\nx {x:+.14} y {y:+.14} c {c:+.14} torque {tq:+.14} ");
            }
            s += "\n";
        }
        "servo-guide" => {
            s += "SERVO GUIDE\nMachine,NMV5000\nDate,2026/11/27 10:00\nSampling(ms),1\nChannels,5\nTime [ms],POS X(um),POS Y(um),POS C(deg),TCMD C(Nm)\n";
            for [t, x, y, c, tq] in &rows {
                s += &format!("{},{},{},{c},{tq}\n", t * 1e3, x * 1e3, y * 1e3);
            }
        }
        "semicolon" => {
            s += "Zeit [s];X [mm];Y [mm];C [deg];Torque [Nm]\n";
            for [t, x, y, c, tq] in &rows {
                s += &format!(
                    "{};{};{};{};{}\n",
                    comma(*t),
                    comma(*x),
                    comma(*y),
                    comma(*c),
                    comma(*tq)
                );
            }
        }
        _ => unreachable!("{layout}"),
    }
    s
}

/// Per layout: its format name, the table column of each quantity (time,
/// X, Y, C, torque), and the factor from the simulation's unit to the file's.
fn expected(layout: &str) -> (&'static str, [usize; 5], [f64; 5]) {
    let one = [1.0; 5];
    match layout {
        "sinumerik" => ("sinumerikTrace", [0, 1, 2, 3, 4], one),
        "twincat-tab" | "twincat-comma" => {
            ("twincatScope", [0, 1, 2, 3, 4], [1e3, 1.0, 1.0, 1.0, 1.0])
        }
        "halsampler" => ("halsampler", [4, 0, 1, 2, 3], one),
        "halsampler-t" => ("halsampler", [5, 1, 2, 3, 4], one),
        "halscope" => ("halscope", [4, 0, 1, 2, 3], one),
        "servo-guide" => ("delimited", [0, 1, 2, 3, 4], [1e3, 1e3, 1e3, 1.0, 1.0]),
        "semicolon" => ("delimited", [0, 1, 2, 3, 4], one),
        _ => unreachable!(),
    }
}

const LAYOUTS: [&str; 8] = [
    "sinumerik",
    "twincat-tab",
    "twincat-comma",
    "halsampler",
    "halsampler-t",
    "halscope",
    "servo-guide",
    "semicolon",
];

fn read(layout: &str, text: &str) -> TableRead {
    let opts = ReadOptions {
        sample_period: layout.starts_with("halsampler").then_some(1e-3),
        ..ReadOptions::default()
    };
    read_table(text, &opts).unwrap_or_else(|e| panic!("{layout}: {e}"))
}

#[test]
fn every_layout_is_recognised_and_reads_back_to_the_same_numbers() {
    let (_, r) = sim();
    let want = rows(&r);
    for layout in LAYOUTS {
        let text = written(&r, layout);
        let got = read(layout, &text);
        let (format, cols, factor) = expected(layout);
        assert_eq!(got.layout.format, format, "{layout}");
        let t = &got.table;
        assert_eq!(t.rows(), want.len(), "{layout}");
        for q in 0..5 {
            let col = &t.columns[cols[q]];
            for (i, row) in want.iter().enumerate() {
                assert!(
                    close(col[i], row[q] * factor[q]),
                    "{layout}: {} row {i}: {} vs {}",
                    NAMES[q],
                    col[i],
                    row[q] * factor[q]
                );
            }
        }
        // the time column states its unit, so the core scales it
        let time = got.info(cols[0]).unwrap();
        assert_eq!(time.factor, Some(1.0 / factor[0]), "{layout}: {time:?}");
    }
}

#[test]
fn layouts_report_what_was_read() {
    let (_, r) = sim();
    let sin = read("sinumerik", &written(&r, "sinumerik"));
    assert_eq!(sin.table.names[1], "/Nck/MachineAxis/aaIm[X1]");
    assert_eq!(
        sin.layout.columns[1].note.as_deref(),
        Some("description: X")
    );
    assert_eq!(
        sin.table.lines[0], 11,
        "the first record (no value) is dropped"
    );
    let notes = sin.layout.notes.join(" | ");
    assert!(
        notes.contains("1 of 3002 records have no value for a signal (first on line 10): dropped"),
        "{notes}"
    );
    for (layout, delim, comma) in [("twincat-tab", "tab", true), ("twincat-comma", ",", false)] {
        let tc = read(layout, &written(&r, layout));
        assert_eq!(
            tc.table.names,
            [
                "time [ms]",
                "MAIN.X [mm]",
                "MAIN.Y [mm]",
                "MAIN.C [deg]",
                "MAIN.Torque"
            ],
            "{layout}"
        );
        assert_eq!(
            (tc.layout.delimiter, tc.layout.decimal_comma),
            (delim, comma)
        );
        assert_eq!(tc.layout.header_line, Some(7));
        assert_eq!(tc.layout.first_data_line, 22);
        assert_eq!(tc.layout.metadata[0].value, "feedvector");
        assert_eq!(tc.layout.columns[3].factor, Some(PI / 180.0));
        let note = tc.layout.columns[4].note.as_deref().unwrap();
        assert!(note.starts_with("sample time 1 ms, ScaleFactor 1, Offset 0, Unit ScaleFactor 1, Unit Offset 0 (applied by the export)"), "{note}");
    }
    let hs = read("halsampler-t", &written(&r, "halsampler-t"));
    assert_eq!(hs.table.names[0], "sample");
    assert_eq!(hs.layout.columns[5].kind, ColumnKind::Generated);
    let hs = read("halsampler", &written(&r, "halsampler"));
    assert_eq!(hs.table.names[0], "column 1", "no -t: column 1 is data");
    let sc = read("halscope", &written(&r, "halscope"));
    assert_eq!(sc.table.names, ["x", "y", "c", "torque", "time [s]"]);
    assert_eq!(sc.layout.first_data_line, 3);
}

#[test]
fn halsampler_t_keeps_the_time_of_dropped_samples() {
    // samples 0, 1, 2, 5 (3 and 4 lost): the time says so
    let text = "0 1.5 2\n1 1.6 2\n2 1.7 2\n5 2.0 2\n";
    let got = read_table(
        text,
        &ReadOptions {
            sample_period: Some(0.5),
            ..ReadOptions::default()
        },
    )
    .unwrap();
    assert_eq!(got.table.columns[3], [0.0, 0.5, 1.0, 2.5]);
    // a first column that does not grow by whole samples is data
    let got = read_table(
        "0 1.5 2\n1 1.6 2\n1 1.7 2\n",
        &ReadOptions {
            sample_period: Some(0.5),
            ..ReadOptions::default()
        },
    )
    .unwrap();
    assert_eq!(got.table.names[0], "column 1");
    assert_eq!(got.table.columns[3], [0.0, 0.5, 1.0]);
}

#[test]
fn each_layout_gives_the_simulations_own_summary() {
    let (cond, r) = sim();
    for layout in LAYOUTS {
        let text = written(&r, layout);
        let (_, cols, _) = expected(layout);
        let got = read(layout, &text);
        let n = |q: usize| Some(got.table.names[cols[q]].clone());
        let map = ColumnMap {
            time: n(0),
            x: n(1),
            y: n(2),
            c: n(3),
            torque: n(4),
            sample_period: layout.starts_with("halsampler").then_some(1e-3),
            steady_from: Some(r.summary.steady_from),
            ..ColumnMap::default()
        };
        let tr = analyze_trace(&text, &cond, &map).unwrap_or_else(|e| panic!("{layout}: {e}"));
        let d = (tr.summary.mean_angle_diff - r.summary.mean_angle_diff).abs();
        assert!(d < 1e-9, "{layout}: {d} rad");
        assert_eq!(tr.summary.periods, r.summary.periods, "{layout}");
    }
}

/// Each malformed file in a layout, the line its error must name, and a
/// word of the cause.
#[test]
fn every_refusal_names_its_cause_and_line() {
    let tc = "Name\tS\n\nName\tX\tName\tY\nSampleTime[ms]\t1\tSampleTime[ms]\t1\n\n0\t1\t0\t2\n1\t1\t1\t3\n2\tx\t2\t4\n3\t1\t3\t5\n";
    let cases: Vec<(String, Option<f64>, usize, &str)> = vec![
        (tc.to_string(), None, 8, "'x' is not a number"),
        (tc.replace("\n1\t1\t1\t3", "\n1\t1\t1\t"), None, 7, "channel 'Y' (field 4) has no sample"),
        (tc.replace("Name\tX\tName\tY", "Name\t\tName\tY"), None, 3, "field 2 of the Name row is empty"),
        (tc.replace("\n0\t1\t0\t2\n1\t1\t1\t3\n2\tx\t2\t4\n3\t1\t3\t5\n", "\n"), None, 3, "no sample row below the channel block (lines 3–4)"),
        (tc.replace("\n1\t1\t1\t3", "\n\t1\t1\t3"), None, 7, "the time column (field 1) ends here but rows follow"),
        ("Sampling period is -5 ns\n\nx +1 \n".into(), None, 1, "is not 'Sampling period is <n> ns'"),
        ("Sampling period is 1000 ns\n\nx +1 y +2\nx +1 z +2\nx +1 y +2\n".into(), None, 4, "not those of line 3 (x, y)"),
        ("Sampling period is 1000 ns\n\nx +1 y\nx +1 y +2\n".into(), None, 3, "'<channel> <value>' pairs"),
        ("Sampling period is 1000 ns\n\nx +1\nx nan\nx 3\n".into(), None, 4, "'nan' is not a number"),
        ("Sampling period is 1000 ns\n\nx +1\nx 2\n".into(), Some(1.0), 1, "states its sample period"),
        ("1.5 2\n1.6 2\n1.7 2\n".into(), None, 1, "numbers only (no header line, as halsampler writes it), so it has no time axis: give samplePeriod"),
        ("<a>\n<traceData>\n</a>\n<!-- end -->\n".into(), None, 3, "XML: </a> closes <traceData>"),
        ("<a>\n<traceData><dataFrame>\n<dataSignal name='X'/>\n<rec time='0' f1='1' f2='3'/>\n</dataFrame></traceData></a>\n".into(), None, 4, "has f2, but the frame names 1 signals"),
    ];
    for (text, dt, line, cause) in cases {
        let opts = ReadOptions {
            sample_period: dt,
            ..ReadOptions::default()
        };
        let e = read_table(&text, &opts).unwrap_err().to_string();
        assert!(
            e.starts_with(&format!("line {line}: ")) || e.starts_with(&format!("line {line}, ")),
            "{text:?}: {e}"
        );
        assert!(e.contains(cause), "{text:?}: {e}");
        // the fault is never on the file's last line, so a message that
        // points at the last line whatever the fault cannot pass
        let last = text.trim_end().lines().count();
        assert!(
            line < last,
            "{text:?}: the case must have lines after its fault"
        );
    }
}
