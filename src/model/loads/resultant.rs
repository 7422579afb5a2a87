//! What each `[[load]]` and `[[force]]` applies as a whole: its resultant
//! force and moment at factor 1, from its nodal forces, so that a run can
//! report the load it applied beside the reactions it met (a pair of
//! self-equilibrated loads shows each one's force, not their zero sum).
//!
//! The resultant of nodal forces f_a at nodes x_a is F = Σ_a f_a and its
//! moment about the origin M = Σ_a x_a × f_a. In axisymmetry the nodal forces
//! are those of the whole revolution (2π r in every integral), so F_y is the
//! axial force on the whole ring and F_x the sum of the radial ring forces
//! (a radial pressure's Σ p 2π r ds, no net force); with twist the torque
//! about the axis is Σ_a r_a f_θ,a.

use crate::input::mesh::Mesh;

/// The components a model's resultants have, with their labels in the CSV
/// (N, N·mm).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Components {
    /// F_x, F_y and the moment M_z about the origin (plane models).
    Plane,
    /// F_r (the sum of radial ring forces), F_z (axial).
    Axisymmetric,
    /// F_r, F_z and the torque about the axis.
    Twist,
    /// F_x, F_y, F_z and M_x, M_y, M_z about the origin.
    Solid,
}

impl Components {
    /// The model's components: by its dimension and its dofs per node.
    pub fn of(mesh: &Mesh, axisymmetric: bool) -> Components {
        match (mesh.dim(), axisymmetric, mesh.node_dofs.twist()) {
            (3, ..) => Components::Solid,
            (_, true, true) => Components::Twist,
            (_, true, false) => Components::Axisymmetric,
            _ => Components::Plane,
        }
    }

    /// Column labels (`reactions.csv`'s style): forces in N, moments in N·mm.
    pub fn labels(self) -> &'static [&'static str] {
        match self {
            Components::Plane => &["fx_n", "fy_n", "mz_nmm"],
            Components::Axisymmetric => &["fx_n", "fy_n"],
            Components::Twist => &["fx_n", "fy_n", "torque_nmm"],
            Components::Solid => &["fx_n", "fy_n", "fz_n", "mx_nmm", "my_nmm", "mz_nmm"],
        }
    }

    /// Whether component `c` is a moment (N·mm).
    pub fn is_moment(self, c: usize) -> bool {
        self.labels()[c].ends_with("_nmm")
    }
}

/// The resultant of nodal forces `terms` (global dof, force) in the
/// components `comp`; terms on no mesh node (a pretension section's
/// reference dof) are not a force on the body and are skipped.
pub fn resultant(terms: &[(usize, f64)], mesh: &Mesh, comp: Components) -> Vec<f64> {
    let nd = mesh.node_dofs;
    let mut r = vec![0.0; comp.labels().len()];
    for &(dof, f) in terms {
        let (node, c) = nd.node_of(dof);
        let Some(x) = mesh.nodes.get(node) else {
            continue;
        };
        let mut force = [0.0; 3];
        force[c] = f;
        match comp {
            Components::Plane => {
                r[c] += f;
                r[2] += x[0] * force[1] - x[1] * force[0];
            }
            Components::Axisymmetric => r[c] += f,
            Components::Twist if c == 2 => r[2] += x[0] * f,
            Components::Twist => r[c] += f,
            Components::Solid => {
                r[c] += f;
                let m = cross(*x, force);
                for k in 0..3 {
                    r[3 + k] += m[k];
                }
            }
        }
    }
    r
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// A load's words for the summary and `check`: what it applies and where.
pub(super) mod what {
    use crate::input::case::{ForceSpec, LoadSpec};

    /// "pressure 20 MPa, shear 3 MPa": every traction the load gives.
    pub fn load(ld: &LoadSpec) -> String {
        let mut parts = Vec::new();
        let mut add = |name: &str, v: f64, unit: &str| {
            if v != 0.0 {
                parts.push(format!("{name} {} {unit}", crate::numbers::num(v)));
            }
        };
        add("pressure", ld.pressure, "MPa");
        add("shear", ld.shear, "MPa");
        add("hoop_shear", ld.hoop_shear.unwrap_or(0.0), "MPa");
        add("torque", ld.torque.unwrap_or(0.0), "N·mm");
        if let Some(t) = &ld.traction {
            let v: Vec<String> = t.iter().map(|&c| crate::numbers::num(c)).collect();
            parts.push(format!("traction ({}) MPa", v.join(", ")));
        }
        if parts.is_empty() {
            "nothing (every traction 0)".into()
        } else {
            parts.join(", ")
        }
    }

    /// "force (0, 100) N at each node".
    pub fn force(fs: &ForceSpec, solid: bool) -> String {
        let s = crate::numbers::num;
        match solid {
            true => format!(
                "force ({}, {}, {}) N at each node",
                s(fs.fx),
                s(fs.fy),
                s(fs.fz)
            ),
            false => format!("force ({}, {}) N at each node", s(fs.fx), s(fs.fy)),
        }
    }

    /// "edges top_plate.top, x in [8.5, 12.5]".
    pub fn selection(set: &str, faces: bool, r: [&Option<[f64; 2]>; 3]) -> String {
        let kind = if faces { "faces" } else { "edges" };
        format!("{kind} {set}{}", ranges(r))
    }

    /// ", x in [lo, hi]" for each range given.
    pub fn ranges(r: [&Option<[f64; 2]>; 3]) -> String {
        let mut s = String::new();
        for (axis, r) in ["x", "y", "z"].iter().zip(r) {
            if let Some([lo, hi]) = r {
                let n = crate::numbers::num;
                s += &format!(", {axis} in [{}, {}]", n(*lo), n(*hi));
            }
        }
        s
    }
}
