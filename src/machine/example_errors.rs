//! Example geometric and drive errors for the 5-axis presets, so that the
//! page's cone-frustum test has something to show. **Illustrative, not measured**:
//! neither kato-cone-frustum-ballbar nor thasana-htm-nc-compensation tables
//! the location errors of their machines, so these are typical magnitudes
//! of the ISO 230-7 location errors of a well-aligned commercial 5-axis
//! machining centre of the kind they test:
//!
//! - rotary-axis centre offsets (`EX0C`, `EY0C`, `EY0A`, `EZ0A`, …):
//!   10–20 µm (0.010–0.020 mm);
//! - orientation (squareness / parallelism) errors of the rotary axes
//!   (`EB0C`, `EC0A`, …): 15–20 µrad (≈ 3–4 arc-seconds);
//! - backlash of the worm-gear rotary axes (kato §2 models it; no value
//!   given): 0.01° = 1.745e-4 rad on the table axis, 0.005° = 8.73e-5 rad
//!   on the tilting axis (full width). It is a drive error
//!   ([`DriveErrors`], the preset's `exampleDrives`), not a geometric one.
//!
//! Every symbol is one the cone-frustum test can see
//! ([`crate::kinematics::errors::error_symbols`]), so the page shows
//! each of them in its error table.
//!
//! Units: mm, rad.

use std::collections::BTreeMap;

use crate::kinematics::GeometricErrors;
use crate::servo::transmission::DriveErrors;

/// 0.01° in rad: backlash of the table (C or B) worm gear.
pub const TABLE_BACKLASH_RAD: f64 = 0.01 * std::f64::consts::PI / 180.0;
/// 0.005° in rad: backlash of the tilting-axis worm gear.
pub const TILT_BACKLASH_RAD: f64 = 0.005 * std::f64::consts::PI / 180.0;

/// An example: the geometric errors and the drive errors.
pub type Example = (GeometricErrors, DriveErrors);

fn errors(location: &[(&str, f64)], backlash: &[(&str, f64)]) -> Example {
    let map = |v: &[(&str, f64)]| -> BTreeMap<String, f64> {
        v.iter().map(|(k, x)| (k.to_string(), *x)).collect()
    };
    (
        GeometricErrors {
            location: map(location),
            ..GeometricErrors::default()
        },
        DriveErrors {
            backlash: map(backlash),
            ..DriveErrors::default()
        },
    )
}

/// Trunnion A–C (kato's layout): C and A axis offsets, C squareness, A
/// parallelism, worm-gear backlash of both.
pub fn trunnion_ac() -> Example {
    errors(
        &[
            ("EX0C", 0.015),
            ("EY0C", -0.010),
            ("EY0A", 0.020),
            ("EZ0A", -0.012),
            ("EB0C", 20e-6),
            ("EC0A", -15e-6),
        ],
        &[("c", TABLE_BACKLASH_RAD), ("a", TILT_BACKLASH_RAD)],
    )
}

/// Table-on-table B–C (NMV5000 layout): C and B axis offsets, C
/// squareness, B parallelism, worm-gear backlash of both.
pub fn table_on_table_bc() -> Example {
    errors(
        &[
            ("EX0C", 0.015),
            ("EY0C", -0.010),
            ("EX0B", 0.020),
            ("EZ0B", -0.012),
            ("EA0C", 20e-6),
            ("EC0B", -15e-6),
        ],
        &[("c", TABLE_BACKLASH_RAD), ("b", TILT_BACKLASH_RAD)],
    )
}

/// Pocket NC V2-10 (thasana Eq. 8, A trunnion carrying a B table): A and B
/// axis offsets and orientation errors, backlash of both.
pub fn pocketnc_v2_10() -> Example {
    errors(
        &[
            ("EY0A", 0.015),
            ("EZ0A", -0.010),
            ("EX0B", 0.020),
            ("EZ0B", -0.012),
            ("EC0A", 20e-6),
            ("EA0B", -15e-6),
        ],
        &[("b", TABLE_BACKLASH_RAD), ("a", TILT_BACKLASH_RAD)],
    )
}
