//! Checks of a parsed case that need no mesh: numbers in range, laws complete,
//! parameters that belong to another law rejected.

use super::Weights;
use super::{Case, InterfaceLawSpec};
use crate::error::{Error, Result};
use crate::interface::{FrictionScheme, NormalLaw, TangentialLaw};
use std::collections::BTreeMap;

/// What validation derives from the case.
pub struct Checked {
    pub laws: BTreeMap<String, NormalLaw>,
    pub tangential: BTreeMap<String, (TangentialLaw, FrictionScheme)>,
}

/// Validates everything that does not depend on the mesh.
pub fn check_case(case: &Case) -> Result<Checked> {
    let place = case.source.display().to_string();
    let at = |key: &str| format!("{place}: {key}");
    let t = case.model.thickness;
    if !(t.is_finite() && t > 0.0) {
        return Err(Error::input(
            at("[model] thickness"),
            format!("{t} must be a positive number (mm)"),
        ));
    }
    if case.mesh.refine == 0 {
        return Err(Error::input(at("[mesh] refine"), "must be at least 1"));
    }
    if case.mesh.file.is_some() {
        if !case.mesh.block.is_empty() {
            return Err(Error::input(
                at("[mesh]"),
                "give either file or [[mesh.block]], not both",
            ));
        }
        if case.mesh.refine != 1 {
            return Err(Error::input(
                at("[mesh] refine"),
                format!(
                    "refine = {} (or --refine) cannot refine a mesh read from a file; refine it in Gmsh",
                    case.mesh.refine
                ),
            ));
        }
    }
    for (body, m) in &case.materials {
        let key = format!("[materials.{body}]");
        for (name, v) in [
            ("young", m.young),
            ("poisson", m.poisson),
            ("hardening", m.hardening),
        ] {
            if !v.is_finite() {
                return Err(Error::input(
                    at(&format!("{key} {name}")),
                    format!("{v} is not a finite number"),
                ));
            }
        }
        if let Some(y) = m.yield_stress {
            if !(y.is_finite() && y > 0.0) {
                return Err(Error::input(
                    at(&format!("{key} yield_stress")),
                    format!("{y} must be a positive number (MPa); omit it for an elastic body"),
                ));
            }
        }
    }
    let mut laws = BTreeMap::new();
    let mut tangential = BTreeMap::new();
    for (name, spec) in &case.interface {
        let key = format!("[interface.{name}]");
        let law = normal_law(spec).map_err(|m| Error::input(at(&key), m))?;
        if !spec.gap.is_finite() {
            return Err(Error::input(
                at(&format!("{key} gap")),
                "must be a finite number (mm)",
            ));
        }
        if let Some(p) = spec.start_pressure {
            if !(p.is_finite() && p > 0.0) {
                return Err(Error::input(
                    at(&format!("{key} start_pressure")),
                    format!("{p} must be positive (MPa)"),
                ));
            }
        }
        laws.insert(name.clone(), law);
        if let Some(t) = &spec.tangential {
            let key = format!("{key} tangential");
            if spec.weights != Weights::Lumped {
                return Err(Error::input(at(&key), "a tangential law needs weights = \"lumped\" (one spring and one slip history per pair)"));
            }
            let law = TangentialLaw::new(t.r, t.s, t.kp_ratio, t.mu, t.beta, t.n, t.yield_ratio)
                .map_err(|m| Error::input(at(&key), m))?;
            tangential.insert(name.clone(), (law, t.scheme));
        }
    }
    check_solver(case, &at)?;
    Ok(Checked { laws, tangential })
}

fn normal_law(s: &InterfaceLawSpec) -> std::result::Result<NormalLaw, String> {
    let given = [
        ("c_n", s.c_n),
        ("m", s.m),
        ("a", s.a),
        ("b", s.b),
        ("slope", s.slope),
        ("p_c", s.p_c),
    ];
    let (needed, law): (&[&str], _) = match s.law.as_str() {
        "power" => (&["c_n", "m"], "power"),
        "exponential" => (&["a", "b"], "exponential"),
        "linear" => (&["c_n", "m", "slope", "p_c"], "linear"),
        other => {
            return Err(format!(
                "law = \"{other}\" is not a known law (power, exponential, linear)"
            ))
        }
    };
    for (k, v) in given {
        match (needed.contains(&k), v) {
            (true, None) => return Err(format!("the {law} law needs `{k}`")),
            (false, Some(_)) => return Err(format!("`{k}` is not a parameter of the {law} law")),
            _ => {}
        }
    }
    let g = |v: Option<f64>| v.unwrap_or(f64::NAN);
    match law {
        "power" => NormalLaw::new_power(g(s.c_n), g(s.m)),
        "exponential" => NormalLaw::new_exponential(g(s.a), g(s.b)),
        _ => NormalLaw::new_linear(g(s.c_n), g(s.m), g(s.slope), g(s.p_c)),
    }
}

fn check_solver(case: &Case, at: &dyn Fn(&str) -> String) -> Result<()> {
    let s = &case.solver;
    if s.increments == 0 {
        return Err(Error::input(
            at("[solver] increments"),
            "must be at least 1",
        ));
    }
    if let Some(f) = s.first_increment {
        if !(f.is_finite() && f > 0.0 && f <= 1.0) {
            return Err(Error::input(
                at("[solver] first_increment"),
                format!("{f} must be in (0, 1]"),
            ));
        }
    }
    if let Some(l) = &s.load_factors {
        let ok = !l.is_empty()
            && l.iter().all(|v| v.is_finite())
            && l[0] != 0.0
            && l.windows(2).all(|w| w[1] != w[0]);
        if !ok {
            return Err(Error::input(
                at("[solver] load_factors"),
                "must be a non-empty list of finite numbers, the first non-zero and no two neighbours equal (it may go down: unloading)",
            ));
        }
    }
    for (name, v) in [
        ("residual_tolerance", s.residual_tolerance),
        ("displacement_tolerance", s.displacement_tolerance),
    ] {
        if !(v.is_finite() && v > 0.0 && v < 1.0) {
            return Err(Error::input(
                at(&format!("[solver] {name}")),
                format!("{v} must be in (0, 1)"),
            ));
        }
    }
    if s.max_iterations == Some(0) {
        return Err(Error::input(
            at("[solver] max_iterations"),
            "must be at least 1",
        ));
    }
    if case.output.vtu_every == 0 {
        return Err(Error::input(at("[output] vtu_every"), "must be at least 1"));
    }
    Ok(())
}

impl super::SolverSpec {
    /// The scheduled load factors: explicit list, or a first step then equal steps to 1.
    pub fn schedule(&self) -> Vec<f64> {
        if let Some(l) = &self.load_factors {
            return l.clone();
        }
        let n = self.increments;
        match self.first_increment {
            Some(f) if f < 1.0 && n > 1 => {
                let mut v = vec![f];
                let rest = n - 1;
                v.extend((1..=rest).map(|i| f + (1.0 - f) * i as f64 / rest as f64));
                v
            }
            _ => (1..=n).map(|i| i as f64 / n as f64).collect(),
        }
    }

    pub fn iteration_limit(&self) -> usize {
        self.max_iterations.unwrap_or(match self.method {
            super::Method::FullNewton => 30,
            _ => 400,
        })
    }
}
