//! `asperity study stability`: load-step size × method (× friction scheme), each
//! run once without cutbacks (does the method survive this step?) and once with
//! the default cutbacks (what does the rescue cost?), plus a column of automatic
//! step control. Accuracy is the error of the final settlement against a
//! full-Newton run with four times the finest fixed steps. Picture: a map of
//! where each method fails, with the program's default framed.

use super::runner::{self, Which};
use crate::error::{Error, Result};
use crate::files::plot::{load_font, save_grid, Grid};
use crate::input::case::Method;
use std::path::{Path, PathBuf};

pub struct Outcome {
    pub(crate) config: String,
    /// Equal load steps; 0 for automatic step control.
    pub steps: usize,
    pub plain: std::result::Result<runner::Point, String>,
    pub(crate) rescued: std::result::Result<runner::Point, String>,
}

/// One row of the map: a method, perhaps a friction scheme, perhaps without
/// Anderson acceleration (`plain`).
struct Setting<'a> {
    method: Method,
    scheme: Option<&'a str>,
    plain: bool,
}

impl Setting<'_> {
    /// The row's name, e.g. "modified-newton, return-mapping, plain".
    fn label(&self) -> String {
        let mut l = self.method.name().to_string();
        if let Some(s) = self.scheme {
            l += &format!(", {s}");
        }
        if self.plain {
            l += ", plain";
        }
        l
    }

    /// The `run` arguments that choose this setting.
    fn args(&self) -> Vec<String> {
        let mut a = vec!["--method".to_string(), self.method.name().into()];
        if let Some(s) = self.scheme {
            a.extend(["--friction-scheme".into(), s.into()]);
        }
        if self.plain {
            a.push("--plain".into());
        }
        a
    }

    /// The scratch folder of this setting's run `tag`.
    fn dir(&self, scratch: &Path, tag: &str) -> PathBuf {
        scratch.join(format!("{}-{tag}", self.label().replace([',', ' '], "_")))
    }
}

/// The rows: each method with and without acceleration (full Newton only
/// with), times each friction scheme when schemes are given.
fn settings<'a>(methods: &[Method], schemes: &[&'a str]) -> Vec<Setting<'a>> {
    let mut settings = Vec::new();
    for &method in methods {
        for plain in [false, true] {
            if plain && method == Method::FullNewton {
                continue;
            }
            if schemes.is_empty() {
                settings.push(Setting {
                    method,
                    scheme: None,
                    plain,
                });
            }
            for &s in schemes {
                settings.push(Setting {
                    method,
                    scheme: Some(s),
                    plain,
                });
            }
        }
    }
    settings
}

/// `n` equal steps: once without cutbacks, and only when that fails, again
/// with eight.
fn run_fixed(
    case: &Path,
    setting: &Setting,
    n: usize,
    scratch: &Path,
    limit: Option<std::time::Duration>,
) -> Outcome {
    let mut base = vec!["--increments".to_string(), n.to_string()];
    base.extend(setting.args());
    let run = |cut: &str, tag: &str| {
        let mut a = base.clone();
        a.extend(["--max-cutbacks".into(), cut.into()]);
        runner::run_limited(
            case,
            &a,
            Which::Serial,
            &setting.dir(scratch, &format!("{n}-{tag}")),
            limit,
        )
    };
    let plain = run("0", "plain");
    let rescued = if plain.is_ok() {
        plain.clone()
    } else {
        run("8", "rescued")
    };
    eprintln!(
        "study: {} with {n} steps: {}",
        setting.label(),
        if plain.is_ok() {
            "ok"
        } else {
            "failed without cutbacks"
        }
    );
    Outcome {
        config: setting.label(),
        steps: n,
        plain,
        rescued,
    }
}

/// Automatic steps (cutbacks are part of the method: one run).
fn run_auto(
    case: &Path,
    setting: &Setting,
    scratch: &Path,
    limit: Option<std::time::Duration>,
) -> Outcome {
    let mut a = vec!["--step-control".to_string(), "auto".into()];
    a.extend(setting.args());
    let auto = runner::run_limited(
        case,
        &a,
        Which::Serial,
        &setting.dir(scratch, "auto"),
        limit,
    );
    eprintln!(
        "study: {} with automatic steps: {}",
        setting.label(),
        if auto.is_ok() { "ok" } else { "failed" }
    );
    Outcome {
        config: setting.label(),
        steps: 0,
        plain: auto.clone(),
        rescued: auto,
    }
}

/// The reference settlement: full Newton with `finest` equal steps.
fn reference(case: &Path, finest: usize, scratch: &Path) -> Result<f64> {
    let reference = runner::run(
        case,
        &[
            "--increments".to_string(),
            finest.to_string(),
            "--method".into(),
            "full-newton".into(),
        ],
        Which::Serial,
        &scratch.join("reference"),
    )
    .map_err(|e| Error::Study(format!("the reference run ({finest} steps) failed: {e}")))?;
    Ok(reference.center)
}

/// Error of a run's final settlement against the reference, in percent.
fn error_percent(p: &runner::Point, reference: f64) -> f64 {
    100.0 * ((p.center - reference) / reference).abs()
}

/// One cell of the map: converged (green) or not, and its text.
fn cell(o: &Outcome, reference: f64) -> (bool, String) {
    let err = |p: &runner::Point| error_percent(p, reference);
    match (&o.plain, &o.rescued) {
        (Ok(p), _) if o.steps == 0 => (
            true,
            format!(
                "{:.0} steps, {:.0} cut\n{:.0} it, {:.2} s\nerror {:.3}%",
                p.increments,
                p.cutbacks,
                p.iterations,
                p.wall,
                err(p)
            ),
        ),
        (Ok(p), _) => (
            true,
            format!(
                "{:.0} it, {:.2} s\nerror {:.3}%",
                p.iterations,
                p.wall,
                err(p)
            ),
        ),
        (Err(_), Ok(p)) => (
            false,
            format!(
                "fails; rescued by\n{:.0} cutbacks:\n{:.0} it, {:.1} s",
                p.cutbacks, p.iterations, p.wall
            ),
        ),
        (Err(_), Err(e)) if e.starts_with("stopped after") => {
            (false, format!("fails; the rescue\n{e}"))
        }
        (Err(_), Err(_)) => (false, "fails even\nwith cutbacks".into()),
    }
}

/// The map: a row per setting, a column per step count and one for automatic
/// steps, the program's default (full Newton, automatic steps) framed.
fn map(
    case: &Path,
    steps: &[usize],
    settings: &[Setting],
    outcomes: &[Outcome],
    finest: usize,
    reference: f64,
) -> Grid {
    let cells: Vec<Vec<(bool, String)>> = settings
        .iter()
        .map(|s| {
            outcomes
                .iter()
                .filter(|o| o.config == s.label())
                .map(|o| cell(o, reference))
                .collect()
        })
        .collect();
    let default_row = settings
        .iter()
        .position(|s| s.method == Method::FullNewton && !s.plain);
    Grid {
        title: format!("Where each method fails: {}", case.display()),
        x_label: format!(
            "green: converges (fixed steps: without a cutback); Newton iterations, time, error of the final settlement against {finest} full-Newton steps"
        ),
        columns: steps
            .iter()
            .map(|n| format!("{n} steps"))
            .chain(std::iter::once("automatic".to_string()))
            .collect(),
        rows: settings.iter().map(Setting::label).collect(),
        cells,
        marked: default_row.map(|r| {
            (
                r,
                steps.len(),
                "framed: the program's default when a case names no method and no schedule".into(),
            )
        }),
    }
}

/// The fastest run without cutbacks within 0.1% of the reference settlement.
fn recommendation(outcomes: &[Outcome], reference: f64) -> String {
    outcomes
        .iter()
        .filter_map(|o| {
            o.plain
                .as_ref()
                .ok()
                .filter(|p| error_percent(p, reference) <= 0.1)
                .map(|p| (o, p.wall))
        })
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(o, w)| {
            let how = if o.steps == 0 {
                "automatic steps".to_string()
            } else {
                format!("{} steps", o.steps)
            };
            format!(
                "fastest within 0.1% of the reference settlement: {} with {how} ({w:.2} s)",
                o.config
            )
        })
        .unwrap_or_else(|| "no configuration came within 0.1% of the reference".into())
}

/// Runs the grid; returns the files written, the outcomes and the recommendation.
pub fn stability(
    case: &Path,
    steps: &[usize],
    methods: &[Method],
    schemes: &[&str],
    out: &Path,
    limit: Option<std::time::Duration>,
) -> Result<(Vec<PathBuf>, Vec<Outcome>, String)> {
    std::fs::create_dir_all(out).map_err(|e| Error::io(out, e))?;
    let scratch = out.join(format!(".runs/stability-{}", std::process::id()));
    let settings = settings(methods, schemes);
    let mut outcomes = Vec::new();
    for setting in &settings {
        for &n in steps {
            outcomes.push(run_fixed(case, setting, n, &scratch, limit));
        }
        outcomes.push(run_auto(case, setting, &scratch, limit));
    }
    let finest = steps.iter().copied().max().unwrap_or(1) * 4;
    let reference = reference(case, finest, &scratch)?;
    let _ = std::fs::remove_dir_all(&scratch);
    // the parent too, when no other study is using it
    let _ = std::fs::remove_dir(out.join(".runs"));
    let grid = map(case, steps, &settings, &outcomes, finest, reference);
    let files = save_grid(&grid, &out.join("stability-map"), load_font())?;
    let best = recommendation(&outcomes, reference);
    Ok((files, outcomes, best))
}
