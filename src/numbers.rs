//! How numbers are printed in messages and files: the shortest form that
//! reads back as the value, or a few significant digits.

/// `1e-310` as `1e-310`, `2000` as `2000`, `0.05` as `0.05`: the shortest
/// form that reads back as the value; a value that needs more than 10
/// characters (one computed rather than typed) with 5 significant digits.
pub fn num(v: f64) -> String {
    let short = exact(v);
    if short.len() > 10 {
        sig(v, 5)
    } else {
        short
    }
}

/// The shorter of `v`'s plain and scientific forms, every digit that reads
/// back as `v` (for values typed in and compared: `10.0000000001`).
pub fn exact(v: f64) -> String {
    let plain = format!("{v}");
    let sci = format!("{v:e}");
    if plain.len() <= sci.len() {
        plain
    } else {
        sci
    }
}

/// `v` to `digits` significant digits, in the shorter of plain and scientific
/// form: 4 significant digits of 23.86547 are `23.87`, of 1.2884e-16 `1.288e-16`.
pub fn sig(v: f64, digits: usize) -> String {
    let rounded: f64 = format!("{:.*e}", digits.max(1) - 1, v).parse().unwrap_or(v);
    exact(rounded)
}
