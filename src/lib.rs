//! # mtmotion — a motion-accuracy workbench for CNC machining centres
//!
//! Predicts, diagnoses and compensates the motion errors of machining
//! centres, above all 5-axis ones. The core is plain Rust (units: mm, s, rad,
//! N·m, kg·m²); `wasm` is a thin binding layer compiled for `wasm32` only.
//!
//! The catalogue — one line per model, with its source (full citations in
//! `docs/references.md`):
//!
//! | module | model | source |
//! |---|---|---|
//! | [`servo`] | cascaded feed drive with Pre-Control, saturation, backlash, worm gear | suzuki-best-kffp Fig. 11, 18, Table 1; kato Eq. 1 |
//! | [`servo::response`] | exact frequency response, ΔR, α, β | suzuki Eqs. 12–19 |
//! | [`servo::simulate`] | fixed-step time simulation with saturation | suzuki Fig. 18 |
//! | [`feed_vector`] | constant-feed-speed-vector test and its trace analysis | suzuki §2.3, §4.1–4.2, Eqs. 1–11 |
//! | [`best_kffp`] | Best K_FFP per axis; torque-saturation limits | suzuki §4.7, §5.2–5.3, Eq. 20, Fig. 21 |
//! | [`toolpath`] | NC acc/dec + first-order servo lag, contour error | qiu §4-1, §4-2, Eqs. 1–2 |
//! | [`toolpath::identify`] | radius loss Eq. 3 and identification of tA, T | qiu Eq. 3 |
//! | [`compensate::reverse`] | reverse compensation of the NC program | qiu §4-3(2) |
//! | [`compensate::nc5`] | 5-axis NC compensation by inverting the HTM error model | thasana §II-D |
//! | [`ballbar`] | circle fit, harmonics, ISO 230-4 circular test | takayama; ISO 230-4 |
//! | [`alignment`] | rotary-axis offset and angle from partial-range traces | takayama §2–4 |
//! | [`kinematics`] | 4×4 HTM chains with error matrices, FK and IK | thasana §II-B, Eq. 3, Eq. 8; kato |
//! | [`cone_frustum`] | ISO 10791-6 cone-frustum ball-bar test | kato |
//! | [`machine`] | machine presets as data, each citing its source | suzuki Table 1; thasana §II-D |
//! | [`nc`] | NC program lexer, interpreter (G0–G3, G4, G17–G19, G90/G91, G20/G21, modal F, A/B/C) and writer | RS-274 / ISO 6983 |
//! | [`trace`] | CSV/TSV trace import with line- and column-naming errors | — |
//! | [`budget`] | work budgets: the most text, samples, harmonics and points one call may take | — |
//! | [`numeric`] | shared kernels: Brent, Levenberg–Marquardt, angle wrap | Brent 1973; Marquardt 1963 |
//! | `wasm` | the JS binding layer (wasm32 only) | — |

pub mod alignment;
pub mod axes;
pub mod ballbar;
pub mod best_kffp;
pub mod budget;
pub mod compensate;
pub mod cone_frustum;
pub mod feed_vector;
pub mod kinematics;
pub mod machine;
pub mod nc;
pub mod numeric;
pub mod servo;
pub mod toolpath;
pub mod trace;

#[cfg(target_arch = "wasm32")]
pub mod wasm;
