//! `asperity calibrate`: an interface law from the surface (issue 20).
//!
//! From Greenwood-Williamson parameters ([`gw`]) or a measured profile or
//! height map ([`profile`], McCool 1986), the load-approach curve of the
//! rough pair, its best power law u_N = c_N p^m (eq. 2.1) over a pressure
//! range ([`fit`]), and ready-to-paste `[interface.*]` tables for the power
//! law and for `law = "table"`; from the Ra or Rz of a drawing
//! ([`roughness`], an assumed spectrum) and, with `[tangential]`, the
//! Mindlin-GW shear stiffness as a `k_table` ([`tangential`], issue 28).
//! docs/calibration.md has the equations.

pub mod fit;
pub mod gw;
mod input;
pub mod limits;
pub mod profile;
mod report;
pub mod roughness;
pub mod tangential;

use crate::error::{Error, Result};
use fit::{Point, PowerFit};
use gw::{Asperity, Distribution, Gw};
use limits::Warning;
use serde::Deserialize;
use std::path::{Path, PathBuf};

pub use input::*;

/// Largest input file read.
const MAX_INPUT_BYTES: u64 = 1 << 20;
/// Largest profile read.
const MAX_PROFILE_BYTES: u64 = 256 << 20;

/// The surface as analysed: the GW model and, for a profile, its moments.
#[derive(Clone, Debug)]
pub struct Calibration {
    pub gw: Gw,
    pub moments: Option<(profile::Moments, profile::Summits)>,
    pub range: [f64; 2],
    pub reference_pressure: f64,
    /// d₀, mm.
    pub d0: f64,
    /// The dense curve from the reference to twice the upper pressure.
    pub curve: Vec<Point>,
    /// The points of the fit (101, evenly in log p over the range).
    pub fitted: Vec<Point>,
    pub fit: PowerFit,
    /// The table law's points.
    pub table: Vec<Point>,
    /// Legal but suspicious values ([`limits`]), in fit.json and interface.toml.
    pub warnings: Vec<Warning>,
    /// The roughness model's derivation (None for gw and profile input).
    pub roughness: Option<roughness::Derived>,
    /// The tangential request and its k_table [p_N MPa, k_T^e MPa/µm].
    pub tangential: Option<(tangential::Spec, Vec<(f64, f64)>)>,
    /// The roughness model redone at the ends of the Hurst band (none when
    /// `surface.hurst` is given).
    pub band: Vec<BandEnd>,
}

/// The calibration at one end of the assumed Hurst band.
#[derive(Clone, Debug)]
pub struct BandEnd {
    pub hurst: f64,
    /// c_N, m, η, β, σ_s and k_T^e (MPa/µm) at lo and hi; or why it failed.
    pub result: std::result::Result<[f64; 7], String>,
}

/// Composite modulus E* = 1/((1−ν₁²)/E₁ + (1−ν₂²)/E₂) (Johnson 1985, eq. 4.22).
pub(crate) fn composite_modulus(a: &Body, b: &Body) -> f64 {
    1.0 / ((1.0 - a.poisson * a.poisson) / a.young + (1.0 - b.poisson * b.poisson) / b.young)
}

/// Fewer summits in contact per mm² than this at the lower fit pressure (one
/// per m² of nominal area): no asperity touches, refused.
pub(crate) const NO_CONTACT: f64 = 1e-6;
/// Fewer than this (one per cm²): the law rests on few summits, a warning.
pub(crate) const FEW_CONTACTS: f64 = 1e-2;
/// The approach, in σ_s, within which the surface must carry twice the upper
/// fit pressure (the curve's end).
pub(crate) const DEEPEST: f64 = 50.0;
/// Smallest separation step, in σ_s, between the reference and the lower fit
/// pressure and between the two fit pressures: 1e5 × the bisection's 1e-14 σ.
pub(crate) const RESOLVED: f64 = 1e-9;

/// The input checked, the surface's GW model and the separations its pressures
/// map to: everything [`calibrate`] needs before the expensive curve and fit.
/// Every refusal of an input comes from [`prepare`]; the two checks after the
/// fit in [`calibrate`] are a safety net that no known input reaches.
#[derive(Clone, Debug)]
pub(crate) struct Prepared {
    pub gw: Gw,
    pub moments: Option<(profile::Moments, profile::Summits)>,
    pub range: [f64; 2],
    pub reference_pressure: f64,
    pub(crate) table_points: usize,
    /// Separations (mm) at the reference pressure (d₀), at lo and at hi
    /// (the bracket the reach checks found; the unit tests read it).
    pub d0: f64,
    #[cfg_attr(not(test), allow(dead_code))]
    pub(crate) d_lo: f64,
    #[cfg_attr(not(test), allow(dead_code))]
    pub(crate) d_hi: f64,
    /// Summits in contact per mm² at lo.
    #[cfg_attr(not(test), allow(dead_code))]
    pub(crate) contacts_lo: f64,
    pub warnings: Vec<Warning>,
    pub roughness: Option<roughness::Derived>,
    pub tangential: Option<tangential::Spec>,
}

/// The surface's values as the messages quote them.
fn surface_values(
    input: &Input,
    gw: &Gw,
    profile_place: Option<&str>,
    derived: Option<&roughness::Derived>,
) -> String {
    let n = limits::num;
    let e_star = format!(
        "E* = {} MPa (materials.a, materials.b)",
        n(gw.e_star.round())
    );
    match (&input.surface, profile_place) {
        (Surface::Profile { .. }, Some(file)) => format!(
            "η = {} /mm², β = {} mm and σ_s = {} mm from the profile {file}, {e_star}",
            limits::sig(gw.density, 4),
            limits::sig(gw.radius, 4),
            limits::sig(gw.sigma, 4)
        ),
        (Surface::Roughness { .. }, _) => format!(
            "η = {} /mm², β = {} mm and σ_s = {} mm from {} and the assumed spectrum, {e_star}",
            limits::sig(gw.density, 4),
            limits::sig(gw.radius, 4),
            limits::sig(gw.sigma, 4),
            derived.map_or("surface.ra".into(), |d| d.keys())
        ),
        _ => format!(
            "surface.density = {} /mm², surface.radius = {} mm, surface.sigma = {} mm, {e_star}",
            n(gw.density),
            n(gw.radius),
            n(gw.sigma)
        ),
    }
}

/// The error of a combination of values that cannot be calibrated: at the key
/// of the most suspicious value among those that set the contact (σ_s, η, β,
/// E, the pressures) that drew a warning, the surface's before the moduli
/// before the pressure's, with that warning's text; else at `key` of `place`.
/// (A negative ν or an odd hardness is not blamed: neither moves the summits
/// in contact by orders of magnitude.)
fn combined(warnings: &[Warning], place: &str, key: &str, message: String) -> Error {
    let rank = |w: &Warning| {
        if w.key.ends_with(".poisson") || w.key.ends_with(".hardness") {
            None
        } else if w.key.ends_with(".young") {
            Some(1)
        } else if w.key.starts_with("fit") {
            Some(2)
        } else {
            Some(0)
        }
    };
    match warnings
        .iter()
        .filter_map(|w| rank(w).map(|r| (r, w)))
        .min_by_key(|(r, _)| *r)
    {
        Some((_, w)) => Error::input(
            format!("{}: {}", w.place, w.key),
            format!("{} With it, {message}", w.message),
        ),
        None => Error::input(format!("{place}: {key}"), message),
    }
}

/// The faces of the roughness model: `ra` or `rz` (one number for the pair or
/// [face a, face b]), or a table per face (`a = { ra = … }`, `b = { rz = … }`,
/// each face its own parameter); never both forms for a face, never both
/// parameters for one face.
fn roughness_faces(
    ra: &Option<toml::Value>,
    rz: &Option<toml::Value>,
    a: &Option<FaceInput>,
    b: &Option<FaceInput>,
    place: &str,
) -> Result<Vec<roughness::Given>> {
    use roughness::Parameter::{Ra, Rz};
    let err = |key: &str, message: String| Error::input(format!("{place}: {key}"), message);
    let per_face = "a drawing with Ra on one face and Rz on the other takes a table per face: a = { ra = 0.4e-3 } and b = { rz = 4e-3 }";
    let pair = match (ra, rz) {
        (Some(_), Some(_)) => {
            return Err(err(
                "surface.rz",
                format!("surface.ra and surface.rz both give the same faces: give one of them (which one would hold?); {per_face}"),
            ))
        }
        (Some(v), None) => Some((Ra, v)),
        (None, Some(v)) => Some((Rz, v)),
        (None, None) => None,
    };
    if let Some((parameter, v)) = pair {
        let key = format!("surface.{}", parameter.key());
        let values = roughness::values(v, place, &key)?;
        if let Some((name, _)) = [("a", a), ("b", b)].into_iter().find(|(_, f)| f.is_some()) {
            let which = if values.len() == 1 {
                "as the pair's roughness".to_string()
            } else {
                format!("as {key} = [face a, face b]")
            };
            return Err(err(
                &format!("surface.{name}"),
                format!("face {name} is given twice, by {key} ({which}) and by surface.{name}: give the faces either by surface.ra or surface.rz, or by the tables a and b, not both"),
            ));
        }
        return Ok(values
            .into_iter()
            .map(|value| roughness::Given {
                parameter,
                value,
                key: key.clone(),
            })
            .collect());
    }
    if a.is_none() && b.is_none() {
        return Err(err(
            "surface.ra",
            format!("missing: the roughness model needs surface.ra or surface.rz (mm); {per_face}"),
        ));
    }
    let mut given = Vec::new();
    for (name, face) in [("a", a), ("b", b)] {
        let Some(face) = face else {
            return Err(err(
                &format!("surface.{name}"),
                "missing: with a table per face give both faces, a = { ra = … } and b = { rz = … } (one rough face on a smooth one: surface.ra or surface.rz alone, one number)".to_string(),
            ));
        };
        let (parameter, v) = match (&face.ra, &face.rz) {
            (Some(_), Some(_)) => {
                return Err(err(
                    &format!("surface.{name}.rz"),
                    format!("face {name} has both ra and rz: give the one its drawing states (which one would hold?); the other face may take the other parameter"),
                ))
            }
            (Some(v), None) => (Ra, v),
            (None, Some(v)) => (Rz, v),
            (None, None) => {
                return Err(err(
                    &format!("surface.{name}"),
                    format!("missing: face {name} needs its ra or its rz (mm), e.g. {name} = {{ ra = 0.4e-3 }}"),
                ))
            }
        };
        let key = format!("surface.{name}.{}", parameter.key());
        let value =
            roughness::number(v).ok_or_else(|| err(&key, "must be a number (mm)".to_string()))?;
        given.push(roughness::Given {
            parameter,
            value,
            key,
        });
    }
    Ok(given)
}

/// Checks every value of the input against its range ([`limits`]), reads and
/// analyses a profile, and maps the pressures to separations: a fit range in
/// which no summit touches, a surface that cannot carry the upper pressure or
/// pressures too close to resolve are refused here, in milliseconds, before the
/// curve and the fit. `base` is the folder that relative profile paths start
/// from.
pub(crate) fn prepare(input: &Input, place: &str, base: &Path) -> Result<Prepared> {
    let mut warnings = Vec::new();
    let w = &mut warnings;
    check_materials(input, place, w)?;
    // the fit's numbers: cheap, checked before a profile is read
    let fit = fit_numbers(&input.fit, place, w)?;
    let c = SurfaceContext {
        input,
        place,
        base,
        e_star: composite_modulus(&input.materials.a, &input.materials.b),
    };
    let tangential = match &input.tangential {
        Some(t) => Some(tangential::spec(
            t,
            &input.materials.a,
            &input.materials.b,
            place,
        )?),
        None => None,
    };
    let surface = c.analyse(w)?;
    let (d_lo, contacts_lo) = c.check_reach(&surface, &fit, w)?;
    let (d0, d_hi) = check_resolved(place, &surface.gw, &fit, d_lo)?;
    let Analysed {
        gw,
        moments,
        derived,
        ..
    } = surface;
    Ok(Prepared {
        gw,
        moments,
        range: [fit.lo, fit.hi],
        reference_pressure: fit.p_ref,
        table_points: fit.n_table,
        d0,
        d_lo,
        d_hi,
        contacts_lo,
        warnings,
        roughness: derived,
        tangential,
    })
}

/// The fit's numbers as checked by [`fit_numbers`].
struct FitNumbers {
    lo: f64,
    hi: f64,
    /// The reference pressure and the key that names it (given or default).
    p_ref: f64,
    ref_key: &'static str,
    n_table: usize,
}

/// The surface as analysed by [`SurfaceContext::analyse`], before the
/// pressures are mapped to separations.
struct Analysed {
    gw: Gw,
    moments: Option<(profile::Moments, profile::Summits)>,
    /// The profile's path as messages name it (profile input only).
    profile_place: Option<String>,
    /// The roughness model's derivation (roughness input only).
    derived: Option<roughness::Derived>,
}

/// What the analysis of the surface reads besides the surface itself.
struct SurfaceContext<'a> {
    input: &'a Input,
    place: &'a str,
    /// The folder that relative profile paths start from.
    base: &'a Path,
    e_star: f64,
}

/// Checks both bodies' elastic constants and hardness against their ranges.
fn check_materials(input: &Input, place: &str, w: &mut Vec<Warning>) -> Result<()> {
    for (name, body) in [("a", &input.materials.a), ("b", &input.materials.b)] {
        let p = format!("materials.{name}");
        limits::YOUNG.check(place, &format!("{p}.young"), body.young, w)?;
        limits::check_poisson(place, &format!("{p}.poisson"), body.poisson, w)?;
        if let Some(h) = body.hardness {
            limits::HARDNESS.check(place, &format!("{p}.hardness"), h, w)?;
        }
    }
    Ok(())
}

/// Checks `[fit]`: the pressure range, the reference pressure below it and the
/// number of table points.
fn fit_numbers(fs: &FitSpec, place: &str, w: &mut Vec<Warning>) -> Result<FitNumbers> {
    let [lo, hi] = match fs.pressure[..] {
        [lo, hi] => [lo, hi],
        _ => {
            return Err(Error::input(
                format!("{place}: fit.pressure"),
                format!(
                    "must be two pressures [lo, hi] in MPa, got {} numbers",
                    fs.pressure.len()
                ),
            ))
        }
    };
    limits::PRESSURE.check(place, "fit.pressure", lo, w)?;
    limits::PRESSURE.check(place, "fit.pressure", hi, w)?;
    if lo >= hi {
        return Err(Error::input(
            format!("{place}: fit.pressure"),
            format!("lo {lo} must be below hi {hi}"),
        ));
    }
    let (p_ref, ref_key) = match fs.reference_pressure {
        Some(p) => (p, "fit.reference_pressure"),
        None => (1e-3 * lo, "fit.reference_pressure (default 10⁻³ × lo)"),
    };
    limits::REFERENCE.check(place, ref_key, p_ref, w)?;
    if p_ref >= lo {
        return Err(Error::input(
            format!("{place}: {ref_key}"),
            format!("{p_ref} must be below the fit range's lower pressure {lo}"),
        ));
    }
    let n_table = fs.table_points.unwrap_or(10);
    if !(2..=100).contains(&n_table) {
        return Err(Error::input(
            format!("{place}: fit.table_points"),
            format!("must be 2 to 100, got {n_table}"),
        ));
    }
    Ok(FitNumbers {
        lo,
        hi,
        p_ref,
        ref_key,
        n_table,
    })
}

impl SurfaceContext<'_> {
    /// The summits' law named by `surface.asperities`.
    fn asperity(&self, key: &str) -> Result<Asperity> {
        let (input, place) = (self.input, self.place);
        match key {
            "elastic" => Ok(Asperity::Elastic),
            "elastic-plastic" => {
                // the softer body: the lower hardness of those given
                let soft = [&input.materials.a, &input.materials.b]
                    .into_iter()
                    .filter_map(|b| b.hardness.map(|h| (h, b.poisson)))
                    .min_by(|x, y| x.0.total_cmp(&y.0));
                let (hardness, nu) = soft.ok_or_else(|| {
                    Error::input(
                        format!("{place}: surface.asperities"),
                        "\"elastic-plastic\" needs the hardness of a body ([materials] a or b: hardness = …, MPa)",
                    )
                })?;
                Ok(Asperity::Ceb {
                    hardness,
                    k: 0.454 + 0.41 * nu,
                })
            }
            other => Err(Error::input(
                format!("{place}: surface.asperities"),
                format!("unknown \"{other}\" (elastic | elastic-plastic)"),
            )),
        }
    }

    /// The surface as a GW model: given directly, from a profile's moments
    /// ([`Self::profile`]) or from the roughness model ([`Self::roughness`]).
    fn analyse(&self, w: &mut Vec<Warning>) -> Result<Analysed> {
        let place = self.place;
        match &self.input.surface {
            Surface::Gw {
                density,
                radius,
                sigma,
                distribution,
                asperities,
            } => {
                limits::DENSITY.check(place, "surface.density", *density, w)?;
                limits::RADIUS.check(place, "surface.radius", *radius, w)?;
                limits::SIGMA.check(place, "surface.sigma", *sigma, w)?;
                let distribution = match distribution.as_str() {
                    "gaussian" => Distribution::Gaussian,
                    "exponential" => Distribution::Exponential,
                    other => {
                        return Err(Error::input(
                            format!("{place}: surface.distribution"),
                            format!("unknown \"{other}\" (gaussian | exponential)"),
                        ))
                    }
                };
                let gw = Gw {
                    density: *density,
                    radius: *radius,
                    sigma: *sigma,
                    distribution,
                    asperity: self.asperity(asperities)?,
                    e_star: self.e_star,
                };
                Ok(Analysed {
                    gw,
                    moments: None,
                    profile_place: None,
                    derived: None,
                })
            }
            Surface::Profile {
                file,
                sampling,
                kind,
                detrend,
                asperities,
            } => {
                limits::SAMPLING.check(place, "surface.sampling", *sampling, w)?;
                let areal = match kind.as_str() {
                    "line" => false,
                    "areal" => true,
                    other => {
                        return Err(Error::input(
                            format!("{place}: surface.kind"),
                            format!("unknown \"{other}\" (line | areal)"),
                        ))
                    }
                };
                let how = match detrend.as_str() {
                    "linear" => profile::Detrend::Linear,
                    "mean" => profile::Detrend::Mean,
                    other => {
                        return Err(Error::input(
                            format!("{place}: surface.detrend"),
                            format!("unknown \"{other}\" (linear | mean)"),
                        ))
                    }
                };
                let asperity = self.asperity(asperities)?;
                let read = ProfileRead {
                    file,
                    sampling: *sampling,
                    areal,
                    how,
                };
                self.profile(&read, asperity, w)
            }
            Surface::Roughness {
                ra,
                rz,
                a,
                b,
                hurst,
                cutoff,
                short_cutoff,
                asperities,
            } => {
                let given = roughness_faces(ra, rz, a, b, place)?;
                let overrides = roughness::Overrides {
                    hurst: *hurst,
                    cutoff: *cutoff,
                    short_cutoff: *short_cutoff,
                };
                self.roughness(&given, overrides, asperities, w)
            }
        }
    }

    /// Reads and analyses a profile: its moments, its summits (checked
    /// against the same ranges as GW input) and the GW model they make.
    fn profile(
        &self,
        read: &ProfileRead,
        asperity: Asperity,
        w: &mut Vec<Warning>,
    ) -> Result<Analysed> {
        let place = self.place;
        let path = self.base.join(read.file);
        let fplace = path.display().to_string();
        let bytes = crate::input::case::read_input(&path, MAX_PROFILE_BYTES, "profile")?;
        let text = String::from_utf8(bytes)
            .map_err(|_| Error::input(&fplace, "the profile is not valid UTF-8 text"))?;
        let heights = profile::parse(&text, &fplace, read.areal, read.sampling)?;
        let m = heights.rough_moments(read.how, &fplace)?;
        let s = m.summits(&fplace)?;
        // the summits the moments give, against the same ranges as GW input
        // named by the keys that made them: σ_s scales with the
        // heights, η and β with their spacing too
        let hint = Some("are the heights in mm and surface.sampling in mm?");
        let heights = format!("derived from the heights of {fplace}");
        let spaced = format!("{heights} and their spacing");
        let (file, both) = ("surface.file", "surface.file, surface.sampling");
        limits::SIGMA.check_derived(place, file, &heights, s.sigma, w, hint)?;
        limits::DENSITY.check_derived(place, both, &spaced, s.density, w, hint)?;
        limits::RADIUS.check_derived(place, both, &spaced, s.radius, w, hint)?;
        let gw = Gw {
            density: s.density,
            radius: s.radius,
            sigma: s.sigma,
            distribution: Distribution::Gaussian,
            asperity,
            e_star: self.e_star,
        };
        Ok(Analysed {
            gw,
            moments: Some((m, s)),
            profile_place: Some(fplace),
            derived: None,
        })
    }

    /// The roughness model from Ra / Rz: its moments, its summits (checked
    /// against the same ranges as GW input, named by the keys that made them)
    /// and the GW model they make.
    fn roughness(
        &self,
        given: &[roughness::Given],
        overrides: roughness::Overrides,
        asperities: &str,
        w: &mut Vec<Warning>,
    ) -> Result<Analysed> {
        let place = self.place;
        let d = roughness::derive(given, overrides, place, w)?;
        let s = d.moments.summits(&format!("{place}: {}", d.keys()))?;
        // named by the keys that made them, not as derived quantities
        let hint = Some("are the Ra / Rz values in mm?");
        let (keys, how) = d.inputs(&overrides);
        limits::SIGMA.check_derived(place, &keys, &how, s.sigma, w, hint)?;
        limits::DENSITY.check_derived(place, &keys, &how, s.density, w, hint)?;
        limits::RADIUS.check_derived(place, &keys, &how, s.radius, w, hint)?;
        let gw = Gw {
            density: s.density,
            radius: s.radius,
            sigma: s.sigma,
            distribution: Distribution::Gaussian,
            asperity: self.asperity(asperities)?,
            e_star: self.e_star,
        };
        Ok(Analysed {
            gw,
            moments: None,
            profile_place: None,
            derived: Some(d),
        })
    }

    /// Checks that the surface carries twice the upper pressure within
    /// [`DEEPEST`] σ_s and that summits touch at the lower one (warning when
    /// few do); returns the separation at lo and the summits touching there.
    fn check_reach(
        &self,
        s: &Analysed,
        fit: &FitNumbers,
        w: &mut Vec<Warning>,
    ) -> Result<(f64, f64)> {
        let (place, gw, lo, hi) = (self.place, &s.gw, fit.lo, fit.hi);
        let values = || {
            surface_values(
                self.input,
                gw,
                s.profile_place.as_deref(),
                s.derived.as_ref(),
            )
        };
        let sigma = gw.sigma;
        // the upper pressure: the curve runs to 2 hi, within DEEPEST σ of approach
        let deepest = gw.pressure(-DEEPEST * sigma);
        if deepest.is_nan() || deepest <= 2.0 * hi {
            return Err(combined(
                w,
                place,
                "fit.pressure",
                format!(
                    "the surface carries {} MPa at an approach of {DEEPEST} σ_s (the summits flattened {DEEPEST} times their height spread, far beyond Greenwood-Williamson), not twice the upper fit pressure fit.pressure = {} MPa that the curve runs to, for {}",
                    limits::sig(deepest, 4),
                    limits::num(hi),
                    values()
                ),
            ));
        }
        // the lower pressure: how many summits touch there
        let d_lo = gw.separation(lo);
        let contacts_lo = gw.density * gw.contact_fraction(d_lo);
        if contacts_lo.is_nan() || contacts_lo < NO_CONTACT {
            let onset = NO_CONTACT / gw.density;
            let from = if onset < 0.5 {
                format!(
                    "; one summit per m² touches from {} MPa up",
                    limits::sig(gw.pressure(gw.separation_for_fraction(onset)), 4)
                )
            } else {
                String::new()
            };
            return Err(combined(
                w,
                place,
                "fit.pressure",
                format!(
                    "no summit touches at the lower fit pressure fit.pressure = {} MPa: it maps to a separation of {} σ_s above the mean summit height, where {} summits per mm² touch (fewer than one per m² of nominal area), for {}{from}",
                    limits::num(lo),
                    limits::sig(d_lo / sigma, 4),
                    limits::sig(contacts_lo, 4),
                    values()
                ),
            ));
        }
        if contacts_lo < FEW_CONTACTS {
            w.push(Warning {
                place: place.to_string(),
                key: "fit.pressure".into(),
                message: format!(
                    "at the lower fit pressure {} MPa only {} summits per mm² touch (one per {} mm²): Greenwood-Williamson averages over many summits, so the law holds only on contacts far larger than that; for {}",
                    limits::num(lo),
                    limits::sig(contacts_lo, 4),
                    limits::sig(1.0 / contacts_lo, 4),
                    values()
                ),
            });
        }
        Ok((d_lo, contacts_lo))
    }
}

/// How [`SurfaceContext::profile`] reads a profile.
struct ProfileRead<'a> {
    file: &'a str,
    sampling: f64,
    areal: bool,
    how: profile::Detrend,
}

/// Checks that the separations at the reference, lower and upper pressures
/// are far enough apart to be resolved; returns those at the reference
/// pressure (d₀) and at hi.
fn check_resolved(place: &str, gw: &Gw, fit: &FitNumbers, d_lo: f64) -> Result<(f64, f64)> {
    let (lo, hi, p_ref, ref_key) = (fit.lo, fit.hi, fit.p_ref, fit.ref_key);
    let sigma = gw.sigma;
    let d0 = gw.separation(p_ref);
    let step = d0 - d_lo;
    if step.is_nan() || step <= RESOLVED * sigma {
        return Err(Error::input(
            format!("{place}: {ref_key}"),
            format!(
                "{} MPa maps to a separation only {} σ_s from that of the lower fit pressure {} MPa: the approaches would be round-off; take a reference pressure further below lo",
                limits::exact(p_ref),
                limits::sig(step / sigma, 4),
                limits::exact(lo)
            ),
        ));
    }
    let d_hi = gw.separation(hi);
    let span = d_lo - d_hi;
    if span.is_nan() || span <= RESOLVED * sigma * (fit.n_table - 1) as f64 {
        return Err(Error::input(
            format!("{place}: fit.pressure"),
            format!(
                "lo {} and hi {} MPa map to separations only {} σ_s apart: the table's approaches would not be resolved; widen the range",
                limits::exact(lo),
                limits::exact(hi),
                limits::sig(span / sigma, 4)
            ),
        ));
    }
    Ok((d0, d_hi))
}

/// Checks the input (`prepare`) and computes the curve, the fit and the
/// table; `base` is the folder that relative profile paths start from.
pub fn calibrate(input: &Input, place: &str, base: &Path) -> Result<Calibration> {
    let Prepared {
        gw,
        moments,
        range: [lo, hi],
        reference_pressure: p_ref,
        table_points: n_table,
        d0,
        warnings,
        roughness: derived,
        tangential: wanted,
        ..
    } = prepare(input, place, base)?;
    let fitted = fit::curve(&gw, d0, &fit::log_space(lo, hi, 101));
    let mut ps = fit::log_space(p_ref, lo, 41);
    ps.pop();
    ps.extend(fit::log_space(lo, hi, 101));
    ps.pop();
    ps.extend(fit::log_space(hi, 2.0 * hi, 21));
    let curve = fit::curve(&gw, d0, &ps);
    let fit = fit::power_law(&fitted).ok_or_else(|| {
        Error::input(
            format!("{place}: fit.pressure"),
            "the curve cannot be fitted (no approach)",
        )
    })?;
    let table = fit::curve(&gw, d0, &fit::log_space(lo, hi, n_table));
    let increasing = table
        .windows(2)
        .all(|w| w[1].approach > w[0].approach && w[1].pressure > w[0].pressure);
    if !increasing || table[0].approach <= 0.0 {
        return Err(Error::input(
            format!("{place}: fit.pressure"),
            "the table's approaches are not positive and strictly increasing (range too narrow for the model's accuracy)",
        ));
    }
    // the table as interface.toml writes it must be one a case accepts (rows
    // far enough apart to give a slope, every value in its range)
    let written: Vec<(f64, f64)> = table
        .iter()
        .map(|q| {
            let r = |v: f64| format!("{v:.9e}").parse::<f64>().unwrap_or(f64::NAN);
            (r(q.approach), r(q.pressure))
        })
        .collect();
    if let Err(m) = crate::physics::contact::normal::table::new(&written) {
        return Err(Error::input(
            format!("{place}: fit.pressure"),
            format!("[{lo}, {hi}] MPa gives a table that a case file would refuse ({m}); widen the fit range"),
        ));
    }
    let tangential = match wanted {
        Some(spec) => {
            let pressures: Vec<f64> = table.iter().map(|q| q.pressure).collect();
            let rows = tangential::k_table(&gw, spec.g_star, &pressures);
            tangential::check(&rows, &spec, place)?;
            Some((spec, rows))
        }
        None => None,
    };
    let band = match &derived {
        Some(d) if !d.hurst_given => hurst_band(input, place, base),
        _ => Vec::new(),
    };
    Ok(Calibration {
        gw,
        moments,
        range: [lo, hi],
        reference_pressure: p_ref,
        d0,
        curve,
        fitted,
        fit,
        table,
        warnings,
        roughness: derived,
        tangential,
        band,
    })
}

/// The roughness model calibrated again at each end of the assumed Hurst band
/// ([`roughness::HURST_BAND`]): what the missing spectral information is worth.
fn hurst_band(input: &Input, place: &str, base: &Path) -> Vec<BandEnd> {
    roughness::HURST_BAND
        .iter()
        .map(|&h| {
            let mut at = input.clone();
            if let Surface::Roughness { hurst, .. } = &mut at.surface {
                *hurst = Some(h);
            }
            // k_T^e at lo and hi; 0 when no tangential law is asked for
            at.tangential.get_or_insert(tangential::Input {
                mu: Some(1.0),
                ..Default::default()
            });
            let result = calibrate(&at, place, base)
                .map(|c| {
                    let k = c
                        .tangential
                        .map_or([0.0, 0.0], |(_, r)| [r[0].1, r[r.len() - 1].1]);
                    let g = c.gw;
                    [c.fit.c_n, c.fit.m, g.density, g.radius, g.sigma, k[0], k[1]]
                })
                .map_err(|e| e.to_string());
            BandEnd { hurst: h, result }
        })
        .collect()
}

/// What `asperity calibrate` wrote.
#[derive(Clone, Debug)]
pub struct Written {
    /// The files, relative to DIR.
    pub files: Vec<PathBuf>,
    /// One line for stdout.
    pub summary: String,
    /// Legal but suspicious values, for `warning: …` lines on stderr.
    pub warnings: Vec<Warning>,
}

/// Runs `asperity calibrate INPUT --out DIR`: every check and the whole
/// computation come first, then the files are written into a temporary folder
/// next to DIR, which replaces DIR only when complete; a refused input leaves
/// DIR as it was.
pub fn run(input_path: &Path, out: &Path) -> Result<Written> {
    let input = load(input_path)?;
    let place = input_path.display().to_string();
    let base = input_path.parent().unwrap_or(Path::new("."));
    let cal = calibrate(&input, &place, base)?;
    let name = out
        .file_name()
        .map_or("calibration".into(), |n| n.to_string_lossy().into_owned());
    let parent = out
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    std::fs::create_dir_all(parent).map_err(|e| Error::io(parent, e))?;
    let tmp = parent.join(format!(".{name}.partial-{}", std::process::id()));
    if tmp.exists() {
        std::fs::remove_dir_all(&tmp).map_err(|e| Error::io(&tmp, e))?;
    }
    std::fs::create_dir_all(&tmp).map_err(|e| Error::io(&tmp, e))?;
    let result = (|| -> Result<Vec<PathBuf>> {
        let write = |rel: &str, text: &str| -> Result<PathBuf> {
            let p = tmp.join(rel);
            std::fs::write(&p, text).map_err(|e| Error::io(&p, e))?;
            Ok(PathBuf::from(rel))
        };
        let mut files = Vec::new();
        let pictures = crate::files::plot::load_font();
        crate::files::plot::save_pictures(&cal.chart(), &tmp.join("curve"), pictures)?;
        if pictures {
            files.push("curve.svg".into());
            files.push("curve.png".into());
        }
        files.push(write("curve.csv", &cal.curve_csv())?);
        let json = serde_json::to_string_pretty(&cal.fit_json(&place))
            .map_err(|e| Error::Output(e.to_string()))?;
        files.push(write("fit.json", &(json + "\n"))?);
        files.push(write("interface.toml", &cal.interface_toml(&place))?);
        crate::files::output::replace_dir(&tmp, out)?;
        Ok(files)
    })();
    if result.is_err() {
        let _ = std::fs::remove_dir_all(&tmp);
    }
    let summary = format!(
        "c_n = {:.6e} mm/MPa^m, m = {:.6} over {}-{} MPa (max relative error in u_N {:.2}%); E* = {:.1} MPa, η = {:.4e}/mm², β = {:.4e} mm, σ_s = {:.4e} mm{}; written to {}",
        cal.fit.c_n,
        cal.fit.m,
        cal.range[0],
        cal.range[1],
        100.0 * cal.fit.max_error,
        cal.gw.e_star,
        cal.gw.density,
        cal.gw.radius,
        cal.gw.sigma,
        cal.summary_extra(),
        out.display()
    );
    result.map(|files| Written {
        files,
        summary,
        warnings: cal.warnings,
    })
}

#[cfg(test)]
mod tests;
