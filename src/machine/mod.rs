//! Machine presets as data. Every preset is a JSON-serialisable struct that
//! cites its source; `machinePreset(name)` in JS returns one of these.
//!
//! Presets are looked up by name with [`preset`]; [`names`] lists them.

pub mod example_errors;
mod nmv5000;
pub mod paper_sweep;
mod pocketnc_v2_10;
mod table_on_table_bc;
mod trunnion_ac;

/// Chain of a C rotary table carried by a tilting axis (`tilt`, e.g. "a"
/// about x or "b" about y) whose axis lies `table_height` mm below the
/// table face, then X, Y, Z in the column and head; workpiece → tool. At
/// q = 0 the tool tip is at the centre of the table face, tool axis +z.
fn tilting_table_chain(
    tilt_name: &str,
    tilt: &str,
    tilt_dir: crate::kinematics::htm::Dir,
    table_height: f64,
) -> crate::kinematics::Chain {
    use crate::kinematics::htm::Dir;
    use crate::kinematics::{Chain, Link};
    Chain {
        links: vec![
            Link::rotary("C table", [0.0; 3], "c", Dir::Z),
            Link::rotary(tilt_name, [0.0, 0.0, -table_height], tilt, tilt_dir),
            Link::linear("X", [0.0, 0.0, table_height], "x", Dir::X),
            Link::linear("Y", [0.0; 3], "y", Dir::Y),
            Link::linear("Z head", [0.0; 3], "z", Dir::Z),
        ],
        tool_point: [0.0; 3],
        tool_axis: [0.0, 0.0, 1.0],
    }
}

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use crate::kinematics::{Chain, GeometricErrors};
use crate::servo::transmission::DriveErrors;
use crate::servo::AxisParams;

/// Errors of the preset registry.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MachineError {
    /// No preset has this name.
    #[error("unknown machine preset '{name}'; known presets: {known}")]
    UnknownPreset {
        /// The name asked for.
        name: String,
        /// The known names, comma-separated.
        known: String,
    },
    /// The preset has no loop reading of this name.
    #[error(
        "machine '{}' has no loop reading '{}'; known readings: {known}",
        crate::budget::clip(machine, 40),
        crate::budget::clip(reading, 40)
    )]
    UnknownReading {
        /// The preset's name.
        machine: String,
        /// The reading asked for.
        reading: String,
        /// The known readings, comma-separated ("none" when the preset has none).
        known: String,
    },
    /// The machine has no kinematic chain.
    #[error("machine '{}' has no kinematic chain (`kinematics`); use pocketnc-v2-10, table-on-table-bc or trunnion-ac, or describe its links", crate::budget::clip(name, 40))]
    NoChain {
        /// The machine's name.
        name: String,
    },
}

/// A machine: its feed-drive axes (servo parameters) and travel limits.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase", deny_unknown_fields)]
pub struct Machine {
    /// Preset name, e.g. `nmv5000`.
    pub name: String,
    /// One line on what the machine is.
    pub description: String,
    /// Where the numbers come from (paper, table, section).
    pub source: String,
    /// Feed-drive parameters per axis, keyed by lower-case axis letter.
    pub axes: BTreeMap<String, AxisParams>,
    /// Travel limits per axis: mm for linear axes, degrees for rotary axes.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub limits: BTreeMap<String, [f64; 2]>,
    /// The kinematic chain, workpiece to tool (thasana Eq. 8 style), for the
    /// 5-axis models; absent for machines described by their drives only.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub kinematics: Option<Chain>,
    /// Illustrative geometric errors for the page's "Load example errors"
    /// (typical ISO 230-7 location errors, see [`example_errors`]); not
    /// measured values of this machine.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub example_errors: Option<GeometricErrors>,
    /// Illustrative drive errors to go with them (worm-gear backlash, see
    /// [`example_errors`]); not measured values of this machine.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub example_drives: Option<DriveErrors>,
    /// The conditions a paper ran on this machine and the values it quotes
    /// (see [`paper_sweep`]); absent when no paper tests the preset so.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub paper_sweep: Option<paper_sweep::PaperSweep>,
    /// Names of the readings `torqueSaturation` accepts for this machine
    /// (first = default; see [`crate::best_kffp::saturation`]); empty when
    /// the machine has no torque-limited rotary axis of the feed-vector test.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub saturation_readings: Vec<String>,
    /// Names of the readings of the paper's loop parameters that
    /// [`preset_with_reading`] accepts (first = default, the preset as
    /// returned by [`preset`]); empty when the preset has none.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub loop_readings: Vec<String>,
}

type Builder = fn() -> Machine;

/// The registry: name and builder of every preset.
const PRESETS: &[(&str, Builder)] = &[
    ("nmv5000", nmv5000::machine),
    ("pocketnc-v2-10", pocketnc_v2_10::machine),
    ("table-on-table-bc", table_on_table_bc::machine),
    ("trunnion-ac", trunnion_ac::machine),
];

/// The presets whose C axis the torque-saturation limit is read on (those
/// with `saturation_readings`); the embed module's `torqueSaturation` looks
/// its machine up here only, so it links no other preset.
const SATURATION_PRESETS: &[(&str, Builder)] = &[("nmv5000", nmv5000::machine)];

/// Names of all presets, in registry order.
pub fn names() -> Vec<&'static str> {
    PRESETS.iter().map(|(n, _)| *n).collect()
}

/// The description of one 5-axis preset (the page's kinematics machines).
struct FiveAxis<'a> {
    name: &'a str,
    description: &'a str,
    source: &'a str,
    axes: BTreeMap<String, AxisParams>,
    /// Travel limits per axis letter: mm, or degrees for rotary axes.
    limits: [(&'a str, [f64; 2]); 5],
    chain: Chain,
    example: example_errors::Example,
}

impl FiveAxis<'_> {
    /// The preset: its chain, limits and illustrative example errors; no
    /// paper sweep and no readings.
    fn machine(self) -> Machine {
        Machine {
            name: self.name.into(),
            description: self.description.into(),
            source: self.source.into(),
            axes: self.axes,
            limits: self.limits.iter().map(|(k, v)| ((*k).into(), *v)).collect(),
            kinematics: Some(self.chain),
            example_errors: Some(self.example.0),
            example_drives: Some(self.example.1),
            paper_sweep: None,
            saturation_readings: Vec::new(),
            loop_readings: Vec::new(),
        }
    }
}

/// The preset called `name`.
///
/// # Examples
/// ```
/// let m = mtmotion::machine::preset("nmv5000").unwrap();
/// assert!((m.axes["c"].torque_max.unwrap() - 725.0).abs() < 1e-12);
/// let err = mtmotion::machine::preset("nope").unwrap_err().to_string();
/// assert!(err.contains("nmv5000"));
/// ```
pub fn preset(name: &str) -> Result<Machine, MachineError> {
    lookup(PRESETS, name)
}

/// The preset called `name` among those with a torque-saturation reading
/// (`saturation_readings` not empty): the same machine as [`preset`] gives,
/// and an error listing only those names for any other.
///
/// # Examples
/// ```
/// let m = mtmotion::machine::saturation_preset("NMV5000").unwrap();
/// assert_eq!(m, mtmotion::machine::preset("nmv5000").unwrap());
/// let err = mtmotion::machine::saturation_preset("trunnion-ac").unwrap_err().to_string();
/// assert!(err.contains("known presets: nmv5000"), "{err}");
/// ```
pub fn saturation_preset(name: &str) -> Result<Machine, MachineError> {
    lookup(SATURATION_PRESETS, name)
}

/// The preset of `registry` called `name` (trimmed, any case).
fn lookup(registry: &[(&str, Builder)], name: &str) -> Result<Machine, MachineError> {
    let wanted = name.trim().to_ascii_lowercase();
    registry
        .iter()
        .find(|(n, _)| *n == wanted)
        .map(|(_, build)| build())
        .ok_or_else(|| MachineError::UnknownPreset {
            // a message quotes at most about 60 characters of the input
            name: crate::budget::clip(name, 60),
            known: registry
                .iter()
                .map(|(n, _)| *n)
                .collect::<Vec<_>>()
                .join(", "),
        })
}

/// The preset called `name` under its loop reading `reading` (one of its
/// `loop_readings`; see the preset's module, e.g. nmv5000's Kpp and X
/// inertia readings).
///
/// # Examples
/// ```
/// use mtmotion::machine::{preset, preset_with_reading};
/// let m = preset_with_reading("nmv5000", "kppText").unwrap();
/// assert_eq!(m.axes["x"].kpp, 30.0);
/// assert_eq!(preset_with_reading("nmv5000", "table").unwrap(), preset("nmv5000").unwrap());
/// let e = preset_with_reading("nmv5000", "nope").unwrap_err().to_string();
/// assert!(e.contains("'nope'") && e.contains("kppText"), "{e}");
/// ```
pub fn preset_with_reading(name: &str, reading: &str) -> Result<Machine, MachineError> {
    let m = preset(name)?;
    if m.name == "nmv5000" {
        return nmv5000::with_loop_reading(reading.trim());
    }
    Err(MachineError::UnknownReading {
        machine: m.name,
        reading: reading.to_string(),
        known: "none".into(),
    })
}

/// A machine given by preset name or described in full. Read from a
/// string (a preset name) or an object (a description); anything else is
/// refused in those words (not serde's "untagged enum").
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
#[serde(untagged)]
pub enum MachineRef {
    /// A preset name, e.g. `trunnion-ac`.
    Name(String),
    /// A full description (e.g. an edited preset).
    Spec(Box<Machine>),
}

impl<'de> Deserialize<'de> for MachineRef {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Either;
        impl<'de> serde::de::Visitor<'de> for Either {
            type Value = MachineRef;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a preset name or a machine description { name, axes, … }")
            }
            fn visit_str<E: serde::de::Error>(self, s: &str) -> Result<MachineRef, E> {
                Ok(MachineRef::Name(s.to_string()))
            }
            fn visit_map<A: serde::de::MapAccess<'de>>(
                self,
                map: A,
            ) -> Result<MachineRef, A::Error> {
                let m = Machine::deserialize(serde::de::value::MapAccessDeserializer::new(map))?;
                Ok(MachineRef::Spec(Box::new(m)))
            }
        }
        d.deserialize_any(Either)
    }
}

impl MachineRef {
    /// The machine, and its chain.
    pub fn resolve(&self) -> Result<(Machine, Chain), MachineError> {
        let m = match self {
            MachineRef::Name(n) => preset(n)?,
            MachineRef::Spec(m) => (**m).clone(),
        };
        let chain = m.kinematics.clone().ok_or_else(|| MachineError::NoChain {
            name: m.name.clone(),
        })?;
        Ok((m, chain))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_preset_is_valid_and_cites_a_source() {
        for name in names() {
            let m = preset(name).unwrap();
            assert_eq!(m.name, name);
            assert!(!m.source.is_empty());
            for (axis, p) in &m.axes {
                p.validate()
                    .unwrap_or_else(|e| panic!("{name}.{axis}: {e}"));
            }
        }
    }

    #[test]
    fn the_saturation_presets_are_the_presets_with_saturation_readings() {
        let with_readings: Vec<&str> = names()
            .into_iter()
            .filter(|n| !preset(n).unwrap().saturation_readings.is_empty())
            .collect();
        let listed: Vec<&str> = SATURATION_PRESETS.iter().map(|(n, _)| *n).collect();
        assert_eq!(listed, with_readings);
        for name in listed {
            assert_eq!(saturation_preset(name).unwrap(), preset(name).unwrap());
        }
    }

    #[test]
    fn unknown_name_lists_known_names() {
        let e = preset("dmu50").unwrap_err().to_string();
        assert!(e.contains("'dmu50'") && e.contains("nmv5000"), "{e}");
    }
}
