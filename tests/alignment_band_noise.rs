//! The alignment band is honest on noisy measured sections with default
//! options: over noise 0.01–1 µm and travel ranges 90–360°, each offset and
//! angle error lies within its band of the truth, and the band is narrow
//! (≤ 5 µm for an offset, ≤ 20 µrad for an angle error, the issue's
//! limits), where fitting a fixed 10 orders gave ±1,795 µm. The sections
//! sit at heights not centred on 0 (120/270/420 mm), their arcs are not
//! centred on 0°, and the offsets are not zero. With real motion-error
//! harmonics the band still covers the truth, and its systematic part is
//! the actual error (a second computation: the estimate's error itself).

use mtmotion::alignment::{estimate_alignment_band, AlignmentBand, BandConfig, Section};

use mtmotion::numeric::gaussian as gauss;

/// Harmonic motion error: (order, amplitude mm, phase rad).
type Motion = [(f64, f64, f64)];

/// What a 100 mm ball bar about the nominal pivot reads when the axis
/// centre is at (cz, cx) mm: the table point turns about the centre with
/// the motion error; the bar gives its angle about the pivot and its
/// length − 100 mm, plus gaussian noise of `noise` mm. 2000 samples per
/// revolution, over `range` degrees from `from`.
fn section(
    y: f64,
    (cz, cx): (f64, f64),
    from: f64,
    range: f64,
    motion: &Motion,
    noise: f64,
    seed: u64,
) -> Section {
    let n = (2000.0 * range / 360.0) as usize;
    let e = gauss(seed, n);
    let (mut angle_deg, mut deviation) = (Vec::new(), Vec::new());
    for (i, ei) in e.iter().enumerate() {
        let t = (from + range * i as f64 / (n - 1) as f64).to_radians();
        let r = 100.0
            + motion
                .iter()
                .map(|(k, a, p)| a * (k * t + p).sin())
                .sum::<f64>();
        let (pz, px) = (cz + r * t.cos(), cx + r * t.sin());
        angle_deg.push(px.atan2(pz).to_degrees());
        deviation.push(pz.hypot(px) - 100.0 + noise * ei);
    }
    Section {
        y,
        angle_deg,
        deviation,
    }
}

const HEIGHTS: [f64; 3] = [120.0, 270.0, 420.0];
/// Centres (Z, X) at the three heights, mm: X 0/10/20 µm, Z 5/2/−1 µm.
const CENTRES: [(f64, f64); 3] = [(0.005, 0.0), (0.002, 0.010), (-0.001, 0.020)];
/// ΔBz, ΔBx of those centres, rad.
const TRUE_BZ: f64 = -0.006 / 300.0;
const TRUE_BX: f64 = 0.020 / 300.0;

fn run(range: f64, noise: f64, motion: &Motion, seed: u64) -> AlignmentBand {
    let secs: Vec<Section> = (0..3)
        .map(|k| {
            section(
                HEIGHTS[k],
                CENTRES[k],
                25.0 + 10.0 * k as f64,
                range,
                motion,
                noise,
                seed + k as u64,
            )
        })
        .collect();
    // Default options, as the page and the README give them.
    estimate_alignment_band(
        &secs,
        &BandConfig {
            radius: 100.0,
            max_order: 10,
        },
    )
    .unwrap()
}

/// Every offset and angle error within its band of the truth.
fn assert_covers(b: &AlignmentBand, what: &str) {
    for (k, (s, e)) in b.sections.iter().zip(&b.estimate.sections).enumerate() {
        let (tz, tx) = CENTRES[k];
        assert!(
            (e.z - tz).abs() <= s.band_z,
            "{what} section {k}: Z {} vs {tz} ± {}",
            e.z,
            s.band_z
        );
        assert!(
            (e.x - tx).abs() <= s.band_x,
            "{what} section {k}: X {} vs {tx} ± {}",
            e.x,
            s.band_x
        );
    }
    let (gz, gx) = (b.band_bz.unwrap(), b.band_bx.unwrap());
    let (bz, bx) = (b.estimate.delta_bz.unwrap(), b.estimate.delta_bx.unwrap());
    assert!(
        (bz - TRUE_BZ).abs() <= gz.band,
        "{what}: ΔBz {bz} vs {TRUE_BZ} ± {}",
        gz.band
    );
    assert!(
        (bx - TRUE_BX).abs() <= gx.band,
        "{what}: ΔBx {bx} vs {TRUE_BX} ± {}",
        gx.band
    );
}

#[test]
fn the_issue_case_three_180_degree_sections_with_0_3_um_noise() {
    let b = run(180.0, 0.3e-3, &[], 11);
    assert_covers(&b, "180°, 0.3 µm");
    for s in &b.sections {
        assert!(s.band_z <= 0.005 && s.band_x <= 0.005, "{s:?}");
        // Noise only: no harmonic is kept, so no systematic term.
        assert_eq!((s.order, s.bias_z, s.bias_x), (1, 0.0, 0.0), "{s:?}");
        // The band is 3σ plus the second-order term, and σ is what the
        // noise allows: 0.3 µm over ~1000 points, some tens of nm.
        assert!(s.sigma_x > 5e-6 && s.sigma_x < 1e-4, "{s:?}");
        assert!((s.noise - 0.3e-3).abs() < 0.03e-3, "{s:?}");
    }
    let (gz, gx) = (b.band_bz.unwrap(), b.band_bx.unwrap());
    assert!(gz.band <= 20e-6 && gx.band <= 20e-6, "{gz:?} {gx:?}");
    // And not vacuous: the band is at least the statistical spread.
    assert!(
        gz.statistical > 1e-8 && gx.statistical > 1e-8,
        "{gz:?} {gx:?}"
    );
}

#[test]
fn noise_from_0_01_to_1_um_and_ranges_from_90_to_360_degrees() {
    for (i, &range) in [90.0, 120.0, 180.0, 270.0, 360.0].iter().enumerate() {
        for (j, &noise_um) in [0.01, 0.1, 0.3, 1.0].iter().enumerate() {
            let what = format!("{range}°, {noise_um} µm");
            let b = run(range, noise_um * 1e-3, &[], 100 + 10 * i as u64 + j as u64);
            assert_covers(&b, &what);
            for s in &b.sections {
                assert!(s.band_z <= 0.005 && s.band_x <= 0.005, "{what}: {s:?}");
                assert!(s.determined_z && s.determined_x, "{what}: {s:?}");
            }
            let (gz, gx) = (b.band_bz.unwrap(), b.band_bx.unwrap());
            assert!(
                gz.band <= 20e-6 && gx.band <= 20e-6,
                "{what}: {gz:?} {gx:?}"
            );
            // The band narrows with the noise: at 0.01 µm it is below 0.2 µm.
            if noise_um == 0.01 {
                assert!(
                    b.sections
                        .iter()
                        .all(|s| s.band_z < 2e-4 && s.band_x < 2e-4),
                    "{what}: {:?}",
                    b.sections
                );
            }
        }
    }
}

#[test]
fn real_motion_error_is_kept_and_its_bias_is_the_actual_error() {
    // Orders 2 and 3 of 3 and 1.5 µm with 0.1 µm noise, 180°: BIC keeps
    // them, the systematic term is the estimate's actual error, and the
    // band still covers the truth.
    let motion = [(2.0, 0.003, 0.4), (3.0, 0.0015, -1.1)];
    let b = run(180.0, 0.1e-3, &motion, 7);
    assert_covers(&b, "180°, harmonics");
    for (k, (s, e)) in b.sections.iter().zip(&b.estimate.sections).enumerate() {
        assert!(s.order >= 3, "{s:?}");
        let (tz, tx) = CENTRES[k];
        assert!(s.bias_z.hypot(s.bias_x) > 1e-3, "{s:?}");
        // The statistical part of the band covers what the bias leaves.
        assert!(
            (e.z - tz - s.bias_z).abs() < 3.0 * s.sigma_z + s.second_order_z,
            "{s:?}"
        );
        assert!(
            (e.x - tx - s.bias_x).abs() < 3.0 * s.sigma_x + s.second_order_x,
            "{s:?}"
        );
    }
}
