//! What a designer concludes from a run: the ratings of the standards a joint is designed to
//! (DIN 7190-1:2017 for interference fits, VDI 2230-1:2015 for bolted joints) and of a joint
//! under load cycles (its steady loops for the part, [`cycles`]), the handbook's side
//! computed from the standard's own formulas or a closed form ([`handbook`]) and set beside the
//! numbers the run measured ([`rating::Rating`]).

pub mod bolt;
pub mod cycles;
pub mod fit;
pub mod handbook;
pub mod rating;

use crate::error::Result;
use crate::input::case::rating::RatingSpec;
use crate::model::Model;
use crate::solve::RunResult;

/// Checks that every `[[rating]]` can be rated on this model (the names it
/// gives exist, the model is of the kind the standard rates), before the
/// run; returns a line per rating for `check`: the standard, its name and
/// its inputs.
pub fn prepare(model: &Model) -> Result<Vec<String>> {
    let mut lines = Vec::new();
    for (i, spec) in model.ratings.iter().enumerate() {
        let at = at(model, i, spec);
        let inputs = match spec {
            RatingSpec::Fit(f) => fit::pose(model, f, &at)?.inputs,
            RatingSpec::Bolt(b) => bolt::pose(model, b, &at)?.inputs,
            RatingSpec::Cycles(c) => cycles::pose(model, c, &at)?.inputs,
        };
        let words: Vec<String> = inputs
            .iter()
            .map(|x| {
                format!(
                    "{} {} {}",
                    x.symbol,
                    crate::numbers::sig(x.value, 5),
                    x.unit
                )
                .trim_end()
                .to_string()
            })
            .collect();
        lines.push(format!(
            "rating \"{}\" ({}): {}",
            spec.name(),
            spec.standard(),
            words.join(", ")
        ));
    }
    Ok(lines)
}

/// The ratings of a finished run, in the case's order.
pub fn rate(model: &Model, r: &RunResult) -> Result<Vec<rating::Rating>> {
    let mut out = Vec::new();
    for (i, spec) in model.ratings.iter().enumerate() {
        let at = at(model, i, spec);
        match spec {
            RatingSpec::Fit(f) => {
                let posed = fit::pose(model, f, &at)?;
                out.push(fit::rate(model, r, f, posed));
            }
            RatingSpec::Bolt(b) => {
                let posed = bolt::pose(model, b, &at)?;
                out.push(bolt::rate(model, r, b, posed));
            }
            RatingSpec::Cycles(c) => {
                let posed = cycles::pose(model, c, &at)?;
                out.push(cycles::rate(model, r, c, posed));
            }
        }
    }
    if let Some(stop) = &r.stopped {
        let t = r.increments.last().map_or(0.0, |i| i.load_factor);
        for rating in &mut out {
            rating.incomplete = Some(format!(
                "the run stopped early ({}, λ = {}): these are the checks of a partial run, no verdict",
                stop.name(),
                crate::numbers::sig(t, 6)
            ));
        }
    }
    Ok(out)
}

fn at(model: &Model, i: usize, spec: &RatingSpec) -> String {
    format!(
        "{}: rating[{i}] ({})",
        model.source.display(),
        spec.standard()
    )
}
