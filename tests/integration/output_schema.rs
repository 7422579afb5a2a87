//! `summary.json` matches its documented schema (docs/output.md): every key
//! written is documented with its type, every documented key is written.

use crate::common;
use serde_json::Value;
use std::collections::BTreeMap;

/// key → type from the summary table of docs/output.md.
fn documented() -> BTreeMap<String, String> {
    let doc = std::fs::read_to_string(common::root().join("docs/output.md")).unwrap();
    let section = doc
        .split("## `summary.json`")
        .nth(1)
        .unwrap()
        .split("\n## ")
        .next()
        .unwrap();
    section
        .lines()
        .filter(|l| l.starts_with("| `"))
        .map(|l| {
            let cells: Vec<&str> = l.split('|').map(str::trim).collect();
            (cells[1].trim_matches('`').to_string(), cells[2].to_string())
        })
        .collect()
}

fn type_of(v: &Value) -> &'static str {
    match v {
        Value::Null => "null",
        Value::Bool(_) => "boolean",
        Value::Number(n) if n.is_u64() || n.is_i64() => "integer",
        Value::Number(_) => "number",
        Value::String(_) => "string",
        Value::Array(_) => "array",
        Value::Object(_) => "object",
    }
}

/// Every key path of the summary with its JSON type; object members of
/// `backend_stats` are reported as `backend_stats.*`, the members of objects
/// in an array `a` as `a[].member`.
fn leaves(prefix: &str, v: &Value, out: &mut Vec<(String, &'static str)>) {
    if let Value::Array(items) = v {
        for x in items {
            leaves(&format!("{prefix}[]"), x, out);
        }
    }
    if let Value::Object(m) = v {
        for (k, x) in m {
            let key = if prefix == "backend_stats" {
                "backend_stats.*".to_string()
            } else if prefix.is_empty() {
                k.clone()
            } else {
                format!("{prefix}.{k}")
            };
            out.push((key.clone(), type_of(x)));
            leaves(&key, x, out);
        }
    }
}

fn summary_of(tag: &str, case: &std::path::Path, extra: &[&str]) -> Value {
    let out = common::scratch(&format!("schema-{tag}")).join("out");
    let st = std::process::Command::new(env!("CARGO_BIN_EXE_asperity"))
        .arg("run")
        .arg(case)
        .args(extra)
        .arg("--quiet")
        .arg("--out")
        .arg(&out)
        .status()
        .unwrap();
    assert!(st.success());
    serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap()
}

fn allowed(doc: &str, actual: &str) -> bool {
    doc.split(" or ")
        .any(|t| t == actual || (t == "number" && actual == "integer"))
}

#[test]
fn summary_json_matches_the_documented_schema() {
    let doc = documented();
    assert!(doc.len() > 30, "the table was not found: {doc:?}");
    // with first yield (punch) and without (friction case at a fifth of the load)
    let cases = common::root().join("cases");
    let with = summary_of("yield", &cases.join("punch-plane-stress"), &[]);
    let dir = common::scratch("schema-elastic-case");
    let text = std::fs::read_to_string(cases.join("punch-friction-a/case.toml")).unwrap();
    let text = text.replace("pressure = 250.0", "pressure = 50.0");
    assert!(text.contains("pressure = 50.0"));
    std::fs::write(dir.join("case.toml"), text).unwrap();
    let without = summary_of("elastic", &dir, &["--increments", "2"]);
    assert!(without["first_yield"].is_null(), "{without}");
    // curve.csv: load_ratio is 0 in every row of a run that never yields
    // (docs/output.md), a number below 1 before the first yield otherwise
    for (tag, never) in [("elastic", true), ("yield", false)] {
        let csv = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
            .join(format!("schema-{tag}"))
            .join("out/curve.csv");
        let csv = std::fs::read_to_string(csv).unwrap();
        let ratios: Vec<f64> = csv
            .lines()
            .skip(1)
            .map(|l| l.split(',').nth(4).unwrap().parse().unwrap())
            .collect();
        assert!(!ratios.is_empty(), "{csv}");
        for r in &ratios {
            assert!(r.is_finite() && (!never || *r == 0.0), "{tag}: {csv}");
        }
        if !never {
            assert!(
                ratios[0] > 0.0 && ratios[0] < 1.0 && ratios.last() > Some(&1.0),
                "{csv}"
            );
        }
    }
    // a gap closed under force control: the stabilization's report
    let gap = summary_of("gap", &cases.join("punch-gap"), &[]);
    assert!(gap["stabilization"].is_object(), "{gap}");
    assert!(with.get("stabilization").is_none(), "{with}");
    // axisymmetric: the full-revolution statement
    let axi = common::root().join("tests/data/axisymmetric-punch");
    let axi = summary_of("axisymmetric", &axi, &[]);
    assert!(
        axi["forces"].is_string() && with.get("forces").is_none(),
        "{axi}"
    );
    // tabulated laws, both used far beyond their last rows (20 MPa under
    // 250 MPa): the `tables` array and the `warnings`
    let text = std::fs::read_to_string(cases.join("punch-friction-a/case.toml")).unwrap();
    let tabulated = text
        .replace(
            "law = \"power\"\nc_n = 0.001          # mm/MPa^m: 14 µm of approach at 200 MPa\nm = 0.5",
            "law = \"table\"\ntable = [[0.002236, 5.0], [0.003162, 10.0], [0.004472, 20.0]]",
        )
        .replace(
            "r = 0.9              # k_T^e = p_N^S / R in MPa/um\ns = 0.5",
            "k_table = [[5.0, 2.485], [10.0, 3.514], [20.0, 4.969]]",
        );
    assert!(tabulated.contains("table = [[") && tabulated.contains("k_table"));
    let dir = common::scratch("schema-tables-case");
    std::fs::write(dir.join("case.toml"), tabulated).unwrap();
    let tab = summary_of("tables", &dir, &["--increments", "2"]);
    let uses = tab["tables"].as_array().unwrap();
    assert_eq!(uses.len(), 2, "{tab}");
    assert!(uses.iter().all(|t| t["beyond_limit"] == true), "{tab}");
    assert_eq!(tab["warnings"].as_array().unwrap().len(), 2, "{tab}");
    assert!(with.get("tables").is_none() && with.get("warnings").is_none());
    let mut seen = std::collections::BTreeSet::new();
    let mut errors = Vec::new();
    // a closed load cycle needs a load history: the summary's cycle object
    // from a synthetic cycle (src/files/output/joints_csv.rs writes it the same way)
    let cycle = asperity::files::output::joints_csv::cycle_json(
        1,
        &asperity::measure::joint::Cycle {
            start_increment: 2,
            end_increment: 9,
            start_time: 1.0,
            end_time: 4.0,
            dissipation: 0.5,
            work: 0.5,
            secant_stiffness: Some(1e4),
            force_range: [-30.0, 30.0],
            slip_range: [-0.01, 0.01],
            tip_slip: [-0.008, 0.01],
            force_scale: 0.0,
            floor: 0.0,
            torque_range: [-5e5, 5e5],
            twist_range: [-1e-3, 1e-3],
            torsional_stiffness: Some(5e8),
            tip_twist: [-8e-4, 1e-3],
        },
        // with twist: the torque-twist loop's keys too
        true,
    );
    // probes of both kinds, interface events with histories and reactions
    let stack = summary_of(
        "stack",
        &common::root().join("tests/data/stack-separation"),
        &[],
    );
    assert_eq!(stack["probes"].as_array().unwrap().len(), 5, "{stack}");
    assert_eq!(stack["events"].as_array().unwrap().len(), 2, "{stack}");
    // a pretension section (the bolted joint): its account in `pretension`
    let bolt = summary_of("bolted-joint", &cases.join("bolted-joint"), &[]);
    assert_eq!(bolt["pretension"].as_array().unwrap().len(), 1, "{bolt}");
    assert!(with.get("pretension").is_none(), "{with}");
    let mut with_cycle = with.clone();
    with_cycle["joints"][0]["cycles"] = Value::Array(vec![cycle]);
    // a fitted sweep (src/files/output/damping.rs writes it the same way)
    let sweep_of = |f: f64, d: f64| asperity::measure::joint::Cycle {
        start_increment: 1,
        end_increment: 2,
        start_time: 1.0,
        end_time: 2.0,
        dissipation: d,
        work: d,
        secant_stiffness: Some(1e4),
        force_range: [-f, f],
        slip_range: [-f / 1e4, f / 1e4],
        tip_slip: [-f / 1e4, f / 1e4],
        force_scale: 0.0,
        floor: 0.0,
        torque_range: [0.0; 2],
        twist_range: [0.0; 2],
        torsional_stiffness: None,
        tip_twist: [0.0; 2],
    };
    let sweep = asperity::measure::sweep::sweep(&[sweep_of(10.0, 0.1), sweep_of(20.0, 0.6)]);
    assert!(sweep.fit.is_some());
    with_cycle["damping"][0] = asperity::files::output::damping::fit_json("contact", &sweep);
    // twist: the torque, circumferential slip and twist of a joint
    let torque = summary_of("torque", &cases.join("shrink-fit-torque"), &[]);
    // twist with a [[probe]]: u_θ as its third value
    let face = summary_of("face", &cases.join("face-coupling-torque"), &[]);
    assert_eq!(face["probes"][0]["max_mm"].as_array().unwrap().len(), 3);
    // a joint-cycles rating: each check names its cycle
    let slide = summary_of("slide", &cases.join("slideway-cycles"), &[]);
    assert_eq!(slide["ratings"][0]["checks"][0]["cycle"], 1, "{slide}");
    // 3D: z beside x and y (first yield, events, peaks), u_z of a probe
    let solid = summary_of("solid", &cases.join("block-3d"), &[]);
    assert!(solid["first_yield"]["z_mm"].as_f64().is_some(), "{solid}");
    // no interface: no interface force at first yield, the applied force in space
    assert!(solid["first_yield"]["total_load_kn"].is_null(), "{solid}");
    let fy_event = solid["events"]
        .as_array()
        .unwrap()
        .iter()
        .find(|e| e["event"] == "first_yield")
        .unwrap();
    let applied = fy_event["applied_force_n"].as_array().unwrap();
    assert_eq!(applied.len(), 3);
    // the pressed square's 600 MPa × 8 × 8 mm, downwards, times the load factor
    let lambda = fy_event["load_factor"].as_f64().unwrap();
    let fy_n = applied[1].as_f64().unwrap();
    assert!((fy_n + 38_400.0 * lambda).abs() < 1e-6 * 38_400.0, "{fy_n}");
    // curve.csv's load_ratio without an interface: λ over the first yield's λ
    let curve = std::fs::read_to_string(
        std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
            .join("schema-solid")
            .join("out")
            .join("curve.csv"),
    )
    .unwrap();
    let fy_lambda = solid["first_yield"]["load_factor"].as_f64().unwrap();
    for row in curve.lines().skip(1) {
        let v: Vec<f64> = row.split(',').map(|x| x.parse().unwrap()).collect();
        assert!((v[4] - v[1] / fy_lambda).abs() < 1e-8, "{row}");
    }
    // a cyclic sector: its `cyclic` object and the `forces` line
    let cyclic = summary_of("cyclic", &cases.join("tube-sector-cyclic"), &[]);
    assert_eq!(cyclic["cyclic"]["sectors"], 12, "{cyclic}");
    assert!(cyclic["forces"].is_string() && solid.get("cyclic").is_none());
    // a cyclic sector with interfaces: the whole part's joint numbers
    let flange = summary_of("flange", &cases.join("flange-sector-cyclic"), &[]);
    let part = &flange["joints"][0]["final"]["part"];
    assert_eq!(part["sectors"], 12, "{flange}");
    assert!(solid["joints"]
        .as_array()
        .is_none_or(|j| j.iter().all(|j| j["final"].get("part").is_none())));
    assert!(torque["joints"][0]["final"]["torque_nmm"].as_f64().unwrap() > 0.0);
    assert!(
        with["joints"][0]["final"].get("torque_nmm").is_none(),
        "{with}"
    );
    for s in [
        &with_cycle,
        &without,
        &gap,
        &axi,
        &tab,
        &stack,
        &bolt,
        &torque,
        &face,
        &solid,
        &slide,
        &cyclic,
        &flange,
    ] {
        let mut l = Vec::new();
        leaves("", s, &mut l);
        for (k, t) in l {
            match doc.get(&k) {
                None => errors.push(format!("`{k}` ({t}) is written but not documented")),
                Some(d) if !allowed(d, t) => {
                    errors.push(format!("`{k}` is {t}, documented as {d}"))
                }
                _ => {}
            }
            seen.insert(k);
        }
    }
    for k in doc.keys() {
        if k != "backend_stats.*" && !seen.contains(k) {
            errors.push(format!("`{k}` is documented but never written"));
        }
    }
    assert_eq!(with["schema"], 1);
    // memory stages: peaks so far, so in stage order and never above the run's peak
    for s in [&with, &without] {
        let m = &s["memory_stages_mb"];
        let mut last = 0.0;
        for stage in ["model", "setup", "first_assembly", "first_increment"] {
            let v = m[stage].as_f64().unwrap_or_else(|| panic!("{stage}: {m}"));
            assert!(v > 0.0 && v >= last, "{stage}: {m}");
            last = v;
        }
        assert!(last <= s["peak_memory_mb"].as_f64().unwrap(), "{s}");
    }
    assert!(errors.is_empty(), "{}", errors.join("\n"));
}

/// The columns a CSV section of docs/output.md lists: the backquoted text
/// before the first `:` after its `## \`NAME\`` heading.
fn documented_columns(doc: &str, name: &str) -> Vec<String> {
    let section = doc
        .split(&format!("\n## `{name}`\n"))
        .nth(1)
        .unwrap_or_else(|| panic!("no section for {name}"));
    let list = section.split("`:").next().unwrap();
    let list = &list[list.find('`').unwrap() + 1..];
    list.split(',').map(|c| c.trim().to_string()).collect()
}

#[test]
fn the_joint_csv_files_have_the_documented_columns() {
    use asperity::files::output::{damping, joints_csv as joints};
    let doc = std::fs::read_to_string(common::root().join("docs/output.md")).unwrap();
    for (name, header) in [
        ("joints.csv", joints::JOINTS_HEADER),
        ("cycles.csv", joints::CYCLES_HEADER),
        ("damping.csv", damping::DAMPING_HEADER),
        ("backbone.csv", damping::BACKBONE_HEADER),
    ] {
        let written: Vec<&str> = header.trim_end().split(',').collect();
        assert_eq!(documented_columns(&doc, name), written, "{name}");
        // and the file table lists it
        assert!(
            doc.contains(&format!("| `{name}` |")),
            "{name} not in the table"
        );
    }
    for f in ["damping.svg", "damping.png"] {
        assert!(doc.contains(&format!("`{f}`")), "{f} not documented");
    }
    // a twisting model's extra columns, each named in its file's section
    for (name, extra) in [
        ("joints.csv", joints::JOINTS_TWIST_COLUMNS),
        ("cycles.csv", joints::CYCLES_TWIST_COLUMNS),
    ] {
        let section = doc.split(&format!("\n## `{name}`\n")).nth(1).unwrap();
        let section = section.split("\n## ").next().unwrap();
        for c in extra.split(',').filter(|c| !c.is_empty()) {
            assert!(
                section.contains(&format!("`{c}`")),
                "{name}: {c} not documented"
            );
        }
    }
}
