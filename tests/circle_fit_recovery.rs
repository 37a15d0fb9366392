//! The circle fit recovers centre and radius exactly from noiseless arcs of
//! any span from 30° to 360°, anywhere in the plane, and refuses fewer than
//! three points or collinear points with an actionable message.

use mtmotion::ballbar::{fit_circle, FitError};

fn arc(cx: f64, cy: f64, r: f64, from_deg: f64, span_deg: f64, n: usize) -> (Vec<f64>, Vec<f64>) {
    (0..n)
        .map(|i| {
            let t = (from_deg + span_deg * i as f64 / (n - 1) as f64).to_radians();
            (cx + r * t.cos(), cy + r * t.sin())
        })
        .unzip()
}

#[test]
fn exact_on_noiseless_arcs_down_to_30_degrees() {
    for &(cx, cy, r) in &[(0.0, 0.0, 100.0), (512.3, -77.0, 25.0), (-3.0, 1e4, 0.01)] {
        for span in [30.0, 45.0, 90.0, 150.0, 180.0, 270.0, 360.0] {
            for from in [-170.0, 0.0, 33.0] {
                let (x, y) = arc(cx, cy, r, from, span, 40);
                let c = fit_circle(&x, &y).unwrap();
                // Relative to the radius: 1e-9 (rounding of coordinates
                // ~1e4 times the radius in the last case costs digits).
                let tol = 1e-9 * r.max(1.0) * (1.0 + cx.abs().max(cy.abs()) / r).min(1e4);
                assert!(
                    (c.cx - cx).abs() < tol && (c.cy - cy).abs() < tol && (c.r - r).abs() < tol,
                    "span {span} from {from}: {c:?}"
                );
                assert!(c.rms_residual < tol);
            }
        }
    }
}

#[test]
fn noisy_arc_is_recovered_to_the_noise_level() {
    // ±1 µm deterministic noise on a 60° arc of R = 100 mm.
    let (mut x, mut y) = arc(10.0, 20.0, 100.0, 0.0, 60.0, 2001);
    for i in 0..x.len() {
        let e = 0.001 * ((i * 7919 % 13) as f64 / 6.0 - 1.0);
        let t = (60.0 * i as f64 / 2000.0f64).to_radians();
        x[i] += e * t.cos();
        y[i] += e * t.sin();
    }
    let c = fit_circle(&x, &y).unwrap();
    assert!(
        (c.r - 100.0).abs() < 0.01 && (c.cx - 10.0).abs() < 0.01,
        "{c:?}"
    );
    assert!(c.rms_residual > 1e-4 && c.rms_residual < 1e-3, "{c:?}");
}

#[test]
fn too_few_or_collinear_points_are_errors() {
    assert_eq!(fit_circle(&[], &[]), Err(FitError::TooFewPoints(0)));
    assert_eq!(
        fit_circle(&[0.0, 1.0], &[0.0, 1.0]),
        Err(FitError::TooFewPoints(2))
    );
    let x: Vec<f64> = (0..50).map(|i| i as f64 * 0.3 - 4.0).collect();
    let y: Vec<f64> = x.iter().map(|v| 2.0 * v + 1.0).collect();
    let e = fit_circle(&x, &y).unwrap_err();
    assert_eq!(e, FitError::Collinear);
    assert!(e.to_string().contains("collinear"));
    // Vertical line and coincident points.
    assert_eq!(
        fit_circle(&[3.0; 5], &[0.0, 1.0, 2.0, 3.0, 4.0]),
        Err(FitError::Collinear)
    );
    assert_eq!(fit_circle(&[1.0; 3], &[1.0; 3]), Err(FitError::Collinear));
}
