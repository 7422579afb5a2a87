//! The joint outputs of a run ([`crate::measure::joint`]): `joints.csv`
//! (per increment and interface), `cycles.csv` (per closed load cycle and
//! interface), the `joints` entry of `summary.json`, the hysteresis
//! figure (tangential force against slip) of a run with a cycle and, with
//! twist, the torque-twist figure.

use crate::error::Result;
use crate::measure::joint::{Cycle, JointMeasures};
use crate::model::Model;
use crate::solve::RunResult;
use serde_json::{json, Value};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// A CSV field: as is, or quoted (quotes doubled) when it holds a comma, a
/// quote or a line break.
pub(crate) fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// `mm` for plane models (lengths of interface), `mm2` in axisymmetry and
/// in 3D (areas).
fn measure_unit(model: &Model) -> &'static str {
    if model.section.axisymmetric || model.mesh.dim() == 3 {
        "mm2"
    } else {
        "mm"
    }
}

pub const JOINTS_HEADER: &str = "increment,time,interface,normal_force_n,tangential_force_n,mean_approach_mm,mean_slip_mm,open_measure,closed_measure,stick_measure,micro_slip_measure,macro_slip_measure,dissipation_nmm,work_nmm\n";

/// The columns a twisting model's `joints.csv` adds at the end of a row.
pub const JOINTS_TWIST_COLUMNS: &str = ",torque_nmm,mean_hoop_slip_mm,mean_twist_rad";

/// The columns a 3D model's `joints.csv` adds at the end of a row.
pub const JOINTS_SPACE_COLUMNS: &str = ",tangential_force_2_n,mean_slip_2_mm,force_x_n,force_y_n,force_z_n,moment_x_nmm,moment_y_nmm,moment_z_nmm";

/// The columns a cyclic sector's `joints.csv` adds at the end of a row:
/// the whole part's numbers ([`JointMeasures::part`]).
pub const JOINTS_CYCLIC_COLUMNS: &str = ",part_normal_force_n,part_axial_force_n,part_torque_nmm,part_contact_measure,part_dissipation_nmm";

/// `joints.csv`: one row per committed increment and interface.
/// A twisting model's rows end with T, ū_θ and φ̄ ([`JOINTS_TWIST_COLUMNS`]),
/// a 3D model's with F_T2, ū_T2 and the force and moment on A
/// ([`JOINTS_SPACE_COLUMNS`]), a cyclic sector's then with the whole
/// part's numbers ([`JOINTS_CYCLIC_COLUMNS`]).
pub fn joints_csv(model: &Model, r: &RunResult) -> String {
    let twist = model.node_dofs().twist();
    let space = model.node_dofs().solid();
    let sectors = model.cyclic_sectors();
    let mut s = String::from(JOINTS_HEADER);
    for (on, columns) in [
        (twist, JOINTS_TWIST_COLUMNS),
        (space, JOINTS_SPACE_COLUMNS),
        (sectors.is_some(), JOINTS_CYCLIC_COLUMNS),
    ] {
        if on {
            s.pop();
            s += columns;
            s.push('\n');
        }
    }
    for inc in &r.increments {
        for (im, m) in model.interfaces.iter().zip(&inc.joints) {
            let mut values = m.pack().to_vec();
            if twist {
                values.extend(m.pack_twist());
            }
            if space {
                values.extend(m.pack_space());
            }
            if let Some(n) = sectors {
                values.extend(m.part(n, im.moment_point));
            }
            let _ = writeln!(
                s,
                "{},{:.9},{},{}",
                inc.increment,
                inc.load_factor,
                csv_field(&im.name),
                values
                    .iter()
                    .map(|v| format!("{v:.9e}"))
                    .collect::<Vec<_>>()
                    .join(",")
            );
        }
    }
    s
}

pub const CYCLES_HEADER: &str = "interface,cycle,start_increment,end_increment,start_time,end_time,dissipation_nmm,work_nmm,secant_stiffness_n_per_mm,force_min_n,force_max_n,slip_min_mm,slip_max_mm,force_amplitude_n,slip_amplitude_mm,stored_energy_nmm,loss_factor\n";

/// The columns a twisting model's `cycles.csv` adds at the end of a row.
pub const CYCLES_TWIST_COLUMNS: &str =
    ",torque_min_nmm,torque_max_nmm,twist_min_rad,twist_max_rad,torsional_stiffness_nmm_per_rad,torque_amplitude_nmm,twist_amplitude_rad,torsional_stored_energy_nmm,torsional_loss_factor";

/// `cycles.csv`: one row per closed load cycle and interface (the header
/// alone when there is none); an empty stiffness where it is undefined and
/// an empty loss factor where the stored energy is not positive. The
/// amplitude, stored energy and loss factor ([`Cycle::loss_factor`]) were
/// added at the end of the row: readers of the older columns keep working.
/// A twisting model's rows end with the torque-twist loop
/// ([`CYCLES_TWIST_COLUMNS`]): its ranges, torsional secant stiffness,
/// amplitudes, stored energy and torsional loss factor
/// ([`Cycle::torsional_loss_factor`]).
pub fn cycles_csv(model: &Model, cycles: &[Vec<Cycle>]) -> String {
    let twist = model.node_dofs().twist();
    let mut s = String::from(CYCLES_HEADER);
    if twist {
        s.pop();
        s += CYCLES_TWIST_COLUMNS;
        s.push('\n');
    }
    for (im, list) in model.interfaces.iter().zip(cycles) {
        for (k, c) in list.iter().enumerate() {
            let _ = write!(
                s,
                "{},{},{},{},{:.9},{:.9},{:.9e},{:.9e},{},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{}",
                csv_field(&im.name),
                k + 1,
                c.start_increment,
                c.end_increment,
                c.start_time,
                c.end_time,
                c.dissipation,
                c.work,
                opt(c.secant_stiffness),
                c.force_range[0],
                c.force_range[1],
                c.slip_range[0],
                c.slip_range[1],
                c.force_amplitude(),
                c.slip_amplitude(),
                c.stored_energy(),
                opt(c.loss_factor()),
            );
            if twist {
                let _ = write!(
                    s,
                    ",{:.9e},{:.9e},{:.9e},{:.9e},{},{:.9e},{:.9e},{:.9e},{}",
                    c.torque_range[0],
                    c.torque_range[1],
                    c.twist_range[0],
                    c.twist_range[1],
                    opt(c.torsional_stiffness),
                    c.torque_amplitude(),
                    c.twist_amplitude(),
                    c.torsional_stored_energy(),
                    opt(c.torsional_loss_factor()),
                );
            }
            s.push('\n');
        }
    }
    s
}

/// A CSV number (`{:.9e}`), or an empty field for None.
pub(crate) fn opt(v: Option<f64>) -> String {
    v.map_or(String::new(), |v| format!("{v:.9e}"))
}

/// One cycle as a `summary.json` object (the keys of `cycles.csv`; with
/// twist its torque-twist loop too).
pub fn cycle_json(number: usize, c: &Cycle, twist: bool) -> Value {
    let mut v = json!({
        "cycle": number,
        "start_increment": c.start_increment,
        "end_increment": c.end_increment,
        "start_time": c.start_time,
        "end_time": c.end_time,
        "dissipation_nmm": c.dissipation,
        "work_nmm": c.work,
        "secant_stiffness_n_per_mm": c.secant_stiffness,
        "force_min_n": c.force_range[0],
        "force_max_n": c.force_range[1],
        "slip_min_mm": c.slip_range[0],
        "slip_max_mm": c.slip_range[1],
        "force_amplitude_n": c.force_amplitude(),
        "slip_amplitude_mm": c.slip_amplitude(),
        "stored_energy_nmm": c.stored_energy(),
        "loss_factor": c.loss_factor(),
    });
    if twist {
        v["torque_min_nmm"] = json!(c.torque_range[0]);
        v["torque_max_nmm"] = json!(c.torque_range[1]);
        v["twist_min_rad"] = json!(c.twist_range[0]);
        v["twist_max_rad"] = json!(c.twist_range[1]);
        v["torsional_stiffness_nmm_per_rad"] = json!(c.torsional_stiffness);
        v["torque_amplitude_nmm"] = json!(c.torque_amplitude());
        v["twist_amplitude_rad"] = json!(c.twist_amplitude());
        v["torsional_stored_energy_nmm"] = json!(c.torsional_stored_energy());
        v["torsional_loss_factor"] = json!(c.torsional_loss_factor());
    }
    v
}

/// The joint measures of one increment as a `summary.json` object (with
/// twist, the torque, circumferential slip and twist too).
fn measures_json(time: f64, m: &JointMeasures, twist: bool, space: bool) -> Value {
    let mut v = json!({
        "time": time,
        "normal_force_n": m.normal_force,
        "tangential_force_n": m.tangential_force,
        "mean_approach_mm": m.mean_approach,
        "mean_slip_mm": m.mean_slip,
        "open_measure": m.open,
        "closed_measure": m.closed,
        "stick_measure": m.stick,
        "micro_slip_measure": m.micro_slip,
        "macro_slip_measure": m.macro_slip,
        "dissipation_nmm": m.dissipation,
        "work_nmm": m.work,
    });
    if twist {
        v["torque_nmm"] = json!(m.torque);
        v["mean_hoop_slip_mm"] = json!(m.hoop_slip);
        v["mean_twist_rad"] = json!(m.twist);
    }
    if space {
        v["tangential_force_2_n"] = json!(m.tangential_force_2);
        v["mean_slip_2_mm"] = json!(m.mean_slip_2);
        v["force_n"] = json!(m.force);
        v["moment_nmm"] = json!(m.moment);
    }
    v
}

/// The `joints` entry of `summary.json`: per interface its bodies, joint
/// direction, the last increment's measures and the closed cycles.
pub fn summary(model: &Model, r: &RunResult, cycles: &[Vec<Cycle>]) -> Value {
    let last = r.increments.last();
    let list: Vec<Value> = model
        .interfaces
        .iter()
        .enumerate()
        .map(|(k, im)| {
            let fin = last
                .and_then(|i| {
                    let m = i.joints.get(k)?;
                    let space = im.node_dofs.solid();
                    let mut v = measures_json(i.load_factor, m, im.twist(), space);
                    if let Some(n) = model.cyclic_sectors() {
                        let p = m.part(n, im.moment_point);
                        v["part"] = json!({
                            "sectors": n,
                            "normal_force_n": p[0],
                            "axial_force_n": p[1],
                            "torque_nmm": p[2],
                            "contact_measure": p[3],
                            "dissipation_nmm": p[4],
                        });
                    }
                    Some(v)
                })
                .unwrap_or(Value::Null);
            let cyc: Vec<Value> = cycles
                .get(k)
                .map(|l| {
                    l.iter()
                        .enumerate()
                        .map(|(n, c)| cycle_json(n + 1, c, im.twist()))
                        .collect()
                })
                .unwrap_or_default();
            let mut v = json!({
                "interface": im.name,
                "body_a": model.mesh.bodies[im.body_a],
                "body_b": model.mesh.bodies[im.body_b],
                "direction": crate::model::interface::arcs::direction(im),
                "measure_unit": measure_unit(model),
                "final": fin,
                "cycles": cyc,
            });
            if im.node_dofs.solid() {
                // the slip frame of the first pair: F_T and ū_T along t₁,
                // F_T2 and ū_T2 along t₂
                let n = im.pairs.first().map_or([0.0, 1.0, 0.0], |p| p.normal);
                let [t1, t2] = crate::model::interface::tangents(n);
                v["direction"] = json!(t1.map(|c| c + 0.0));
                v["direction_2"] = json!(t2.map(|c| c + 0.0));
                v["moment_point_mm"] = json!(im.moment_point);
            }
            v
        })
        .collect();
    Value::Array(list)
}

/// The hysteresis figure `hysteresis.svg` / `.png` (with the points in
/// `hysteresis.csv`) in `dir`: F_T against ū_T from the start of the run, one
/// line per interface with a closed cycle. Nothing when no interface has a
/// cycle; the CSV alone when no font is found.
pub fn hysteresis(
    model: &Model,
    r: &RunResult,
    cycles: &[Vec<Cycle>],
    dir: &Path,
) -> Result<Vec<PathBuf>> {
    use crate::files::plot::{load_font, save, Chart};
    let series = loop_series(
        model,
        r,
        cycles,
        |_| String::new(),
        |m| (m.mean_slip, m.tangential_force),
    );
    if series.is_empty() {
        return Ok(Vec::new());
    }
    let chart = Chart {
        title: format!("{}: tangential force against slip", model.name),
        x_label: "ū_T: mean slip of A relative to B along t (mm)".into(),
        y_label: "F_T: tangential force dragging A along t (N)".into(),
        series,
        ..Chart::default()
    };
    save(&chart, &dir.join("hysteresis"), load_font())
}

/// One line per interface with a closed cycle, from the origin through
/// every increment's `point` of the joint measures, labelled with the
/// interface, its cycle count and `extra` of its cycles.
fn loop_series(
    model: &Model,
    r: &RunResult,
    cycles: &[Vec<Cycle>],
    extra: impl Fn(&[Cycle]) -> String,
    point: impl Fn(&JointMeasures) -> (f64, f64),
) -> Vec<crate::files::plot::Series> {
    model
        .interfaces
        .iter()
        .enumerate()
        .filter(|(k, _)| cycles.get(*k).is_some_and(|c| !c.is_empty()))
        .map(|(k, im)| {
            let c = &cycles[k];
            crate::files::plot::Series {
                label: format!(
                    "{} ({} closed cycle{}{})",
                    im.name,
                    c.len(),
                    if c.len() == 1 { "" } else { "s" },
                    extra(c)
                ),
                points: std::iter::once((0.0, 0.0))
                    .chain(
                        r.increments
                            .iter()
                            .filter_map(|i| i.joints.get(k).map(&point)),
                    )
                    .collect(),
            }
        })
        .collect()
}

/// The torque-twist chart of a twisting run: T (kN·mm) against φ̄ (mrad)
/// from the start of the run, one line per interface with a closed cycle.
/// None without twist or without a cycle.
pub(crate) fn torsion_chart(
    model: &Model,
    r: &RunResult,
    cycles: &[Vec<Cycle>],
) -> Option<crate::files::plot::Chart> {
    use crate::files::plot::Chart;
    if !model.node_dofs().twist() {
        return None;
    }
    let series = loop_series(
        model,
        r,
        cycles,
        |c| {
            c.last()
                .and_then(Cycle::torsional_loss_factor)
                .map_or(String::new(), |e| format!(", last η_θ = {e:.3}"))
        },
        |m| (1e3 * m.twist, 1e-3 * m.torque),
    );
    (!series.is_empty()).then(|| Chart {
        title: format!("{}: torque against twist", model.name),
        x_label: "φ̄: mean twist of A relative to B at the interface (mrad)".into(),
        y_label: "T: torque on A the joint resists (kN·mm)".into(),
        series,
        ..Chart::default()
    })
}

/// The torque-twist figure `torsion.svg` / `.png` (with the points in
/// `torsion.csv`) in `dir`: `torsion_chart`. Nothing without twist or
/// without a closed cycle; the CSV alone when no font is found.
pub fn torsion(
    model: &Model,
    r: &RunResult,
    cycles: &[Vec<Cycle>],
    dir: &Path,
) -> Result<Vec<PathBuf>> {
    use crate::files::plot::{load_font, save};
    match torsion_chart(model, r, cycles) {
        Some(chart) => save(&chart, &dir.join("torsion"), load_font()),
        None => Ok(Vec::new()),
    }
}
