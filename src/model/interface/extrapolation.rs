//! How far beyond their data the tabulated laws are used (issue 30).
//!
//! Beyond its last row a `table` (u_N → p) or `k_table` (p_N → k_T^e) is
//! extrapolated linearly ([`crate::physics::contact::table`]): a fallback, not a
//! measurement. A run records the largest approach and pressure of every
//! interface over its converged states ([`Reach`], kept in the checkpoint and
//! the restart file); `table_uses` sets them against the tables' last rows,
//! and a law evaluated beyond `EXTRAPOLATION_LIMIT` times its last row's
//! argument is reported: a `warning:` line on stderr after the run, the
//! `tables` and `warnings` fields of summary.json, and, where the applied load
//! alone predicts it, a warning of `asperity check`.

use super::InterfaceModel;
use crate::physics::contact::table::{Monotone, EXTRAPOLATION_LIMIT};

/// The largest arguments an interface's laws met: the approach u_N (of the
/// normal law, mm) and the normal pressure p_N (of k_T^e, MPa), over every
/// spring point of the states seen.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Reach {
    pub u_n: f64,
    pub p_n: f64,
}

impl Reach {
    /// Doubles per interface in the restart file's `table_reach` section.
    pub const PACKED: usize = 2;

    /// The largest u_N and p_N of the interface's points in the state with
    /// displacements `u` at pseudo-time `time`.
    pub fn of(im: &InterfaceModel, u: &[f64], time: f64) -> Reach {
        let gap = im.gap_at(time);
        im.points.iter().fold(Reach::default(), |r, pt| {
            let u_n = im.point_kinematics_at(pt, u, gap).0;
            r.max(Reach {
                u_n,
                p_n: im.law.pressure(u_n).0,
            })
        })
    }

    /// The larger of each.
    pub fn max(self, o: Reach) -> Reach {
        Reach {
            u_n: self.u_n.max(o.u_n),
            p_n: self.p_n.max(o.p_n),
        }
    }

    pub fn pack(&self) -> [f64; Self::PACKED] {
        [self.u_n, self.p_n]
    }

    pub(crate) fn unpack(v: &[f64]) -> Reach {
        Reach {
            u_n: v[0],
            p_n: v[1],
        }
    }
}

/// One tabulated law of an interface and the largest argument it met.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct TableUse {
    pub interface: String,
    /// The case key: `table` (the normal law) or `tangential k_table`.
    pub key: &'static str,
    /// The law's argument: `u_N` or `p_N`.
    pub argument: &'static str,
    /// Its unit: `mm` or `MPa`.
    pub unit: &'static str,
    /// The argument of the table's last row.
    pub(crate) last_row: f64,
    /// The largest argument met (0 when the interface never closed).
    pub largest: f64,
}

impl TableUse {
    /// largest / last_row.
    pub fn ratio(&self) -> f64 {
        self.largest / self.last_row
    }

    /// Beyond [`EXTRAPOLATION_LIMIT`] times the last row.
    pub fn far(&self) -> bool {
        self.ratio() > EXTRAPOLATION_LIMIT
    }

    /// The warning (without `warning: `): `how` says what reached `largest`
    /// ("the run evaluated it up to", "the applied load alone needs").
    pub fn warning(&self, place: &str, how: &str) -> String {
        format!(
            "{place}: [interface.{}] {}: {how} {} = {:.4e} {}, {:.3} × its last row's {} = {:.4e} {} (more than {EXTRAPOLATION_LIMIT} ×): beyond its last row the table is extrapolated linearly, not measured; give rows up to the largest {} the model reaches",
            self.interface,
            self.key,
            self.argument,
            self.largest,
            self.unit,
            self.ratio(),
            self.argument,
            self.last_row,
            self.unit,
            if self.argument == "u_N" { "approach" } else { "pressure" }
        )
    }
}

/// Every tabulated law of the interfaces, in order (the normal table before
/// the k_table of one interface), with the largest argument of `reach`
/// (one per interface).
pub(crate) fn table_uses(interfaces: &[InterfaceModel], reach: &[Reach]) -> Vec<TableUse> {
    let mut out = Vec::new();
    for (im, r) in interfaces.iter().zip(reach) {
        let last = |t: &Monotone| t.last().0;
        if let Some(t) = im.law.table() {
            out.push(TableUse {
                interface: im.name.clone(),
                key: "table",
                argument: "u_N",
                unit: "mm",
                last_row: last(t),
                largest: r.u_n,
            });
        }
        if let Some(t) = im.tangential.as_ref().and_then(|t| t.k_table.as_ref()) {
            out.push(TableUse {
                interface: im.name.clone(),
                key: "tangential k_table",
                argument: "p_N",
                unit: "MPa",
                last_row: last(t),
                largest: r.p_n,
            });
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn far_means_beyond_twice_the_last_row() {
        let t = |largest| TableUse {
            interface: "c".into(),
            key: "table",
            argument: "u_N",
            unit: "mm",
            last_row: 0.01,
            largest,
        };
        assert!(!t(0.02).far() && !t(0.005).far() && !t(0.0).far());
        assert!(t(0.0201).far());
        let w = t(10.0).warning("case.toml", "the run evaluated it up to");
        assert!(
            w.contains("[interface.c] table: the run evaluated it up to u_N = 1.0000e1 mm, 1000.000 × its last row's u_N = 1.0000e-2 mm"),
            "{w}"
        );
        assert_eq!(
            Reach::unpack(&Reach { u_n: 1.0, p_n: 2.0 }.pack()),
            Reach { u_n: 1.0, p_n: 2.0 }
        );
    }
}
