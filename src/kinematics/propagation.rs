//! First-order error propagation through the chain (thasana Eq. 3 as
//! printed, the infinitesimal `E = I + ΔE`).
//!
//! The chain is the product of factors `M_1 … M_n` (fixed transforms,
//! location errors `E` and `E⁻¹ ≈ I − ΔE` around each joint, the joint, the
//! component errors `E(q)`, the tool error `E_ST`). To first order
//! `T = T₀ + Σ_k M_1…M_{k−1} · ΔM_k · M_{k+1}…M_n`, with `ΔM = ΔE` for an
//! error factor and `ΔM = ∂J/∂q · q₀` for a joint with zero-position error
//! `q₀`. It is written with 4×4 HTMs (nalgebra `Matrix4`), independently of
//! the compiled forward kinematics, which it must match to second order.
//!
//! [`sensitivity`] is the first-order change of the pose per unit error
//! parameter (mm/mm, mm/rad), used for the cone-frustum sensitivity
//! coefficients.
//!
//! Units: mm, rad.

use nalgebra::{Matrix3, Matrix4, Vector4};

use super::chain::{Chain, JointKind};
use super::errors::{parse_symbol, GeometricErrors};
use super::forward::Pose;
use super::htm::{error_matrix_linear, rot, rot_xyz, Affine, Dir};
use super::KinematicsError;

fn joint(kind: JointKind, dir: Dir, v: f64) -> Matrix4<f64> {
    match kind {
        JointKind::Linear => {
            let mut m = Matrix4::identity();
            m[(dir.index(), 3)] = v;
            m
        }
        JointKind::Rotary => Affine::rotation(rot(dir, v)).to_matrix4(),
    }
}

fn djoint(kind: JointKind, dir: Dir, v: f64) -> Matrix4<f64> {
    let mut m = Matrix4::zeros();
    match kind {
        JointKind::Linear => m[(dir.index(), 3)] = 1.0,
        JointKind::Rotary => {
            // dR/dv = R(v)·[u]×
            let u = dir.unit();
            let skew = Matrix3::new(0.0, -u.z, u.y, u.z, 0.0, -u.x, -u.y, u.x, 0.0);
            m.fixed_view_mut::<3, 3>(0, 0)
                .copy_from(&(rot(dir, v) * skew));
        }
    }
    m
}

/// The nominal pose and its first-order change for `errors`.
///
/// # Units
/// `q` in mm and rad; `tool_length` mm.
///
/// # Examples
/// ```
/// use mtmotion::kinematics::{forward, propagation::first_order, GeometricErrors};
/// let chain = mtmotion::machine::preset("trunnion-ac").unwrap().kinematics.unwrap();
/// let mut e = GeometricErrors::default();
/// e.location.insert("EB0C".into(), 2e-6);
/// let q = [30.0, -20.0, 10.0, 0.5, 0.0, 1.2];
/// let exact = forward(&chain, &q, &e, 50.0).unwrap();
/// let lin = first_order(&chain, &q, &e, 50.0).unwrap();
/// assert!((0..3).all(|i| (exact.position[i] - lin.position[i]).abs() < 1e-9));
/// ```
pub fn first_order(
    chain: &Chain,
    q: &[f64; 6],
    errors: &GeometricErrors,
    tool_length: f64,
) -> Result<Pose, KinematicsError> {
    chain.validate()?;
    let per_axis = errors.resolve(chain)?;
    // Factors with their first-order deltas.
    let mut m: Vec<Matrix4<f64>> = Vec::new();
    let mut d: Vec<Matrix4<f64>> = Vec::new();
    let id = Matrix4::identity();
    let mut push = |mm: Matrix4<f64>, dd: Matrix4<f64>| {
        m.push(mm);
        d.push(dd);
    };
    for link in &chain.links {
        let mut fixed = Affine::rotation(rot_xyz(link.rotation)).to_matrix4();
        fixed[(0, 3)] = link.translation[0];
        fixed[(1, 3)] = link.translation[1];
        fixed[(2, 3)] = link.translation[2];
        push(fixed, Matrix4::zeros());
        let Some(j) = &link.joint else { continue };
        let qi = Chain::axis_index(&j.axis).unwrap_or(0);
        let ae = &per_axis[qi];
        let de = error_matrix_linear(&ae.location) - id;
        push(id, de);
        let v = j.sign * q[qi];
        push(
            joint(j.kind, j.dir, v),
            djoint(j.kind, j.dir, v) * (j.sign * ae.zero),
        );
        push(id, -de);
        push(id, error_matrix_linear(&ae.component_at(q[qi])) - id);
    }
    push(id, error_matrix_linear(&errors.tool) - id);
    let n = m.len();
    let mut prefix = vec![id; n + 1];
    for i in 0..n {
        prefix[i + 1] = prefix[i] * m[i];
    }
    let mut suffix = vec![id; n + 1];
    for i in (0..n).rev() {
        suffix[i] = m[i] * suffix[i + 1];
    }
    let mut t = prefix[n];
    for i in 0..n {
        if d[i] != Matrix4::zeros() {
            t += prefix[i] * d[i] * suffix[i + 1];
        }
    }
    let axis = chain.tool_axis;
    let tip = Vector4::new(
        chain.tool_point[0] - axis[0] * tool_length,
        chain.tool_point[1] - axis[1] * tool_length,
        chain.tool_point[2] - axis[2] * tool_length,
        1.0,
    );
    let p = t * tip;
    let k = t * Vector4::new(axis[0], axis[1], axis[2], 0.0);
    Ok(Pose {
        position: [p.x, p.y, p.z],
        orientation: [k.x, k.y, k.z],
    })
}

/// First-order change of the pose per unit of the error `symbol` (an ISO
/// location or constant component symbol, e.g. `EX0C`, `EBC`):
/// `[dx, dy, dz, di, dj, dk]` per mm or per rad.
///
/// # Units
/// `q` in mm and rad; result mm/mm or mm/rad (position) and 1/mm or 1/rad
/// (orientation).
///
/// # Examples
/// ```
/// use mtmotion::kinematics::propagation::sensitivity;
/// let chain = mtmotion::machine::preset("trunnion-ac").unwrap().kinematics.unwrap();
/// // An X offset of the C axis moves the tool relative to the work by
/// // (1 − cos c) in x and −sin c in y… per mm: at c = 90° that is (1, −1).
/// let q = [0.0, 0.0, 0.0, 0.0, 0.0, std::f64::consts::FRAC_PI_2];
/// let s = sensitivity(&chain, &q, 0.0, "EX0C").unwrap();
/// assert!((s[0] - 1.0).abs() < 1e-12 && (s[1] + 1.0).abs() < 1e-12);
/// ```
pub fn sensitivity(
    chain: &Chain,
    q: &[f64; 6],
    tool_length: f64,
    symbol: &str,
) -> Result<[f64; 6], KinematicsError> {
    let s = parse_symbol(symbol).ok_or_else(|| KinematicsError::BadError {
        key: symbol.to_string(),
        why: "expected an ISO 230 error symbol such as EX0C or EBX".into(),
    })?;
    let mut e = GeometricErrors::default();
    let name = super::errors::symbol_name(s);
    if s.location {
        e.location.insert(name, 1.0);
    } else {
        e.component
            .insert(name, super::errors::Coeffs::Constant(1.0));
    }
    let base = first_order(chain, q, &GeometricErrors::default(), tool_length)?;
    let one = first_order(chain, q, &e, tool_length)?;
    let mut out = [0.0; 6];
    for i in 0..3 {
        out[i] = one.position[i] - base.position[i];
        out[i + 3] = one.orientation[i] - base.orientation[i];
    }
    Ok(out)
}
