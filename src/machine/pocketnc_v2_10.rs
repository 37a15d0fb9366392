//! Pocket NC V2-10 mini 5-axis milling machine: the chain of
//! thasana-htm-nc-compensation Eq. 8 with the d-parameters of §II-D.
//!
//! Eq. 8, workpiece → tool:
//! `A²(d1y)A⁵(γ)E_BA · A¹(d2x)A⁴(α)E_AY · A²(d2y)A¹(d3x)A²(d3y)E_YX ·
//! A³(d3z)A³(d4z)A¹(d4x)A²(d4y)E_XZ · A³(d5z)A²(d5y)A³(d6z)E_ZS · A⁶(θ)E_ST · r_e`.
//!
//! Readings chosen (the printed Eq. 8 has no factor for the X, Y and Z
//! motions): the Y, X and Z joints sit in the links that end with `E_YX`,
//! `E_XZ` and `E_ZS` (B, A and Y carry the workpiece; X and Z the spindle).
//! Translations commute, so where the joint sits among the pure
//! translations of its link does not matter. `d7z = −76 mm`, listed in
//! §II-D but absent from Eq. 8, is the tool point `r_e = (0, 0, d7z)`. The
//! spindle rotation `A⁶(θ)` does not move a point on the tool axis and is
//! left out. The component errors of each axis are the `E` after its joint
//! (`E_BA` for B, `E_AY` for A, `E_YX` for Y, `E_XZ` for X, `E_ZS` for Z),
//! `E_ST` is the `tool` error.
//!
//! Limits: not in the paper; the maker's published travels (X 4.5 in,
//! Y 5 in, Z 3.5 in, A −25…135°, B continuous, here ±360°), placed so that
//! the workpiece origin and the S part 12 mm below it are reachable. No servo parameters (the paper's PID
//! model is a Simulink block without physical values): cone-frustum tests
//! on this machine need `idealServo`.

use std::collections::BTreeMap;

use super::Machine;
use crate::kinematics::htm::Dir;
use crate::kinematics::{Chain, Link};

const D1Y: f64 = -21.1734;
const D2X: f64 = 75.0;
const D2Y: f64 = 21.1734;
const D3X: f64 = 1.0;
const D3Y: f64 = -44.823;
const D3Z: f64 = 20.455;
const D4Z: f64 = 161.76;
const D4X: f64 = -12.5;
const D4Y: f64 = 50.99;
const D5Z: f64 = 29.05;
const D5Y: f64 = 57.333;
const D6Z: f64 = -53.7;
const D7Z: f64 = -76.0;

/// The chain of Eq. 8.
pub fn chain() -> Chain {
    Chain {
        links: vec![
            Link::rotary("B table (A²(d1y) A⁵(γ) E_BA)", [0.0, D1Y, 0.0], "b", Dir::Y),
            Link::rotary(
                "A trunnion (A¹(d2x) A⁴(α) E_AY)",
                [D2X, 0.0, 0.0],
                "a",
                Dir::X,
            ),
            Link::linear(
                "Y carriage (A²(d2y) A¹(d3x) A²(d3y) E_YX)",
                [D3X, D2Y + D3Y, 0.0],
                "y",
                Dir::Y,
            ),
            Link::linear(
                "X carriage (A³(d3z) A³(d4z) A¹(d4x) A²(d4y) E_XZ)",
                [D4X, D4Y, D3Z + D4Z],
                "x",
                Dir::X,
            ),
            Link::linear(
                "Z head (A³(d5z) A²(d5y) A³(d6z) E_ZS)",
                [0.0, D5Y, D5Z + D6Z],
                "z",
                Dir::Z,
            ),
        ],
        tool_point: [0.0, 0.0, D7Z],
        tool_axis: [0.0, 0.0, 1.0],
    }
}

/// The preset.
pub fn machine() -> Machine {
    let example = super::example_errors::pocketnc_v2_10();
    super::FiveAxis {
        name: "pocketnc-v2-10",
        description: "Pocket NC V2-10 mini 5-axis mill: B table on an A trunnion, Y under the work, X and Z in the head",
        source: "thasana-htm-nc-compensation Eq. 8 and §II-D (d-parameters); travel limits from the maker's specification",
        axes: BTreeMap::new(),
        limits: [
            ("x", [-114.3, 0.0]),
            ("y", [-127.0, 0.0]),
            ("z", [-110.0, -21.1]),
            ("a", [-25.0, 135.0]),
            ("b", [-360.0, 360.0]),
        ],
        chain: chain(),
        example,
    }
    .machine()
}
