//! `asperity calibrate`'s bad inputs: one `error:` line naming file and key,
//! exit code 2, no output folder (nor a temporary folder beside it).

use crate::calibrate::{asperity, calibrate, FIT, GW, MATERIALS};
use crate::common;

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
    // a rough line profile (heights of ±5 µm)
    let rough: String = (0..400)
        .map(|i| {
            format!(
                "{}\n",
                1e-3 * ((i * 37 % 11) - 5) as f64 + 4e-4 * ((i * 13 % 7) - 3) as f64
            )
        })
        .collect();
    std::fs::write(dir.join("rough.csv"), rough).unwrap();
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
pub fn profile(file: &str, extra: &str) -> String {
    format!("{MATERIALS}[surface]\nmodel = \"profile\"\nfile = \"{file}\"\nsampling = 1e-3\n{extra}{FIT}")
}

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
    // a summit value no key gives, refused at the keys that made it (it was
    // named as itself, "β from the roughness", "η of the profile", until
    // issue 42)
    bad(
        "derived-density-of-a-profile",
        &profile("rough.csv", "").replace("sampling = 1e-3", "sampling = 1e-9"),
        "surface.toml: surface.file, surface.sampling: 9.5107e16 /mm² for η, the summit density, derived from the heights of",
    );
    bad(
        "derived-radius-of-a-roughness",
        &format!("{MATERIALS}[surface]\nmodel = \"roughness\"\nra = 0.5\ncutoff = 1e-3\nshort_cutoff = 1e-6\n{FIT}"),
        "surface.toml: surface.ra, surface.cutoff, surface.short_cutoff: 8.2653e-12 mm for β, the summit radius, derived from them with H = 0.8 assumed, is far outside any use",
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
