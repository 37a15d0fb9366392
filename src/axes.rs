//! Machine axis letters, shared by the kinematic chain, the drive errors
//! and every check that names an axis: `x y z a b c` in the order of the
//! joint vector `q` (ISO 841 names: X, Y, Z linear; A, B, C rotary about
//! them).
//!
//! Source: none (naming, not a model).

/// Axis letters in the order of the joint vector `q`.
pub const AXES: [&str; 6] = ["x", "y", "z", "a", "b", "c"];

/// Index of an axis letter (either case) in [`AXES`].
pub fn index(key: &str) -> Option<usize> {
    AXES.iter().position(|a| a.eq_ignore_ascii_case(key))
}

/// `Ok` when axis `axis` (index into [`AXES`]) is among the machine's
/// `present` letters; otherwise the reason in words, e.g. "this machine
/// has no B axis (axes: x, y, z, a, c)".
pub fn require(present: &[&str], axis: usize) -> Result<(), String> {
    if present.contains(&AXES[axis]) {
        Ok(())
    } else {
        Err(format!(
            "this machine has no {} axis (axes: {})",
            AXES[axis].to_uppercase(),
            present.join(", ")
        ))
    }
}
