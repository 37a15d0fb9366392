//! Exact frequency response of the feed drive (suzuki-best-kffp Eqs. 12–19).
//! Written under issue 3.
