//! LinuxCNC's own interpreter as an oracle: every LinuxCNC-dialect and
//! generic program of the shared corpus (`support/corpus.rs`), every
//! team-written `.ngc`/`.nc` program under `tests/`, and the built-in
//! tool-path examples are run through `rs274 -g` (Debian's
//! `linuxcnc-uspace`, installed by `./scripts/bootstrap`) and through
//! mtmotion, and compared move by move: the kind (rapid, feed, arc), the
//! end point of every straight move and arc on all six axes, and of every
//! arc its centre, its direction and its turn count. Tolerance: half of
//! rs274's last printed digit (it prints 4 decimals in the program's
//! units: 0.00005 mm, or 0.00005 in = 0.00127 mm under G20), plus 1e-9 mm.
//!
//! rs274 prints no source line, only a block's N number, so it is given a
//! copy of the program whose every block is numbered by its line (an N
//! word added, or put in place of the block's own); mtmotion reads the file
//! as it is. Both move lists are cut into runs of consecutive moves of one
//! source line and compared run by run. rs274 prints in the program frame
//! (its G5x and G92 offsets taken off) and in the program's unit: the G92
//! offset it reports is added back (its G5x offsets are not: see
//! [`Kind::WorkFrame`]) and inch is converted to mm. Its parameter file
//! starts empty each run (all offsets zero) and its tool table holds
//! tools 1–99 of zero length and diameter.
//! Dwells are not compared; moves of zero length are dropped from both.
//!
//! Splines (G5.1, G5.2/G5.3): rs274 prints one `NURBS_FEED(count, ...)`
//! per curve, without its geometry, so the curve comes from LinuxCNC's
//! preview interpreter (the `gcode` Python module of the same package,
//! `tests/support/linuxcnc_preview.py`): its straight feeds end at points
//! of the curve evaluated by LinuxCNC's own code (15 per control point),
//! printed in full precision. Each of those points must lie within
//! [`SPLINE_TOL`] (mtmotion's chordal tolerance, 1 µm, + 1e-6 mm) of
//! mtmotion's chords of that line, and the curve must end at the same
//! point ([`spline_agrees`]).
//!
//! Every difference is a failure naming the file, the line and both moves,
//! unless it is in [`KNOWN`], the one list of dialect differences, each
//! with its reason. Without rs274 (or without the corpus, for its files)
//! the test prints one line saying what it skipped and why, and passes.
#![cfg(not(target_arch = "wasm32"))]

#[path = "support/corpus.rs"]
mod corpus;

use std::fmt;
use std::path::{Path, PathBuf};
use std::process::Command;

use mtmotion::nc::nurbs::{distance_to_chord, CHORD_TOLERANCE};
use mtmotion::nc::program::{parse_all, Motion, ParseOptions, Plane};

/// How far a point of LinuxCNC's spline may lie from mtmotion's chords of
/// it, mm: the chordal tolerance, and 1e-6 mm for the preview's inch
/// arithmetic.
const SPLINE_TOL: f64 = CHORD_TOLERANCE + 1e-6;

/// How a known difference is compared on the lines it covers.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Kind {
    /// Canned-cycle blocks: only the feed moves are compared (their end
    /// points and order); the rapids differ by dialect.
    CycleFeedsOnly,
    /// The lines' moves are left out on both sides; the moves after them
    /// are compared as usual (by end point, so a move left out does not
    /// shift the others).
    NotCompared,
    /// rs274's G54–G59.3 work offsets are not added back to its moves:
    /// mtmotion's path is in the work frame.
    WorkFrame,
    /// mtmotion refuses the program with this phrase: nothing is
    /// compared, but the refusal is checked (a program that starts to
    /// parse must be compared).
    Refused(&'static str),
    /// rs274 stops with this phrase: the moves before its stop are
    /// compared, mtmotion's later moves are not.
    Rs274Stops(&'static str),
}

/// A known dialect difference: the corpus file (or `*` for every
/// program), the source lines it covers (empty: every line), how those
/// lines are compared, and why.
struct Known {
    file: &'static str,
    lines: &'static [usize],
    kind: Kind,
    why: &'static str,
}

/// THE list of known differences between mtmotion and LinuxCNC's rs274.
/// Anything not here must agree exactly (to the print resolution).
const KNOWN: &[Known] = &[
    Known {
        file: "*",
        lines: &[],
        kind: Kind::CycleFeedsOnly,
        why: "canned cycles follow Fanuc levels (src/nc/cycles.rs): to the hole at the \
              current level then down to R, and G98 returns to the initial level; LinuxCNC \
              moves first to R when below it, returns under G98 to the higher of the \
              initial level and R, and uses its own peck clearance (G73/G83). The feed \
              moves (peck depths and bottoms) are the same and are compared",
    },
    Known {
        file: "*",
        lines: &[],
        kind: Kind::WorkFrame,
        why: "G54-G59.3 work offsets (and G10 L2/L20 setting them) are warned about and not \
              applied: mtmotion simulates the path in the work frame (src/nc/program.rs), \
              so rs274's G5x offsets are not added back (its G92/G52 offset is: both model it). \
              The line of the first move after a G5x change is left out on both sides: \
              rs274's frame jumps on the axes that move does not name",
    },
    Known {
        file: "*",
        lines: &[],
        kind: Kind::Rs274Stops("File ended with no percent sign or program end"),
        why: "LinuxCNC requires M2/M30 or a closing % and stops with this error after the \
              last block; mtmotion reads a program to the end of its text. The moves before \
              are all compared",
    },
    Known {
        file: "cncsprayer_fusion-output.nc",
        lines: &[54, 56],
        kind: Kind::NotCompared,
        why: "G28 G91 Z0. / X0. Y0.: the return to the reference point is not simulated \
              (as in ledfloor_1003.nc). The program (G20 with metric-sized numbers, \
              edited) is compared since the arc tolerance is LinuxCNC's: its arcs are \
              0.001 in off their radius, read by rs274 and by mtmotion with a warning",
    },
    Known {
        file: "linuxcnc_mmount.ngc",
        lines: &[
            72, 74, 81, 140, 143, 156, 162, 165, 167, 172, 178, 184, 187, 197, 203, 213, 217, 218,
            246, 247, 305, 311, 322, 325, 332,
        ],
        kind: Kind::NotCompared,
        why: "G00 G53 Z0 (machine coordinates) is not simulated (src/nc/non_modal.rs), and \
              the X/Y rapids after each, up to the next Z word, run at another Z in rs274; \
              line 72 (G00 Z0.25 after a G81 run) is a rapid up from R in rs274, whose \
              standalone default return mode is G99, and zero-length in mtmotion (G98, \
              Fanuc's default, already returned to Z0.25). Its G33.1 rigid taps are \
              compared: a feed to the bottom and back",
    },
    Known {
        file: "printhor_example3.gcode",
        lines: &[23, 24, 37, 38],
        kind: Kind::NotCompared,
        why: "G88's manual retract (src/nc/cycles.rs): mtmotion rapids out to the return \
              level, rs274 stays at the bottom; the program is in G91 then, so the next \
              holes after a plane change (G18 after line 20, G19 after line 33), where the \
              old drilling axis is a plane axis, start from another level. The feed depths \
              and every G87 back bore (lines 13, 14, 19, 32, 46) are compared",
    },
    Known {
        file: "printhor_example3.gcode",
        lines: &[28, 42],
        kind: Kind::NotCompared,
        why: "G84 in G18 and G19: rs274 passes the hole position and the level to its \
              feeds in the wrong order (interp_cycles.cc, convert_cycle_g74_g84: \
              cycle_feed(y, bottom_z, x) and cycle_feed(bottom_z, x, y)), so \
              g84 z6 x7 r0.2 y-1.1 (G18) taps at X-1.1 Y6 Z7 and g84 y6 z7 r0.2 x-1.1 \
              (G19) at X7 Y-1.1 Z6; mtmotion taps each hole at its position along its \
              drilling axis, as G81-G89 in the same planes",
    },
    Known {
        file: "ledfloor_1003.nc",
        lines: &[202, 205],
        kind: Kind::NotCompared,
        why: "G28 G91 Z0 / X0 Y0: the return to the reference point is not simulated \
              (src/nc/non_modal.rs; the reference position is machine data); rs274 moves \
              to its home (machine zero)",
    },
    Known {
        file: "linuxcnc_Pasta.ngc",
        lines: &[17, 19, 1881, 1882],
        kind: Kind::NotCompared,
        why: "G0 G53 Z-10: a move in machine coordinates is not simulated \
              (src/nc/non_modal.rs), nor are the G53 retracts at the end (1881, 1882); \
              the move after the first (line 19, X0 Y0) starts from another Z and is \
              zero-length in mtmotion",
    },
    Known {
        file: "cncjs_Circle_Diamond_Square_Calibration.gcode",
        lines: &[],
        kind: Kind::Refused("inconsistent radius"),
        why: "line 624 (G3 X21 Y-20 I20 J21): the end is 1.4 mm off the start's radius; \
              mtmotion refuses it, and rs274 stops there too ('Radius to end of arc \
              differs from radius to start')",
    },
    Known {
        file: "cncjs_full-circle-without-xyz.gcode",
        lines: &[],
        kind: Kind::Refused("without a centre"),
        why: "line 11 (`N55 X.75` after a full circle, still in G2) is an arc without a \
              centre: mtmotion refuses it, and rs274 stops there too ('R i j k words all \
              missing for arc')",
    },
];

/// Corpus files that are not compared, each with why (another dialect, or
/// not a milling program). Every corpus file is here or compared: a new
/// file without a decision fails the test.
const OTHER_DIALECTS: &[(&str, &str)] = &[
    ("cncjs_sample.gcode", "3D-printer program (E words)"),
    ("cura_hex2.gcode", "3D-printer program (E words)"),
    (
        "cncsprayer_7997A.NC",
        "Fanuc Macro B laser program (IF/GOTO, #500x system variables)",
    ),
    ("cncsprayer_CIRCLE.NC", "Fanuc Macro B laser program"),
    ("cncsprayer_RECTANGLE.NC", "Fanuc Macro B laser program"),
    ("cncsprayer_WASHER.NC", "Fanuc Macro B laser program"),
    (
        "gcws_FANUC0M.nc",
        "Fanuc 0M program (`:0097` program number)",
    ),
    ("gcws_HAAS.nc", "Haas program (IF [..] THEN)"),
    ("gcws_OSP5020M.nc", "Okuma OSP program"),
];

/// One canonical move, positions in mm (and degrees).
#[derive(Debug, Clone, Copy, PartialEq)]
enum Kinded {
    Traverse,
    Feed,
    /// Centre in the plane (first, second axis, mm) and signed turn count.
    Arc {
        plane: Plane,
        centre: [f64; 2],
        rotation: i64,
    },
    /// A point of LinuxCNC's spline (a G5.1 or G5.3 line), from its
    /// preview interpreter; compared by [`spline_agrees`].
    SplinePoint,
}

#[derive(Debug, Clone, Copy)]
struct Move {
    line: usize,
    kind: Kinded,
    end: [f64; 6],
    /// Tolerance on every coordinate, mm.
    tol: f64,
    /// rs274's first move after its G5x offset changed, when the offsets
    /// are not added back (see [`Kind::WorkFrame`]).
    jump: bool,
}

impl fmt::Display for Move {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let e: Vec<String> = self.end.iter().map(|v| format!("{v:.4}")).collect();
        match self.kind {
            Kinded::Traverse => write!(f, "rapid to ({})", e.join(", ")),
            Kinded::Feed => write!(f, "feed to ({})", e.join(", ")),
            Kinded::SplinePoint => write!(f, "spline point ({})", e.join(", ")),
            Kinded::Arc {
                plane,
                centre,
                rotation,
            } => write!(
                f,
                "G{} arc to ({}) about ({:.4}, {:.4}) rotation {rotation}",
                plane.code(),
                e.join(", "),
                centre[0],
                centre[1]
            ),
        }
    }
}

/// The plane's (first, second, normal) axes as LinuxCNC's ARC_FEED orders
/// them: XY, ZX, YZ (mtmotion's `Plane::axes`).
fn arc_axes(p: Plane) -> (usize, usize, usize) {
    p.axes()
}

/// mtmotion's moves of `text`, or its refusal.
fn mtmotion_moves(text: &str) -> Result<Vec<Move>, String> {
    let p = parse_all(text, &ParseOptions::default()).map_err(|e| e.to_string())?;
    let mut out = Vec::new();
    for s in &p.segments {
        let kind = match s.motion {
            Motion::Dwell { .. } => continue,
            Motion::Rapid => Kinded::Traverse,
            Motion::Linear => Kinded::Feed,
            Motion::Arc(a) => {
                let (u, v, _) = arc_axes(a.plane);
                let turns = (a.sweep.abs() / std::f64::consts::TAU - 1e-9).ceil() as i64;
                Kinded::Arc {
                    plane: a.plane,
                    centre: [a.center[u], a.center[v]],
                    rotation: if a.sweep < 0.0 { -turns } else { turns },
                }
            }
        };
        out.push(Move {
            line: s.line,
            kind,
            end: s.end.to_array(),
            tol: 0.0,
            jump: false,
        });
    }
    Ok(out)
}

/// The program with every block numbered by its line (N word added, or
/// put in place of its own), so that rs274's output names the line.
/// O-word lines, `%` lines and blank lines are left as they are.
fn numbered(text: &str) -> String {
    let mut out = String::with_capacity(text.len() + 8 * text.lines().count());
    for (i, raw) in text.split('\n').enumerate() {
        let line = raw.strip_suffix('\r').unwrap_or(raw);
        let body = line.trim_start();
        let (slash, body) = match body.strip_prefix('/') {
            Some(b) => ("/", b.trim_start()),
            None => ("", body),
        };
        let first = body.chars().next().map(|c| c.to_ascii_uppercase());
        let skip = match first {
            None | Some('%') => true,
            Some('O') => body[1..]
                .trim_start()
                .starts_with(|c: char| c.is_ascii_digit() || c == '<'),
            _ => false,
        };
        if skip {
            out.push_str(line);
        } else {
            let rest = if first == Some('N') {
                body[1..]
                    .trim_start()
                    .trim_start_matches(|c: char| c.is_ascii_digit())
                    .trim_start()
            } else {
                body
            };
            out.push_str(&format!("{slash}N{} {rest}", i + 1));
        }
        out.push('\n');
    }
    out
}

/// A tool table of tools 1–99, zero length and diameter: tool changes and
/// G43 do not stop rs274 and do not move the path (mtmotion has no tool
/// table), G41/G42 offset by zero (mtmotion: no radius given).
fn tool_table() -> String {
    (1..=99).map(|t| format!("T{t} P{t} D0 Z0 ;\n")).collect()
}

/// rs274's moves of `text` (written numbered into `work`), the message it
/// stopped with, if any, and how many of its moves had a G5x offset (not
/// added back unless `add_g5x`).
fn rs274_moves(
    rs274: &Path,
    text: &str,
    work: &Path,
    add_g5x: bool,
) -> (Vec<Move>, Option<String>, usize) {
    std::fs::create_dir_all(work).unwrap();
    let prog = work.join("program.ngc");
    std::fs::write(&prog, numbered(text)).unwrap();
    std::fs::write(work.join("tools.tbl"), tool_table()).unwrap();
    // A fresh, empty parameter file each run (rs274 writes it back).
    let var = work.join("params.var");
    std::fs::write(&var, "").unwrap();
    let out = Command::new(rs274)
        .arg("-g")
        .arg("-b") // block delete on, as mtmotion's default
        .arg("-t")
        .arg(work.join("tools.tbl"))
        .arg("-v")
        .arg(&var)
        .arg(&prog)
        .current_dir(work)
        .output()
        .unwrap_or_else(|e| panic!("{}: {e}", rs274.display()));
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    let mut moves = Vec::new();
    let mut unit = 1.0;
    let mut g5x = [0.0; 6];
    let mut g92 = [0.0; 6];
    let mut plane = Plane::XY;
    let mut shifted = 0;
    let mut last_g5x = [0.0; 6];
    // LinuxCNC's spline points, by source line, only when rs274 cut one.
    let mut curves = if stdout.contains("NURBS_FEED(") {
        preview_curves(&prog, work)
    } else {
        Vec::new()
    };
    for l in stdout.lines() {
        let Some((line, call, args)) = canon(l) else {
            continue;
        };
        let nums: Vec<f64> = args
            .split(',')
            .filter_map(|a| a.trim().parse::<f64>().ok())
            .collect();
        let tol = 0.5e-4 * unit * (1.0 + 1e-9) + 1e-9;
        // Program frame + offsets, in mm (linear axes) or degrees.
        let g5 = if add_g5x { g5x } else { [0.0; 6] };
        let machine = |k: usize, v: f64| {
            let s = if k < 3 { unit } else { 1.0 };
            (v + g5[k] + g92[k]) * s
        };
        let is_move = matches!(
            call,
            "STRAIGHT_TRAVERSE" | "STRAIGHT_FEED" | "ARC_FEED" | "RIGID_TAP"
        );
        if !add_g5x && is_move && g5x.iter().any(|&o| o != 0.0) {
            shifted += 1;
        }
        let jump = !add_g5x && is_move && g5x != last_g5x;
        if is_move {
            last_g5x = g5x;
        }
        match call {
            "USE_LENGTH_UNITS" => unit = if args.contains("INCHES") { 25.4 } else { 1.0 },
            "SET_G5X_OFFSET" => g5x.copy_from_slice(&nums[1..7]),
            "SET_G92_OFFSET" => g92.copy_from_slice(&nums[0..6]),
            "SELECT_PLANE" => {
                plane = match args {
                    a if a.contains("XZ") => Plane::ZX,
                    a if a.contains("YZ") => Plane::YZ,
                    _ => Plane::XY,
                }
            }
            "STRAIGHT_TRAVERSE" | "STRAIGHT_FEED" => {
                let mut end = [0.0; 6];
                for k in 0..6 {
                    end[k] = machine(k, nums[k]);
                }
                let kind = if call == "STRAIGHT_FEED" {
                    Kinded::Feed
                } else {
                    Kinded::Traverse
                };
                moves.push(Move {
                    line,
                    kind,
                    end,
                    tol,
                    jump,
                });
            }
            // G33.1: a feed to (x, y, z) and back to where it started.
            "RIGID_TAP" => {
                let back = moves.last().map_or([0.0; 6], |m: &Move| m.end);
                let mut end = back;
                for k in 0..3 {
                    end[k] = machine(k, nums[k]);
                }
                for end in [end, back] {
                    moves.push(Move {
                        line,
                        kind: Kinded::Feed,
                        end,
                        tol,
                        jump,
                    });
                }
            }
            // A spline: its points from the preview, in inches.
            "NURBS_FEED" => {
                let Some(k) = curves.iter().position(|c| c.0 == line) else {
                    panic!("line {line}: rs274 cuts a spline that LinuxCNC's preview does not");
                };
                let (_, points) = curves.remove(k);
                let at = moves.last().map_or([0.0; 6], |m: &Move| m.end);
                for [x, y] in points {
                    let mut end = at;
                    end[0] = machine(0, x * 25.4 / unit);
                    end[1] = machine(1, y * 25.4 / unit);
                    moves.push(Move {
                        line,
                        kind: Kinded::SplinePoint,
                        end,
                        // full precision: only a repeated point is still
                        tol: 1e-9,
                        jump,
                    });
                }
            }
            "ARC_FEED" => {
                let (u, v, n) = arc_axes(plane);
                let mut end = [0.0; 6];
                end[u] = machine(u, nums[0]);
                end[v] = machine(v, nums[1]);
                end[n] = machine(n, nums[5]);
                for k in 3..6 {
                    end[k] = machine(k, nums[k + 3]);
                }
                let centre = [machine(u, nums[2]), machine(v, nums[3])];
                moves.push(Move {
                    line,
                    kind: Kinded::Arc {
                        plane,
                        centre,
                        rotation: nums[4] as i64,
                    },
                    end,
                    tol,
                    jump,
                });
            }
            _ => {}
        }
    }
    // rs274 reports an error on stderr (or stdout) and stops.
    let stopped = stderr
        .lines()
        .chain(stdout.lines())
        .find(|l| canon(l).is_none() && !l.trim().is_empty() && *l != "executing")
        .map(str::to_string);
    (moves, stopped, shifted)
}

/// The runs of straight feeds of LinuxCNC's preview interpreter on `prog`
/// (see the module header): (source line, points in inches), in order.
fn preview_curves(prog: &Path, work: &Path) -> Vec<(usize, Vec<[f64; 2]>)> {
    let script = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/support/linuxcnc_preview.py"
    );
    let var = work.join("preview.var");
    std::fs::write(&var, "").unwrap();
    let out = Command::new("/usr/bin/python3")
        .arg(script)
        .arg(prog)
        .arg(&var)
        .current_dir(work)
        .output()
        .unwrap_or_else(|e| panic!("/usr/bin/python3 (LinuxCNC's preview, for splines): {e}"));
    assert!(
        out.status.success(),
        "LinuxCNC's preview interpreter failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let mut runs: Vec<(usize, Vec<[f64; 2]>)> = Vec::new();
    let mut open = false;
    for l in String::from_utf8_lossy(&out.stdout).lines() {
        let f: Vec<&str> = l.split_whitespace().collect();
        let line: usize = f.get(1).and_then(|v| v.parse().ok()).unwrap_or(0);
        if f.first() != Some(&"F") {
            open = false;
            continue;
        }
        let p = [f[2].parse().unwrap(), f[3].parse().unwrap()];
        match runs.last_mut() {
            Some((l0, pts)) if open && *l0 == line => pts.push(p),
            _ => runs.push((line, vec![p])),
        }
        open = true;
    }
    runs
}

/// LinuxCNC's spline `theirs` (its points) against mtmotion's chords
/// `ours` of the same line, which start at `from`: every point within
/// [`SPLINE_TOL`] of the chords, the same end point, and the other axes
/// unmoved. `None` when they agree, else what differs.
fn spline_agrees(ours: &[Move], theirs: &[Move], from: [f64; 6]) -> Option<String> {
    if ours.iter().any(|m| m.kind != Kinded::Feed) {
        return Some(format!("mtmotion {} on a spline line", ours[0]));
    }
    let mut poly = vec![[from[0], from[1]]];
    poly.extend(ours.iter().map(|m| [m.end[0], m.end[1]]));
    for q in theirs {
        let p = [q.end[0], q.end[1]];
        let d = poly
            .windows(2)
            .map(|w| distance_to_chord(p, w[0], w[1]))
            .fold(f64::INFINITY, f64::min);
        if d.is_nan() || d > SPLINE_TOL {
            return Some(format!(
                "{q} is {d:.6} mm from mtmotion's chords (tolerance {SPLINE_TOL} mm)"
            ));
        }
    }
    let (a, b) = (ours.last()?, theirs.last()?);
    let off = (0..6)
        .map(|k| (a.end[k] - b.end[k]).abs())
        .fold(0.0, f64::max);
    (off > 1e-6).then(|| format!("the curve ends at mtmotion {a}, LinuxCNC {b}"))
}

/// `   12 N34    CALL(args)` → (34, "CALL", "args"); `N.....` → line 0.
fn canon(l: &str) -> Option<(usize, &str, &str)> {
    let l = l.trim_start();
    let (_, rest) = l.split_once(' ')?;
    let rest = rest.trim_start().strip_prefix('N')?;
    let digits = rest.len()
        - rest
            .trim_start_matches(['.', '0', '1', '2', '3', '4', '5', '6', '7', '8', '9'])
            .len();
    let line = rest[..digits].parse().unwrap_or(0);
    let rest = rest[digits..].trim_start();
    let open = rest.find('(')?;
    let call = &rest[..open];
    if !call
        .chars()
        .all(|c| c.is_ascii_uppercase() || c == '_' || c.is_ascii_digit())
    {
        return None;
    }
    Some((line, call, rest[open + 1..].strip_suffix(')')?))
}

/// Moves of zero length (end at the previous end within its tolerance)
/// dropped: one interpreter may emit them, the other not.
fn moving(moves: Vec<Move>, start: [f64; 6]) -> Vec<Move> {
    let mut at = start;
    let mut out = Vec::new();
    for m in moves {
        let still = (0..6).all(|k| (m.end[k] - at[k]).abs() <= m.tol.max(1e-9));
        // An arc back to its start is a full circle, not a still move.
        let arc = matches!(m.kind, Kinded::Arc { .. });
        if !still || arc {
            out.push(m);
        }
        at = m.end;
    }
    out
}

/// Same move within rs274's tolerance.
fn same(a: &Move, b: &Move) -> bool {
    let tol = a.tol.max(b.tol);
    let close = |x: f64, y: f64| (x - y).abs() <= tol;
    let kinds = match (a.kind, b.kind) {
        (Kinded::Traverse, Kinded::Traverse) | (Kinded::Feed, Kinded::Feed) => true,
        (
            Kinded::Arc {
                plane: p,
                centre: c,
                rotation: r,
            },
            Kinded::Arc {
                plane: q,
                centre: d,
                rotation: s,
            },
        ) => p == q && r == s && close(c[0], d[0]) && close(c[1], d[1]),
        _ => false,
    };
    kinds && (0..6).all(|k| close(a.end[k], b.end[k]))
}

/// Runs of consecutive moves of one source line.
fn runs(moves: &[Move]) -> Vec<&[Move]> {
    moves.chunk_by(|a, b| a.line == b.line).collect()
}

/// What the comparison of one program found.
struct Tally {
    /// Moves compared equal.
    compared: usize,
    /// Per entry of [`KNOWN`]: how many times it applied (moves, runs or
    /// programs, by kind).
    known: [usize; KNOWN.len()],
    failures: Vec<String>,
}

impl Default for Tally {
    fn default() -> Self {
        Self {
            compared: 0,
            known: [0; KNOWN.len()],
            failures: Vec::new(),
        }
    }
}

/// The entry of [`KNOWN`] for `file` (a file's own before `*`) whose kind
/// passes `f`.
fn entry(file: &str, f: impl Fn(&Known) -> bool) -> Option<usize> {
    let own = KNOWN.iter().position(|k| k.file == file && f(k));
    own.or_else(|| KNOWN.iter().position(|k| k.file == "*" && f(k)))
}

/// The known difference of `file` at `line`, if any.
fn known(file: &str, line: usize, cycle_lines: &[usize]) -> Option<usize> {
    entry(file, |k| match k.kind {
        Kind::CycleFeedsOnly => cycle_lines.contains(&line),
        Kind::NotCompared => k.lines.contains(&line),
        Kind::WorkFrame | Kind::Refused(_) | Kind::Rs274Stops(_) => false,
    })
}

/// Source lines of blocks in canned-cycle mode (mtmotion's modal state
/// after the block has a cycle): their holes are the cycle's.
fn cycle_lines(text: &str) -> Vec<usize> {
    let p = match parse_all(text, &ParseOptions::default()) {
        Ok(p) => p,
        Err(_) => return Vec::new(),
    };
    // The modal state after each block.
    let mut lines: Vec<usize> = p
        .blocks
        .iter()
        .zip(&p.modal)
        .filter(|(_, m)| m.cycle.is_some())
        .map(|(b, _)| b.line)
        .collect();
    lines.dedup();
    lines
}

fn compare(file: &str, text: &str, rs274: &Path, work: &Path, t: &mut Tally) {
    let phrase = |i: usize| match KNOWN[i].kind {
        Kind::Refused(p) | Kind::Rs274Stops(p) => p,
        _ => "",
    };
    // A stop listed for this file must happen; one listed for every
    // file ("*") may.
    let stops = entry(file, |k| matches!(k.kind, Kind::Rs274Stops(_)));
    let must_stop = stops.filter(|&i| KNOWN[i].file == file);
    let refused = entry(file, |k| matches!(k.kind, Kind::Refused(_)));
    let ours = mtmotion_moves(text);
    if let Some(i) = refused {
        let phrase = phrase(i);
        match ours {
            Err(e) if e.contains(phrase) => t.known[i] += 1,
            Err(e) => t.failures.push(format!("{file}: refused with '{e}', listed as '{phrase}'")),
            Ok(_) => t.failures.push(format!(
                "{file}: listed as refused ('{phrase}') but parses now: compare it (take it off KNOWN)"
            )),
        }
        return;
    }
    let ours = match ours {
        Ok(m) => m,
        Err(e) => {
            t.failures.push(format!("{file}: mtmotion refuses it: {e}"));
            return;
        }
    };
    let work_frame = entry(file, |k| k.kind == Kind::WorkFrame);
    let (theirs, stopped, shifted) = rs274_moves(rs274, text, work, work_frame.is_none());
    if let Some(i) = work_frame {
        t.known[i] += shifted;
    }
    match (stopped.as_deref(), stops) {
        (Some(s), Some(i)) if s.contains(phrase(i)) => t.known[i] += 1,
        (Some(s), _) => t.failures.push(format!("{file}: rs274 stopped: {s}")),
        (None, _) => {
            if let Some(i) = must_stop {
                t.failures.push(format!(
                    "{file}: listed as stopping rs274 ('{}') but it does not",
                    phrase(i)
                ));
            }
        }
    }
    let cycles = cycle_lines(text);
    let jumps: Vec<usize> = theirs.iter().filter(|m| m.jump).map(|m| m.line).collect();
    let not_compared =
        |m: &Move| known(file, m.line, &cycles).filter(|&i| KNOWN[i].kind == Kind::NotCompared);
    let left_out = |m: &Move| jumps.contains(&m.line) || not_compared(m).is_some();
    for m in &theirs {
        match (not_compared(m), work_frame) {
            (Some(i), _) => t.known[i] += 1,
            (None, Some(i)) if jumps.contains(&m.line) => t.known[i] += 1,
            _ => {}
        }
    }
    let ours = moving(
        ours.into_iter().filter(|m| !left_out(m)).collect(),
        [0.0; 6],
    );
    let theirs = moving(
        theirs.into_iter().filter(|m| !left_out(m)).collect(),
        [0.0; 6],
    );
    let (a, b) = (runs(&ours), runs(&theirs));
    for (k, rb) in b.iter().enumerate() {
        let Some(ra) = a.get(k) else {
            t.failures.push(format!(
                "{file}:{}: rs274 moves, mtmotion has no more: {}",
                rb[0].line, rb[0]
            ));
            return;
        };
        let line = ra[0].line;
        if line != rb[0].line {
            t.failures.push(format!(
                "{file}:{line}: mtmotion {} but rs274 at line {}: {}",
                ra[0], rb[0].line, rb[0]
            ));
            return;
        }
        if rb[0].kind == Kinded::SplinePoint {
            let start = k
                .checked_sub(1)
                .map_or([0.0; 6], |j| a[j][a[j].len() - 1].end);
            if let Some(why) = spline_agrees(ra, rb, start) {
                t.failures.push(format!("{file}:{line}: spline: {why}"));
                return;
            }
            t.compared += rb.len();
            continue;
        }
        let cycle = known(file, line, &cycles).filter(|&i| KNOWN[i].kind == Kind::CycleFeedsOnly);
        let (xa, xb): (Vec<Move>, Vec<Move>) = match cycle {
            Some(i) => {
                let feeds = |r: &[Move]| -> Vec<Move> {
                    r.iter()
                        .filter(|m| m.kind == Kinded::Feed)
                        .copied()
                        .collect()
                };
                if ra.len() != rb.len() || ra.iter().zip(rb.iter()).any(|(x, y)| !same(x, y)) {
                    t.known[i] += 1;
                }
                (feeds(ra), feeds(rb))
            }
            None => (ra.to_vec(), rb.to_vec()),
        };
        if xa.len() != xb.len() {
            t.failures.push(format!(
                "{file}:{line}: mtmotion makes {} moves, rs274 {}: mtmotion {}, rs274 {}",
                xa.len(),
                xb.len(),
                xa.first().map_or("none".into(), |m| m.to_string()),
                xb.first().map_or("none".into(), |m| m.to_string())
            ));
            return;
        }
        for (x, y) in xa.iter().zip(&xb) {
            t.compared += 1;
            if !same(x, y) {
                t.failures
                    .push(format!("{file}:{line}: mtmotion {x}\n    rs274    {y}"));
                return;
            }
        }
    }
    if a.len() > b.len() && stopped.is_none() {
        let m = a[b.len()][0];
        t.failures.push(format!(
            "{file}:{}: mtmotion moves, rs274 has no more: {m}",
            m.line
        ));
    }
}

/// rs274: `$RS274`, else `/usr/bin/rs274`.
fn rs274() -> Option<PathBuf> {
    let p = std::env::var_os("RS274")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from("/usr/bin/rs274"));
    p.is_file().then_some(p)
}

/// Team-written programs under `tests/` (`.ngc`, `.nc`), by path.
fn team_programs() -> Vec<PathBuf> {
    fn walk(d: &Path, out: &mut Vec<PathBuf>) {
        for e in std::fs::read_dir(d).into_iter().flatten().flatten() {
            let p = e.path();
            if p.is_dir() {
                walk(&p, out);
            } else if matches!(
                p.extension()
                    .and_then(|x| x.to_str())
                    .map(str::to_ascii_lowercase)
                    .as_deref(),
                Some("ngc" | "nc")
            ) {
                out.push(p);
            }
        }
    }
    let mut out = Vec::new();
    walk(
        Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/tests")),
        &mut out,
    );
    out.sort();
    out
}

#[test]
fn every_linuxcnc_and_generic_program_moves_as_rs274_says() {
    let Some(rs274) = rs274() else {
        corpus::say(
            "skipped every_linuxcnc_and_generic_program_moves_as_rs274_says: no LinuxCNC \
             rs274 at /usr/bin/rs274 or $RS274 (./scripts/bootstrap installs linuxcnc-uspace)",
        );
        return;
    };
    let work = std::env::temp_dir().join(format!("mtmotion-rs274-{}", std::process::id()));
    let mut programs: Vec<(String, String)> = vec![
        (
            "example arcs".into(),
            mtmotion::toolpath::example::arc_example(),
        ),
        (
            "example lines".into(),
            mtmotion::toolpath::example::line_example(),
        ),
    ];
    for p in team_programs() {
        let name = p
            .strip_prefix(env!("CARGO_MANIFEST_DIR"))
            .unwrap()
            .display()
            .to_string();
        programs.push((name, std::fs::read_to_string(&p).unwrap()));
    }
    let team = programs.len();
    if let Some(dir) = corpus::available(
        "the corpus part of every_linuxcnc_and_generic_program_moves_as_rs274_says",
    ) {
        for name in corpus::names(&dir) {
            if OTHER_DIALECTS.iter().any(|(n, _)| *n == name) {
                continue;
            }
            let text = corpus::read(&name);
            programs.push((name, text));
        }
        assert!(programs.len() - team >= 29, "{}", programs.len() - team);
    }
    let mut t = Tally::default();
    for (name, text) in &programs {
        let before = (t.compared, t.failures.len());
        compare(name, text, &rs274, &work, &mut t);
        // Shown when the test fails (the harness captures it otherwise).
        eprintln!(
            "rs274 oracle: {name}: {} moves compared equal{}",
            t.compared - before.0,
            if t.failures.len() > before.1 {
                ", DIFFERENT"
            } else {
                ""
            }
        );
    }
    let _ = std::fs::remove_dir_all(&work);
    corpus::say(&format!(
        "rs274 oracle: {} programs, {} moves compared equal, {} differences unexplained; KNOWN applied:",
        programs.len(),
        t.compared,
        t.failures.len()
    ));
    for (k, n) in KNOWN.iter().zip(t.known) {
        if n > 0 {
            let what = match k.kind {
                Kind::CycleFeedsOnly => "canned-cycle runs whose rapids differ",
                Kind::NotCompared => "rs274 moves left out",
                Kind::WorkFrame => "rs274 moves under a G5x offset",
                Kind::Refused(_) => "program refused by mtmotion",
                Kind::Rs274Stops(_) => "program stopped by rs274",
            };
            corpus::say(&format!("  {n:>5} {what}: {} ({})", k.file, k.why));
        }
    }
    assert!(t.failures.is_empty(), "{}", t.failures.join("\n"));
}

#[test]
fn the_numbered_copy_keeps_every_block_and_numbers_it_by_line() {
    let src = "%\r\nG21 (mm)\r\nN120 G1 X1 F100\r\n/ G0 X0\r\no100 sub\r\n\r\n  n5g1x2\r\nM2\r\n";
    assert_eq!(
        numbered(src),
        "%\nN2 G21 (mm)\nN3 G1 X1 F100\n/N4 G0 X0\no100 sub\n\nN7 g1x2\nN8 M2\n\n"
    );
    assert_eq!(
        canon("   12 N34    STRAIGHT_FEED(1.0000, 2.0000)"),
        Some((34, "STRAIGHT_FEED", "1.0000, 2.0000"))
    );
    assert_eq!(
        canon("    8 N..... STRAIGHT_TRAVERSE(1.0000)"),
        Some((0, "STRAIGHT_TRAVERSE", "1.0000"))
    );
    assert_eq!(canon("executing"), None);
}
