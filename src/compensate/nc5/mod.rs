//! 5-axis NC compensation by inverting the HTM geometric-error model
//! (thasana-htm-nc-compensation §II-D, Figs. 6–13).
//!
//! Pipeline of [`compensate_nc5`]:
//! 1. the program is read by [`crate::nc::program`] (G90/G91, G20/G21,
//!    G0/G1 with X Y Z and A B C in degrees); every motion block's end point
//!    is an evaluation point;
//! 2. the nominal pose is the error-free forward kinematics of the command;
//! 3. the actual pose is the forward kinematics with the errors
//!    (`errors`, plus one seeded Monte-Carlo machine if asked,
//!    [`monte_carlo`]) and the tool deflection `E_ST` from the cutting force
//!    ([`cutting_force`], Eqs. 4–7, cantilever with E = 200 GPa);
//! 4. corrected axis commands come from Newton iteration on the full model
//!    ([`crate::kinematics::newton`]) so that the actual pose is the nominal
//!    one; the corrected program is written back (4 decimals);
//! 5. before/after statistics of the errors at the evaluation points: mean
//!    and standard deviation of the position errors X, Y, Z (mm) and of the
//!    angle errors A, B (rad, the rotation of the tool axis about X and Y),
//!    as in thasana Figs. 10–13, and the reduction of each standard
//!    deviation. The paper's "total" 80.73 % is the mean of its X, Y, A, B
//!    reductions (76.83, 95, 82.40, 68.72 %); `totalReductionPercent` is
//!    computed the same way.
//!
//! Readings chosen: `E_ST` is the deflection of the tool tip perpendicular
//! to the tool axis, the mean cutting force over a revolution in the feed
//! frame (x along the feed projected normal to the tool axis, y = k × x);
//! it is the same before and after compensation (the feed direction barely
//! changes). The "after" errors are evaluated on the program as written, so
//! the 4-decimal rounding is included. An optional per-point repeatability
//! (`monteCarlo.repeatabilityMm`) is unknown to the compensation and stays
//! in both. Arcs (G2/G3) are rejected: their end points could be corrected
//! but not the path between.
//!
//! Units: mm, rad in results; the program in mm (or inch) and degrees.

pub mod cutting_force;
pub mod feed_drive;
pub mod monte_carlo;
pub mod s_shape;

use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

use crate::kinematics::{
    newton, q_from_degrees, q_to_degrees, GeometricErrors, KinematicsError, Model, AXES,
};
use crate::machine::MachineRef;
use crate::nc::program::{parse, Motion, Pose as NcPose, Program, Segment};
use crate::nc::NcError;
use cutting_force::Cutting;
use monte_carlo::{MonteCarlo, Rng};

/// Errors of the 5-axis compensation.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Nc5Error {
    /// The program could not be read.
    #[error("NC program: {0}")]
    Nc(#[from] NcError),
    /// Model errors.
    #[error("{0}")]
    Kinematics(#[from] KinematicsError),
    /// Machine errors.
    #[error(transparent)]
    Machine(#[from] crate::machine::MachineError),
    /// The corrected program must be written flat (macro code, a
    /// subprogram, a cycle) and that would lose a word
    /// ([`crate::nc::writer::write_checked`]).
    #[error("NC program: the corrected program is written flat (one block per move), and {0}")]
    Flat(String),
    /// Something the compensation does not handle.
    #[error("NC program: line {line}: {why}")]
    Unsupported {
        /// 1-based line.
        line: usize,
        /// Why.
        why: String,
    },
    /// The feed-drive parameters are out of range.
    #[error("compensateNc5: feedDrive: {0}")]
    FeedDrive(#[from] crate::servo::ServoError),
    /// An axis in `compensateAxes` the machine does not have.
    #[error("compensateNc5: `compensateAxes[{index}]` = '{axis}': expected one of the machine's axes {known}")]
    BadAxis {
        /// Position in the list.
        index: usize,
        /// The letter given.
        axis: String,
        /// The machine's axes.
        known: String,
    },
    /// A rotary-axis word the machine does not have (e.g. B on an A–C
    /// machine): the program was written for another machine.
    #[error("NC program: line {line}, column {column}: '{letter}' word, but this machine's axes are {axes}: choose the machine the program was written for")]
    AxisWord {
        /// 1-based line.
        line: usize,
        /// 1-based column of the word.
        column: usize,
        /// The axis letter.
        letter: char,
        /// The machine's axes, e.g. "X, Y, Z, A, C".
        axes: String,
    },
    /// The program is over the compensation's work budget
    /// ([`crate::budget::MAX_NC5_LINES`], [`crate::budget::MAX_NC5_MOVES`]).
    #[error("compensateNc5: {0}")]
    Budget(#[from] crate::budget::BudgetError),
    /// A configuration value is out of range.
    #[error("compensateNc5: `{field}` = {}: {why}", crate::numeric::compact(*.value))]
    BadConfig {
        /// Field.
        field: &'static str,
        /// Value.
        value: f64,
        /// Why.
        why: &'static str,
    },
}

/// Options of [`compensate_nc5`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase", deny_unknown_fields)]
pub struct Nc5Config {
    /// Machine (preset name or description).
    pub machine: MachineRef,
    /// Known geometric errors (mm, rad).
    #[serde(default)]
    pub errors: GeometricErrors,
    /// Tool length, mm.
    #[serde(default)]
    pub tool_length: f64,
    /// Add one seeded random machine to `errors`.
    #[serde(default)]
    pub monte_carlo: Option<MonteCarlo>,
    /// Include the cutting-force deflection `E_ST`.
    #[serde(default)]
    pub cutting: Option<Cutting>,
    /// The axes the compensation may move (lower-case letters); default
    /// all of the machine's axes. thasana §II-D corrects only X, Y, A and
    /// B: `["x", "y", "a", "b"]` (Z and C are then left as programmed and
    /// the pose is met in the least-squares sense).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub compensate_axes: Option<Vec<String>>,
    /// thasana Eq. 9 / Fig. 8 PID feed drives on every axis: the errors
    /// (before and after) are read where the drives are at the end of each
    /// block's command ([`feed_drive`]). The compensation itself inverts
    /// the geometric model only.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub feed_drive: Option<crate::servo::pid::PidDrive>,
}

impl Nc5Config {
    /// The plainest configuration for `machine`: no known errors, a tool
    /// length of 0, no Monte-Carlo machine, no cutting force, every axis
    /// compensated, ideal feed drives.
    ///
    /// # Examples
    /// ```
    /// use mtmotion::compensate::nc5::{compensate_nc5, Nc5Config};
    /// use mtmotion::machine::MachineRef;
    /// let cfg = Nc5Config::new(MachineRef::Name("trunnion-ac".into()));
    /// let r = compensate_nc5("G90\nG1 X10 Y5 Z3 A10 C20 F500\n", &cfg).unwrap();
    /// assert!(r.before.std_mm.iter().all(|s| s.abs() < 1e-12)); // no errors, nothing to correct
    /// ```
    pub fn new(machine: MachineRef) -> Self {
        Self {
            machine,
            errors: GeometricErrors::default(),
            tool_length: 0.0,
            monte_carlo: None,
            cutting: None,
            compensate_axes: None,
            feed_drive: None,
        }
    }
}

/// Mean and standard deviation of the errors at the evaluation points.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct Stats {
    /// Means `[x, y, z]`, mm.
    pub mean_mm: [f64; 3],
    /// Standard deviations `[x, y, z]`, mm.
    pub std_mm: [f64; 3],
    /// Means `[a, b]`, rad.
    pub mean_rad: [f64; 2],
    /// Standard deviations `[a, b]`, rad.
    pub std_rad: [f64; 2],
}

/// Per-point errors.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct PointErrors {
    /// Position errors x, y, z (mm) and angle errors a, b (rad), per point.
    pub x: Vec<f64>,
    /// y, mm.
    pub y: Vec<f64>,
    /// z, mm.
    pub z: Vec<f64>,
    /// about X, rad.
    pub a: Vec<f64>,
    /// about Y, rad.
    pub b: Vec<f64>,
}

/// The result.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct Nc5Result {
    /// Corrected program.
    pub nc: String,
    /// Statistics before compensation.
    pub before: Stats,
    /// Statistics after compensation.
    pub after: Stats,
    /// Per-point errors before.
    pub before_points: PointErrors,
    /// Per-point errors after.
    pub after_points: PointErrors,
    /// Source line of each evaluation point.
    pub lines: Vec<usize>,
    /// Reduction of the std of X, Y, Z, A, B, %.
    pub reduction_percent: [f64; 5],
    /// Mean of the X, Y, A, B reductions (the paper's "total"), %.
    pub total_reduction_percent: f64,
    /// Tool deflection used as `E_ST` (mm, perpendicular to the tool).
    pub deflection_mm: f64,
    /// The errors of the simulated machine (after the Monte-Carlo draw).
    pub machine_errors: GeometricErrors,
}

fn stats(p: &PointErrors) -> Stats {
    let ms = |v: &[f64]| {
        let n = v.len().max(1) as f64;
        let m = v.iter().sum::<f64>() / n;
        let s = (v.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (n - 1.0).max(1.0)).sqrt();
        (m, s)
    };
    let (mx, sx) = ms(&p.x);
    let (my, sy) = ms(&p.y);
    let (mz, sz) = ms(&p.z);
    let (ma, sa) = ms(&p.a);
    let (mb, sb) = ms(&p.b);
    Stats {
        mean_mm: [mx, my, mz],
        std_mm: [sx, sy, sz],
        mean_rad: [ma, mb],
        std_rad: [sa, sb],
    }
}

struct Eval {
    model: Model,
    nominal: Model,
    deflection: [f64; 2],
    noise: Vec<Vector3<f64>>,
}

impl Eval {
    fn defl(&self, k: &Vector3<f64>, feed_dir: &Vector3<f64>) -> Vector3<f64> {
        let f = feed_dir - k * k.dot(feed_dir);
        if f.norm() < 1e-12 || self.deflection == [0.0; 2] {
            return Vector3::zeros();
        }
        let f = f.normalize();
        f * self.deflection[0] + k.cross(&f) * self.deflection[1]
    }
    fn push(
        &self,
        out: &mut PointErrors,
        i: usize,
        q: &[f64; 6],
        qn: &[f64; 6],
        feed_dir: &Vector3<f64>,
    ) {
        let (pn, kn) = self.nominal.eval(qn);
        let (pa, ka) = self.model.eval(q);
        let d = pa
            + self.defl(&ka, feed_dir)
            + self.noise.get(i).copied().unwrap_or_else(Vector3::zeros)
            - pn;
        let w = kn.cross(&ka);
        out.x.push(d.x);
        out.y.push(d.y);
        out.z.push(d.z);
        out.a.push(w.x);
        out.b.push(w.y);
    }
}

/// An evaluation point: source line, joint values (mm, rad), move direction.
type EvalPoint = (usize, [f64; 6], Vector3<f64>);

/// Refuses a rotary-axis word (A, B, C) the machine has no axis for, at
/// its line and column: its value would be dropped from the model yet
/// written back into the corrected program.
fn check_axis_words(blocks: &[crate::nc::Block], axes: &[&str]) -> Result<(), Nc5Error> {
    for b in blocks.iter().filter(|b| !b.block_delete) {
        for w in &b.words {
            let name = w.letter.to_ascii_lowercase().to_string();
            if "ABC".contains(w.letter) && !axes.contains(&name.as_str()) {
                return Err(Nc5Error::AxisWord {
                    line: b.line,
                    column: w.column,
                    letter: w.letter,
                    axes: axes
                        .iter()
                        .map(|a| a.to_ascii_uppercase())
                        .collect::<Vec<_>>()
                        .join(", "),
                });
            }
        }
    }
    Ok(())
}

fn points_of(segments: &[Segment]) -> Result<Vec<EvalPoint>, Nc5Error> {
    let mut out = Vec::new();
    for s in segments {
        match s.motion {
            Motion::Rapid | Motion::Linear => {
                let d = Vector3::new(s.end.x - s.start.x, s.end.y - s.start.y, s.end.z - s.start.z);
                out.push((s.line, q_from_degrees(&s.end.to_array()), d));
            }
            Motion::Arc(_) => {
                return Err(Nc5Error::Unsupported { line: s.line, why: "arcs (G2/G3) are not supported by the 5-axis compensation; post the program as G1 moves".into() })
            }
            Motion::Dwell { .. } => {}
        }
    }
    Ok(out)
}

/// Compensates a 5-axis program for the machine's geometric errors.
///
/// # Units
/// Program in mm (or inch, G20) and degrees; `toolLength` mm; errors mm, rad.
///
/// # Examples
/// ```
/// use mtmotion::compensate::nc5::{compensate_nc5, Nc5Config};
/// use mtmotion::kinematics::GeometricErrors;
/// use mtmotion::machine::MachineRef;
/// let mut errors = GeometricErrors::default();
/// errors.location.insert("EY0A".into(), 0.03);
/// errors.location.insert("EB0C".into(), 2e-4);
/// let cfg = Nc5Config { machine: MachineRef::Name("trunnion-ac".into()), errors,
///     tool_length: 50.0, monte_carlo: None, cutting: None, compensate_axes: None,
///     feed_drive: None };
/// let nc = "G90 G21\nG0 X10 Y0 Z5 A10 C0\nG1 X20 Y5 Z5 A20 C30 F500\nG1 X30 Y-5 Z0 A30 C90\n";
/// let r = compensate_nc5(nc, &cfg).unwrap();
/// assert_eq!(r.lines, vec![2, 3, 4]);
/// assert!(r.before.std_mm[1] > 1e-3 && r.after.std_mm[1] < 1e-4); // 4-decimal output
/// ```
pub fn compensate_nc5(text: &str, cfg: &Nc5Config) -> Result<Nc5Result, Nc5Error> {
    let (_, chain) = cfg.machine.resolve()?;
    if !cfg.tool_length.is_finite() {
        return Err(Nc5Error::BadConfig {
            field: "toolLength",
            value: cfg.tool_length,
            why: "must be a finite length in mm",
        });
    }
    crate::budget::check(
        "program",
        crate::budget::lines(text) as u64,
        crate::budget::MAX_NC5_LINES,
        "lines",
        "compensate the program in parts",
    )?;
    let program = parse(text)?;
    // every move is solved, written out (cycles and subprogram calls
    // expanded) and read back: refused before that work (a 99,992-line G81
    // program was refused after 4 s as "line 1, column 1: program: 399963
    // lines", its own expansion; 200,000 moves took 10.3 s and 481 MiB)
    crate::budget::check(
        "program",
        program.segments.len() as u64,
        crate::budget::MAX_NC5_MOVES,
        "moves (canned cycles and subprogram calls expanded)",
        "compensate the program in parts",
    )?;
    check_axis_words(&program.blocks, &chain.axes())?;
    let pts = points_of(&program.segments)?;
    if pts.is_empty() {
        return Err(Nc5Error::Unsupported {
            line: 1,
            why: "the program has no G0/G1 move to compensate".into(),
        });
    }
    let (errors, noise) = machine_errors(cfg, &chain, pts.len())?;
    let deflection = deflection_of(cfg)?;
    let eval = Eval {
        model: Model::new(&chain, &errors, cfg.tool_length)?,
        nominal: Model::new(&chain, &GeometricErrors::default(), cfg.tool_length)?,
        deflection,
        noise,
    };
    let axes = compensated_axes(cfg, &chain)?;
    let driven = match &cfg.feed_drive {
        Some(d) => Some(feed_drive::positions_at_block_ends(&program.segments, d)?),
        None => None,
    };
    let mut before = PointErrors::default();
    let mut corrected = Vec::with_capacity(pts.len());
    for (i, (line, q, dir)) in pts.iter().enumerate() {
        let actual = driven.as_ref().map_or(q, |d| &d[i]);
        eval.push(&mut before, i, actual, q, dir);
        let (pn, kn) = eval.nominal.eval(q);
        // Target: the tool tip must land on the nominal point after deflection.
        let target = crate::kinematics::Pose {
            position: (pn - eval.defl(&kn, dir)).into(),
            orientation: kn.into(),
        };
        let context = format!("line {line}");
        let qc = if cfg.compensate_axes.is_some() {
            newton::solve_least_squares(&eval.model, &target, q, &axes, &context)?
        } else {
            newton::solve(&eval.model, &target, q, &axes, &context)?
        };
        corrected.push(qc);
    }
    let nc = write_corrected(&program, &corrected, &axes)?;
    let after = evaluate_written(&nc, cfg, &eval, &pts)?;
    let (b, a) = (stats(&before), stats(&after));
    let red = |x: f64, y: f64| if x > 0.0 { 100.0 * (1.0 - y / x) } else { 0.0 };
    let reduction = [
        red(b.std_mm[0], a.std_mm[0]),
        red(b.std_mm[1], a.std_mm[1]),
        red(b.std_mm[2], a.std_mm[2]),
        red(b.std_rad[0], a.std_rad[0]),
        red(b.std_rad[1], a.std_rad[1]),
    ];
    Ok(Nc5Result {
        nc,
        before: b,
        after: a,
        before_points: before,
        after_points: after,
        lines: pts.iter().map(|p| p.0).collect(),
        reduction_percent: reduction,
        total_reduction_percent: (reduction[0] + reduction[1] + reduction[3] + reduction[4]) / 4.0,
        deflection_mm: deflection[0].hypot(deflection[1]),
        machine_errors: errors,
    })
}

/// The machine's errors: the configured ones, plus one seeded Monte-Carlo
/// machine and per-point repeatability noise (mm) when asked for.
fn machine_errors(
    cfg: &Nc5Config,
    chain: &crate::kinematics::Chain,
    points: usize,
) -> Result<(GeometricErrors, Vec<Vector3<f64>>), Nc5Error> {
    let Some(mc) = &cfg.monte_carlo else {
        return Ok((cfg.errors.clone(), Vec::new()));
    };
    for (f, v) in [
        ("monteCarlo.sigmaMm", mc.sigma_mm),
        ("monteCarlo.sigmaRad", mc.sigma_rad),
        ("monteCarlo.repeatabilityMm", mc.repeatability_mm),
    ] {
        if !(v.is_finite() && v >= 0.0) {
            return Err(Nc5Error::BadConfig {
                field: f,
                value: v,
                why: "must be ≥ 0",
            });
        }
    }
    let mut rng = Rng::new(mc.seed);
    let errors = monte_carlo::draw(chain, &cfg.errors, mc, &mut rng);
    let mut noise = Vec::new();
    if mc.repeatability_mm > 0.0 {
        noise = (0..points)
            .map(|_| Vector3::new(rng.normal(), rng.normal(), rng.normal()) * mc.repeatability_mm)
            .collect();
    }
    Ok((errors, noise))
}

/// The tool-tip deflection (mm) of the mean lateral cutting force, in the
/// feed frame; zero without a cutting model.
fn deflection_of(cfg: &Nc5Config) -> Result<[f64; 2], Nc5Error> {
    match &cfg.cutting {
        Some(c) => {
            c.validate()
                .map_err(|(field, value, why)| Nc5Error::BadConfig { field, value, why })?;
            let f = c.forces(720);
            // Mean lateral force in the feed frame → tip deflection.
            Ok([c.deflection(f.mean[0]), c.deflection(f.mean[1])])
        }
        None => Ok([0.0; 2]),
    }
}

/// The axes the compensation may move: the chosen ones, or all of the machine's.
fn compensated_axes(
    cfg: &Nc5Config,
    chain: &crate::kinematics::Chain,
) -> Result<Vec<usize>, Nc5Error> {
    let axes: Vec<usize> = (0..6)
        .filter(|i| chain.axes().contains(&AXES[*i]))
        .collect();
    let Some(only) = &cfg.compensate_axes else {
        return Ok(axes);
    };
    let mut chosen = Vec::with_capacity(only.len());
    for (index, a) in only.iter().enumerate() {
        match axes.iter().find(|&&i| AXES[i] == a.as_str()) {
            Some(&i) => chosen.push(i),
            None => {
                return Err(Nc5Error::BadAxis {
                    index,
                    axis: a.clone(),
                    known: axes.iter().map(|&i| AXES[i]).collect::<Vec<_>>().join(", "),
                })
            }
        }
    }
    Ok(chosen)
}

/// The program with each G0/G1 end point replaced by its corrected axis
/// values (axes not compensated keep their programmed value).
fn write_corrected(
    program: &Program,
    corrected: &[[f64; 6]],
    axes: &[usize],
) -> Result<String, Nc5Error> {
    let mut segs = program.segments.clone();
    let mut k = 0;
    let mut last: Option<NcPose> = None;
    for s in segs.iter_mut() {
        if let Some(p) = last {
            s.start = p;
        }
        if matches!(s.motion, Motion::Rapid | Motion::Linear) {
            if let Some(qc) = corrected.get(k) {
                let mut d = q_to_degrees(qc);
                for (i, v) in d.iter_mut().enumerate() {
                    if !axes.contains(&i) {
                        *v = s.end.get(i);
                    }
                }
                s.end = NcPose::from_array(d);
            }
            k += 1;
        } else {
            s.end = s.start;
        }
        last = Some(s.end);
    }
    crate::nc::writer::write_checked(program, &segs).map_err(Nc5Error::Flat)
}

/// The errors of the program as written (read back, so its rounding
/// counts), at the original program's evaluation points.
fn evaluate_written(
    nc: &str,
    cfg: &Nc5Config,
    eval: &Eval,
    pts: &[EvalPoint],
) -> Result<PointErrors, Nc5Error> {
    let written = parse(nc)?;
    let wpts = points_of(&written.segments)?;
    let driven_after = match &cfg.feed_drive {
        Some(d) => Some(feed_drive::positions_at_block_ends(&written.segments, d)?),
        None => None,
    };
    let mut after = PointErrors::default();
    for (i, ((_, qw, _), (_, qn, dir))) in wpts.iter().zip(pts).enumerate() {
        let actual = driven_after.as_ref().map_or(qw, |d| &d[i]);
        eval.push(&mut after, i, actual, qn, dir);
    }
    Ok(after)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn axis_words_the_machine_lacks_are_refused_at_their_column() {
        let cfg = Nc5Config {
            machine: MachineRef::Name("trunnion-ac".into()),
            errors: GeometricErrors::default(),
            tool_length: 50.0,
            monte_carlo: None,
            cutting: None,
            compensate_axes: None,
            feed_drive: None,
        };
        let nc = "G90 G21\nG0 X10 Y0 Z5 A10 C0\nG1 X20 Y5 Z5 B20 F500\n";
        let e = compensate_nc5(nc, &cfg).unwrap_err().to_string();
        assert!(
            e.starts_with("NC program: line 3, column 14: 'B' word"),
            "{e}"
        );
        assert!(e.contains("X, Y, Z, A, C"), "{e}");
    }
}
