//! Property: the geometric circle fit is equivariant under rigid motions —
//! translating and rotating the points translates and rotates the fitted
//! centre the same way and leaves the radius and RMS residual unchanged,
//! for noisy partial arcs of any span ≥ 30°.
#![cfg(not(target_arch = "wasm32"))]

use mtmotion::ballbar::fit_circle;
use proptest::prelude::*;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]
    #[test]
    fn fit_is_rigid_motion_equivariant(
        cx in -500.0f64..500.0, cy in -500.0f64..500.0, r in 1.0f64..200.0,
        from in -180.0f64..180.0, span in 30.0f64..360.0,
        noise in 0.0f64..0.01, seed in 0u64..1000,
        tx in -1000.0f64..1000.0, ty in -1000.0f64..1000.0, rot in -3.2f64..3.2,
    ) {
        let n = 60;
        let mut s = seed;
        let (x, y): (Vec<f64>, Vec<f64>) = (0..n).map(|i| {
            s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            let e = noise * r * ((s >> 11) as f64 / (1u64 << 53) as f64 - 0.5);
            let t = (from + span * i as f64 / (n - 1) as f64).to_radians();
            (cx + (r + e) * t.cos(), cy + (r + e) * t.sin())
        }).unzip();
        let a = fit_circle(&x, &y).unwrap();
        let (c, sn) = (rot.cos(), rot.sin());
        let (x2, y2): (Vec<f64>, Vec<f64>) = x.iter().zip(&y)
            .map(|(px, py)| (c * px - sn * py + tx, sn * px + c * py + ty)).unzip();
        let b = fit_circle(&x2, &y2).unwrap();
        let (ex, ey) = (c * a.cx - sn * a.cy + tx, sn * a.cx + c * a.cy + ty);
        // Tolerance: relative 1e-8 of the coordinate magnitude involved.
        let tol = 1e-8 * (1.0 + r + cx.abs() + cy.abs() + tx.abs() + ty.abs());
        prop_assert!((b.cx - ex).abs() < tol && (b.cy - ey).abs() < tol, "{a:?} {b:?}");
        prop_assert!((b.r - a.r).abs() < tol);
        prop_assert!((b.rms_residual - a.rms_residual).abs() < tol);
    }
}
