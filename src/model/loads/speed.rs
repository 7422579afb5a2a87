//! The model's rotational speed (`[speed]`, docs/case-schema.md "Speed"):
//! every body spins at ω about the model's axis and carries, in the frame
//! that turns with it, the centrifugal body force (docs/theory.md, "Body
//! force of a speed")
//! ```text
//!   b = ρ ω² r  (radially outward, r the distance from the axis)
//!   f_a = ∫ N_a ρ ω² r dV                  (the consistent nodal forces)
//! ```
//! with r = x in axisymmetry (the axis x = r = 0), (x, y) in a plane model
//! (the axis is z through the origin: a disk spinning in its plane) and
//! (x, 0, z) in 3D (the axis is y, as `revolve` sweeps). The speed follows
//! a history: ω(t) = ω h(t), so the force at t is h(t)² f (the pattern's
//! `model::Scale::Squared`). Small strain: r is the undeformed
//! position, as the closed forms of a spinning disk take it.

use super::{clip, Resolver, Scaled};
use crate::error::{Error, Result};
use crate::input::case::{ranges, Case};
use crate::input::mesh::Mesh;
use crate::physics::element::solid::ElementGeometry;
use crate::physics::element::solid3::ElementGeometry3;
use crate::physics::element::Section;

/// kg/m³ in the model's units (t/mm³: N s²/mm⁴).
const KG_PER_M3: f64 = 1e-12;

/// The model's speed and the nodal forces it sets at factor 1.
#[derive(Clone, Debug)]
pub struct Speed {
    /// n at factor 1, rpm.
    pub rpm: f64,
    /// Its history (`None`: the load factor, or the default ramp).
    pub history: Option<usize>,
    /// The centrifugal nodal forces at n (all dofs), N.
    pub f: Vec<f64>,
    /// Each body's density, kg/m³.
    pub density: Vec<f64>,
}

impl Speed {
    /// ω at factor 1, rad/s.
    pub fn omega(&self) -> f64 {
        self.rpm * std::f64::consts::PI / 30.0
    }

    /// ρ ω² r² of body `b` at factor 1, MPa: the scale of the hoop stress
    /// of a ring of radius r spinning free (σ_θ = ρ ω² r² for a thin one).
    pub fn hoop_scale(&self, b: usize, r: f64) -> f64 {
        self.density[b] * KG_PER_M3 * self.omega().powi(2) * r * r
    }
}

/// The distance of point x from the axis a model spins about: |x| in
/// axisymmetry (x = r), √(x² + y²) in a plane model (about z), √(x² + z²)
/// in 3D (about y).
pub fn radius(x: [f64; 3], dim: usize, axisymmetric: bool) -> f64 {
    match (dim, axisymmetric) {
        (3, _) => x[0].hypot(x[2]),
        (_, true) => x[0].abs(),
        _ => x[0].hypot(x[1]),
    }
}

/// The case's `[speed]`: its history resolved, every body's density
/// known, its largest value within [`ranges::SPEED`]; `None` without one.
pub(super) fn read(
    case: &Case,
    mesh: &Mesh,
    (section, nd): (Section, usize),
    place: &str,
    res: &mut Resolver<'_>,
    scaled: &mut Vec<Scaled>,
) -> Result<Option<Speed>> {
    let Some(spec) = &case.speed else {
        return Ok(None);
    };
    let at = format!("{place}: [speed]");
    if !(spec.rpm.is_finite() && spec.rpm > 0.0) {
        return Err(Error::input(
            format!("{at} rpm"),
            format!(
                "{} must be a positive number (revolutions per minute; the direction of a spin does not change its body force)",
                spec.rpm
            ),
        ));
    }
    let history = res.resolve(spec.history.as_ref(), &format!("{at} history"))?;
    scaled.push((format!("{at} rpm"), spec.rpm, &ranges::SPEED, history));
    let mut density = Vec::with_capacity(mesh.bodies.len());
    for body in &mesh.bodies {
        let rho = case.materials.get(body).and_then(|m| m.density);
        let Some(rho) = rho else {
            return Err(Error::input(
                at.clone(),
                format!(
                    "[materials.{}] has no density: every body of a spinning model carries ρ ω² r, give its density (kg/m³)",
                    clip(body)
                ),
            ));
        };
        density.push(rho);
    }
    let omega = spec.rpm * std::f64::consts::PI / 30.0;
    let rho: Vec<f64> = density.iter().map(|d| d * KG_PER_M3).collect();
    let f = nodal_forces(mesh, section, &rho, omega * omega, nd)
        .map_err(|m| Error::input(at.clone(), m))?;
    Ok(Some(Speed {
        rpm: spec.rpm,
        history,
        f,
        density,
    }))
}

/// f_a = Σ_ip N_a ρ ω² r dV over every element with the full Gauss rule
/// (the integrand is a polynomial of the element's degree times r: the
/// reduced rule would not integrate it).
fn nodal_forces(
    mesh: &Mesh,
    section: Section,
    density: &[f64],
    w2: f64,
    nd: usize,
) -> std::result::Result<Vec<f64>, String> {
    let mut f = vec![0.0; nd];
    let dofs = &mesh.node_dofs;
    for (e, el) in mesh.elements.iter().enumerate() {
        let scale = density[el.body] * w2;
        let mut add = |a: usize, c: usize, v: f64| f[dofs.dof(el.nodes()[a], c)] += v;
        if let Some(solid) = el.family.solid() {
            let coords = mesh.element_coords3(e);
            let g = ElementGeometry3::new(solid, &coords[..el.family.nodes()], &solid.rule(true))
                .map_err(|m| format!("element {e}: {m}"))?;
            for ip in 0..g.n {
                let [x, _, z] = g.x[ip];
                for a in 0..g.nodes {
                    let w = g.shape[ip][a] * scale * g.dv[ip];
                    add(a, 0, w * x);
                    add(a, 2, w * z);
                }
            }
        } else {
            let coords = mesh.element_coords(e);
            let rule = el.family.rule(true);
            let g = ElementGeometry::with_section(el.family, &coords, &rule, &section)
                .map_err(|m| format!("element {e}: {m}"))?;
            for ip in 0..g.n {
                let [x, y] = g.x[ip];
                for a in 0..g.nodes {
                    let w = g.shape[ip][a] * scale * g.dv[ip];
                    add(a, 0, w * x);
                    if !section.axisymmetric {
                        add(a, 1, w * y);
                    }
                }
            }
        }
    }
    Ok(f)
}
