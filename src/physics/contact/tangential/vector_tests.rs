//! The vector law (issue 26): along one axis the scalar law, tangents
//! against finite differences after 2-D histories, isotropy, the state's
//! packing and check. Closed-form 2-D paths and the Iwan discretization's
//! error: `vector_paths_tests`.

use super::jenkins::Stretch2;
use super::vector::VectorEval;
use super::*;
use crate::numbers::fd;

/// p(u_N) = (u/c)², as in the scalar law's tests.
pub(super) fn pressure(un: f64) -> (f64, f64) {
    let c = 0.001;
    ((un / c).powi(2), 2.0 * un / (c * c))
}

/// u_N of pressure p.
pub(super) fn approach(p: f64) -> f64 {
    0.001 * p.sqrt()
}

/// The first-loading u_T at which p_T reaches μ p_N (φ of the kinematic
/// memory; k_T^p = 0: the yield slip).
pub(super) fn reach(law: &TangentialLaw, p: f64) -> f64 {
    law.mu * p * law.density().big_c / law.elastic_stiffness(p).0
}

/// A deterministic stream of uniform numbers in [0, 1).
pub(super) struct Lcg(pub u64);

impl Lcg {
    pub fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn iwan(memory: Memory, chi: f64, spike: f64) -> TangentialLaw {
    TangentialLaw::new(0.9, 0.5, 1.0, 0.2, 1.0, 0.0, 0.625)
        .unwrap()
        .with_memory(memory, Backbone::Iwan { chi, spike })
        .unwrap()
}

fn kinematic(kp: f64) -> TangentialLaw {
    TangentialLaw::new(0.9, 0.5, kp, 0.2, 1.0, 0.0, 0.625)
        .unwrap()
        .with_memory(Memory::Kinematic, Backbone::Bilinear)
        .unwrap()
}

fn table(kp: f64, beta: f64) -> TangentialLaw {
    let rows: Vec<(f64, f64)> = [20.0, 35.0, 60.0, 100.0, 150.0]
        .iter()
        .map(|&p: &f64| (p, p.sqrt() / 0.9))
        .collect();
    TangentialLaw::with_k_table(&rows, kp, 0.2, beta, 275.0, 0.625).unwrap()
}

/// Every law whose vector form is exact: the isotropic memory with both
/// backbones, slip hardening, k_tables, and the bilinear kinematic memory.
pub(super) fn exact_laws() -> Vec<TangentialLaw> {
    vec![
        TangentialLaw::new(0.9, 0.5, 1.0, 0.2, 1.0, 275.0, 0.625).unwrap(),
        TangentialLaw::new(0.9, 0.5, 0.05, 0.2, 1.0, 275.0, 0.625).unwrap(),
        TangentialLaw::new(0.9, 0.5, 0.05, 0.2, 0.2, 275.0, 0.625).unwrap(),
        TangentialLaw::new(0.9, 0.0, 0.0, 0.3, 0.5, 100.0, 0.5).unwrap(),
        table(1.0, 1.0),
        table(0.05, 0.2),
        iwan(Memory::Isotropic, 0.0, 0.0),
        iwan(Memory::Isotropic, -0.5, 0.2),
        kinematic(0.05),
        kinematic(0.3),
        kinematic(1.0),
        kinematic(0.0),
        table(0.3, 1.0)
            .with_memory(Memory::Kinematic, Backbone::Bilinear)
            .unwrap(),
    ]
}

/// An irregular history of (p_N, k_N, s): a random walk of s with drifts
/// into macro-slip and reversals, the pressure wandering in 16 ... 256 MPa
/// with drops, and a few open steps (p_N = 0).
fn history(law: &TangentialLaw, seed: u64, steps: usize) -> Vec<(f64, f64, f64)> {
    let mut rng = Lcg(seed);
    let f = reach(law, 150.0);
    let (mut s, mut un, mut drift) = (0.0, approach(150.0), 1.0);
    (0..steps)
        .map(|i| {
            if rng.next() < 0.08 {
                drift = -drift;
            }
            s += f * (0.3 * drift + 0.6 * (rng.next() - 0.5)) * if i % 50 < 10 { 1.0 } else { 0.3 };
            un = (un + 0.0015 * (rng.next() - 0.5)).clamp(0.004, 0.016);
            if rng.next() < 0.02 {
                return (0.0, 0.0, s);
            }
            let (p, kn) = pressure(un);
            (p, kn, s)
        })
        .collect()
}

#[test]
fn one_component_reproduces_the_scalar_law_to_round_off() {
    for law in exact_laws() {
        let mut worst = 0.0f64;
        for seed in [3, 11, 29] {
            let hist = history(&law, seed, 600);
            for axis in [0, 1] {
                let (mut s1, mut s2) = (SlipState::default(), SlipState2::default());
                let mut seen = Vec::new();
                for (step, &(p, kn, u)) in hist.iter().enumerate() {
                    let mut u2 = [0.0; 2];
                    u2[axis] = u;
                    let a = law.eval(p, kn, u, &s1);
                    let b = law.eval_vector(p, kn, u2, &s2);
                    let other = 1 - axis;
                    let (k, _) = law.elastic_stiffness(p.max(1.0));
                    let cap = law.mu * p.max(1.0);
                    let rel = [
                        (a.p_t - b.p_t[axis]).abs() / cap,
                        (a.d_ut - b.d_ut[axis][axis]).abs() / k,
                        (a.d_un - b.d_un[axis]).abs()
                            / (a.d_un.abs() + kn * law.mu).max(f64::MIN_POSITIVE),
                        // sums over the history: relative to their size
                        (a.state.u_p - b.state.u_p[axis]).abs() / a.state.u_p.abs().max(cap / k),
                        (a.state.kappa - b.state.kappa).abs() / a.state.kappa.max(cap / k),
                    ];
                    let w = rel.iter().fold(0.0f64, |m, &x| m.max(x));
                    worst = worst.max(w);
                    // the isotropic memory takes the same operations: equal bits
                    let bound = if law.memory == Memory::Isotropic {
                        0.0
                    } else {
                        1e-12
                    };
                    assert!(
                        w <= bound,
                        "{law:?} seed {seed} axis {axis} step {step}: {rel:?}\n{a:?}\n{b:?}"
                    );
                    assert_eq!(a.slip, b.slip, "{law:?} step {step}");
                    assert_eq!(a.mu_f, b.mu_f);
                    // nothing across the axis
                    assert_eq!(b.p_t[other], 0.0);
                    assert_eq!(b.d_ut[axis][other], 0.0);
                    assert_eq!(b.d_ut[other][axis], 0.0);
                    assert_eq!(b.d_un[other], 0.0);
                    assert_eq!(b.state.u_p[other], 0.0);
                    seen.push(a.slip);
                    s1 = a.state;
                    s2 = b.state;
                }
                assert!(seen.contains(&Slip::Stick), "{law:?}: {seen:?}");
                if law.kp_ratio > 0.0 {
                    assert!(seen.contains(&Slip::MacroSlip), "{law:?}: {seen:?}");
                }
                if law.kp_ratio < 1.0 || matches!(law.backbone, Backbone::Iwan { .. }) {
                    assert!(seen.contains(&Slip::MicroSlip), "{law:?}: {seen:?}");
                }
            }
        }
        eprintln!(
            "{:?} {:?}: largest relative difference vector - scalar {worst:e}",
            law.memory, law.backbone
        );
    }
}

/// The exact laws and two Iwan densities under the kinematic memory.
pub(super) fn all_laws() -> Vec<TangentialLaw> {
    let mut v = exact_laws();
    v.push(iwan(Memory::Kinematic, 0.0, 0.0));
    v.push(iwan(Memory::Kinematic, -0.5, 0.1));
    v
}

/// Steps of (p_N, u_T).
pub(super) type Path = Vec<(f64, [f64; 2])>;

/// `n` steps of (p_N, u_T) from `a` to `b` at pressure p, `b` included.
fn line(p: f64, a: [f64; 2], b: [f64; 2], n: usize) -> Path {
    (1..=n)
        .map(|i| {
            let s = i as f64 / n as f64;
            (p, [a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1])])
        })
        .collect()
}

/// 2-D histories in units of f: a circle, a figure-eight, a reversal at an
/// angle, a pressure drop while slipping across the earlier slip.
pub(super) fn paths(f: f64) -> Vec<(&'static str, Path)> {
    use std::f64::consts::TAU;
    let p = 150.0;
    let mut circle = line(p, [0.0; 2], [0.8 * f, 0.0], 10);
    circle.extend((1..=75).map(|i| {
        let t = 1.25 * TAU * i as f64 / 75.0;
        (p, [0.8 * f * t.cos(), 0.8 * f * t.sin()])
    }));
    let eight = (1..=80)
        .map(|i| {
            let t = TAU * i as f64 / 80.0;
            (p, [0.9 * f * t.sin(), 0.9 * f * t.sin() * t.cos()])
        })
        .collect();
    let (c, s) = (0.5f64.cos(), 0.5f64.sin());
    let mut reversal = line(p, [0.0; 2], [1.2 * f * c, 1.2 * f * s], 20);
    reversal.extend(line(
        p,
        [1.2 * f * c, 1.2 * f * s],
        [-0.5 * f * c, -0.5 * f * s],
        20,
    ));
    let mut drop = line(200.0, [0.0; 2], [0.7 * f, 0.0], 10);
    drop.extend((1..=10).map(|i| {
        let s = i as f64 / 10.0;
        (200.0 - 150.0 * s, [0.7 * f, 0.3 * f * s])
    }));
    vec![
        ("circle", circle),
        ("figure-eight", eight),
        ("reversal", reversal),
        ("pressure drop", drop),
    ]
}

/// Drives a point through (p_N, u_T) steps; the committed state after each.
pub(super) fn drive2(
    law: &TangentialLaw,
    path: &[(f64, [f64; 2])],
    st: &mut SlipState2,
) -> Vec<VectorEval> {
    path.iter()
        .map(|&(p, u)| {
            let ev = law.eval_vector(p, 0.0, u, st);
            *st = ev.state;
            ev
        })
        .collect()
}

#[test]
fn vector_tangents_match_finite_differences_after_2d_histories() {
    for law in all_laws() {
        let f = reach(&law, 150.0);
        let (mut checked, mut probes, mut seen) = (0, 0, Vec::new());
        // the virgin state too: the isotropic limit may have reached the
        // cap on every path
        let mut histories = paths(f);
        histories.push(("virgin", vec![(150.0, [0.0; 2])]));
        for (name, path) in histories {
            let mut committed = SlipState2::default();
            drive2(&law, &path, &mut committed);
            let (p_end, u_end) = *path.last().unwrap();
            for un in [approach(p_end), 0.85 * approach(p_end)] {
                for d in [0.02, 0.3, 0.9, 2.0] {
                    for alpha in [0.0f64, 1.3, 2.9, 4.4] {
                        probes += 1;
                        let u = [
                            u_end[0] + d * f * alpha.cos(),
                            u_end[1] + d * f * alpha.sin(),
                        ];
                        let g = |un: f64, u: [f64; 2]| {
                            let (p, kn) = pressure(un);
                            law.eval_vector(p, kn, u, &committed).p_t
                        };
                        let (p, kn) = pressure(un);
                        let ev = law.eval_vector(p, kn, u, &committed);
                        seen.push(ev.slip);
                        let k = law.elastic_stiffness(p).0;
                        let (h, hn) = (1e-7 * f, 1e-9);
                        // columns ∂p/∂u₁, ∂p/∂u₂, ∂p/∂u_N by central differences;
                        // one-sided ones that disagree: a kink (an element
                        // starting or ending to slide) here, not checked
                        let diffs = fd::sided_columns(&[h, h, hn], |j, step| {
                            if j < 2 {
                                let mut v = u;
                                v[j] += step;
                                g(un, v).to_vec()
                            } else {
                                g(un + step, u).to_vec()
                            }
                        });
                        let s = ev.d_un[0].hypot(ev.d_un[1]).max(k * 1e-2);
                        let smooth = (0..3).all(|j| {
                            let scale = if j < 2 { k } else { s };
                            (0..2).all(|i| diffs.kink(i, j) < 1e-4 * scale)
                        });
                        if !smooth {
                            continue;
                        }
                        checked += 1;
                        for (i, (row, dun)) in ev.d_ut.iter().zip(ev.d_un).enumerate() {
                            for (j, &dij) in row.iter().enumerate() {
                                let m = fd::Mismatch::of(
                                    i,
                                    j,
                                    dij,
                                    diffs.central[(i, j)],
                                    fd::Scale::Absolute,
                                );
                                assert!(
                                    m.diff < 1e-5 * k,
                                    "{law:?} {name}, d = {d} f, α = {alpha}, {:?}: ∂p{i}/∂u{j} {m}",
                                    ev.slip,
                                );
                            }
                            let m = fd::Mismatch::of(
                                i,
                                2,
                                dun,
                                diffs.central[(i, 2)],
                                fd::Scale::Relative(k * 1e-3),
                            );
                            assert!(
                                m.diff < 1e-5 * m.scale,
                                "{law:?} {name}, d = {d} f, α = {alpha}, {:?}: ∂p{i}/∂u_N {m}",
                                ev.slip
                            );
                        }
                    }
                }
            }
        }
        assert!(
            checked * 5 >= probes * 4,
            "{law:?}: only {checked} of {probes} probes smooth"
        );
        // (an Iwan density's smallest elements slide at once: no stick
        // beyond 0.02 f)
        let iwan = matches!(law.backbone, Backbone::Iwan { .. });
        if !(iwan && law.memory == Memory::Kinematic) {
            assert!(seen.contains(&Slip::Stick), "{law:?}: {seen:?}");
        }
        if law.kp_ratio > 0.0 {
            assert!(seen.contains(&Slip::MacroSlip), "{law:?}: {seen:?}");
        }
        if law.kp_ratio < 1.0 || iwan {
            assert!(seen.contains(&Slip::MicroSlip), "{law:?}: {seen:?}");
        }
        eprintln!(
            "{:?} {:?}: {checked} of {probes} probes checked",
            law.memory, law.backbone
        );
    }
}

/// Q v for the rotation Q by θ.
fn rotate(t: f64, v: [f64; 2]) -> [f64; 2] {
    let (c, s) = (t.cos(), t.sin());
    [c * v[0] - s * v[1], s * v[0] + c * v[1]]
}

#[test]
fn a_rotated_path_gives_the_rotated_response() {
    for law in all_laws() {
        let f = reach(&law, 150.0);
        // an irregular 2-D walk with pressure changes and reversals
        let mut rng = Lcg(5);
        let (mut u, mut un) = ([0.0; 2], approach(150.0));
        let walk: Vec<(f64, f64, [f64; 2])> = (0..300)
            .map(|_| {
                u[0] += 0.5 * f * (rng.next() - 0.45);
                u[1] += 0.5 * f * (rng.next() - 0.55);
                un = (un + 0.002 * (rng.next() - 0.5)).clamp(0.005, 0.016);
                let (p, kn) = pressure(un);
                (p, kn, u)
            })
            .collect();
        for theta in [0.3, 1.1, std::f64::consts::FRAC_PI_2, 2.7, -2.0] {
            let (mut a, mut b) = (SlipState2::default(), SlipState2::default());
            let mut worst = 0.0f64;
            for (step, &(p, kn, u)) in walk.iter().enumerate() {
                let x = law.eval_vector(p, kn, u, &a);
                let y = law.eval_vector(p, kn, rotate(theta, u), &b);
                let k = law.elastic_stiffness(p).0;
                let cap = law.mu * p;
                let diff = |v: [f64; 2], w: [f64; 2]| (v[0] - w[0]).hypot(v[1] - w[1]);
                // Q D Qᵀ column by column: D Qᵀ e_j rotated
                let col = |d: [[f64; 2]; 2], j: usize| [d[0][j], d[1][j]];
                let qdq = |j: usize| {
                    let e = rotate(-theta, if j == 0 { [1.0, 0.0] } else { [0.0, 1.0] });
                    let de = [
                        x.d_ut[0][0] * e[0] + x.d_ut[0][1] * e[1],
                        x.d_ut[1][0] * e[0] + x.d_ut[1][1] * e[1],
                    ];
                    rotate(theta, de)
                };
                let rel = [
                    diff(rotate(theta, x.p_t), y.p_t) / cap,
                    diff(qdq(0), col(y.d_ut, 0)) / k,
                    diff(qdq(1), col(y.d_ut, 1)) / k,
                    diff(rotate(theta, x.d_un), y.d_un) / (kn * law.mu),
                    diff(rotate(theta, x.state.u_p), y.state.u_p) / f,
                    (x.state.kappa - y.state.kappa).abs() / x.state.kappa.max(f),
                ];
                let w = rel.iter().fold(0.0f64, |m, &r| m.max(r));
                worst = worst.max(w);
                assert!(w < 1e-12, "{law:?} θ = {theta} step {step}: {rel:?}");
                assert_eq!(x.slip, y.slip, "{law:?} θ = {theta} step {step}");
                a = x.state;
                b = y.state;
            }
            if theta == 0.3 {
                eprintln!(
                    "{:?} {:?}: largest relative difference {worst:e}",
                    law.memory, law.backbone
                );
            }
        }
    }
}

#[test]
fn a_state_packs_unpacks_and_checks() {
    let law = iwan(Memory::Kinematic, -0.5, 0.1);
    let f = reach(&law, 150.0);
    let mut st = SlipState2::default();
    drive2(&law, &paths(f)[1].1, &mut st);
    assert!(st.mem.largest() > 0.0);
    let v = st.pack();
    assert_eq!(v.len(), SlipState2::PACKED);
    // unpacked from the middle of a longer buffer, as from an exchange
    let mut buf = vec![7.0; 3 * SlipState2::PACKED];
    buf[SlipState2::PACKED..2 * SlipState2::PACKED].copy_from_slice(&v);
    assert_eq!(SlipState2::unpack(&buf[SlipState2::PACKED..]), st);
    assert_eq!(st.check(Some(&law), 10.0), Ok(()));
    // what an untrusted file may hold
    let bad = |edit: &dyn Fn(&mut SlipState2)| {
        let mut s = st;
        edit(&mut s);
        s
    };
    let nan = bad(&|s| s.mem.e[3][1] = f64::NAN);
    assert!(nan
        .check(Some(&law), 10.0)
        .unwrap_err()
        .contains("value 11"));
    let neg = bad(&|s| s.kappa = -1e-3);
    assert!(neg
        .check(Some(&law), 10.0)
        .unwrap_err()
        .contains("κ = -0.001"));
    let long = bad(&|s| s.mem.e[2] = [8.0, 7.0]);
    assert!(long
        .check(Some(&law), 10.0)
        .unwrap_err()
        .contains("element 3"));
    // stretches under a law without the kinematic memory, or past its elements
    let iso = exact_laws()[1].clone();
    assert!(st
        .check(Some(&iso), 10.0)
        .unwrap_err()
        .contains("element 1"));
    assert!(st.check(None, 10.0).unwrap_err().contains("has 0"));
    let pair = kinematic(0.3);
    assert_eq!(pair.elements().len, 2);
    let extra = bad(&|s| {
        s.mem = Stretch2::default();
        s.mem.e[2] = [1e-4, 0.0];
    });
    assert!(extra
        .check(Some(&pair), 10.0)
        .unwrap_err()
        .contains("element 3"));
}
