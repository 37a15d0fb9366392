//! Table-on-table B–C 5-axis machine like the DMG MORI NMV5000: a C rotary
//! table carried by a B tilting cradle, X, Y, Z in the column and head.
//!
//! Chain, workpiece → tool: C table (rotation about z through the origin,
//! the centre of the table face) · B cradle (the B axis, about y, 100 mm
//! below the table face) · bed (back up 100 mm) · X · Y · Z · spindle. At
//! q = 0 the tool tip is at the centre of the table face, with the tool
//! axis along +z.
//!
//! Readings chosen: the 100 mm table-face height over the B axis is an
//! illustrative value (suzuki gives no geometry); the limits are the
//! NMV5000's catalogue travels (X 730, Y 510, Z 510 mm, B −10…110°,
//! C continuous, here ±360°). The feed-drive parameters are suzuki Table 1
//! (X, Y, C); Z copies Y and B copies C, because the paper identifies only
//! X, Y and C.

use super::Machine;
use crate::kinematics::htm::Dir;
use crate::kinematics::Chain;

/// Height of the table face over the B axis, mm.
pub const TABLE_HEIGHT: f64 = 100.0;

/// The chain.
pub fn chain() -> Chain {
    super::tilting_table_chain("B cradle", "b", Dir::Y, TABLE_HEIGHT)
}

/// The preset.
pub fn machine() -> Machine {
    let example = super::example_errors::table_on_table_bc();
    let base = super::nmv5000::machine();
    let mut axes = base.axes.clone();
    if let (Some(y), Some(c)) = (base.axes.get("y"), base.axes.get("c")) {
        axes.insert("z".into(), y.clone());
        axes.insert("b".into(), c.clone());
    }
    super::FiveAxis {
        name: "table-on-table-bc",
        description: "Table-on-table B–C 5-axis machining centre like the NMV5000: C table on a B cradle",
        source: "chain: NMV5000 layout (table-on-table B–C, as in takayama-alignment-travel-range); feed drives suzuki-best-kffp Table 1 (Z copies Y, B copies C); limits: NMV5000 catalogue travels",
        axes,
        limits: [
            ("x", [-365.0, 365.0]),
            ("y", [-255.0, 255.0]),
            ("z", [-150.0, 360.0]),
            ("b", [-10.0, 110.0]),
            ("c", [-360.0, 360.0]),
        ],
        chain: chain(),
        example,
    }
    .machine()
}
