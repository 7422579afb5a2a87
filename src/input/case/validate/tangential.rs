//! The tangential law of an interface from its `[interface.<name>.tangential]`
//! table: R and S or a k_table, the backbone's keys (`kp_ratio` and
//! `yield_ratio`, or `chi` and `spike`) and the memory, each refusal naming
//! the key. `asperity calibrate` checks its `[tangential]` by the same rules.

use super::*;
use crate::physics::contact::tangential::params;

/// The tangential law of interface `name`: r and s, or a k_table; any
/// weights (each integration point keeps its own slip history).
pub(super) fn tangential_law(
    name: &str,
    t: &TangentialSpec,
    at: &dyn Fn(&str) -> String,
) -> Result<TangentialLaw> {
    let key = format!("[interface.{name}] tangential");
    // every integration point of the interface keeps its own slip history,
    // whatever the weights: a pair (lumped), a Gauss point of an edge
    // (consistent, matching or not), a slave node (mortar)
    let kp_ratio = backbone_keys(
        t.backbone,
        [t.kp_ratio, t.yield_ratio, t.chi, t.spike],
        &|k| at(&format!("{key} {k}")),
    )?;
    let law = match (&t.k_table, t.r, t.s) {
        (None, Some(r), Some(s)) => {
            TangentialLaw::new(r, s, kp_ratio, t.mu, t.beta, t.n, t.yield_ratio())
                .map_err(|m| Error::input(at(&key), m))?
        }
        (Some(rows), None, None) => {
            let key = format!("{key} k_table");
            let rows = crate::physics::contact::table::rows_of_two(rows, "p_N", "k_T")
                .map_err(|m| Error::input(at(&key), m))?;
            for (i, &(p, k)) in rows.iter().enumerate() {
                for ((column, range), v) in params::K_TABLE_COLUMNS.iter().zip([p, k]) {
                    range.check(at(&format!("{key} row {} {column}", i + 1)), v)?;
                }
            }
            TangentialLaw::with_k_table(&rows, kp_ratio, t.mu, t.beta, t.n, t.yield_ratio())
                .map_err(|m| Error::input(at(&key), m))?
        }
        (Some(_), r, _) => {
            let k = if r.is_some() { "r" } else { "s" };
            return Err(Error::input(
                at(&format!("{key} {k}")),
                format!("`{k}` is not allowed with `k_table`: give either r and s (k_T^e = p^S/R) or k_table, not both"),
            ));
        }
        (None, r, _) => {
            let k = if r.is_none() { "r" } else { "s" };
            return Err(Error::input(
                at(&key),
                format!("needs `{k}`: give r and s (k_T^e = p^S/R, eq. 2.6) or k_table = [[p_N, k_T], ...]"),
            ));
        }
    };
    for ((k, range), v) in params::NUMBERS.iter().zip([t.r.unwrap_or(0.0), t.mu, t.n]) {
        range.check(at(&format!("{key} {k}")), v)?;
    }
    let backbone = match t.backbone {
        BackboneKind::Bilinear => Backbone::Bilinear,
        BackboneKind::Iwan => Backbone::Iwan {
            chi: t.chi.unwrap_or(0.0),
            spike: t.spike.unwrap_or(0.0),
        },
    };
    law.with_memory(t.memory, backbone)
        .map_err(|m| Error::input(at(&format!("{key} {}", memory_error_key(&m))), m))
}

/// The key a refusal of [`TangentialLaw::with_memory`] is about.
pub(crate) fn memory_error_key(message: &str) -> &'static str {
    ["chi", "spike", "beta"]
        .into_iter()
        .find(|k| message.starts_with(k))
        .unwrap_or("memory")
}

/// The keys of the backbone: `kp_ratio` (and `yield_ratio`) for the
/// paper's two lines, `chi` and `spike` for an Iwan density, each refused
/// with the other; `given` holds kp_ratio, yield_ratio, chi and spike as
/// written, `at` places a key. Returns k_T^p / k_T^e (1 for an Iwan
/// density: unused). `asperity calibrate` checks its `[tangential]` by it.
pub(crate) fn backbone_keys(
    backbone: BackboneKind,
    given: [Option<f64>; 4],
    at: &dyn Fn(&str) -> String,
) -> Result<f64> {
    let [kp_ratio, yield_ratio, chi, spike] = given;
    let refuse = |k: &str, why: &str| Err(Error::input(at(k), why.to_string()));
    match backbone {
        BackboneKind::Bilinear => {
            for (k, v) in [("chi", chi), ("spike", spike)] {
                if v.is_some() {
                    return refuse(k, &format!("`{k}` belongs to backbone = \"iwan\" (a density of slip thresholds); the bilinear backbone takes kp_ratio and yield_ratio"));
                }
            }
            kp_ratio.map_or_else(
                || refuse("kp_ratio", "needs `kp_ratio` (k_T^p / k_T^e in [0, 1], 1: no micro-slip branch) for the paper's bilinear backbone"),
                Ok,
            )
        }
        BackboneKind::Iwan => {
            for (k, v) in [("kp_ratio", kp_ratio), ("yield_ratio", yield_ratio)] {
                if v.is_some() {
                    return refuse(k, &format!("`{k}` belongs to the bilinear backbone; with backbone = \"iwan\" the density (chi, spike) sets how the stiffness falls to μ p_N"));
                }
            }
            Ok(1.0)
        }
    }
}
