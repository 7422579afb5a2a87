//! Case files: the TOML schema (serde, unknown keys rejected) and its validation.
//!
//! A case is data, never code: geometry and mesh, materials per body, the
//! interface law per interface, boundary conditions, loads and solver settings.
//! The full schema is documented in `docs/case-schema.md`; every field below
//! carries the same text.

pub mod adapt;
pub mod cyclic;
pub mod expression;
pub mod outputs;
pub mod overrides;
pub mod ranges;
pub mod rating;
pub mod solid;
pub mod twist;
mod validate;

pub use validate::check_case;
pub(crate) use validate::{
    backbone_keys, memory_error_key, Checked, MAX_ELEMENTS, MAX_INCREMENTS, MAX_NAME_BYTES,
};

pub use crate::physics::contact::Memory;
pub use crate::physics::material::Plane;
pub use settings::FrictionScheme;
pub(crate) use settings::Weights;
pub mod settings;
pub(crate) use settings::{Acceleration, Stabilization};
pub use settings::{Method, StepControl};
mod solver;
pub(crate) use solver::default_plastic_strain_step;
pub use solver::SolverSpec;
#[cfg(test)]
mod tests;

use crate::error::{Error, Result};
use crate::input::mesh::blocks::{BlockSpec, InterfaceSpec};
use crate::physics::contact::normal::{Given, Value};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// A parsed case file, before validation against its mesh.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Case {
    /// Name used for the output folder; default: the case folder's name.
    pub name: Option<String>,
    /// Free text shown by `asperity check`.
    pub description: Option<String>,
    pub model: ModelSpec,
    pub mesh: MeshSpec,
    /// Material per body, keyed by body name.
    pub materials: BTreeMap<String, MaterialSpec>,
    /// Interface law per interface, keyed by interface name.
    #[serde(default)]
    pub interface: BTreeMap<String, InterfaceLawSpec>,
    #[serde(default)]
    pub boundary: Vec<BoundarySpec>,
    #[serde(default)]
    pub load: Vec<LoadSpec>,
    #[serde(default)]
    pub solver: SolverSpec,
    #[serde(default)]
    pub output: OutputSpec,
    /// Where the case was read from (not part of the schema).
    #[serde(skip)]
    pub source: PathBuf,
    /// What the command line set in place of the file's keys (not part of
    /// the schema, nor of [`Case::key`]: the effective values are).
    #[serde(skip)]
    pub overrides: overrides::Overrides,
    /// Concentrated forces on node sets.
    #[serde(default)]
    pub force: Vec<ForceSpec>,
    /// Named load histories (pseudo-time → factor), referenced by name.
    #[serde(default)]
    pub history: BTreeMap<String, Vec<Vec<f64>>>,
    /// Pretension sections (bolts): [`crate::model::pretension`].
    #[serde(default)]
    pub pretension: Vec<PretensionSpec>,
    /// Named displacement probes (points or node sets).
    #[serde(default)]
    pub probe: Vec<outputs::ProbeSpec>,
    /// An adaptive run (`[adapt]`, [`crate::app::adapt`]).
    pub adapt: Option<adapt::AdaptSpec>,
    /// Joints rated to a design standard ([`crate::verdict`]).
    #[serde(default)]
    pub rating: Vec<rating::RatingSpec>,
    /// Uniform temperature changes of bodies (thermal strain).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub temperature: Vec<TemperatureSpec>,
    /// A rotational speed about the model's axis (centrifugal body force).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub speed: Option<SpeedSpec>,
}

/// A pretension section (`[[pretension]]`, after Abaqus *PRE-TENSION SECTION):
/// a cut across a body along an element line (element faces in 3D), whose two sides are tied but
/// for a relative displacement s along the cut's normal (the shortening),
/// loaded by a force or a prescribed shortening ([`crate::model::pretension`]).
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct PretensionSpec {
    pub name: String,
    /// The body the section cuts.
    pub body: String,
    /// The cut along x = this value (plane and 3D models): its normal is +x.
    pub x: Option<f64>,
    /// The cut along y = this value: its normal is +y.
    pub y: Option<f64>,
    /// The cut in the plane z = this value (3D models): its normal is +z.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub z: Option<f64>,
    /// The section force at factor 1 (N; the whole ring in axisymmetry,
    /// the model's thickness in plane models): tension positive.
    pub force: Option<f64>,
    /// Or the shortening at factor 1 (mm): the side beyond the cut moves
    /// by −s along the normal relative to the other.
    pub shortening: Option<f64>,
    /// The factor's history; none: the load factor (or the default ramp).
    pub history: Option<HistoryRef>,
    /// A force-controlled section is locked (its shortening held) after
    /// its history's last time; default true. Not with `shortening`.
    pub lock: Option<bool>,
}

#[derive(Clone, Copy, Debug, Deserialize, Serialize, PartialEq, Eq, Default)]
#[serde(rename_all = "kebab-case")]
pub enum Integration {
    /// 3×3 Gauss points (the paper's choice for the 8-node element).
    #[default]
    Full,
    /// 2×2 Gauss points: avoids volumetric locking in plane-strain plastic flow.
    Reduced,
}

#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ModelSpec {
    /// "stress", "strain" or "axisymmetric" (x = r, y = z).
    pub plane: Plane,
    /// Thickness in mm (plane stress); plane strain is solved per mm unless
    /// given; refused in axisymmetry (the full revolution is the body).
    #[serde(default)]
    pub thickness: Thickness,
    #[serde(default)]
    pub integration: Integration,
    /// The mesh is the half x ≥ 0 of a body symmetric about x = 0: loads are
    /// reported for the whole body (twice the half model's).
    #[serde(default)]
    pub symmetric_half: bool,
    /// An axisymmetric model with twist: a third displacement u_θ per node
    /// (torsion about the axis; [`crate::input::case::twist`]).
    #[serde(default)]
    pub twist: bool,
    /// The mesh is one sector of a part of `sectors` equal sectors about
    /// the y axis, its cut faces tied by rotational periodicity
    /// ([`cyclic`], [`crate::model::cyclic`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cyclic: Option<cyclic::CyclicSpec>,
}

/// `[model] thickness` as given (None: not in the case file).
#[derive(Clone, Copy, Debug, Default, Deserialize, PartialEq)]
#[serde(transparent)]
pub struct Thickness(pub Option<f64>);

impl Thickness {
    /// The thickness in mm: as given, else 1.
    pub fn value(self) -> f64 {
        self.0.unwrap_or(1.0)
    }
}

/// The value ([`Thickness::value`]): the case's key ([`Case::key`]) is of
/// the effective case, and a thickness left out is 1 mm.
impl Serialize for Thickness {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        s.serialize_f64(self.value())
    }
}

#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct MeshSpec {
    /// Multiplies every element count (mesh sequences); must be 1 for a file mesh.
    #[serde(default = "one_usize")]
    pub refine: usize,
    /// A Gmsh `.msh` 4.1 file (relative to the case folder) instead of blocks.
    pub file: Option<PathBuf>,
    #[serde(default)]
    pub block: Vec<BlockSpec>,
    #[serde(default)]
    pub interface: Vec<InterfaceSpec>,
    /// Local refinement: the elements whose centroid lies in a box split
    /// into four, `levels` times ([`crate::input::mesh::refine`]).
    pub refine_region: Option<RefineRegion>,
    /// A 3D model's mesh: the block layout swept along z
    /// (`input::mesh::extrude`).
    pub extrude: Option<Extrude>,
    /// A 3D model's mesh: the block layout revolved about the y axis
    /// (`input::mesh::revolve`).
    pub revolve: Option<Revolve>,
}

/// `[mesh] revolve = { angle = 90.0, n = 12 }`: the block layout (x the
/// radius) revolved about the y axis from the plane z = 0 through `angle`
/// degrees in `n` equal layers.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Revolve {
    pub angle: f64,
    pub n: usize,
}

/// `[mesh] extrude = { z = [z₀, …], nz = [n, …], rz = [r, …] }`: the layers
/// along z, graded as a block's x and y.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Extrude {
    pub z: Vec<f64>,
    pub nz: Vec<usize>,
    #[serde(default)]
    pub rz: Vec<f64>,
}

/// `[mesh] refine_region = { x = [x₀, x₁], y = [y₀, y₁], levels = N }`.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct RefineRegion {
    pub x: [f64; 2],
    pub y: [f64; 2],
    pub levels: usize,
}

#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialSpec {
    /// Young's modulus E, MPa.
    pub young: f64,
    /// Poisson's ratio ν.
    pub poisson: f64,
    /// Initial yield stress σ_Y, MPa; omit for an elastic body.
    pub yield_stress: Option<f64>,
    /// Plastic modulus H, MPa: σ_y = σ_Y + H ε̄ᵖ (0 = perfectly plastic).
    #[serde(default)]
    pub hardening: f64,
    /// Linear thermal expansion coefficient α, 1/K (≥ 0); needed by a
    /// `[[temperature]]` on the body.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub expansion: Option<f64>,
    /// Density ρ, kg/m³; needed by a `[speed]` (the body force ρ ω² r).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub density: Option<f64>,
    /// Young's modulus against temperature: rows [T °C, E MPa], T rising;
    /// `young` is its value at the body's reference temperature.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub young_table: Option<Vec<Vec<f64>>>,
    /// The initial yield stress against temperature: rows [T °C, σ_Y MPa].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub yield_table: Option<Vec<Vec<f64>>>,
}

/// The model's rotational speed (`[speed]`): every body spins about the
/// model's axis and carries the body force ρ ω² r
/// ([`crate::model::loads::speed`]).
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct SpeedSpec {
    /// The speed n at factor 1, revolutions per minute: ω = 2π n / 60.
    pub rpm: f64,
    /// The speed's history (ω(t) = ω h(t), the force ∝ h(t)²); none: the
    /// load factor (or the default ramp).
    pub history: Option<HistoryRef>,
}

/// A uniform temperature change of one body (`[[temperature]]`): the free
/// thermal strain α ΔT h(t) on every normal strain component of its
/// elements ([`crate::model::loads::thermal`]).
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct TemperatureSpec {
    /// The body heated or cooled.
    pub body: String,
    /// ΔT at factor 1, K, relative to the stress-free (assembly) state.
    pub change: f64,
    /// The temperature of the stress-free state, °C (optional): the body's
    /// temperature may then not fall below absolute zero.
    pub reference: Option<f64>,
    /// The factor's history; none: the load factor (or the default ramp).
    pub history: Option<HistoryRef>,
    /// A temperature field: ΔT(x) = change × the profile's factor at the
    /// coordinate `along` ("x", "y", "z", or "r": the distance from the
    /// model's axis), rows [coordinate mm, factor].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub along: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub profile: Option<Vec<Vec<f64>>>,
    /// A temperature field as a function of position: ΔT(x) = change × the
    /// expression's value at x, y, z and r (the distance from the model's
    /// axis; [`expression`]). Not with `along` and `profile`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub field: Option<String>,
}

/// Normal (and later tangential) law of one interface. The parameters that a law
/// needs are checked by [`check_case`]; parameters that belong to another law are
/// rejected there, so a typo cannot pass silently.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct InterfaceLawSpec {
    /// "power" (u_N = c_N p^m, eq. 2.1), "exponential" (p = a (e^{b u} − 1), eq. 2.2
    /// shifted so p(0) = 0), "linear" (power law below p_c, u = A p + B above, eq. 2.3)
    /// or "table" (measured points, `table`).
    pub law: String,
    /// c_N in mm/MPa^m (power and linear laws).
    pub c_n: Option<f64>,
    /// Exponent m in (0, 1] (power and linear laws).
    pub m: Option<f64>,
    /// a in MPa (exponential law).
    pub a: Option<f64>,
    /// b in 1/mm (exponential law).
    pub b: Option<f64>,
    /// A in mm/MPa: slope of the linear branch (linear law).
    pub slope: Option<f64>,
    /// Critical pressure p_c in MPa where the linear branch starts (linear law).
    pub p_c: Option<f64>,
    /// Measured points [[u_N mm, p MPa], ...] (table law): both columns positive
    /// and strictly increasing, at least 2 rows (a first row [0, 0] is the
    /// implied origin); interpolated monotonically, see docs/case-schema.md.
    pub table: Option<Vec<Vec<f64>>>,
    /// "lumped" (row-sum weights 1/6, 2/3, 1/6, eq. 3.30-3.31) or "consistent"
    /// (Gauss integration along the edge, eq. 3.29).
    #[serde(default)]
    pub weights: Weights,
    /// Initial gap g₀ in mm (positive = open).
    #[serde(default)]
    pub gap: f64,
    /// Reference pressure in MPa for the secant start stiffness (eq. 2.8-2.9);
    /// default: the mean interface pressure of the applied load at the first step.
    pub(crate) start_pressure: Option<f64>,
    /// Tangential compliance and friction (section 2.2, 2.4-2.6); none = frictionless.
    pub tangential: Option<TangentialSpec>,
    /// The gap at pseudo-time t is g₀ · h(t) (an interference pressed in
    /// gradually); none: g₀ from the start.
    pub gap_history: Option<HistoryRef>,
    /// 3D: [x, y, z] (mm), the point the joint's moment is taken about;
    /// none: the interface's centroid.
    pub moment_point: Option<Vec<f64>>,
}

impl InterfaceLawSpec {
    /// The normal law's parameters as written, whichever law they belong to
    /// (the law's file, `physics/contact/normal/`, says which it takes).
    /// A new parameter key is a field above and a row here.
    pub(crate) fn law_params(&self) -> Given<'_> {
        let numbers = [
            ("c_n", self.c_n),
            ("m", self.m),
            ("a", self.a),
            ("b", self.b),
            ("slope", self.slope),
            ("p_c", self.p_c),
        ];
        let rows = [("table", self.table.as_deref())];
        let numbers = numbers
            .into_iter()
            .filter_map(|(k, v)| Some((k, Value::Number(v?))));
        let rows = rows
            .into_iter()
            .filter_map(|(k, v)| Some((k, Value::Rows(v?))));
        Given(rows.chain(numbers).collect())
    }
}

/// `[interface.<name>.tangential]`: elastic-plastic shear compliance with
/// slip-hardening friction, one slip history per integration point (a pair
/// with lumped weights, a Gauss point with consistent ones, a slave node
/// with mortar).
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct TangentialSpec {
    /// R: k_T^e = p_N^S / R in MPa/µm with p_N in MPa (eq. 2.6); not with `k_table`.
    pub r: Option<f64>,
    /// S, in [0, 1]; not with `k_table`.
    pub s: Option<f64>,
    /// Measured [[p_N MPa, k_T^e MPa/µm], ...] in place of `r` and `s`.
    pub k_table: Option<Vec<Vec<f64>>>,
    /// k_T^p / k_T^e in [0, 1] (1: no micro-slip branch); the bilinear backbone only.
    pub kp_ratio: Option<f64>,
    /// Macroscopic (static) friction coefficient μ_m.
    pub mu: f64,
    /// Initial friction coefficient as a fraction of μ_m (eq. 2.21), in (0, 1].
    #[serde(default = "one")]
    pub beta: f64,
    /// Slip-hardening rate n, 1/mm (eq. 2.21).
    #[serde(default)]
    pub n: f64,
    /// p_T^Y / (μ_m p_N): 0.625 per eq. 2.18 (eq. 2.5 says 0.5); the bilinear backbone only.
    /// In the case's key the ratio in force ([`TangentialSpec::yield_ratio`]).
    #[serde(serialize_with = "effective_yield_ratio")]
    pub(crate) yield_ratio: Option<f64>,
    /// "return-mapping" (consistent tangent) or "stiffness-modification" (the paper's 2.25-2.26).
    #[serde(default)]
    pub scheme: FrictionScheme,
    /// "isotropic" (section 2.2) or "kinematic" (Masing).
    #[serde(default)]
    pub memory: Memory,
    /// "bilinear" (the paper's two lines) or "iwan" (a density of slip thresholds).
    #[serde(default)]
    pub backbone: BackboneKind,
    /// Iwan: the exponent χ of the threshold density, in [−0.99, 1] (0: uniform).
    pub chi: Option<f64>,
    /// Iwan: the fraction of the elements at the top threshold, in [0, 1).
    pub spike: Option<f64>,
}

/// `backbone` of `[interface.<name>.tangential]`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum BackboneKind {
    #[default]
    Bilinear,
    Iwan,
}

impl TangentialSpec {
    /// p_T^Y / (μ_m p_N), 0.625 unless given.
    pub(crate) fn yield_ratio(&self) -> f64 {
        self.yield_ratio.unwrap_or_else(default_yield_ratio)
    }
}

/// `yield_ratio` as the key holds it: the ratio in force, given or not.
fn effective_yield_ratio<S: serde::Serializer>(
    v: &Option<f64>,
    s: S,
) -> std::result::Result<S::Ok, S::Error> {
    s.serialize_f64(v.unwrap_or_else(default_yield_ratio))
}

fn default_yield_ratio() -> f64 {
    0.625
}

/// A load's history: the name of a `[history]` entry, or a table given in place.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(untagged)]
pub enum HistoryRef {
    Name(String),
    Table(Vec<Vec<f64>>),
}

impl<'de> Deserialize<'de> for HistoryRef {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        struct Visit;
        impl<'de> serde::de::Visitor<'de> for Visit {
            type Value = HistoryRef;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("the name of a [history] entry or a table [[time, value], ...]")
            }
            fn visit_str<E: serde::de::Error>(self, v: &str) -> std::result::Result<HistoryRef, E> {
                Ok(HistoryRef::Name(v.to_string()))
            }
            fn visit_seq<A: serde::de::SeqAccess<'de>>(
                self,
                seq: A,
            ) -> std::result::Result<HistoryRef, A::Error> {
                Vec::deserialize(serde::de::value::SeqAccessDeserializer::new(seq))
                    .map(HistoryRef::Table)
            }
        }
        d.deserialize_any(Visit)
    }
}

/// Prescribed displacement on a node set (value at factor 1; 0 = fixed).
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct BoundarySpec {
    /// Node set name, e.g. "foundation.bottom".
    pub set: String,
    pub ux: Option<f64>,
    pub uy: Option<f64>,
    /// u_z (3D models).
    pub uz: Option<f64>,
    /// Only nodes with x in [lo, hi] (mm).
    #[serde(default, deserialize_with = "two_numbers_opt")]
    pub x_range: Option<[f64; 2]>,
    #[serde(default, deserialize_with = "two_numbers_opt")]
    pub y_range: Option<[f64; 2]>,
    /// Only nodes with z in [lo, hi] (mm; 3D models).
    #[serde(default, deserialize_with = "two_numbers_opt")]
    pub z_range: Option<[f64; 2]>,
    /// The factor's history; none: the load factor (or the default ramp).
    pub history: Option<HistoryRef>,
    /// A prescribed rotation φ about the axis (rad, twist only): u_θ = φ r.
    pub rotation: Option<f64>,
}

/// Uniform traction on an edge set (values at factor 1, MPa): a pressure
/// pushing into the body and a shear along the edge's tangent.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct LoadSpec {
    /// Edge set name, e.g. "punch.top" (plane models).
    #[serde(default)]
    pub edges: String,
    /// Face set name (3D models), e.g. "punch.top".
    pub faces: Option<String>,
    #[serde(default)]
    pub pressure: f64,
    /// A traction vector (t_x, t_y, t_z), MPa (3D models).
    pub traction: Option<Vec<f64>>,
    /// Only edges (faces) whose midpoint (centre) has x in [lo, hi] (mm).
    #[serde(default, deserialize_with = "two_numbers_opt")]
    pub x_range: Option<[f64; 2]>,
    #[serde(default, deserialize_with = "two_numbers_opt")]
    pub y_range: Option<[f64; 2]>,
    #[serde(default, deserialize_with = "two_numbers_opt")]
    pub z_range: Option<[f64; 2]>,
    /// Shear traction along t = (n_y, −n_x), the outward normal turned
    /// clockwise (+x on a top edge).
    #[serde(default)]
    pub shear: f64,
    /// The factor's history; none: the load factor (or the default ramp).
    pub history: Option<HistoryRef>,
    /// A uniform circumferential shear traction τ_θ (MPa, along +θ; twist only).
    pub(crate) hoop_shear: Option<f64>,
    /// A torque about the axis (N·mm, +z right-handed; twist only), carried by
    /// τ_θ = T r / ∫ r² dA over the selected edges (∫ r τ_θ dA = T).
    pub torque: Option<f64>,
}

/// A concentrated force at every node of a node set (N, at factor 1; for
/// the model's thickness, or the whole revolution in axisymmetry).
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ForceSpec {
    /// Node set name, e.g. "punch.top".
    pub nodes: String,
    #[serde(default)]
    pub fx: f64,
    #[serde(default)]
    pub fy: f64,
    /// N (3D models).
    #[serde(default)]
    pub fz: f64,
    /// Only nodes with x in [lo, hi] (mm).
    #[serde(default, deserialize_with = "two_numbers_opt")]
    pub x_range: Option<[f64; 2]>,
    #[serde(default, deserialize_with = "two_numbers_opt")]
    pub y_range: Option<[f64; 2]>,
    #[serde(default, deserialize_with = "two_numbers_opt")]
    pub z_range: Option<[f64; 2]>,
    /// The factor's history; none: the load factor (or the default ramp).
    pub history: Option<HistoryRef>,
}

/// Exactly two numbers: serde's fixed-size arrays would drop a third one
/// silently (`probe = [1, 2, 3]` read as `[1, 2]`).
fn two_numbers<'de, D: serde::Deserializer<'de>>(d: D) -> std::result::Result<[f64; 2], D::Error> {
    let v: Vec<f64> = Vec::deserialize(d)?;
    <[f64; 2]>::try_from(v.as_slice()).map_err(|_| {
        serde::de::Error::custom(format!(
            "expected exactly 2 numbers ([x, y] or [lo, hi]), found {}",
            v.len()
        ))
    })
}

/// A point: [x, y], or [x, y, z] in a 3D model (the count is checked
/// against the model with the case).
pub(crate) fn point_opt<'de, D: serde::Deserializer<'de>>(
    d: D,
) -> std::result::Result<Option<Vec<f64>>, D::Error> {
    let v: Vec<f64> = Vec::deserialize(d)?;
    match v.len() {
        2 | 3 => Ok(Some(v)),
        n => Err(serde::de::Error::custom(format!(
            "expected a point, [x, y] or in a 3D model [x, y, z], found {n} numbers"
        ))),
    }
}

pub(crate) fn two_numbers_opt<'de, D: serde::Deserializer<'de>>(
    d: D,
) -> std::result::Result<Option<[f64; 2]>, D::Error> {
    two_numbers(d).map(Some)
}

#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct OutputSpec {
    /// Point near which the "center" node is taken (the interface node of the lower
    /// body closest to it), mm. Default (0, 0).
    #[serde(default, deserialize_with = "two_numbers")]
    pub probe: [f64; 2],
    /// Write VTU files (every `vtu_every` increments and the last).
    #[serde(default = "yes")]
    pub vtu: bool,
    #[serde(default = "one_usize")]
    pub vtu_every: usize,
    /// Encoding of the VTU files: `binary` (default; raw appended data, the
    /// arrays' exact IEEE-754 bits) or `ascii` (text, `{:e}` shortest form).
    #[serde(default)]
    pub vtu_format: VtuFormat,
    /// Width of an event's bracket in load factor (pseudo-time), in
    /// [1e-12, 1); default 1e-3 (`outputs::DEFAULT_EVENT_TOLERANCE`).
    pub event_tolerance: Option<f64>,
}

/// How the VTU files hold their arrays (docs/output.md, "VTU").
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum VtuFormat {
    /// `<AppendedData encoding="raw">`: little-endian bytes, UInt64 block headers.
    #[default]
    Binary,
    /// Every number as text inside its `<DataArray>`.
    Ascii,
}

impl<'de> Deserialize<'de> for VtuFormat {
    /// A string, `binary` or `ascii`; anything else is refused with the key's
    /// name and both choices (not the TOML crate's "wanted string or table").
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        struct Choice;
        impl serde::de::Visitor<'_> for Choice {
            type Value = VtuFormat;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("vtu_format \"binary\" or \"ascii\"")
            }
            fn visit_str<E: serde::de::Error>(self, v: &str) -> std::result::Result<VtuFormat, E> {
                match v {
                    "binary" => Ok(VtuFormat::Binary),
                    "ascii" => Ok(VtuFormat::Ascii),
                    _ => Err(E::invalid_value(serde::de::Unexpected::Str(v), &self)),
                }
            }
        }
        d.deserialize_any(Choice)
    }
}

impl Default for OutputSpec {
    fn default() -> Self {
        toml::from_str("").expect("the empty output table has only defaults")
    }
}

fn one() -> f64 {
    1.0
}
fn one_usize() -> usize {
    1
}
fn yes() -> bool {
    true
}

impl Case {
    /// Reads a case from a `case.toml` file or from a folder holding one.
    pub fn load(path: &Path) -> Result<Case> {
        let file = if path.is_dir() {
            path.join("case.toml")
        } else {
            path.to_path_buf()
        };
        let bytes = read_input(&file, MAX_CASE_BYTES, "case file")?;
        let text = String::from_utf8(bytes).map_err(|e| {
            Error::input(
                file.display().to_string(),
                format!("the case file is not valid UTF-8 text ({})", e.utf8_error()),
            )
        })?;
        let mut case = Case::parse(&text, &file.display().to_string())?;
        case.source = file;
        Ok(case)
    }

    /// Parses case text; `place` names it in errors.
    pub fn parse(text: &str, place: &str) -> Result<Case> {
        toml::from_str::<Case>(text).map_err(|e| {
            let at = e
                .span()
                .map(|s| {
                    let (line, col) = line_col(text, s.start);
                    format!(":{line}:{col}")
                })
                .unwrap_or_default();
            let mut message = e.message().trim().replace('\n', " ");
            // a value of the wrong type or range: name its key
            if message.starts_with("invalid type") || message.starts_with("invalid value") {
                if let Some(key) = e.span().and_then(|s| key_before(text, s.start)) {
                    message = format!("{key}: {message}");
                }
            }
            Error::input(format!("{place}{at}"), message)
        })
    }

    /// The effective case without its location and description, as text:
    /// what a restart file's fingerprint identifies besides the mesh
    /// ([`crate::files::restart::fingerprint`]). It is the case's canonical
    /// serialization: every key of the schema with its value after serde's
    /// defaults and the command line's overrides, as compact JSON (object
    /// keys sorted, numbers in their shortest round-trip form), without the
    /// fields that say where the case came from (`source`, `description`,
    /// `overrides`). Key order, whitespace, comments and the description of
    /// the case file change nothing; any value of the schema does.
    pub fn key(&self) -> String {
        let mut key = self.clone();
        key.description = None;
        // through a `Value`: its objects are sorted maps, so the key does
        // not depend on the order in which the structs declare their fields
        let value = serde_json::to_value(&key)
            .expect("a case is JSON: its strings and paths come from TOML text (UTF-8)");
        serde_json::to_string(&value).expect("a JSON value is text")
    }

    /// The case name: `name`, else the folder holding the case file, else the file stem.
    pub(crate) fn display_name(&self) -> String {
        if let Some(n) = &self.name {
            return n.clone();
        }
        // `asperity run .`: the folder's own name, not "."
        let source = std::fs::canonicalize(&self.source).unwrap_or_else(|_| self.source.clone());
        let folder = source
            .parent()
            .and_then(|p| p.file_name())
            .map(|s| s.to_string_lossy().into_owned());
        match folder {
            Some(f) if !f.is_empty() && f != "." => f,
            _ => self
                .source
                .file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_else(|| "case".into()),
        }
    }
}

/// Largest case file read (a case is a few kB; 100 000 `load_factors` take ~2 MB).
pub(crate) const MAX_CASE_BYTES: u64 = 16 << 20;
/// Largest mesh file read: over 7 times the ASCII `.msh` of a mesh at the
/// element cap (about 130 bytes per element and its nodes).
pub(crate) const MAX_MESH_BYTES: u64 = 256 << 20;

/// Reads an input file of at most `limit` bytes. Anything that is not a regular
/// file (a folder, a device such as `/dev/zero`, a FIFO) is refused before it
/// is opened, so nothing is read without end; the bound is checked on the
/// size and again while reading (a file that grows).
pub(crate) fn read_input(path: &Path, limit: u64, what: &str) -> Result<Vec<u8>> {
    use std::io::Read;
    let meta = std::fs::metadata(path).map_err(|e| Error::io(path, e))?;
    let kind = |m: &std::fs::Metadata| {
        let t = m.file_type();
        if t.is_dir() {
            "a folder"
        } else {
            "a device, FIFO or socket"
        }
    };
    let too_big = |n: u64| {
        Error::input(
            path.display().to_string(),
            format!(
                "the {what} has {n} bytes or more, more than the limit of {limit} bytes ({} MiB)",
                limit >> 20
            ),
        )
    };
    if !meta.is_file() {
        return Err(Error::input(
            path.display().to_string(),
            format!(
                "is {}, not a regular file: a {what} must be a file",
                kind(&meta)
            ),
        ));
    }
    if meta.len() > limit {
        return Err(too_big(meta.len()));
    }
    let file = std::fs::File::open(path).map_err(|e| Error::io(path, e))?;
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    file.take(limit + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| Error::io(path, e))?;
    if bytes.len() as u64 > limit {
        return Err(too_big(limit + 1));
    }
    Ok(bytes)
}

/// The key whose value starts at `offset`: the word before the last `=` on
/// its line before it (`vtu_every = -1`, `bottom = { radius = "x" }`), if any.
fn key_before(text: &str, offset: usize) -> Option<&str> {
    let before = text.get(..offset)?;
    let line = &before[before.rfind('\n').map_or(0, |i| i + 1)..];
    let lhs = line[..line.rfind('=')?].trim_end();
    let start = lhs
        .rfind(|c: char| !(c.is_alphanumeric() || c == '_' || c == '-'))
        .map_or(0, |i| i + 1);
    let key = &lhs[start..];
    (!key.is_empty()).then_some(key)
}

fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let before = &text[..offset.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let col = before.rfind('\n').map_or(offset, |i| offset - i - 1) + 1;
    (line, col)
}
