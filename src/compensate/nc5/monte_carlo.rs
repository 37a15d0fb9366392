//! Seeded Monte-Carlo of geometric errors (thasana §II-B-2, §II-D: "six
//! parameters, derived from a normal distribution"): every location error a
//! rotary axis can have (as listed by the cone-frustum sensitivity) and the
//! six constant component errors of every axis are drawn from
//! `N(0, σ_mm)` (translations) or `N(0, σ_rad)` (rotations).
//!
//! Random numbers: SplitMix64 (Steele et al. 2014) and the Box–Muller
//! transform, so a seed gives the same machine on every platform.
//!
//! Units: mm, rad.

use serde::{Deserialize, Serialize};

use crate::kinematics::errors::Coeffs;
use crate::kinematics::{Chain, GeometricErrors};

/// Monte-Carlo settings.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase", default)]
pub struct MonteCarlo {
    /// Seed.
    pub seed: u64,
    /// σ of translation errors, mm.
    pub sigma_mm: f64,
    /// σ of angular errors, rad.
    pub sigma_rad: f64,
    /// σ of a per-point random error of the tool tip that no model knows
    /// (repeatability), mm.
    pub repeatability_mm: f64,
}

impl Default for MonteCarlo {
    fn default() -> Self {
        Self {
            seed: 1,
            sigma_mm: 0.01,
            sigma_rad: 5e-5,
            repeatability_mm: 0.0,
        }
    }
}

/// SplitMix64 with a Box–Muller normal generator.
#[derive(Debug, Clone)]
pub struct Rng {
    state: u64,
    spare: Option<f64>,
}

impl Rng {
    /// A generator from `seed`.
    pub fn new(seed: u64) -> Self {
        Self {
            state: seed,
            spare: None,
        }
    }
    /// Uniform in (0, 1).
    pub fn uniform(&mut self) -> f64 {
        self.state = self.state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        ((z >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    }
    /// Standard normal.
    ///
    /// # Examples
    /// ```
    /// let mut r = mtmotion::compensate::nc5::monte_carlo::Rng::new(7);
    /// let xs: Vec<f64> = (0..200_000).map(|_| r.normal()).collect();
    /// let m = xs.iter().sum::<f64>() / xs.len() as f64;
    /// let v = xs.iter().map(|x| (x - m).powi(2)).sum::<f64>() / xs.len() as f64;
    /// assert!(m.abs() < 0.01 && (v - 1.0).abs() < 0.01);
    /// ```
    pub fn normal(&mut self) -> f64 {
        if let Some(s) = self.spare.take() {
            return s;
        }
        let (u1, u2) = (self.uniform(), self.uniform());
        let r = (-2.0 * u1.ln()).sqrt();
        let t = std::f64::consts::TAU * u2;
        self.spare = Some(r * t.sin());
        r * t.cos()
    }
}

/// One random machine: `base` plus normal errors on every parameter.
pub fn draw(
    chain: &Chain,
    base: &GeometricErrors,
    mc: &MonteCarlo,
    rng: &mut Rng,
) -> GeometricErrors {
    let mut e = base.clone();
    let sigma = |sym: &str| {
        if sym.as_bytes().get(1).is_some_and(|c| b"XYZ".contains(c)) {
            mc.sigma_mm
        } else {
            mc.sigma_rad
        }
    };
    for sym in crate::kinematics::errors::error_symbols(chain) {
        let s = sigma(&sym);
        *e.location.entry(sym).or_insert(0.0) += s * rng.normal();
    }
    for axis in chain.axes() {
        let up = axis.to_uppercase();
        for d in ["X", "Y", "Z", "A", "B", "C"] {
            let sym = format!("E{d}{up}");
            let v = sigma(&sym) * rng.normal();
            let mut c = e
                .component
                .get(&sym)
                .map(|c| c.to_vec())
                .unwrap_or_default();
            if c.is_empty() {
                c.push(0.0);
            }
            c[0] += v;
            e.component.insert(sym, Coeffs::Polynomial(c));
        }
    }
    e
}
