//! What every normal law is made of: its [`Kind`] (name, parameters, how it
//! is built) and its evaluation ([`Law`]), behind [`NormalLaw`]. The laws
//! themselves are the other files of this folder.

use crate::physics::contact::table::Monotone;
use crate::physics::range::Range;
use std::sync::Arc;

/// A normal law's kind: its name (the case's `law`), its parameters and how
/// it is built from them. One per file of this folder.
pub struct Kind {
    pub name: &'static str,
    /// Its keys in `[interface.<name>]`, in the order their ranges are checked.
    pub(crate) params: &'static [Param],
    /// The law from its parameters (every one given, checked by the law:
    /// the message names the key).
    pub build: fn(&Given) -> Result<NormalLaw, String>,
}

/// One parameter of a law: its key and what it holds.
#[derive(Clone, Copy, Debug)]
pub struct Param {
    pub key: &'static str,
    pub holds: Holds,
}

/// What a parameter holds.
#[derive(Clone, Copy, Debug)]
pub enum Holds {
    /// A number within a range (none: the law's own check bounds it, as m ∈ (0, 1]).
    Number(Option<&'static Range>),
    /// Rows of two numbers, each column named and within its range.
    Rows([(&'static str, &'static Range); 2]),
}

/// A value of a parameter as the case gives it.
#[derive(Clone, Copy, Debug)]
pub enum Value<'a> {
    Number(f64),
    Rows(&'a [Vec<f64>]),
}

/// The law parameters a case gives (key, value), whichever law they belong to.
pub struct Given<'a>(pub Vec<(&'static str, Value<'a>)>);

impl Given<'_> {
    /// Is `key` given?
    pub fn has(&self, key: &str) -> bool {
        self.0.iter().any(|(k, _)| *k == key)
    }

    /// The number at `key` (NaN when not given or not a number: the law's
    /// check refuses it).
    pub fn number(&self, key: &str) -> f64 {
        self.0
            .iter()
            .find_map(|(k, v)| match v {
                Value::Number(x) if *k == key => Some(*x),
                _ => None,
            })
            .unwrap_or(f64::NAN)
    }

    /// The rows at `key` (none when not given).
    pub fn rows(&self, key: &str) -> &[Vec<f64>] {
        self.0
            .iter()
            .find_map(|(k, v)| match v {
                Value::Rows(r) if *k == key => Some(*r),
                _ => None,
            })
            .unwrap_or(&[])
    }
}

/// One normal law's evaluation (for an approach u > 0 and a pressure p > 0:
/// [`NormalLaw`] answers the open pair itself).
pub trait Law: std::fmt::Debug + Send + Sync {
    /// Pressure and stiffness (p, dp/du) at approach u > 0.
    fn pressure(&self, u: f64) -> (f64, f64);
    /// Approach u at pressure p > 0 (the law's inverse).
    fn approach(&self, p: f64) -> f64;
    /// Stored energy per unit area ∫₀ᵘ p(s) ds, u > 0.
    fn energy(&self, u: f64) -> f64;
    /// The law as `asperity check` prints it.
    fn describe(&self) -> String;
    /// The measured points, when the law is a table (its extrapolation is reported).
    fn table(&self) -> Option<&Monotone> {
        None
    }
}

/// A normal compliance law (one of [`super::KINDS`], built by its file's `new`).
/// `Clone`: the law is shared behind an `Arc`.
#[derive(Clone, Debug)]
pub struct NormalLaw(Arc<dyn Law>);

impl NormalLaw {
    /// A checked law.
    pub fn new(law: impl Law + 'static) -> Self {
        NormalLaw(Arc::new(law))
    }

    /// Pressure and stiffness (p, dp/du) at approach u. Open (u ≤ 0): (0, 0).
    pub fn pressure(&self, u: f64) -> (f64, f64) {
        if u <= 0.0 {
            return (0.0, 0.0);
        }
        self.0.pressure(u)
    }

    /// Approach u at pressure p ≥ 0 (the law's inverse).
    pub fn approach(&self, p: f64) -> f64 {
        if p <= 0.0 {
            return 0.0;
        }
        self.0.approach(p)
    }

    /// Secant stiffness p / u(p) from the origin to pressure p (eq. 2.9).
    pub fn secant_stiffness(&self, p: f64) -> f64 {
        let p = p.max(f64::MIN_POSITIVE.sqrt());
        p / self.approach(p)
    }

    /// Stored energy per unit area ∫₀ᵘ p(s) ds (for checks of the residual as a gradient).
    pub fn energy(&self, u: f64) -> f64 {
        if u <= 0.0 {
            return 0.0;
        }
        self.0.energy(u)
    }

    /// The law as `asperity check` prints it.
    pub(crate) fn describe(&self) -> String {
        self.0.describe()
    }

    /// The measured points of a table law.
    pub fn table(&self) -> Option<&Monotone> {
        self.0.table()
    }
}
