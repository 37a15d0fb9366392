//! Macro variables: local levels, common/global variables, named
//! parameters and the system variables a simulator can know.
//!
//! Sources: the Fanuc Series 0i operator's manual, "Custom macro —
//! variables" (local #1–#33 per macro call level, common #100–#199 and
//! #500–#999, system #1000 and up, #0 always vacant, `#3000` alarm,
//! `#3006` message stop, `#4001`… modal information, `#5001`… positions),
//! and the LinuxCNC G-code reference, "Parameters" (#1–#30 local to a
//! subroutine call, #31–#5000 global, #5xxx system, `#<name>` local,
//! `#<_name>` global, predefined `#<_x>` … `#<_value>`).
//!
//! Readings chosen:
//! - Fanuc: a local or common variable never written is vacant. LinuxCNC:
//!   a numbered parameter never written is 0, and reading a named
//!   parameter never written is an error (as the control stops).
//! - Known system variables come from the interpreter's modal state:
//!   Fanuc #4001 (G0–G3 group, or the canned cycle), #4002 (plane),
//!   #4003 (G90/G91), #4006 (G20/G21), #4109 (F), #5001–#5006 and
//!   #5041–#5046 (position in program coordinates and units); LinuxCNC
//!   #5420–#5425 and `#<_x>` … `#<_c>`, `#<_feed>`, `#<_metric>`,
//!   `#<_imperial>`, `#<_absolute>`, `#<_incremental>`, `#<_value>`.
//!   Any other system variable (tool life, tool offsets, work offsets,
//!   part counters, clocks) reads as vacant (Fanuc) or 0 (LinuxCNC) with a
//!   warning naming it and its line; a write to one is ignored with a
//!   warning. Fanuc #34–#99 do not exist and are an error.

use std::collections::{HashMap, HashSet};

use super::macro_expr::VarKey;
use super::program::{Modal, Warning};

/// The variables of a running macro program.
#[derive(Debug, Clone, Default)]
pub struct Variables {
    /// LinuxCNC readings (see the module header).
    pub linuxcnc: bool,
    /// Local levels: index 0 is the main program, one more per G65 /
    /// o-call.
    levels: Vec<HashMap<VarKey, f64>>,
    /// Common (Fanuc) / global (LinuxCNC) variables, `#<_name>` included.
    globals: HashMap<VarKey, f64>,
    /// (line, variable) pairs already warned about.
    warned: HashSet<(usize, VarKey)>,
    /// The modal state the system variables read, as of the current block.
    pub modal: Modal,
    /// The line being run (for warnings).
    pub line: usize,
    /// Warnings to hand to the interpreter.
    pub warnings: Vec<Warning>,
}

/// How a numbered variable is kept.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Class {
    Null,
    Local,
    Global,
    System,
}

const INCH: f64 = 25.4;

impl Variables {
    /// Empty variables in the given dialect.
    pub fn new(linuxcnc: bool) -> Self {
        Self {
            linuxcnc,
            levels: vec![HashMap::new()],
            ..Self::default()
        }
    }

    fn class(&self, key: &VarKey) -> Result<Class, String> {
        let VarKey::Num(n) = key else {
            let VarKey::Named(name) = key else {
                return Ok(Class::Local);
            };
            return Ok(if name.starts_with('_') {
                Class::Global
            } else {
                Class::Local
            });
        };
        Ok(match (*n, self.linuxcnc) {
            (0, _) => Class::Null,
            (1..=30, true) | (1..=33, false) => Class::Local,
            (31..=5000, true) | (100..=999, false) => Class::Global,
            (34..=99, false) => {
                return Err(format!(
                    "#{n} does not exist on a Fanuc control (locals are #1–#33, commons #100–#199 and #500–#999)"
                ))
            }
            _ => Class::System,
        })
    }

    /// Starts a macro call level with `args` as its locals.
    pub fn push_level(&mut self, args: &[(u32, f64)]) {
        self.levels
            .push(args.iter().map(|&(n, v)| (VarKey::Num(n), v)).collect());
    }

    /// Ends a macro call level.
    pub fn pop_level(&mut self) {
        if self.levels.len() > 1 {
            self.levels.pop();
        }
    }

    /// True when the named parameter exists (local or global).
    pub fn exists(&self, name: &str) -> bool {
        let k = VarKey::Named(name.to_string());
        self.globals.contains_key(&k) || self.levels.last().is_some_and(|l| l.contains_key(&k))
    }

    /// Reads `key`; `None` is vacant.
    ///
    /// # Errors
    /// A variable that does not exist, a LinuxCNC named parameter that was
    /// never set.
    pub fn read(&mut self, key: &VarKey) -> Result<Option<f64>, String> {
        let v = match self.class(key)? {
            Class::Null => None,
            Class::Local => self.levels.last().and_then(|l| l.get(key).copied()),
            Class::Global => self.globals.get(key).copied(),
            Class::System => return Ok(self.system(key)),
        };
        if let (None, VarKey::Named(n)) = (v, key) {
            if let Some(v) = self.predefined(n) {
                return Ok(Some(v));
            }
            return Err(format!(
                "named parameter #<{n}> is read before it is set (LinuxCNC stops here); assign it first"
            ));
        }
        Ok(if self.linuxcnc {
            Some(v.unwrap_or(0.0))
        } else {
            v
        })
    }

    /// Writes `key` (`None`: vacant). A system variable is ignored with a
    /// warning; `#3000`/`#3006` are handled by the caller.
    ///
    /// # Errors
    /// A write to #0 or to a variable that does not exist.
    pub fn write(&mut self, key: &VarKey, v: Option<f64>) -> Result<(), String> {
        let map = match self.class(key)? {
            Class::Null => return Err("#0 is always vacant and cannot be written".into()),
            Class::Local => match self.levels.last_mut() {
                Some(l) => l,
                None => return Ok(()),
            },
            Class::Global => &mut self.globals,
            Class::System => {
                self.warn(
                    key,
                    format!("{key} is a system variable; the write is ignored (it does not change the simulated path)"),
                );
                return Ok(());
            }
        };
        match v {
            Some(v) => map.insert(key.clone(), v),
            None => map.remove(key),
        };
        Ok(())
    }

    fn warn(&mut self, key: &VarKey, message: String) {
        if self.warned.insert((self.line, key.clone())) {
            self.warnings.push(Warning {
                file: None,
                line: self.line,
                column: 1,
                message,
            });
        }
    }

    /// Program-unit scale of the current modal state.
    fn unit(&self) -> f64 {
        if self.modal.inch {
            INCH
        } else {
            1.0
        }
    }

    /// Position axis `i` in program coordinates and units (under G68 in
    /// the rotated frame, so `X#5001` names the current position).
    fn pos(&self, i: usize) -> f64 {
        let pos = match self.modal.rotation {
            Some(r) => r.pose_to_program(self.modal.pos),
            None => self.modal.pos,
        };
        let raw = pos.get(i) - self.modal.offset[i];
        if i < 3 {
            raw / self.unit()
        } else {
            raw
        }
    }

    fn system(&mut self, key: &VarKey) -> Option<f64> {
        let VarKey::Num(n) = *key else {
            return None;
        };
        let m = self.modal;
        let known = match (n, self.linuxcnc) {
            (4001 | 4201, false) => match m.cycle {
                Some(c) => Some((c.code / 10) as f64),
                None => m.motion.map(|c| f64::from(c.code())),
            },
            (4002 | 4202, false) => Some(f64::from(m.plane.code())),
            (4003 | 4203, false) => Some(if m.incremental { 91.0 } else { 90.0 }),
            (4006 | 4206, false) => Some(if m.inch { 20.0 } else { 21.0 }),
            (4109 | 4309, false) => m.feed.map(|f| f / self.unit()),
            (5001..=5006, false) => Some(self.pos((n - 5001) as usize)),
            (5041..=5046, false) => Some(self.pos((n - 5041) as usize)),
            (5420..=5425, true) => Some(self.pos((n - 5420) as usize)),
            _ => None,
        };
        if known.is_some() {
            return known;
        }
        let what = if self.linuxcnc { "0" } else { "vacant" };
        self.warn(
            key,
            format!("system variable {key} (tool, offset, counter or machine data) is not known to the simulator; it reads as {what}"),
        );
        if self.linuxcnc {
            Some(0.0)
        } else {
            None
        }
    }

    fn predefined(&self, name: &str) -> Option<f64> {
        let m = self.modal;
        let axis = ["_x", "_y", "_z", "_a", "_b", "_c"]
            .iter()
            .position(|&a| a == name);
        if let Some(i) = axis {
            return Some(self.pos(i));
        }
        let truth = |b: bool| f64::from(u8::from(b));
        Some(match name {
            "_feed" => m.feed.unwrap_or(0.0) / self.unit(),
            "_metric" => truth(!m.inch),
            "_imperial" => truth(m.inch),
            "_absolute" => truth(!m.incremental),
            "_incremental" => truth(m.incremental),
            "_value" => 0.0,
            _ => return None,
        })
    }
}
