//! Best K_FFP per axis and torque-saturation limits (suzuki-best-kffp §4.7,
//! §5.2–5.3, Eq. 20, Fig. 21). Written under issue 3.
