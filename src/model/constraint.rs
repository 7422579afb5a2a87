//! Linear multi-point constraints of the model, u_s = Σ_i c_i u_i + g h(t):
//! one mechanism for every dof whose value follows from others — the two
//! sides of a pretension section ([`crate::model::pretension`]) and the
//! hanging nodes of a refined mesh (`crate::model::hanging`).
//!
//! The constraints are **eliminated**: a slave dof s has no equation; with
//! T the map from the remaining (master, free or prescribed) dofs to all
//! dofs, u = T ū + g(t), the Newton system is
//!
//! ```text
//!   Tᵀ K T Δū = −Tᵀ R(T ū + g(t))
//! ```
//!
//! (e.g. Cook, Malkus, Plesha & Witt, *Concepts and Applications of Finite
//! Element Analysis*, 4th ed., section 9.2, "transformation equations").
//! Nothing below the model sees a slave: every local block (element or
//! interface point) that holds one is handed to the backends as the block
//! Tₑᵀ kₑ Tₑ over its masters (`Expansion`), and the assembled residual is
//! condensed, r_m += c r_s (`Constraints::condense`); so the serial and the
//! PETSc backends, their patterns and partitions need nothing new. A master
//! is never a slave: chains are substituted when the constraints are made.
//!
//! A dof may also be **held** from a pseudo-time on (a locked pretension
//! section): it keeps its equation, so the pattern and the factorization's
//! analysis do not change, but its row and column of the tangent are zero
//! but for the diagonal and its residual is zero, so Newton leaves it where
//! it was ([`crate::solve::newton`]).

use std::collections::HashMap;

const NONE: u32 = u32::MAX;

/// Substitution depth beyond which a chain of constraints is a cycle.
const MAX_CHAIN: usize = 16;

/// u_slave = Σ c_i u_(dof i) + offset · h(t).
#[derive(Clone, Debug, PartialEq)]
pub struct Constraint {
    pub slave: usize,
    /// (master dof, coefficient); no master twice, none the slave.
    pub terms: Vec<(usize, f64)>,
    /// g at factor 1 (mm).
    pub offset: f64,
    /// The history of g (`None`: the load factor, or the default ramp), as
    /// for a prescribed dof ([`crate::model::Model::factor`]).
    pub history: Option<usize>,
    /// What made it, for messages: e.g. `pretension "bolt"`.
    pub origin: String,
}

/// Every constraint of a model, slaves indexed.
#[derive(Clone, Debug, Default)]
pub struct Constraints {
    pub list: Vec<Constraint>,
    /// dof → its constraint in `list` (NONE: not a slave); empty without
    /// constraints.
    slave_of: Vec<u32>,
}

impl Constraints {
    /// Checks and indexes the constraints over `n_dofs` dofs: one constraint
    /// per slave (else "two values for one constrained dof"), finite
    /// coefficients, dofs in range; a master that is itself a slave is
    /// replaced by its own terms (a chain), a cycle is refused.
    pub fn new(list: Vec<Constraint>, n_dofs: usize) -> Result<Constraints, String> {
        let mut slave_of = vec![NONE; if list.is_empty() { 0 } else { n_dofs }];
        for (k, c) in list.iter().enumerate() {
            if c.slave >= n_dofs || c.terms.iter().any(|&(d, _)| d >= n_dofs) {
                return Err(format!("{}: a dof out of range", c.origin));
            }
            if !(c.offset.is_finite() && c.terms.iter().all(|t| t.1.is_finite())) {
                return Err(format!("{}: a coefficient is not finite", c.origin));
            }
            if slave_of[c.slave] != NONE {
                let other = &list[slave_of[c.slave] as usize];
                return Err(format!(
                    "dof {} is constrained twice, by {} and by {}: one dof takes one value",
                    c.slave, other.origin, c.origin
                ));
            }
            slave_of[c.slave] = k as u32;
        }
        let mut out = Constraints {
            list: list.clone(),
            slave_of,
        };
        for (k, c) in list.iter().enumerate() {
            out.list[k] = out.substituted(c, 0)?;
        }
        Ok(out)
    }

    /// `c` with every master that is a slave replaced by that slave's terms.
    fn substituted(&self, c: &Constraint, depth: usize) -> Result<Constraint, String> {
        if depth > MAX_CHAIN {
            return Err(format!(
                "{}: the constraints of dof {} form a cycle",
                c.origin, c.slave
            ));
        }
        if c.terms.iter().all(|&(d, _)| !self.is_slave(d)) {
            return Ok(c.clone());
        }
        let mut terms: Vec<(usize, f64)> = Vec::new();
        let mut offset = c.offset;
        let mut history = c.history;
        let mut add = |d: usize, v: f64| match terms.iter_mut().find(|t| t.0 == d) {
            Some(t) => t.1 += v,
            None => terms.push((d, v)),
        };
        for &(d, a) in &c.terms {
            match self.of(d) {
                None => add(d, a),
                Some(inner) => {
                    let inner = self.substituted(inner, depth + 1)?;
                    if inner.offset != 0.0 {
                        if offset != 0.0 && history != inner.history {
                            return Err(format!(
                                "{}: chains constraints with offsets on two histories",
                                c.origin
                            ));
                        }
                        history = inner.history;
                        offset += a * inner.offset;
                    }
                    for (m, b) in inner.terms {
                        add(m, a * b);
                    }
                }
            }
        }
        if terms.iter().any(|t| t.0 == c.slave) {
            return Err(format!(
                "{}: the constraints of dof {} form a cycle",
                c.origin, c.slave
            ));
        }
        Ok(Constraint {
            slave: c.slave,
            terms,
            offset,
            history,
            origin: c.origin.clone(),
        })
    }

    pub fn is_empty(&self) -> bool {
        self.list.is_empty()
    }

    pub(crate) fn is_slave(&self, d: usize) -> bool {
        self.slave_of.get(d).is_some_and(|&k| k != NONE)
    }

    /// The constraint whose slave is `d`.
    pub fn of(&self, d: usize) -> Option<&Constraint> {
        match self.slave_of.get(d) {
            Some(&k) if k != NONE => Some(&self.list[k as usize]),
            _ => None,
        }
    }

    /// Sets every slave from its masters: u_s = Σ c u_m + g · factor(h).
    pub fn fill(&self, u: &mut [f64], factor: impl Fn(Option<usize>) -> f64) {
        for c in &self.list {
            let mut v: f64 = c.terms.iter().map(|&(d, a)| a * u[d]).sum();
            if c.offset != 0.0 {
                v += c.offset * factor(c.history);
            }
            u[c.slave] = v;
        }
    }

    /// The residual over all dofs condensed onto the masters, r ← Tᵀ r
    /// (r_m += c r_s), the slaves' entries then zero.
    pub(crate) fn condense(&self, r: &mut [f64]) {
        for c in &self.list {
            let rs = r[c.slave];
            for &(d, a) in &c.terms {
                r[d] += a * rs;
            }
            r[c.slave] = 0.0;
        }
    }

    /// The transformation of a local block whose dofs hold a slave (`None`
    /// when none does).
    pub(crate) fn expand(&self, dofs: &[usize]) -> Option<Expansion> {
        if self.slave_of.is_empty() || !dofs.iter().any(|&d| self.is_slave(d)) {
            return None;
        }
        let mut masters: Vec<usize> = Vec::new();
        let mut index: HashMap<usize, usize> = HashMap::new();
        let mut col = |d: usize, masters: &mut Vec<usize>| {
            *index.entry(d).or_insert_with(|| {
                masters.push(d);
                masters.len() - 1
            })
        };
        let mut entries = Vec::new();
        for (i, &d) in dofs.iter().enumerate() {
            match self.of(d) {
                None => entries.push((i, col(d, &mut masters), 1.0)),
                Some(c) => {
                    for &(m, a) in &c.terms {
                        entries.push((i, col(m, &mut masters), a));
                    }
                }
            }
        }
        let (n, m) = (dofs.len(), masters.len());
        let mut t = vec![0.0; n * m];
        for (i, j, a) in entries {
            t[i * m + j] += a;
        }
        Some(Expansion {
            dofs: masters,
            t,
            n,
        })
    }
}

/// The map Tₑ (n × m, row-major) from a block's masters to its own dofs.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Expansion {
    /// The masters (global dofs), the columns of T.
    pub dofs: Vec<usize>,
    pub t: Vec<f64>,
    /// The block's own dofs, the rows of T.
    pub n: usize,
}

impl Expansion {
    /// Tᵀ k T (m × m, row-major) of a row-major n × n block.
    pub fn matrix(&self, k: &[f64]) -> Vec<f64> {
        let (n, m) = (self.n, self.dofs.len());
        // k T (n × m), then Tᵀ (k T)
        let mut kt = vec![0.0; n * m];
        for i in 0..n {
            for l in 0..n {
                let a = k[i * n + l];
                if a == 0.0 {
                    continue;
                }
                for j in 0..m {
                    kt[i * m + j] += a * self.t[l * m + j];
                }
            }
        }
        let mut out = vec![0.0; m * m];
        for l in 0..n {
            for i in 0..m {
                let a = self.t[l * m + i];
                if a == 0.0 {
                    continue;
                }
                for j in 0..m {
                    out[i * m + j] += a * kt[l * m + j];
                }
            }
        }
        out
    }

    /// Tᵀ g (m) of a vector over the block's own dofs.
    pub fn vector(&self, g: &[f64]) -> Vec<f64> {
        let m = self.dofs.len();
        let mut out = vec![0.0; m];
        for (l, &gl) in g.iter().enumerate().take(self.n) {
            for (o, t) in out.iter_mut().zip(&self.t[l * m..(l + 1) * m]) {
                *o += t * gl;
            }
        }
        out
    }
}

#[cfg(test)]
mod tests;
