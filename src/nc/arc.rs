//! Arc centre and sweep from an NC block: the centre as I/J/K (incremental
//! from the start, per plane: G17 I/J, G18 K/I, G19 J/K) or as R (R > 0 the
//! arc up to 180°, R < 0 the arc over 180°). A full circle (end = start)
//! needs I/J/K. Consistency: an end radius that differs from the start
//! radius by up to 0.005 mm + 1e-5·R passes; beyond it, up to LinuxCNC's
//! tolerance, the arc is read with a warning, and beyond that it is
//! refused. LinuxCNC refuses a difference above
//! `CENTER_ARC_RADIUS_TOLERANCE` (2·0.01·√2 mm = 0.0283 mm, or
//! 2·0.0005·√2 in = 0.00141 in in an inch program) that is also above
//! 0.1 % of the radius (`SPIRAL_RELATIVE_TOLERANCE`), and any difference
//! above 100 times that tolerance (checked on the installed `rs274`,
//! LinuxCNC 2.9: on an 895 mm arc 0.5 mm passes and 0.9 mm is refused; on
//! a 100 m arc 2 mm passes and 3 mm is refused). Grbl refuses a difference
//! above 0.005 mm that is above 0.5 mm or 0.1 % of the radius. mtmotion
//! takes LinuxCNC's (the rs274 oracle's), so a 0.025 mm mismatch on an
//! 895 mm CAM arc (Fusion 360) is read, warned.
//! R must be at least half the chord within 0.005 mm + 1e-5·R. The arc's
//! radius is the mean of start and end radii (LinuxCNC runs a spiral).
//!
//! Units: mm, rad.

use super::program::{Arc, Plane, Pose};
use super::{Block, NcError, Word};

fn err(b: &Block, w: &Word, msg: impl Into<String>) -> NcError {
    NcError::new(b.line, w.column, msg)
}

/// The arc of a G2 (`cw`) or G3 block from `start` to `end`; `scale`
/// converts the block's lengths to mm (25.4 under G20).
///
/// # Errors
/// No centre word, a zero radius, a full circle given by R, an R shorter
/// than half the chord, or end and start radii that differ; each names the
/// word's line and column.
pub fn arc(
    b: &Block,
    first: &Word,
    plane: Plane,
    cw: bool,
    start: Pose,
    end: Pose,
    scale: f64,
) -> Result<Arc, NcError> {
    arc_warned(b, first, plane, cw, start, end, scale).map(|(a, _)| a)
}

/// As [`arc`], with the warning of an end radius that differs from the
/// start radius beyond the few-µm tolerance but within LinuxCNC's (see the
/// module header).
///
/// # Errors
/// As [`arc`].
pub fn arc_warned(
    b: &Block,
    first: &Word,
    plane: Plane,
    cw: bool,
    start: Pose,
    end: Pose,
    scale: f64,
) -> Result<(Arc, Option<String>), NcError> {
    let (u, v, n) = plane.axes();
    let g = ArcBlock {
        b,
        first,
        plane,
        cw,
        p0: start.p(),
        p1: end.p(),
        scale,
    };
    let (p0, p1) = (g.p0, g.p1);
    let chord = (p1[u] - p0[u]).hypot(p1[v] - p0[v]);
    let mut center = [0.0; 3];
    center[n] = p0[n];
    let r_form = b.word('R').is_some();
    let mut warning = None;
    let (cu, cv, radius) = match b.word('R') {
        Some(rw) => g.centre_from_r(rw, chord)?,
        None => g.centre_from_ijk(&mut warning)?,
    };
    center[u] = cu;
    center[v] = cv;
    let th0 = (p0[v] - center[v]).atan2(p0[u] - center[u]);
    let th1 = (p1[v] - center[v]).atan2(p1[u] - center[u]);
    let tau = std::f64::consts::TAU;
    let full = chord < 1e-9;
    let sweep = if full {
        if cw {
            -tau
        } else {
            tau
        }
    } else if cw {
        -(th0 - th1).rem_euclid(tau)
    } else {
        (th1 - th0).rem_euclid(tau)
    };
    Ok((
        Arc {
            center,
            radius,
            plane,
            sweep,
            r_form,
        },
        warning,
    ))
}

/// Tolerance of the radius checks, mm: 0.005 mm + 1e-5·R.
fn tol(r: f64) -> f64 {
    0.005 + 1e-5 * r.abs()
}

/// LinuxCNC's `CENTER_ARC_RADIUS_TOLERANCE_MM`, mm.
pub const LINUXCNC_ARC_TOLERANCE_MM: f64 = 2.0 * 0.01 * std::f64::consts::SQRT_2;
/// LinuxCNC's `CENTER_ARC_RADIUS_TOLERANCE_INCH`, inch.
pub const LINUXCNC_ARC_TOLERANCE_INCH: f64 = 2.0 * 0.0005 * std::f64::consts::SQRT_2;
/// LinuxCNC's `SPIRAL_RELATIVE_TOLERANCE`.
pub const SPIRAL_RELATIVE_TOLERANCE: f64 = 0.001;

/// A G2/G3 block with its start and end points (mm).
struct ArcBlock<'a> {
    b: &'a Block,
    first: &'a Word,
    plane: Plane,
    cw: bool,
    p0: [f64; 3],
    p1: [f64; 3],
    scale: f64,
}

impl ArcBlock<'_> {
    /// The centre's in-plane coordinates and the radius from R: R > 0 the
    /// arc up to 180°, R < 0 the arc over 180°.
    fn centre_from_r(&self, rw: &Word, chord: f64) -> Result<(f64, f64, f64), NcError> {
        let (b, p0, p1) = (self.b, self.p0, self.p1);
        let (u, v, _) = self.plane.axes();
        let r = rw.value * self.scale;
        if r == 0.0 {
            return Err(err(
                b,
                rw,
                "arc radius R is zero; expected a non-zero radius",
            ));
        }
        if chord < 1e-9 {
            return Err(err(
                b,
                rw,
                "a full circle cannot be given by R; expected I/J/K for the centre",
            ));
        }
        let half = chord / 2.0;
        if half > r.abs() + tol(r) {
            return Err(err(
                b,
                rw,
                format!(
                    "inconsistent radius: R{} is smaller than half the chord ({:.4} mm); expected |R| ≥ {:.4}",
                    rw.text,
                    half / self.scale,
                    half / self.scale
                ),
            ));
        }
        let h = (r * r - half * half).max(0.0).sqrt();
        let (mu, mv) = ((p0[u] + p1[u]) / 2.0, (p0[v] + p1[v]) / 2.0);
        let (du, dv) = ((p1[u] - p0[u]) / chord, (p1[v] - p0[v]) / chord);
        // Left of the chord for CCW minor arcs; right for CW; flipped for R < 0.
        let side = if self.cw { -1.0 } else { 1.0 } * r.signum();
        Ok((mu - dv * h * side, mv + du * h * side, r.abs()))
    }

    /// The centre's in-plane coordinates from I/J/K (incremental from the
    /// start) and the radius, the mean of the start and end radii.
    fn centre_from_ijk(&self, warning: &mut Option<String>) -> Result<(f64, f64, f64), NcError> {
        let (b, first, p0, p1) = (self.b, self.first, self.p0, self.p1);
        let (u, v, _) = self.plane.axes();
        let letters = ['I', 'J', 'K'];
        let (lu, lv) = (letters[u], letters[v]);
        let iw = b.word(lu);
        let jw = b.word(lv);
        if iw.is_none() && jw.is_none() {
            return Err(err(
                b,
                first,
                format!(
                    "arc (G{}) without a centre in the G{} plane; expected {lu}/{lv} or R",
                    if self.cw { 2 } else { 3 },
                    self.plane.code()
                ),
            ));
        }
        let cu = p0[u] + iw.map_or(0.0, |w| w.value * self.scale);
        let cv = p0[v] + jw.map_or(0.0, |w| w.value * self.scale);
        let r0 = (p0[u] - cu).hypot(p0[v] - cv);
        let r1 = (p1[u] - cu).hypot(p1[v] - cv);
        if r0 < 1e-9 {
            return Err(err(
                b,
                iw.or(jw).unwrap_or(first),
                "arc centre equals the start point; expected a non-zero radius",
            ));
        }
        let diff = (r0 - r1).abs();
        let abs_tol = if self.scale == 1.0 {
            LINUXCNC_ARC_TOLERANCE_MM
        } else {
            LINUXCNC_ARC_TOLERANCE_INCH * self.scale
        };
        let rel = diff / r0.max(r1);
        if diff > 100.0 * abs_tol || (diff > abs_tol && rel > SPIRAL_RELATIVE_TOLERANCE) {
            return Err(err(
                b,
                iw.or(jw).unwrap_or(first),
                format!(
                    "inconsistent radius: start radius {:.4} but end radius {:.4} (mm), {diff:.4} mm apart, beyond LinuxCNC's tolerance ({abs_tol:.4} mm and 0.1 % of the radius, or 100 × {abs_tol:.4} mm); check the end point and {lu}/{lv}",
                    r0, r1
                ),
            ));
        }
        if diff > tol(r0) {
            *warning = Some(format!(
                "arc radius mismatch: start radius {r0:.4} but end radius {r1:.4} (mm), {diff:.4} mm apart; read as an arc of their mean radius (within LinuxCNC's tolerance: {abs_tol:.4} mm or 0.1 % of the radius; a Fanuc control may alarm above a few µm)"
            ));
        }
        Ok((cu, cv, 0.5 * (r0 + r1)))
    }
}
