//! Synthetic ball-bar traces with known machine errors, for validating the
//! ISO 230-4 analysis and for the page's "generate" button.
//!
//! Source: the error signatures of a two-axis circular test as described in
//! ISO 230-4 Annex (interpretation) and ball-bar practice; the radial
//! motion-error harmonics of takayama-alignment-travel-range §2.1.
//!
//! Model (exact geometry, XY plane, θ = 0 along +X, CCW positive): the
//! commanded point R·(cos θ, sin θ) is moved by
//! - servo mismatch τ: X follows the command τ later than Y,
//!   x = R cos(θ − s·ωτ) (s = +1 CCW, −1 CW; ω = feed/R);
//! - scale errors: x·(1 + sx), y·(1 + sy);
//! - squareness α: x += α·y (the Y axis leans towards +X: the axes enclose
//!   90° − α);
//! - backlash bx, by (dead band): x −= (bx/2)·sign(ẋ), y −= (by/2)·sign(ẏ);
//! - cyclic (pitch) error A·sin(2π·x_cmd/p) on X and on Y;
//! - set-up offset (ox, oy) of the bar's centre;
//! - radial harmonics Σ Aₙ sin(nθ + φₙ) and a reversal spike
//!   h·exp(−φ/decay) added radially after each quadrant point, φ being
//!   the angle travelled since it;
//! - uniform noise ±noise from a fixed-seed generator.
//!
//! The deviation is |p| − R at the commanded angle θ.
//!
//! Units: mm, rad, s, mm/min (feed); angles of the range in degrees.

use serde::{Deserialize, Serialize};

use super::harmonics::{synthesize, Harmonic};
use super::trace_import::{BallbarTrace, Direction, Run};

/// Errors of the generator.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{field}: {message}")]
pub struct SyntheticError {
    /// The field.
    pub field: &'static str,
    /// What was expected.
    pub message: String,
}

fn d_radius() -> f64 {
    100.0
}
fn d_feed() -> f64 {
    1000.0
}
fn d_samples() -> usize {
    3600
}
fn d_range() -> f64 {
    360.0
}
fn d_true() -> bool {
    true
}
fn d_decay() -> f64 {
    3.0
}
fn d_pitch() -> f64 {
    10.0
}

/// Machine errors and test settings of a synthetic trace.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase", default)]
pub struct SyntheticConfig {
    /// Bar length R, mm.
    #[serde(default = "d_radius")]
    pub radius: f64,
    /// Feed, mm/min.
    #[serde(default = "d_feed")]
    pub feed: f64,
    /// Samples per revolution.
    #[serde(default = "d_samples")]
    pub samples: usize,
    /// Angular range of each run, degrees.
    #[serde(default = "d_range")]
    pub range_deg: f64,
    /// Centre of the range, degrees.
    pub centre_deg: f64,
    /// CCW then CW (true) or CCW only.
    #[serde(default = "d_true")]
    pub both_directions: bool,
    /// Set-up offset of the centre, X, mm.
    pub offset_x: f64,
    /// Set-up offset of the centre, Y, mm.
    pub offset_y: f64,
    /// Radial harmonics, mm.
    pub harmonics: Vec<Harmonic>,
    /// Scale error of X (dimensionless, 1e-6 = 1 ppm).
    pub scale_x: f64,
    /// Scale error of Y (dimensionless).
    pub scale_y: f64,
    /// Squareness α, rad.
    pub squareness: f64,
    /// Servo mismatch τ, s (X lags Y).
    pub servo_mismatch: f64,
    /// Backlash of X, mm.
    pub backlash_x: f64,
    /// Backlash of Y, mm.
    pub backlash_y: f64,
    /// Reversal-spike height, mm.
    pub spike: f64,
    /// Reversal-spike decay angle, degrees.
    #[serde(default = "d_decay")]
    pub spike_decay_deg: f64,
    /// Cyclic-error amplitude on X and Y, mm.
    pub cyclic_amplitude: f64,
    /// Cyclic-error pitch, mm.
    #[serde(default = "d_pitch")]
    pub cyclic_pitch: f64,
    /// Uniform noise half-width, mm.
    pub noise: f64,
}

impl Default for SyntheticConfig {
    fn default() -> Self {
        Self {
            radius: d_radius(),
            feed: d_feed(),
            samples: d_samples(),
            range_deg: d_range(),
            centre_deg: 0.0,
            both_directions: true,
            offset_x: 0.0,
            offset_y: 0.0,
            harmonics: Vec::new(),
            scale_x: 0.0,
            scale_y: 0.0,
            squareness: 0.0,
            servo_mismatch: 0.0,
            backlash_x: 0.0,
            backlash_y: 0.0,
            spike: 0.0,
            spike_decay_deg: d_decay(),
            cyclic_amplitude: 0.0,
            cyclic_pitch: d_pitch(),
            noise: 0.0,
        }
    }
}

fn err(field: &'static str, message: impl Into<String>) -> SyntheticError {
    SyntheticError {
        field,
        message: message.into(),
    }
}

/// Shortest bar, mm: 1 µm (a subnormal radius would make ω infinite).
pub const MIN_RADIUS: f64 = 1e-3;
/// Longest bar, mm (1 km).
pub const MAX_RADIUS: f64 = 1e6;
/// Highest feed, mm/min (1 km/min).
pub const MAX_FEED: f64 = 1e6;
/// Lowest feed a measured trace may state, mm/min (a subnormal feed made
/// the circular test's servo-mismatch time infinite).
pub const MIN_FEED: f64 = 1e-3;
/// Most harmonics of the radial error ([`crate::budget::MAX_HARMONICS`]).
pub const MAX_HARMONICS: usize = crate::budget::MAX_HARMONICS;

/// Generates a ball-bar trace with the configured errors.
///
/// # Units
/// See [`SyntheticConfig`]: mm, rad, s, mm/min, degrees for the range.
///
/// # Errors
/// [`SyntheticError`] naming the field for non-positive radius, feed,
/// pitch, decay, a range outside (0, 360] or too few samples.
///
/// # Examples
/// ```
/// use mtmotion::ballbar::{synthetic_trace, SyntheticConfig};
/// let t = synthetic_trace(&SyntheticConfig { backlash_x: 0.004, ..Default::default() }).unwrap();
/// assert_eq!(t.runs.len(), 2);
/// // Just after 0° (CCW) X has reversed: +b/2 on the radius.
/// assert!((t.runs[0].deviation[1800 + 5] - 0.002).abs() < 1e-5);
/// ```
pub fn synthetic_trace(c: &SyntheticConfig) -> Result<BallbarTrace, SyntheticError> {
    validate(c)?;
    let n = ((c.samples as f64 * c.range_deg / 360.0).round() as usize).max(8);
    crate::budget::check(
        "synthetic trace",
        (n as u64)
            .saturating_mul(1 + u64::from(c.both_directions))
            .saturating_mul(1 + c.harmonics.len() as u64),
        crate::budget::MAX_SYNTHETIC_TERMS,
        "terms (samples × directions × (1 + harmonics))",
        "use fewer samples per revolution or fewer harmonics",
    )
    .map_err(|e| err("config", e.to_string()))?;
    let mut noise = Lcg(0x9E37_79B9_7F4A_7C15);
    let mut runs = vec![run(c, Direction::Ccw, n, &mut noise)];
    if c.both_directions {
        runs.push(run(c, Direction::Cw, n, &mut noise));
    }
    // Finite inputs can still overflow (an offset of 1e308 mm): say so
    // instead of returning Infinity or NaN.
    if runs
        .iter()
        .any(|r| r.deviation.iter().any(|d| !d.is_finite()))
    {
        return Err(err(
            "config",
            "the error values are too large: the deviation overflows; use values in mm and rad",
        ));
    }
    Ok(BallbarTrace {
        nominal_radius: c.radius,
        feed: Some(c.feed),
        runs,
        centre: None,
        trimming: None,
        warnings: Vec::new(),
    })
}

/// Positive radius, feed, pitch and decay, 16 … 10⁷ samples, a range in
/// (0, 360] degrees and finite error values.
fn validate(c: &SyntheticConfig) -> Result<(), SyntheticError> {
    let pos = |v: f64| v.is_finite() && v > 0.0;
    let compact = crate::numeric::compact;
    if !(c.radius.is_finite() && (MIN_RADIUS..=MAX_RADIUS).contains(&c.radius)) {
        return Err(err(
            "radius",
            format!(
                "expected a bar length from 0.001 to 1e6 mm, got {}",
                compact(c.radius)
            ),
        ));
    }
    if !(pos(c.feed) && c.feed <= MAX_FEED) {
        return Err(err(
            "feed",
            format!(
                "expected a feed above 0 and at most 1e6 mm/min, got {}",
                compact(c.feed)
            ),
        ));
    }
    if c.harmonics.len() > MAX_HARMONICS {
        return Err(err(
            "harmonics",
            format!(
                "{} harmonics; at most {MAX_HARMONICS} can matter on a ball-bar trace",
                c.harmonics.len()
            ),
        ));
    }
    if !(16..=10_000_000).contains(&c.samples) {
        return Err(err(
            "samples",
            format!(
                "expected 16 … 10000000 samples per revolution, got {}",
                c.samples
            ),
        ));
    }
    if !(c.range_deg > 0.0 && c.range_deg <= 360.0) {
        return Err(err(
            "rangeDeg",
            format!(
                "expected a range in (0, 360] degrees, got {}",
                crate::numeric::compact(c.range_deg)
            ),
        ));
    }
    if !pos(c.cyclic_pitch) || !pos(c.spike_decay_deg) {
        return Err(err(
            "cyclicPitch",
            "cyclicPitch and spikeDecayDeg must be > 0",
        ));
    }
    let finite = [
        c.centre_deg,
        c.offset_x,
        c.offset_y,
        c.scale_x,
        c.scale_y,
        c.squareness,
        c.servo_mismatch,
        c.backlash_x,
        c.backlash_y,
        c.spike,
        c.cyclic_amplitude,
        c.noise,
    ];
    if finite.iter().any(|v| !v.is_finite())
        || c.harmonics
            .iter()
            .any(|h| !h.amplitude.is_finite() || !h.phase.is_finite())
    {
        return Err(err("config", "every error value must be a finite number"));
    }
    Ok(())
}

/// A linear congruential generator (Knuth's MMIX constants): uniform noise
/// in [−1, 1), the same sequence on every platform.
struct Lcg(u64);

impl Lcg {
    fn uniform(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }
}

/// One run of `n + 1` samples over the configured range in direction `dir`.
fn run(c: &SyntheticConfig, dir: Direction, n: usize, noise: &mut Lcg) -> Run {
    let r = c.radius;
    let omega = c.feed / 60.0 / r; // rad/s
    let (a0, a1) = (
        (c.centre_deg - c.range_deg / 2.0).to_radians(),
        (c.centre_deg + c.range_deg / 2.0).to_radians(),
    );
    let decay = c.spike_decay_deg.to_radians();
    let quarter = std::f64::consts::FRAC_PI_2;
    let s = dir.sign();
    let (mut angle, mut deviation) = (Vec::with_capacity(n + 1), Vec::with_capacity(n + 1));
    for i in 0..=n {
        let f = i as f64 / n as f64;
        let th = if s > 0.0 {
            a0 + (a1 - a0) * f
        } else {
            a1 - (a1 - a0) * f
        };
        let (xc, yc) = (r * th.cos(), r * th.sin());
        let mut x = r * (th - s * omega * c.servo_mismatch).cos();
        let mut y = yc;
        x *= 1.0 + c.scale_x;
        y *= 1.0 + c.scale_y;
        x += c.squareness * y;
        // Velocity signs: ẋ ∝ −s sin θ, ẏ ∝ s cos θ.
        x -= c.backlash_x / 2.0 * sgn(-s * th.sin());
        y -= c.backlash_y / 2.0 * sgn(s * th.cos());
        x += c.cyclic_amplitude * (std::f64::consts::TAU * xc / c.cyclic_pitch).sin();
        y += c.cyclic_amplitude * (std::f64::consts::TAU * yc / c.cyclic_pitch).sin();
        x += c.offset_x;
        y += c.offset_y;
        // Angle travelled since the last quadrant point.
        let since = if s > 0.0 {
            th.rem_euclid(quarter)
        } else {
            (-th).rem_euclid(quarter)
        };
        let spike = if c.spike != 0.0
            && since < 10.0 * decay
            && (th - s * since - a0).abs() > 1e-9
            && (th - s * since - a1).abs() > 1e-9
        {
            c.spike * (-since / decay).exp()
        } else {
            0.0
        };
        let dr = synthesize(&c.harmonics, th) + spike + c.noise * noise.uniform();
        let dev = x.hypot(y) + dr - r;
        angle.push(th);
        deviation.push(dev);
    }
    Run {
        direction: dir,
        angle,
        deviation,
        lines: Vec::new(),
    }
}

fn sgn(v: f64) -> f64 {
    if v > 1e-12 {
        1.0
    } else if v < -1e-12 {
        -1.0
    } else {
        0.0
    }
}
