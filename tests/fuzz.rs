//! A stable-Rust fuzz loop over the parsers, the writers and the config
//! conversion: seeded mutation of corpus seeds (the shared NC corpus,
//! generated ball-bar and servo traces, each export's config as JSON), fed
//! to the targets of `support/fuzz_targets.rs` (the same functions the
//! cargo-fuzz crate in `fuzz/` runs under libFuzzer):
//!
//! - `nc`: the NC lexer and interpreter (`parse_all`);
//! - `nc_write`: the writer round trips (`parse → write → parse` gives the
//!   same segments within the written precision);
//! - `ballbar`: the ball-bar trace import, then the ISO 230-4 test on it;
//! - `servo`: the servo trace import (`Table::parse`, the column lookup,
//!   the feed-vector trace analysis);
//! - `config`: JSON → each export's config type (native serde_json, the
//!   same derive the wasm binding uses), then its validation or, where the
//!   call is cheap, the call itself.
//!
//! A crash is a panic (caught per input, the input is written to
//! `target/fuzz-crashes/`) or a failed property (a NaN/∞ where the API
//! promises finite numbers, a round trip that changes the segments).
//! `cargo test --test fuzz` runs a short, fixed loop; `scripts/fuzz
//! --stable` runs the ignored `fuzz_long` with `FUZZ_EXECS` inputs per
//! target (default 1,000,000) and prints counts and times. Each crash
//! found (by either loop) becomes a regression test below.
#![cfg(not(target_arch = "wasm32"))]

#[path = "support/corpus.rs"]
mod corpus;
#[path = "support/fuzz_targets.rs"]
mod fuzz_targets;

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::time::Instant;

/// SplitMix64: a seeded generator, so a run is reproducible from its seed.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    fn below(&mut self, n: usize) -> usize {
        if n == 0 {
            0
        } else {
            (self.next() % n as u64) as usize
        }
    }
}

/// Tokens a mutation inserts: line ends, encodings, extreme numbers, NC
/// and JSON syntax.
const TOKENS: &[&str] = &[
    "\n",
    "\r",
    "\r\n",
    "\u{feff}",
    "\u{1a}",
    "\u{0}",
    "\u{7}",
    "\t",
    ",",
    ";",
    " ",
    "%",
    "(",
    ")",
    "[",
    "]",
    "{",
    "}",
    "\"",
    ":",
    "-",
    ".",
    "e",
    "E",
    "1e308",
    "-1e308",
    "1e999",
    "5e-324",
    "1e-320",
    "NaN",
    "inf",
    "-0",
    "0",
    "4294967297",
    "9007199254740993",
    "null",
    "true",
    "[]",
    "{}",
    "G0",
    "G1",
    "G2",
    "G3",
    "G4",
    "G17",
    "G18",
    "G19",
    "G20",
    "G68",
    "G69",
    "G81",
    "G90",
    "G91",
    "M97",
    "M98",
    "M99",
    "G103",
    "G187",
    "O1",
    "P",
    "L",
    "Q",
    "R",
    "X",
    "Y",
    "Z",
    "A",
    "B",
    "C",
    "I",
    "J",
    "K",
    "F",
    "N",
    "#1",
    "[#1+1]",
    "/",
    "µ",
    "°",
    "é",
];

/// One mutation of `input` (byte-level; the result is made valid UTF-8
/// the way a browser decodes a file: invalid bytes become U+FFFD).
fn mutate(rng: &mut Rng, input: &str, seeds: &[String]) -> String {
    let mut b = input.as_bytes().to_vec();
    for _ in 0..1 + rng.below(4) {
        let at = rng.below(b.len() + 1);
        match rng.below(8) {
            0 if !b.is_empty() => {
                let i = rng.below(b.len());
                b[i] ^= 1 << rng.below(8);
            }
            1 | 2 => {
                let t = TOKENS[rng.below(TOKENS.len())].as_bytes();
                b.splice(at..at, t.iter().copied());
            }
            3 if !b.is_empty() => {
                let end = (at + 1 + rng.below(16)).min(b.len());
                b.drain(at.min(end)..end);
            }
            4 if !b.is_empty() => {
                let start = rng.below(b.len());
                let end = (start + 1 + rng.below(64)).min(b.len());
                let piece = b[start..end].to_vec();
                b.splice(at..at, piece);
            }
            5 => {
                let other = seeds[rng.below(seeds.len())].as_bytes();
                if !other.is_empty() {
                    let start = rng.below(other.len());
                    let end = (start + 1 + rng.below(256)).min(other.len());
                    b.splice(at..at, other[start..end].iter().copied());
                }
            }
            6 => {
                // Replace a run of digits by an extreme number.
                let nums = [
                    "1e308",
                    "5e-324",
                    "0",
                    "-0",
                    "1e999",
                    "99999999999999999999",
                ];
                let n = nums[rng.below(nums.len())].as_bytes();
                let mut end = at;
                while end < b.len() && (b[end].is_ascii_digit() || b[end] == b'.') {
                    end += 1;
                }
                b.splice(at..end, n.iter().copied());
            }
            _ if !b.is_empty() => {
                let i = rng.below(b.len());
                b[i] = rng.next() as u8;
            }
            _ => {}
        }
    }
    String::from_utf8_lossy(&b).into_owned()
}

type Target = fuzz_targets::Target;

fn targets() -> Vec<(&'static str, Target, Vec<String>)> {
    fuzz_targets::targets()
}

/// Findings of one run: how many inputs failed, the first 20 kept.
#[derive(Default)]
struct Findings {
    count: u64,
    failures: Vec<(String, String)>,
}

/// The failure of one input: a failed property or a panic.
fn outcome(target: Target, input: &str) -> Option<String> {
    match catch_unwind(AssertUnwindSafe(|| target(input))) {
        Ok(Ok(())) => None,
        Ok(Err(e)) => Some(e),
        Err(p) => Some(format!(
            "panic: {}",
            p.downcast_ref::<String>()
                .cloned()
                .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_default()
        )),
    }
}

/// Runs `execs` mutated inputs through `target`.
fn run(name: &str, target: Target, seeds: &[String], execs: u64, seed: u64) -> Findings {
    let mut rng = Rng(seed);
    let mut found = Findings::default();
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    let mut current = seeds[0].clone();
    // FUZZ_SAVE_CURRENT=path writes each input there before it runs.
    let save_current = std::env::var("FUZZ_SAVE_CURRENT").ok();
    for k in 0..execs {
        // Mostly mutate a fresh seed; sometimes keep mutating the last input.
        if k % 4 == 0 || current.len() > 64 * 1024 {
            current = seeds[rng.below(seeds.len())].clone();
        }
        current = mutate(&mut rng, &current, seeds);
        if let Some(path) = &save_current {
            // Kept for an input that aborts the process (out of memory).
            let _ = std::fs::write(path, &current);
        }
        let Some(f) = outcome(target, &current) else {
            continue;
        };
        found.count += 1;
        if found.failures.len() < 20 {
            let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/target/fuzz-crashes");
            let _ = std::fs::create_dir_all(dir);
            let _ = std::fs::write(format!("{dir}/{name}-{seed}-{k}.txt"), &current);
            found.failures.push((current.clone(), f));
        }
    }
    std::panic::set_hook(hook);
    found
}

fn report(failures: &[(String, String)]) -> String {
    failures
        .iter()
        .map(|(i, f)| format!("{f}\n  input: {:?}", mtmotion::budget::clip(i, 300)))
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn fuzz_short() {
    for (name, target, seeds) in targets() {
        let found = run(name, target, &seeds, 300, 7);
        assert!(
            found.failures.is_empty(),
            "{name}:\n{}",
            report(&found.failures)
        );
    }
}

/// `FUZZ_EXECS` (default 1,000,000) inputs per target, `FUZZ_SEED`,
/// `FUZZ_TARGET` (one name, or all).
#[test]
#[ignore]
fn fuzz_long() {
    let execs: u64 = std::env::var("FUZZ_EXECS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(1_000_000);
    let seed: u64 = std::env::var("FUZZ_SEED")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(1);
    let only = std::env::var("FUZZ_TARGET").ok();
    let mut all = Vec::new();
    for (name, target, seeds) in targets() {
        if only.as_deref().is_some_and(|o| o != name) {
            continue;
        }
        let t0 = Instant::now();
        let found = run(name, target, &seeds, execs, seed);
        println!(
            "fuzz {name}: {execs} executions in {:.1} s, {} failures",
            t0.elapsed().as_secs_f64(),
            found.count
        );
        if !found.failures.is_empty() {
            all.push(format!("{name}:\n{}", report(&found.failures)));
        }
    }
    assert!(all.is_empty(), "{}", all.join("\n"));
}

/// Writes each target's seeds to `FUZZ_SEED_DIR/<target>/seed-<k>`: the
/// cargo-fuzz corpora start from them (`scripts/fuzz`).
#[test]
#[ignore]
fn fuzz_write_seeds() {
    let dir = std::env::var("FUZZ_SEED_DIR").expect("FUZZ_SEED_DIR: a directory for the seeds");
    for (name, _, seeds) in targets() {
        let d = std::path::Path::new(&dir).join(name);
        std::fs::create_dir_all(&d).unwrap();
        for (k, s) in seeds.iter().enumerate() {
            std::fs::write(d.join(format!("seed-{k}")), s).unwrap();
        }
    }
}

/// Inputs the fuzz loop once crashed on, each with what it now gives.
#[test]
fn fuzz_regressions() {
    // G83 with a 1e20 mm deep hole and Q0.21: 4.7e20 pecks; the loop
    // allocated until the process was killed (22 GB), and past 2^53 mm
    // `done + q == done` would never have ended.
    let text = "G90 G17 G21 F100\nG83 X0 Y0 R1 Z-99999999999999999999 Q0.21\n";
    let e = mtmotion::nc::program::parse(text).unwrap_err();
    assert_eq!((e.line, e.column), (2, 37));
    assert_eq!(
        e.message,
        "4.7619e20 pecks of Q0.21 mm for a 1e20 mm deep hole; at most 10000 per hole: check Q, R and the bottom level"
    );
    assert!(mtmotion::nc::program::parse("G90 G21 F100\nG83 X0 Y0 R1 Z-999 Q0.125\n").is_ok());
}

/// Canned cycles gave segments without limit: libFuzzer (`nc`, a 10 s
/// "slow unit" of 1.8 GB, minimised below) and one G83 line, now both
/// stopped by the segment budget (`budget::MAX_SEGMENTS`, lowered by
/// `ParseOptions::max_executed_blocks`).
#[test]
fn cycle_segment_budget_regressions() {
    use mtmotion::nc::program::{parse_all, ParseOptions};
    // 9,999 holes of 9,995 pecks: 3·10⁸ segments, 60 GB (the fuzzer's
    // process was stopped at its 2 GB limit).
    let text = "G90 G21 F100\nG83 X0 Y0 R1 Z-2099 Q0.21 L9999\n";
    let e = parse_all(text, &ParseOptions::default()).unwrap_err();
    assert_eq!(e.errors.len(), 1, "{e}");
    assert_eq!((e.errors[0].line, e.errors[0].column), (2, 1), "{e}");
    assert!(
        e.errors[0].message.starts_with(&format!(
            "more than {} segments:",
            mtmotion::budget::MAX_SEGMENTS
        )),
        "{e}"
    );
    // Under G91 each of 800 o-word repeats starts the cycle higher, so its
    // holes get deeper: 1.8·10⁷ segments from 6 lines (1.8 GB, 8 s).
    let text = "o100 repeat [800]\nn0240     g91 z1 x0 r0 l3\nn0290 g83 g90 z5 x6 r0.2 y-1.1 q0.21\nn0080     g91 x-2 y2 r0 l4 (four more g82’s)\ng1 z-.1 f24\no100 endrepeat";
    let e = parse_all(text, &fuzz_targets::nc_fuzz_options()).unwrap_err();
    let budget = fuzz_targets::FUZZ_EXECUTED_BLOCKS;
    assert!(
        e.errors.iter().any(|e| e
            .message
            .starts_with(&format!("more than {budget} segments:"))),
        "{e}"
    );
    fuzz_targets::nc_target(text).unwrap();
    fuzz_targets::nc_write_target(text).unwrap();
    // A program under the budget still runs: 100 holes of 10 pecks.
    let text = "G90 G21 F100\nG0 Z5\nG83 X0 Y0 R1 Z-1 Q0.2 L100\n";
    assert!(parse_all(text, &ParseOptions::default()).is_ok());
}

/// Writer round trips the fuzz loops found broken (`parse → write → parse`
/// changed the segments), each with the text it is now written as.
#[test]
fn writer_round_trip_regressions() {
    use mtmotion::nc::program::parse;
    // A G91 subprogram called twice was written as two absolute blocks in
    // the body, so the call ran 4 moves: a program with subprograms is now
    // written flat, as the path it runs.
    let text = "O100\nG90 G17 G21\nG0 X0 Y0\nG1 X10 F600\nM98 P200 L2\nM30\nO200\nG91 G1 X1\nM99\n";
    fuzz_targets::nc_write_target(text).unwrap();
    let p = parse(text).unwrap();
    assert_eq!(
        p.write(),
        "G21 G90 G94 G17\nG0 X0.\nG1 X10. F600.\nX11.\nX12.\nM30"
    );
    // An inch R arc of 172° (R0.1191 in = 3.02514 mm, written R3.0251):
    // the rounded R moved the centre read back by 0.28 µm; such an arc is
    // now written with I/J. A quarter arc of the helical inch R chain
    // keeps R.
    let text = "G20 G17 G90\nG0 X0 Y0\nG2 X0.2376 Y0 R0.1191 F16.\nG91 G3 X0.0939 Y0.0939 Z0.0179 R0.0939\n";
    fuzz_targets::nc_write_target(text).unwrap();
    let w = parse(text).unwrap().write();
    assert_eq!(
        w,
        "G21 G17 G90\nG0 X0. Y0.\nG2 X6.035 Y0. I3.0175 J-0.2146 F406.4\nG90 G3 X8.4201 Y2.3851 Z0.4547 R2.3851"
    );
    // Stable loop (`nc_write`, seed 21, on the corpus's bolt circle): a
    // canned-cycle block that also ends the program (`… L6 F1M2`) was
    // written flat with its M2 in front of the first hole, so the read
    // back stopped there (25 segments became 2). Its M2 now follows its
    // last segment; with X words as with polar ones.
    for text in [
        "G0 X1.5 Y0 Z0\nG91 G81 R.1 Z-.5 ^60 L6 F1M2\n",
        "G0 X1.5 Y0 Z0\nG91 G81 R.1 Z-.5 X1 L3 F1M30\n",
    ] {
        fuzz_targets::nc_write_target(text).unwrap();
        let w = parse(text).unwrap().write();
        assert!(w.ends_with("\nM2") || w.ends_with("\nM30"), "{w}");
    }
    // A `;` comment with an unpaired parenthesis was written as `( … )`,
    // which does not read back: it stays a `;` comment.
    let text = "; dri(Ci\nG0 X1 (a) ; b)c\n";
    fuzz_targets::nc_write_target(text).unwrap();
    assert_eq!(parse(text).unwrap().write(), "; dri(Ci\nG0 X1 (a) ; b)c");
    // libFuzzer (`nc_write`): a G0 block with only an R word gave a
    // zero-length rapid, written as a bare `G0` that gives none (10
    // segments became 9). A G0/G1 block without axis words now moves
    // nowhere (the R is still warned about); a corner R there is an error.
    let text = "G17\nG20\nG91\nG01 Z-0.6533 F100. \nG42 D00 \nG01 X0.0235 Y-0.0939 F10.\nG03 X0.0939 Y0.0939 Z0.0179 R0.0939 \nG0R0.0975\n";
    fuzz_targets::nc_write_target(text).unwrap();
    let p = parse(text).unwrap();
    assert_eq!(p.segments.len(), 3);
    assert!(p
        .warnings
        .iter()
        .any(|w| (w.line, w.column) == (8, 3) && w.message.contains("R0.0975 has no meaning")));
    // libFuzzer (`nc_write`, run 762,278): a call whose body ends with M30
    // ends the run inside the subprogram, before the main program's own
    // M30; the flat writer took the body's block for a main-program block
    // and wrote the main program's unrun blocks, M30 included, before it,
    // so the body's move was lost on reading back (5 segments became 4).
    let text = "O100\rG90 G17 G21\nG0 X1 Y0\nG1 X10 F600\nb4 P500\nM98 P200 D2 X10 F600\nb4 P500\nM98 P200 D2\nM30\nO200\nG91 G1 X1\nM30\nO200\nG91 G1 X1\nM99\n";
    fuzz_targets::nc_write_target(text).unwrap();
    assert_eq!(
        parse(&parse(text).unwrap().write()).unwrap().segments.len(),
        5
    );
    // The stable loop (`nc_write`, FUZZ_SEED=12345): a flat-written
    // dwell of 5.01e19 s became `G04 P9223372036854775807` (the
    // milliseconds saturated as an i64), read back as 9.2e15 s. Whole
    // milliseconds are now written with every digit (of the f64 nearest
    // 5.01e22 ms, which reads back as itself).
    let text =
        "O100\nG0 X0\nG4 P50099999999999999999999\nM98 P200 L2\nM30\nO200\nG91 G1 X1 F100\nM99\n";
    fuzz_targets::nc_write_target(text).unwrap();
    let w = parse(text).unwrap().write();
    assert!(w.contains("\nG04 P50100000000000003145728\n"), "{w}");
    let e = parse("G90 G21 F100\nG1 X10\nG1 R2\nG1 Y10\n").unwrap_err();
    assert_eq!((e.line, e.column), (3, 4), "{e}");
    assert!(
        e.message
            .starts_with("corner word R2 on a G1 block without an end point"),
        "{e}"
    );
    if let Some(text) = corpus::text("cncjs_helical-thread-milling.gcode") {
        fuzz_targets::nc_write_target(&text).unwrap();
    }
}

/// The stable loop (`servo`, seed 1, 50,000 runs: 11 failures): a SERVO
/// GUIDE-style trace with a position of ~1e305 mm gave a feed-vector
/// summary with an infinite half amplitude (the shape error's span
/// overflowed). Each column now has a physical range, refused at its line.
#[test]
fn servo_trace_magnitude_regressions() {
    use mtmotion::feed_vector::{trace_analysis, Condition};
    let seed = &fuzz_targets::servo_seeds()[0];
    let map = trace_analysis::ColumnMap::default();
    let cond = Condition::paper(1.0);
    for (old, new, at) in [
        // run 37,900: Y [um] 1e308 on the second sample
        (
            "1;0.993833508538892;110.88262850995298;",
            "1;0.993833508538892;1e308;",
            // (the header's µm now scales it: 1e305 mm)
            "line 5, column 3 ('Y [um]'): 1e305 mm",
        ),
        // run 10,588: X = -0.69e308 mm
        (
            "21;-0.6907581397498764;",
            "21;-0.69075813974987641e308;",
            "line 25, column 2 ('X(mm)'): -6.90758e307 mm",
        ),
        // no overflow, but 1e20 mm is no machine's
        (
            "35;-0.7335291829995831;",
            "35;-099999999999999999999;",
            "line 39, column 2 ('X(mm)'): -1e20 mm",
        ),
    ] {
        assert!(seed.contains(old), "{old}");
        let text = seed.replacen(old, new, 1);
        fuzz_targets::servo_target(&text).unwrap();
        let e = trace_analysis::analyze_trace(&text, &cond, &map)
            .err()
            .unwrap();
        assert!(
            e.to_string()
                .starts_with(&format!("{at} (after scaling) is outside ±1e5 mm")),
            "{e}"
        );
    }
    // the seed itself is analysed, and its summary is finite: its
    // `Time [ms]` is 59 ms of C turning at 0.5 deg/ms (8.7 rad/s), so the
    // steady window is the whole trace and ω is C's (it was read as 59 s
    // at 1 rad/s before the header's units were read)
    let map = trace_analysis::ColumnMap {
        steady_from: Some(0.0),
        ..map
    };
    let cond = Condition::paper(500f64.to_radians());
    let r = trace_analysis::analyze_trace(seed, &cond, &map).unwrap();
    assert!(r.summary.half_amplitude.is_finite() && r.summary.half_amplitude > 0.0);
}

/// The stable loop (`nc_write`, seeds 2024, 4242 and 31337): a program read
/// as multi-axis only because of a `B0` on a G4 block (the flat writer
/// does not write it back, so `G1 C1` became a chamfer), and inch numbers
/// of 2e22 written in mm with more characters than an NC number has.
#[test]
fn writer_multi_axis_and_huge_number_regressions() {
    use mtmotion::nc::program::parse;
    let text = "O100\nG90 G17 G21\nG0 X0 Y0\nG1 X10 F600\nG4 P5b0\nM98 P200 L2\nM30\nO200\nG91 G1 C1\nM99\n";
    fuzz_targets::nc_write_target(text).unwrap();
    // a B word on a dwell says nothing of the machine: C1 is a chamfer
    let e = parse(text).unwrap_err();
    assert!(e.message.contains("C1"), "{e}");
    // with a B axis moved somewhere, C is an axis
    assert!(parse("G0 B0\nG1 C1 F100\n").is_ok());
    for (text, line, what) in [
        (
            "G20 G17 G90\nG0 X19999999999999999999999 Y0 Z0\nM2\n",
            2,
            "end point X (mm) 5.08e23 is beyond ±1e9",
        ),
        (
            "G21 G90\nG1 X1 F600\nY-1 F100099999999999999999999\n",
            3,
            "feed (mm/min) 1.001e23 is beyond ±1e9",
        ),
        (
            "G21 G90\nG0 X0 Y0\nG2 X1 Y0 R100000000000000000000 F100\n",
            3,
            "arc centre (mm)",
        ),
    ] {
        fuzz_targets::nc_write_target(text).unwrap();
        let e = parse(text).unwrap_err();
        assert_eq!(e.line, line, "{e}");
        assert!(
            e.message.starts_with(what) && e.message.contains("check the units"),
            "{e}"
        );
    }
    // seed 4242: a Fanuc corner R0.4322 at a near-reversal (a 173° arc)
    // written as an R arc read back 0.2 µm further along; now written with I/J
    let text = "G90 G17 G21\nG0 X201.3501 Y31.3929\nG1 X203.0498 Y29.9465 F600\nN690 G1 X204.6894 Y2R.4322\nN700 G1 X206.2694 Y26.8558\nG1 X207.9896 Y25.0172\n";
    fuzz_targets::nc_write_target(text).unwrap();
    // libFuzzer (`nc_write`, run 216,6xx): a G92 naming the current
    // position (no shift) in an inch block was written block by block,
    // its X10.5 kept under G21, so the read back shifted X by 256 mm
    let text = "G21\nG0 X0 Y0 Z20\nF100\nG1 X2 Y-4 Z16\nG1 X10.5 G20\nG1 X10.5 G20 G92 G17\nG0 X-.2 Y-.2\n";
    fuzz_targets::nc_write_target(text).unwrap();
    // a long but real path is still read
    assert!(parse("G21 G91 G1 X999999 F600\nX999999\n").is_ok());
}
