//! Reverse compensation of the NC program (qiu §4-3(2)).
//!
//! The paper's method, for arc programs: simulate the program (§4-2), take
//! each arc's mean radius loss `Δrᵢ` over the samples nearest to it, give
//! the arc the radius `Rᵢ + |Δrᵢ|` about the same centre, recompute the
//! joints between segments ([`geometry`]), and write the new program. Where
//! short segments cluster the servo's delay limits the effect, so the paper
//! adds 0.1 s dwells at B and D and compensates again: 63.1 µm → 18.2 µm,
//! motion time 11.018 s → 11.445 s.
//!
//! Readings and extensions:
//! - the loss is signed (`Rᵢ − ρ`, positive inside) rather than its
//!   absolute value, so an arc that overshoots is pulled in, not pushed out;
//! - *iteration*: the compensated program is simulated against the
//!   **original** path and the radii are corrected again by the remaining
//!   mean loss; this repeats while the maximum error keeps falling (at most
//!   `iterations` times), and the best program is kept;
//! - *lines*: for line–line joints (programs made only of lines) the
//!   equivalent move is a vertex shift: the mean signed normal deviation of
//!   the samples in the half-segments on either side of the vertex, moved
//!   against along the bisector (scaled by `1/cos(φ/2)` as for an offset
//!   polyline), iterated the same way;
//! - *dwells*: candidates are the joints where a run of at least three short
//!   cutting segments (nominal duration `< max(2·tA, 4·T)`) meets a longer
//!   one — the paper's B and D. With `dwell` unset, 0.1 s dwells are tried
//!   at all candidates, then each is removed again if the error does not
//!   rise by more than 1 % without it; dwells are dropped altogether when
//!   they do not lower the error or when the motion time would grow by more
//!   than 5 %. `dwell: 0` disables them; a positive `dwell` sets their length;
//! - the output keeps every source block with its N number, comments and
//!   other words ([`crate::nc::writer`]); connecting lines and dwells are new
//!   blocks without N numbers. "After" is measured by parsing that text and
//!   simulating it against the original path.
//!
//! Units: mm, s; errors reported in µm where the field says so.

pub mod geometry;

use serde::{Deserialize, Serialize};

use crate::nc::program::{dist, parse, Motion, Program, Segment};
use crate::nc::writer::write;
use crate::toolpath::{simulate, SimConfig, Simulation, ToolpathError};
use geometry::{rebuild, Edit};

/// Settings of the reverse compensation.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct ReverseConfig {
    /// The model (tA, T, dt, …).
    #[serde(flatten)]
    pub sim: SimConfig,
    /// Dwell length at cluster joints, s: unset = automatic 0.1 s, 0 = none.
    pub dwell: Option<f64>,
    /// Most correction rounds after the first.
    pub iterations: usize,
}

impl Default for ReverseConfig {
    fn default() -> Self {
        Self {
            sim: SimConfig::default(),
            dwell: None,
            iterations: 6,
        }
    }
}

/// Maximum error and motion time of one program.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct Summary {
    /// Maximum contour error against the original path, µm.
    pub max_error_um: f64,
    /// Motion time, s.
    pub motion_time: f64,
}

/// What happened to one original segment.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct SegmentChange {
    /// Index into the original segments.
    pub segment: usize,
    /// Source line.
    pub line: usize,
    /// `"arc"`, `"line"`, `"rapid"` or `"dwell"`.
    pub kind: &'static str,
    /// Original radius (arcs), mm.
    pub radius_before: f64,
    /// New radius (arcs), mm.
    pub radius_after: f64,
    /// How far the segment's end point moved, µm.
    pub end_shift_um: f64,
}

/// A dwell the compensation inserted.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct DwellAt {
    /// After the block on this source line.
    pub after_line: usize,
    /// Length, s.
    pub seconds: f64,
}

/// The result of [`reverse_compensate`].
#[derive(Debug, Clone)]
pub struct Compensation {
    /// The corrected program.
    pub nc: String,
    /// The original program against its own path.
    pub before: Summary,
    /// The corrected program against the original path.
    pub after: Summary,
    /// Per original segment.
    pub segments: Vec<SegmentChange>,
    /// Inserted dwells.
    pub dwells: Vec<DwellAt>,
    /// Maximum error of each correction round of the kept run, µm.
    pub history_um: Vec<f64>,
    /// The simulation of the original program.
    pub sim_before: Simulation,
    /// The simulation of the corrected program against the original path.
    pub sim_after: Simulation,
}

struct Run {
    segments: Vec<Segment>,
    edit: Edit,
    error: f64,
    time: f64,
    history: Vec<f64>,
}

fn run(orig: &[Segment], cfg: &ReverseConfig, dwell_after: Vec<f64>) -> Result<Run, ToolpathError> {
    let n = orig.len();
    let mut edit = Edit {
        radius: orig
            .iter()
            .map(|s| {
                if let Motion::Arc(a) = s.motion {
                    a.radius
                } else {
                    0.0
                }
            })
            .collect(),
        vertex_shift: vec![[0.0; 3]; n],
        dwell_after,
    };
    let moves: Vec<usize> = (0..n)
        .filter(|&i| !matches!(orig[i].motion, Motion::Dwell { .. }))
        .collect();
    let mut best: Option<Run> = None;
    let mut history = Vec::new();
    let mut stall = 0;
    for round in 0..=cfg.iterations {
        let segs = rebuild(orig, &edit);
        let sim = simulate(&segs, orig, &cfg.sim)?;
        history.push(sim.max_error * 1e3);
        if best.as_ref().is_none_or(|b| sim.max_error < b.error) {
            best = Some(Run {
                segments: segs,
                edit: edit.clone(),
                error: sim.max_error,
                time: sim.motion_time,
                history: Vec::new(),
            });
            stall = 0;
        } else {
            stall += 1;
            if stall >= 2 {
                break;
            }
        }
        if round == cfg.iterations {
            break;
        }
        let mut by_seg = vec![None; n];
        for st in &sim.segments {
            if let Some(slot) = by_seg.get_mut(st.segment) {
                *slot = Some(st);
            }
        }
        for (i, s) in orig.iter().enumerate() {
            if let (Motion::Arc(_), Some(Some(st))) = (s.motion, by_seg.get(i)) {
                edit.radius[i] += st.mean_deviation.unwrap_or(0.0);
            }
        }
        for w in moves.windows(2) {
            let (i, k) = (w[0], w[1]);
            let (a, b) = (&orig[i], &orig[k]);
            if !(matches!(a.motion, Motion::Linear) && matches!(b.motion, Motion::Linear)) {
                continue;
            }
            let devs: Vec<f64> = [
                by_seg[i].and_then(|s| s.half_deviation[1]),
                by_seg[k].and_then(|s| s.half_deviation[0]),
            ]
            .into_iter()
            .flatten()
            .collect();
            if devs.is_empty() {
                continue;
            }
            let dev = devs.iter().sum::<f64>() / devs.len() as f64;
            let left = |s: &Segment| {
                let (dx, dy) = (s.end.x - s.start.x, s.end.y - s.start.y);
                let l = dx.hypot(dy);
                if l > 0.0 {
                    [-dy / l, dx / l]
                } else {
                    [0.0, 0.0]
                }
            };
            let (na, nb) = (left(a), left(b));
            let (bx, by) = (na[0] + nb[0], na[1] + nb[1]);
            let bl = bx.hypot(by);
            if bl < 1e-9 {
                continue;
            }
            let (bx, by) = (bx / bl, by / bl);
            let cos = (bx * na[0] + by * na[1]).max(0.2);
            edit.vertex_shift[i][0] -= dev * bx / cos;
            edit.vertex_shift[i][1] -= dev * by / cos;
        }
    }
    let mut best = best.ok_or(ToolpathError::Empty)?;
    best.history = history;
    Ok(best)
}

/// The joints after which a dwell may help: where a run of ≥ 3 short
/// cutting segments meets a longer one.
pub fn dwell_candidates(orig: &[Segment], sim: &SimConfig) -> Vec<usize> {
    let tmax = sim.t.per_axis().into_iter().fold(0.0, f64::max);
    let limit = (2.0 * sim.t_a).max(4.0 * tmax);
    let moves: Vec<usize> = (0..orig.len()).filter(|&i| orig[i].is_cutting()).collect();
    let short: Vec<bool> = moves
        .iter()
        .map(|&i| orig[i].length() / (orig[i].feed * sim.feed_override / 60.0) < limit)
        .collect();
    let mut out = Vec::new();
    let mut k = 0;
    while k < moves.len() {
        if !short[k] {
            k += 1;
            continue;
        }
        let a = k;
        while k < moves.len() && short[k] {
            k += 1;
        }
        if k - a >= 3 {
            if a > 0 {
                out.push(moves[a - 1]);
            }
            if k < moves.len() {
                out.push(moves[k - 1]);
            }
        }
    }
    out
}

/// Reverse-compensates `text` (qiu §4-3(2)); see the module header.
///
/// # Units
/// Config in s and mm/min; summaries in µm and s.
///
/// # Errors
/// NC errors naming line and column, invalid settings, an empty program.
///
/// # Examples
/// ```
/// use mtmotion::compensate::reverse::{reverse_compensate, ReverseConfig};
/// let nc = mtmotion::toolpath::example::arc_example();
/// let c = reverse_compensate(&nc, &ReverseConfig::default()).unwrap();
/// assert!(c.after.max_error_um < 0.4 * c.before.max_error_um);
/// assert!(c.nc.contains("N40 G3") && c.nc.contains("(C)"));
/// ```
pub fn reverse_compensate(text: &str, cfg: &ReverseConfig) -> Result<Compensation, ToolpathError> {
    cfg.sim.validate()?;
    if let Some(d) = cfg.dwell {
        if !(d.is_finite() && (0.0..=10.0).contains(&d)) {
            return Err(ToolpathError::Config {
                field: "dwell",
                message: "expected a dwell between 0 and 10 s".into(),
            });
        }
    }
    if cfg.iterations > 50 {
        return Err(ToolpathError::Config {
            field: "iterations",
            message: "expected at most 50 iterations".into(),
        });
    }
    let program = parse(text)?;
    let orig = &program.segments;
    let sim_before = simulate(orig, orig, &cfg.sim)?;
    let n = orig.len();
    let mut best = run(orig, cfg, vec![0.0; n])?;
    let dwell = cfg.dwell.unwrap_or(0.1);
    let cands = if dwell > 0.0 {
        dwell_candidates(orig, &cfg.sim)
    } else {
        Vec::new()
    };
    if !cands.is_empty() {
        let with = |set: &[usize]| {
            let mut d = vec![0.0; n];
            for &i in set {
                d[i] = dwell;
            }
            run(orig, cfg, d)
        };
        let mut set = cands.clone();
        let mut cur = with(&set)?;
        for c in cands {
            let trial_set: Vec<usize> = set.iter().copied().filter(|&x| x != c).collect();
            let trial = with(&trial_set)?;
            if trial.error <= cur.error * 1.01 {
                set = trial_set;
                cur = trial;
            }
        }
        if !set.is_empty() && cur.error < best.error && cur.time <= 1.05 * sim_before.motion_time {
            best = cur;
        }
    }
    let nc = write(&program, &best.segments);
    let written = parse(&nc)?;
    let sim_after = simulate(&written.segments, orig, &cfg.sim)?;
    Ok(Compensation {
        before: summary(&sim_before),
        after: summary(&sim_after),
        segments: changes(&program, &best),
        dwells: best
            .edit
            .dwell_after
            .iter()
            .enumerate()
            .filter(|(_, &d)| d > 0.0)
            .map(|(i, &d)| DwellAt {
                after_line: orig[i].line,
                seconds: d,
            })
            .collect(),
        history_um: best.history,
        nc,
        sim_before,
        sim_after,
    })
}

fn summary(s: &Simulation) -> Summary {
    Summary {
        max_error_um: s.max_error * 1e3,
        motion_time: s.motion_time,
    }
}

fn changes(p: &Program, best: &Run) -> Vec<SegmentChange> {
    p.segments
        .iter()
        .enumerate()
        .map(|(i, s)| {
            let new_end = best
                .segments
                .iter()
                .rev()
                .find(|x| x.block == s.block && s.block.is_some())
                .map_or(s.end, |x| x.end);
            let (kind, r) = match s.motion {
                Motion::Arc(a) => ("arc", a.radius),
                Motion::Linear => ("line", 0.0),
                Motion::Rapid => ("rapid", 0.0),
                Motion::Dwell { .. } => ("dwell", 0.0),
            };
            SegmentChange {
                segment: i,
                line: s.line,
                kind,
                radius_before: r,
                radius_after: if kind == "arc" {
                    best.edit.radius[i]
                } else {
                    0.0
                },
                end_shift_um: dist(s.end.p(), new_end.p()) * 1e3,
            }
        })
        .collect()
}
