//! Tangential interface (paper sections 2.2, 2.4-2.6): a block sliding on a
//! compliant joint, the Fig. 7 punch cases against the paper's conclusions 3-6
//! (section 6), and the two friction schemes reaching the same answer.

use crate::common;
use asperity::app::driver::{self, RunOptions};
use asperity::model::Model;
use asperity::solve::{Increment, Observer, RunResult, State};

struct Record(Vec<(f64, f64)>);
impl Observer for Record {
    fn increment(&mut self, _: &Model, s: &State, inc: &Increment) -> asperity::Result<()> {
        self.0.push((inc.load_factor, s.prescribed_reaction));
        Ok(())
    }
}

#[test]
fn a_block_slides_at_mu_m_times_the_normal_load_once_hardening_saturates() {
    // upper block pressed by p λ and dragged sideways by δ λ on its left side
    let (p, w, t, mu, beta) = (100.0, 10.0, 1.0, 0.2, 0.3);
    let text = common::case()
        .plane("stress")
        .thickness(t)
        .block("block", [0.0, w], [4], [0.0, 4.0], [2])
        .block("base", [0.0, w], [4], [-4.0, 0.0], [2])
        .interface("joint", "block", "base")
        .material("block", 206000.0, 0.3)
        .material("base", 206000.0, 0.3)
        .law("joint", "power", 0.001, 0.5)
        .tangential("joint", 0.9, 0.5, 0.05, mu)
        .with("beta", beta)
        .with("n", 275.0)
        .fixed("base.bottom")
        .ux("block.left", 0.2)
        .pressure("block.top", p)
        .solver("increments = 50")
        .build();
    let model = common::model(&text);
    let mut rec = Record(Vec::new());
    asperity::app::driver::solve(&model, &mut rec).unwrap_or_else(|e| panic!("{e}"));
    let ratios: Vec<f64> = rec
        .0
        .iter()
        .map(|(l, f)| f.abs() / (l * p * w * t))
        .collect();
    let last = *ratios.last().unwrap();
    eprintln!("friction force / normal load per increment: {ratios:.4?}");
    assert!(
        (last - mu).abs() < 1e-3 * mu,
        "slides at {last}, μ_m = {mu}"
    );
    // it first slips near β μ_m and hardens monotonically toward μ_m
    assert!(ratios.iter().all(|r| *r <= mu * (1.0 + 1e-9)));
    assert!(
        ratios[0] < 0.9 * mu,
        "no slip hardening visible: {:?}",
        &ratios[..4]
    );
    assert!(
        ratios.windows(2).all(|w| w[1] >= w[0] - 1e-9),
        "friction softened: {ratios:?}"
    );
}

fn run(tag: &str, case: &str, scheme: Option<&str>) -> (std::path::PathBuf, RunResult) {
    let src = common::root().join("cases").join(case).join("case.toml");
    let mut text = std::fs::read_to_string(&src).unwrap();
    if let Some(s) = scheme {
        text = text.replace("scheme = \"return-mapping\"", &format!("scheme = \"{s}\""));
    }
    if tag == "schemes" {
        // the schemes' tangents compared by plain Newton's iterations: the
        // interface loop solves the interface law exactly whatever the
        // scheme's tangent (both take 66 iterations on punch-friction-a)
        text = common::with_interface_loop(&text, false);
    }
    let path = common::case_dir(&format!("friction-{tag}-{case}-{scheme:?}"), &text);
    let out = path.parent().unwrap().join("out");
    let opts = RunOptions {
        out: Some(out.clone()),
        quiet: true,
        ..Default::default()
    };
    let (_, _, r) = driver::run(&path, &opts).unwrap_or_else(|e| panic!("{case}: {e}"));
    (out, r)
}

/// (x, p_n, p_t) per pair of increment `i`.
fn interface(out: &std::path::Path, i: usize) -> Vec<(f64, f64, f64)> {
    let text = std::fs::read_to_string(out.join(format!("interface/{i:04}.csv"))).unwrap();
    let mut lines = text.lines();
    let head: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |n: &str| head.iter().position(|h| *h == n).unwrap();
    let (cx, cp, ct) = (col("x_mm"), col("p_n_mpa"), col("p_t_mpa"));
    lines
        .map(|l| {
            let v: Vec<&str> = l.split(',').collect();
            (
                v[cx].parse().unwrap(),
                v[cp].parse().unwrap(),
                v[ct].parse().unwrap(),
            )
        })
        .collect()
}

#[test]
fn the_paper_conclusions_3_to_6_on_the_fig_7_cases() {
    let (out0, frictionless) = run("c36", "punch-plane-stress", None);
    let (out_a, a) = run("c36", "punch-friction-a", None);
    let (out_b, b) = run("c36", "punch-friction-b", None);
    let (out_c, c) = run("c36", "punch-friction-c", None);
    let n = a.increments.len();
    // 4: with tangential compliance the foundation yields at a smaller load
    let fy0 = frictionless.first_yield.unwrap().total_load_kn;
    for (name, r) in [("a", &a), ("b", &b), ("c", &c)] {
        let fy = r.first_yield.as_ref().unwrap().total_load_kn;
        eprintln!("first yield {name}: {fy:.3} kN (frictionless {fy0:.3} kN)");
        assert!(fy < fy0, "{name}: {fy} vs {fy0}");
    }
    // 3 and 5: the elastic-plastic tangential compliance (k_T^p = 0.05 k_T^e, b and c)
    // lowers the pressure at the punch edge and its gradient there, against the
    // stiff tangential interface (k_T^p = k_T^e, a), at every load before the last
    for i in 1..n {
        let (pa, pb, pc) = (
            interface(&out_a, i),
            interface(&out_b, i),
            interface(&out_c, i),
        );
        let edge = |v: &[(f64, f64, f64)]| v[v.len() - 1].1;
        let grad = |v: &[(f64, f64, f64)]| {
            let (q, r) = (v[v.len() - 2], v[v.len() - 1]);
            (r.1 - q.1) / (r.0 - q.0)
        };
        assert!(
            edge(&pb) < edge(&pa) && edge(&pc) < edge(&pa),
            "increment {i}: edge pressure"
        );
        assert!(
            grad(&pb) < grad(&pa) && grad(&pc) < grad(&pa),
            "increment {i}: edge gradient"
        );
    }
    // ... but not against frictionless contact: there friction raises the edge
    // pressure in this model (docs/verification.md, "Friction: the Fig. 7 cases"); checked so that a change is noticed
    let mid = n / 2;
    let (p0, pa) = (interface(&out0, mid), interface(&out_a, mid));
    assert!(pa[pa.len() - 1].1 > p0[p0.len() - 1].1);
    // elastic-plastic friction lowers the shear force (paper, section 5): the sum
    // of |p_T| over the interface is smaller for b than for a at every increment
    for i in 1..=n {
        let total =
            |out: &std::path::Path| interface(out, i).iter().map(|v| v.2.abs()).sum::<f64>();
        assert!(total(&out_b) < total(&out_a), "increment {i}");
    }
    // 6: in the plastically deformed region the shear tractions fall as the load
    // grows: below their peak over the history at most nodes of the plastic zone
    // (the edge pair is excluded: its pressure, and so its cap μ p_N, keeps rising)
    for (name, out) in [("a", &out_a), ("b", &out_b), ("c", &out_c)] {
        let last = interface(out, n);
        let plastic: Vec<usize> = (0..last.len() - 1).filter(|&k| last[k].0 > 15.0).collect();
        let falling = plastic
            .iter()
            .filter(|&&k| {
                let peak = (1..=n)
                    .map(|i| interface(out, i)[k].2.abs())
                    .fold(0.0, f64::max);
                last[k].2.abs() < 0.9 * peak
            })
            .count();
        eprintln!(
            "{name}: shear fell by > 10% from its peak at {falling} of {} plastic-zone nodes",
            plastic.len()
        );
        assert!(
            2 * falling > plastic.len(),
            "{name}: {falling} of {}",
            plastic.len()
        );
    }
}

#[test]
fn the_two_friction_schemes_reach_the_same_answer() {
    for case in ["punch-friction-a", "punch-friction-b", "punch-friction-c"] {
        let (_, rm) = run("schemes", case, None);
        let (_, sm) = run("schemes", case, Some("stiffness-modification"));
        let (x, y) = (
            rm.increments.last().unwrap().measures,
            sm.increments.last().unwrap().measures,
        );
        let d = common::rel(x.center_displacement, y.center_displacement);
        eprintln!(
            "{case}: iterations {} (return mapping) vs {} (stiffness modification), Δ = {d:.1e}",
            rm.stats.iterations, sm.stats.iterations
        );
        // identical increments give identical answers; a cutback changes the
        // load path of the plastic foundation by a few 1e-6
        let tol = if rm.cutbacks + sm.cutbacks == 0 {
            1e-8
        } else {
            1e-5
        };
        assert!(
            d < tol,
            "{case}: {} vs {}",
            x.center_displacement,
            y.center_displacement
        );
        assert!(sm.stats.iterations > rm.stats.iterations);
    }
}
