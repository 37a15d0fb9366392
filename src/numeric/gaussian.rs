//! A deterministic standard-normal sequence (xorshift64 then Box–Muller):
//! the same numbers natively and in wasm for a seed, so tests and
//! synthetic traces with gaussian noise are reproducible.
//!
//! Units: none (mean 0, standard deviation 1).

/// `n` standard-normal numbers from `seed` (any seed, 0 included).
///
/// # Examples
/// ```
/// use mtmotion::numeric::gaussian;
/// let g = gaussian(7, 20_000);
/// let mean = g.iter().sum::<f64>() / g.len() as f64;
/// let var = g.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / g.len() as f64;
/// assert!(mean.abs() < 0.03 && (var - 1.0).abs() < 0.03);
/// assert_eq!(g, gaussian(7, 20_000));
/// assert_ne!(g[..5], gaussian(8, 5)[..]);
/// ```
pub fn gaussian(seed: u64, n: usize) -> Vec<f64> {
    let mut s = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
    let mut u = move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        ((s >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    };
    (0..n)
        .map(|_| (-2.0 * u().ln()).sqrt() * (std::f64::consts::TAU * u()).cos())
        .collect()
}
