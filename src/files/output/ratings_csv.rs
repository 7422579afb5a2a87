//! `ratings.csv`: each `[[rating]]`'s checks over the run, one row per
//! increment at which a check's numbers changed ([`crate::verdict::history`]:
//! the ratings of the run as it stood there), so a designer reads when a
//! safety fell below its demand without the summary's last word alone.

use super::joints_csv::csv_field;
use crate::error::Result;
use crate::model::Model;
use crate::solve::RunResult;
use std::collections::BTreeMap;
use std::fmt::Write as _;

/// A check of a rating: the rating's index, the check's symbol and cycle.
type Key<'a> = (usize, &'a str, Option<usize>);
/// A check's numbers as bits (fe, handbook, required, safety) and its pass.
type Numbers = [Option<u64>; 5];

/// The columns of `ratings.csv`.
pub const RATINGS_HEADER: &str =
    "increment,time,rating,symbol,cycle,fe,handbook,required,safety,pass";

/// The file's text: a row for a check at the first increment it has a
/// number at and at every increment one of its numbers (fe, handbook,
/// required, safety, pass) differs from its last row; empty fields for
/// null, `pass` 1 or 0. A rating that cannot be rated yet at an increment
/// (a bolt before its lock, cycles before the first closes) has no row there.
pub fn csv(model: &Model, r: &RunResult) -> Result<String> {
    let mut s = String::from(RATINGS_HEADER);
    s.push('\n');
    let mut last: BTreeMap<Key, Numbers> = BTreeMap::new();
    for (increment, time, ratings) in crate::verdict::history(model, r)? {
        for (k, rating) in ratings.iter().enumerate() {
            if rating.incomplete.is_some() {
                continue;
            }
            for c in &rating.checks {
                let bits = |v: Option<f64>| v.map(f64::to_bits);
                let now = [
                    bits(c.fe),
                    bits(c.handbook),
                    bits(c.required),
                    bits(c.safety),
                    c.pass.map(u64::from),
                ];
                let key = (k, c.symbol, c.cycle);
                if now.iter().all(Option::is_none) || last.get(&key) == Some(&now) {
                    continue;
                }
                last.insert(key, now);
                let num = |v: Option<f64>| v.map_or(String::new(), |x| format!("{x:.9e}"));
                let _ = writeln!(
                    s,
                    "{increment},{time:.9},{},{},{},{},{},{},{},{}",
                    csv_field(&rating.name),
                    csv_field(c.symbol),
                    c.cycle.map_or(String::new(), |n| n.to_string()),
                    num(c.fe),
                    num(c.handbook),
                    num(c.required),
                    num(c.safety),
                    c.pass.map_or("", |p| if p { "1" } else { "0" }),
                );
            }
        }
    }
    Ok(s)
}
