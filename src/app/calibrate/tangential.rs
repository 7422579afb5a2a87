//! The tangential law of the surface: Mindlin's elastic shear stiffness of one
//! Hertzian summit summed over the Greenwood-Williamson population.
//!
//! One summit of contact radius a, pressed and then sheared without slip, has
//! the tangential stiffness (Mindlin 1949; Johnson, Contact Mechanics 1985,
//! §7.2)
//!
//! k_t = 8 G* a,  1/G* = (2 − ν₁)/G₁ + (2 − ν₂)/G₂,  G = E / (2(1 + ν)),
//!
//! with a = √(β ω) (Hertz) at interference ω. Over the population, exactly as
//! the normal load is summed (GW 1966, eq. 7), per unit nominal area:
//!
//! K_T(d) = η ∫_d^∞ 8 G* a(z − d) φ(z) dz,
//!
//! paired with p(d) at the same separation d. For Chang-Etsion-Bogy summits
//! above the critical interference the contact radius of their area,
//! a = √(β (2ω − ω_c)), is used (an assumption: the flattened tip is taken to
//! shear elastically over its actual contact).

use super::gw::{Asperity, Gw};
use super::Body;
use crate::error::{Error, Result};
use crate::input::case::BackboneKind;
use crate::physics::contact::{Backbone, Memory, TangentialLaw};

/// `[tangential]` of the calibration input: present = the tangential law is
/// wanted.
#[derive(Clone, Debug, Default, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Input {
    /// μ_m, the friction coefficient of the case's law (required).
    pub mu: Option<f64>,
    /// k_T^p / k_T^e in [0, 1], default 1 (no micro-slip branch); the
    /// bilinear backbone only.
    pub kp_ratio: Option<f64>,
    /// "isotropic" | "kinematic", written into the snippet when given.
    pub memory: Option<String>,
    /// "bilinear" | "iwan", written into the snippet when given.
    pub backbone: Option<String>,
    /// Iwan: χ in [−0.99, 1] and the spike in [0, 1), written when given.
    pub chi: Option<f64>,
    pub spike: Option<f64>,
}

/// The tangential request, checked.
#[derive(Clone, Debug, PartialEq)]
pub struct Spec {
    pub mu: f64,
    /// k_T^p / k_T^e: None with the Iwan backbone (the case refuses it there).
    pub kp_ratio: Option<f64>,
    /// The memory and the backbone the law is checked with; `given` holds
    /// the keys written into the snippet (memory, backbone, chi, spike as
    /// the input had them).
    pub memory: Memory,
    pub backbone: Backbone,
    pub given: Given,
    /// G*, MPa.
    pub(crate) g_star: f64,
}

/// The optional keys of the tangential law as the input gave them.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Given {
    pub memory: Option<String>,
    pub backbone: Option<String>,
    pub chi: Option<f64>,
    pub spike: Option<f64>,
}

/// Checks `[tangential]`: μ given, positive and within the case file's range
/// of a friction coefficient; kp_ratio in [0, 1]; memory and backbone known,
/// their keys by the case file's rules (`crate::input::case::backbone_keys`) and
/// their values by `TangentialLaw::with_memory`.
pub fn spec(t: &Input, a: &Body, b: &Body, place: &str) -> Result<Spec> {
    let at = |k: &str| format!("{place}: tangential.{k}");
    let mu = t.mu.ok_or_else(|| {
        Error::input(
            at("mu"),
            "missing: the friction coefficient μ_m of the tangential law (the surface does not give it), e.g. mu = 0.15",
        )
    })?;
    if !(mu.is_finite() && mu > 0.0) {
        return Err(Error::input(
            at("mu"),
            format!(
                "must be a positive finite number, got {}",
                super::limits::num(mu)
            ),
        ));
    }
    crate::input::case::ranges::FRICTION.check(at("mu"), mu)?;
    let memory = match t.memory.as_deref() {
        None | Some("isotropic") => Memory::Isotropic,
        Some("kinematic") => Memory::Kinematic,
        Some(other) => {
            return Err(Error::input(
                at("memory"),
                format!("unknown \"{other}\" (isotropic | kinematic)"),
            ))
        }
    };
    let kind = match t.backbone.as_deref() {
        None | Some("bilinear") => BackboneKind::Bilinear,
        Some("iwan") => BackboneKind::Iwan,
        Some(other) => {
            return Err(Error::input(
                at("backbone"),
                format!("unknown \"{other}\" (bilinear | iwan)"),
            ))
        }
    };
    // kp_ratio defaults to 1 here (the case file requires it: it is written)
    let kp_given = match kind {
        BackboneKind::Bilinear => Some(t.kp_ratio.unwrap_or(1.0)),
        BackboneKind::Iwan => t.kp_ratio,
    };
    let kp = crate::input::case::backbone_keys(kind, [kp_given, None, t.chi, t.spike], &at)?;
    let backbone = match kind {
        BackboneKind::Bilinear => Backbone::Bilinear,
        BackboneKind::Iwan => Backbone::Iwan {
            chi: t.chi.unwrap_or(0.0),
            spike: t.spike.unwrap_or(0.0),
        },
    };
    TangentialLaw::new(1.0, 0.0, kp, mu, 1.0, 0.0, 0.625)
        .map_err(|m| Error::input(at("kp_ratio"), kp_message(&m)))?
        .with_memory(memory, backbone)
        .map_err(|m| Error::input(at(crate::input::case::memory_error_key(&m)), m))?;
    Ok(Spec {
        mu,
        kp_ratio: (kind == BackboneKind::Bilinear).then_some(kp),
        memory,
        backbone,
        given: Given {
            memory: t.memory.clone(),
            backbone: t.backbone.clone(),
            chi: t.chi,
            spike: t.spike,
        },
        g_star: shear_modulus_star(a, b),
    })
}

/// The message of a refused kp_ratio as this input has always given it.
fn kp_message(m: &str) -> String {
    match m.strip_prefix("kp_ratio = ") {
        Some(rest) => format!(
            "must be in [0, 1], got {}",
            rest.trim_end_matches(" must be in [0, 1]")
        ),
        None => m.to_string(),
    }
}

/// G* of Mindlin's tangential stiffness: 1/G* = (2 − ν₁)/G₁ + (2 − ν₂)/G₂
/// (Johnson 1985, §7.2).
pub(crate) fn shear_modulus_star(a: &Body, b: &Body) -> f64 {
    let g = |x: &Body| x.young / (2.0 * (1.0 + x.poisson));
    1.0 / ((2.0 - a.poisson) / g(a) + (2.0 - b.poisson) / g(b))
}

impl Gw {
    /// The contact radius (mm) of one summit at interference ω ≥ 0: Hertz
    /// √(β ω); CEB above ω_c: √(β (2ω − ω_c)) (area π β (2ω − ω_c)).
    pub(crate) fn contact_radius(&self, omega: f64) -> f64 {
        match self.asperity {
            Asperity::Elastic => (self.radius * omega).sqrt(),
            Asperity::Ceb { .. } => {
                let wc = self.critical_interference();
                if omega <= wc {
                    (self.radius * omega).sqrt()
                } else {
                    (self.radius * (2.0 * omega - wc)).sqrt()
                }
            }
        }
    }

    /// K_T(d) = η ∫_d^∞ 8 G* a(z − d) φ(z) dz, MPa/mm, at separation d (mm),
    /// by the quadrature of [`Gw::pressure`].
    pub fn tangential_stiffness(&self, d: f64, g_star: f64) -> f64 {
        self.over_summits(d, &|omega| 8.0 * g_star * self.contact_radius(omega))
    }
}

/// The k_table rows [p_N MPa, k_T^e MPa/µm] at the pressures `pressures`,
/// each paired with K_T at the separation where the surface carries it.
pub fn k_table(gw: &Gw, g_star: f64, pressures: &[f64]) -> Vec<(f64, f64)> {
    pressures
        .iter()
        .map(|&p| (p, 1e-3 * gw.tangential_stiffness(gw.separation(p), g_star)))
        .collect()
}

/// The rows as `interface.toml` writes them (ten significant digits).
pub fn written(rows: &[(f64, f64)]) -> Vec<(f64, f64)> {
    let r = |v: f64| format!("{v:.9e}").parse::<f64>().unwrap_or(f64::NAN);
    rows.iter().map(|&(p, k)| (r(p), r(k))).collect()
}

/// Checks that the written k_table is one a case accepts: every stiffness in
/// the case file's range, rows by the tangential law's own table rules, with
/// the requested memory and backbone.
pub fn check(rows: &[(f64, f64)], spec: &Spec, place: &str) -> Result<()> {
    let at = format!("{place}: fit.pressure");
    for (i, &(_, k)) in written(rows).iter().enumerate() {
        crate::input::case::ranges::SHEAR_STIFFNESS
            .check(format!("{at} (tangential k_table row {} k_T)", i + 1), k)?;
    }
    let kp = spec.kp_ratio.unwrap_or(1.0);
    TangentialLaw::with_k_table(&written(rows), kp, spec.mu, 1.0, 0.0, 0.625)
        .and_then(|law| law.with_memory(spec.memory, spec.backbone))
        .map(|_| ())
        .map_err(|m| {
            Error::input(
                at,
                format!("gives a tangential k_table that a case file would refuse ({m}); widen the fit range"),
            )
        })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::app::calibrate::gw::Distribution;

    fn steel() -> Body {
        Body {
            young: 206000.0,
            poisson: 0.3,
            hardness: None,
        }
    }

    fn input(text: &str) -> Input {
        toml::from_str(text).unwrap()
    }

    /// The memory and backbone keys: iwan drops kp_ratio, bilinear keeps its
    /// default 1, and each refusal names its key.
    #[test]
    fn memory_and_backbone_keys_by_the_case_rules() {
        let (a, b) = (steel(), steel());
        let s = spec(
            &input("mu = 0.15\nmemory = \"kinematic\"\nbackbone = \"iwan\"\nchi = -0.5\n"),
            &a,
            &b,
            "s",
        )
        .unwrap();
        assert_eq!(s.kp_ratio, None);
        assert_eq!(s.memory, Memory::Kinematic);
        assert_eq!(
            s.backbone,
            Backbone::Iwan {
                chi: -0.5,
                spike: 0.0
            }
        );
        let s = spec(&input("mu = 0.15\nmemory = \"kinematic\"\n"), &a, &b, "s").unwrap();
        assert_eq!((s.kp_ratio, s.backbone), (Some(1.0), Backbone::Bilinear));
        for (text, key) in [
            (
                "backbone = \"iwan\"\nkp_ratio = 0.5\n",
                "tangential.kp_ratio: `kp_ratio` belongs to the bilinear backbone",
            ),
            (
                "chi = 0.5\n",
                "tangential.chi: `chi` belongs to backbone = \"iwan\"",
            ),
            (
                "backbone = \"bilinear\"\nspike = 0.1\n",
                "tangential.spike: `spike` belongs",
            ),
            (
                "backbone = \"iwan\"\nchi = -1.0\n",
                "tangential.chi: chi = -1 must be in [-0.99, 1]",
            ),
            (
                "backbone = \"iwan\"\nspike = 1.0\n",
                "tangential.spike: spike = 1 must be in [0, 1)",
            ),
            (
                "backbone = \"masing\"\n",
                "tangential.backbone: unknown \"masing\" (bilinear | iwan)",
            ),
            (
                "memory = \"Kinematic\"\n",
                "tangential.memory: unknown \"Kinematic\"",
            ),
            (
                "kp_ratio = -0.1\n",
                "tangential.kp_ratio: must be in [0, 1], got -0.1",
            ),
        ] {
            let e = spec(&input(&format!("mu = 0.15\n{text}")), &a, &b, "s").unwrap_err();
            assert!(
                e.to_string().starts_with(&format!("s: {key}")),
                "{text}: {e}"
            );
        }
    }

    #[test]
    fn g_star_of_two_steels_by_hand() {
        // G = 206000 / 2.6 = 79230.77 MPa; 1/G* = 2 × 1.7 / G
        let g = 206000.0 / 2.6;
        let got = shear_modulus_star(&steel(), &steel());
        assert!((got / (g / 3.4) - 1.0).abs() < 1e-14, "{got}");
    }

    /// CEB contact radius: Hertz below ω_c, continuous at ω_c (the CEB area
    /// π β (2ω − ω_c) equals Hertz's π β ω_c there).
    #[test]
    fn ceb_contact_radius_is_continuous_at_the_critical_interference() {
        let g = Gw {
            density: 1.0,
            radius: 0.05,
            sigma: 1e-3,
            distribution: Distribution::Gaussian,
            asperity: Asperity::Ceb {
                hardness: 2000.0,
                k: 0.577,
            },
            e_star: 113_000.0,
        };
        let wc = g.critical_interference();
        let (a, b) = (
            g.contact_radius(wc * (1.0 - 1e-12)),
            g.contact_radius(wc * (1.0 + 1e-12)),
        );
        assert!((a / b - 1.0).abs() < 1e-11);
        assert!((g.contact_radius(3.0 * wc) / (0.05 * 5.0 * wc).sqrt() - 1.0).abs() < 1e-14);
    }
}
