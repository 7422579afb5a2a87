//! The Greenwood-Williamson model (Greenwood & Williamson 1966): the nominal
//! pressure of a rough surface pressed against a flat at separation d,
//!
//! p(d) = η ∫_d^∞ P(z − d) φ(z) dz,                                   (GW 1966, eq. 7)
//!
//! with η summits per unit area, φ the density of summit heights (standard
//! deviation σ) and P(ω) the load on one summit of radius β at interference ω:
//! Hertz, P = (4/3) E* β^{1/2} ω^{3/2}, for elastic summits, which gives
//! p(d) = (4/3) η E* β^{1/2} σ^{3/2} F_{3/2}(d/σ) for Gaussian heights; or
//! the elastic-plastic summit of Chang, Etsion & Bogy (1987), see [`Asperity`].
//!
//! The integral is evaluated by composite Gauss-Legendre quadrature after the
//! substitution ω = σ u² (which makes the Hertz integrand ω^{3/2} smooth at the
//! first contact), split at every kink of the integrand (the CEB critical
//! interference, the foot of the exponential distribution) and refined by
//! doubling the panels until two successive sums agree to 1e-13.

use std::f64::consts::PI;

/// Distribution of summit heights, standardized by σ.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Distribution {
    /// φ(x) = e^{−x²/2} / √(2π).
    Gaussian,
    /// φ(x) = e^{−x} for x ≥ 0, 0 below (GW 1966's exponential case).
    Exponential,
}

impl Distribution {
    /// The standardized density φ̂(x), x = z/σ.
    pub fn density(self, x: f64) -> f64 {
        match self {
            Distribution::Gaussian => (-0.5 * x * x).exp() / (2.0 * PI).sqrt(),
            Distribution::Exponential => {
                if x >= 0.0 {
                    (-x).exp()
                } else {
                    0.0
                }
            }
        }
    }
}

/// The load-interference law of one summit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Asperity {
    /// Hertz: P = (4/3) E* β^{1/2} ω^{3/2}.
    Elastic,
    /// Chang, Etsion & Bogy (1987), J. Tribology 109, 257-263: Hertz up to the
    /// critical interference ω_c = (π K H / 2E*)² β (their eq. 5), above it
    /// volume conservation of the plastically deformed tip, contact area
    /// π β (2ω − ω_c) at mean pressure K H: P = π β ω (2 − ω_c/ω) K H (their
    /// eq. 12), with K = 0.454 + 0.41 ν (ν of the softer body, H its hardness).
    /// The load jumps by a factor 3/2 at ω_c (a known property of the model).
    Ceb { hardness: f64, k: f64 },
}

/// A Greenwood-Williamson surface in contact with a flat (the pair's
/// combined roughness against a flat with the composite modulus E*).
#[derive(Clone, Copy, Debug)]
pub struct Gw {
    /// Summit density η, 1/mm².
    pub density: f64,
    /// Summit radius β, mm.
    pub radius: f64,
    /// Standard deviation of the summit heights σ_s, mm.
    pub sigma: f64,
    pub distribution: Distribution,
    pub asperity: Asperity,
    /// Composite modulus E* = 1/((1−ν₁²)/E₁ + (1−ν₂²)/E₂), MPa.
    pub e_star: f64,
}

impl Gw {
    /// CEB's critical interference ω_c (mm); infinite for elastic summits.
    pub(crate) fn critical_interference(&self) -> f64 {
        match self.asperity {
            Asperity::Elastic => f64::INFINITY,
            Asperity::Ceb { hardness, k } => {
                (PI * k * hardness / (2.0 * self.e_star)).powi(2) * self.radius
            }
        }
    }

    /// Load on one summit at interference ω ≥ 0 (N).
    pub(crate) fn summit_load(&self, omega: f64) -> f64 {
        let hertz = |w: f64| 4.0 / 3.0 * self.e_star * self.radius.sqrt() * w.powf(1.5);
        match self.asperity {
            Asperity::Elastic => hertz(omega),
            Asperity::Ceb { hardness, k } => {
                let wc = self.critical_interference();
                if omega <= wc {
                    hertz(omega)
                } else {
                    PI * self.radius * (2.0 * omega - wc) * k * hardness
                }
            }
        }
    }

    /// Nominal pressure p(d) (MPa) at separation d (mm) of the flat from the
    /// mean summit height (the plane z = 0 of φ).
    pub fn pressure(&self, d: f64) -> f64 {
        self.over_summits(d, &|omega| self.summit_load(omega))
    }

    /// η ∫_d^∞ q(z − d) φ(z) dz: a quantity q(ω) of one summit at interference
    /// ω summed over the summits per unit area at separation d (the load in
    /// [`Gw::pressure`], the shear stiffness in `tangential.rs`), by the
    /// substitution ω = σ u² and the panels described at the top of the module.
    pub(crate) fn over_summits(&self, d: f64, q: &dyn Fn(f64) -> f64) -> f64 {
        let s = self.sigma;
        let h = d / s;
        let f = |u: f64| {
            let t = u * u;
            2.0 * u * q(s * t) * self.distribution.density(h + t)
        };
        // end of the integration: the density is below e^{-60} of its peak
        let top = match self.distribution {
            Distribution::Gaussian => (h.max(0.0).powi(2) + 150.0).sqrt() - h,
            Distribution::Exponential => (-h).max(0.0) + 60.0,
        };
        let mut breaks = vec![0.0, top.sqrt()];
        let wc = self.critical_interference() / s;
        if wc.is_finite() && wc < top {
            breaks.push(wc.sqrt());
        }
        if self.distribution == Distribution::Exponential && h < 0.0 {
            breaks.push((-h).sqrt());
        }
        breaks.sort_by(f64::total_cmp);
        let integral: f64 = breaks
            .windows(2)
            .map(|w| integrate(&f, w[0], w[1], 1e-13))
            .sum();
        self.density * integral
    }

    /// The separation d at which the pressure is `p` (bisection on the
    /// monotone p(d), to 1e-14 σ or to adjacent floating-point numbers; the
    /// bracket grows at most `MAX_STEPS` times, to 3^MAX_STEPS σ).
    pub fn separation(&self, p: f64) -> f64 {
        let s = self.sigma;
        bisect(-s, s, |d| self.pressure(d) > p, 1e-14 * s)
    }

    /// The fraction of the summits in contact at separation d: the share of
    /// summit heights above d, ∫_{d/σ}^∞ φ̂.
    pub(crate) fn contact_fraction(&self, d: f64) -> f64 {
        let h = d / self.sigma;
        match self.distribution {
            Distribution::Gaussian => {
                let top = (h.max(0.0).powi(2) + 150.0).sqrt() - h;
                integrate(&|t| Distribution::Gaussian.density(h + t), 0.0, top, 1e-13)
            }
            Distribution::Exponential => (-h.max(0.0)).exp(),
        }
    }

    /// The separation at which the fraction `f` (0 < f < 1) of the summits
    /// touches (bisection on the monotone [`Gw::contact_fraction`]).
    pub(crate) fn separation_for_fraction(&self, f: f64) -> f64 {
        let s = self.sigma;
        bisect(-s, s, |d| self.contact_fraction(d) > f, 1e-12 * s)
    }
}

/// Most steps of each loop of [`bisect`]: the bracket grows 3× a step, the
/// bisection halves it.
pub(crate) const MAX_STEPS: usize = 200;

/// The d where the monotone `above(d)` (true below, false above) turns, from
/// the bracket [lo, hi] widened until it holds the turn, bisected to `tol` or to
/// adjacent floating-point numbers. Every loop is bounded by [`MAX_STEPS`], so a
/// target the model cannot reach (underflow, overflow, NaN) costs at most
/// 3 × MAX_STEPS evaluations instead of a hang.
fn bisect(mut lo: f64, mut hi: f64, above: impl Fn(f64) -> bool, tol: f64) -> f64 {
    for _ in 0..MAX_STEPS {
        if above(lo) {
            break;
        }
        lo -= 2.0 * (hi - lo);
    }
    for _ in 0..MAX_STEPS {
        if !above(hi) {
            break;
        }
        hi += 2.0 * (hi - lo);
    }
    for _ in 0..MAX_STEPS {
        let mid = 0.5 * (lo + hi);
        if !(mid > lo && mid < hi) {
            break;
        }
        if above(mid) {
            lo = mid;
        } else {
            hi = mid;
        }
        if hi - lo < tol {
            break;
        }
    }
    0.5 * (lo + hi)
}

/// F_{3/2}(h) = ∫_h^∞ (s − h)^{3/2} e^{−s²/2}/√(2π) ds (Greenwood & Tripp),
/// by the quadrature of [`Gw::pressure`] (relative accuracy about 1e-12).
pub fn f32(h: f64) -> f64 {
    let f = |u: f64| {
        let t = u * u;
        2.0 * u * t.powf(1.5) * Distribution::Gaussian.density(h + t)
    };
    let top = (h.max(0.0).powi(2) + 150.0).sqrt() - h;
    integrate(&f, 0.0, top.sqrt(), 1e-13)
}

/// 16-point Gauss-Legendre nodes and weights on [−1, 1], by Newton's method
/// on P_16 (computed once).
fn gauss16() -> &'static [(f64, f64); 16] {
    static RULE: std::sync::OnceLock<[(f64, f64); 16]> = std::sync::OnceLock::new();
    RULE.get_or_init(|| {
        const N: usize = 16;
        let mut rule = [(0.0, 0.0); N];
        for (i, r) in rule.iter_mut().enumerate() {
            let mut x = (PI * (i as f64 + 0.75) / (N as f64 + 0.5)).cos();
            let mut dp = 1.0;
            for _ in 0..100 {
                // P_N(x) and P_N'(x) by the three-term recurrence
                let (mut p0, mut p1) = (1.0, x);
                for k in 2..=N {
                    let k = k as f64;
                    (p0, p1) = (p1, ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k);
                }
                dp = N as f64 * (x * p1 - p0) / (x * x - 1.0);
                let dx = p1 / dp;
                x -= dx;
                if dx.abs() < 1e-16 {
                    break;
                }
            }
            *r = (x, 2.0 / ((1.0 - x * x) * dp * dp));
        }
        rule
    })
}

/// ∫_a^b f by composite 16-point Gauss-Legendre, the panels doubled (from 4)
/// until two sums agree to `tol` relative (at most 8192 panels), or differ by
/// less than the smallest normal number: an integral that underflows into the
/// subnormals has no relative accuracy to converge to, and doubling to 8192
/// panels at every call made a bisection through such values take minutes.
pub(crate) fn integrate(f: &dyn Fn(f64) -> f64, a: f64, b: f64, tol: f64) -> f64 {
    if b <= a {
        return 0.0;
    }
    let rule = gauss16();
    let sum = |n: usize| {
        let w = (b - a) / n as f64;
        (0..n)
            .map(|k| {
                let c = a + (k as f64 + 0.5) * w;
                rule.iter()
                    .map(|(x, wt)| wt * f(c + 0.5 * w * x))
                    .sum::<f64>()
                    * 0.5
                    * w
            })
            .sum::<f64>()
    };
    let mut n = 4;
    let mut last = sum(n);
    while n < 8192 {
        n *= 2;
        let next = sum(n);
        if (next - last).abs() <= (tol * next.abs()).max(f64::MIN_POSITIVE) {
            return next;
        }
        last = next;
    }
    last
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gauss_rule_integrates_polynomials_of_degree_31() {
        let s: f64 = gauss16().iter().map(|(x, w)| w * x.powi(30)).sum();
        assert!((s - 2.0 / 31.0).abs() < 1e-14, "{s}");
        let s: f64 = gauss16().iter().map(|(_, w)| w).sum();
        assert!((s - 2.0).abs() < 1e-14);
    }

    #[test]
    fn f32_at_zero_is_its_closed_form() {
        // ∫_0^∞ s^{3/2} e^{−s²/2} ds = 2^{1/4} Γ(5/4); Γ(5/4) = Γ(1/4)/4 with
        // Γ(1/4) from its Gauss-Legendre integral ∫_0^∞ e^{−t^4} dt = Γ(5/4)
        let g54 = integrate(&|t: f64| (-t.powi(4)).exp(), 0.0, 8.0, 1e-15);
        let exact = 2f64.powf(0.25) * g54 / (2.0 * PI).sqrt();
        assert!((f32(0.0) / exact - 1.0).abs() < 1e-12, "{}", f32(0.0));
    }

    #[test]
    fn ceb_summit_load_is_hertz_below_and_plastic_above_the_critical_interference() {
        let g = Gw {
            density: 1.0,
            radius: 0.05,
            sigma: 1e-3,
            distribution: Distribution::Gaussian,
            asperity: Asperity::Ceb {
                hardness: 2000.0,
                k: 0.454 + 0.41 * 0.3,
            },
            e_star: 113_000.0,
        };
        let wc = g.critical_interference();
        let below = g.summit_load(wc * (1.0 - 1e-12));
        let above = g.summit_load(wc * (1.0 + 1e-12));
        assert!((above / below - 1.5).abs() < 1e-9, "{}", above / below);
        let w = 10.0 * wc;
        let k = 0.454 + 0.41 * 0.3;
        assert!((g.summit_load(w) / (PI * 0.05 * (2.0 * w - wc) * k * 2000.0) - 1.0).abs() < 1e-14);
    }

    #[test]
    fn contact_fraction_against_closed_forms() {
        let mut g = Gw {
            density: 2000.0,
            radius: 0.05,
            sigma: 1e-3,
            distribution: Distribution::Gaussian,
            asperity: Asperity::Elastic,
            e_star: 113_000.0,
        };
        // half the Gaussian summits stand above their mean, nearly all above −8σ
        assert!((g.contact_fraction(0.0) - 0.5).abs() < 1e-14);
        assert!((g.contact_fraction(-8e-3) - 1.0).abs() < 1e-14);
        let d = g.separation_for_fraction(1e-6);
        assert!((g.contact_fraction(d) / 1e-6 - 1.0).abs() < 1e-9);
        g.distribution = Distribution::Exponential;
        assert_eq!(g.contact_fraction(-1e-3), 1.0);
        assert!((g.contact_fraction(3e-3) - (-3f64).exp()).abs() < 1e-16);
    }

    /// A target the model cannot reach ends the bisection after a bounded
    /// number of evaluations, and an integrand in the subnormals after a few
    /// panel doublings (before, 8192 panels at every call: a fit range where
    /// nothing touches took minutes).
    #[test]
    fn unreachable_targets_and_underflow_end_in_bounded_work() {
        let calls = std::cell::Cell::new(0);
        let d = bisect(
            -1.0,
            1.0,
            |_| {
                calls.set(calls.get() + 1);
                true
            },
            1e-14,
        );
        assert!(
            calls.get() <= 3 * MAX_STEPS && d.is_finite(),
            "{}",
            calls.get()
        );
        let calls = std::cell::Cell::new(0);
        let v = integrate(
            &|x: f64| {
                calls.set(calls.get() + 1);
                1e-310 * (1.0 + x.sin())
            },
            0.0,
            1.0,
            1e-13,
        );
        assert!(
            v < f64::MIN_POSITIVE && calls.get() <= 16 * (4 + 8),
            "{}",
            calls.get()
        );
    }

    #[test]
    fn separation_inverts_pressure() {
        for dist in [Distribution::Gaussian, Distribution::Exponential] {
            let g = Gw {
                density: 2000.0,
                radius: 0.05,
                sigma: 1e-3,
                distribution: dist,
                asperity: Asperity::Elastic,
                e_star: 113_000.0,
            };
            for p in [0.01, 1.0, 100.0, 5000.0] {
                let d = g.separation(p);
                assert!((g.pressure(d) / p - 1.0).abs() < 1e-10, "{dist:?} {p}");
            }
        }
    }
}
