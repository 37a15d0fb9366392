//! Mechanistic cutting force of an end mill (thasana-htm-nc-compensation
//! §II-B-3, Eqs. 4–7, after Altintas and the lumped mechanism model).
//!
//! Each flute `i` is cut into axial elements `j` of height `dz`; at spindle
//! angle `φ` the element's immersion is `φ_ij = φ + i·2π/N − z_j·tan(helix)/R`.
//! Inside the engagement it cuts a chip `h = f_t·sin φ_ij·sin κ` (Eq. 5) of
//! width `b = dz/sin κ` (Eq. 6) and feels (Eq. 4)
//! `F_T = K_Tc·h·b + K_Te·b`, `F_R = K_Rc·h·b + K_Re·b`,
//! `F_A = K_Ac·h·b + K_Ae·b`, resolved into the feed frame
//! (`F_x = −F_T cos φ − F_R sin φ`, `F_y = F_T sin φ − F_R cos φ`,
//! `F_z = F_A`) and summed (Eq. 7).
//!
//! Readings chosen: a flat end mill (`κ = 90°`, so `sin κ = 1`); the paper's
//! "depth of cut 0.5 mm" is the radial depth of a peripheral (flank) cut;
//! up-milling by default (engagement `0 … acos(1 − a_e/R)`). The
//! coefficients default to §II-D: `K_Tc = 937.334`, `K_Rc = 292.067`,
//! `K_Ac = 171.37` N/mm², `K_Te = 5.0386`, `K_Re = 6.7597`,
//! `K_Ae = −0.83067` N/mm.
//!
//! Units: mm, N, rpm, mm/min.

use std::f64::consts::{PI, TAU};

use serde::{Deserialize, Serialize};

/// Cutting conditions and coefficients.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase", default)]
pub struct Cutting {
    /// Tool diameter, mm (paper: 6).
    pub diameter: f64,
    /// Number of flutes (paper: 4).
    pub flutes: u32,
    /// Helix angle, degrees (paper: 30).
    pub helix_deg: f64,
    /// Radial depth of cut, mm (paper: 0.5).
    pub radial_depth: f64,
    /// Axial depth of cut, mm (the 12 mm wall of the S part).
    pub axial_depth: f64,
    /// Feed, mm/min (paper: 1000).
    pub feed: f64,
    /// Spindle speed, rpm (paper: 5000).
    pub spindle_rpm: f64,
    /// Down-milling instead of up-milling.
    pub down_milling: bool,
    /// `[K_Tc, K_Rc, K_Ac]`, N/mm².
    pub kc: [f64; 3],
    /// `[K_Te, K_Re, K_Ae]`, N/mm.
    pub ke: [f64; 3],
    /// Free length of the tool (cantilever), mm.
    pub overhang: f64,
    /// Young's modulus, N/mm² (paper: E = 200 GPa).
    pub youngs_modulus: f64,
}

impl Default for Cutting {
    fn default() -> Self {
        Self {
            diameter: 6.0,
            flutes: 4,
            helix_deg: 30.0,
            radial_depth: 0.5,
            axial_depth: 12.0,
            feed: 1000.0,
            spindle_rpm: 5000.0,
            down_milling: false,
            kc: [937.334, 292.067, 171.37],
            ke: [5.0386, 6.7597, -0.83067],
            overhang: 20.0,
            youngs_modulus: 200_000.0,
        }
    }
}

/// Force over one spindle revolution.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct ForceProfile {
    /// Spindle angle, degrees.
    pub angle_deg: Vec<f64>,
    /// Feed-direction force, N.
    pub fx: Vec<f64>,
    /// Normal force, N.
    pub fy: Vec<f64>,
    /// Axial force, N.
    pub fz: Vec<f64>,
    /// Mean over the revolution `[Fx, Fy, Fz]`, N.
    pub mean: [f64; 3],
    /// Largest resultant, N.
    pub peak: f64,
}

impl Cutting {
    /// Checks the values; returns the field and why.
    pub fn validate(&self) -> Result<(), (&'static str, f64, &'static str)> {
        let pos = [
            ("diameter", self.diameter),
            ("axialDepth", self.axial_depth),
            ("feed", self.feed),
            ("spindleRpm", self.spindle_rpm),
            ("overhang", self.overhang),
            ("youngsModulus", self.youngs_modulus),
        ];
        for (f, v) in pos {
            if !(v.is_finite() && v > 0.0) {
                return Err((f, v, "must be > 0"));
            }
        }
        if !(self.radial_depth > 0.0 && self.radial_depth <= self.diameter) {
            return Err((
                "radialDepth",
                self.radial_depth,
                "must be > 0 and ≤ the diameter",
            ));
        }
        if self.flutes == 0 || self.flutes > 20 {
            return Err(("flutes", self.flutes as f64, "must be 1 … 20"));
        }
        if !(self.helix_deg.is_finite() && self.helix_deg.abs() < 80.0) {
            return Err(("helixDeg", self.helix_deg, "must be within ±80°"));
        }
        if !self.kc.iter().chain(&self.ke).all(|v| v.is_finite()) {
            return Err(("kc", f64::NAN, "cutting coefficients must be finite"));
        }
        Ok(())
    }

    /// Feed per tooth, mm.
    pub fn feed_per_tooth(&self) -> f64 {
        self.feed / (self.spindle_rpm * self.flutes as f64)
    }

    /// Forces over one revolution in `steps` samples (Eqs. 4–7).
    ///
    /// # Units
    /// N.
    ///
    /// # Examples
    /// ```
    /// use mtmotion::compensate::nc5::cutting_force::Cutting;
    /// // Full slot, no edge forces: the mean forces of a slot are
    /// // F̄x = −N·a·f_t·K_Rc/4 and F̄y = N·a·f_t·K_Tc/4 (Altintas, average
    /// // milling forces, integrated over 0…π).
    /// let c = Cutting { radial_depth: 6.0, ke: [0.0; 3], ..Cutting::default() };
    /// let f = c.forces(3600);
    /// let (n, a, ft) = (4.0, 12.0, c.feed_per_tooth());
    /// assert!((f.mean[1] - n * a * ft * 937.334 / 4.0).abs() < 1e-3 * f.mean[1]);
    /// assert!((f.mean[0] + n * a * ft * 292.067 / 4.0).abs() < 1e-3 * f.mean[0].abs());
    /// ```
    pub fn forces(&self, steps: usize) -> ForceProfile {
        let r = self.diameter / 2.0;
        let ft = self.feed_per_tooth();
        let imm = (1.0 - self.radial_depth / r).clamp(-1.0, 1.0).acos();
        let (st, ex) = if self.down_milling {
            (PI - imm, PI)
        } else {
            (0.0, imm)
        };
        let elems = 100usize;
        let dz = self.axial_depth / elems as f64;
        let tan_h = self.helix_deg.to_radians().tan();
        let n = self.flutes as usize;
        let steps = steps.max(4);
        let mut p = ForceProfile {
            angle_deg: Vec::with_capacity(steps),
            fx: Vec::with_capacity(steps),
            fy: Vec::with_capacity(steps),
            fz: Vec::with_capacity(steps),
            mean: [0.0; 3],
            peak: 0.0,
        };
        for s in 0..steps {
            let phi = TAU * s as f64 / steps as f64;
            let (mut fx, mut fy, mut fz) = (0.0, 0.0, 0.0);
            for i in 0..n {
                for j in 0..elems {
                    let z = (j as f64 + 0.5) * dz;
                    let a = (phi + i as f64 * TAU / n as f64 - z * tan_h / r).rem_euclid(TAU);
                    if a < st || a > ex {
                        continue;
                    }
                    let h = ft * a.sin(); // Eq. 5, sin κ = 1
                    if h <= 0.0 {
                        continue;
                    }
                    let b = dz; // Eq. 6
                    let t = self.kc[0] * h * b + self.ke[0] * b;
                    let rr = self.kc[1] * h * b + self.ke[1] * b;
                    let ax = self.kc[2] * h * b + self.ke[2] * b;
                    let (sa, ca) = a.sin_cos();
                    fx += -t * ca - rr * sa;
                    fy += t * sa - rr * ca;
                    fz += ax;
                }
            }
            p.angle_deg.push(phi.to_degrees());
            p.fx.push(fx);
            p.fy.push(fy);
            p.fz.push(fz);
            p.mean[0] += fx / steps as f64;
            p.mean[1] += fy / steps as f64;
            p.mean[2] += fz / steps as f64;
            p.peak = p.peak.max((fx * fx + fy * fy + fz * fz).sqrt());
        }
        p
    }

    /// Static deflection of the tool tip under a lateral force (cantilever,
    /// `δ = F·L³/(3·E·I)`, `I = π·D⁴/64`).
    ///
    /// # Units
    /// `force` in N; result in mm.
    ///
    /// # Examples
    /// ```
    /// use mtmotion::compensate::nc5::cutting_force::Cutting;
    /// let c = Cutting::default(); // D 6 mm, L 20 mm, E 200 GPa
    /// let i = std::f64::consts::PI * 6f64.powi(4) / 64.0;
    /// assert!((c.deflection(100.0) - 100.0 * 8000.0 / (3.0 * 200_000.0 * i)).abs() < 1e-15);
    /// ```
    pub fn deflection(&self, force: f64) -> f64 {
        let i = PI * self.diameter.powi(4) / 64.0;
        force * self.overhang.powi(3) / (3.0 * self.youngs_modulus * i)
    }
}
