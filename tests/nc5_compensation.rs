//! Proves the 5-axis NC compensation (thasana §II-D): on the ISO 10791-7
//! S-shape program (15 %, 64 points) for the Pocket NC V2-10 with a seeded
//! Monte-Carlo machine, the cutting-force deflection and a per-point
//! repeatability the model does not know, the compensated program cuts the
//! standard deviation of the simulated errors by ≥ 80 % (paper: 80.73 %);
//! the corrected program still reads; zero errors leave the program's
//! motion unchanged; bad input names the line.
#![cfg(not(target_arch = "wasm32"))]

use mtmotion::compensate::nc5::cutting_force::Cutting;
use mtmotion::compensate::nc5::monte_carlo::MonteCarlo;
use mtmotion::compensate::nc5::s_shape::{s_shape, SShapeOptions};
use mtmotion::compensate::nc5::{compensate_nc5, Nc5Config};
use mtmotion::kinematics::GeometricErrors;
use mtmotion::machine::MachineRef;

fn program() -> String {
    s_shape(&SShapeOptions::paper(MachineRef::Name(
        "pocketnc-v2-10".into(),
    )))
    .unwrap()
    .nc
}

#[test]
fn compensation_cuts_std_by_at_least_80_percent() {
    let cfg = Nc5Config {
        machine: MachineRef::Name("pocketnc-v2-10".into()),
        errors: GeometricErrors::default(),
        tool_length: 0.0,
        monte_carlo: Some(MonteCarlo {
            seed: 42,
            sigma_mm: 0.02,
            sigma_rad: 1e-3,
            repeatability_mm: 0.001,
        }),
        cutting: Some(Cutting::default()),
    };
    let r = compensate_nc5(&program(), &cfg).unwrap();
    assert_eq!(r.lines.len(), 64);
    assert!(r.deflection_mm > 1e-3, "deflection {}", r.deflection_mm);
    // Before: tens of µm and mrad.
    assert!(
        r.before.std_mm[0] > 0.01 && r.before.std_rad[1] > 1e-4,
        "{:?}",
        r.before
    );
    for (i, red) in r.reduction_percent.iter().enumerate() {
        assert!(
            *red >= 80.0,
            "axis {i}: {red} % ({:?} → {:?})",
            r.before,
            r.after
        );
    }
    assert!(r.total_reduction_percent >= 80.0);
    // The repeatability (1 µm) is what remains in position.
    assert!(r.after.std_mm.iter().all(|s| *s < 0.003), "{:?}", r.after);
    // The same seed gives the same machine.
    let r2 = compensate_nc5(&program(), &cfg).unwrap();
    assert_eq!(r.nc, r2.nc);
}

#[test]
fn zero_errors_leave_the_motion_unchanged() {
    let cfg = Nc5Config {
        machine: MachineRef::Name("pocketnc-v2-10".into()),
        errors: GeometricErrors::default(),
        tool_length: 0.0,
        monte_carlo: None,
        cutting: None,
    };
    let nc = program();
    let r = compensate_nc5(&nc, &cfg).unwrap();
    let a = mtmotion::nc::program::parse(&nc).unwrap();
    let b = mtmotion::nc::program::parse(&r.nc).unwrap();
    for (s, t) in a.segments.iter().zip(&b.segments) {
        for i in 0..6 {
            assert!((s.end.get(i) - t.end.get(i)).abs() < 1e-9);
        }
    }
    assert!(r.before.std_mm.iter().all(|v| *v < 1e-9));
}

#[test]
fn errors_name_the_line() {
    let cfg = Nc5Config {
        machine: MachineRef::Name("trunnion-ac".into()),
        errors: GeometricErrors::default(),
        tool_length: 0.0,
        monte_carlo: None,
        cutting: None,
    };
    let e = compensate_nc5("G90\nG1 X1 F100\nG2 X2 Y1 R1\n", &cfg)
        .unwrap_err()
        .to_string();
    assert!(e.contains("line 3"), "{e}");
    let e = compensate_nc5("G90\nG1 X1 Q\n", &cfg)
        .unwrap_err()
        .to_string();
    assert!(e.contains("line 2"), "{e}");
}
