//! The vector law (issue 26): along one axis the scalar law, tangents
//! against finite differences after 2-D histories, isotropy, the state's
//! packing and check. Closed-form 2-D paths and the Iwan discretization's
//! error: `vector_paths_tests`.

use super::*;

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
