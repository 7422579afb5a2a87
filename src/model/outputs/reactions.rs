//! Reaction forces: the residual R = f_int + f_c − f_ext at the prescribed
//! dofs of a converged state (the force the supports exert on the bodies),
//! summed per named group and component. Every `[[boundary]]` entry is a
//! group (its components: `fx_n` where it prescribes ux, `fy_n` where it
//! prescribes uy), and in axisymmetry the axis r = 0 where no entry holds it
//! (`fx_n`: the radial component). A dof that several entries prescribe (a
//! corner in two fixed sets) counts in the first of them only, so the groups
//! together hold every prescribed dof once and their sum balances the
//! applied loads.
//!
//! The groups are a list of (name, components) reductions ([`Group`]): the
//! columns of `reactions.csv` and the entries of `reactions` in
//! summary.json follow it, so a further group (a section force) is one more
//! entry of [`groups`] (docs/output.md, "reactions.csv").

use crate::input::case::Case;
use crate::input::mesh::Mesh;

/// One component of a group: its column label and the terms it sums, each
/// an index into [`crate::model::Model::prescribed`] (the residual there).
#[derive(Clone, Debug)]
pub struct Component {
    /// `fx_n`, `fy_n`, …: the label of its column and of its summary value.
    pub label: &'static str,
    pub terms: Vec<usize>,
    /// Each term's lever arm, when the component is a moment (`torque_nmm`:
    /// the radius r of each prescribed u_θ, T = Σ r R_θ); empty: a force,
    /// the plain sum.
    pub(crate) arms: Vec<f64>,
}

/// A named reduction of reaction forces.
#[derive(Clone, Debug)]
pub struct Group {
    /// Unique among the groups: the set's name, with `boundary[i]` added
    /// when two entries name the same set; `axis`.
    pub name: String,
    /// Where it comes from: `boundary[i]`, `axis`.
    pub source: String,
    /// The node set (`None` for the axis).
    pub set: Option<String>,
    pub components: Vec<Component>,
}

impl Group {
    /// Its values in a converged state, component by component, from the
    /// residual at every prescribed dof (in the model's order).
    pub fn values<'a>(&'a self, residual: &'a [f64]) -> impl Iterator<Item = f64> + 'a {
        self.components.iter().map(move |c| {
            let at = |k: usize| residual.get(k).copied().unwrap_or(f64::NAN);
            // + 0.0: no negative zero (an empty sum)
            if c.arms.is_empty() {
                c.terms.iter().map(|&k| at(k)).sum::<f64>() + 0.0
            } else {
                c.terms
                    .iter()
                    .zip(&c.arms)
                    .map(|(&k, r)| r * at(k))
                    .sum::<f64>()
                    + 0.0
            }
        })
    }
}

/// The reaction groups of a case: one per `[[boundary]]` entry, then the
/// axis of an axisymmetric model where no entry prescribes it. `prescribed`
/// is the model's list (every dof once, sorted); the entries are resolved
/// as the loads resolve them ([`crate::model::loads`]: the set, then `x_range` and
/// `y_range`), which the model has already checked.
pub fn groups(case: &Case, mesh: &Mesh, prescribed: &[(usize, f64)]) -> Vec<Group> {
    let index: std::collections::HashMap<usize, usize> = prescribed
        .iter()
        .enumerate()
        .map(|(k, &(d, _))| (d, k))
        .collect();
    let mut owned = vec![false; prescribed.len()];
    let mut out = Vec::new();
    for (i, bc) in case.boundary.iter().enumerate() {
        let nodes = mesh
            .node_sets
            .get(&bc.set)
            .map_or(&[][..], |v| v.as_slice());
        let mut components = Vec::new();
        let twist = mesh.node_dofs.twist();
        let given = [
            (bc.ux, "fx_n"),
            (bc.uy, "fy_n"),
            if twist {
                (bc.rotation, "torque_nmm")
            } else {
                (bc.uz, "fz_n")
            },
        ];
        for (c, (given, label)) in given.into_iter().enumerate() {
            if given.is_none() {
                continue;
            }
            let (mut terms, mut arms) = (Vec::new(), Vec::new());
            for &n in nodes {
                let x = mesh.nodes[n];
                let ranges = [&bc.x_range, &bc.y_range, &bc.z_range];
                if !(0..3).all(|k| crate::model::loads::in_range(x[k], ranges[k])) {
                    continue;
                }
                if let Some(&k) = index.get(&mesh.node_dofs.dof(n, c)) {
                    if !owned[k] {
                        owned[k] = true;
                        terms.push(k);
                        if c == 2 && twist {
                            arms.push(x[0]);
                        }
                    }
                }
            }
            components.push(Component { label, terms, arms });
        }
        let shared = case.boundary.iter().filter(|b| b.set == bc.set).count() > 1;
        out.push(Group {
            name: if shared {
                format!("{} boundary[{i}]", bc.set)
            } else {
                bc.set.clone()
            },
            source: format!("boundary[{i}]"),
            set: Some(bc.set.clone()),
            components,
        });
    }
    // what no entry gives: u_r = 0 on the axis of an axisymmetric model (a
    // pretension section's reference node is no node: its force is in
    // pretension.csv)
    // (with twist the axis's u_θ = 0 too, whose reactions have no lever arm)
    let axis: Vec<usize> = (0..prescribed.len())
        .filter(|&k| {
            let d = prescribed[k].0;
            !owned[k] && d < mesh.num_dofs() && mesh.node_dofs.node_of(d).1 == 0
        })
        .collect();
    if !axis.is_empty() {
        out.push(Group {
            name: "axis".into(),
            source: "axis".into(),
            set: None,
            components: vec![Component {
                label: "fx_n",
                terms: axis,
                arms: Vec::new(),
            }],
        });
    }
    out
}

/// Values per group and component, flattened in group order.
pub fn values(groups: &[Group], residual: &[f64]) -> Vec<f64> {
    groups.iter().flat_map(|g| g.values(residual)).collect()
}

/// Number of values of [`values`].
pub fn width(groups: &[Group]) -> usize {
    groups.iter().map(|g| g.components.len()).sum()
}
