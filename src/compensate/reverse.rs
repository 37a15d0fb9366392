//! Reverse compensation of the NC program (qiu §4-3(2)). Written under issue 4.
