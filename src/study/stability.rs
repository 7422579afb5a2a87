//! `asperity study stability`: load-step size × method (× friction scheme), each
//! run once without cutbacks (does the method survive this step?) and once with
//! the default cutbacks (what does the rescue cost?). Picture: a map of where each
//! method fails; the fastest plain success is the recommended default.

use super::plot::{load_font, save_grid, Grid};
use super::runner::{self, Which};
use crate::case::Method;
use crate::error::{Error, Result};
use std::path::{Path, PathBuf};

pub struct Outcome {
    pub config: String,
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
) -> Result<(Vec<PathBuf>, Vec<Outcome>, String)> {
    std::fs::create_dir_all(out).map_err(|e| Error::io(out, e))?;
    let scratch = out.join(".runs");
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
                runner::run(
                    case,
                    &a,
                    Which::Serial,
                    &scratch.join(format!("{}-{n}-{tag}", label(cfg).replace([',', ' '], "_"))),
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
    }
    let _ = std::fs::remove_dir_all(&scratch);
    // accuracy: the final centre displacement against the first configuration's
    // finest-step run (plastic flow is path-dependent: big steps are less accurate)
    let reference = outcomes
        .iter()
        .filter(|o| o.config == label(&configs[0]))
        .max_by_key(|o| o.steps)
        .and_then(|o| o.plain.as_ref().ok().map(|p| p.center));
    let err =
        |p: &runner::Point| reference.map_or(f64::NAN, |r| 100.0 * ((p.center - r) / r).abs());
    let cells: Vec<Vec<(bool, String)>> = configs
        .iter()
        .map(|cfg| {
            outcomes
                .iter()
                .filter(|o| o.config == label(cfg))
                .map(|o| match (&o.plain, &o.rescued) {
                    (Ok(p), _) => (
                        true,
                        format!("{:.0} it, {:.2} s, {:.2}%", p.iterations, p.wall, err(p)),
                    ),
                    (Err(_), Ok(p)) => (
                        false,
                        format!(
                            "cut {:.0}×: {:.0} it, {:.1} s",
                            p.cutbacks, p.iterations, p.wall
                        ),
                    ),
                    (Err(_), Err(_)) => (false, "fails even with cutbacks".into()),
                })
                .collect()
        })
        .collect();
    let grid = Grid {
        title: format!("Where each method fails: {}", case.display()),
        x_label: "equal load steps; green: converges without a cutback (iterations, time, error of the final settlement)".into(),
        columns: steps.iter().map(|n| format!("{n} steps")).collect(),
        rows: configs.iter().map(label).collect(),
        cells,
    };
    let files = save_grid(&grid, &out.join("stability-map"), load_font())?;
    let best = outcomes
        .iter()
        .filter_map(|o| o.plain.as_ref().ok().filter(|p| err(p) <= 1.0).map(|p| (o, p.wall)))
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(o, w)| format!("fastest within 1% of the finest-step answer, without a cutback: {} with {} steps ({w:.2} s)", o.config, o.steps))
        .unwrap_or_else(|| "no configuration converged within 1% without cutbacks".into());
    Ok((files, outcomes, best))
}
