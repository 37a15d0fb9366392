//! 5-axis NC compensation by inverting the HTM error model (thasana §II-D).
//! Written under issue 6.
