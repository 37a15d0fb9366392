//! Trunnion A–C 5-axis machine like the one of kato-cone-frustum-ballbar: a
//! C rotary table on an A tilting trunnion, both worm-gear driven (kato
//! Fig. 2(b)), X, Y, Z ball-screw axes.
//!
//! Chain, workpiece → tool: C table (about z through the origin, the centre
//! of the table face) · A trunnion (about x, 50 mm below the table face) ·
//! bed · X · Y · Z · spindle. At q = 0 the tool tip is at the table centre,
//! tool axis +z.
//!
//! Readings chosen: kato gives no geometry or servo numbers. The 50 mm
//! table height and the limits (X ±300, Y ±250, Z −200…400 mm,
//! A −30…120°, C ±360°) are illustrative. The feed drives copy suzuki
//! Table 1 (linear axes: X; rotary axes: C) and are marked as such in
//! `source`; worm-gear ratio, backlash and pitch error are set per test
//! through `drives.backlash` / `drives.pitchError`.

use std::collections::BTreeMap;

use super::Machine;
use crate::kinematics::htm::Dir;
use crate::kinematics::Chain;

/// Height of the table face over the A axis, mm.
pub const TABLE_HEIGHT: f64 = 50.0;

/// The chain.
pub fn chain() -> Chain {
    super::tilting_table_chain("A trunnion", "a", Dir::X, TABLE_HEIGHT)
}

/// The preset.
pub fn machine() -> Machine {
    let example = super::example_errors::trunnion_ac();
    let base = super::nmv5000::machine();
    let mut axes = BTreeMap::new();
    if let (Some(x), Some(c)) = (base.axes.get("x"), base.axes.get("c")) {
        for l in ["x", "y", "z"] {
            axes.insert(l.to_string(), x.clone());
        }
        for r in ["a", "c"] {
            axes.insert(r.to_string(), c.clone());
        }
    }
    super::FiveAxis {
        name: "trunnion-ac",
        description: "Trunnion A–C 5-axis machining centre like kato's: C table on an A trunnion",
        source: "layout: kato-cone-frustum-ballbar §2 (A and C worm-gear axes); geometry and limits illustrative; feed drives copied from suzuki-best-kffp Table 1 (X for linear, C for rotary axes)",
        axes,
        limits: [
            ("x", [-300.0, 300.0]),
            ("y", [-250.0, 250.0]),
            ("z", [-200.0, 400.0]),
            ("a", [-30.0, 120.0]),
            ("c", [-360.0, 360.0]),
        ],
        chain: chain(),
        example,
    }
    .machine()
}
