//! Profile analysis: spectral moments of a measured profile or height map
//! and the Greenwood-Williamson parameters of the surface after McCool (1986)
//! and Nayak (1971).
//!
//! m0 = ⟨z²⟩, m2 = ⟨z'²⟩, m4 = ⟨z''²⟩ (the moments of the profile's power
//! spectrum, Nayak 1971 eq. 2), by finite differences at the sampling
//! interval Δ: z' ≈ (z_{i+1} − z_i)/Δ, z'' ≈ (z_{i+1} − 2z_i + z_{i−1})/Δ².
//! For a harmonic of wavenumber k these give k² sinc²(kΔ/2) and
//! k⁴ sinc⁴(kΔ/2) instead of k² and k⁴: m2 and m4 are low by at most
//! (kΔ)²/12 and (kΔ)²/6 relative for the shortest resolved wavelength.
//!
//! The summit parameters of an isotropic Gaussian surface from the profile
//! moments (McCool 1986, Wear 107, eqs. 4-6 as usually quoted; Nayak 1971):
//! bandwidth α = m0 m4 / m2², summit density η = m4 / (6π√3 m2),
//! summit radius β = 0.375 √(π/m4), summit height standard deviation
//! σ_s = √((1 − 0.8968/α) m0).

use crate::error::{Error, Result};

/// How the profile is levelled before the moments.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Detrend {
    /// Subtract the mean.
    Mean,
    /// Subtract the least-squares line (line profile) or plane (areal map).
    Linear,
}

/// A height record at spacing Δ: one line (`cols` = length, `rows` = 1) or a
/// grid of `rows` × `cols` (row-major).
#[derive(Clone, Debug)]
pub struct Heights {
    pub z: Vec<f64>,
    pub rows: usize,
    pub cols: usize,
    /// Sampling interval Δ (mm), the same in both directions of a grid.
    pub sampling: f64,
}

/// Spectral moments of a record.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Moments {
    /// ⟨z²⟩, mm².
    pub m0: f64,
    /// ⟨z'²⟩ (dimensionless).
    pub m2: f64,
    /// ⟨z''²⟩, 1/mm².
    pub m4: f64,
}

/// Greenwood-Williamson parameters from the moments (McCool 1986).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Summits {
    /// Bandwidth α = m0 m4 / m2².
    pub alpha: f64,
    /// η, summits per mm².
    pub density: f64,
    /// β, mm.
    pub radius: f64,
    /// σ_s, mm.
    pub sigma: f64,
}

/// Largest height magnitude read, mm: the case file's coordinate range (1 km).
pub(crate) const MAX_HEIGHT: f64 = crate::input::case::ranges::COORDINATE.hi;

/// The rms height left after removing the least-squares line or plane, below
/// which (relative to the largest height) a record is flat: the round-off of
/// the levelling is a few 1e-16 of the heights.
pub(crate) const FLAT: f64 = 1e-12;

/// The lines of `text`, ended by LF, CRLF or a lone CR (Unix, Windows and
/// old Mac spreadsheet exports), without their ends.
fn lines(text: &str) -> impl Iterator<Item = &str> {
    let mut rest = text;
    std::iter::from_fn(move || {
        if rest.is_empty() {
            return None;
        }
        let (line, next) = match rest.find(['\n', '\r']) {
            None => (rest, ""),
            Some(i) => {
                let end = if rest[i..].starts_with("\r\n") { 2 } else { 1 };
                (&rest[..i], &rest[i + end..])
            }
        };
        rest = next;
        Some(line)
    })
}

/// Reads heights from text: numbers separated by commas, semicolons, spaces or
/// tabs (not other white space: a no-break space as a thousands separator is
/// refused, not read as two heights); `#` starts a comment; lines end in LF,
/// CRLF or CR and a leading byte-order mark is skipped (a spreadsheet's CSV
/// export). A line profile takes
/// every number in order; an areal map takes one grid row per non-empty line
/// (all rows equally long). Heights must be finite, not subnormal and at most
/// `MAX_HEIGHT` in magnitude.
pub fn parse(text: &str, place: &str, areal: bool, sampling: f64) -> Result<Heights> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut z = Vec::new();
    let mut rows = 0;
    let mut cols = 0;
    for (n, line) in lines(text).enumerate() {
        let body = line.split('#').next().unwrap_or("");
        // an empty cell between two separators is a missing sample (a
        // trailing separator at the end of a line is not)
        let fields: Vec<&str> = body.trim_end().split([',', ';']).collect();
        if fields.len() > 1
            && fields[..fields.len() - 1]
                .iter()
                .any(|f| f.trim().is_empty())
        {
            return Err(Error::input(
                format!("{place}:{}", n + 1),
                "has an empty cell (two separators with nothing between them): a missing sample would shift every height after it; fill it or remove the separator",
            ));
        }
        let mut count = 0;
        for tok in body
            .split(|c: char| c == ',' || c == ';' || c.is_ascii_whitespace())
            .filter(|t| !t.is_empty())
        {
            let v: f64 = tok.parse().map_err(|_| {
                Error::input(
                    format!("{place}:{}", n + 1),
                    format!("\"{tok}\" is not a number"),
                )
            })?;
            if !v.is_finite() {
                return Err(Error::input(
                    format!("{place}:{}", n + 1),
                    format!("height {tok} is not finite"),
                ));
            }
            if v != 0.0 && v.abs() < f64::MIN_POSITIVE {
                return Err(Error::input(
                    format!("{place}:{}", n + 1),
                    format!("height {tok} is a subnormal number (below 2.2e-308 mm in magnitude)"),
                ));
            }
            if v.abs() > MAX_HEIGHT {
                return Err(Error::input(
                    format!("{place}:{}", n + 1),
                    format!("height {tok} is beyond {MAX_HEIGHT:e} mm (1 km) in magnitude: heights are in mm"),
                ));
            }
            z.push(v);
            count += 1;
        }
        if areal && count > 0 {
            if rows > 0 && count != cols {
                return Err(Error::input(
                    format!("{place}:{}", n + 1),
                    format!("row of {count} heights, the first row has {cols}"),
                ));
            }
            cols = count;
            rows += 1;
        }
    }
    if !areal {
        rows = 1;
        cols = z.len();
    }
    let need = 8;
    if cols < need || (areal && rows < need) {
        return Err(Error::input(
            place,
            format!(
                "too few heights: {} (at least {need} per {} needed)",
                z.len(),
                if areal { "row and column" } else { "profile" }
            ),
        ));
    }
    Ok(Heights {
        z,
        rows,
        cols,
        sampling,
    })
}

impl Heights {
    /// A line profile.
    pub fn line(z: Vec<f64>, sampling: f64) -> Heights {
        let cols = z.len();
        Heights {
            z,
            rows: 1,
            cols,
            sampling,
        }
    }

    /// The record levelled by `how` (mean, or least-squares line/plane), in two
    /// passes: the second levels the first's residual, which removes the
    /// round-off of the first's sums (a large offset).
    pub fn levelled(&self, how: Detrend) -> Vec<f64> {
        let once = self.level(&self.z, how);
        self.level(&once, how)
    }

    /// One pass of [`Heights::levelled`] on `z` (of this record's shape).
    fn level(&self, z: &[f64], how: Detrend) -> Vec<f64> {
        let n = z.len() as f64;
        let mean = z.iter().sum::<f64>() / n;
        let mut out: Vec<f64> = z.iter().map(|v| v - mean).collect();
        if how == Detrend::Linear {
            // the index coordinates are centred, so the slopes decouple
            let (r, c) = (self.rows, self.cols);
            let cx = (c as f64 - 1.0) / 2.0;
            let cy = (r as f64 - 1.0) / 2.0;
            let (mut sxz, mut sxx, mut syz, mut syy) = (0.0, 0.0, 0.0, 0.0);
            for i in 0..r {
                for j in 0..c {
                    let (x, y, v) = (j as f64 - cx, i as f64 - cy, out[i * c + j]);
                    sxz += x * v;
                    sxx += x * x;
                    syz += y * v;
                    syy += y * y;
                }
            }
            let bx = if sxx > 0.0 { sxz / sxx } else { 0.0 };
            let by = if syy > 0.0 { syz / syy } else { 0.0 };
            for i in 0..r {
                for j in 0..c {
                    out[i * c + j] -= bx * (j as f64 - cx) + by * (i as f64 - cy);
                }
            }
        }
        out
    }

    /// The rms height left after removing the least-squares line or plane, and
    /// the largest height magnitude of the record.
    pub(crate) fn flatness(&self) -> (f64, f64) {
        let z = self.levelled(Detrend::Linear);
        let rms = (z.iter().map(|v| v * v).sum::<f64>() / z.len() as f64).sqrt();
        let top = self.z.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        (rms, top)
    }

    /// The moments ([`Heights::moments`]), or an error at `place` when the record
    /// has no roughness: its heights lie on a line or plane (level or tilted)
    /// up to round-off, [`FLAT`] of its largest height. A tilt is no roughness
    /// whatever `how` says: levelled by the mean only, it would give summits of
    /// round-off.
    pub(crate) fn rough_moments(&self, how: Detrend, place: &str) -> Result<Moments> {
        let (rms, top) = self.flatness();
        if rms.is_nan() || rms <= FLAT * top {
            let shape = if self.rows > 1 { "plane" } else { "line" };
            let level = top > 0.0;
            let (rms, top) = (crate::numbers::sig(rms, 4), crate::numbers::sig(top, 4));
            let what = match (how, level) {
                (_, false) => "every height is 0".to_string(),
                (Detrend::Linear, true) => format!(
                    "detrend = \"linear\" leaves an rms height of {rms} mm of heights up to {top} mm, round-off"
                ),
                (Detrend::Mean, true) => format!(
                    "the least-squares {shape} leaves an rms height of {rms} mm of heights up to {top} mm, round-off; detrend = \"mean\" would leave the tilt alone, which has no summits"
                ),
            };
            return Err(Error::input(
                place,
                format!("the profile is flat: its heights lie on a {shape} (level or tilted) and {what}; there is no roughness to calibrate"),
            ));
        }
        Ok(self.moments(how))
    }

    /// m0, m2, m4 of the levelled record; a grid averages the moments along its
    /// rows and along its columns (an isotropic surface has the same profile
    /// moments in every direction).
    pub fn moments(&self, how: Detrend) -> Moments {
        let z = self.levelled(how);
        let (r, c, d) = (self.rows, self.cols, self.sampling);
        let m0 = z.iter().map(|v| v * v).sum::<f64>() / z.len() as f64;
        // derivative moments along one line of stride `step`, `len` points
        let line = |start: usize, step: usize, len: usize, acc: &mut [f64; 4]| {
            let at = |k: usize| z[start + k * step];
            for k in 0..len - 1 {
                let s = (at(k + 1) - at(k)) / d;
                acc[0] += s * s;
                acc[1] += 1.0;
            }
            for k in 1..len - 1 {
                let q = (at(k + 1) - 2.0 * at(k) + at(k - 1)) / (d * d);
                acc[2] += q * q;
                acc[3] += 1.0;
            }
        };
        let mut x = [0.0; 4];
        for i in 0..r {
            line(i * c, 1, c, &mut x);
        }
        let (mut m2, mut m4) = (x[0] / x[1], x[2] / x[3]);
        if r > 1 {
            let mut y = [0.0; 4];
            for j in 0..c {
                line(j, c, r, &mut y);
            }
            m2 = 0.5 * (m2 + y[0] / y[1]);
            m4 = 0.5 * (m4 + y[2] / y[3]);
        }
        Moments { m0, m2, m4 }
    }
}

impl Moments {
    /// The summit parameters (McCool 1986); an error when the record has no
    /// roughness or a bandwidth α ≤ 0.8968 (no summit height spread).
    pub fn summits(&self, place: &str) -> Result<Summits> {
        let Moments { m0, m2, m4 } = *self;
        if !(m0 > 0.0 && m2 > 0.0 && m4 > 0.0) {
            return Err(Error::input(
                place,
                format!(
                    "the profile is flat after levelling (m0 = {m0:e}, m2 = {m2:e}, m4 = {m4:e})"
                ),
            ));
        }
        let alpha = m0 * m4 / (m2 * m2);
        if alpha <= 0.8968 {
            return Err(Error::input(
                place,
                format!("bandwidth α = m0 m4 / m2² = {alpha:.4} ≤ 0.8968: no summit height distribution (McCool 1986)"),
            ));
        }
        Ok(Summits {
            alpha,
            density: m4 / (6.0 * std::f64::consts::PI * 3f64.sqrt() * m2),
            radius: 0.375 * (std::f64::consts::PI / m4).sqrt(),
            sigma: ((1.0 - 0.8968 / alpha) * m0).sqrt(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_tilted_line_is_levelled_to_zero() {
        let h = Heights::line((0..100).map(|i| 3.0 + 0.25 * i as f64).collect(), 1e-3);
        let m = h.moments(Detrend::Linear);
        assert!(m.m0 < 1e-25 && m.m2 < 1e-20 && m.m4 < 1e-10, "{m:?}");
        assert!(m.summits("p").is_err());
        let m = h.moments(Detrend::Mean);
        assert!(m.m0 > 1.0, "{m:?}");
    }

    #[test]
    fn a_tilted_plane_is_levelled_to_zero() {
        let (r, c) = (10, 12);
        let z = (0..r * c)
            .map(|k| 1.0 + 0.5 * (k % c) as f64 - 0.2 * (k / c) as f64)
            .collect();
        let h = Heights {
            z,
            rows: r,
            cols: c,
            sampling: 1.0,
        };
        let m = h.moments(Detrend::Linear);
        assert!(m.m0 < 1e-25, "{m:?}");
    }

    #[test]
    fn parse_reads_lines_and_grids_and_refuses_ragged_rows() {
        let t = "# comment\n1, 2\n3 4\n5;6\n7\n8\n";
        let h = parse(t, "p", false, 1.0).unwrap();
        assert_eq!((h.rows, h.cols), (1, 8));
        let grid: String = (0..8).map(|_| "1 2 3 4 5 6 7 8 9\n").collect();
        let h = parse(&grid, "p", true, 1.0).unwrap();
        assert_eq!((h.rows, h.cols), (8, 9));
        let bad = format!("{grid}1 2\n");
        let e = parse(&bad, "p", true, 1.0).unwrap_err().to_string();
        assert!(e.contains("p:9") && e.contains("row of 2"), "{e}");
        let e = parse("1 x 3", "p", false, 1.0).unwrap_err().to_string();
        assert!(e.contains("\"x\" is not a number"), "{e}");
        let e = parse("", "p", false, 1.0).unwrap_err().to_string();
        assert!(e.contains("too few heights: 0"), "{e}");
    }

    /// A spreadsheet's CSV export: byte-order mark, CRLF (or old Mac CR) line
    /// ends; read as the clean text.
    #[test]
    fn bom_crlf_and_cr_read_as_the_clean_text() {
        let clean = "# z, mm\n1.5,2.5\n-3e-3;4\n5\n6\n7\n8\n9\n";
        let want = parse(clean, "p", true, 1.0);
        assert!(want.is_err()); // ragged as a grid: rows are lines
        let want = parse(clean, "p", false, 1.0).unwrap();
        for text in [
            format!("\u{feff}{}", clean.replace('\n', "\r\n")),
            format!("\u{feff}{}", clean.replace('\n', "\r")),
            clean.replace('\n', "\r\n"),
        ] {
            let got = parse(&text, "p", false, 1.0).unwrap();
            assert_eq!((got.z, got.rows, got.cols), (want.z.clone(), 1, 9));
        }
        let grid: String = (0..8).map(|_| "1 2 3 4 5 6 7 8 9\r\n").collect();
        let h = parse(&format!("\u{feff}{grid}"), "p", true, 1.0).unwrap();
        assert_eq!((h.rows, h.cols), (8, 9));
        let h = parse(&grid.replace("\r\n", "\r"), "p", true, 1.0).unwrap();
        assert_eq!((h.rows, h.cols), (8, 9));
        // line numbers count CRLF once
        let e = parse("1\r\n2\r\nx\r\n", "p", false, 1.0)
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("p:3: "), "{e}");
    }

    #[test]
    fn invisible_subnormal_and_huge_heights_are_refused_escaped() {
        let e = parse("1\n\u{feff}2\n", "p", false, 1.0)
            .unwrap_err()
            .to_string();
        assert_eq!(e, "p:2: \"\\u{feff}2\" is not a number");
        let e = parse("1\n2\u{a0}000\n", "p", false, 1.0)
            .unwrap_err()
            .to_string();
        assert_eq!(e, "p:2: \"2\\u{a0}000\" is not a number");
        let e = parse("1\n1e-310\n", "p", false, 1.0)
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("p:2: height 1e-310 is a subnormal"), "{e}");
        let e = parse("1\n2e6\n", "p", false, 1.0).unwrap_err().to_string();
        assert!(e.starts_with("p:2: height 2e6 is beyond"), "{e}");
    }

    #[test]
    fn flat_records_are_refused_whatever_the_detrend() {
        let tilted = Heights::line((0..500).map(|i| 3.0 + 0.25e-3 * i as f64).collect(), 1e-3);
        for how in [Detrend::Linear, Detrend::Mean] {
            let e = tilted.rough_moments(how, "p.csv").unwrap_err().to_string();
            assert!(
                e.starts_with("p.csv: the profile is flat: its heights lie on a line"),
                "{e}"
            );
        }
        let level = Heights::line(vec![0.0; 50], 1e-3);
        let e = level
            .rough_moments(Detrend::Mean, "p.csv")
            .unwrap_err()
            .to_string();
        assert!(e.contains("every height is 0"), "{e}");
        let (r, c) = (10, 12);
        let plane = Heights {
            z: (0..r * c)
                .map(|k| 25.0 + 0.5e-3 * (k % c) as f64 - 0.2e-3 * (k / c) as f64)
                .collect(),
            rows: r,
            cols: c,
            sampling: 1e-3,
        };
        let e = plane
            .rough_moments(Detrend::Linear, "p.csv")
            .unwrap_err()
            .to_string();
        assert!(e.contains("lie on a plane"), "{e}");
        // a roughness of 1e-10 of a 25 mm offset is kept
        let mut z = plane.z.clone();
        for (k, v) in z.iter_mut().enumerate() {
            *v += 2.5e-9 * ((k * 7919) % 13) as f64;
        }
        let rough = Heights { z, ..plane };
        assert!(rough.rough_moments(Detrend::Linear, "p.csv").is_ok());
    }

    #[test]
    fn mccool_relations() {
        let m = Moments {
            m0: 1e-6,
            m2: 1e-3,
            m4: 10.0,
        };
        let s = m.summits("p").unwrap();
        assert!((s.alpha - 10.0).abs() < 1e-12);
        let pi = std::f64::consts::PI;
        assert!((s.density - 10.0 / (6.0 * pi * 3f64.sqrt() * 1e-3)).abs() < 1e-9);
        assert!((s.radius - 0.375 * (pi / 10.0).sqrt()).abs() < 1e-15);
        assert!((s.sigma - (0.91032e-6f64).sqrt()).abs() < 1e-15);
    }
}
