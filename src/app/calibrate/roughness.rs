//! `[surface] model = "roughness"`: Greenwood-Williamson parameters from the
//! Ra or Rz written on a drawing.
//!
//! One height parameter gives the rms height and nothing about the summits,
//! so the spectrum is assumed: the roughness profile of ISO 4287 / ISO 21920
//! is the band between the short-wavelength cutoff λs (ISO 3274, Table 1) and
//! the cutoff λc (ISO 4288, Tables 1-2, Gaussian filters ISO 16610-21), and
//! within it the profile's one-sided power spectral density is taken
//! self-affine, C(k) ∝ k^{−(1+2H)} (Hurst exponent H; Persson et al. 2005,
//! J. Phys.: Condens. Matter 17, R1; Majumdar & Bhushan 1990), H = 0.8 unless
//! `surface.hurst` is given. Its moments
//!
//! m_n = m0 ∫_{k1}^{k2} k^{n−1−2H} dk / ∫_{k1}^{k2} k^{−1−2H} dk,  k1 = 2π/λc, k2 = 2π/λs,
//!
//! give η, β, σ_s by McCool (1986), as for a measured profile. Heights are
//! Gaussian: Ra = σ √(2/π), so σ = √(π/2) Ra (exact); Rz, the mean of five
//! sampling lengths' (lr = λc) peak-to-valley heights, is twice the expected
//! largest height over lr, Davenport (1964):
//!
//! Rz = 2σ (√(2 ln N) + γ/√(2 ln N)),  N = (lr / 2π) √(m2/m0),  γ = 0.5772…,
//!
//! N being Rice's (1945) number of zero up-crossings in lr. Two faces add
//! their spectra (independent heights): m_n = m_n,a + m_n,b, so σ² = σ_a² + σ_b².

use super::limits::{self, Warning, CUTOFF, HURST_LIMIT, RA, RZ, SHORT_CUTOFF};
use super::profile::Moments;
use crate::error::{Error, Result};
use std::f64::consts::PI;

/// The Hurst exponent assumed when none is given, and the range over which
/// the calibration is repeated to show what the assumption is worth.
pub(crate) const HURST: f64 = 0.8;
pub(crate) const HURST_BAND: [f64; 2] = [0.5, 1.0];
/// Euler's constant γ (Davenport's formula).
const EULER_GAMMA: f64 = 0.577_215_664_901_532_9;
/// Smallest λc / λs accepted: a band narrower than a decade has no summits
/// to speak of (the ISO pairs are 30 to 300).
pub(crate) const MIN_BAND: f64 = 10.0;

/// Which height parameter was given.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Parameter {
    Ra,
    Rz,
}

impl Parameter {
    pub fn key(self) -> &'static str {
        match self {
            Parameter::Ra => "ra",
            Parameter::Rz => "rz",
        }
    }
}

/// λc (mm) for a face of roughness `value` (mm): ISO 4288:1996 Table 1 (Ra)
/// and Table 2 (Rz), non-periodic profiles; the end rows beyond the tables.
pub(crate) fn iso4288_cutoff(parameter: Parameter, value: f64) -> f64 {
    let rows: [(f64, f64); 4] = match parameter {
        Parameter::Ra => [(0.02e-3, 0.08), (0.1e-3, 0.25), (2e-3, 0.8), (10e-3, 2.5)],
        Parameter::Rz => [(0.1e-3, 0.08), (0.5e-3, 0.25), (10e-3, 0.8), (50e-3, 2.5)],
    };
    rows.iter()
        .find(|(top, _)| value <= *top)
        .map_or(8.0, |(_, lc)| *lc)
}

/// λs (mm) for the cutoff λc: ISO 3274:1996 Table 1 (λs 2.5 µm up to
/// λc = 0.8 mm, 8 µm up to 2.5 mm, 25 µm above).
pub(crate) fn iso3274_short_cutoff(lc: f64) -> f64 {
    if lc <= 0.8 * (1.0 + 1e-12) {
        2.5e-3
    } else if lc <= 2.5 * (1.0 + 1e-12) {
        8e-3
    } else {
        25e-3
    }
}

/// ∫_{k1}^{k2} k^e dk, without cancellation near e = −1.
fn power_integral(e: f64, k1: f64, k2: f64) -> f64 {
    let f = e + 1.0;
    let r = (k2 / k1).ln();
    if f.abs() * r < 1e-12 {
        r
    } else {
        k1.powf(f) * (f * r).exp_m1() / f
    }
}

/// The moments of a profile of rms height `sigma` whose one-sided PSD is
/// C k^{−(1+2H)} between k1 = 2π/λc and k2 = 2π/λs (zero outside).
pub(crate) fn band_moments(sigma: f64, hurst: f64, lc: f64, ls: f64) -> Moments {
    let (k1, k2) = (2.0 * PI / lc, 2.0 * PI / ls);
    let q = 1.0 + 2.0 * hurst;
    let i0 = power_integral(-q, k1, k2);
    let m0 = sigma * sigma;
    Moments {
        m0,
        m2: m0 * power_integral(2.0 - q, k1, k2) / i0,
        m4: m0 * power_integral(4.0 - q, k1, k2) / i0,
    }
}

/// σ from Ra for Gaussian heights: E|z| = σ √(2/π), so σ = √(π/2) Ra.
pub(crate) fn sigma_from_ra(ra: f64) -> f64 {
    (PI / 2.0).sqrt() * ra
}

/// Rz / σ of a Gaussian profile with `moments`, sampling length `lr`
/// (Davenport 1964 with Rice's up-crossing count N = (lr/2π)√(m2/m0)).
pub(crate) fn rz_over_sigma(moments: &Moments, lr: f64) -> f64 {
    let n = lr / (2.0 * PI) * (moments.m2 / moments.m0).sqrt();
    let l = (2.0 * n.ln()).sqrt();
    2.0 * (l + EULER_GAMMA / l)
}

/// One face's height parameter as the input gave it.
#[derive(Clone, Debug, PartialEq)]
pub struct Given {
    pub parameter: Parameter,
    /// mm.
    pub value: f64,
    /// The key that gave it (`surface.ra`, `surface.a.rz` …), for messages.
    pub key: String,
}

/// One face as derived.
#[derive(Clone, Debug, PartialEq)]
pub struct Face {
    pub parameter: Parameter,
    /// The key that gave it.
    pub key: String,
    /// The Ra or Rz given, mm.
    pub value: f64,
    /// σ (= Rq) of the profile, mm.
    pub sigma: f64,
    /// λc and λs, mm.
    pub cutoff: f64,
    pub short_cutoff: f64,
    /// Rz / σ by Davenport over lr = λc (for Ra input too, as information).
    pub(crate) rz_over_sigma: f64,
    pub moments: Moments,
}

/// The surface as derived from the drawing's roughness.
#[derive(Clone, Debug, PartialEq)]
pub struct Derived {
    pub hurst: f64,
    /// H was given (no band is computed then).
    pub(crate) hurst_given: bool,
    pub faces: Vec<Face>,
    /// The pair's moments (sum over the faces).
    pub moments: Moments,
}

impl Derived {
    /// The parameter of every face ("ra", "rz"), or "mixed" (Ra on one
    /// face, Rz on the other).
    pub fn parameter(&self) -> &'static str {
        match self.faces.iter().map(|f| f.parameter).collect::<Vec<_>>()[..] {
            [p, ..] if self.faces.iter().all(|f| f.parameter == p) => p.key(),
            _ => "mixed",
        }
    }

    /// What the faces were given as, for messages: "ra", or for a mixed
    /// input "ra (face a) and rz (face b)".
    pub fn source(&self) -> String {
        match self.parameter() {
            "mixed" => self
                .faces
                .iter()
                .zip(["a", "b"])
                .map(|(f, n)| format!("{} (face {n})", f.parameter.key()))
                .collect::<Vec<_>>()
                .join(" and "),
            p => p.to_string(),
        }
    }

    /// The keys that gave the faces: "surface.ra", "surface.a.ra and surface.b.rz".
    pub fn keys(&self) -> String {
        let mut keys: Vec<&str> = self.faces.iter().map(|f| f.key.as_str()).collect();
        keys.dedup();
        keys.join(" and ")
    }

    /// The input keys the summits (η, β, σ_s) come from, and how, for a
    /// message about one of them: the faces' keys and the spectrum's keys
    /// given in `o` ("surface.ra, surface.cutoff"), and "derived from them"
    /// with what the spectrum assumed in place of the others.
    pub fn inputs(&self, o: &Overrides) -> (String, String) {
        let mut keys = vec![self.keys()];
        let mut assumed = Vec::new();
        for (key, given, otherwise) in [
            (
                "surface.hurst",
                o.hurst.is_some(),
                format!("H = {HURST} assumed"),
            ),
            (
                "surface.cutoff",
                o.cutoff.is_some(),
                "λc of ISO 4288".to_string(),
            ),
            (
                "surface.short_cutoff",
                o.short_cutoff.is_some(),
                "λs of ISO 3274".to_string(),
            ),
        ] {
            if given {
                keys.push(key.to_string());
            } else {
                assumed.push(otherwise);
            }
        }
        let them = if keys.len() > 1 || self.keys().contains(" and ") {
            "them"
        } else {
            "it"
        };
        let how = if assumed.is_empty() {
            format!("derived from {them}")
        } else {
            format!("derived from {them} with {}", assumed.join(", "))
        };
        (keys.join(", "), how)
    }
}

/// The numbers of `ra` / `rz`: one (the pair's combined roughness, or one
/// rough face against a smooth one) or two (face of body a, face of body b).
pub fn values(v: &toml::Value, place: &str, key: &str) -> Result<Vec<f64>> {
    let refuse = || {
        Error::input(
            format!("{place}: {key}"),
            "must be a number (mm: the pair's roughness) or two numbers [face of body a, face of body b]",
        )
    };
    match v {
        toml::Value::Array(a) if (1..=2).contains(&a.len()) => {
            a.iter().map(|x| number(x).ok_or_else(refuse)).collect()
        }
        other => number(other).map(|x| vec![x]).ok_or_else(refuse),
    }
}

/// A TOML number as f64.
pub fn number(v: &toml::Value) -> Option<f64> {
    match v {
        toml::Value::Float(f) => Some(*f),
        toml::Value::Integer(i) => Some(*i as f64),
        _ => None,
    }
}

/// The optional keys of the roughness model.
#[derive(Clone, Copy, Debug, Default)]
pub struct Overrides {
    pub hurst: Option<f64>,
    pub cutoff: Option<f64>,
    pub short_cutoff: Option<f64>,
}

/// Checks the faces and the overrides and derives the pair's moments; each
/// face's σ and default λc follow its own parameter.
pub fn derive(given: &[Given], o: Overrides, place: &str, w: &mut Vec<Warning>) -> Result<Derived> {
    for g in given {
        let limit = match g.parameter {
            Parameter::Ra => &RA,
            Parameter::Rz => &RZ,
        };
        limit.check(place, &g.key, g.value, w)?;
    }
    if let Some(h) = o.hurst {
        HURST_LIMIT.check(place, "surface.hurst", h, w)?;
    }
    if let Some(lc) = o.cutoff {
        CUTOFF.check(place, "surface.cutoff", lc, w)?;
    }
    if let Some(ls) = o.short_cutoff {
        SHORT_CUTOFF.check(place, "surface.short_cutoff", ls, w)?;
    }
    let hurst = o.hurst.unwrap_or(HURST);
    let mut faces = Vec::new();
    for g in given {
        let (parameter, value) = (g.parameter, g.value);
        let lc = o.cutoff.unwrap_or_else(|| iso4288_cutoff(parameter, value));
        let ls = o.short_cutoff.unwrap_or_else(|| iso3274_short_cutoff(lc));
        if lc < MIN_BAND * ls {
            let k = if o.short_cutoff.is_some() {
                "surface.short_cutoff"
            } else {
                "surface.cutoff"
            };
            return Err(Error::input(
                format!("{place}: {k}"),
                format!(
                    "λc = {} mm and λs = {} mm leave a band of {} (λc/λs), under the {MIN_BAND} the roughness model needs (ISO 3274 pairs them 30 to 300 apart)",
                    limits::num(lc),
                    limits::num(ls),
                    limits::sig(lc / ls, 3)
                ),
            ));
        }
        let shape = band_moments(1.0, hurst, lc, ls);
        let k = rz_over_sigma(&shape, lc);
        let sigma = match parameter {
            Parameter::Ra => sigma_from_ra(value),
            Parameter::Rz => value / k,
        };
        faces.push(Face {
            parameter,
            key: g.key.clone(),
            value,
            sigma,
            cutoff: lc,
            short_cutoff: ls,
            rz_over_sigma: k,
            moments: band_moments(sigma, hurst, lc, ls),
        });
    }
    let sum = |f: fn(&Moments) -> f64| faces.iter().map(|x| f(&x.moments)).sum::<f64>();
    let moments = Moments {
        m0: sum(|m| m.m0),
        m2: sum(|m| m.m2),
        m4: sum(|m| m.m4),
    };
    Ok(Derived {
        hurst,
        hurst_given: o.hurst.is_some(),
        faces,
        moments,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Composite Simpson on [a, b] with n (even) intervals.
    fn simpson(f: impl Fn(f64) -> f64, a: f64, b: f64, n: usize) -> f64 {
        let h = (b - a) / n as f64;
        let s: f64 = (1..n)
            .map(|i| f(a + i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 })
            .sum();
        (f(a) + f(b) + s) * h / 3.0
    }

    #[test]
    fn ra_is_the_mean_absolute_height_of_gaussian_heights() {
        // E|z| for z ~ N(0, σ²), by quadrature, against Ra = σ √(2/π)
        let sigma = 1.7e-3;
        let ra = simpson(
            |z: f64| 2.0 * z * (-z * z / (2.0 * sigma * sigma)).exp() / (sigma * (2.0 * PI).sqrt()),
            0.0,
            12.0 * sigma,
            4000,
        );
        assert!((sigma_from_ra(ra) / sigma - 1.0).abs() < 1e-10, "{ra}");
    }

    #[test]
    fn band_moments_against_quadrature_of_the_spectrum() {
        // log-spaced Simpson in ln k: ∫ k^{n−q} dk = ∫ k^{n−q+1} d(ln k)
        for hurst in [0.5, 0.8, 1.0] {
            let (lc, ls) = (0.8, 2.5e-3);
            let (k1, k2) = (2.0 * PI / lc, 2.0 * PI / ls);
            let q = 1.0 + 2.0 * hurst;
            let i = |n: f64| simpson(|t: f64| t.exp().powf(n - q + 1.0), k1.ln(), k2.ln(), 20000);
            let m = band_moments(2e-3, hurst, lc, ls);
            assert!(
                (m.m2 / (4e-6 * i(2.0) / i(0.0)) - 1.0).abs() < 1e-9,
                "{hurst}"
            );
            assert!(
                (m.m4 / (4e-6 * i(4.0) / i(0.0)) - 1.0).abs() < 1e-9,
                "{hurst}"
            );
        }
        // H = 1, n = 2: the logarithmic case, m2/m0 = ln(k2/k1) / ∫k^{-3}
        let m = band_moments(1.0, 1.0, 1.0, 0.01);
        let (k1, k2) = (2.0 * PI, 200.0 * PI);
        let i0 = (k1.powi(-2) - k2.powi(-2)) / 2.0;
        assert!((m.m2 / ((k2 / k1).ln() / i0) - 1.0).abs() < 1e-13);
    }

    #[test]
    fn iso_cutoffs_at_the_table_edges() {
        use Parameter::*;
        assert_eq!(iso4288_cutoff(Ra, 0.02e-3), 0.08);
        assert_eq!(iso4288_cutoff(Ra, 0.021e-3), 0.25);
        assert_eq!(iso4288_cutoff(Ra, 0.8e-3), 0.8);
        assert_eq!(iso4288_cutoff(Ra, 2.0e-3), 0.8);
        assert_eq!(iso4288_cutoff(Ra, 2.1e-3), 2.5);
        assert_eq!(iso4288_cutoff(Ra, 12.5e-3), 8.0);
        assert_eq!(iso4288_cutoff(Rz, 6.3e-3), 0.8);
        assert_eq!(iso4288_cutoff(Rz, 0.4e-3), 0.25);
        assert_eq!(iso4288_cutoff(Rz, 63e-3), 8.0);
        assert_eq!(iso3274_short_cutoff(0.8), 2.5e-3);
        assert_eq!(iso3274_short_cutoff(2.5), 8e-3);
        assert_eq!(iso3274_short_cutoff(8.0), 25e-3);
    }

    /// Rz/σ: Davenport's formula from the band's up-crossing count, computed
    /// by hand for H = 1 (m2/m0 = 2 ln(k2/k1) / (k1⁻² − k2⁻²)).
    #[test]
    fn rz_over_sigma_by_hand() {
        let (lc, ls) = (0.8, 2.5e-3);
        let (k1, k2) = (2.0 * PI / lc, 2.0 * PI / ls);
        let ratio = 2.0 * (k2 / k1).ln() / (k1.powi(-2) - k2.powi(-2));
        let n = lc / (2.0 * PI) * ratio.sqrt();
        let l = (2.0 * n.ln()).sqrt();
        let k = 2.0 * (l + 0.5772156649 / l);
        let got = rz_over_sigma(&band_moments(1.0, 1.0, lc, ls), lc);
        assert!((got / k - 1.0).abs() < 1e-10, "{got} {k}");
        // a Gaussian profile: Rz between 3 and 6 σ for the ISO bands
        assert!(got > 3.0 && got < 6.0, "{got}");
    }

    /// Ra on face a, Rz on face b: each face's σ and λc by its own
    /// parameter (Rz 20 µm is λc 2.5 mm by ISO 4288 Table 2; read as Ra it
    /// would be 8 mm), the pair's m0 the sum of the two σ².
    #[test]
    fn each_face_follows_its_own_parameter() {
        let mut w = Vec::new();
        let given = [
            Given {
                parameter: Parameter::Ra,
                value: 0.4e-3,
                key: "surface.a.ra".into(),
            },
            Given {
                parameter: Parameter::Rz,
                value: 20e-3,
                key: "surface.b.rz".into(),
            },
        ];
        let d = derive(&given, Overrides::default(), "s", &mut w).unwrap();
        assert_eq!((d.faces[0].cutoff, d.faces[1].cutoff), (0.8, 2.5));
        assert_eq!(d.faces[1].short_cutoff, 8e-3);
        let a = sigma_from_ra(0.4e-3);
        let b = 20e-3 / rz_over_sigma(&band_moments(1.0, HURST, 2.5, 8e-3), 2.5);
        assert!((d.faces[0].sigma / a - 1.0).abs() < 1e-15);
        assert!((d.faces[1].sigma / b - 1.0).abs() < 1e-14);
        assert!((d.moments.m0 / (a * a + b * b) - 1.0).abs() < 1e-14);
        assert_eq!(d.parameter(), "mixed");
        assert_eq!(d.source(), "ra (face a) and rz (face b)");
        assert_eq!(d.keys(), "surface.a.ra and surface.b.rz");
    }

    #[test]
    fn two_faces_add_their_spectra() {
        let mut w = Vec::new();
        let o = Overrides::default();
        let ra = |value: f64| Given {
            parameter: Parameter::Ra,
            value,
            key: "surface.ra".into(),
        };
        let d = derive(&[ra(0.8e-3), ra(3.2e-3)], o, "s", &mut w).unwrap();
        let (a, b) = (sigma_from_ra(0.8e-3), sigma_from_ra(3.2e-3));
        assert!((d.moments.m0 / (a * a + b * b) - 1.0).abs() < 1e-14);
        // each face its own ISO cutoff
        assert_eq!((d.faces[0].cutoff, d.faces[1].cutoff), (0.8, 2.5));
        assert!(w.is_empty());
        let o = Overrides {
            short_cutoff: Some(0.1),
            ..o
        };
        let e = derive(&[ra(0.8e-3)], o, "s", &mut w).unwrap_err();
        assert!(
            e.to_string()
                .starts_with("s: surface.short_cutoff: λc = 0.8 mm"),
            "{e}"
        );
    }
}
