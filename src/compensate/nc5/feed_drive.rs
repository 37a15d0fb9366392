//! The feed drives of the 5-axis simulation (thasana §II-D 2, Eq. 9,
//! Fig. 8): every axis follows its command through the PID drive of
//! [`crate::servo::pid`], and the S-shape errors are read where the drives
//! actually are when each block's command ends.
//!
//! Readings (the paper gives the gains only):
//! - timing: a G1 block lasts its XYZ length over its feed; a block that
//!   moves only rotary axes lasts its largest rotary move (degrees) over the
//!   feed read as degrees/min; a G0 block moves at 5000 mm/min; every axis
//!   command is linear in time within a block;
//! - the same drive for every axis, in mm for linear and rad for rotary
//!   axes; the command is sampled every `dt` = 1 ms; the drives start at
//!   rest on the first block's start;
//! - the point read for block k is its end point plus the drives'
//!   following error at the end time of its command (interpolated between
//!   samples; no exact stop: the program runs continuously).
//!
//! Units: mm, rad, s.

use crate::kinematics::q_from_degrees;
use crate::nc::program::{Motion, Segment};
use crate::servo::pid::{simulate_pid, PidDrive};
use crate::servo::ServoError;

/// G0 speed of the timing reading, mm/min.
pub const RAPID_FEED: f64 = 5000.0;
/// Command sampling of the drives, s.
pub const DT: f64 = 1e-3;

/// The joint values (mm, rad) the drives reach at the end of each G0/G1
/// block, in program order (the evaluation points of [`super`]).
///
/// # Errors
/// Bad drive parameters.
pub fn positions_at_block_ends(
    segments: &[Segment],
    drive: &PidDrive,
) -> Result<Vec<[f64; 6]>, ServoError> {
    drive.validate()?;
    let moves: Vec<&Segment> = segments
        .iter()
        .filter(|s| matches!(s.motion, Motion::Rapid | Motion::Linear))
        .collect();
    let Some(first) = moves.first() else {
        return Ok(Vec::new());
    };
    // knots: time and joint values at each block end
    let mut times = vec![0.0];
    let mut knots = vec![q_from_degrees(&first.start.to_array())];
    let mut t = 0.0;
    for s in &moves {
        let (a, b) = (s.start.to_array(), s.end.to_array());
        let xyz = ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2) + (b[2] - a[2]).powi(2)).sqrt();
        let rot = (3..6).map(|i| (b[i] - a[i]).abs()).fold(0.0, f64::max);
        let feed = match s.motion {
            Motion::Rapid => RAPID_FEED,
            _ => s.feed,
        } / 60.0;
        let len = if xyz > 0.0 { xyz } else { rot };
        let dur = if feed > 0.0 { len / feed } else { 0.0 };
        t += dur.max(DT);
        times.push(t);
        knots.push(q_from_degrees(&b));
    }
    let n = (t / DT).ceil() as usize + 1;
    let mut out = vec![[0.0; 6]; moves.len()];
    for axis in 0..6 {
        let mut k = 0;
        let cmd: Vec<f64> = (0..n)
            .map(|i| {
                let ti = (i as f64 * DT).min(t);
                while k + 2 < times.len() && times[k + 1] < ti {
                    k += 1;
                }
                let (t0, t1) = (times[k], times[k + 1]);
                let f = if t1 > t0 {
                    ((ti - t0) / (t1 - t0)).clamp(0.0, 1.0)
                } else {
                    1.0
                };
                knots[k][axis] + f * (knots[k + 1][axis] - knots[k][axis])
            })
            .collect();
        let x = simulate_pid(drive, DT, &cmd)?;
        for (j, o) in out.iter_mut().enumerate() {
            // the block's end point plus the drive's following error there
            // (interpolated between samples), so that a drive that follows
            // exactly returns the end point exactly
            let u = times[j + 1] / DT;
            let i0 = (u.floor() as usize).min(n - 1);
            let i1 = (i0 + 1).min(n - 1);
            let f = u - i0 as f64;
            let lag0 = x[i0] - cmd[i0];
            let lag1 = x[i1] - cmd[i1];
            o[axis] = knots[j + 1][axis] + lag0 + f * (lag1 - lag0);
        }
    }
    Ok(out)
}
