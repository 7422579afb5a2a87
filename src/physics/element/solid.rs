//! The 8-node serendipity solid element, small strain, plane stress or strain,
//! or axisymmetric.
//!
//! ```text
//!   fᵉ = ∫ Bᵀ σ t dA          Kᵉ = ∫ Bᵀ C B t dA          (eq. 3.23, 4.2)
//!   B = ⎡∂N/∂x  0    ⎤   per node, strain [εxx, εyy, γxy]
//!       ⎢0      ∂N/∂y⎥
//!       ⎣∂N/∂y  ∂N/∂x⎦
//! ```
//!
//! Axisymmetric (x = r, y = z; `axisymmetric_forces`): the strain gains the
//! hoop component ε_θθ = u_r/r, B a fourth row, C is 4×4 and the volume element
//! is that of the full revolution:
//! ```text
//!   B = ⎡∂N/∂r  0    ⎤   per node, strain [ε_rr, ε_zz, γ_rz, ε_θθ]
//!       ⎢0      ∂N/∂z⎥
//!       ⎢∂N/∂z  ∂N/∂r⎥
//!       ⎣N/r    0    ⎦
//!   dv = det J · w · 2π r   (r at the Gauss point, inside the element: r > 0
//!                            even where the element touches the axis)
//! ```
//!
//! Geometry (dN/dx and det J · w · t per Gauss point) never changes (small
//! strain). It is recomputed from the node coordinates whenever an element is
//! evaluated rather than stored: about 1,000 flops against the element's
//! 20,000, and it saves 1.4 KB per element (a quarter of the model's memory).

use super::dofs::NodeDofs;
use crate::physics::element::family::{Family, GaussRule, MAX_NODES};
use crate::physics::element::Section;
use crate::physics::material::{Plane, PointMaterials, PointState, VonMises};
use nalgebra::{Matrix3, Matrix4};

pub(crate) use crate::physics::element::family::MAX_POINTS;

/// Per-element Gauss point geometry, on the stack.
#[derive(Clone, Debug)]
pub struct ElementGeometry {
    /// Number of Gauss points.
    pub n: usize,
    /// Number of nodes (the family's: 8 or 6).
    pub nodes: usize,
    /// dN_a/dx, dN_a/dy for each Gauss point.
    pub(crate) dndx: [[[f64; 2]; MAX_NODES]; MAX_POINTS],
    /// det J · weight · thickness (or · 2π r, [`Section::measure`]) for each
    /// Gauss point.
    pub dv: [f64; MAX_POINTS],
    /// Physical coordinates of each Gauss point.
    pub x: [[f64; 2]; MAX_POINTS],
    /// N_a at each Gauss point.
    pub shape: [[f64; MAX_NODES]; MAX_POINTS],
}

impl ElementGeometry {
    /// Precomputes the geometry of a plane element of the given thickness; an
    /// Err names the Gauss point with det J ≤ 0.
    pub fn new(
        family: Family,
        coords: &[[f64; 2]],
        rule: &GaussRule,
        thickness: f64,
    ) -> Result<Self, String> {
        let section = Section {
            axisymmetric: false,
            thickness,
        };
        Self::with_section(family, coords, rule, &section)
    }

    /// Precomputes the geometry, the volume element dv being det J · w ·
    /// `section.measure(x)` (thickness, or 2π r); an Err names the Gauss point
    /// with det J ≤ 0.
    pub fn with_section(
        family: Family,
        coords: &[[f64; 2]],
        rule: &GaussRule,
        section: &Section,
    ) -> Result<Self, String> {
        if rule.points.len() > MAX_POINTS {
            return Err(format!(
                "{} Gauss points (at most {MAX_POINTS})",
                rule.points.len()
            ));
        }
        let mut g = ElementGeometry {
            n: rule.points.len(),
            nodes: family.nodes(),
            dndx: [[[0.0; 2]; MAX_NODES]; MAX_POINTS],
            dv: [0.0; MAX_POINTS],
            x: [[0.0; 2]; MAX_POINTS],
            shape: [[0.0; MAX_NODES]; MAX_POINTS],
        };
        for (ip, &(xi, w)) in rule.points.iter().enumerate() {
            let (det, d) = family
                .physical_derivs(coords, xi)
                .map_err(|e| format!("Gauss point {ip}: {e}"))?;
            let n = family.shape(xi);
            let mut x = [0.0; 2];
            for a in 0..family.nodes() {
                x[0] += n[a] * coords[a][0];
                x[1] += n[a] * coords[a][1];
            }
            g.dndx[ip] = d;
            g.dv[ip] = det * w * section.measure(x);
            g.x[ip] = x;
            g.shape[ip] = n;
        }
        Ok(g)
    }

    /// Strain [εxx, εyy, γxy] at Gauss point `ip` from element displacements.
    pub fn strain(&self, ip: usize, ue: &[f64]) -> [f64; 3] {
        let d = &self.dndx[ip];
        let mut e = [0.0; 3];
        for a in 0..self.nodes {
            let (ux, uy) = (ue[2 * a], ue[2 * a + 1]);
            e[0] += d[a][0] * ux;
            e[1] += d[a][1] * uy;
            e[2] += d[a][1] * ux + d[a][0] * uy;
        }
        e
    }

    /// Axisymmetric strain [ε_rr, ε_zz, γ_rz, ε_θθ] at Gauss point `ip`, with
    /// ε_θθ = Σ N_a u_ra / r.
    pub fn strain_axisymmetric(&self, ip: usize, ue: &[f64]) -> [f64; 4] {
        let [e0, e1, e2] = self.strain(ip, ue);
        let ur: f64 = (0..self.nodes).map(|a| self.shape[ip][a] * ue[2 * a]).sum();
        [e0, e1, e2, ur / self.x[ip][0]]
    }
}

/// Which material matrix goes into the element tangent.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Tangent {
    /// Algorithmic tangent of the return mapping (full Newton).
    Consistent,
    /// Continuum C_ep at the committed state (modified Newton, eq. 3.13).
    Continuum,
    /// Elastic D (initial stiffness, eq. 4.8).
    Elastic,
}

/// How stresses are updated.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Response {
    /// Return mapping (elastic-plastic).
    Plastic,
    /// Purely elastic from the committed plastic strain (first-yield location).
    ElasticOnly,
}

/// An element's displacements or forces, node-major, [`NodeDofs::element`]
/// entries used (16, or 24 with twist).
pub(crate) type ElementVector = [f64; NodeDofs::MAX_ELEMENT];

/// Internal force and (optionally) tangent of one element of a plane or
/// axisymmetric model with two dofs per node ([`super::element_forces`]
/// chooses the element).
#[allow(clippy::too_many_arguments)]
pub fn forces(
    geom: &ElementGeometry,
    mats: PointMaterials<'_>,
    thermal: &[f64],
    ue: &[f64],
    committed: &[PointState],
    trial: &mut [PointState],
    response: Response,
    tangent: Option<Tangent>,
    fe: &mut [f64],
    ke: &mut [f64],
) -> Result<(), String> {
    if mats.plane() == Plane::Axisymmetric {
        return axisymmetric_forces(
            geom, mats, thermal, ue, committed, trial, response, tangent, fe, ke,
        );
    }
    fe.fill(0.0);
    if tangent.is_some() {
        ke.fill(0.0);
    }
    for ip in 0..geom.n {
        let mat = mats.at(ip);
        let eps = geom.strain(ip, ue);
        let (state, c_alg) = match response {
            Response::Plastic => mat
                .update_thermal(&committed[ip], &eps, thermal[ip])
                .map_err(|e| format!("Gauss point {ip}: {e}"))?,
            Response::ElasticOnly => (
                elastic_state_thermal(mat, &committed[ip], &eps, thermal[ip]),
                mat.elastic_matrix(),
            ),
        };
        trial[ip] = state;
        let dv = geom.dv[ip];
        let d = &geom.dndx[ip];
        let s = &state.stress;
        for a in 0..geom.nodes {
            fe[2 * a] += dv * (d[a][0] * s[0] + d[a][1] * s[2]);
            fe[2 * a + 1] += dv * (d[a][1] * s[1] + d[a][0] * s[2]);
        }
        if let Some(t) = tangent {
            let c = match t {
                Tangent::Consistent => c_alg,
                Tangent::Continuum => mat.continuum_tangent(&committed[ip]),
                Tangent::Elastic => mat.elastic_matrix(),
            };
            add_btcb(d, geom.nodes, &c, dv, ke);
        }
    }
    Ok(())
}

/// Stress from the elastic law only, keeping the committed plastic strain.
pub fn elastic_state(mat: &VonMises, committed: &PointState, eps: &[f64; 3]) -> PointState {
    elastic_state_thermal(mat, committed, eps, 0.0)
}

/// [`elastic_state`] less the free thermal strain `thermal` = α ΔT on the
/// normal components ([`VonMises::update_thermal`]).
pub fn elastic_state_thermal(
    mat: &VonMises,
    committed: &PointState,
    eps: &[f64; 3],
    thermal: f64,
) -> PointState {
    let ep = &committed.plastic_strain;
    let ee = [
        eps[0] - thermal - ep[0],
        eps[1] - thermal - ep[1],
        eps[2] - 2.0 * ep[2],
    ];
    let d = mat.elastic_matrix();
    let mut s = d * nalgebra::Vector3::new(ee[0], ee[1], ee[2]);
    let szz = match mat.plane {
        crate::physics::material::Plane::Stress => 0.0,
        crate::physics::material::Plane::Solid => {
            unreachable!("a plane element's state in a 3D model")
        }
        crate::physics::material::Plane::Axisymmetric => {
            // the plane strains with zero hoop strain
            let e4 = [eps[0] - thermal, eps[1] - thermal, eps[2], 0.0 - thermal];
            return mat.elastic_state_axisymmetric(committed, &e4);
        }
        crate::physics::material::Plane::Strain => {
            // ε_zz = 0, so the elastic ε_zz is −α ΔT − εᵖzz; it adds λ·εᵉzz
            // to every normal stress
            let lambda =
                mat.young * mat.poisson / ((1.0 + mat.poisson) * (1.0 - 2.0 * mat.poisson));
            let g2 = mat.young / (1.0 + mat.poisson);
            let ezz = -thermal - ep[3];
            s[0] += lambda * ezz;
            s[1] += lambda * ezz;
            lambda * (ee[0] + ee[1] + ezz) + g2 * ezz
        }
    };
    PointState {
        stress: [s[0], s[1], s[2], szz, 0.0, 0.0],
        plastic_strain: *ep,
        peeq: committed.peeq,
        yielding: false,
    }
}

/// ke += Bᵀ C B dv, exploiting the 2-row sparsity of each nodal B block.
fn add_btcb(d: &[[f64; 2]; MAX_NODES], nn: usize, c: &Matrix3<f64>, dv: f64, ke: &mut [f64]) {
    let ne = 2 * nn;
    // CB for each node b: 3×2 block
    let mut cb = [[0.0f64; 6]; MAX_NODES];
    for b in 0..nn {
        let (bx, by) = (d[b][0], d[b][1]);
        for r in 0..3 {
            cb[b][2 * r] = c[(r, 0)] * bx + c[(r, 2)] * by;
            cb[b][2 * r + 1] = c[(r, 1)] * by + c[(r, 2)] * bx;
        }
    }
    for a in 0..nn {
        let (ax, ay) = (d[a][0], d[a][1]);
        for b in 0..nn {
            let m = &cb[b];
            // rows of Bᵀ for node a: x-dof = [ax, 0, ay], y-dof = [0, ay, ax]
            let kxx = ax * m[0] + ay * m[4];
            let kxy = ax * m[1] + ay * m[5];
            let kyx = ay * m[2] + ax * m[4];
            let kyy = ay * m[3] + ax * m[5];
            ke[(2 * a) * ne + 2 * b] += dv * kxx;
            ke[(2 * a) * ne + 2 * b + 1] += dv * kxy;
            ke[(2 * a + 1) * ne + 2 * b] += dv * kyx;
            ke[(2 * a + 1) * ne + 2 * b + 1] += dv * kyy;
        }
    }
}

/// Internal force and (optionally) tangent of one axisymmetric element (x = r,
/// y = z): fᵉ = Σ Bᵀ σ dv and Kᵉ = Σ Bᵀ C B dv over the Gauss points with the
/// four-row B of the module text, σ = [σ_rr, σ_zz, σ_rz, σ_θθ], C the 4×4
/// algorithmic tangent ([`VonMises::update_axisymmetric`]), the continuum
/// C_ep (eq. 3.13, [`VonMises::continuum_tangent_4`]) or the elastic D, and
/// dv = det J · w · 2π r from `geom` (built with an axisymmetric [`Section`]).
/// Errors name the Gauss point.
#[allow(clippy::too_many_arguments)]
pub(crate) fn axisymmetric_forces(
    geom: &ElementGeometry,
    mats: PointMaterials<'_>,
    thermal: &[f64],
    ue: &[f64],
    committed: &[PointState],
    trial: &mut [PointState],
    response: Response,
    tangent: Option<Tangent>,
    fe: &mut [f64],
    ke: &mut [f64],
) -> Result<(), String> {
    fe.fill(0.0);
    if tangent.is_some() {
        ke.fill(0.0);
    }
    for ip in 0..geom.n {
        let r = geom.x[ip][0];
        #[allow(clippy::neg_cmp_op_on_partial_ord)] // NaN is refused too
        if !(r > 0.0) {
            return Err(format!(
                "Gauss point {ip} at r = {r}: an axisymmetric element must lie at r ≥ 0"
            ));
        }
        let mat = mats.at(ip);
        let eps = less_thermal(geom.strain_axisymmetric(ip, ue), thermal[ip]);
        let (state, c_alg) = match response {
            Response::Plastic => mat.update_axisymmetric(&committed[ip], &eps),
            Response::ElasticOnly => (
                mat.elastic_state_axisymmetric(&committed[ip], &eps),
                mat.elastic_matrix_4(),
            ),
        };
        trial[ip] = state;
        let b = b_axisymmetric(geom, ip);
        let (dv, s) = (geom.dv[ip], &state.stress);
        for (j, f) in fe.iter_mut().enumerate().take(2 * geom.nodes) {
            *f += dv * (0..4).map(|i| b[i][j] * s[i]).sum::<f64>();
        }
        if let Some(t) = tangent {
            let c = match t {
                Tangent::Consistent => c_alg,
                Tangent::Continuum => mat.continuum_tangent_4(&committed[ip]),
                Tangent::Elastic => mat.elastic_matrix_4(),
            };
            add_btcb_4(&b, 2 * geom.nodes, &c, dv, ke);
        }
    }
    Ok(())
}

/// The mechanical strain: `eps` less the free thermal strain α ΔT on its
/// normal components, 0, 1 and 3 in every order of four or six components
/// the elements use ([rr, zz, rz, θθ, …] and [xx, yy, xy, zz, xz, yz]).
pub(crate) fn less_thermal<const N: usize>(mut eps: [f64; N], thermal: f64) -> [f64; N] {
    for i in [0, 1, 3] {
        eps[i] -= thermal;
    }
    eps
}

/// The 4×16 axisymmetric B at Gauss point `ip` (rows rr, zz, rz, θθ).
fn b_axisymmetric(geom: &ElementGeometry, ip: usize) -> [[f64; 16]; 4] {
    let (d, n, r) = (&geom.dndx[ip], &geom.shape[ip], geom.x[ip][0]);
    let mut b = [[0.0; 16]; 4];
    for a in 0..geom.nodes {
        b[0][2 * a] = d[a][0];
        b[1][2 * a + 1] = d[a][1];
        b[2][2 * a] = d[a][1];
        b[2][2 * a + 1] = d[a][0];
        b[3][2 * a] = n[a] / r;
    }
    b
}

/// ke += Bᵀ C B dv for the 4-row B.
fn add_btcb_4(b: &[[f64; 16]; 4], ne: usize, c: &Matrix4<f64>, dv: f64, ke: &mut [f64]) {
    let mut cb = [[0.0f64; 16]; 4];
    for (i, row) in cb.iter_mut().enumerate() {
        for (j, v) in row.iter_mut().enumerate().take(ne) {
            *v = (0..4).map(|k| c[(i, k)] * b[k][j]).sum();
        }
    }
    for p in 0..ne {
        for q in 0..ne {
            ke[p * ne + q] += dv * (0..4).map(|i| b[i][p] * cb[i][q]).sum::<f64>();
        }
    }
}
