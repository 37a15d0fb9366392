//! Fixed-step time simulation of the feed drive with saturation
//! (suzuki-best-kffp Fig. 18). Written under issue 3.
