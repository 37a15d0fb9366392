//! kato's conclusion (abstract, §4): "the trajectory due to the errors of
//! the axis of rotation is strongly affected by the sensitive direction of
//! the ball bar for the case of a half apex angle of 45°". Checked on the
//! sensitivity coefficient of the tilting rotary axis (`n·∂p/∂q`, RMS over
//! the revolution): the relative difference between the perpendicular and
//! the parallel bar is at least twice as large at θ = 45° (β = 30°) as at
//! θ = 15° (β = 10°), on both tilting-table presets.

use mtmotion::cone_frustum::{cone_frustum_test, ConeFrustumConfig, Method};
use mtmotion::kinematics::GeometricErrors;
use mtmotion::machine::MachineRef;

fn rms_tilt(machine: &str, tilt: &str, theta: f64, beta: f64, method: Method) -> f64 {
    let cfg = ConeFrustumConfig {
        machine: MachineRef::Name(machine.into()),
        half_apex_deg: theta,
        inclination_deg: beta,
        method,
        bar_length: 100.0,
        feed: 1000.0,
        radius: None,
        centre: None,
        errors: GeometricErrors::default(),
        drives: Default::default(),
        ideal_servo: true,
        tool_length: 0.0,
        points: 360,
        clockwise: false,
        lead_in_deg: 0.0,
        sensitivities: true,
    };
    let r = cone_frustum_test(&cfg).unwrap();
    let s = r.axis_sensitivity.iter().find(|s| s.name == tilt).unwrap();
    (s.values.iter().map(|v| v * v).sum::<f64>() / s.values.len() as f64).sqrt()
}

#[test]
fn bar_direction_matters_far_more_at_45_degrees() {
    for (machine, tilt) in [("trunnion-ac", "a"), ("table-on-table-bc", "b")] {
        let rel = |theta: f64, beta: f64| {
            let perp = rms_tilt(machine, tilt, theta, beta, Method::Perpendicular);
            let par = rms_tilt(machine, tilt, theta, beta, Method::Parallel);
            (perp / par - 1.0).abs()
        };
        let (r15, r45) = (rel(15.0, 10.0), rel(45.0, 30.0));
        println!("{machine}: |perp/par − 1| = {r15:.3} at 15°, {r45:.3} at 45°");
        assert!(r45 > 2.0 * r15, "{machine}: {r15} at 15°, {r45} at 45°");
    }
}
