//! Canned drilling cycles G73, G74, G76, G81–G86 and G89 expanded into the
//! moves the machine really makes, in the G17, G18 or G19 plane (drilling
//! along Z, Y or X). Fanuc rules (Fanuc Series 0i-MF/30i-B operator's
//! manuals, "canned cycles for drilling"); where LinuxCNC differs (its G98
//! returns to the *higher* of the initial level and R, it has no G74/G76),
//! Fanuc is followed:
//!
//! - A hole is drilled on the block that gives the cycle code and on every
//!   later block, until G80 or a G0–G3, that gives a plane-axis word, the
//!   drilling-axis word or R. Per hole: rapid to the hole position at the
//!   current level, rapid to the R level, the cycle's own moves, then the
//!   return: to the initial level under G98 (the drilling-axis position when
//!   the cycle mode began) and to R under G99.
//! - Under G90 the R and bottom words are absolute. Under G91, R is the
//!   distance from the initial level and the bottom the distance from R,
//!   and the hole position is incremental, so `K`/`L` repeats (K0: store
//!   the data, drill nothing) step from hole to hole.
//! - G81: feed to the bottom, rapid out. G82: the same with a dwell P at the
//!   bottom. G83 (peck): feed by Q, rapid back to R, rapid down to
//!   [`PECK_CLEARANCE`] above the last depth, feed on. G73 (high-speed
//!   peck): feed by Q, rapid back by [`PECK_CLEARANCE`], feed on. G84/G74
//!   (tapping, right-/left-hand): feed to the bottom, dwell P, feed back to
//!   R. G85: feed in, feed out to R. G89: as G85 with a dwell. G86: feed
//!   in, rapid out. G76 (fine boring): feed in, dwell, rapid out; the tool
//!   shift Q at the bottom (a machine parameter gives its direction) is not
//!   modelled and is warned about.
//! - G87 (back boring) and G88 (manual retract) are refused with a located
//!   error.
//! - P is read like a G4 P ([`super::program::DwellP`]); Q and the
//!   clearance are in the program's length unit (converted to mm).
//!
//! Every expanded segment is `fixed`: its end points are not words of one
//! block execution. Units: mm, s.

use serde::{Deserialize, Serialize};

use super::program::{Motion, Plane, Pose, Segment};

/// Retract/approach clearance of G73 and G83 pecks, mm (Fanuc parameters
/// 5114/5115; a common setting).
pub const PECK_CLEARANCE: f64 = 0.5;

/// Most pecks of one G73/G83 hole (a 1 m hole at 0.1 mm pecks): a larger
/// count is a typo in Q or the bottom level, and each peck is 2–3 segments.
pub const MAX_PECKS: usize = 10_000;

/// An active canned cycle (modal data).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct Cycle {
    /// The G code ×10 (810 for G81).
    pub code: i64,
    /// Initial level: drilling-axis position when the cycle mode began, mm.
    pub initial: f64,
    /// R level, absolute, mm (`None` until given).
    pub r: Option<f64>,
    /// Bottom, absolute, mm (`None` until given).
    pub bottom: Option<f64>,
    /// Peck depth Q, mm.
    pub q: f64,
    /// Dwell at the bottom, s.
    pub dwell: f64,
}

/// Segments of one hole at plane position (`pu`, `pv`) from `pos`.
///
/// `r`, `bottom`: levels (mm); `g99`: return to R; `feed`: mm/min.
#[allow(clippy::too_many_arguments)]
pub fn hole(
    c: &Cycle,
    plane: Plane,
    pos: Pose,
    pu: f64,
    pv: f64,
    r: f64,
    bottom: f64,
    g99: bool,
    feed: f64,
    block: usize,
    line: usize,
) -> Vec<Segment> {
    let (u, v, n) = plane.axes();
    let mut out = Vec::new();
    let mut cur = pos;
    let go = |out: &mut Vec<Segment>, cur: &mut Pose, motion: Motion, target: Pose, f: f64| {
        if (0..3).all(|k| (target.get(k) - cur.get(k)).abs() < 1e-12) {
            return;
        }
        out.push(Segment {
            block: Some(block),
            line,
            motion,
            start: *cur,
            end: target,
            feed: f,
            fixed: true,
        });
        *cur = target;
    };
    let lv = |out: &mut Vec<Segment>, cur: &mut Pose, motion: Motion, level: f64, f: f64| {
        let mut t = *cur;
        t.set(n, level);
        go(out, cur, motion, t, f);
    };
    let mut over = cur;
    over.set(u, pu);
    over.set(v, pv);
    go(&mut out, &mut cur, Motion::Rapid, over, 0.0);
    lv(&mut out, &mut cur, Motion::Rapid, r, 0.0);
    let dir = if bottom < r { -1.0 } else { 1.0 };
    let dwell = |out: &mut Vec<Segment>, cur: Pose| {
        if c.dwell > 0.0 {
            out.push(Segment {
                block: Some(block),
                line,
                motion: Motion::Dwell { seconds: c.dwell },
                start: cur,
                end: cur,
                feed: 0.0,
                fixed: true,
            });
        }
    };
    let depth_total = (bottom - r).abs();
    match c.code {
        730 | 830 => {
            let mut done = 0.0;
            while done < depth_total - 1e-12 {
                let next = (done + c.q).min(depth_total);
                if done > 0.0 {
                    if c.code == 830 {
                        lv(&mut out, &mut cur, Motion::Rapid, r, 0.0);
                    }
                    let back = (done - PECK_CLEARANCE).max(0.0);
                    lv(&mut out, &mut cur, Motion::Rapid, r + dir * back, 0.0);
                }
                lv(&mut out, &mut cur, Motion::Linear, r + dir * next, feed);
                done = next;
            }
        }
        _ => lv(&mut out, &mut cur, Motion::Linear, bottom, feed),
    }
    match c.code {
        820 | 760 | 890 | 840 | 740 => dwell(&mut out, cur),
        _ => {}
    }
    let level = if g99 { r } else { c.initial };
    match c.code {
        840 | 740 | 850 | 890 => {
            lv(&mut out, &mut cur, Motion::Linear, r, feed);
            lv(&mut out, &mut cur, Motion::Rapid, level, 0.0);
        }
        _ => lv(&mut out, &mut cur, Motion::Rapid, level, 0.0),
    }
    out
}
