//! The kinematic (Masing) memory and the Iwan backbone through the whole
//! program (issue 28, docs/theory.md "Slip memory"): a joint of identical
//! springs (every node of both bodies prescribed, as in cycles.rs) cycled
//! at a displacement amplitude a = x φ.
//!
//! * kinematic memory, Iwan density χ = −0.5: every cycle, the first
//!   included, dissipates D = 4 k φ² (1+χ) x^{χ+3} / ((χ+2)(χ+3)) × L, the
//!   loop's force amplitude is F_a = k φ (x − x^{χ+2}/(χ+2)) × L and its loss
//!   factor D / (π F_a a);
//! * the isotropic memory with the same backbone: the second cycle
//!   dissipates less than the first (its limit grew), the kinematic one
//!   the same;
//! * the shipped slideway-damping against the uniform joint at each steady
//!   cycle's slip amplitude, its exponent against the slip amplitude 3 + χ,
//!   its running dissipation never falling, also while its preload is
//!   removed (issue 42).

use crate::common;

const C_N: f64 = 0.001;
const M: f64 = 0.5;
const R: f64 = 0.9;
const S: f64 = 0.5;
const MU: f64 = 0.2;
const CHI: f64 = -0.5;
/// Interface length (plane strain, thickness 1), mm.
const L: f64 = 10.0;

/// The joint of identical springs with an Iwan backbone and `memory`.
fn uniform(memory: &str, d: f64, a: f64, increments: usize) -> String {
    common::case()
        .plane("strain")
        .block("block", [0.0, L], [4], [0.0, 2.0], [1])
        .block("base", [0.0, L], [4], [-2.0, 0.0], [1])
        .interface("joint", "block", "base")
        .material("block", 210000.0, 0.3)
        .material("base", 210000.0, 0.3)
        .law("joint", "power", C_N, M)
        .weights("lumped")
        .raw("[interface.joint.tangential]")
        .with("r", R)
        .with("s", S)
        .with("mu", MU)
        .with("memory", memory)
        .with("backbone", "iwan")
        .with("chi", CHI)
        .histories(&[
            ("preload", "[[0, 0], [1, 1]]"),
            ("drag", "[[1, 0], [2, 1], [3, -1], [4, 1], [5, -1], [6, 1]]"),
        ])
        .fixed("base.all")
        .uy("block.all", -d)
        .history("preload")
        .ux("block.all", a)
        .history("drag")
        .solver(&format!("increments = {increments}"))
        .no_vtu()
        .build()
}

/// Runs the joint; cycles.csv's path.
fn run(name: &str, memory: &str, d: f64, a: f64, increments: usize) -> std::path::PathBuf {
    let case = common::case_dir(name, &uniform(memory, d, a, increments));
    let out = case.parent().unwrap().join("out");
    common::run_ok(case.parent().unwrap(), &out);
    out.join("cycles.csv")
}

#[test]
fn masing_loops_of_an_iwan_joint_match_the_closed_form_every_cycle() {
    let d = 0.01;
    let p = (d / C_N).powf(1.0 / M); // 100 MPa
    let k = 1000.0 * p.powf(S) / R;
    let f1 = 1.0 - 1.0 / (CHI + 2.0);
    let phi = MU * p / (k * f1);
    let x = 0.5;
    let a = x * phi;
    let closed =
        L * 4.0 * k * phi * phi * (1.0 + CHI) * x.powf(CHI + 3.0) / ((CHI + 2.0) * (CHI + 3.0));
    let f_a = L * k * phi * (x - x.powf(CHI + 2.0) / (CHI + 2.0));
    let eta = closed / (std::f64::consts::PI * f_a * a);

    let cycles = run("memory-kinematic", "kinematic", d, a, 200);
    let dis = common::csv_column(&cycles, "dissipation_nmm");
    let work = common::csv_column(&cycles, "work_nmm");
    let fa = common::csv_column(&cycles, "force_amplitude_n");
    let loss = common::csv_column(&cycles, "loss_factor");
    assert_eq!(dis.len(), 2, "two closed cycles");
    for c in 0..2 {
        eprintln!(
            "cycle {}: D {:.6e} (closed form {closed:.6e}), F_a {:.6} N ({f_a:.6}), η {:.6} ({eta:.6})",
            c + 1,
            dis[c],
            fa[c],
            loss[c]
        );
        // the trapezoid rule over 200 steps a half-cycle
        assert!(common::rel(dis[c], closed) < 1e-3, "cycle {c}: D");
        assert!(common::rel(work[c], dis[c]) < 1e-9, "cycle {c}: W = D");
        assert!(common::rel(fa[c], f_a) < 1e-9, "cycle {c}: F_a");
        assert!(common::rel(loss[c], eta) < 1e-3, "cycle {c}: η");
    }
    assert!(
        common::rel(dis[0], dis[1]) < 1e-9,
        "steady from the first cycle"
    );

    let iso = run("memory-isotropic", "isotropic", d, a, 200);
    let dis_iso = common::csv_column(&iso, "dissipation_nmm");
    eprintln!("isotropic: D {dis_iso:?}");
    assert!(
        dis_iso[1] < (1.0 - 1e-3) * dis_iso[0],
        "the isotropic limit grew"
    );
}

/// The shipped `slideway-damping` against a uniform joint: 60 mm of
/// springs at the mean pressure p = 20 MPa, each an Iwan point (χ = −0.5).
/// Per steady cycle (the last of each block): D against the closed form at
/// the cycle's slip amplitude u_a = x φ (measured within 0.4-0.8 %; the
/// accounting before issue 42, the shear on u_T − p_T/k_T^e, was 0.8-2.5 %
/// above: the k_T^e of the slider's ends follows their pressure, which the
/// shear's moment changes, and that term was counted as dissipation), and
/// the log-log slope of D against u_a, 3 + χ (measured 2.498); the fitted
/// exponent against F_a against the closed form's at the same force ratios
/// r = F_a / (μ p A) = F(x)/F(1) (about 3.07, not 3 + χ: docs/joints.md).
/// At the same force ratio the run is 7-9 % below the uniform joint (its
/// ends are softer: they carry more shear and less pressure). The running
/// dissipation in joints.csv never falls (before issue 42 it fell in 130
/// of the 291 increments).
#[test]
fn the_shipped_slideway_damping_follows_the_uniform_joint() {
    let out = common::scratch("memory-slideway").join("out");
    common::run_ok(&common::root().join("cases/slideway-damping"), &out);
    never_falls(&out.join("joints.csv"), 0.0);
    let (p, mu, len, r, s) = (20.0, 0.15, 60.0, 0.9, 0.5);
    let k = 1000.0 * f64::powf(p, s) / r;
    let q = CHI + 2.0;
    let f = |x: f64| x - x.powf(q) / q;
    let f1 = f(1.0);
    let phi = mu * p / (k * f1);
    // the uniform joint's D at x = u_a / φ
    let of_x =
        |x: f64| len * 4.0 * k * phi * phi * (1.0 + CHI) * x.powf(CHI + 3.0) / (q * (CHI + 3.0));
    let closed = |ratio: f64| {
        // F(x)/F(1) = ratio, F increasing on [0, 1]
        let (mut lo, mut hi) = (0.0, 1.0);
        for _ in 0..100 {
            let mid = 0.5 * (lo + hi);
            if f(mid) / f1 < ratio {
                lo = mid
            } else {
                hi = mid
            }
        }
        of_x(0.5 * (lo + hi))
    };
    let damping = out.join("damping.csv");
    let fa = common::csv_column(&damping, "force_amplitude_n");
    let ua = common::csv_column(&damping, "slip_amplitude_mm");
    let dis = common::csv_column(&damping, "dissipation_nmm");
    let text = std::fs::read_to_string(&damping).unwrap();
    let head: Vec<&str> = text.lines().next().unwrap().split(',').collect();
    let kl = head.iter().position(|h| *h == "last_in_block").unwrap();
    let steady: Vec<usize> = text
        .lines()
        .skip(1)
        .enumerate()
        .filter(|(_, l)| l.split(',').nth(kl) == Some("true"))
        .map(|(i, _)| i)
        .collect();
    assert_eq!(steady.len(), 5, "five blocks");
    let (mut xs, mut us, mut ys, mut yc) = (vec![], vec![], vec![], vec![]);
    for &i in &steady {
        let ratio = fa[i] / (mu * p * len);
        let (d, du) = (closed(ratio), of_x(ua[i] / phi));
        eprintln!(
            "F_a/(μpA) = {ratio:.3}, u_a/φ = {:.3}: D {:.4e} N·mm, uniform joint at u_a {du:.4e} \
             ({:+.2} %), at F_a {d:.4e} ({:+.1} %)",
            ua[i] / phi,
            dis[i],
            100.0 * (dis[i] / du - 1.0),
            100.0 * (dis[i] / d - 1.0)
        );
        assert!(common::rel(dis[i], du) < 0.015, "r = {ratio}");
        xs.push(fa[i].ln());
        us.push(ua[i].ln());
        ys.push(dis[i].ln());
        yc.push(d.ln());
    }
    // least-squares slopes of log y against log x
    let fit = |x: &[f64], y: &[f64]| {
        let n = x.len() as f64;
        let (mx, my) = (x.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
        let sxy: f64 = x.iter().zip(y).map(|(x, y)| (x - mx) * (y - my)).sum();
        let sxx: f64 = x.iter().map(|x| (x - mx) * (x - mx)).sum();
        sxy / sxx
    };
    let slope = |y: &[f64]| fit(&xs, y);
    // against the slip amplitude the Iwan exponent itself
    let q_u = fit(&us, &ys);
    eprintln!("exponent against u_a {q_u:.4} (3 + χ = {})", 3.0 + CHI);
    assert!((q_u - (3.0 + CHI)).abs() < 0.02, "{q_u}");
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let q_fe = summary["damping"][0]["exponent"].as_f64().unwrap();
    assert!(
        (q_fe - slope(&ys)).abs() < 1e-9,
        "the summary's fit is the steady cycles'"
    );
    eprintln!("exponent {q_fe:.3}, uniform joint {:.3}", slope(&yc));
    assert!((q_fe - slope(&yc)).abs() < 0.1);
    // steady: the second and third cycles of the first block alike
    assert!(common::rel(dis[1], dis[2]) < 1e-6);
}

/// Asserts joints.csv's `dissipation_nmm` never falls (after pseudo-time
/// `from`).
fn never_falls(joints: &std::path::Path, from: f64) {
    let t = common::csv_column(joints, "time");
    let d = common::csv_column(joints, "dissipation_nmm");
    for k in 1..d.len() {
        assert!(
            t[k] <= from || d[k] >= d[k - 1],
            "{}: D falls at t = {}: {} → {}",
            joints.display(),
            t[k],
            d[k - 1],
            d[k]
        );
    }
}

/// The shipped slideway-damping with its preload removed at the end (20 →
/// 1 MPa over t = 29 … 30, the drive at 0): the shear its cycles locked in
/// slides as the elements' ranges η φ shrink, and the running dissipation
/// grows. Before issue 42 it fell at t = 29.1 … 29.6.
#[test]
fn the_slideway_dissipates_while_its_preload_is_removed() {
    let shipped = common::root().join("cases/slideway-damping/case.toml");
    let text = std::fs::read_to_string(shipped).unwrap();
    let old = "preload = [[0.0, 0.0], [1.0, 1.0]]";
    assert!(text.contains(old));
    let text = text.replace(
        old,
        "preload = [[0.0, 0.0], [1.0, 1.0], [29.0, 1.0], [30.0, 0.05]]",
    );
    let case = common::case_dir("memory-slideway-unload", &text);
    let out = case.parent().unwrap().join("out");
    common::run_ok(case.parent().unwrap(), &out);
    let joints = out.join("joints.csv");
    never_falls(&joints, 0.0);
    let (t, d) = (
        common::csv_column(&joints, "time"),
        common::csv_column(&joints, "dissipation_nmm"),
    );
    assert_eq!(*t.last().unwrap(), 30.0);
    let at = |x: f64| d[t.iter().position(|&v| (v - x).abs() < 1e-9).unwrap()];
    eprintln!("D {:.6e} at t = 29, {:.6e} at t = 30", at(29.0), at(30.0));
    assert!(at(30.0) > at(29.0) * (1.0 + 1e-3));
}
