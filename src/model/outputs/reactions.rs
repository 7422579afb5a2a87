//! Reaction forces: the residual R = f_int + f_c − f_ext at the prescribed
//! dofs of a converged state (the force the supports exert on the bodies),
//! summed per named group and component. Every `[[boundary]]` entry is a
//! group (its components: `fx_n` where it prescribes ux, `fy_n` where it
//! prescribes uy), and in axisymmetry the axis r = 0 where no entry holds it
//! (`fx_n`: the radial component). A dof that several entries prescribe (a
//! corner in two fixed sets) counts in the first of them only, so the groups
//! together hold every prescribed dof once and their sum balances the
//! applied loads. A cyclic sector's groups add the moment about the y axis
//! and the whole part's axial force and moment (`whole_part`); its axis
//! (u_x = u_z = 0 at r = 0) is the group `axis` with `fx_n` and `fz_n`.
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
    /// the radius r of each prescribed u_θ, T = Σ r R_θ; `my_nmm` of a
    /// cyclic sector: z for a u_x, −x for a u_z); empty: a force, the plain
    /// sum.
    pub(crate) arms: Vec<f64>,
    /// The factor on the sum: 1, or N for a cyclic sector's whole-part
    /// component (`fy_part_n`, `my_part_nmm`).
    pub(crate) scale: f64,
}

impl Component {
    fn new(label: &'static str, terms: Vec<usize>, arms: Vec<f64>) -> Component {
        Component {
            label,
            terms,
            arms,
            scale: 1.0,
        }
    }
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
            let sum = if c.arms.is_empty() {
                c.terms.iter().map(|&k| at(k)).sum::<f64>()
            } else {
                c.terms
                    .iter()
                    .zip(&c.arms)
                    .map(|(&k, r)| r * at(k))
                    .sum::<f64>()
            };
            c.scale * sum + 0.0
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
            components.push(Component::new(label, terms, arms));
        }
        if let Some(c) = &case.model.cyclic {
            whole_part(&mut components, mesh, prescribed, c.sectors);
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
    // (a cyclic sector's axis holds u_x and u_z)
    let on_axis = |c: usize| -> Vec<usize> {
        (0..prescribed.len())
            .filter(|&k| {
                let d = prescribed[k].0;
                !owned[k] && d < mesh.num_dofs() && mesh.node_dofs.node_of(d).1 == c
            })
            .collect()
    };
    let mut components = vec![Component::new("fx_n", on_axis(0), Vec::new())];
    if mesh.dim() == 3 {
        components.push(Component::new("fz_n", on_axis(2), Vec::new()));
    }
    if components.iter().any(|c| !c.terms.is_empty()) {
        out.push(Group {
            name: "axis".into(),
            source: "axis".into(),
            set: None,
            components,
        });
    }
    out
}

/// A cyclic sector's group gains the moment of its reactions about the y
/// axis, `my_nmm` = Σ (z R_x − x R_z) (where it prescribes u_x or u_z), and
/// the whole part's axial force and moment, N × `fy_n` (`fy_part_n`) and N ×
/// `my_nmm` (`my_part_nmm`): every sector carries the same about the axis.
/// Its `fx_n` and `fz_n` stay the sector's: rotated through the N sectors
/// they sum to zero over the part.
fn whole_part(
    components: &mut Vec<Component>,
    mesh: &Mesh,
    prescribed: &[(usize, f64)],
    sectors: usize,
) {
    let (mut terms, mut arms) = (Vec::new(), Vec::new());
    for c in components.iter().filter(|c| c.label != "fy_n") {
        for &k in &c.terms {
            let (n, comp) = mesh.node_dofs.node_of(prescribed[k].0);
            let x = mesh.nodes[n];
            terms.push(k);
            arms.push(if comp == 0 { x[2] } else { -x[0] });
        }
    }
    let n = sectors as f64;
    let axial = components
        .iter()
        .find(|c| c.label == "fy_n")
        .map(|c| Component {
            label: "fy_part_n",
            scale: n,
            ..c.clone()
        });
    let moment = (components.iter().any(|c| c.label != "fy_n"))
        .then(|| Component::new("my_nmm", terms, arms));
    let whole = moment.as_ref().map(|c| Component {
        label: "my_part_nmm",
        scale: n,
        ..c.clone()
    });
    components.extend(moment);
    components.extend(axial);
    components.extend(whole);
}

/// Values per group and component, flattened in group order.
pub fn values(groups: &[Group], residual: &[f64]) -> Vec<f64> {
    groups.iter().flat_map(|g| g.values(residual)).collect()
}

/// Number of values of [`values`].
pub fn width(groups: &[Group]) -> usize {
    groups.iter().map(|g| g.components.len()).sum()
}
