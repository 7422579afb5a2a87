//! `asperity study stability`: load-step size × method (× friction scheme), each
//! run once without cutbacks (does the method survive this step?) and once with
//! the default cutbacks (what does the rescue cost?), plus a column of automatic
//! step control. Accuracy is the error of the final settlement against a
//! full-Newton run with four times the finest fixed steps. Picture: a map of
//! where each method fails, with the program's default framed.

use super::plot::{load_font, save_grid, Grid};
use super::runner::{self, Which};
use crate::case::Method;
use crate::error::{Error, Result};
use std::path::{Path, PathBuf};

pub struct Outcome {
    pub config: String,
    /// Equal load steps; 0 for automatic step control.
    pub steps: usize,
    pub plain: std::result::Result<runner::Point, String>,
    pub rescued: std::result::Result<runner::Point, String>,
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
    let mut outcomes = Vec::new();
    // (method, friction scheme, plain = without Anderson acceleration)
    let mut configs: Vec<(Method, Option<&str>, bool)> = Vec::new();
    for &m in methods {
        for plain in [false, true] {
            if plain && m == Method::FullNewton {
                continue;
            }
            if schemes.is_empty() {
                configs.push((m, None, plain));
            }
            for &s in schemes {
                configs.push((m, Some(s), plain));
            }
        }
    }
    let label = |(m, s, plain): &(Method, Option<&str>, bool)| {
        let mut l = m.name().to_string();
        if let Some(s) = s {
            l += &format!(", {s}");
        }
        if *plain {
            l += ", plain";
        }
        l
    };
    for cfg in &configs {
        for &n in steps {
            let mut base = vec![
                "--increments".to_string(),
                n.to_string(),
                "--method".into(),
                cfg.0.name().into(),
            ];
            if let Some(s) = cfg.1 {
                base.extend(["--friction-scheme".into(), s.into()]);
            }
            if cfg.2 {
                base.push("--plain".into());
            }
            let run = |cut: &str, tag: &str| {
                let mut a = base.clone();
                a.extend(["--max-cutbacks".into(), cut.into()]);
                runner::run_limited(
                    case,
                    &a,
                    Which::Serial,
                    &scratch.join(format!("{}-{n}-{tag}", label(cfg).replace([',', ' '], "_"))),
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
                label(cfg),
                if plain.is_ok() {
                    "ok"
                } else {
                    "failed without cutbacks"
                }
            );
            outcomes.push(Outcome {
                config: label(cfg),
                steps: n,
                plain,
                rescued,
            });
        }
        // automatic steps (cutbacks are part of the method: one run)
        let mut a = vec!["--step-control".to_string(), "auto".into()];
        a.extend(["--method".into(), cfg.0.name().into()]);
        if let Some(s) = cfg.1 {
            a.extend(["--friction-scheme".into(), s.into()]);
        }
        if cfg.2 {
            a.push("--plain".into());
        }
        let auto = runner::run_limited(
            case,
            &a,
            Which::Serial,
            &scratch.join(format!("{}-auto", label(cfg).replace([',', ' '], "_"))),
            limit,
        );
        eprintln!(
            "study: {} with automatic steps: {}",
            label(cfg),
            if auto.is_ok() { "ok" } else { "failed" }
        );
        outcomes.push(Outcome {
            config: label(cfg),
            steps: 0,
            plain: auto.clone(),
            rescued: auto,
        });
    }
    let finest = steps.iter().copied().max().unwrap_or(1) * 4;
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
    let _ = std::fs::remove_dir_all(&scratch);
    // the parent too, when no other study is using it
    let _ = std::fs::remove_dir(out.join(".runs"));
    let reference = Some(reference.center);
    let err =
        |p: &runner::Point| reference.map_or(f64::NAN, |r| 100.0 * ((p.center - r) / r).abs());
    let cells: Vec<Vec<(bool, String)>> = configs
        .iter()
        .map(|cfg| {
            outcomes
                .iter()
                .filter(|o| o.config == label(cfg))
                .map(|o| match (&o.plain, &o.rescued) {
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
                })
                .collect()
        })
        .collect();
    let default_row = configs
        .iter()
        .position(|c| c.0 == Method::FullNewton && !c.2);
    let grid = Grid {
        title: format!("Where each method fails: {}", case.display()),
        x_label: format!(
            "green: converges (fixed steps: without a cutback); Newton iterations, time, error of the final settlement against {finest} full-Newton steps"
        ),
        columns: steps
            .iter()
            .map(|n| format!("{n} steps"))
            .chain(std::iter::once("automatic".to_string()))
            .collect(),
        rows: configs.iter().map(label).collect(),
        cells,
        marked: default_row.map(|r| {
            (
                r,
                steps.len(),
                "framed: the program's default when a case names no method and no schedule".into(),
            )
        }),
    };
    let files = save_grid(&grid, &out.join("stability-map"), load_font())?;
    let best = outcomes
        .iter()
        .filter_map(|o| {
            o.plain
                .as_ref()
                .ok()
                .filter(|p| err(p) <= 0.1)
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
        .unwrap_or_else(|| "no configuration came within 0.1% of the reference".into());
    Ok((files, outcomes, best))
}
