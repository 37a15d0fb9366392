//! Pitch-error identification of a rotary axis from a measured trace
//! (kato-cone-frustum-ballbar §2.3, Fig. 3): the angular error of the table
//! against its command, measured over whole revolutions (the paper measures
//! it with a ball bar in the tangential direction while X, Y and C, or Y, Z
//! and A, move together), is analysed by Fourier transform and its peaks
//! become the harmonics of Eq. 1.
//!
//! Method:
//! 1. the trace `(θ, e)` — commanded table angle and error, any sampling,
//!    θ monotone — is resampled by linear interpolation onto `samples`
//!    points per revolution over the largest whole number K of revolutions
//!    it covers (so every integer order falls on an FFT bin: no leakage);
//! 2. the discrete Fourier transform is evaluated at every integer order
//!    `N = 0 … maxOrder` cycles per revolution (the FFT's bins `N·K`,
//!    computed directly, O(samples·K·maxOrder)); the one-sided amplitude
//!    `a_N` and phase `ψ_N` are those of `a_N sin(N θ + ψ_N)`;
//! 3. the peaks are the orders `N ≥ 1` with `a_N ≥ threshold` (default
//!    5 % of the largest `a_N`), largest first, at most `maxPeaks`.
//!
//! # Readings of Eq. 1's amplitude (named options)
//! kato writes `R = R_all + Σ W_i sin(N_i R_all θm + φ_i)`.
//! - `additive` (the peaks as measured): the table angle is
//!   `θ = x + Σ a_i sin(N_i x + ψ_i)`, `a_i` in rad — what the FFT of a
//!   measured error gives directly;
//! - `gearRatio` (the crate's reading of `R` as the local ratio, used by
//!   [`super::transmission`]): `θ = x − Σ (W_i g/N_i)[cos(N_i x + φ_i) −
//!   cos φ_i]`, so a peak maps to `W_i = a_i N_i/g`, `φ_i = ψ_i + π/2`
//!   ([`PitchPeak::worm_harmonic`]; the two differ only by the constant
//!   `a_i sin ψ_i`, the error at x = 0). Entering a measured angle
//!   amplitude as `W` is off by g/N (90× at N = 1 for g = 90).
//!
//! # Units
//! Angles and errors in rad; orders in cycles per table revolution.

use serde::{Deserialize, Serialize};

use super::WormHarmonic;

/// Errors of the identification.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PitchIdentifyError {
    /// A field is out of range.
    #[error("`{field}`: {message}")]
    BadField {
        /// The field, e.g. `angle[12]`.
        field: String,
        /// What is wrong and what was expected.
        message: String,
    },
}

fn bad(field: impl Into<String>, message: impl Into<String>) -> PitchIdentifyError {
    PitchIdentifyError::BadField {
        field: field.into(),
        message: message.into(),
    }
}

fn default_samples() -> usize {
    4096
}
fn default_max_order() -> usize {
    400
}
fn default_max_peaks() -> usize {
    10
}

/// Options of [`identify_pitch_error`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase", deny_unknown_fields)]
pub struct PitchIdentifyOptions {
    /// Resampled points per revolution (default 4096).
    #[serde(default = "default_samples")]
    pub samples: usize,
    /// Highest order analysed, cycles/rev (default 400; < samples/2).
    #[serde(default = "default_max_order")]
    pub max_order: usize,
    /// Smallest peak amplitude, rad (default 5 % of the largest).
    #[serde(default)]
    pub threshold: Option<f64>,
    /// At most this many peaks (default 10).
    #[serde(default = "default_max_peaks")]
    pub max_peaks: usize,
}

impl Default for PitchIdentifyOptions {
    fn default() -> Self {
        Self {
            samples: default_samples(),
            max_order: default_max_order(),
            threshold: None,
            max_peaks: default_max_peaks(),
        }
    }
}

/// One identified harmonic `a sin(N θ + ψ)`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct PitchPeak {
    /// Order N, cycles per revolution.
    pub order: usize,
    /// Amplitude a, rad at the table (the `additive` reading).
    pub amplitude: f64,
    /// Phase ψ, rad.
    pub phase: f64,
}

impl PitchPeak {
    /// The peak as a [`WormHarmonic`] of the `gearRatio` reading for a worm
    /// gear of ratio `gear` (motor turns per table turn): `W = a N/g`,
    /// `φ = ψ + π/2`.
    ///
    /// # Examples
    /// ```
    /// use mtmotion::servo::pitch_identify::PitchPeak;
    /// let h = PitchPeak { order: 2, amplitude: 1e-5, phase: 0.0 }.worm_harmonic(90.0);
    /// assert!((h.w - 2e-5 / 90.0).abs() < 1e-18 && h.n == 2.0);
    /// ```
    pub fn worm_harmonic(&self, gear: f64) -> WormHarmonic {
        WormHarmonic {
            w: self.amplitude * self.order as f64 / gear,
            n: self.order as f64,
            phi: self.phase + std::f64::consts::FRAC_PI_2,
        }
    }
}

/// The identification: spectrum and peaks.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct PitchIdentification {
    /// Whole revolutions analysed.
    pub revolutions: usize,
    /// One-sided amplitude per order 0…maxOrder, rad (order 0: the mean).
    pub spectrum: Vec<f64>,
    /// The peaks, largest first.
    pub peaks: Vec<PitchPeak>,
}

/// Identifies the pitch-error harmonics of a rotary axis from its error
/// trace (module header).
///
/// # Errors
/// Arrays of different or too small length, non-finite values, an angle
/// that is not strictly increasing or covers less than one revolution, and
/// out-of-range options, each naming the field and index.
///
/// # Examples
/// ```
/// use mtmotion::servo::pitch_identify::{identify_pitch_error, PitchIdentifyOptions};
/// let th: Vec<f64> = (0..=2000).map(|i| i as f64 * std::f64::consts::TAU / 1000.0).collect();
/// let e: Vec<f64> = th.iter().map(|t| 2e-5 * (3.0 * t + 0.4).sin()).collect();
/// let r = identify_pitch_error(&th, &e, &PitchIdentifyOptions::default()).unwrap();
/// assert_eq!(r.peaks[0].order, 3);
/// assert!((r.peaks[0].amplitude - 2e-5).abs() < 1e-7 && (r.peaks[0].phase - 0.4).abs() < 1e-2);
/// ```
pub fn identify_pitch_error(
    angle: &[f64],
    error: &[f64],
    opts: &PitchIdentifyOptions,
) -> Result<PitchIdentification, PitchIdentifyError> {
    check_trace(angle, error)?;
    check_options(opts)?;
    let tau = std::f64::consts::TAU;
    let span = angle[angle.len() - 1] - angle[0];
    // span ≤ 2e6 rad (check_trace), so the count fits a usize
    let revolutions = (span / tau + 1e-9).floor() as usize;
    if revolutions == 0 {
        return Err(bad(
            "angle",
            format!(
                "covers {} rad; the FFT needs at least one whole revolution (2π rad)",
                crate::numeric::compact(span)
            ),
        ));
    }
    let terms = (opts.samples as u64)
        .saturating_mul(revolutions as u64)
        .saturating_mul(opts.max_order as u64 + 1);
    crate::budget::check(
        "pitch-error identification",
        terms,
        crate::budget::MAX_PITCH_DFT_TERMS,
        "DFT terms (samples × revolutions × (maxOrder + 1))",
        "lower samples or maxOrder, or give fewer revolutions",
    )
    .map_err(|e| bad("angle", e.to_string()))?;
    let y = resample(angle, error, opts.samples, revolutions);
    let (spectrum, mut peaks) = spectrum_at_orders(&y, angle[0], opts, revolutions);
    // 3. the peaks
    let largest = peaks.iter().map(|p| p.amplitude).fold(0.0, f64::max);
    let threshold = opts.threshold.unwrap_or(0.05 * largest);
    peaks.retain(|p| p.amplitude >= threshold && p.amplitude > 0.0);
    peaks.sort_by(|a, b| b.amplitude.total_cmp(&a.amplitude));
    peaks.truncate(opts.max_peaks);
    Ok(PitchIdentification {
        revolutions,
        spectrum,
        peaks,
    })
}

/// Largest |angle| of a trace, rad (160,000 turns): a larger span asked for
/// a resampled record beyond any memory (1e308 rad trapped the module).
pub const MAX_ANGLE: f64 = 1e6;
/// Largest |error| of a trace, rad (57°: far beyond any pitch error).
pub const MAX_ERROR: f64 = 1.0;

/// The trace: equal lengths, at least 8 finite samples within ±[`MAX_ANGLE`]
/// and ±[`MAX_ERROR`], strictly increasing angle.
fn check_trace(angle: &[f64], error: &[f64]) -> Result<(), PitchIdentifyError> {
    if angle.len() != error.len() {
        return Err(bad(
            "error",
            format!(
                "has {} samples but angle has {}; give one error per angle",
                error.len(),
                angle.len()
            ),
        ));
    }
    if angle.len() < 8 {
        return Err(bad(
            "angle",
            format!(
                "{} samples; give at least 8 over one revolution or more",
                angle.len()
            ),
        ));
    }
    for (name, v) in [("angle", angle), ("error", error)] {
        if let Some(i) = v.iter().position(|x| !x.is_finite()) {
            return Err(bad(
                format!("{name}[{i}]"),
                format!("{} is not a finite number", v[i]),
            ));
        }
        let limit = if name == "angle" {
            MAX_ANGLE
        } else {
            MAX_ERROR
        };
        if let Some(i) = v.iter().position(|x| x.abs() > limit) {
            return Err(bad(
                format!("{name}[{i}]"),
                format!(
                    "{} rad is outside ±{} rad; check the trace's units",
                    crate::numeric::compact(v[i]),
                    crate::numeric::compact(limit)
                ),
            ));
        }
    }
    if let Some(i) = angle.windows(2).position(|w| w[1] <= w[0]) {
        return Err(bad(
            format!("angle[{}]", i + 1),
            format!(
                "{} after {}: the angle must increase strictly (sort the trace, or reverse a negative rotation)",
                angle[i + 1],
                angle[i]
            ),
        ));
    }
    Ok(())
}

/// The options: samples ≥ 16, 1 ≤ maxOrder < samples/2, threshold ≥ 0.
fn check_options(opts: &PitchIdentifyOptions) -> Result<(), PitchIdentifyError> {
    if opts.samples < 16 {
        return Err(bad(
            "samples",
            format!("{}: expected at least 16 per revolution", opts.samples),
        ));
    }
    if opts.max_order == 0 || 2 * opts.max_order >= opts.samples {
        return Err(bad(
            "maxOrder",
            format!(
                "{}: expected 1 ≤ maxOrder < samples/2 = {}",
                opts.max_order,
                opts.samples / 2
            ),
        ));
    }
    if let Some(t) = opts.threshold {
        if !(t.is_finite() && t >= 0.0) {
            return Err(bad(
                "threshold",
                format!("{t}: expected a finite amplitude ≥ 0 rad"),
            ));
        }
    }
    Ok(())
}

/// Step 1: the error resampled onto `samples` points per revolution over
/// `revolutions` whole revolutions from the first angle (linear interpolation).
fn resample(angle: &[f64], error: &[f64], samples: usize, revolutions: usize) -> Vec<f64> {
    let m = samples * revolutions;
    let step = std::f64::consts::TAU / samples as f64;
    let mut y = Vec::with_capacity(m);
    let mut j = 0;
    for i in 0..m {
        let t = angle[0] + i as f64 * step;
        while j + 2 < angle.len() && angle[j + 1] < t {
            j += 1;
        }
        let (t0, t1) = (angle[j], angle[j + 1]);
        let f = ((t - t0) / (t1 - t0)).clamp(0.0, 1.0);
        y.push(error[j] + f * (error[j + 1] - error[j]));
    }
    y
}

/// Step 2: the DFT of the resampled record `y` at each integer order 0…maxOrder
/// (bin N·K): the one-sided amplitude spectrum and one candidate peak per
/// order ≥ 1, phases referred to θ = 0 (the record starts at `theta0`).
fn spectrum_at_orders(
    y: &[f64],
    theta0: f64,
    opts: &PitchIdentifyOptions,
    revolutions: usize,
) -> (Vec<f64>, Vec<PitchPeak>) {
    let tau = std::f64::consts::TAU;
    let m = y.len();
    let step = tau / opts.samples as f64;
    let mut spectrum = Vec::with_capacity(opts.max_order + 1);
    let mut peaks = Vec::new();
    for n in 0..=opts.max_order {
        let (mut s, mut c) = (0.0, 0.0);
        let dphi = n as f64 * step;
        let (sd, cd) = dphi.sin_cos();
        // rotate (sin, cos) of N·(θ − θ0) by recurrence, re-seeded per revolution
        for r in 0..revolutions {
            let (mut sn, mut cn) = (0.0_f64, 1.0_f64);
            for k in 0..opts.samples {
                let v = y[r * opts.samples + k];
                s += v * sn;
                c += v * cn;
                let sn1 = sn * cd + cn * sd;
                cn = cn * cd - sn * sd;
                sn = sn1;
            }
        }
        let (s, c) = (s / m as f64, c / m as f64);
        if n == 0 {
            spectrum.push(c);
            continue;
        }
        // y ≈ 2s sin + 2c cos = a sin(Nθ' + ψ'), θ' = θ − θ0
        let a = 2.0 * s.hypot(c);
        let psi = (2.0 * c).atan2(2.0 * s) - n as f64 * theta0;
        spectrum.push(a);
        peaks.push(PitchPeak {
            order: n,
            amplitude: a,
            phase: psi.rem_euclid(tau),
        });
    }
    (spectrum, peaks)
}
