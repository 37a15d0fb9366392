//! Ball-bar traces are read by the core's tolerant reader (issue 26,
//! item 2): a synthetic ball-bar run of known deviations, written by this
//! test as X/Y positions in a `;` file with decimal commas, a text column
//! and a preamble, in a file with `EncoderX_Pos, EncoderY_Pos` columns
//! read through the column mapping, in a TwinCAT Scope export and in a
//! SINUMERIK trace, reads back to the same deviations (within 1e-12 mm on
//! a 100 mm bar) at the same lines; the same run recorded as a MATLAB
//! `.mat` capture (dSPACE ControlDesk's struct, and plain vectors) reads
//! back to the same deviations at the same samples, and a damaged capture
//! is refused naming its byte; a mapping that names a missing column is
//! refused, naming the mapping's field and the file's columns.
#![cfg(not(target_arch = "wasm32"))]

use mtmotion::ballbar::synthetic::{synthetic_trace, SyntheticConfig};
use mtmotion::ballbar::Harmonic;
use mtmotion::ballbar::{
    parse_ballbar_trace, parse_ballbar_trace_bytes, BallbarColumns, ParseOptions, PlanePoint,
};
#[path = "support/mat_writer.rs"]
mod mat_writer;
use mat_writer::Mat;

/// X/Y positions (mm) of a synthetic CCW + CW run about (0, 0), and their
/// deviations from the 100 mm bar (mm).
fn run() -> (Vec<[f64; 2]>, Vec<f64>) {
    let t = synthetic_trace(&SyntheticConfig {
        samples: 180,
        harmonics: vec![Harmonic {
            order: 2,
            amplitude: 0.004,
            phase: 0.3,
        }],
        backlash_x: 0.002,
        ..SyntheticConfig::default()
    })
    .unwrap();
    let mut xy = Vec::new();
    let mut dev = Vec::new();
    for r in &t.runs {
        for (a, d) in r.angle.iter().zip(&r.deviation) {
            let rho = t.nominal_radius + d;
            xy.push([rho * a.cos(), rho * a.sin()]);
            dev.push(rho.hypot(0.0) - t.nominal_radius);
        }
    }
    (xy, dev)
}

/// The file in `layout` and the line of its first sample.
fn written(layout: &str, xy: &[[f64; 2]]) -> (String, usize) {
    let comma = |v: f64| v.to_string().replace('.', ",");
    let mut s = String::new();
    let first = match layout {
        "semicolon" => {
            s += "Kreisformtest;QC20-W\nRadius;100 mm\nX [mm];Y [mm];Zustand\n";
            for [x, y] in xy {
                s += &format!("{};{};Messung\n", comma(*x), comma(*y));
            }
            4
        }
        "encoder" => {
            s += "Sample,EncoderX_Pos,EncoderY_Pos,EncoderZ_Pos\n";
            for (i, [x, y]) in xy.iter().enumerate() {
                s += &format!("{i},{x},{y},0\n");
            }
            2
        }
        "twincat" => {
            s += "Name\tballbar\nFile\tC:\\scope\\ballbar.svdx\n\nName\tMAIN.EncoderX\tName\tMAIN.EncoderY\nSampleTime[ms]\t2\tSampleTime[ms]\t2\nUnit\tmm (Millimeter)\tUnit\tmm (Millimeter)\n\n";
            for (i, [x, y]) in xy.iter().enumerate() {
                let t = comma(i as f64 * 2.0);
                s += &format!("{t}\t{}\t{t}\t{}\n", comma(*x), comma(*y));
            }
            8
        }
        "sinumerik" => {
            s += "<?xml version=\"1.0\"?>\n<traceCaptureFile>\n<traceData>\n<dataFrame>\n<dataSignal name=\"/Nck/MachineAxis/aaIm[X1]\"/>\n<dataSignal name=\"/Nck/MachineAxis/aaIm[Y1]\"/>\n";
            for (i, [x, y]) in xy.iter().enumerate() {
                s += &format!(
                    "<rec time=\"{}\" f1=\"{x}\" f2=\"{y}\"/>\n",
                    i as f64 * 0.002
                );
            }
            s += "</dataFrame>\n</traceData>\n</traceCaptureFile>\n";
            7
        }
        _ => unreachable!(),
    };
    (s, first)
}

fn columns(layout: &str) -> BallbarColumns {
    let (x, y, time) = match layout {
        "encoder" => ("EncoderX_Pos", "EncoderY_Pos", None),
        "twincat" => ("MAIN.EncoderX [mm]", "MAIN.EncoderY [mm]", None),
        "sinumerik" => (
            "/Nck/MachineAxis/aaIm[X1]",
            "/Nck/MachineAxis/aaIm[Y1]",
            Some("time [s]"),
        ),
        _ => return BallbarColumns::default(),
    };
    BallbarColumns {
        x: Some(x.into()),
        y: Some(y.into()),
        time: time.map(Into::into),
        ..BallbarColumns::default()
    }
}

#[test]
fn every_layout_reads_back_to_the_same_deviations() {
    let (xy, dev) = run();
    let opts = ParseOptions {
        nominal_radius: Some(100.0),
        centre: Some(PlanePoint { x: 0.0, y: 0.0 }),
        trim: false,
        ..ParseOptions::default()
    };
    for layout in ["semicolon", "encoder", "twincat", "sinumerik"] {
        let (text, first) = written(layout, &xy);
        let opts = ParseOptions {
            columns: columns(layout),
            ..opts.clone()
        };
        let t = parse_ballbar_trace(&text, opts).unwrap_or_else(|e| panic!("{layout}: {e}"));
        assert_eq!(t.runs.len(), 2, "{layout}");
        let mut seen = 0;
        for r in &t.runs {
            for (d, line) in r.deviation.iter().zip(&r.lines) {
                let want = dev[line - first];
                assert!(
                    (d - want).abs() < 1e-12,
                    "{layout}: line {line}: {d} vs {want}"
                );
                seen += 1;
            }
        }
        assert!(seen >= xy.len(), "{layout}: {seen} samples");
        // the deviations are the synthetic errors, not zero
        let span = dev.iter().fold(0.0f64, |m, d| m.max(d.abs()));
        assert!(span > 0.003, "{span}");
    }
}

#[test]
fn without_the_mapping_the_encoder_file_is_refused_naming_its_columns() {
    let (xy, _) = run();
    let (text, _) = written("encoder", &xy);
    let e = parse_ballbar_trace(&text, ParseOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("expected 'angle' and 'deviation' (or 'x' and 'y')")
            && e.contains("EncoderX_Pos, EncoderY_Pos"),
        "{e}"
    );
    let wrong = BallbarColumns {
        x: Some("EncoderX_Pos".into()),
        y: Some("Encoder_Y".into()),
        ..BallbarColumns::default()
    };
    let with = |columns| ParseOptions {
        columns,
        ..ParseOptions::default()
    };
    let e = parse_ballbar_trace(&text, with(wrong))
        .unwrap_err()
        .to_string();
    assert_eq!(
        e,
        "columns.y: no column named 'Encoder_Y' in the file (columns: Sample, EncoderX_Pos, EncoderY_Pos, EncoderZ_Pos)"
    );
    // an angle/deviation file is read as X/Y when the mapping says so
    let mixed = "angle,deviation,px,py\n0,1,100,0\n";
    let cols = BallbarColumns {
        x: Some("px".into()),
        ..BallbarColumns::default()
    };
    let e = parse_ballbar_trace(mixed, with(cols))
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("no ball-bar columns found"), "{e}");
}

/// The run as a `.mat` capture: `dspace` a ControlDesk struct (`X` the
/// time, `Y(i)` with `Name`, `Data`, `Unit`), else plain vectors `t`, `x`,
/// `y`, one sample every 2 ms.
fn mat(xy: &[[f64; 2]], dspace: bool) -> Vec<u8> {
    let w = Mat { big: dspace };
    let t: Vec<f64> = (0..xy.len()).map(|i| i as f64 * 0.002).collect();
    let x: Vec<f64> = xy.iter().map(|p| p[0]).collect();
    let y: Vec<f64> = xy.iter().map(|p| p[1]).collect();
    let mut out = w.header();
    if !dspace {
        out.extend(w.doubles("t", &t));
        out.extend(w.doubles("x", &x));
        out.extend(w.doubles("y", &y));
        return out;
    }
    let fields = ["Name", "Data", "Unit"];
    let time = w.structure(
        "",
        &fields,
        &[vec![
            w.chars("", "Time"),
            w.doubles("", &t),
            w.chars("", "s"),
        ]],
    );
    let ys: Vec<Vec<Vec<u8>>> = [("EncoderX", &x), ("EncoderY", &y)]
        .iter()
        .map(|(n, v)| vec![w.chars("", n), w.doubles("", v), w.chars("", "mm")])
        .collect();
    let signals = w.structure("", &fields, &ys);
    let top = w.structure("ballbar_001", &["X", "Y"], &[vec![time, signals]]);
    out.extend(w.compressed(&top));
    out
}

#[test]
fn a_mat_capture_reads_back_to_the_same_deviations() {
    let (xy, dev) = run();
    for dspace in [true, false] {
        let columns = if dspace {
            BallbarColumns {
                x: Some("EncoderX [mm]".into()),
                y: Some("EncoderY [mm]".into()),
                ..BallbarColumns::default()
            }
        } else {
            BallbarColumns::default()
        };
        let opts = ParseOptions {
            nominal_radius: Some(100.0),
            centre: Some(PlanePoint { x: 0.0, y: 0.0 }),
            trim: false,
            columns,
            ..ParseOptions::default()
        };
        let bytes = mat(&xy, dspace);
        let t = parse_ballbar_trace_bytes(&bytes, opts.clone())
            .unwrap_or_else(|e| panic!("dspace {dspace}: {e}"));
        assert_eq!(t.runs.len(), 2, "dspace {dspace}");
        let mut seen = 0;
        for r in &t.runs {
            for (d, sample) in r.deviation.iter().zip(&r.lines) {
                let want = dev[sample - 1];
                assert!((d - want).abs() < 1e-12, "sample {sample}: {d} vs {want}");
                seen += 1;
            }
        }
        assert!(seen >= xy.len(), "{seen} samples");
        // the time column is read: the feed is measured, not unknown
        assert!(t.feed.is_some(), "dspace {dspace}: {:?}", t.warnings);
        // a damaged capture is refused naming its byte, never read as text
        let e = parse_ballbar_trace_bytes(&bytes[..200], opts)
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("byte "), "{e}");
    }
    // bytes that are text are read as text
    let (text, _) = written("semicolon", &xy);
    let from_bytes = parse_ballbar_trace_bytes(text.as_bytes(), ParseOptions::default()).unwrap();
    assert_eq!(
        from_bytes,
        parse_ballbar_trace(&text, ParseOptions::default()).unwrap()
    );
}
