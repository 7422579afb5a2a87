//! `asperity calibrate` as a user meets it: the worked example end to end
//! (the files, the power-law snippet pasted into a shipped case and checked,
//! the table snippet's shape, and the table law pasted into the punch runs), a measured profile
//! (clean and as a spreadsheet exports it), and unit slips that warn. Roughness
//! (Ra, Rz) inputs and tangential laws in `calibrate_roughness`, bad inputs in
//! `calibrate_bad`.

use crate::common;
use std::path::Path;
use std::process::Command;

pub fn asperity(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_asperity"))
        .args(args)
        .output()
        .unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into(),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}

pub fn calibrate(input: &Path, out: &Path) -> (i32, String, String) {
    asperity(&[
        "calibrate",
        input.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ])
}

pub const MATERIALS: &str =
    "[materials]\na = { young = 206000.0, poisson = 0.3 }\nb = { young = 206000.0, poisson = 0.3 }\n";
pub const GW: &str = "[surface]\nmodel = \"gw\"\ndensity = 2e3\nradius = 0.05\nsigma = 1e-3\n";
pub const FIT: &str = "[fit]\npressure = [10.0, 200.0]\n";

#[test]
fn the_example_writes_a_curve_a_fit_and_pasteable_laws() {
    let dir = common::scratch("calibrate-example");
    let out = dir.join("out");
    let (code, stdout, err) =
        calibrate(&common::root().join("docs/calibration/example.toml"), &out);
    assert_eq!(code, 0, "{err}");
    assert!(err.is_empty(), "the example draws no warning: {err}");
    assert!(stdout.contains("c_n = "), "{stdout}");
    for f in ["curve.csv", "fit.json", "interface.toml"] {
        assert!(out.join(f).is_file(), "{f}");
    }
    // no temporary folder left beside it
    let left: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(left, vec!["out".to_string()], "{left:?}");
    let csv = std::fs::read_to_string(out.join("curve.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(lines.next(), Some("approach_mm,pressure_mpa"));
    let pts: Vec<(f64, f64)> = lines
        .map(|l| {
            let (a, b) = l.split_once(',').unwrap();
            (a.parse().unwrap(), b.parse().unwrap())
        })
        .collect();
    assert!(pts.len() > 100);
    assert!(pts.windows(2).all(|w| w[1].0 > w[0].0 && w[1].1 > w[0].1));
    let fit: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("fit.json")).unwrap()).unwrap();
    let (c_n, m) = (fit["c_n"].as_f64().unwrap(), fit["m"].as_f64().unwrap());
    assert!(
        fit["max_relative_error_approach"].as_f64().unwrap() < 0.05,
        "{fit}"
    );
    assert_eq!(fit["pressure_range_mpa"], serde_json::json!([10.0, 200.0]));

    // interface.toml is TOML with two [interface.*] tables
    let text = std::fs::read_to_string(out.join("interface.toml")).unwrap();
    let v: toml::Table = toml::from_str(&text).unwrap();
    let iface = v["interface"].as_table().unwrap();
    let power = iface["calibrated_power"].as_table().unwrap();
    assert_eq!(power["law"].as_str(), Some("power"));
    assert!((power["c_n"].as_float().unwrap() / c_n - 1.0).abs() < 1e-6);
    assert!((power["m"].as_float().unwrap() - m).abs() < 1e-6);
    let table = iface["calibrated_table"].as_table().unwrap();
    assert_eq!(table["law"].as_str(), Some("table"));
    let rows: Vec<(f64, f64)> = table["table"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| {
            let r = r.as_array().unwrap();
            (r[0].as_float().unwrap(), r[1].as_float().unwrap())
        })
        .collect();
    assert_eq!(rows.len(), 10);
    assert!(rows[0].0 > 0.0 && rows[0].1 == 10.0 && rows[9].1 == 200.0);
    assert!(rows.windows(2).all(|w| w[1].0 > w[0].0 && w[1].1 > w[0].1));

    // the power snippet pasted into a shipped case: parsed and checked
    let case =
        std::fs::read_to_string(common::root().join("cases/punch-plane-stress/case.toml")).unwrap();
    let start = case.find("[interface.contact]").unwrap();
    let end = start + case[start..].find("\n[[").unwrap();
    let snippet_start = text.find("[interface.calibrated_power]").unwrap();
    let snippet_end = snippet_start + text[snippet_start..].find("\n\n").unwrap();
    let snippet = text[snippet_start..snippet_end]
        .replace("[interface.calibrated_power]", "[interface.contact]");
    let pasted = format!("{}{}\n{}", &case[..start], snippet, &case[end..]);
    let parsed = asperity::input::case::Case::parse(&pasted, "pasted.toml").unwrap();
    assert_eq!(
        parsed.interface["contact"].c_n,
        Some(power["c_n"].as_float().unwrap())
    );
    let path = common::case_dir("calibrate-pasted", &pasted);
    let (code, _, err) = asperity(&["check", path.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    // and the table snippet: a valid `law = "table"` that runs the punch
    let snippet_start = text.find("[interface.calibrated_table]").unwrap();
    let snippet_end = snippet_start + text[snippet_start..].find("\n]").unwrap() + 2;
    let snippet = text[snippet_start..snippet_end]
        .replace("[interface.calibrated_table]", "[interface.contact]");
    let pasted = format!("{}{}\n{}", &case[..start], snippet, &case[end..]);
    let path = common::case_dir("calibrate-pasted-table", &pasted);
    let out = path.parent().unwrap().join("out");
    let (code, _, err) = asperity(&[
        "run",
        path.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ]);
    assert_eq!(code, 0, "{err}");
}

/// Three harmonics, whole periods, 4000 samples 1 µm apart: m0, m2, m4 known
/// (finite-difference bias < 1%). The text (one height per line, LF) and the modes.
pub fn three_harmonics() -> (String, usize, f64, [(f64, f64); 3]) {
    let n = 4000;
    let dx = 1e-3;
    let len = n as f64 * dx;
    let modes = [(1e-3, 10.0), (3e-4, 47.0), (1e-4, 180.0)];
    let mut text = String::from("# heights in mm, one per line, spacing 1 µm\n");
    for i in 0..n {
        let x = i as f64 * dx;
        let z: f64 = modes
            .iter()
            .map(|(a, j)| a * (2.0 * std::f64::consts::PI * j * x / len + 0.4).sin())
            .sum();
        text.push_str(&format!("{z:.12e}\n"));
    }
    (text, n, len, modes)
}

/// surface.toml for `profile.csv` in `dir`, with `detrend`.
fn profile_input(dir: &Path, file: &str, detrend: &str) -> std::path::PathBuf {
    let input = dir.join(format!("{file}.toml"));
    std::fs::write(
        &input,
        format!("[materials]\na = {{ young = 206000.0, poisson = 0.3 }}\nb = {{ young = 206000.0, poisson = 0.3 }}\n\
         [surface]\nmodel = \"profile\"\nfile = \"{file}\"\nsampling = 1e-3\nkind = \"line\"\ndetrend = \"{detrend}\"\n\
         [fit]\npressure = [10.0, 200.0]\n"),
    )
    .unwrap();
    input
}

#[test]
fn a_measured_profile_gives_its_summit_parameters() {
    let dir = common::scratch("calibrate-profile");
    let (text, _, len, modes) = three_harmonics();
    std::fs::write(dir.join("profile.csv"), text).unwrap();
    let input = profile_input(&dir, "profile.csv", "mean");
    let (code, _, err) = calibrate(&input, &dir.join("out"));
    assert_eq!(code, 0, "{err}");
    let fit: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("out/fit.json")).unwrap()).unwrap();
    let m0: f64 = modes.iter().map(|(a, _)| a * a / 2.0).sum();
    let got = fit["profile"]["m0_mm2"].as_f64().unwrap();
    assert!((got / m0 - 1.0).abs() < 1e-3, "{got} vs {m0}");
    let pi = std::f64::consts::PI;
    let m2: f64 = modes
        .iter()
        .map(|(a, j)| a * a / 2.0 * (2.0 * pi * j / len).powi(2))
        .sum();
    let m4: f64 = modes
        .iter()
        .map(|(a, j)| a * a / 2.0 * (2.0 * pi * j / len).powi(4))
        .sum();
    let eta = m4 / (6.0 * pi * 3f64.sqrt() * m2);
    let got = fit["gw"]["density_per_mm2"].as_f64().unwrap();
    assert!((got / eta - 1.0).abs() < 0.02, "{got} vs {eta}");
}

/// The same profile as a spreadsheet exports it (UTF-8 byte-order mark, CRLF
/// line ends; and old Mac CR line ends) calibrates exactly like the clean file.
#[test]
fn a_spreadsheet_profile_calibrates_like_the_clean_file() {
    let dir = common::scratch("calibrate-spreadsheet");
    let (text, ..) = three_harmonics();
    std::fs::write(dir.join("clean.csv"), &text).unwrap();
    let crlf = format!("\u{feff}{}", text.replace('\n', "\r\n"));
    assert!(crlf.as_bytes().starts_with(&[0xef, 0xbb, 0xbf]) && crlf.contains("\r\n"));
    std::fs::write(dir.join("excel.csv"), crlf).unwrap();
    std::fs::write(
        dir.join("mac.csv"),
        format!("\u{feff}{}", text.replace('\n', "\r")),
    )
    .unwrap();
    let fit = |file: &str| -> serde_json::Value {
        let out = dir.join(format!("out-{file}"));
        let (code, _, err) = calibrate(&profile_input(&dir, file, "linear"), &out);
        assert_eq!(code, 0, "{file}: {err}");
        assert!(err.is_empty(), "{file}: {err}");
        serde_json::from_str(&std::fs::read_to_string(out.join("fit.json")).unwrap()).unwrap()
    };
    let clean = fit("clean.csv");
    for file in ["excel.csv", "mac.csv"] {
        let got = fit(file);
        for key in [
            &["c_n"][..],
            &["m"],
            &["d0_mm"],
            &["gw", "density_per_mm2"],
            &["gw", "radius_mm"],
            &["gw", "sigma_mm"],
            &["profile", "m0_mm2"],
            &["profile", "m4_per_mm2"],
        ] {
            let at = |v: &serde_json::Value| key.iter().fold(v.clone(), |v, k| v[*k].clone());
            let (a, b) = (at(&clean).as_f64().unwrap(), at(&got).as_f64().unwrap());
            assert!(common::rel(a, b) < 1e-14, "{file} {key:?}: {a} vs {b}");
        }
    }
}

/// Legal but implausible values (σ in µm written as mm, a density per m²
/// written per mm²): the calibration is made, each value named in a warning on
/// stderr and in the output.
#[test]
fn unit_slips_are_calibrated_with_warnings() {
    let dir = common::scratch("calibrate-warnings");
    let input = dir.join("surface.toml");
    std::fs::write(
        &input,
        format!(
            "{MATERIALS}{}{FIT}",
            GW.replace("sigma = 1e-3", "sigma = 1.0")
                .replace("density = 2e3", "density = 2e9")
        ),
    )
    .unwrap();
    let out = dir.join("out");
    let (code, stdout, err) = calibrate(&input, &out);
    assert_eq!(code, 0, "{err}");
    assert!(stdout.contains("c_n = "), "{stdout}");
    let lines: Vec<&str> = err.lines().collect();
    assert!(lines.iter().all(|l| l.starts_with("warning: ")), "{err}");
    assert!(
        lines.iter().any(
            |l| l.contains("surface.sigma: 1 mm is above the usual range")
                && l.contains("µm written as mm")
        ),
        "{err}"
    );
    assert!(
        lines.iter().any(
            |l| l.contains("surface.density: 2e9 /mm² is above the usual range")
                && l.contains("per m² written as per mm²")
        ),
        "{err}"
    );
    let fit: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("fit.json")).unwrap()).unwrap();
    assert_eq!(fit["warnings"].as_array().unwrap().len(), lines.len());
    let text = std::fs::read_to_string(out.join("interface.toml")).unwrap();
    assert_eq!(text.matches("# WARNING: ").count(), lines.len(), "{text}");
    // a summit value no key gives is named by the key that made it, Ra in
    // mm here ("σ_s from the roughness" until issue 42), in the warning line
    // and fit.json
    let rough = format!("{MATERIALS}[surface]\nmodel = \"roughness\"\nra = 0.9\n{FIT}");
    std::fs::write(&input, rough).unwrap();
    let (code, _, err) = calibrate(&input, &out);
    assert_eq!(code, 0, "{err}");
    assert!(
        err.lines().any(|l| l.contains(
            "surface.toml: surface.ra: 1.127 mm for σ_s, the standard deviation of summit heights, derived from it with H = 0.8 assumed, λc of ISO 4288, λs of ISO 3274, is above its usual range"
        )),
        "{err}"
    );
    let fit: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("fit.json")).unwrap()).unwrap();
    let warnings = fit["warnings"].as_array().unwrap();
    assert!(
        warnings
            .iter()
            .any(|w| w.as_str().unwrap().contains("surface.ra: 1.127 mm for σ_s")),
        "{warnings:?}"
    );
    assert!(!err.contains("from the roughness"), "{err}");
}
