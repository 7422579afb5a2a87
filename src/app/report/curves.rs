//! Sections 3 and 4: the key curves of the run (curve.csv, joints.csv,
//! pretension.csv) and, per interface, the contact pressure and slip along
//! it at the last increment and its hysteresis loops, drawn as inline SVG by
//! the crate's charts ([`crate::files::plot`]).

use super::csv::Table;
use super::format::{figure, with_unit};
use super::html::{Cell, Page};
use super::read::Folder;
use super::{num, text};
use crate::error::Result;
use crate::files::plot::{self, Chart, Series};
use serde_json::Value;

/// Most points of a series drawn (a longer one is thinned evenly, its last
/// point kept).
const MOST_POINTS: usize = 2000;
/// Pixels of a chart.
const SIZE: (u32, u32) = (780, 440);

/// How charts are drawn: with a font to lay out their text, or not at all.
pub(super) struct Charts {
    pub font: bool,
}

impl Charts {
    /// Draws `chart` into the page with `caption`, or says why it cannot.
    pub fn draw(&self, page: &mut Page, chart: Chart, caption: &str) -> Result<()> {
        if !self.font {
            page.absent(&format!(
                "{}: not drawn, no system font (DejaVu Sans or Liberation Sans) to lay out a chart's text; the numbers are in the CSV files",
                chart.title
            ));
            return Ok(());
        }
        let mut chart = chart;
        let mut thinned = false;
        for s in &mut chart.series {
            thinned |= thin(&mut s.points);
        }
        let svg = plot::svg(&chart, SIZE)?;
        let svg = svg.trim_start_matches(|c: char| c != '<');
        let note = if thinned {
            format!("{caption} (series of more than {MOST_POINTS} points drawn through every k-th point)")
        } else {
            caption.to_string()
        };
        page.figure(svg, &note);
        Ok(())
    }
}

/// Keeps at most [`MOST_POINTS`] of `points`, evenly, the last one kept;
/// true when it dropped some.
fn thin(points: &mut Vec<(f64, f64)>) -> bool {
    if points.len() <= MOST_POINTS {
        return false;
    }
    let step = points.len().div_ceil(MOST_POINTS);
    let last = points[points.len() - 1];
    let mut kept: Vec<(f64, f64)> = points.iter().copied().step_by(step).collect();
    if kept.last() != Some(&last) {
        kept.push(last);
    }
    *points = kept;
    true
}

/// The points (x, y) of two columns of `t`, each scaled; rows where either
/// is not a finite number are left out.
fn points(t: &Table, x: &str, y: &str, scale: (f64, f64)) -> Result<Vec<(f64, f64)>> {
    let (xs, ys) = (t.numbers(x)?, t.numbers(y)?);
    Ok(xs
        .iter()
        .zip(&ys)
        .map(|(a, b)| (a * scale.0, b * scale.1))
        .filter(|p| p.0.is_finite() && p.1.is_finite())
        .collect())
}

fn series(label: &str, points: Vec<(f64, f64)>) -> Series {
    Series {
        label: label.to_string(),
        points,
    }
}

fn chart(title: &str, x: &str, y: &str, series: Vec<Series>) -> Chart {
    Chart {
        title: title.to_string(),
        x_label: x.to_string(),
        y_label: y.to_string(),
        series,
        ..Chart::default()
    }
}

/// Section 3: load against displacement, mean pressure and PEEQ against the
/// load factor (curve.csv), each interface's forces and torque against
/// time (joints.csv), the bolts' forces (pretension.csv).
pub(super) fn key_curves(page: &mut Page, f: &Folder, charts: &Charts) -> Result<()> {
    page.section("curves", "Key curves");
    match &f.curve {
        Some(t) => curve(page, t, charts)?,
        None => page.absent("curve.csv is absent: no load curve."),
    }
    match &f.joints {
        Some(t) if !t.rows.is_empty() => joint_forces(page, t, charts)?,
        Some(_) => page.absent("joints.csv has no rows: the model has no interface."),
        None => page.absent("joints.csv is absent: no interface forces."),
    }
    match &f.pretension {
        Some(t) => pretension(page, t, charts)?,
        None => page.absent("pretension.csv is absent: the case has no pretension section."),
    }
    Ok(())
}

/// The three charts of curve.csv.
fn curve(page: &mut Page, t: &Table, charts: &Charts) -> Result<()> {
    let loads = t.numbers("total_load_kn")?;
    let x = "u_y of the probe node (mm)";
    if loads.iter().any(|&v| v != 0.0 && v.is_finite()) {
        let p = points(t, "center_displacement_mm", "total_load_kn", (1.0, 1.0))?;
        let c = chart(
            "Load against displacement",
            x,
            "total load (kN)",
            vec![series("total load", p)],
        );
        charts.draw(page, c, "total_load_kn (the first interface's normal force) against center_displacement_mm (u_y of the probe node), curve.csv")?;
    } else {
        let p = points(t, "center_displacement_mm", "load_factor", (1.0, 1.0))?;
        let c = chart(
            "Load factor against displacement",
            x,
            "load factor",
            vec![series("load factor", p)],
        );
        charts.draw(page, c, "The model has no interface force (total_load_kn is 0): the load factor against u_y of the probe node, curve.csv")?;
    }
    if t.numbers("mean_pressure_mpa")?
        .iter()
        .any(|&v| v != 0.0 && v.is_finite())
    {
        let p = points(t, "load_factor", "mean_pressure_mpa", (1.0, 1.0))?;
        let c = chart(
            "Mean contact pressure",
            "load factor (pseudo-time)",
            "mean pressure (MPa)",
            vec![series("mean pressure", p)],
        );
        charts.draw(page, c, "mean_pressure_mpa: the first interface's normal force over its nominal area, curve.csv")?;
    }
    let p = points(t, "load_factor", "max_peeq", (1.0, 1.0))?;
    let c = chart(
        "Largest equivalent plastic strain",
        "load factor (pseudo-time)",
        "PEEQ",
        vec![series("max PEEQ", p)],
    );
    charts.draw(
        page,
        c,
        "max_peeq: the largest equivalent plastic strain of any Gauss point, curve.csv",
    )
}

/// Per interface: F_N and F_T against time (kN), and the torque (N·m) of
/// a model with twist.
fn joint_forces(page: &mut Page, t: &Table, charts: &Charts) -> Result<()> {
    for name in t.distinct("interface") {
        let rows = t.select("interface", &name);
        let n = points(&rows, "time", "normal_force_n", (1.0, 1e-3))?;
        let s = points(&rows, "time", "tangential_force_n", (1.0, 1e-3))?;
        let c = chart(
            &format!("Interface {name}: forces"),
            "time (load factor)",
            "force (kN)",
            vec![
                series("normal force F_N", n),
                series("tangential force F_T", s),
            ],
        );
        charts.draw(page, c, &format!("F_N (compressive positive) and F_T (joint convention) of interface {name}, joints.csv"))?;
        if rows.column("torque_nmm").is_some() {
            let m = points(&rows, "time", "torque_nmm", (1.0, 1e-3))?;
            let c = chart(
                &format!("Interface {name}: torque"),
                "time (load factor)",
                "torque (N·m)",
                vec![series("torque T", m)],
            );
            charts.draw(page, c, &format!("T, the torque about the axis that interface {name} resists (joint convention), joints.csv"))?;
        }
    }
    Ok(())
}

/// The bolt forces of pretension.csv against time (kN).
fn pretension(page: &mut Page, t: &Table, charts: &Charts) -> Result<()> {
    let mut lines = Vec::new();
    for col in t.columns.iter().filter(|c| c.ends_with("_force_n")) {
        let name = col.trim_end_matches("_force_n");
        lines.push(series(
            &format!("section {name}"),
            points(t, "load_factor", col, (1.0, 1e-3))?,
        ));
    }
    if lines.is_empty() {
        page.absent("pretension.csv lists no section.");
        return Ok(());
    }
    let c = chart(
        "Bolt force",
        "time (load factor)",
        "force across the section (kN)",
        lines,
    );
    charts.draw(
        page,
        c,
        "The force across each pretension section, tension positive, pretension.csv",
    )
}

/// Section 4: per interface, pressure and slip along it at the last
/// increment, and its hysteresis loops.
pub(super) fn interfaces(page: &mut Page, f: &Folder, charts: &Charts) -> Result<()> {
    page.section("interfaces", "Interfaces");
    let names = interface_names(f);
    if names.is_empty() {
        page.absent(
            "The model has no interface (summary.json joints and the interface files list none).",
        );
        return Ok(());
    }
    for name in names {
        page.heading(&format!("Interface {name}"));
        contact_line(page, &f.summary, &name);
        match &f.interface {
            Some((rel, t)) => along(page, rel, &t.select("interface", &name), &name, charts)?,
            None => {
                page.absent("The last increment's interface file (interface/NNNN.csv) is absent.")
            }
        }
        loops(page, f, &name, charts)?;
    }
    Ok(())
}

/// The interfaces' names: summary.json's joints, else the files'.
fn interface_names(f: &Folder) -> Vec<String> {
    let from_summary: Vec<String> = f
        .summary
        .get("joints")
        .and_then(Value::as_array)
        .map(|a| a.iter().filter_map(|j| text(j, "interface")).collect())
        .unwrap_or_default();
    if !from_summary.is_empty() {
        return from_summary;
    }
    let from = |t: &Option<Table>| {
        t.as_ref()
            .map(|t| t.distinct("interface"))
            .unwrap_or_default()
    };
    let joints = from(&f.joints);
    if joints.is_empty() {
        f.interface
            .as_ref()
            .map(|t| t.1.distinct("interface"))
            .unwrap_or_default()
    } else {
        joints
    }
}

/// The interface's largest pressure and final contact extent (summary.json
/// `contact`), in a sentence.
fn contact_line(page: &mut Page, s: &Value, name: &str) {
    let entry = s.get("contact").and_then(Value::as_array).and_then(|a| {
        a.iter()
            .find(|c| text(c, "interface").as_deref() == Some(name))
    });
    let Some(c) = entry else {
        page.absent("summary.json has no contact entry for this interface.");
        return;
    };
    let peak = c.get("max_pressure").filter(|v| v.is_object()).map_or(
        "never in contact".to_string(),
        |m| {
            format!(
                "largest contact pressure {} at s = {}, (x, y) = {} mm, increment {}",
                with_unit(num(m, "value_mpa").unwrap_or(f64::NAN), "MPa"),
                with_unit(num(m, "s_mm").unwrap_or(f64::NAN), "mm"),
                super::results::place(m),
                num(m, "increment").map_or("—".into(), figure)
            )
        },
    );
    let extent = c.get("final_extent").filter(|v| v.is_object()).map_or(
        "nothing in contact at the end".to_string(),
        |e| {
            format!(
                "in contact at the end from s = {} to s = {}",
                with_unit(num(e, "from_s_mm").unwrap_or(f64::NAN), "mm"),
                with_unit(num(e, "to_s_mm").unwrap_or(f64::NAN), "mm")
            )
        },
    );
    page.text(&format!("{}; {}.", capitalised(&peak), extent));
}

fn capitalised(s: &str) -> String {
    let mut c = s.chars();
    c.next()
        .map_or(String::new(), |f| f.to_uppercase().chain(c).collect())
}

/// Pressure and slip against the arc length s at the last increment.
fn along(page: &mut Page, rel: &str, t: &Table, name: &str, charts: &Charts) -> Result<()> {
    if t.rows.is_empty() {
        page.absent(&format!("{rel} has no row for this interface."));
        return Ok(());
    }
    let p = points(t, "s_mm", "p_n_mpa", (1.0, 1.0))?;
    let c = chart(
        &format!("Interface {name}: contact pressure"),
        "s along the interface (mm)",
        "p_N (MPa)",
        vec![series("contact pressure", p)],
    );
    charts.draw(
        page,
        c,
        &format!("The contact pressure along interface {name} at the last increment, {rel}"),
    )?;
    let k = t.column("tangential_status");
    let tangential = t
        .rows
        .iter()
        .any(|(_, r)| k.is_some_and(|k| r[k] != "none"));
    if !tangential {
        page.absent(
            "No tangential law on this interface (or consistent weights): no slip to draw.",
        );
        return Ok(());
    }
    let mut lines = vec![series("u_T", points(t, "s_mm", "u_t_mm", (1.0, 1.0))?)];
    if t.column("u_t_theta_mm").is_some() {
        lines.push(series(
            "u_Tθ (circumferential)",
            points(t, "s_mm", "u_t_theta_mm", (1.0, 1.0))?,
        ));
    }
    let c = chart(
        &format!("Interface {name}: slip"),
        "s along the interface (mm)",
        "slip (mm)",
        lines,
    );
    charts.draw(page, c, &format!("The slip along interface {name} at the last increment (internal convention: B's displacement relative to A along t), {rel}"))
}

/// The hysteresis loops of an interface with closed cycles: F_T against
/// ū_T over the whole run (joints.csv) with the backbone (backbone.csv),
/// and the table of its cycles (cycles.csv).
fn loops(page: &mut Page, f: &Folder, name: &str, charts: &Charts) -> Result<()> {
    let Some(cycles) = &f.cycles else {
        page.absent("cycles.csv is absent: no load cycles.");
        return Ok(());
    };
    let mine = cycles.select("interface", name);
    if mine.rows.is_empty() {
        page.absent("No closed load cycle on this interface.");
        return Ok(());
    }
    let mut lines = Vec::new();
    if let Some(j) = &f.joints {
        let rows = j.select("interface", name);
        let mut p = points(&rows, "mean_slip_mm", "tangential_force_n", (1.0, 1.0))?;
        p.insert(0, (0.0, 0.0));
        lines.push(series("F_T against ū_T", p));
    }
    if let Some(b) = &f.backbone {
        lines.push(series(
            "backbone (first loading)",
            points(
                &b.select("interface", name),
                "mean_slip_mm",
                "tangential_force_n",
                (1.0, 1.0),
            )?,
        ));
    }
    let c = chart(
        &format!("Interface {name}: hysteresis"),
        "ū_T, mean slip of A relative to B (mm)",
        "F_T (N)",
        lines,
    );
    charts.draw(page, c, "The tangential force against the mean slip over every increment from the origin (joint convention), joints.csv and backbone.csv")?;
    cycle_table(page, &mine)
}

/// One row per closed cycle: times, amplitudes, dissipation, loss factor,
/// secant stiffness.
fn cycle_table(page: &mut Page, t: &Table) -> Result<()> {
    let cols = [
        "cycle",
        "start_time",
        "end_time",
        "force_amplitude_n",
        "slip_amplitude_mm",
        "dissipation_nmm",
        "loss_factor",
        "secant_stiffness_n_per_mm",
    ];
    let mut rows = Vec::new();
    for (line, r) in &t.rows {
        let mut row = Vec::new();
        for c in cols {
            let v = t
                .column(c)
                .map_or(Ok(f64::NAN), |k| t.number(*line, c, &r[k]))?;
            row.push(Cell::n(figure(v)));
        }
        rows.push(row);
    }
    let head = [
        "cycle",
        "from t",
        "to t",
        "F_a (N)",
        "u_a (mm)",
        "D (N·mm)",
        "loss factor η",
        "secant stiffness (N/mm)",
    ];
    page.table("Closed load cycles (cycles.csv)", &head, rows);
    Ok(())
}
