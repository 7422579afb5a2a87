//! A uniform joint of Jenkins elements under Masing's rules: every point of
//! the joint at one pressure, its springs in parallel, each with a slider of
//! its own threshold (Iwan 1966, the parallel-series model; Segalman 2005,
//! J. Appl. Mech. 72, for the density c (1 + χ) η^χ). Cycled at a slip
//! amplitude a from −a to +a, its loop has the force amplitude f(a) and the
//! area D(a) in closed form (docs/theory.md, "Slip memory: isotropic or
//! kinematic, and the Iwan backbone"): the closed form a joint-cycles rating
//! sets beside the run's steady cycles.
//!
//! Per unit area, with the elastic shear stiffness k (MPa/mm), the slip range
//! φ = μ p C / k (mm) and x = a / φ:
//!
//! ```text
//!   f(a) = k [c φ G(x) + Σⱼ mⱼ min(a, ηⱼ φ)]
//!   D(a) = 4 k [c (1 + χ) φ² H(x) + Σⱼ mⱼ ηⱼ φ (a − ηⱼ φ)₊]
//!   G(x) = x − x^{χ+2}/(χ+2),  H(x) = x^{χ+3}/((χ+2)(χ+3))     x ≤ 1
//!   G(x) = (1+χ)/(χ+2),        H(x) = x/(χ+2) − 1/(χ+3)          x > 1
//! ```
//!
//! (the elements of threshold η φ < a slide: each dissipates 4 k w ηφ (a − ηφ)
//! per cycle; the loss factor η = D / (2π · ½ f a)).

/// The joint: its elastic shear stiffness, slip range and density of
/// thresholds, and its area.
#[derive(Clone, Debug, PartialEq)]
pub struct UniformJoint {
    /// k_T^e at the joint's pressure, MPa/mm.
    pub stiffness: f64,
    /// φ = μ p C / k_T^e, mm: the slip at which every element slides.
    pub slip_range: f64,
    /// c, the weight of the continuous density (1 + χ) η^χ, and χ > −1.
    pub c: f64,
    pub chi: f64,
    /// Point masses (ηⱼ, mⱼ) of the density.
    pub masses: Vec<(f64, f64)>,
    /// The joint's area, mm² (a plane model's: its length × thickness).
    pub area: f64,
}

impl UniformJoint {
    /// The loop's force amplitude at slip amplitude `a` (mm), N.
    pub fn force_amplitude(&self, a: f64) -> Option<f64> {
        let (phi, chi) = self.valid(a)?;
        let x = a / phi;
        let g = if x <= 1.0 {
            x - x.powf(chi + 2.0) / (chi + 2.0)
        } else {
            (1.0 + chi) / (chi + 2.0)
        };
        let points: f64 = self.masses.iter().map(|&(e, m)| m * a.min(e * phi)).sum();
        Some(self.area * self.stiffness * (self.c * phi * g + points))
    }

    /// The energy one cycle from −a to +a and back dissipates, N·mm.
    pub fn dissipation(&self, a: f64) -> Option<f64> {
        let (phi, chi) = self.valid(a)?;
        let x = a / phi;
        let h = if x <= 1.0 {
            x.powf(chi + 3.0) / ((chi + 2.0) * (chi + 3.0))
        } else {
            x / (chi + 2.0) - 1.0 / (chi + 3.0)
        };
        let points: f64 = self
            .masses
            .iter()
            .map(|&(e, m)| m * e * phi * (a - e * phi).max(0.0))
            .sum();
        let continuous = self.c * (1.0 + chi) * phi * phi * h;
        Some(4.0 * self.area * self.stiffness * (continuous + points))
    }

    /// The secant stiffness f(a)/a, N/mm.
    pub fn secant_stiffness(&self, a: f64) -> Option<f64> {
        Some(self.force_amplitude(a)? / a)
    }

    /// The loss factor D / (2π U), U = ½ f(a) a (Ungar & Kerwin 1962).
    pub fn loss_factor(&self, a: f64) -> Option<f64> {
        let u = 0.5 * self.force_amplitude(a)? * a;
        (u > 0.0).then_some(self.dissipation(a)? / (2.0 * std::f64::consts::PI * u))
    }

    /// (φ, χ) when the joint and the amplitude make sense.
    fn valid(&self, a: f64) -> Option<(f64, f64)> {
        let ok = |v: f64| v.is_finite() && v > 0.0;
        (ok(a)
            && ok(self.stiffness)
            && ok(self.slip_range)
            && ok(self.area)
            && self.chi > -1.0
            && (0.0..=1.0).contains(&self.c))
        .then_some((self.slip_range, self.chi))
    }
}
