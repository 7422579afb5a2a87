//! DIN 7190's side of a fit in service: the run's end state (each part's
//! uniform temperature change, the speed) read off the model and turned
//! into the interference the service takes off, ΔU_ϑ
//! ([`Fit::thermal_loss`]) and ΔU_ω ([`Fit::centrifugal_loss`]), so that the
//! handbook's pressure p = (U_w − ΔU_ϑ − ΔU_ω)/(D_F K)
//! ([`Fit::pressure_in_service`]) is the fit's where the FE's is: at the
//! run's end. A part at a temperature field there has no uniform ΔT for the
//! standard: the handbook side then stays the fit at assembly, and says so.

use crate::model::Model;
use crate::verdict::handbook::din7190::Fit;
use crate::verdict::rating::Input;

/// kg/m³ in the handbook's units (t/mm³).
const KG_PER_M3: f64 = 1e-12;

/// What the handbook side of a run rates.
pub(crate) enum Side {
    /// A run with neither temperatures nor a speed: the fit at assembly.
    Assembly,
    /// The fit at the run's end, at uniform temperatures and its speed.
    Service(Box<Service>),
    /// A part (`"hub"` or `"shaft"`) at a temperature field at the run's end:
    /// the handbook side stays the fit at assembly.
    Field(&'static str),
}

/// The fit at the run's end.
pub(crate) struct Service {
    /// The fit with the parts' E and ν at their temperatures there (the same
    /// as at assembly without a temperature table).
    pub fit: Fit,
    /// ΔU_ϑ and ΔU_ω, mm.
    pub thermal: f64,
    pub centrifugal: f64,
    /// ΔT of the hub and of the shaft (K), each when it has a temperature.
    pub dt: [Option<f64>; 2],
    /// The speed (rpm) and the densities ρ_A, ρ_I (t/mm³), when the model
    /// spins.
    pub spin: Option<(f64, f64, f64)>,
}

impl Service {
    /// p at the run's end (MPa).
    pub fn pressure(&self) -> Option<f64> {
        self.fit.pressure_in_service(self.thermal, self.centrifugal)
    }

    /// U_w − ΔU_ϑ − ΔU_ω (mm): the interference the service leaves.
    pub fn left(&self) -> f64 {
        self.fit.effective_interference() - self.thermal - self.centrifugal
    }

    /// The end state's inputs: each part's ΔT, ΔU_ϑ, the speed, ΔU_ω and
    /// the opening speed at the end's temperatures.
    pub fn inputs(&self) -> Vec<Input> {
        let mut out = Vec::new();
        let names = [
            ("hub temperature change at the run's end", "ΔT_A"),
            ("shaft temperature change at the run's end", "ΔT_I"),
        ];
        for ((name, symbol), dt) in names.into_iter().zip(self.dt) {
            if let Some(dt) = dt {
                out.push(Input::new(name, symbol, dt, "K", "run"));
            }
        }
        if self.dt.iter().any(Option::is_some) {
            out.push(Input::new(
                "interference lost to the temperatures, D_F (α_A ΔT_A − α_I ΔT_I)",
                "ΔU_ϑ",
                self.thermal * 1e3,
                "µm",
                "run",
            ));
        }
        if let Some((rpm, rho_a, rho_i)) = self.spin {
            out.push(Input::new("speed at the run's end", "n", rpm, "rpm", "run"));
            out.push(Input::new(
                "interference lost to the speed",
                "ΔU_ω",
                self.centrifugal * 1e3,
                "µm",
                "run",
            ));
            let at_end = self.dt.iter().any(Option::is_some).then(|| {
                self.fit
                    .opening_speed_in_service(self.thermal, rho_a, rho_i)
            });
            if let Some(Some(w)) = at_end.filter(|w| w.is_some_and(f64::is_finite)) {
                out.push(Input::new(
                    "opening speed at the run's end temperatures",
                    "n_ab,ϑ",
                    rpm_of(w),
                    "rpm",
                    "run",
                ));
            }
        }
        out
    }
}

/// The run's end as the rating's subject tells it, and its handbook side.
pub(crate) struct End {
    /// Each part's ΔT and the speed, in words.
    pub words: Vec<String>,
    pub side: Side,
}

impl End {
    /// The fit in service, unless the handbook side stays at assembly.
    pub fn service(&self) -> Option<&Service> {
        match &self.side {
            Side::Service(s) => Some(s),
            _ => None,
        }
    }
}

/// The run's end at pseudo-time `t`: each part's temperature change
/// ΔT h(t) and the speed n h(t), the handbook's side from them.
pub(crate) fn end(model: &Model, t: f64, fit: &Fit, (hub, shaft): (usize, usize)) -> End {
    let mut words = Vec::new();
    let mut dt = [None; 2];
    let mut alpha = [0.0; 2];
    let mut field = None;
    for (k, (b, what)) in [(hub, "hub"), (shaft, "shaft")].into_iter().enumerate() {
        let Some(bt) = model.temperatures.iter().find(|bt| bt.body == b) else {
            continue;
        };
        let change = bt.change * model.factor(bt.history, t);
        if bt.field.is_some() && change != 0.0 {
            words.push(format!(
                "{what}: a temperature field, ΔT = {change} K × its field's factor"
            ));
            field = field.or(Some(what));
        } else {
            words.push(format!("{what} ΔT = {change} K"));
        }
        dt[k] = Some(change);
        alpha[k] = bt.alpha;
    }
    let rpm = model.rpm(t);
    if let Some(n) = rpm {
        words.push(format!("{n} rpm"));
    }
    let side = match (field, words.is_empty()) {
        (Some(what), _) => Side::Field(what),
        (None, true) => Side::Assembly,
        (None, false) => Side::Service(Box::new(at_end(
            model,
            t,
            fit,
            (hub, shaft),
            (dt, alpha),
            rpm,
        ))),
    };
    End { words, side }
}

/// The fit at the run's end with uniform temperature changes `dt` of
/// expansion `alpha` (hub, shaft) and the speed `rpm`.
fn at_end(
    model: &Model,
    t: f64,
    fit: &Fit,
    (hub, shaft): (usize, usize),
    (dt, alpha): ([Option<f64>; 2], [f64; 2]),
    rpm: Option<f64>,
) -> Service {
    let (mh, ms) = (model.material_at(hub, t), model.material_at(shaft, t));
    let fit = Fit {
        e_hub: mh.young,
        poisson_hub: mh.poisson,
        e_shaft: ms.young,
        poisson_shaft: ms.poisson,
        ..*fit
    };
    let thermal = fit
        .thermal_loss(
            (alpha[0], dt[0].unwrap_or(0.0)),
            (alpha[1], dt[1].unwrap_or(0.0)),
        )
        .unwrap_or(0.0);
    let spin = rpm
        .zip(model.speed.as_ref())
        .map(|(n, s)| (n, s.density[hub] * KG_PER_M3, s.density[shaft] * KG_PER_M3));
    let centrifugal = spin
        .and_then(|(n, rho_a, rho_i)| fit.centrifugal_loss(omega_of(n), rho_a, rho_i))
        .unwrap_or(0.0);
    Service {
        fit,
        thermal,
        centrifugal,
        dt,
        spin,
    }
}

/// The inputs of a fit posed on a model with temperatures or a speed, known
/// before the run: each heated part's α and the temperature change at which
/// the fit opens, standing, with the heated parts warmed alike
/// ([`Fit::opening_temperature_change`]); each part's density and the
/// opening speed at the assembly temperature ([`Fit::opening_speed`]).
/// Empty for a model with neither.
pub(crate) fn posed_inputs(model: &Model, fit: &Fit, (hub, shaft): (usize, usize)) -> Vec<Input> {
    let mut out = Vec::new();
    let alpha = |b: usize| (model.temperatures.iter().find(|bt| bt.body == b)).map(|bt| bt.alpha);
    let (a_hub, a_shaft) = (alpha(hub), alpha(shaft));
    if let Some(a) = a_hub {
        out.push(Input::new(
            "hub expansion coefficient",
            "α_A",
            a,
            "1/K",
            "material",
        ));
    }
    if let Some(a) = a_shaft {
        out.push(Input::new(
            "shaft expansion coefficient",
            "α_I",
            a,
            "1/K",
            "material",
        ));
    }
    let opening = match (a_hub, a_shaft) {
        (Some(a), Some(i)) => Some((
            "temperature change at which the fit opens, hub and shaft warmed alike (standing)",
            a,
            i,
        )),
        (Some(a), None) => Some((
            "temperature change of the hub alone at which the fit opens (standing)",
            a,
            0.0,
        )),
        (None, Some(i)) => Some((
            "temperature change of the shaft alone at which the fit opens (standing)",
            0.0,
            i,
        )),
        (None, None) => None,
    };
    if let Some((name, a, i)) = opening {
        if let Some(dt) = fit.opening_temperature_change(a, i) {
            out.push(Input::new(name, "ΔT_ab", dt, "K", "material"));
        }
    }
    if let Some(s) = &model.speed {
        let (rho_a, rho_i) = (s.density[hub], s.density[shaft]);
        out.push(Input::new("hub density", "ρ_A", rho_a, "kg/m³", "material"));
        out.push(Input::new(
            "shaft density",
            "ρ_I",
            rho_i,
            "kg/m³",
            "material",
        ));
        // none when the hub grows no more than the shaft: it never opens
        let w = fit.opening_speed(rho_a * KG_PER_M3, rho_i * KG_PER_M3);
        if let Some(w) = w.filter(|w| w.is_finite()) {
            out.push(Input::new(
                "opening speed at the assembly temperature",
                "n_ab",
                rpm_of(w),
                "rpm",
                "material",
            ));
        }
    }
    out
}

/// ω (rad/s) of n (rpm).
fn omega_of(rpm: f64) -> f64 {
    rpm * std::f64::consts::PI / 30.0
}

/// n (rpm) of ω (rad/s).
fn rpm_of(omega: f64) -> f64 {
    omega * 30.0 / std::f64::consts::PI
}
