//! `asperity calibrate` as a user meets it: the worked example end to end
//! (the files, the power-law snippet pasted into a shipped case and checked,
//! the table snippet's shape, and the table law pasted into the punch runs), a measured profile
//! (clean and as a spreadsheet exports it), unit slips that warn, and bad inputs (one `error:`
//! line naming file and key, exit code 2, no output folder).

use crate::common;
use std::path::Path;
use std::process::Command;

fn asperity(args: &[&str]) -> (i32, String, String) {
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

fn calibrate(input: &Path, out: &Path) -> (i32, String, String) {
    asperity(&[
        "calibrate",
        input.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ])
}

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
    let parsed = asperity::case::Case::parse(&pasted, "pasted.toml").unwrap();
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
fn three_harmonics() -> (String, usize, f64, [(f64, f64); 3]) {
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
}

fn bad(name: &str, input: &str, expect: &str) {
    let dir = common::scratch(&format!("calibrate-bad-{name}"));
    std::fs::write(dir.join("empty.csv"), "# nothing\n").unwrap();
    // a missing sample: an empty cell between two separators (line 201)
    let gap: String = (0..400)
        .map(|i| {
            let (a, b) = (1e-3 * (i * 37 % 11) as f64, 1e-3 * (i * 13 % 7) as f64);
            let sep = if i == 200 { ",," } else { "," };
            format!("{a}{sep}{b}\n")
        })
        .collect();
    std::fs::write(dir.join("gap.csv"), gap).unwrap();
    // flat records: a tilted line, and a tilted plane (CRLF) with an offset
    let tilted: String = (0..400)
        .map(|i| format!("{}\n", 3.0 + 2.5e-4 * i as f64))
        .collect();
    std::fs::write(dir.join("tilted.csv"), tilted).unwrap();
    let plane: String = (0..12)
        .map(|r| {
            let row: Vec<String> = (0..15)
                .map(|c| format!("{}", 25.0 + 5e-4 * c as f64 - 2e-4 * r as f64))
                .collect();
            row.join(",") + "\r\n"
        })
        .collect();
    std::fs::write(dir.join("plane.csv"), plane).unwrap();
    // a byte-order mark and a no-break space inside the record, not at its start
    std::fs::write(
        dir.join("invisible.csv"),
        "1e-3\n\u{feff}2e-3\n3e-3\n-1e-3\n2e-3\n0\n1e-3\n-2e-3\n",
    )
    .unwrap();
    std::fs::write(dir.join("nbsp.csv"), "1e-3\n2\u{a0}000\n").unwrap();
    std::fs::write(dir.join("huge.csv"), "1e-3\n2e-3\n1e300\n").unwrap();
    std::fs::write(dir.join("subnormal.csv"), "1e-3\n4e-320\n").unwrap();
    let path = dir.join("surface.toml");
    std::fs::write(&path, input).unwrap();
    let (code, out, err) = calibrate(&path, &dir.join("out"));
    assert_eq!(code, 2, "{name}: {out} {err}");
    assert_eq!(err.lines().count(), 1, "{name}: {err}");
    assert!(err.starts_with("error: "), "{name}: {err}");
    assert!(err.contains(expect), "{name}: {err}");
    assert!(
        !err.trim_end_matches('\n')
            .chars()
            .any(|c| c.is_control() || asperity::error::invisible(c)),
        "{name}: {err:?}"
    );
    assert!(!dir.join("out").exists(), "{name}");
    // nor a temporary folder beside it
    let left: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with('.'))
        .collect();
    assert!(left.is_empty(), "{name}: {left:?}");
}

/// A profile input over `file` (written by [`bad`]).
fn profile(file: &str, extra: &str) -> String {
    format!("{MATERIALS}[surface]\nmodel = \"profile\"\nfile = \"{file}\"\nsampling = 1e-3\n{extra}{FIT}")
}

const MATERIALS: &str =
    "[materials]\na = { young = 206000.0, poisson = 0.3 }\nb = { young = 206000.0, poisson = 0.3 }\n";
const GW: &str = "[surface]\nmodel = \"gw\"\ndensity = 2e3\nradius = 0.05\nsigma = 1e-3\n";
const FIT: &str = "[fit]\npressure = [10.0, 200.0]\n";

#[test]
fn bad_inputs_are_one_error_line_and_exit_2() {
    bad(
        "unknown-key",
        &format!("{MATERIALS}{GW}colour = 3\n{FIT}"),
        "unknown field `colour`",
    );
    bad(
        "negative-sigma",
        &format!(
            "{MATERIALS}{}{FIT}",
            GW.replace("sigma = 1e-3", "sigma = -1e-3")
        ),
        "surface.sigma: must be a positive finite number",
    );
    bad(
        "empty-profile",
        &format!("{MATERIALS}[surface]\nmodel = \"profile\"\nfile = \"empty.csv\"\nsampling = 1e-3\n{FIT}"),
        "too few heights: 0",
    );
    bad(
        "profile-empty-cell",
        &format!(
            "{MATERIALS}[surface]\nmodel = \"profile\"\nfile = \"gap.csv\"\nsampling = 1e-3\n{FIT}"
        ),
        "gap.csv:201: has an empty cell",
    );
    bad(
        "range-too-narrow-for-a-table",
        &format!("{MATERIALS}{GW}[fit]\npressure = [10.0, 10.00000034]\n"),
        "gives a table that a case file would refuse",
    );
    bad(
        "range-reversed",
        &format!("{MATERIALS}{GW}[fit]\npressure = [200.0, 10.0]\n"),
        "fit.pressure: lo 200 must be below hi 10",
    );
    bad(
        "range-equal",
        &format!("{MATERIALS}{GW}[fit]\npressure = [10.0, 10.0]\n"),
        "must be below hi",
    );
    bad(
        "no-hardness",
        &format!("{MATERIALS}{GW}asperities = \"elastic-plastic\"\n{FIT}"),
        "needs the hardness",
    );
    bad(
        "distribution-unknown",
        &format!("{MATERIALS}{GW}distribution = \"weibull\"\n{FIT}"),
        "unknown \"weibull\"",
    );
    bad(
        "model-unknown",
        &format!("{MATERIALS}[surface]\nmodel = \"fractal\"\n{FIT}"),
        "fractal",
    );
    bad(
        "missing-fit",
        &format!("{MATERIALS}{GW}"),
        "missing field `fit`",
    );
    bad(
        "poisson-half",
        &format!("{}{GW}{FIT}", MATERIALS.replacen("0.3", "0.5", 1)),
        "materials.a.poisson",
    );
    // issue 30: subnormal, huge and non-finite values name their key
    bad(
        "subnormal-sigma",
        &format!(
            "{MATERIALS}{}{FIT}",
            GW.replace("sigma = 1e-3", "sigma = 1e-310")
        ),
        "surface.toml: surface.sigma: 1e-310 is a subnormal number",
    );
    bad(
        "huge-sigma",
        &format!(
            "{MATERIALS}{}{FIT}",
            GW.replace("sigma = 1e-3", "sigma = 1e300")
        ),
        "surface.sigma: 1e300 mm is far outside any use as σ_s",
    );
    bad(
        "huge-young",
        &format!("{}{GW}{FIT}", MATERIALS.replacen("206000.0", "1e300", 1)),
        "materials.a.young: 1e300 MPa is far outside any use as Young's modulus",
    );
    bad(
        "subnormal-poisson",
        &format!("{}{GW}{FIT}", MATERIALS.replacen("0.3", "1e-315", 1)),
        "materials.a.poisson: 1e-315 is a subnormal number",
    );
    bad(
        "huge-density",
        &format!(
            "{MATERIALS}{}{FIT}",
            GW.replace("density = 2e3", "density = 1e20")
        ),
        "surface.density: 1e20 /mm² is far outside",
    );
    bad(
        "subnormal-radius",
        &format!(
            "{MATERIALS}{}{FIT}",
            GW.replace("radius = 0.05", "radius = 2e-308")
        ),
        "surface.radius: 2e-308 is a subnormal number",
    );
    bad(
        "infinite-pressure",
        &format!("{MATERIALS}{GW}[fit]\npressure = [10.0, inf]\n"),
        "fit.pressure: must be a finite number, got inf",
    );
    bad(
        "subnormal-pressure",
        &format!("{MATERIALS}{GW}[fit]\npressure = [1e-310, 200.0]\n"),
        "fit.pressure: 1e-310 is a subnormal number",
    );
    bad(
        "tiny-pressure",
        &format!("{MATERIALS}{GW}[fit]\npressure = [1e-30, 1e-25]\n"),
        "fit.pressure: 1e-30 MPa is far outside any use as a fit pressure",
    );
    bad(
        "subnormal-reference",
        &format!("{MATERIALS}{GW}{FIT}reference_pressure = 5e-324\n"),
        "fit.reference_pressure: 5e-324 is a subnormal number",
    );
    bad(
        "subnormal-sampling",
        &profile("tilted.csv", "").replace("sampling = 1e-3", "sampling = 1e-320"),
        "surface.sampling: 1e-320 is a subnormal number",
    );
    // no summit touches: the key at fault, the pressure and the roughness named
    bad(
        "no-contact-sigma-in-um",
        &format!(
            "{MATERIALS}{}[fit]\npressure = [1e-3, 1e-2]\n",
            GW.replace("sigma = 1e-3", "sigma = 1.0")
        ),
        "surface.toml: surface.sigma: 1 mm is above the usual range of σ_s",
    );
    bad(
        "no-contact-pressure",
        "[materials]\na = { young = 1.2e6, poisson = 0.1 }\nb = { young = 1.2e6, poisson = 0.1 }\n\
         [surface]\nmodel = \"gw\"\ndensity = 1e6\nradius = 10.0\nsigma = 0.1\n[fit]\npressure = [1e-3, 1e-2]\n",
        "surface.toml: fit.pressure: no summit touches at the lower fit pressure fit.pressure = 1e-3 MPa",
    );
    bad(
        "no-contact-names-roughness",
        "[materials]\na = { young = 1.2e6, poisson = 0.1 }\nb = { young = 1.2e6, poisson = 0.1 }\n\
         [surface]\nmodel = \"gw\"\ndensity = 1e6\nradius = 10.0\nsigma = 0.1\n[fit]\npressure = [1e-3, 1e-2]\n",
        "surface.density = 1e6 /mm², surface.radius = 10 mm, surface.sigma = 0.1 mm",
    );
    bad(
        "cannot-carry-hi",
        &format!(
            "{MATERIALS}{}[fit]\npressure = [10.0, 2000.0]\n",
            GW.replace("sigma = 1e-3", "sigma = 1e-5")
        ),
        "surface.toml: fit.pressure: the surface carries",
    );
    bad(
        "pressures-unresolved",
        &format!("{MATERIALS}{GW}[fit]\npressure = [10.0, 10.0000000001]\n"),
        "fit.pressure: lo 10 and hi 10.0000000001 MPa map to separations only",
    );
    bad(
        "reference-unresolved",
        &format!("{MATERIALS}{GW}{FIT}reference_pressure = 9.99999999999\n"),
        "fit.reference_pressure: 9.99999999999 MPa maps to a separation only",
    );
    // flat and unreadable profiles name the height file
    bad(
        "flat-tilted-line",
        &profile("tilted.csv", ""),
        "tilted.csv: the profile is flat: its heights lie on a line",
    );
    bad(
        "flat-tilted-line-mean",
        &profile("tilted.csv", "detrend = \"mean\"\n"),
        "detrend = \"mean\" would leave the tilt alone",
    );
    bad(
        "flat-tilted-plane",
        &profile("plane.csv", "kind = \"areal\"\n"),
        "plane.csv: the profile is flat: its heights lie on a plane",
    );
    bad(
        "bom-inside-profile",
        &profile("invisible.csv", ""),
        "invisible.csv:2: \"\\u{feff}2e-3\" is not a number",
    );
    bad(
        "no-break-space-in-profile",
        &profile("nbsp.csv", ""),
        "nbsp.csv:2: \"2\\u{a0}000\" is not a number",
    );
    bad(
        "huge-height",
        &profile("huge.csv", ""),
        "huge.csv:3: height 1e300 is beyond",
    );
    bad(
        "subnormal-height",
        &profile("subnormal.csv", ""),
        "subnormal.csv:2: height 4e-320 is a subnormal number",
    );
    let (code, _, err) = asperity(&["calibrate", "no/such/file.toml", "--out", "x"]);
    assert_eq!(code, 2);
    assert!(err.starts_with("error: no/such/file.toml"), "{err}");
}

/// The [interface.calibrated_table] snippet and its tangential table, as
/// written, pasted into the punch-friction case as `contact`.
fn paste_with_tangential(text: &str) -> String {
    let case =
        std::fs::read_to_string(common::root().join("cases/punch-friction-a/case.toml")).unwrap();
    let start = case.find("[interface.contact]").unwrap();
    let end = start + case[start..].find("\n[[").unwrap();
    let from = text.find("[interface.calibrated_table]").unwrap();
    let snippet = text[from..]
        .replace("[interface.calibrated_table]", "[interface.contact]")
        .replace(
            "[interface.calibrated_table.tangential]",
            "[interface.contact.tangential]",
        );
    format!("{}{}\n{}", &case[..start], snippet, &case[end..])
}

/// The drawing's Ra of two faces to a normal and a tangential law: the
/// k_table has a row at every pressure of the normal table, stiffness
/// non-decreasing, equal to fit.json's; pasted with its μ into a case with
/// a tangential law, `asperity check` accepts it. The Hurst band is reported
/// on stdout, in fit.json and as comments of interface.toml.
#[test]
fn the_roughness_example_writes_a_normal_and_a_tangential_law() {
    let dir = common::scratch("calibrate-roughness");
    let out = dir.join("out");
    let (code, stdout, err) = calibrate(
        &common::root().join("docs/calibration/roughness.toml"),
        &out,
    );
    assert_eq!(code, 0, "{err}");
    assert!(err.is_empty(), "{err}");
    assert!(
        stdout.contains("(from ra, assumed H = 0.8); over H 0.5-1: c_n ")
            && stdout.contains("MPa/µm over the range, μ = 0.15"),
        "{stdout}"
    );
    let fit: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("fit.json")).unwrap()).unwrap();
    // σ² = σ_a² + σ_b², σ = √(π/2) Ra for each face
    let m0 = fit["roughness"]["m0_mm2"].as_f64().unwrap();
    let want = std::f64::consts::PI / 2.0 * (0.8e-3f64.powi(2) + 0.4e-3f64.powi(2));
    assert!(common::rel(m0, want) < 1e-14, "{m0} vs {want}");
    assert_eq!(fit["roughness"]["hurst_band"].as_array().unwrap().len(), 2);
    let text = std::fs::read_to_string(out.join("interface.toml")).unwrap();
    assert!(
        text.contains("# ASSUMPTION: ra gives the rms height only"),
        "{text}"
    );
    assert_eq!(text.matches("\n# at H = ").count(), 2, "{text}");
    let v: toml::Table = toml::from_str(&text).unwrap();
    let table = v["interface"]["calibrated_table"].as_table().unwrap();
    let t = table["tangential"].as_table().unwrap();
    assert_eq!(t["mu"].as_float(), Some(0.15));
    let rows: Vec<(f64, f64)> = t["k_table"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| (r[0].as_float().unwrap(), r[1].as_float().unwrap()))
        .collect();
    let normal = table["table"].as_array().unwrap();
    assert_eq!(rows.len(), normal.len());
    for (r, n) in rows.iter().zip(normal) {
        assert_eq!(
            r.0,
            n[1].as_float().unwrap(),
            "a row at each normal pressure"
        );
    }
    assert!(rows.windows(2).all(|w| w[1].0 > w[0].0 && w[1].1 >= w[0].1));
    let json_rows = fit["tangential"]["k_table"].as_array().unwrap();
    for (r, j) in rows.iter().zip(json_rows) {
        assert!(common::rel(r.1, j[1].as_f64().unwrap()) < 1e-9);
    }
    let pasted = paste_with_tangential(&text);
    let path = common::case_dir("calibrate-pasted-tangential", &pasted);
    let (code, _, err) = asperity(&["check", path.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}\n{pasted}");
}

/// Rz = 2σ(√(2 ln N) + γ/√(2 ln N)), N = (λc/2π)√(m2/m0) (Davenport 1964),
/// computed here for H = 1 on the ISO band of Ra 0.8 µm (λc 0.8 mm, λs
/// 2.5 µm: m2/m0 = 2 ln(k2/k1)/(k1⁻² − k2⁻²)): the Rz of the surface with
/// σ = √(π/2) × 0.8 µm calibrates exactly as that Ra.
#[test]
fn ra_and_the_rz_of_the_same_gaussian_surface_calibrate_alike() {
    use std::f64::consts::PI;
    let sigma = (PI / 2.0).sqrt() * 0.8e-3;
    let (k1, k2) = (2.0 * PI / 0.8, 2.0 * PI / 2.5e-3);
    let n = 0.8 / (2.0 * PI) * (2.0 * (k2 / k1).ln() / (k1.powi(-2) - k2.powi(-2))).sqrt();
    let l = (2.0 * n.ln()).sqrt();
    let rz = 2.0 * sigma * (l + 0.5772156649015329 / l);
    assert!(rz > 3e-3 && rz < 5e-3, "{rz}"); // λc 0.8 mm for this Rz too
    let dir = common::scratch("calibrate-ra-rz");
    let run = |key: &str| -> serde_json::Value {
        let input = dir.join(format!("{key}.toml"));
        std::fs::write(
            &input,
            format!("{MATERIALS}[surface]\nmodel = \"roughness\"\n{key}\nhurst = 1.0\n{FIT}"),
        )
        .unwrap();
        let out = dir.join(format!("out-{}", &key[..2]));
        let (code, _, err) = calibrate(&input, &out);
        assert_eq!(code, 0, "{err}");
        serde_json::from_str(&std::fs::read_to_string(out.join("fit.json")).unwrap()).unwrap()
    };
    let a = run("ra = 0.8e-3");
    let b = run(&format!("rz = {rz:e}"));
    for key in ["c_n", "m", "d0_mm"] {
        let (x, y) = (a[key].as_f64().unwrap(), b[key].as_f64().unwrap());
        assert!(common::rel(x, y) < 1e-9, "{key}: {x} vs {y}");
    }
    // H given: no band
    assert!(a["roughness"]["hurst_band"].as_array().unwrap().is_empty());
}

/// Rz/σ by Davenport's formula on the ISO band of λc = 0.8 mm, λs = 2.5 µm
/// for the spectrum k^−(1+2H), computed here from the closed-form moments
/// m2/m0 = ∫k^{1−2H} / ∫k^{−1−2H} (the logarithm at H = 1).
fn rz_over_sigma_by_hand(hurst: f64) -> f64 {
    use std::f64::consts::PI;
    let (k1, k2) = (2.0 * PI / 0.8, 2.0 * PI / 2.5e-3);
    let q = 1.0 + 2.0 * hurst;
    let i2 = if hurst == 1.0 {
        (k2 / k1).ln()
    } else {
        (k2.powf(3.0 - q) - k1.powf(3.0 - q)) / (3.0 - q)
    };
    let i0 = (k1.powf(1.0 - q) - k2.powf(1.0 - q)) / (q - 1.0);
    let n = 0.8 / (2.0 * PI) * (i2 / i0).sqrt();
    let l = (2.0 * n.ln()).sqrt();
    2.0 * (l + 0.5772156649015329 / l)
}

/// Ra 0.4 µm on the carriage (face a), Rz 4 µm on the ground bed (face b):
/// the same calibration as both faces given by Ra, face b's Ra computed here
/// from its Rz (σ = Rz / (Rz/σ), Ra = σ √(2/π)); to 1e-9. The Hurst band
/// moves the Rz face's σ with H: each end equals the all-Ra input at that H
/// with the Ra of that H, and the band is far wider than that of the all-Ra
/// input (whose σ does not move), so the mixed input does not hide it.
#[test]
fn ra_on_one_face_and_rz_on_the_other_calibrate_as_the_rz_converted() {
    let dir = common::scratch("calibrate-mixed");
    let ra_of =
        |hurst: f64| 4e-3 / rz_over_sigma_by_hand(hurst) * (2.0 / std::f64::consts::PI).sqrt();
    let run = |name: &str, surface: &str| -> serde_json::Value {
        let input = dir.join(format!("{name}.toml"));
        std::fs::write(
            &input,
            format!("{MATERIALS}[surface]\nmodel = \"roughness\"\n{surface}{FIT}[tangential]\nmu = 0.15\n"),
        )
        .unwrap();
        let out = dir.join(format!("out-{name}"));
        let (code, stdout, err) = calibrate(&input, &out);
        assert_eq!(code, 0, "{name}: {err}");
        assert!(err.is_empty(), "{name}: {err}");
        if name == "mixed" {
            assert!(
                stdout.contains("(from ra (face a) and rz (face b), assumed H = 0.8)"),
                "{stdout}"
            );
            let text = std::fs::read_to_string(out.join("interface.toml")).unwrap();
            assert!(
                text.contains("# ASSUMPTION: ra (face a) and rz (face b) give the rms height only"),
                "{text}"
            );
        }
        serde_json::from_str(&std::fs::read_to_string(out.join("fit.json")).unwrap()).unwrap()
    };
    let close = |a: &serde_json::Value, b: &serde_json::Value, what: &str| {
        for key in ["c_n", "m"] {
            let (x, y) = (a[key].as_f64().unwrap(), b[key].as_f64().unwrap());
            assert!(common::rel(x, y) < 1e-9, "{what} {key}: {x} vs {y}");
        }
    };
    let mixed = run("mixed", "a = { ra = 0.4e-3 }\nb = { rz = 4e-3 }\n");
    let ra = run("all-ra", &format!("ra = [0.4e-3, {:e}]\n", ra_of(0.8)));
    close(&mixed, &ra, "H = 0.8");
    let (x, y) = (
        mixed["d0_mm"].as_f64().unwrap(),
        ra["d0_mm"].as_f64().unwrap(),
    );
    assert!(common::rel(x, y) < 1e-9, "d0_mm: {x} vs {y}");
    let (kx, ky) = (
        &mixed["tangential"]["k_table"],
        &ra["tangential"]["k_table"],
    );
    for (x, y) in kx.as_array().unwrap().iter().zip(ky.as_array().unwrap()) {
        assert!(common::rel(x[1].as_f64().unwrap(), y[1].as_f64().unwrap()) < 1e-9);
    }
    let faces = &mixed["roughness"]["faces"];
    assert_eq!(mixed["roughness"]["parameter"], "mixed");
    assert_eq!(faces[0]["key"], "surface.a.ra");
    assert_eq!(faces[1]["key"], "surface.b.rz");
    assert_eq!(faces[1]["rz"].as_f64(), Some(4e-3));
    let sigma_b = 4e-3 / rz_over_sigma_by_hand(0.8);
    assert!(common::rel(faces[1]["sigma_mm"].as_f64().unwrap(), sigma_b) < 1e-12);
    // the band: each end as the all-Ra input with that H and that H's Ra
    let band = mixed["roughness"]["hurst_band"].as_array().unwrap();
    assert_eq!(band.len(), 2);
    for (end, hurst) in band.iter().zip([0.5, 1.0]) {
        assert_eq!(end["hurst"].as_f64(), Some(hurst));
        let at = run(
            &format!("all-ra-{hurst}"),
            &format!("ra = [0.4e-3, {:e}]\nhurst = {hurst:?}\n", ra_of(hurst)),
        );
        close(end, &at, &format!("H = {hurst}"));
    }
    let spread = |v: &serde_json::Value| {
        let b = v["roughness"]["hurst_band"].as_array().unwrap();
        let c = |i: usize| b[i]["c_n"].as_f64().unwrap();
        (c(1) - c(0)).abs() / v["c_n"].as_f64().unwrap()
    };
    let (wide, narrow) = (spread(&mixed), spread(&ra));
    assert!(wide > 0.1 && wide > 5.0 * narrow, "{wide} vs {narrow}");
}

/// A damping study's tangential law: with `backbone = "iwan"` the snippet
/// has no kp_ratio and carries memory, backbone, chi and spike as given; with
/// the kinematic memory alone it keeps kp_ratio. Pasted into a case with a
/// tangential law, `asperity check` accepts both.
#[test]
fn the_iwan_snippet_pastes_into_a_case() {
    let dir = common::scratch("calibrate-iwan");
    let rough = format!("{MATERIALS}[surface]\nmodel = \"roughness\"\na = {{ ra = 0.4e-3 }}\nb = {{ rz = 4e-3 }}\nhurst = 0.8\n{FIT}");
    for (name, keys, lines, absent) in [
        (
            "iwan",
            "memory = \"kinematic\"\nbackbone = \"iwan\"\nchi = -0.5\nspike = 0.1\n",
            "]\nmu = 0.15\nmemory = \"kinematic\"\nbackbone = \"iwan\"\nchi = -0.5\nspike = 0.1\n",
            Some("kp_ratio"),
        ),
        (
            "iwan-defaults",
            "backbone = \"iwan\"\n",
            "]\nmu = 0.15\nbackbone = \"iwan\"\n",
            Some("kp_ratio"),
        ),
        (
            "kinematic-bilinear",
            "memory = \"kinematic\"\n",
            "]\nkp_ratio = 1    # elastic up to the friction cap: Mindlin-GW gives no micro-slip branch\nmu = 0.15\nmemory = \"kinematic\"\n",
            Some("chi"),
        ),
    ] {
        let path = dir.join(format!("{name}.toml"));
        std::fs::write(&path, format!("{rough}[tangential]\nmu = 0.15\n{keys}")).unwrap();
        let out = dir.join(format!("out-{name}"));
        let (code, _, err) = calibrate(&path, &out);
        assert_eq!(code, 0, "{name}: {err}");
        let text = std::fs::read_to_string(out.join("interface.toml")).unwrap();
        let from = text.find("[interface.calibrated_table.tangential]").unwrap();
        let snippet = &text[from..];
        assert!(snippet.ends_with(lines), "{name}: {snippet}");
        if let Some(k) = absent {
            assert!(!snippet.contains(&format!("\n{k} =")), "{name}: {snippet}");
        }
        let fit: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("fit.json")).unwrap()).unwrap();
        assert_eq!(fit["tangential"]["kp_ratio"].is_null(), name != "kinematic-bilinear");
        let pasted = paste_with_tangential(&text);
        let case = common::case_dir(&format!("calibrate-pasted-{name}"), &pasted);
        let (code, _, err) = asperity(&["check", case.to_str().unwrap()]);
        assert_eq!(code, 0, "{name}: {err}\n{pasted}");
    }
}

/// The tangential table from every surface model, elastic-plastic summits
/// included (the contact radius of the CEB area).
#[test]
fn every_surface_model_gives_a_tangential_table() {
    let dir = common::scratch("calibrate-tangential-models");
    let (text, ..) = three_harmonics();
    std::fs::write(dir.join("profile.csv"), text).unwrap();
    let tangential = "[tangential]\nmu = 0.2\nkp_ratio = 0.1\n";
    let hard = MATERIALS.replace("poisson = 0.3 }\n", "poisson = 0.3, hardness = 2000.0 }\n");
    for (name, input) in [
        (
            "gw-ceb",
            format!("{hard}{GW}asperities = \"elastic-plastic\"\n{FIT}{tangential}"),
        ),
        (
            "profile",
            profile("profile.csv", "").replace(FIT, &format!("{FIT}{tangential}")),
        ),
        (
            "rz",
            format!("{MATERIALS}[surface]\nmodel = \"roughness\"\nrz = 6.3e-3\n{FIT}{tangential}"),
        ),
    ] {
        let path = dir.join(format!("{name}.toml"));
        std::fs::write(&path, input).unwrap();
        let out = dir.join(format!("out-{name}"));
        let (code, _, err) = calibrate(&path, &out);
        assert_eq!(code, 0, "{name}: {err}");
        let text = std::fs::read_to_string(out.join("interface.toml")).unwrap();
        assert!(text.contains("kp_ratio = 0.1\nmu = 0.2"), "{name}: {text}");
        let pasted = paste_with_tangential(&text);
        let case = common::case_dir(&format!("calibrate-tangential-{name}"), &pasted);
        let (code, _, err) = asperity(&["check", case.to_str().unwrap()]);
        assert_eq!(code, 0, "{name}: {err}");
    }
}

#[test]
fn bad_roughness_and_tangential_inputs_are_one_error_line_and_exit_2() {
    let rough = |keys: &str| format!("{MATERIALS}[surface]\nmodel = \"roughness\"\n{keys}{FIT}");
    let t = |keys: &str| format!("{}[tangential]\n{keys}", rough("ra = 0.8e-3\n"));
    for (name, input, expect) in [
        (
            "ra-and-rz",
            rough("ra = 0.8e-3\nrz = 6.3e-3\n"),
            "surface.toml: surface.rz: surface.ra and surface.rz both give the same faces: give one of them (which one would hold?); a drawing with Ra on one face and Rz on the other takes a table per face",
        ),
        (
            "face-ra-and-rz",
            rough("a = { ra = 0.4e-3, rz = 4e-3 }\nb = { rz = 4e-3 }\n"),
            "surface.toml: surface.a.rz: face a has both ra and rz",
        ),
        (
            "face-empty",
            rough("a = { ra = 0.4e-3 }\nb = {}\n"),
            "surface.toml: surface.b: missing: face b needs its ra or its rz",
        ),
        (
            "one-face-table",
            rough("a = { ra = 0.4e-3 }\n"),
            "surface.toml: surface.b: missing: with a table per face give both faces",
        ),
        (
            "face-twice-pair",
            rough("ra = 0.4e-3\nb = { rz = 4e-3 }\n"),
            "surface.toml: surface.b: face b is given twice, by surface.ra (as the pair's roughness) and by surface.b",
        ),
        (
            "face-twice-array",
            rough("rz = [4e-3, 4e-3]\na = { ra = 0.4e-3 }\nb = { rz = 4e-3 }\n"),
            "surface.toml: surface.a: face a is given twice, by surface.rz (as surface.rz = [face a, face b])",
        ),
        (
            "face-table-twice",
            rough("[surface.a]\nra = 0.4e-3\n[surface.b]\nrz = 4e-3\n[surface.a]\nrz = 1e-3\n"),
            "surface.toml:10:10: duplicate key `a`: each key and table may be given once",
        ),
        (
            "face-text",
            rough("a = { ra = \"0.4\" }\nb = { rz = 4e-3 }\n"),
            "surface.toml: surface.a.ra: must be a number (mm)",
        ),
        (
            "face-rz-absurd",
            rough("a = { ra = 0.4e-3 }\nb = { rz = 8.0 }\n"),
            "surface.toml: surface.b.rz: 8 mm is far outside any use as Rz",
        ),
        (
            "face-unknown",
            rough("a = { ra = 0.4e-3 }\nb = { rq = 4e-3 }\n"),
            "unknown field `rq`, expected `ra` or `rz`",
        ),
        (
            "iwan-kp-ratio",
            t("mu = 0.2\nbackbone = \"iwan\"\nkp_ratio = 1.0\n"),
            "surface.toml: tangential.kp_ratio: `kp_ratio` belongs to the bilinear backbone",
        ),
        (
            "chi-bilinear",
            t("mu = 0.2\nmemory = \"kinematic\"\nchi = -0.5\n"),
            "surface.toml: tangential.chi: `chi` belongs to backbone = \"iwan\"",
        ),
        (
            "spike-bilinear",
            t("mu = 0.2\nbackbone = \"bilinear\"\nspike = 0.2\n"),
            "surface.toml: tangential.spike: `spike` belongs to backbone = \"iwan\"",
        ),
        (
            "chi-out-of-range",
            t("mu = 0.2\nbackbone = \"iwan\"\nchi = 1.5\n"),
            "surface.toml: tangential.chi: chi = 1.5 must be in [-0.99, 1]",
        ),
        (
            "spike-out-of-range",
            t("mu = 0.2\nbackbone = \"iwan\"\nspike = 1.0\n"),
            "surface.toml: tangential.spike: spike = 1 must be in [0, 1)",
        ),
        (
            "memory-unknown",
            t("mu = 0.2\nmemory = \"masing\"\n"),
            "surface.toml: tangential.memory: unknown \"masing\" (isotropic | kinematic)",
        ),
        (
            "backbone-unknown",
            t("mu = 0.2\nbackbone = \"Iwan\"\n"),
            "surface.toml: tangential.backbone: unknown \"Iwan\" (bilinear | iwan)",
        ),
        ("neither", rough(""), "surface.toml: surface.ra: missing"),
        (
            "ra-zero",
            rough("ra = 0.0\n"),
            "surface.ra: must be a positive finite number",
        ),
        (
            "ra-negative",
            rough("ra = [0.8e-3, -1e-3]\n"),
            "surface.ra: must be a positive finite number",
        ),
        (
            "ra-absurd",
            rough("ra = 2.0\n"),
            "surface.ra: 2 mm is far outside any use as Ra",
        ),
        (
            "rz-absurd",
            rough("rz = 8.0\n"),
            "surface.rz: 8 mm is far outside any use as Rz",
        ),
        (
            "ra-three",
            rough("ra = [1e-3, 2e-3, 3e-3]\n"),
            "surface.ra: must be a number (mm: the pair's roughness) or two numbers",
        ),
        (
            "ra-text",
            rough("ra = \"0.8\"\n"),
            "surface.ra: must be a number",
        ),
        (
            "ra-with-profile",
            profile("tilted.csv", "ra = 0.8e-3\n"),
            "unknown field `ra`",
        ),
        (
            "sigma-with-roughness",
            rough("ra = 0.8e-3\nsigma = 1e-3\n"),
            "unknown field `sigma`",
        ),
        (
            "hurst-high",
            rough("ra = 0.8e-3\nhurst = 1.5\n"),
            "surface.hurst: 1.5 is far outside any use as H",
        ),
        (
            "hurst-zero",
            rough("ra = 0.8e-3\nhurst = 0.0\n"),
            "surface.hurst: must be a positive finite number",
        ),
        (
            "cutoff-huge",
            rough("ra = 0.8e-3\ncutoff = 1e4\n"),
            "surface.cutoff: 1e4 mm is far outside",
        ),
        (
            "band-narrow",
            rough("ra = 0.8e-3\nshort_cutoff = 0.1\n"),
            "surface.short_cutoff: λc = 0.8 mm and λs = 0.1 mm leave a band of 8",
        ),
        (
            "ceb-no-hardness",
            rough("ra = 0.8e-3\nasperities = \"elastic-plastic\"\n"),
            "surface.asperities: \"elastic-plastic\" needs the hardness",
        ),
        (
            "mu-missing",
            t("kp_ratio = 0.5\n"),
            "surface.toml: tangential.mu: missing",
        ),
        (
            "mu-zero",
            t("mu = 0.0\n"),
            "tangential.mu: must be a positive finite number, got 0",
        ),
        (
            "mu-negative",
            t("mu = -0.2\n"),
            "tangential.mu: must be a positive finite number, got -0.2",
        ),
        ("mu-huge", t("mu = 1e3\n"), "tangential.mu: "),
        (
            "kp-ratio",
            t("mu = 0.2\nkp_ratio = 1.5\n"),
            "tangential.kp_ratio: must be in [0, 1], got 1.5",
        ),
        (
            "tangential-unknown",
            t("mu = 0.2\nr = 0.9\n"),
            "unknown field `r`",
        ),
    ] {
        bad(name, &input, expect);
    }
}
