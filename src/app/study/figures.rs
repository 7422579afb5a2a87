//! `asperity figures`: the paper's Figs 5, 6a/6b, 7a/7b/7c and 8 regenerated
//! from our runs of the shipped cases, with the paper's quoted numbers marked,
//! and the torque-twist loop of `cases/shrink-fit-combined` (docs/joints.md).

use crate::error::{Error, Result};
use crate::files::plot::{load_font, save, Chart, Series};
use crate::input::case::Case;
use crate::model::Model;
use crate::solve::{Increment, Measures, Observer, RunResult, State};
use std::path::{Path, PathBuf};

/// What is kept of every converged increment.
pub(crate) struct Snapshot {
    pub measures: Measures,
    /// (x, p_n, p_t) along the interface, ordered by x.
    pub interface: Vec<(f64, f64, f64)>,
    /// (x, u_y) along the top of the lower body ("<lower>.top"), ordered by x.
    pub surface: Vec<(f64, f64)>,
}

#[derive(Default)]
struct Capture(Vec<Snapshot>);

impl Observer for Capture {
    fn increment(&mut self, model: &Model, state: &State, inc: &Increment) -> Result<()> {
        let mut interface = Vec::new();
        let mut base = 0;
        for im in &model.interfaces {
            for (i, pr) in im.pairs.iter().enumerate() {
                let un = im.pair_approach_at(pr, &state.u, im.gap_at(state.time));
                let p_n = im.law.pressure(un).0;
                let p_t = if im.points.len() == im.pairs.len() {
                    state.contact[base + i].p_t
                } else {
                    0.0
                };
                interface.push((pr.x[0], p_n, p_t));
            }
            base += im.points.len();
        }
        interface.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut surface = Vec::new();
        if let Some(im) = model.interfaces.first() {
            let set = format!("{}.top", model.mesh.bodies[im.body_b]);
            if let Some(nodes) = model.mesh.node_sets.get(&set) {
                surface = nodes
                    .iter()
                    .map(|&n| (model.mesh.nodes[n][0], state.u[model.node_dofs().dof(n, 1)]))
                    .collect();
                surface.sort_by(|a, b| a.0.total_cmp(&b.0));
            }
        }
        self.0.push(Snapshot {
            measures: inc.measures,
            interface,
            surface,
        });
        Ok(())
    }
}

/// Runs a case (possibly modified) and keeps every increment.
pub(crate) fn capture(case: Case) -> Result<(RunResult, Vec<Snapshot>)> {
    let model = Model::build(case)?;
    let mut cap = Capture::default();
    let r = crate::app::driver::solve(&model, &mut cap)?;
    Ok((r, cap.0))
}

fn load(cases: &Path, name: &str) -> Result<Case> {
    Case::load(&cases.join(name))
}

/// Four increments spread over the run: a quarter, half, three quarters, all.
fn quarters(n: usize) -> Vec<usize> {
    (1..=4).map(|k| (k * n / 4).max(1) - 1).collect()
}

fn profile(
    snaps: &[Snapshot],
    pick: &[usize],
    value: impl Fn(&(f64, f64, f64)) -> f64,
) -> Vec<Series> {
    pick.iter()
        .map(|&i| Series {
            label: format!("P = {:.2} kN", snaps[i].measures.total_load_kn),
            points: snaps[i].interface.iter().map(|r| (r.0, value(r))).collect(),
        })
        .collect()
}

/// The first-yield load of a run (kN; NaN when it never yields).
fn first_yield(r: &RunResult) -> f64 {
    r.first_yield.as_ref().map_or(f64::NAN, |f| f.total_load_kn)
}

/// Load ratio (load over the first-yield load `f`) against the settlement of
/// the centre contact node, from the origin.
fn load_ratio_curve(snaps: &[Snapshot], f: f64) -> Vec<(f64, f64)> {
    std::iter::once((0.0, 0.0))
        .chain(snaps.iter().map(|s| {
            (
                -s.measures.center_displacement,
                s.measures.total_load_kn / f,
            )
        }))
        .collect()
}

/// Fig. 5: load ratio against the settlement of the centre contact node, plane
/// stress and plane strain.
fn fig5(
    out: &Path,
    stress: &(RunResult, Vec<Snapshot>),
    strain: &(RunResult, Vec<Snapshot>),
    pictures: bool,
) -> Result<Vec<PathBuf>> {
    let ((rs, ss), (re, se)) = (stress, strain);
    let fig5 = Chart {
        title: "Fig. 5: load ratio r against centre displacement".into(),
        x_label: "settlement of the centre contact node (mm)".into(),
        y_label: "r = load / first-yield load".into(),
        series: vec![
            Series {
                label: format!(
                    "plane stress (r = 1 at {:.2} kN; paper 7.17)",
                    first_yield(rs)
                ),
                points: load_ratio_curve(ss, first_yield(rs)),
            },
            Series {
                label: format!(
                    "plane strain (r = 1 at {:.2} kN; paper 9.75)",
                    first_yield(re)
                ),
                points: load_ratio_curve(se, first_yield(re)),
            },
        ],
        hlines: vec![
            (1.42, "paper: sharp bend at r = 1.42 (plane stress)".into()),
            (1.0, "first yield".into()),
        ],
        ..Chart::default()
    };
    save(&fig5, &out.join("fig5-load-displacement"), pictures)
}

/// Figs 6a and 6b: contact pressure at four stages, plane stress and plane strain.
fn fig6(out: &Path, ss: &[Snapshot], se: &[Snapshot], pictures: bool) -> Result<Vec<PathBuf>> {
    let mut files = Vec::new();
    for (tag, snaps, what) in [("6a", ss, "plane stress"), ("6b", se, "plane strain")] {
        let mut c = Chart {
            title: format!("Fig. {tag}: contact pressure, {what}"),
            x_label: "x (mm), punch edge at 20".into(),
            y_label: "p_N (MPa)".into(),
            series: profile(snaps, &quarters(snaps.len()), |r| r.1),
            ..Chart::default()
        };
        if tag == "6a" {
            c.hlines = vec![
                (240.0, "paper: mean pressure saturates near 240 MPa".into()),
                (226.3, "2 σ_Y/√3 = 226 MPa".into()),
            ];
        }
        files.extend(save(
            &c,
            &out.join(format!("fig{tag}-contact-pressure")),
            pictures,
        )?);
    }
    Ok(files)
}

/// Figs 7a-c: shear tractions of the three friction cases.
fn fig7(cases: &Path, out: &Path, pictures: bool) -> Result<Vec<PathBuf>> {
    let mut files = Vec::new();
    for (tag, name) in [
        ("7a", "punch-friction-a"),
        ("7b", "punch-friction-b"),
        ("7c", "punch-friction-c"),
    ] {
        let case = load(cases, name)?;
        let title = case.description.clone().unwrap_or_default();
        let (r, snaps) = capture(case)?;
        let c = Chart {
            title: format!(
                "Fig. {tag}: shear traction ({})",
                title.split(": ").last().unwrap_or("")
            ),
            x_label: "x (mm), punch edge at 20".into(),
            y_label: "p_T (MPa)".into(),
            series: profile(&snaps, &quarters(snaps.len()), |r| r.2),
            marks: vec![(
                6.0,
                0.0,
                format!(
                    "first yield {:.2} kN (paper 7.00 kN with, 7.17 without)",
                    first_yield(&r)
                ),
            )],
            legend_low: true,
            ..Chart::default()
        };
        files.extend(save(
            &c,
            &out.join(format!("fig{tag}-shear-traction")),
            pictures,
        )?);
    }
    Ok(files)
}

/// Fig. 8: surface deflection of the foundation at 10.35 kN against the
/// hardening modulus (plane stress, h = E/100 … E/10).
fn fig8(cases: &Path, out: &Path, pictures: bool) -> Result<Vec<PathBuf>> {
    let mut series = Vec::new();
    for k in [100.0, 50.0, 20.0, 10.0] {
        let mut case = load(cases, "punch-plane-stress")?;
        let e = case.materials["foundation"].young;
        if let Some(m) = case.materials.get_mut("foundation") {
            m.hardening = e / k;
        }
        case.load[0].pressure = 10350.0 / 40.0; // 10.35 kN on the 40 mm punch
        let (_, snaps) = capture(case)?;
        let last = snaps
            .last()
            .ok_or_else(|| Error::Study("no increment converged".into()))?;
        series.push(Series {
            label: format!("h = E/{k}"),
            points: last.surface.clone(),
        });
    }
    let c = Chart {
        title: "Fig. 8: foundation surface deflection at 10.35 kN against hardening".into(),
        x_label: "x (mm)".into(),
        y_label: "u_y (mm)".into(),
        series,
        vlines: vec![(20.0, "punch edge".into())],
        ..Chart::default()
    };
    save(&c, &out.join("fig8-deflection-hardening"), pictures)
}

/// The torque-twist loop of the shipped combined shrink fit (pushed, then
/// turned back and forth; docs/joints.md): the run's own torsion chart
/// ([`crate::files::output::joints_csv::torsion_chart`]).
fn torque_twist(cases: &Path, out: &Path, pictures: bool) -> Result<Vec<PathBuf>> {
    let model = Model::build(load(cases, "shrink-fit-combined")?)?;
    let r = crate::app::driver::solve(&model, &mut Capture::default())?;
    let cycles = r.cycles(&model);
    let chart = crate::files::output::joints_csv::torsion_chart(&model, &r, &cycles)
        .ok_or_else(|| Error::Study("shrink-fit-combined: no torque-twist cycle".into()))?;
    save(&chart, &out.join("torque-twist-loop"), pictures)
}

/// Writes every figure into `out`; returns the files written.
pub fn figures(cases: &Path, out: &Path) -> Result<Vec<PathBuf>> {
    std::fs::create_dir_all(out).map_err(|e| Error::io(out, e))?;
    let pictures = load_font();
    if !pictures {
        eprintln!("figures: no system font found (DejaVu Sans); writing the CSV data only");
    }
    let mut files = Vec::new();
    let stress = capture(load(cases, "punch-plane-stress")?)?;
    let strain = capture(load(cases, "punch-plane-strain")?)?;
    files.extend(fig5(out, &stress, &strain, pictures)?);
    files.extend(fig6(out, &stress.1, &strain.1, pictures)?);
    files.extend(fig7(cases, out, pictures)?);
    files.extend(fig8(cases, out, pictures)?);
    files.extend(torque_twist(cases, out, pictures)?);
    Ok(files)
}
