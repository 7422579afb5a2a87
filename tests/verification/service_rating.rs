//! DIN 7190 ratings of fits in service (docs/joints.md, "A rating in
//! service"): the handbook's side follows the run's end state, p = (U_w −
//! ΔU_ϑ − ΔU_ω)/(D_F K) with ΔU_ϑ = D_F (α_A ΔT_A − α_I ΔT_I) and ΔU_ω the
//! spinning disks' (src/verdict/handbook/din7190.rs), so that on a fit the
//! standard's formulas describe (plane stress: free faces, a thin disk;
//! frictionless; an interface layer too stiff to matter, no roughness) the
//! FE side and the handbook side of the same rating agree at every
//! increment, heated and spun, and the fit opens in the run where the
//! rating's opening temperature and speed say.

use crate::common;
use asperity::model::Model;
use asperity::solve::events::Kind;
use asperity::solve::RunResult;
use asperity::verdict::rating::Rating;

/// Radii of the shaft and the hub's rim, the disk's thickness (mm).
const B: f64 = 20.0;
const C: f64 = 50.0;
const H: f64 = 1.0;
/// The radial interference (U = 40 µm on D_F = 40 mm).
const DELTA: f64 = 0.02;
/// A linear interface layer u_N = c_N p: it takes 2 c_N/(D_F K) ≈ 2e-6 of
/// the pressure.
const C_N: f64 = 1e-9;

/// An aluminium hub (r 20 … 50) on a solid steel shaft, both H thick with
/// free faces (plane stress), frictionless, with a DIN 7190 rating of
/// `adhesion` 0.15; `loads` adds the temperatures and the speed.
fn thin_fit(loads: &str) -> String {
    common::case()
        .plane("axisymmetric")
        .block("shaft", [0.0, B], [24], [0.0, H], [1])
        .block("hub", [B, C], [56], [0.0, H], [1])
        .rx([6.0])
        .vertical_interface("fit", "shaft", "hub")
        .material("shaft", 210_000.0, 0.3)
        .with("density", 7850.0)
        .with("expansion", 11.5e-6)
        .material("hub", 70_000.0, 0.33)
        .with("density", 2700.0)
        .with("expansion", 23.5e-6)
        .law("fit", "power", C_N, 1.0)
        .gap(-DELTA)
        .uy("shaft.bottom", 0.0)
        .uy("hub.bottom", 0.0)
        .raw(loads)
        .raw("[[rating]]\nstandard = \"DIN 7190\"\ninterface = \"fit\"\nadhesion = 0.15")
        .solver("increments = 10\nstep_control = \"fixed\"")
        .tolerances(1e-9, 1e-9)
        .raw("[output]")
        .with("event_tolerance", 1e-7)
        .with("vtu", false)
        .build()
}

fn run(text: &str) -> (Model, RunResult, Vec<(f64, Rating)>) {
    let model = common::model(text);
    let r =
        asperity::app::driver::solve(&model, &mut common::Quiet).unwrap_or_else(|e| panic!("{e}"));
    let ratings = asperity::verdict::history(&model, &r)
        .unwrap_or_else(|e| panic!("{e}"))
        .into_iter()
        .map(|(_, t, mut ratings)| (t, ratings.remove(0)))
        .collect();
    (model, r, ratings)
}

/// The check `symbol`'s (FE, handbook) values.
fn sides(rating: &Rating, symbol: &str) -> (f64, f64) {
    let c = (rating.checks.iter())
        .find(|c| c.symbol == symbol)
        .unwrap_or_else(|| panic!("no check {symbol}"));
    (c.fe.unwrap(), c.handbook.unwrap())
}

/// The input `symbol`'s value.
fn input(rating: &Rating, symbol: &str) -> f64 {
    (rating.inputs.iter())
        .find(|i| i.symbol == symbol)
        .unwrap_or_else(|| panic!("no input {symbol}"))
        .value
}

/// At every increment the rating's FE pressure (the interface's normal
/// force over π D_F l_F) is its handbook pressure within `tol` of `scale`:
/// both 0 where the fit is open.
fn sides_agree(ratings: &[(f64, Rating)], scale: f64, tol: f64, x: impl Fn(f64) -> String) {
    for (t, rating) in ratings {
        let (fe, hb) = sides(rating, "p");
        eprintln!(
            "{}: FE {fe:.6} MPa, handbook {hb:.6} ({:.1e})",
            x(*t),
            (fe - hb) / scale
        );
        assert!((fe - hb).abs() < tol * scale, "{}: FE {fe} vs {hb}", x(*t));
    }
}

/// The load factor of the fit's event `kind`.
fn event(r: &RunResult, kind: Kind) -> f64 {
    (r.events.iter())
        .find(|e| e.kind == kind)
        .unwrap_or_else(|| panic!("no {kind:?}"))
        .load_factor
}

/// Heated alike past the rating's opening temperature ΔT_ab = U_w / (D_F
/// (α_A − α_I)) = 83.33 K (plane stress is exact here): the rating's two
/// sides agree within 1e-5 of the pressure at rest at each increment, the
/// handbook's 0 once the fit is open as the FE's is, and the FE's fit
/// first opens at ΔT_ab within 1e-5.
#[test]
fn a_heated_fit_s_rating_follows_the_fe_to_its_opening_temperature() {
    let dt_ab = 2.0 * DELTA / (2.0 * B * 12e-6);
    let top = 1.3 * dt_ab;
    let mut loads = String::new();
    for body in ["shaft", "hub"] {
        loads +=
            &format!("[[temperature]]\nbody = \"{body}\"\nchange = {top:?}\nreference = 20.0\n");
    }
    let (_, r, ratings) = run(&thin_fit(&loads));
    let last = &ratings.last().unwrap().1;
    let rated = input(last, "ΔT_ab");
    assert!(common::rel(rated, dt_ab) < 1e-12, "{rated} vs {dt_ab}");
    let p0 = sides(&ratings[0].1, "p_max").1;
    sides_agree(&ratings, p0, 1e-5, |t| format!("ΔT = {:7.3} K", top * t));
    let at = top * event(&r, Kind::FirstOpening);
    eprintln!(
        "opens at ΔT = {at:.5} K, rated {rated:.5} K ({:.1e})",
        common::rel(at, rated)
    );
    assert!(common::rel(at, rated) < 1e-5, "{at} vs {rated}");
}

/// Heated alike by 40 K (ΔU_ϑ = 19.2 µm of U = 40), then spun up past the
/// rating's opening speed at that temperature, n_ab,ϑ (24 309 rpm): the
/// rating's two sides agree at each increment, hot and spinning, within
/// 1e-5 of the pressure at rest (measured 1.8e-6: the interface layer's
/// share), and the FE's fit is wholly open (its `full_separation`) at
/// n_ab,ϑ within 5e-5 (measured 7.8e-6). Spinning, a free disk is plane
/// stress only on average over its thickness (ε_z varies with r), so the
/// pressure is not quite uniform along the joint and its edge lets go a
/// little earlier: the `first_opening` lies below n_ab,ϑ, within 5e-4
/// (measured 2.1e-4 at H = 1 mm, 5.9e-4 at H = 2 mm).
#[test]
fn a_heated_and_spun_fit_s_rating_follows_the_fe_to_its_opening_speed() {
    const DT: f64 = 40.0;
    const RPM: f64 = 30_000.0;
    let mut loads = String::from(
        "[history]\nheat = [[0, 0], [1, 1], [2, 1]]\nspin = [[0, 0], [1, 0], [2, 1]]\n",
    );
    for body in ["shaft", "hub"] {
        loads += &format!(
            "[[temperature]]\nbody = \"{body}\"\nchange = {DT:?}\nreference = 20.0\nhistory = \"heat\"\n"
        );
    }
    loads += &format!("[speed]\nrpm = {RPM:?}\nhistory = \"spin\"\n");
    let (model, r, ratings) = run(&thin_fit(&loads).replace("increments = 10", "increments = 20"));
    let p0 = sides(&ratings[0].1, "p_max").1;
    let x = |t: f64| {
        let n = model.rpm(t).unwrap();
        format!("t = {t:.2}, {:5.1} K, {n:7.0} rpm", DT * t.min(1.0))
    };
    sides_agree(&ratings, p0, 1e-5, x);
    let last = &ratings.last().unwrap().1;
    let rated = input(last, "n_ab,ϑ");
    let at = model.rpm(event(&r, Kind::FirstOpening)).unwrap();
    let all = model.rpm(event(&r, Kind::FullSeparation)).unwrap();
    eprintln!(
        "opens at {at:.3} rpm, all open at {all:.3}, rated {rated:.3} rpm ({:.1e})",
        common::rel(at, rated)
    );
    assert!(
        rated < RPM && common::rel(all, rated) < 5e-5,
        "{all} vs {rated}"
    );
    assert!(
        at < rated && common::rel(at, rated) < 5e-4,
        "{at} vs {rated}"
    );
    let thermal = input(last, "ΔU_ϑ");
    assert!(
        common::rel(thermal, 2.0 * B * 12e-6 * DT * 1e3) < 1e-12,
        "{thermal}"
    );
    // open at the end: nothing left, the check fails
    let left = (last.checks.iter()).find(|c| c.symbol == "U_w,s").unwrap();
    assert!(
        left.handbook.unwrap() < 0.0 && left.pass == Some(false),
        "{left:?}"
    );
}

/// A hub at a temperature field has no uniform ΔT for the standard: the
/// rating says so in its subject and keeps the handbook side at assembly,
/// p = (U/D_F)/K with K = (1/E_A)((1 + Q_A²)/(1 − Q_A²) + ν_A) + (1 −
/// ν_I)/E_I (solid shaft), typed here; no service check.
#[test]
fn a_fit_rating_with_a_temperature_field_stays_at_assembly_and_says_so() {
    let loads = "[[temperature]]\nbody = \"hub\"\nchange = 30.0\nreference = 20.0\nalong = \"x\"\nprofile = [[20.0, 1.0], [50.0, 0.4]]\n";
    let (_, _, ratings) = run(&thin_fit(loads).replace("increments = 10", "increments = 1"));
    let rating = &ratings.last().unwrap().1;
    assert!(
        rating
            .subject
            .contains("the hub has a temperature field there")
            && rating
                .subject
                .contains("the handbook side the fit at assembly"),
        "{}",
        rating.subject
    );
    let q2 = (B / C).powi(2);
    let k = ((1.0 + q2) / (1.0 - q2) + 0.33) / 70_000.0 + (1.0 - 0.3) / 210_000.0;
    let p = 2.0 * DELTA / (2.0 * B) / k;
    let hb = sides(rating, "p").1;
    assert!(common::rel(hb, p) < 1e-12, "{hb} vs {p}");
    assert!(rating.checks.iter().all(|c| c.symbol != "U_w,s"));
}

/// A DIN 7190 rating of the shipped hub in service (cases/hub-in-service
/// with a `[[rating]]`): its subject names the run's end (the hub and the
/// shaft 60 K warm, 6000 rpm) as the state of both sides; its handbook
/// pressure is DIN 7190's there, typed here with the case's numbers (D_F =
/// 40, D_aA = 100 mm, solid shaft, U = 60 µm, no roughness):
/// ΔU_ϑ = D_F (α_A − α_I) 60 K = 28.8 µm, ΔU_ω = 2 (u_A − u_I) with
/// u = ρ ω² D_F/(32 E) ((3 + ν) D_a² + (1 − ν) D_F²) (D_a = D_aA for the
/// hub, 0 for the solid shaft), p = (U − ΔU_ϑ − ΔU_ω)/(D_F K), and M_t
/// from it; its peak and yield checks at assembly, p = U/(D_F K), the
/// larger; its inputs give the opening speed at 80 °C, √((U − ΔU_ϑ)/c) with
/// ΔU_ω = c ω², and DIN 7190's joining temperature ϑ_A = 20 + (U + 0.001
/// D_F)/(α_A D_F) = 126.38 °C.
#[test]
fn the_shipped_hub_s_rating_in_service_is_din_7190_at_its_end() {
    let path = common::root().join("cases/hub-in-service/case.toml");
    let text = std::fs::read_to_string(&path).unwrap()
        + "\n[[rating]]\nstandard = \"DIN 7190\"\ninterface = \"fit\"\ntorque = 100.0\n";
    let dir = common::case_dir("service-rating", &text);
    let out = common::scratch("service-rating-out").join("out");
    let (code, err) = common::run_asperity(&[
        "run",
        dir.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ]);
    assert_eq!(code, 0, "{err}");
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let rating = &s["ratings"][0];
    let subject = rating["subject"].as_str().unwrap();
    assert!(
        subject.contains(
            "in service, both sides are the run's end (hub ΔT = 60 K, shaft ΔT = 60 K, 6000 rpm)"
        ),
        "{subject}"
    );
    let check = |symbol: &str| {
        (rating["checks"].as_array().unwrap().iter())
            .find(|c| c["symbol"] == symbol)
            .unwrap_or_else(|| panic!("no check {symbol}"))
    };
    let input = |symbol: &str| {
        (rating["inputs"].as_array().unwrap().iter())
            .find(|i| i["symbol"] == symbol)
            .unwrap_or_else(|| panic!("no input {symbol}"))["value"]
            .as_f64()
            .unwrap()
    };
    let (d_f, d_aa, u) = (40.0, 100.0, 0.06);
    let (e_a, nu_a, rho_a, e_i, nu_i, rho_i) = (71_000.0, 0.33, 2810e-12, 210_000.0, 0.3, 7850e-12);
    let q2: f64 = (d_f / d_aa) * (d_f / d_aa);
    let k = ((1.0 + q2) / (1.0 - q2) + nu_a) / e_a + (1.0 - nu_i) / e_i;
    let thermal = d_f * (23.5e-6 - 11.5e-6) * 60.0;
    let w = 6000.0 * std::f64::consts::PI / 30.0;
    let growth = |rho: f64, e: f64, nu: f64, d_a: f64| {
        rho * w * w * d_f / (32.0 * e) * ((3.0 + nu) * d_a * d_a + (1.0 - nu) * d_f * d_f)
    };
    let spin = 2.0 * (growth(rho_a, e_a, nu_a, d_aa) - growth(rho_i, e_i, nu_i, 0.0));
    let p = (u - thermal - spin) / (d_f * k);
    let p_assembly = u / (d_f * k);
    eprintln!("handbook in service: ΔU_ϑ = {thermal} mm, ΔU_ω = {spin} mm, p = {p} MPa (assembly {p_assembly})");
    let got = |symbol: &str| check(symbol)["handbook"].as_f64().unwrap();
    assert!(common::rel(got("p"), p) < 1e-12, "{} vs {p}", got("p"));
    let m_t = p * std::f64::consts::PI * d_f * d_f * 20.0 * 0.15 / 2.0 * 1e-3;
    assert!(
        common::rel(got("M_t"), m_t) < 1e-12,
        "{} vs {m_t}",
        got("M_t")
    );
    assert!(common::rel(got("p_max"), p_assembly) < 1e-12);
    assert!(common::rel(got("σ_v,I"), p_assembly) < 1e-12); // a solid shaft: σ_v = p
    assert!(check("σ_v,A")["note"]
        .as_str()
        .unwrap()
        .contains("handbook at assembly"));
    assert!(common::rel(input("ΔU_ϑ"), thermal * 1e3) < 1e-12);
    assert!(common::rel(input("ΔU_ω"), spin * 1e3) < 1e-12);
    let n_ab = ((u - thermal) / (spin / (w * w))).sqrt() * 30.0 / std::f64::consts::PI;
    assert!(
        common::rel(input("n_ab,ϑ"), n_ab) < 1e-12,
        "{} vs {n_ab}",
        input("n_ab,ϑ")
    );
    let joining = 20.0 + (0.06 + 0.04) / (23.5e-6 * 40.0);
    assert!(
        common::rel(input("ϑ_A"), joining) < 1e-9,
        "{} vs {joining}",
        input("ϑ_A")
    );
}
