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
use crate::interrupt::Stop;
use crate::model::Model;
use crate::solve::events::Event;
use crate::solve::{Increment, RunResult};

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

/// What a rating reads of a run: its increments, the events located in
/// them, and why it stopped early (if it did).
#[derive(Clone, Copy)]
pub struct Run<'a> {
    pub increments: &'a [Increment],
    pub events: &'a [Event],
    pub stopped: Option<&'a Stop>,
}

impl<'a> Run<'a> {
    /// A finished run.
    pub fn of(r: &'a RunResult) -> Self {
        Run {
            increments: &r.increments,
            events: &r.events,
            stopped: r.stopped.as_ref(),
        }
    }

    /// Its first `k` increments, as a run that ended there (the events of
    /// those increments; not stopped: the history goes on).
    fn until(&self, k: usize, events: &'a [Event]) -> Self {
        Run {
            increments: &self.increments[..k],
            events,
            stopped: None,
        }
    }
}

/// The ratings of a finished run, in the case's order.
pub fn rate(model: &Model, r: &RunResult) -> Result<Vec<rating::Rating>> {
    rate_run(model, &Run::of(r))
}

/// The ratings as they stood at each increment of the run: (increment,
/// load factor, the ratings of the run up to it), each on the increments
/// and events reached by then, so a check reads what it would have read had
/// the run ended there (a bolt before its lock: nothing to rate yet).
pub fn history(model: &Model, r: &RunResult) -> Result<Vec<(usize, f64, Vec<rating::Rating>)>> {
    let all = Run::of(r);
    let mut out = Vec::new();
    for (k, inc) in r.increments.iter().enumerate() {
        let events: Vec<Event> = r
            .events
            .iter()
            .filter(|e| e.increment <= inc.increment)
            .cloned()
            .collect();
        let ratings = rate_run(model, &all.until(k + 1, &events))?;
        out.push((inc.increment, inc.load_factor, ratings));
    }
    Ok(out)
}

fn rate_run(model: &Model, r: &Run) -> Result<Vec<rating::Rating>> {
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
    if let Some(stop) = r.stopped {
        let t = r.increments.last().map_or(0.0, |i| i.load_factor);
        for rating in &mut out {
            rating.incomplete = Some(if *stop == crate::interrupt::Stop::TorqueLimit {
                format!(
                    "the run ended at its torque limit (λ = {}): a body held by friction could not hold the torque on it beyond, so the load history was not carried to its end; these are the checks of the state that last held, no verdict",
                    crate::numbers::sig(t, 6)
                )
            } else {
                format!(
                    "the run stopped early ({}, λ = {}): these are the checks of a partial run, no verdict",
                    stop.name(),
                    crate::numbers::sig(t, 6)
                )
            });
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
