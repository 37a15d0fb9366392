//! 4×4 homogeneous-transform machine chains with error matrices
//! (thasana-htm-nc-compensation §II-B, Eq. 3, Eq. 8). Written under issue 6.
