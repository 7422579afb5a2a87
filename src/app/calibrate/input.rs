//! The input file of `asperity calibrate`: `[materials]`, `[surface]`,
//! `[fit]` and `[tangential]`, read and parsed with its errors placed by
//! line and column (docs/calibration.md "The input file").

use super::*;

/// The input file.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Input {
    pub materials: Materials,
    pub surface: Surface,
    pub fit: FitSpec,
    /// `[tangential]`: the Mindlin-GW shear stiffness as a k_table too.
    pub tangential: Option<tangential::Input>,
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
    /// Ra or Rz (mm) of the drawing, one number or [face a, face b], or a
    /// table per face (`a = { ra = … }`, `b = { rz = … }`), and an assumed
    /// spectrum ([`roughness`]).
    Roughness {
        ra: Option<toml::Value>,
        rz: Option<toml::Value>,
        /// The face of body a, with its own parameter.
        a: Option<FaceInput>,
        /// The face of body b.
        b: Option<FaceInput>,
        /// H of the assumed spectrum (default 0.8, band 0.5-1 reported).
        hurst: Option<f64>,
        /// λc, mm (default ISO 4288 for the roughness).
        cutoff: Option<f64>,
        /// λs, mm (default ISO 3274 for λc).
        short_cutoff: Option<f64>,
        #[serde(default = "elastic")]
        asperities: String,
    },
}

/// `surface.a` / `surface.b` of the roughness model: the face's Ra or its
/// Rz (mm), exactly one.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FaceInput {
    pub ra: Option<toml::Value>,
    pub rz: Option<toml::Value>,
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
    pub(crate) table_points: Option<usize>,
}

/// Reads and parses an input file (errors name the file, line and column).
pub fn load(path: &Path) -> Result<Input> {
    let place = path.display().to_string();
    let bytes = crate::input::case::read_input(path, MAX_INPUT_BYTES, "calibration input")?;
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
        let mut message = e.message().trim().replace('\n', " ");
        // a table written twice (`[surface.a]` twice): name it
        if let (true, Some(s)) = (message == "duplicate key", e.span()) {
            if let Some(key) = text.get(s).filter(|k| !k.is_empty() && k.len() <= 80) {
                message = format!("duplicate key `{key}`: each key and table may be given once");
            }
        }
        Error::input(format!("{place}{at}"), message)
    })
}
