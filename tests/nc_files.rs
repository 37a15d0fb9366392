//! Several program files at once: M98, G65 and o-word calls find their
//! subprograms in extra files; errors and warnings in an extra file name
//! the file, line and column; the main program's end is the end of the
//! run; the main file is picked among dropped files. Read from owned texts
//! (`parse_files_owned`, what the wasm bindings call: the texts freed once
//! lexed) a program gives the same program and the same errors.

use mtmotion::nc::files::{main_file, parse_files, parse_files_keeping, parse_files_owned, NcFile};
use mtmotion::nc::program::{Keep, ParseOptions};

fn file(name: &str, text: &str) -> NcFile {
    NcFile {
        name: name.into(),
        text: text.into(),
    }
}

fn xs(main: &str, files: &[NcFile]) -> Vec<f64> {
    parse_files(main, files, &ParseOptions::default())
        .unwrap_or_else(|e| panic!("{e}"))
        .segments
        .iter()
        .map(|s| s.end.x)
        .collect()
}

#[test]
fn calls_reach_subprograms_in_other_files() {
    let fanuc = [
        file("O2000.nc", "%\nO2000\nG91 G1 X5 F100\nG90\nM99\n%"),
        file("O9010.nc", "O9010\nG1 X[#24*2] F100\nM99"),
    ];
    // No M30: the run still ends with the main program.
    assert_eq!(
        xs("G0 X0\nM98 P2000 L2\nG65 P9010 X7\nG0 X1", &fanuc),
        vec![0.0, 5.0, 10.0, 14.0, 1.0]
    );
    let linuxcnc = [file(
        "drill.ngc",
        "o<drill> sub\nG0 X#1\nG1 Z-#2 F50\no<drill> endsub\nM2",
    )];
    let p = parse_files(
        "G21 G90\no<drill> call [3] [1]\no<drill> call [6] [2]\nM2",
        &linuxcnc,
        &ParseOptions::default(),
    )
    .unwrap();
    let ends: Vec<(f64, f64)> = p.segments.iter().map(|s| (s.end.x, s.end.z)).collect();
    assert_eq!(
        ends,
        vec![(3.0, 0.0), (3.0, -1.0), (6.0, -1.0), (6.0, -2.0)]
    );
    assert!(p.segments.iter().all(|s| s.fixed));
    // Segments keep their line in their own file.
    assert_eq!(p.segments[1].line, 3);
}

/// `parse_files_owned` is `parse_files_keeping` with the texts given up:
/// the same segments, warnings, blocks and errors (their files and lines
/// included), for both `Keep`s.
#[test]
fn owned_texts_read_as_borrowed_ones() {
    let o = ParseOptions::default();
    let cases: [(&str, Vec<NcFile>); 4] = [
        (
            "G0 X0\nM98 P2000\nG0 X100\nM30",
            vec![file("O2000.nc", "O2000\nG91 G1 X5 F100 M8\nG90\nM99")],
        ),
        (
            "G0 X0\nM98 P2000\nG1 Y\nM30",
            vec![file("O2000.nc", "O2000\nG1 X1 F100 M8\nG1 X\nM99")],
        ),
        ("G90 G21\nG0 X1 Y1\nG2 X3 Y1 R1 F300\n(done)\nM30", vec![]),
        ("G1 X1\nG0 X(open", vec![]),
    ];
    for keep in [Keep::All, Keep::Motion] {
        for (text, files) in &cases {
            let borrowed = parse_files_keeping(text, files, &o, keep);
            let owned = parse_files_owned(text.to_string(), files.clone(), &o, keep);
            assert_eq!(borrowed, owned, "{text}");
        }
    }
}

#[test]
fn errors_and_warnings_name_the_file() {
    let subs = [file("O2000.nc", "O2000\nG1 X1 F100 M8\nG1 X\nM99")];
    let e = parse_files(
        "G0 X0\nM98 P2000\nG1 Y\nM30",
        &subs,
        &ParseOptions::default(),
    )
    .unwrap_err();
    let got: Vec<String> = e.errors.iter().map(|e| e.to_string()).collect();
    assert_eq!(
        got,
        vec![
            "line 3, column 4: expected a number after address 'Y'".to_string(),
            "file O2000.nc, line 3, column 4: expected a number after address 'X'".to_string(),
        ]
    );
    let subs = [file("O2000.nc", "O2000\nG1 X1 F100 M8\nM99")];
    let p = parse_files("G0 X0\nM98 P2000\nM30", &subs, &ParseOptions::default()).unwrap();
    let w = p
        .warnings
        .iter()
        .find(|w| w.message.contains("M8"))
        .unwrap();
    assert_eq!(
        (w.file.as_deref(), w.line, w.column),
        (Some("O2000.nc"), 2, 12)
    );
    // A subprogram running off the end of its file.
    let subs = [file("O2000.nc", "O2000\nG1 X1 F100"), file("b.nc", "G0 X9")];
    let e = parse_files("M98 P2000\nM30", &subs, &ParseOptions::default()).unwrap_err();
    assert_eq!(e.errors[0].file.as_deref(), Some("O2000.nc"), "{e}");
    assert!(e.errors[0].message.contains("without M99"), "{e}");
    // A call with no file holding the subprogram.
    let e = parse_files("M98 P4000\nM30", &subs, &ParseOptions::default()).unwrap_err();
    assert!(
        e.errors[0].message.contains("O4000 is not in this program"),
        "{e}"
    );
}

#[test]
fn the_main_program_is_the_one_that_ends() {
    assert_eq!(
        main_file(&["O2000\nG1 X1\nM99", "G0 X0\nM98 P2000\nM30"]),
        1
    );
    assert_eq!(main_file(&["G0 X0\nM98 P2000", "O2000\nG1 X1\nM99"]), 0);
    assert_eq!(main_file(&["O1\nM99", "O2\nM99"]), 0);
}
