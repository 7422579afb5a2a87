//! The kinematic memory in two directions: a finite set of Jenkins elements
//! with vector stretches.
//!
//! Element i (stiffness k_T^e mᵢ, slip radius rᵢ = ηᵢ φ) carries a stretch
//! eᵢ ∈ ℝ² with |eᵢ| ≤ rᵢ; the shear is their sum (the parallel model of
//! [`super::kinematic`] with a circular slider per element: Iwan 1967, "On a
//! class of models for the yielding behavior of continuous and composite
//! systems", J. Appl. Mech. 34, the multi-dimensional parallel-series model;
//! Sanliturk & Ewins 1996, J. Sound Vib. 193, a 2-D microslip element):
//!
//! ```text
//!   p_T = k_T^e Σᵢ mᵢ eᵢ,      |eᵢ| ≤ ηᵢ φ,      φ = μ p_N C / k_T^e
//!   eᵢ ← P(eᵢ + Δu_T) = (eᵢ + Δu_T) min(1, rᵢ / |eᵢ + Δu_T|)
//! ```
//!
//! P is the closest-point projection onto the disc |e| ≤ rᵢ: the backward-
//! Euler update of one element (its radial return). It is exact for a
//! straight increment whose stretch stays collinear with it (every 1-D
//! history, any proportional path); for a straight increment at an angle to
//! a sliding element's stretch the exact path is a tractrix, the angle θ
//! between stretch and path obeying tan(θ/2) = tan(θ₀/2) e^{−s/r} after a
//! slide s, and P is its first-order approximation (tested in
//! `vector_paths_tests`).
//!
//! The 1-D state e(η) is stored exactly as a piecewise-linear function; in
//! the plane a stretch field over η has no such finite form, so the
//! density is discretized:
//!
//! - `bilinear`: its two elements (masses 1 − k_T^p/k_T^e at η_y = ρ/C and
//!   k_T^p/k_T^e at η = 1) are already a finite set: exact.
//! - `iwan`: the continuous part c (1+χ) η^χ is cut at η = 0, b₁, …, b_M = 1
//!   with bⱼ = λ^{(M−j)/(M−1)}, λ = [`IWAN_LOWEST`] (geometric above λ, so
//!   the relative error of a loop is about the same over the decades of
//!   amplitude above λ φ), M = [`JENKINS`] − 1; each interval becomes one
//!   element with its mass and at its centre of mass (so Σ mᵢ and Σ mᵢ ηᵢ,
//!   the initial stiffness and the friction limit, are those of the
//!   density), and the spike is the last element at η = 1. The error this
//!   makes in the loop areas is measured in `vector_paths_tests` and
//!   stated in docs/theory.md.

use super::{Backbone, Density, TangentialLaw};

/// Jenkins elements a point of the vector law keeps.
pub(crate) const JENKINS: usize = 24;

/// The first cut bⱼ of the Iwan density's continuous part: below λ φ the
/// discrete set dissipates less than the density (nothing below η₁ φ).
pub(crate) const IWAN_LOWEST: f64 = 0.01;

/// The vector stretches eᵢ of a point's Jenkins elements, mm (slots beyond
/// the law's element count, and every slot under the isotropic memory, 0).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Stretch2 {
    pub e: [[f64; 2]; JENKINS],
}

/// A finite set of Jenkins elements: thresholds ηᵢ ∈ (0, 1], masses mᵢ > 0.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Elements {
    pub eta: [f64; JENKINS],
    pub(crate) mass: [f64; JENKINS],
    pub len: usize,
    /// C of φ = μ p_N C / k_T^e (the density's).
    pub(crate) big_c: f64,
}

/// One update of a point's stretches and what the tangent needs.
#[derive(Clone, Copy, Debug)]
pub struct Update2 {
    pub stretch: Stretch2,
    /// Σ mᵢ eᵢ, mm (p_T / k_T^e).
    pub sum: [f64; 2],
    /// Σ mᵢ ∂eᵢ/∂u_T: mᵢ I sticking, mᵢ rᵢ/|eᵢ^tr| (I − nᵢ nᵢᵀ) sliding.
    pub(crate) d_sum: [[f64; 2]; 2],
    /// Σ over sliding elements of mᵢ ηᵢ nᵢ (∂Σ mᵢ eᵢ/∂φ).
    pub(crate) slipping_moment: [f64; 2],
    /// Σ mᵢ over the elements that stick.
    pub sticking: f64,
    /// Whether any element slides.
    pub slips: bool,
}

impl Elements {
    /// The elements of a density with no continuous part (the bilinear pair).
    fn of_masses(d: &Density) -> Self {
        let mut el = Elements {
            eta: [0.0; JENKINS],
            mass: [0.0; JENKINS],
            len: 0,
            big_c: d.big_c,
        };
        for &(eta, m) in &d.masses {
            el.push(eta, m);
        }
        el
    }

    fn push(&mut self, eta: f64, m: f64) {
        if m > 0.0 {
            self.eta[self.len] = eta;
            self.mass[self.len] = m;
            self.len += 1;
        }
    }

    /// The Iwan density c (1+χ) η^χ + spike δ(η − 1) as `JENKINS` − 1
    /// elements on geometric intervals above [`IWAN_LOWEST`] plus the spike.
    fn iwan(chi: f64, spike: f64, big_c: f64) -> Self {
        let mut el = Elements {
            eta: [0.0; JENKINS],
            mass: [0.0; JENKINS],
            len: 0,
            big_c,
        };
        let (c, q1, q2) = (1.0 - spike, chi + 1.0, chi + 2.0);
        let m = JENKINS - 1;
        // bⱼ^{χ+1} and bⱼ^{χ+2}, j = 0 … m: geometric from b_m = 1 down to
        // b₁ = λ (three powers, not one per cut: this runs per evaluation)
        let step = IWAN_LOWEST.powf(1.0 / (m - 1) as f64);
        let (s1, s2) = (step.powf(q1), step.powf(q2));
        let (mut p1, mut p2) = ([0.0; JENKINS], [0.0; JENKINS]);
        let (mut x1, mut x2) = (1.0, 1.0);
        for j in (1..=m).rev() {
            p1[j] = x1;
            p2[j] = x2;
            x1 *= s1;
            x2 *= s2;
        }
        for j in 1..=m {
            let (w0, w1) = (p1[j] - p1[j - 1], p2[j] - p2[j - 1]);
            el.push(q1 / q2 * w1 / w0, c * w0);
        }
        el.push(1.0, spike);
        el
    }

    /// The stretches after a shift `du` of u_T with slip range φ (mm):
    /// every element's eᵢ + du projected onto its disc |e| ≤ ηᵢ φ.
    pub fn update(&self, from: &Stretch2, du: [f64; 2], phi: f64) -> Update2 {
        let tol = 1e-12 * phi;
        let mut up = Update2 {
            stretch: Stretch2::default(),
            sum: [0.0; 2],
            d_sum: [[0.0; 2]; 2],
            slipping_moment: [0.0; 2],
            sticking: 0.0,
            slips: false,
        };
        for i in 0..self.len {
            let (m, eta) = (self.mass[i], self.eta[i]);
            let r = eta * phi;
            let tr = [from.e[i][0] + du[0], from.e[i][1] + du[1]];
            let a = tr[0].hypot(tr[1]);
            let e = if a > r {
                [r * (tr[0] / a), r * (tr[1] / a)]
            } else {
                tr
            };
            if a - r > tol {
                // sliding: ∂e/∂u = (r/a) (I − n nᵀ), ∂e/∂φ = η n
                let n = [tr[0] / a, tr[1] / a];
                let t = across(n);
                let s = m * (r / a);
                for (row, t_row) in up.d_sum.iter_mut().zip(t) {
                    for (x, tij) in row.iter_mut().zip(t_row) {
                        *x += s * tij;
                    }
                }
                up.slipping_moment[0] += m * eta * n[0];
                up.slipping_moment[1] += m * eta * n[1];
                up.slips = true;
            } else {
                up.d_sum[0][0] += m;
                up.d_sum[1][1] += m;
                up.sticking += m;
            }
            up.sum[0] += m * e[0];
            up.sum[1] += m * e[1];
            up.stretch.e[i] = e;
        }
        up
    }

    /// The work of the elements' friction over one step
    /// ([`super::work`]): Σᵢ mᵢ max(0, Fᵢ·sᵢ) with the element's slip
    /// sᵢ = eᵢ⁰ + du − eᵢ¹ (what its projection removed) and its mean force
    /// Fᵢ = ½ (k₀ eᵢ⁰ + k₁ eᵢ¹) (k₀, k₁: k_T^e at the step's start and end,
    /// MPa/mm), eᵢ⁰ from `from`, eᵢ¹ from `to`. MPa·mm.
    pub(crate) fn slip_work(
        &self,
        from: &Stretch2,
        k0: f64,
        du: [f64; 2],
        to: &Stretch2,
        k1: f64,
    ) -> f64 {
        (0..self.len)
            .map(|i| {
                let (e0, e1) = (from.e[i], to.e[i]);
                let dot = (0..2)
                    .map(|j| 0.5 * (k0 * e0[j] + k1 * e1[j]) * (e0[j] + du[j] - e1[j]))
                    .sum::<f64>();
                self.mass[i] * dot.max(0.0)
            })
            .sum()
    }

    /// Σ mᵢ eᵢ of stored stretches, mm.
    pub fn sum(&self, s: &Stretch2) -> [f64; 2] {
        let mut v = [0.0; 2];
        for i in 0..self.len {
            v[0] += self.mass[i] * s.e[i][0];
            v[1] += self.mass[i] * s.e[i][1];
        }
        v
    }
}

/// I − n nᵀ of a unit vector n, written [[n₂², −n₁n₂], [−n₁n₂, n₁²]] so that
/// along an axis it is exactly zero across.
pub(super) fn across(n: [f64; 2]) -> [[f64; 2]; 2] {
    let c = -n[0] * n[1];
    [[n[1] * n[1], c], [c, n[0] * n[0]]]
}

impl TangentialLaw {
    /// The Jenkins elements of the kinematic memory in two directions (see
    /// the module comment); under the isotropic memory none.
    pub fn elements(&self) -> Elements {
        if self.memory != super::Memory::Kinematic {
            return Elements {
                eta: [0.0; JENKINS],
                mass: [0.0; JENKINS],
                len: 0,
                big_c: 0.0,
            };
        }
        let d = self.density();
        match self.backbone {
            Backbone::Bilinear => Elements::of_masses(&d),
            Backbone::Iwan { chi, spike } => Elements::iwan(chi, spike, d.big_c),
        }
    }
}

impl Stretch2 {
    /// The largest |eᵢ|, mm.
    pub fn largest(&self) -> f64 {
        self.e.iter().map(|e| e[0].hypot(e[1])).fold(0.0, f64::max)
    }
}
