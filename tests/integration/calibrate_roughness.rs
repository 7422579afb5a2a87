//! `asperity calibrate` on roughness inputs (Ra, Rz, one per face, a Hurst
//! band) and tangential laws (every surface model, the Iwan backbone): the
//! snippets pasted into a case with a tangential law and checked.

use crate::calibrate::{asperity, calibrate, three_harmonics, FIT, GW, MATERIALS};
use crate::calibrate_bad::profile;
use crate::common;

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
