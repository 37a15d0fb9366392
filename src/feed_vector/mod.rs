//! The constant-feed-speed-vector test (suzuki-best-kffp §2.3, §4.1–4.2,
//! Eqs. 1–11). Written under issue 3.
