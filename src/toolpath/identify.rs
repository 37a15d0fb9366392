//! Radius loss (qiu Eq. 3) and identification of tA and T. Written under issue 4.
