//! Ball-bar analysis: circle fit, harmonics, ISO 230-4 circular test
//! (takayama-alignment-travel-range; ISO 230-4). Written under issue 5.
