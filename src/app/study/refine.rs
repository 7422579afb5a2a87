//! `asperity study refine`: one case on a sequence of meshes, every method and
//! backend asked for, the graded mesh against an ungraded one. Reference values by
//! Richardson extrapolation of the three finest levels of the first configuration;
//! pictures: error against dofs and against wall time (work-precision), log-log,
//! with fitted slopes.

use super::runner::{self, Point, Which};
use crate::error::{Error, Result};
use crate::files::plot::{load_font, save, Chart, Series};
use crate::input::case::Method;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Richardson extrapolation from q_i = q* + C h_i^p at three mesh sizes h (any
/// ratios): returns (q*, p), or None when the sequence is not monotone.
pub fn richardson(h: [f64; 3], q: [f64; 3]) -> Option<(f64, f64)> {
    let (d1, d2) = (q[0] - q[1], q[1] - q[2]);
    if d1 == 0.0 || d2 == 0.0 || d1.signum() != d2.signum() {
        return None;
    }
    let ratio = d1 / d2;
    let g = |p: f64| (h[0].powf(p) - h[1].powf(p)) / (h[1].powf(p) - h[2].powf(p)) - ratio;
    let (mut lo, mut hi) = (1e-3, 12.0);
    if g(lo).signum() == g(hi).signum() {
        return None;
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if g(mid).signum() == g(lo).signum() {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let p = 0.5 * (lo + hi);
    let c = d1 / (h[0].powf(p) - h[1].powf(p));
    Some((q[2] - c * h[2].powf(p), p))
}

/// Least-squares slope of log10 y against log10 x.
fn slope(pts: &[(f64, f64)]) -> f64 {
    let n = pts.len() as f64;
    let (sx, sy) = pts.iter().fold((0.0, 0.0), |a, p| (a.0 + p.0, a.1 + p.1));
    let (mx, my) = (sx / n, sy / n);
    let (num, den) = pts.iter().fold((0.0, 0.0), |a, p| {
        (a.0 + (p.0 - mx) * (p.1 - my), a.1 + (p.0 - mx).powi(2))
    });
    num / den
}

pub struct Config {
    pub method: Method,
    /// Levels this configuration runs (None: all of the study's).
    pub levels: Option<Vec<usize>>,
    pub which: Which,
    pub uniform: bool,
    /// An adaptive run ([`crate::app::adapt`]) from the case's mesh: its cycles
    /// are the points (the wall time summed over the cycles so far).
    pub adapt: bool,
}

impl Config {
    fn label(&self) -> String {
        format!(
            "{}, {}{}",
            self.method.name(),
            self.which.label(),
            if self.adapt {
                ", adaptive"
            } else if self.uniform {
                ", uniform mesh"
            } else {
                ""
            }
        )
    }
}

const QUANTITIES: [(&str, &str); 3] = [
    ("first_yield", "first-yield load"),
    ("center", "centre displacement"),
    ("edge_pressure", "edge pressure"),
];

fn value(p: &Point, q: &str) -> f64 {
    match q {
        "first_yield" => p.first_yield_kn,
        "center" => p.center,
        _ => p.edge_pressure,
    }
}

/// The adaptive configuration's tolerance: below what its cycles reach, so
/// that it runs its `max_cycles` (8) and draws a line as long as the mesh
/// sequence's.
const ADAPT_TOLERANCE: &str = "1e-6";

/// One run of the study: (configuration index, refinement level (an adaptive
/// run's cycle), its point).
type Row = (usize, usize, Point);

/// Every configuration at each of its levels (configurations that cannot
/// run here skipped), with automatic steps: the load-step error (first order;
/// 0.8% of the settlement with 20 fixed steps) must not hide the mesh error.
fn run_levels(
    case: &Path,
    levels: &[usize],
    configs: &[Config],
    scratch: &Path,
) -> Result<Vec<Row>> {
    let mut rows: Vec<Row> = Vec::new();
    for (c, cfg) in configs.iter().enumerate() {
        if !cfg.which.available() {
            eprintln!(
                "study: skipping {} (needs the parallel build and mpirun)",
                cfg.label()
            );
            continue;
        }
        if cfg.adapt {
            let dir = scratch.join(format!("c{c}-adapt"));
            let args: Vec<String> = [
                "--adapt",
                ADAPT_TOLERANCE,
                "--method",
                cfg.method.name(),
                "--step-control",
                "auto",
            ]
            .iter()
            .map(|s| s.to_string())
            .collect();
            let points = runner::run_adaptive(case, &args, cfg.which, &dir)
                .map_err(|m| Error::Study(format!("{}: {m}", cfg.label())))?;
            for (k, p) in points.into_iter().enumerate() {
                eprintln!(
                    "study: {} cycle {}: {} dofs, {:.2} s so far",
                    cfg.label(),
                    k + 1,
                    p.dofs,
                    p.wall
                );
                rows.push((c, k + 1, p));
            }
            continue;
        }
        for &l in levels {
            if cfg.levels.as_ref().is_some_and(|v| !v.contains(&l)) {
                continue;
            }
            let mut args = vec![
                "--refine".to_string(),
                l.to_string(),
                "--method".into(),
                cfg.method.name().into(),
                "--step-control".into(),
                "auto".into(),
            ];
            if cfg.uniform {
                args.push("--uniform".into());
            }
            let dir = scratch.join(format!("c{c}-r{l}"));
            let p = runner::run(case, &args, cfg.which, &dir)
                .map_err(|m| Error::Study(format!("{} at refine {l}: {m}", cfg.label())))?;
            eprintln!(
                "study: {} refine {l}: {} dofs, {:.2} s",
                cfg.label(),
                p.dofs,
                p.wall
            );
            rows.push((c, l, p));
        }
    }
    Ok(rows)
}

/// Reference values, one per quantity: Richardson on the three finest levels
/// of the first configuration (its finest value when the sequence is not
/// monotone); with the Markdown table that reports them.
fn references(rows: &[Row]) -> (Vec<f64>, String) {
    let first: Vec<&Row> = rows.iter().filter(|r| r.0 == 0).collect();
    let n = first.len();
    let mut refs = Vec::new();
    let mut summary = String::from("| quantity | reference (Richardson) | observed order in h | finest level |\n|---|---:|---:|---:|\n");
    for (q, name) in QUANTITIES {
        let pick = |k: usize| first[n - 3 + k];
        let h = [
            1.0 / pick(0).1 as f64,
            1.0 / pick(1).1 as f64,
            1.0 / pick(2).1 as f64,
        ];
        let v = [
            value(&pick(0).2, q),
            value(&pick(1).2, q),
            value(&pick(2).2, q),
        ];
        let (qs, p) = richardson(h, v).unwrap_or((v[2], f64::NAN));
        let _ = writeln!(summary, "| {name} | {qs:.6} | {p:.2} | {:.6} |", v[2]);
        refs.push(qs);
    }
    (refs, summary)
}

/// refine-data.csv: a line per run, its values and relative errors.
fn write_data(out: &Path, rows: &[Row], configs: &[Config], refs: &[f64]) -> Result<PathBuf> {
    let mut csv = String::from("config,refine,dofs,wall_seconds,iterations,first_yield_kn,center_displacement_mm,edge_pressure_mpa,err_first_yield,err_center,err_edge\n");
    for (c, l, p) in rows {
        let e: Vec<f64> = QUANTITIES
            .iter()
            .zip(refs)
            .map(|((q, _), r)| ((value(p, q) - r) / r).abs())
            .collect();
        let _ = writeln!(
            csv,
            "\"{}\",{l},{},{:.4},{},{:.9},{:.9},{:.9},{:.3e},{:.3e},{:.3e}",
            configs[*c].label(),
            p.dofs,
            p.wall,
            p.iterations,
            p.first_yield_kn,
            p.center,
            p.edge_pressure,
            e[0],
            e[1],
            e[2]
        );
    }
    let data = out.join("refine-data.csv");
    std::fs::write(&data, csv).map_err(|e| Error::io(&data, e))?;
    Ok(data)
}

/// For each quantity, error against dofs and against wall time (log-log), a
/// series per configuration with two runs or more, labelled with its slope.
fn charts(
    out: &Path,
    rows: &[Row],
    configs: &[Config],
    refs: &[f64],
    pictures: bool,
) -> Result<Vec<PathBuf>> {
    let mut files = Vec::new();
    for ((q, name), r) in QUANTITIES.iter().zip(refs) {
        for (axis, label) in [("dofs", "log10 dofs"), ("time", "log10 wall time (s)")] {
            let mut series = Vec::new();
            for (c, cfg) in configs.iter().enumerate() {
                let pts: Vec<(f64, f64)> = rows
                    .iter()
                    .filter(|row| row.0 == c && value(&row.2, q).is_finite())
                    .map(|(_, _, p)| {
                        let x = if axis == "dofs" { p.dofs } else { p.wall };
                        (x.log10(), ((value(p, q) - r) / r).abs().max(1e-12).log10())
                    })
                    .collect();
                if pts.len() >= 2 {
                    series.push(Series {
                        label: format!("{} (slope {:.2})", cfg.label(), slope(&pts)),
                        points: pts,
                    });
                }
            }
            let chart = Chart {
                title: format!(
                    "{name}: error against {}",
                    if axis == "dofs" { "dofs" } else { "wall time" }
                ),
                x_label: label.into(),
                y_label: "log10 relative error".into(),
                series,
                legend_low: true,
                ..Chart::default()
            };
            files.extend(save(
                &chart,
                &out.join(format!("refine-{q}-{axis}")),
                pictures,
            )?);
        }
    }
    Ok(files)
}

/// Runs the study; returns the files written and a Markdown summary.
pub fn refine(
    case: &Path,
    levels: &[usize],
    configs: &[Config],
    out: &Path,
) -> Result<(Vec<PathBuf>, String)> {
    if levels.len() < 3 {
        return Err(Error::input(
            "--levels",
            "give at least three levels for Richardson extrapolation",
        ));
    }
    std::fs::create_dir_all(out).map_err(|e| Error::io(out, e))?;
    let scratch = out.join(format!(".runs/refine-{}", std::process::id()));
    let rows = run_levels(case, levels, configs, &scratch)?;
    let _ = std::fs::remove_dir_all(&scratch);
    // the parent too, when no other study is using it
    let _ = std::fs::remove_dir(out.join(".runs"));
    let (refs, summary) = references(&rows);
    // data and pictures
    let pictures = load_font();
    let mut files = vec![write_data(out, &rows, configs, &refs)?];
    files.extend(charts(out, &rows, configs, &refs, pictures)?);
    Ok((files, summary))
}

#[cfg(test)]
mod tests {
    #[test]
    fn richardson_recovers_order_and_limit_for_unequal_ratios() {
        let (q0, c, p): (f64, f64, f64) = (5.3, 2.0, 1.7);
        let h: [f64; 3] = [1.0 / 2.0, 1.0 / 3.0, 1.0 / 5.0];
        let q = h.map(|h| q0 + c * h.powf(p));
        let (qs, ps) = super::richardson(h, q).unwrap();
        assert!((qs - q0).abs() < 1e-9 && (ps - p).abs() < 1e-9, "{qs} {ps}");
        assert!(super::richardson(h, [1.0, 2.0, 1.5]).is_none());
    }
}
