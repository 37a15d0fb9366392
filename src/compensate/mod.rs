//! Compensation of NC programs: reverse compensation of tool-path motion
//! error (qiu §4-3(2)) and 5-axis geometric-error compensation (thasana §II-D).

pub mod nc5;
pub mod reverse;
