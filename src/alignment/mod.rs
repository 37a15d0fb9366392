//! Rotary-axis alignment from partial-range ball-bar traces
//! (takayama-alignment-travel-range §2–4). Written under issue 5.
