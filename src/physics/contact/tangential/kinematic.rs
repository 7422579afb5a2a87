//! Kinematic (Masing) memory: the tangential law as a parallel Iwan model.
//!
//! A spring point is a continuum of Jenkins elements (a spring in series with
//! a Coulomb slider) in parallel, labelled by η ∈ [0, 1]. Element η has the
//! stiffness k_T^e w(η) dη and slips when its stretch e(η) reaches η φ, so
//!
//! ```text
//!   p_T = k_T^e ∫₀¹ w(η) e(η) dη,      |e(η)| ≤ η φ,      de = du_T while |e| < η φ
//!   w(η) = c (1 + χ) η^χ + Σⱼ mⱼ δ(η − ηⱼ),              c + Σⱼ mⱼ = 1
//! ```
//!
//! (Iwan 1966, the parallel-series model; Segalman 2005, eq. 3, the density
//! R φ^χ on [0, φ_max] with a point mass S at φ_max, here normalised to η =
//! φ / φ_max). φ is fixed by the friction limit: when every element slips,
//! p_T = μ p_N, so φ = μ p_N C / k_T^e with 1/C = c (1+χ)/(2+χ) + Σⱼ mⱼ ηⱼ.
//!
//! Under any history of u_T at constant p_N this is exactly Masing's model
//! with the extended rules (a reversal starts the first-loading curve
//! scaled by two about the turning point; a branch that meets the branch
//! of an earlier reversal continues on it, so nested loops close; Iwan
//! 1966, section 3). A drop of p_N shrinks every element's range η φ and
//! clips the stretches that no longer fit (they slip); a rise clips nothing.
//!
//! The state of a point is the function e(η), continuous and piecewise
//! linear through (0, 0): a shift of u_T adds a constant, the slip limits
//! clip it to the cone |e| ≤ η φ, and both keep it piecewise linear, so it
//! is stored exactly as its breakpoints. At most [`MEMORY_POINTS`] are kept:
//! beyond, the breakpoint whose removal changes ∫ e dη least is dropped
//! (the smallest, innermost loop is forgotten first).
//!
//! The paper's two straight lines (section 2.2: elastic to p_T^Y = ρ μ p_N,
//! then the micro-slip slope k_T^p up to μ p_N) are two Jenkins elements:
//! masses 1 − k_T^p/k_T^e at η_y = ρ / C and k_T^p/k_T^e at η = 1, with C =
//! ρ + (1 − ρ) k_T^e / k_T^p (a single element at η = 1 with C = ρ when k_T^p = 0).

/// Breakpoints of the stretch function e(η) a point keeps.
pub(crate) const MEMORY_POINTS: usize = 10;

/// Working room: every segment of a stored function split at most in three.
const ROOM: usize = 3 * (MEMORY_POINTS + 1) + 2;

/// The stretch function e(η) of a spring point, mm: breakpoints (ηᵢ, eᵢ)
/// after (0, 0), η strictly increasing up to η = 1, the slots after the
/// one at η = 1 zero. All zero: no stretch anywhere (e ≡ 0).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Stretch {
    pub eta: [f64; MEMORY_POINTS],
    pub e: [f64; MEMORY_POINTS],
}

/// The breakpoints of a function, (0, 0) first.
#[derive(Clone, Copy)]
struct Points {
    eta: [f64; ROOM],
    e: [f64; ROOM],
    len: usize,
}

impl Points {
    fn new() -> Self {
        Points {
            eta: [0.0; ROOM],
            e: [0.0; ROOM],
            len: 1,
        }
    }

    fn push(&mut self, eta: f64, e: f64) {
        // a piece shorter than round-off is no piece
        if eta - self.eta[self.len - 1] <= 1e-14 {
            self.e[self.len - 1] = e;
            return;
        }
        self.eta[self.len] = eta;
        self.e[self.len] = e;
        self.len += 1;
    }

    /// The value at η by linear interpolation.
    fn at(&self, eta: f64) -> f64 {
        let k = (1..self.len)
            .find(|&k| self.eta[k] >= eta)
            .unwrap_or(self.len - 1);
        let (a, b) = (self.eta[k - 1], self.eta[k]);
        let s = if b > a { (eta - a) / (b - a) } else { 1.0 };
        self.e[k - 1] + s * (self.e[k] - self.e[k - 1])
    }

    /// Removes breakpoint k (0 < k < len − 1).
    fn remove(&mut self, k: usize) {
        for j in k..self.len - 1 {
            self.eta[j] = self.eta[j + 1];
            self.e[j] = self.e[j + 1];
        }
        self.len -= 1;
    }

    /// The deviation of breakpoint k from the chord of its neighbours, times
    /// the chord's length: twice the area a removal changes.
    fn bend(&self, k: usize) -> f64 {
        let (a, b) = (self.eta[k - 1], self.eta[k + 1]);
        let s = (self.eta[k] - a) / (b - a);
        let chord = self.e[k - 1] + s * (self.e[k + 1] - self.e[k - 1]);
        (self.e[k] - chord).abs() * (b - a)
    }

    /// Collinear breakpoints removed (within `tol` mm), then the least
    /// bent ones until at most [`MEMORY_POINTS`] follow (0, 0).
    fn simplify(&mut self, tol: f64) {
        let mut k = 1;
        while k + 1 < self.len {
            let (a, b) = (self.eta[k - 1], self.eta[k + 1]);
            if self.bend(k) <= tol * (b - a) {
                self.remove(k);
            } else {
                k += 1;
            }
        }
        while self.len > MEMORY_POINTS + 1 {
            let k = (1..self.len - 1)
                .min_by(|&i, &j| self.bend(i).total_cmp(&self.bend(j)))
                .expect("more than two points");
            self.remove(k);
        }
    }
}

impl Stretch {
    fn points(&self) -> Points {
        let mut p = Points::new();
        if self.eta[0] == 0.0 {
            p.push(1.0, 0.0);
            return p;
        }
        for k in 0..MEMORY_POINTS {
            p.eta[p.len] = self.eta[k];
            p.e[p.len] = self.e[k];
            p.len += 1;
            if self.eta[k] >= 1.0 {
                break;
            }
        }
        p
    }

    fn from_points(p: &Points) -> Self {
        let mut s = Stretch::default();
        if p.e[1..p.len].iter().all(|&e| e == 0.0) {
            return s;
        }
        for k in 1..p.len {
            s.eta[k - 1] = p.eta[k];
            s.e[k - 1] = p.e[k];
        }
        s
    }

    /// Whether the slots hold a function as stored (restart files are
    /// untrusted): all zero, or η strictly increasing in (0, 1] up to
    /// η = 1 and zeros after it.
    pub(crate) fn is_valid(&self) -> bool {
        if self.eta[0] == 0.0 {
            return self.eta.iter().chain(&self.e).all(|&x| x == 0.0);
        }
        let mut last = 0.0;
        for k in 0..MEMORY_POINTS {
            let eta = self.eta[k];
            if !(eta > last && eta <= 1.0) {
                return false;
            }
            if eta == 1.0 {
                return self.eta[k + 1..]
                    .iter()
                    .chain(&self.e[k + 1..])
                    .all(|&x| x == 0.0);
            }
            last = eta;
        }
        false
    }

    /// e(η), mm: the stored function between its breakpoints.
    pub fn at(&self, eta: f64) -> f64 {
        self.points().at(eta)
    }

    /// The largest |e(η)| / η over the breakpoints: the slip range φ the
    /// stretches fit in, mm.
    pub(crate) fn largest_ratio(&self) -> f64 {
        self.eta
            .iter()
            .zip(&self.e)
            .filter(|(&eta, _)| eta > 0.0)
            .map(|(&eta, &e)| e.abs() / eta)
            .fold(0.0, f64::max)
    }
}

/// The density w(η) of the slip thresholds (see the module comment).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Density {
    /// Weight c of the continuous part (1 + χ) η^χ.
    pub c: f64,
    pub chi: f64,
    /// Point masses (ηⱼ, mⱼ).
    pub(crate) masses: [(f64, f64); 2],
    /// C of φ = μ p_N C / k_T^e.
    pub(crate) big_c: f64,
}

/// One update of a point's stretches: the new function and what the
/// tangent needs.
#[derive(Clone, Copy, Debug)]
pub struct Update {
    pub stretch: Stretch,
    /// ∫ w e dη of the new function, mm (p_T / k_T^e).
    pub integral: f64,
    /// ∫ w dη over the elements that stick (dp_T/du_T / k_T^e).
    pub sticking: f64,
    /// ∫ w sign(e) η dη over the elements that slip (∂∫w e/∂φ).
    pub(crate) slipping_moment: f64,
    /// Whether any element slips.
    pub slips: bool,
}

impl Density {
    /// ∫ₐᵇ c (1+χ) η^χ dη and ∫ₐᵇ c (1+χ) η^{χ+1} dη.
    fn weights(&self, a: f64, b: f64) -> (f64, f64) {
        if self.c == 0.0 {
            return (0.0, 0.0);
        }
        let (p1, p2) = (self.chi + 1.0, self.chi + 2.0);
        let pw = |x: f64, q: f64| if x > 0.0 { x.powf(q) } else { 0.0 };
        (
            self.c * (pw(b, p1) - pw(a, p1)),
            self.c * p1 / p2 * (pw(b, p2) - pw(a, p2)),
        )
    }

    /// ∫₀¹ w e dη of a stored function, mm.
    pub fn integral(&self, s: &Stretch) -> f64 {
        let p = s.points();
        let mut sum = 0.0;
        for k in 1..p.len {
            let (a, b) = (p.eta[k - 1], p.eta[k]);
            let slope = (p.e[k] - p.e[k - 1]) / (b - a);
            let (w0, w1) = self.weights(a, b);
            sum += (p.e[k - 1] - slope * a) * w0 + slope * w1;
        }
        sum + self
            .masses
            .iter()
            .map(|&(eta, m)| m * p.at(eta))
            .sum::<f64>()
    }

    /// The stretches after a shift `du` of u_T with slip range `phi`
    /// (mm): e ← clip(e + du, −η φ, η φ).
    pub fn update(&self, from: &Stretch, du: f64, phi: f64) -> Update {
        let old = from.points();
        let tol = 1e-12 * phi;
        let mut new = Points::new();
        let (mut sticking, mut moment, mut slips) = (0.0, 0.0, false);
        // the side a shifted value lies on: +1 above η φ, −1 below −η φ
        let side = |v: f64, eta: f64| {
            if v - phi * eta > tol {
                1.0
            } else if v + phi * eta < -tol {
                -1.0
            } else {
                0.0
            }
        };
        let clip = |v: f64, eta: f64| v.clamp(-phi * eta, phi * eta);
        for k in 1..old.len {
            let (a, b) = (old.eta[k - 1], old.eta[k]);
            let (va, vb) = (old.e[k - 1] + du, old.e[k] + du);
            // where v − η φ and v + η φ change sign inside (a, b)
            let mut cuts = [b, b, b];
            let mut n = 0;
            for sgn in [1.0, -1.0] {
                let (fa, fb) = (va - sgn * phi * a, vb - sgn * phi * b);
                if fa * fb < 0.0 {
                    cuts[n] = a + (b - a) * fa / (fa - fb);
                    n += 1;
                }
            }
            cuts[..n].sort_by(f64::total_cmp);
            let v = |eta: f64| va + (vb - va) * (eta - a) / (b - a);
            let mut s = a;
            for &t in &cuts[..=n] {
                if t - s <= 0.0 {
                    continue;
                }
                let m = 0.5 * (s + t);
                let (w0, w1) = self.weights(s, t);
                let sgn = side(v(m), m);
                if sgn == 0.0 {
                    sticking += w0;
                } else {
                    moment += sgn * w1;
                    slips |= w0 > 0.0;
                }
                new.push(t, clip(v(t), t));
                s = t;
            }
        }
        for &(eta, m) in &self.masses {
            if m > 0.0 {
                let sgn = side(old.at(eta) + du, eta);
                if sgn == 0.0 {
                    sticking += m;
                } else {
                    moment += sgn * m * eta;
                    slips = true;
                }
            }
        }
        new.simplify(tol);
        let stretch = Stretch::from_points(&new);
        Update {
            stretch,
            integral: self.integral(&stretch),
            sticking,
            slipping_moment: moment,
            slips,
        }
    }
}

/// Merged breakpoints of two functions: at most every point of both.
const MERGED: usize = 2 * (MEMORY_POINTS + 1) + 1;

impl Density {
    /// ∫ₐᵇ c (1+χ) η^{χ+j} dη for j = 0, 1, 2.
    fn moments(&self, a: f64, b: f64) -> [f64; 3] {
        if self.c == 0.0 {
            return [0.0; 3];
        }
        let p1 = self.chi + 1.0;
        let pw = |x: f64, q: f64| if x > 0.0 { x.powf(q) } else { 0.0 };
        std::array::from_fn(|j| {
            let q = p1 + j as f64;
            self.c * p1 / q * (pw(b, q) - pw(a, q))
        })
    }

    /// The work of the elements' friction over one step ([`super::work`]),
    /// per unit of k_T^e-weighted area: ∫ w(η) max(0, F(η) s(η)) dη with
    /// the element's slip s = e₀ + du − e₁ (what the return mapping clipped)
    /// and its mean force F = ½ (k₀ e₀ + k₁ e₁) (k₀, k₁: k_T^e at the
    /// step's start and end, MPa/mm), e₀ = `from`, e₁ = `to`. Exact for
    /// the piecewise-linear stretches: both functions are cut at each
    /// other's breakpoints and at the zeros of F and s, and the weight's
    /// moments integrate the quadratic F s on each piece. MPa·mm.
    pub(crate) fn slip_work(&self, from: &Stretch, k0: f64, du: f64, to: &Stretch, k1: f64) -> f64 {
        let (p0, p1) = (from.points(), to.points());
        let force = |eta: f64| 0.5 * (k0 * p0.at(eta) + k1 * p1.at(eta));
        let slip = |eta: f64| p0.at(eta) + du - p1.at(eta);
        let mut sum = 0.0;
        if self.c > 0.0 {
            // the breakpoints of both, in order
            let mut cuts = [0.0; MERGED];
            let mut n = 0;
            for &eta in p0.eta[1..p0.len].iter().chain(&p1.eta[1..p1.len]) {
                cuts[n] = eta;
                n += 1;
            }
            cuts[..n].sort_by(f64::total_cmp);
            let mut a = 0.0;
            for &b in &cuts[..n] {
                if b > a {
                    sum += self.positive_part(a, b, &force, &slip);
                    a = b;
                }
            }
        }
        for &(eta, m) in &self.masses {
            if m > 0.0 {
                sum += m * (force(eta) * slip(eta)).max(0.0);
            }
        }
        sum
    }

    /// ∫ₐᵇ c (1+χ) η^χ max(0, F s) dη for F and s linear on [a, b].
    fn positive_part(&self, a: f64, b: f64, f: &dyn Fn(f64) -> f64, s: &dyn Fn(f64) -> f64) -> f64 {
        let (fa, fb, sa, sb) = (f(a), f(b), s(a), s(b));
        let (f1, s1) = ((fb - fa) / (b - a), (sb - sa) / (b - a));
        let (f0, s0) = (fa - f1 * a, sa - s1 * a);
        // where F or s changes sign inside (a, b)
        let mut cuts = [b; 3];
        let mut n = 0;
        for (x, y) in [(fa, fb), (sa, sb)] {
            if x * y < 0.0 {
                cuts[n] = a + (b - a) * x / (x - y);
                n += 1;
            }
        }
        cuts[..n].sort_by(f64::total_cmp);
        let mut sum = 0.0;
        let mut lo = a;
        for &hi in &cuts[..=n] {
            let mid = 0.5 * (lo + hi);
            if hi > lo && (f0 + f1 * mid) * (s0 + s1 * mid) > 0.0 {
                let m = self.moments(lo, hi);
                sum += f0 * s0 * m[0] + (f0 * s1 + f1 * s0) * m[1] + f1 * s1 * m[2];
            }
            lo = hi;
        }
        sum
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn uniform() -> Density {
        Density {
            c: 1.0,
            chi: 0.0,
            masses: [(1.0, 0.0); 2],
            big_c: 2.0,
        }
    }

    #[test]
    fn first_loading_of_the_uniform_density_is_the_parabola() {
        // e = u where u < η φ, else η φ: ∫ e dη = u − u²/(2φ) for u ≤ φ
        let d = uniform();
        let phi = 0.01;
        for u in [0.001, 0.004, 0.0099, 0.02] {
            let up = d.update(&Stretch::default(), u, phi);
            let x: f64 = (u / phi).min(1.0);
            let expect = phi * (x - 0.5 * x * x);
            assert!((up.integral - expect).abs() < 1e-15, "u = {u}");
            assert!((up.sticking - (1.0 - x)).abs() < 1e-12);
            assert!(up.stretch.is_valid());
        }
    }

    #[test]
    fn a_long_irregular_history_keeps_a_valid_bounded_function() {
        let d = Density {
            c: 0.7,
            chi: -0.4,
            masses: [(0.3, 0.1), (1.0, 0.2)],
            big_c: 1.5,
        };
        let mut s = Stretch::default();
        let mut x: u64 = 7;
        for i in 0..2000 {
            x = x
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let r = (x >> 11) as f64 / (1u64 << 53) as f64;
            let phi = 0.01 * (1.0 + 0.5 * (i as f64 * 0.01).sin());
            let up = d.update(&s, 0.02 * (r - 0.5), phi);
            assert!(up.stretch.is_valid(), "step {i}: {:?}", up.stretch);
            assert!(up.stretch.largest_ratio() <= phi * (1.0 + 1e-9), "step {i}");
            s = up.stretch;
        }
    }
}
