//! Tool-path motion error from NC acc/dec and servo lag
//! (qiu-toolpath-error-reverse-compensation §4-1, §4-2). Written under issue 4.

pub mod identify;
