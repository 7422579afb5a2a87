//! `asperity calibrate`: an interface law from the surface (issue 20).
//!
//! From Greenwood-Williamson parameters ([`gw`]) or a measured profile or
//! height map ([`profile`], McCool 1986), the load-approach curve of the
//! rough pair, its best power law u_N = c_N p^m (eq. 2.1) over a pressure
//! range ([`fit`]), and ready-to-paste `[interface.*]` tables for the power
//! law and for `law = "table"`. docs/calibration.md has the equations.

pub mod fit;
pub mod gw;
pub mod profile;

use crate::error::{Error, Result};
use fit::{Point, PowerFit};
use gw::{Asperity, Distribution, Gw};
use serde::Deserialize;
use serde_json::json;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Largest input file read.
const MAX_INPUT_BYTES: u64 = 1 << 20;
/// Largest profile read.
const MAX_PROFILE_BYTES: u64 = 256 << 20;

/// The input file.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Input {
    pub materials: Materials,
    pub surface: Surface,
    pub fit: FitSpec,
}

/// `[materials]`: the two bodies.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Materials {
    pub a: Body,
    pub b: Body,
}

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Body {
    /// Young's modulus, MPa.
    pub young: f64,
    pub poisson: f64,
    /// Hardness, MPa (elastic-plastic summits only).
    pub hardness: Option<f64>,
}

/// `[surface]`: GW parameters or a measured record.
#[derive(Clone, Debug, Deserialize)]
#[serde(tag = "model", rename_all = "lowercase", deny_unknown_fields)]
pub enum Surface {
    Gw {
        /// η, summits per mm².
        density: f64,
        /// β, mm.
        radius: f64,
        /// σ_s, mm.
        sigma: f64,
        #[serde(default = "gaussian")]
        distribution: String,
        #[serde(default = "elastic")]
        asperities: String,
    },
    Profile {
        /// Path of the heights (mm), relative to the input file.
        file: String,
        /// Sampling interval Δ, mm.
        sampling: f64,
        /// "line" or "areal".
        #[serde(default = "line")]
        kind: String,
        /// "linear" (line / plane) or "mean".
        #[serde(default = "linear")]
        detrend: String,
        #[serde(default = "elastic")]
        asperities: String,
    },
}

fn gaussian() -> String {
    "gaussian".into()
}
fn elastic() -> String {
    "elastic".into()
}
fn line() -> String {
    "line".into()
}
fn linear() -> String {
    "linear".into()
}

/// `[fit]`.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FitSpec {
    /// [lo, hi], MPa: the range of the power-law fit and of the table.
    pub pressure: Vec<f64>,
    /// Pressure (MPa) at the reference separation d₀ where u_N = 0;
    /// default 10⁻³ × lo.
    pub reference_pressure: Option<f64>,
    /// Points of the table law (default 10, 2 to 100).
    pub table_points: Option<usize>,
}

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
}

fn positive(place: &str, key: &str, v: f64) -> Result<()> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(Error::input(
            format!("{place}: {key}"),
            format!("must be a positive finite number, got {v}"),
        ))
    }
}

/// Reads and parses an input file (errors name the file, line and column).
pub fn load(path: &Path) -> Result<Input> {
    let place = path.display().to_string();
    let bytes = crate::case::read_input(path, MAX_INPUT_BYTES, "calibration input")?;
    let text = String::from_utf8(bytes)
        .map_err(|_| Error::input(&place, "the input file is not valid UTF-8 text"))?;
    parse(&text, &place)
}

/// Parses input text; `place` names it in errors.
pub fn parse(text: &str, place: &str) -> Result<Input> {
    toml::from_str::<Input>(text).map_err(|e| {
        let at = e
            .span()
            .map(|s| {
                let before = &text[..s.start.min(text.len())];
                let line = before.matches('\n').count() + 1;
                let col = before.rfind('\n').map_or(s.start, |i| s.start - i - 1) + 1;
                format!(":{line}:{col}")
            })
            .unwrap_or_default();
        Error::input(
            format!("{place}{at}"),
            e.message().trim().replace('\n', " "),
        )
    })
}

/// Composite modulus E* = 1/((1−ν₁²)/E₁ + (1−ν₂²)/E₂) (Johnson 1985, eq. 4.22).
pub fn composite_modulus(a: &Body, b: &Body) -> f64 {
    1.0 / ((1.0 - a.poisson * a.poisson) / a.young + (1.0 - b.poisson * b.poisson) / b.young)
}

/// Checks the input and computes the curve, the fit and the table; `base` is
/// the folder that relative profile paths start from.
pub fn calibrate(input: &Input, place: &str, base: &Path) -> Result<Calibration> {
    for (name, body) in [("a", &input.materials.a), ("b", &input.materials.b)] {
        let p = format!("materials.{name}");
        positive(place, &format!("{p}.young"), body.young)?;
        if !(body.poisson > -1.0 && body.poisson < 0.5) {
            return Err(Error::input(
                format!("{place}: {p}.poisson"),
                format!("must be in (−1, 0.5), got {}", body.poisson),
            ));
        }
        if let Some(h) = body.hardness {
            positive(place, &format!("{p}.hardness"), h)?;
        }
    }
    let e_star = composite_modulus(&input.materials.a, &input.materials.b);
    let asperity = |key: &str| -> Result<Asperity> {
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
    };
    let (gw, moments) = match &input.surface {
        Surface::Gw {
            density,
            radius,
            sigma,
            distribution,
            asperities,
        } => {
            positive(place, "surface.density", *density)?;
            positive(place, "surface.radius", *radius)?;
            positive(place, "surface.sigma", *sigma)?;
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
                asperity: asperity(asperities)?,
                e_star,
            };
            (gw, None)
        }
        Surface::Profile {
            file,
            sampling,
            kind,
            detrend,
            asperities,
        } => {
            positive(place, "surface.sampling", *sampling)?;
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
            let asperity = asperity(asperities)?;
            let path = base.join(file);
            let fplace = path.display().to_string();
            let bytes = crate::case::read_input(&path, MAX_PROFILE_BYTES, "profile")?;
            let text = String::from_utf8(bytes)
                .map_err(|_| Error::input(&fplace, "the profile is not valid UTF-8 text"))?;
            let heights = profile::parse(&text, &fplace, areal, *sampling)?;
            let m = heights.moments(how);
            let s = m.summits(&fplace)?;
            let gw = Gw {
                density: s.density,
                radius: s.radius,
                sigma: s.sigma,
                distribution: Distribution::Gaussian,
                asperity,
                e_star,
            };
            (gw, Some((m, s)))
        }
    };
    let fs = &input.fit;
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
    positive(place, "fit.pressure", lo)?;
    positive(place, "fit.pressure", hi)?;
    if lo >= hi {
        return Err(Error::input(
            format!("{place}: fit.pressure"),
            format!("lo {lo} must be below hi {hi}"),
        ));
    }
    let p_ref = fs.reference_pressure.unwrap_or(1e-3 * lo);
    positive(place, "fit.reference_pressure", p_ref)?;
    if p_ref >= lo {
        return Err(Error::input(
            format!("{place}: fit.reference_pressure"),
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
    // pressures beyond what the model can carry: a surface far too soft or stiff
    let deepest = gw.pressure(-50.0 * gw.sigma);
    if deepest.is_nan() || deepest <= 2.0 * hi {
        return Err(Error::input(
            format!("{place}: fit.pressure"),
            format!("the surface does not reach {hi} MPa within 50 σ of approach"),
        ));
    }
    let d0 = gw.separation(p_ref);
    let fitted = fit::curve(&gw, d0, &fit::log_space(lo, hi, 101));
    let mut ps = fit::log_space(p_ref, lo, 41);
    ps.pop();
    ps.extend(fit::log_space(lo, hi, 101));
    ps.pop();
    ps.extend(fit::log_space(hi, 2.0 * hi, 21));
    let curve = fit::curve(&gw, d0, &ps);
    let fit = fit::power_law(&fitted)
        .ok_or_else(|| Error::input(place, "the curve cannot be fitted (no approach)"))?;
    let table = fit::curve(&gw, d0, &fit::log_space(lo, hi, n_table));
    let increasing = table
        .windows(2)
        .all(|w| w[1].approach > w[0].approach && w[1].pressure > w[0].pressure);
    if !increasing || table[0].approach <= 0.0 {
        return Err(Error::input(
            place,
            "the table's approaches are not positive and strictly increasing (range too narrow for the model's accuracy)",
        ));
    }
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
    })
}

impl Calibration {
    /// `curve.csv`.
    pub fn curve_csv(&self) -> String {
        let mut s = String::from("approach_mm,pressure_mpa\n");
        for q in &self.curve {
            let _ = writeln!(s, "{:.12e},{:.12e}", q.approach, q.pressure);
        }
        s
    }

    /// `fit.json`.
    pub fn fit_json(&self, source: &str) -> serde_json::Value {
        let g = &self.gw;
        let (model, hardness, k) = match g.asperity {
            Asperity::Elastic => ("elastic (Hertz)", None, None),
            Asperity::Ceb { hardness, k } => (
                "elastic-plastic (Chang, Etsion & Bogy 1987)",
                Some(hardness),
                Some(k),
            ),
        };
        let profile = self.moments.map(|(m, s)| {
            json!({"m0_mm2": m.m0, "m2": m.m2, "m4_per_mm2": m.m4, "bandwidth_alpha": s.alpha})
        });
        json!({
            "input": source,
            "c_n": self.fit.c_n,
            "m": self.fit.m,
            "pressure_range_mpa": self.range,
            "max_relative_error_approach": self.fit.max_error,
            "rms_relative_error_approach": self.fit.rms_error,
            "fit_points": self.fitted.len(),
            "reference_pressure_mpa": self.reference_pressure,
            "d0_mm": self.d0,
            "d0_over_sigma": self.d0 / g.sigma,
            "e_star_mpa": g.e_star,
            "gw": {
                "density_per_mm2": g.density,
                "radius_mm": g.radius,
                "sigma_mm": g.sigma,
                "distribution": match g.distribution {
                    Distribution::Gaussian => "gaussian",
                    Distribution::Exponential => "exponential",
                },
                "asperities": model,
                "hardness_mpa": hardness,
                "ceb_k": k,
                "critical_interference_mm": g.critical_interference().is_finite().then(|| g.critical_interference()),
                "plasticity_index": hardness.map(|h| g.e_star / h * (g.sigma / g.radius).sqrt()),
            },
            "profile": profile,
        })
    }

    /// `interface.toml`: the two snippets.
    pub fn interface_toml(&self, source: &str) -> String {
        let [lo, hi] = self.range;
        let f = &self.fit;
        let mut s = String::new();
        let _ = writeln!(s, "# asperity calibrate {source}");
        let _ = writeln!(
            s,
            "# Two interface laws for the same surface; paste one into the case and rename\n# the table to the interface's name ([interface.<name>]). Approaches in mm from\n# the separation where p = {:.4e} MPa; pressures in MPa.\n",
            self.reference_pressure
        );
        let _ = writeln!(
            s,
            "# power law u_N = c_N p^m fitted over {lo}-{hi} MPa: max relative error in u_N {:.2}%",
            100.0 * f.max_error
        );
        if !(f.m > 0.0 && f.m <= 1.0) {
            let _ = writeln!(
                s,
                "# NOTE: m = {:.4} is outside (0, 1], which the case file refuses: use the table",
                f.m
            );
        }
        let _ = writeln!(
            s,
            "[interface.calibrated_power]\nlaw = \"power\"\nc_n = {:.6e}\nm = {:.6}\n",
            f.c_n, f.m
        );
        let _ = writeln!(
            s,
            "# the curve itself at {} pressures spaced evenly in log p over {lo}-{hi} MPa",
            self.table.len()
        );
        let rows: Vec<String> = self
            .table
            .iter()
            .map(|q| format!("  [{:.9e}, {:.9e}],", q.approach, q.pressure))
            .collect();
        let _ = writeln!(
            s,
            "[interface.calibrated_table]\nlaw = \"table\"\ntable = [\n{}\n]",
            rows.join("\n")
        );
        s
    }

    /// The figure: pressure against approach, the GW curve and the power law.
    fn chart(&self) -> crate::study::plot::Chart {
        use crate::study::plot::{Chart, Series};
        let [lo, hi] = self.range;
        let f = self.fit;
        let shown: Vec<&Point> = self
            .curve
            .iter()
            .filter(|q| q.pressure >= 0.5 * lo)
            .collect();
        let power = fit::log_space(0.5 * lo, 2.0 * hi, 80)
            .into_iter()
            .map(|p| (1e3 * f.c_n * p.powf(f.m), p))
            .collect();
        Chart {
            title: "Load-approach curve of the rough pair".into(),
            x_label: "approach u_N (µm)".into(),
            y_label: "nominal pressure p (MPa)".into(),
            series: vec![
                Series {
                    label: "Greenwood-Williamson".into(),
                    points: shown
                        .iter()
                        .map(|q| (1e3 * q.approach, q.pressure))
                        .collect(),
                },
                Series {
                    label: format!(
                        "u_N = {:.4e} p^{:.4} (max error {:.2}% over {lo}-{hi} MPa)",
                        f.c_n,
                        f.m,
                        100.0 * f.max_error
                    ),
                    points: power,
                },
            ],
            hlines: vec![(lo, format!("{lo} MPa")), (hi, format!("{hi} MPa"))],
            ..Chart::default()
        }
    }
}

/// Runs `asperity calibrate INPUT --out DIR`: the files are written into a
/// temporary folder next to DIR, which replaces DIR only when complete.
/// Returns the files written (relative names) and a one-line summary.
pub fn run(input_path: &Path, out: &Path) -> Result<(Vec<PathBuf>, String)> {
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
        let pictures = crate::study::plot::load_font();
        crate::study::plot::save_pictures(&cal.chart(), &tmp.join("curve"), pictures)?;
        if pictures {
            files.push("curve.svg".into());
            files.push("curve.png".into());
        }
        files.push(write("curve.csv", &cal.curve_csv())?);
        let json = serde_json::to_string_pretty(&cal.fit_json(&place))
            .map_err(|e| Error::Output(e.to_string()))?;
        files.push(write("fit.json", &(json + "\n"))?);
        files.push(write("interface.toml", &cal.interface_toml(&place))?);
        crate::output::replace_dir(&tmp, out)?;
        Ok(files)
    })();
    if result.is_err() {
        let _ = std::fs::remove_dir_all(&tmp);
    }
    let summary = format!(
        "c_n = {:.6e} mm/MPa^m, m = {:.6} over {}-{} MPa (max relative error in u_N {:.2}%); E* = {:.1} MPa, η = {:.4e}/mm², β = {:.4e} mm, σ_s = {:.4e} mm; written to {}",
        cal.fit.c_n,
        cal.fit.m,
        cal.range[0],
        cal.range[1],
        100.0 * cal.fit.max_error,
        cal.gw.e_star,
        cal.gw.density,
        cal.gw.radius,
        cal.gw.sigma,
        out.display()
    );
    result.map(|f| (f, summary))
}
