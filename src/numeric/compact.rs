//! Numbers in error messages: a value the user gave is echoed so they can
//! find it, but `f64`'s `Display` writes every digit (1e300 as 301 of
//! them, 5e-324 as 324 decimals). [`compact`] writes at most 6 significant
//! digits, in exponent form outside 1e-4…1e6.

/// `v` with at most 6 significant digits: `2000`, `0.064`, `1e18`,
/// `4.94066e-324`, `NaN`, `inf`.
///
/// # Examples
/// ```
/// use mtmotion::numeric::compact;
/// assert_eq!(compact(2000.0), "2000");
/// assert_eq!(compact(-0.0641), "-0.0641");
/// assert_eq!(compact(1e18), "1e18");
/// assert_eq!(compact(5e-324), "4.94066e-324"); // the smallest subnormal
/// assert_eq!(compact(1.0 / 3.0), "0.333333");
/// assert_eq!(compact(f64::NAN), "NaN");
/// ```
pub fn compact(v: f64) -> String {
    if !v.is_finite() || v == 0.0 {
        return format!("{v}");
    }
    let a = v.abs();
    if (1e-4..1e6).contains(&a) {
        let digits = (5 - a.log10().floor() as i32).max(0) as usize;
        let s = format!("{v:.digits$}");
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        }
    } else {
        let s = format!("{v:.5e}");
        let (m, e) = s.split_once('e').unwrap_or((&s, "0"));
        let m = if m.contains('.') {
            m.trim_end_matches('0').trim_end_matches('.')
        } else {
            m
        };
        format!("{m}e{e}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn short_and_faithful_to_six_digits() {
        for v in [
            1.0,
            123456.0,
            0.000123456,
            -9.87654321e-7,
            1e300,
            -2.5e15,
            999999.4,
        ] {
            let s = compact(v);
            assert!(s.len() <= 13, "{v} -> {s}");
            let back: f64 = s.parse().unwrap();
            assert!((back - v).abs() <= 5e-6 * v.abs(), "{v} -> {s}");
        }
    }
}
