//! A body's temperature field (`[[temperature]]` with `along` and `profile`,
//! or with `field`; docs/case-schema.md "Temperatures"): the factor f(x) of
//! its change ΔT at each point, ΔT(x) = ΔT f(x), read by every Gauss point.
//! A table runs along one coordinate (x, y, z, or r, the distance from the
//! model's axis); an expression is a function of x, y, z and r
//! ([`crate::input::case::expression`]), refused when it is not a finite
//! number at a node or a Gauss point of the body.

use super::clip;
use super::speed::radius;
use crate::error::{Error, Result};
use crate::input::case::expression::{Expression, Variable};
use crate::input::case::TemperatureSpec;
use crate::input::mesh::Mesh;
use crate::physics::element::family::Family;
use crate::physics::element::solid::ElementGeometry;
use crate::physics::element::solid3::ElementGeometry3;
use crate::physics::element::Section;

/// What a table's rows are given at: a coordinate of the point, or its
/// distance from the model's axis ([`radius`], as a speed's r).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Coordinate {
    /// 0, 1, 2: x (r in axisymmetry), y, z.
    Axis(usize),
    /// r: |x| in axisymmetry, √(x² + y²) in a plane model, √(x² + z²) in 3D.
    Radius { dim: usize, axisymmetric: bool },
}

impl Coordinate {
    /// The coordinate of point x.
    pub fn of(self, x: [f64; 3]) -> f64 {
        match self {
            Coordinate::Axis(a) => x[a],
            Coordinate::Radius { dim, axisymmetric } => radius(x, dim, axisymmetric),
        }
    }

    /// Its name in the case.
    pub fn name(self) -> &'static str {
        match self {
            Coordinate::Axis(a) => ["x", "y", "z"][a],
            Coordinate::Radius { .. } => "r",
        }
    }
}

/// A temperature field along one coordinate (`along`, `profile`): the factor
/// of ΔT at the point's coordinate, linear between rows (coordinate mm,
/// factor).
#[derive(Clone, Debug, PartialEq)]
pub struct Profile {
    pub along: Coordinate,
    pub rows: Vec<[f64; 2]>,
}

/// A temperature field as a function of position (`field`): the factor of ΔT
/// at [x, y, z, r].
#[derive(Clone, Debug, PartialEq)]
pub struct Formula {
    pub expression: Expression,
    /// How r is measured: the model's dimension, and whether axisymmetric.
    dim: usize,
    axisymmetric: bool,
    /// The lowest and the highest factor over the body's nodes and Gauss
    /// points (both integrations).
    lo: f64,
    hi: f64,
}

impl Formula {
    /// The factor at point x.
    pub fn factor(&self, x: [f64; 3]) -> f64 {
        let r = radius(x, self.dim, self.axisymmetric);
        self.expression.value([x[0], x[1], x[2], r])
    }
}

/// A body's temperature field: ΔT(x) = ΔT × [`Field::factor`].
#[derive(Clone, Debug, PartialEq)]
pub enum Field {
    Profile(Profile),
    Formula(Formula),
}

impl Field {
    /// The factor at point x.
    pub fn factor(&self, x: [f64; 3]) -> f64 {
        match self {
            Field::Profile(p) => interpolate(&p.rows, p.along.of(x)),
            Field::Formula(f) => f.factor(x),
        }
    }

    /// The lowest and the highest factor: of the rows (a table), or over
    /// the body's nodes and Gauss points (an expression).
    pub(crate) fn extremes(&self) -> (f64, f64) {
        match self {
            Field::Profile(p) => (p.rows.iter())
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), r| {
                    (lo.min(r[1]), hi.max(r[1]))
                }),
            Field::Formula(f) => (f.lo, f.hi),
        }
    }

    /// The largest |factor|.
    pub(crate) fn largest(&self) -> f64 {
        let (lo, hi) = self.extremes();
        lo.abs().max(hi.abs())
    }
}

/// A `[[temperature]]`'s field, checked: `along` and `profile` together (a
/// table), or `field` alone (an expression); `None` without either.
pub(super) fn read(
    t: &TemperatureSpec,
    mesh: &Mesh,
    (body, section): (usize, &Section),
    at: &str,
) -> Result<Option<Field>> {
    let Some(text) = &t.field else {
        return Ok(profile(t, mesh, (body, section), at)?.map(Field::Profile));
    };
    if let Some(other) = [
        ("along", t.along.is_some()),
        ("profile", t.profile.is_some()),
    ]
    .iter()
    .find(|k| k.1)
    {
        return Err(Error::input(
            format!("{at} field"),
            format!("with `{}`: give the field one way, as an expression (`field`) or as a table (`along`, `profile`)", other.0),
        ));
    }
    formula(text, mesh, (body, section), at).map(|f| Some(Field::Formula(f)))
}

/// The expression `text` of `field`, parsed and checked: no coordinate the
/// model lacks (z in a plane model), a finite value at every node and Gauss
/// point of the body; with the extremes of its values there.
fn formula(
    text: &str,
    mesh: &Mesh,
    (body, section): (usize, &Section),
    at: &str,
) -> Result<Formula> {
    let key = format!("{at} field");
    let quoted = format!("in \"{}\"", clip(text));
    let expression = Expression::parse(text).map_err(|e| {
        Error::input(
            key.clone(),
            format!("column {}: {} ({quoted})", e.column, e.message),
        )
    })?;
    let dim = mesh.dim();
    if dim == 2 {
        if let Some((_, column)) = (expression.variables().into_iter()).find(|v| v.0 == Variable::Z)
        {
            return Err(Error::input(
                key,
                format!("column {column}: z is no coordinate of this plane model (x, y and r are) ({quoted})"),
            ));
        }
    }
    let mut f = Formula {
        expression,
        dim,
        axisymmetric: section.axisymmetric,
        lo: f64::INFINITY,
        hi: f64::NEG_INFINITY,
    };
    for (x, point) in sample_points(mesh, body, section) {
        let r = radius(x, dim, section.axisymmetric);
        match f.expression.checked([x[0], x[1], x[2], r]) {
            Ok(v) => (f.lo, f.hi) = (f.lo.min(v), f.hi.max(v)),
            Err(u) => {
                let coords = match dim {
                    3 => format!("({}, {}, {})", x[0], x[1], x[2]),
                    _ => format!("({}, {})", x[0], x[1]),
                };
                return Err(Error::input(
                    key,
                    format!(
                        "column {}: {} at {coords} mm ({}): give a field that is a finite number over the whole body ({quoted})",
                        u.column,
                        u.message,
                        point.describe(mesh)
                    ),
                ));
            }
        }
    }
    Ok(f)
}

/// A point where a field is read: a node, or a Gauss point of an element.
#[derive(Clone, Copy, Debug)]
enum Point {
    Node(usize),
    Gauss(usize, usize),
}

impl Point {
    fn describe(self, mesh: &Mesh) -> String {
        match self {
            Point::Node(n) => format!("node {n}"),
            Point::Gauss(e, ip) => format!("Gauss point {ip} of {}", mesh.element_label(e)),
        }
    }
}

/// Every node of body `body` and every Gauss point of its elements under
/// both integrations (the run's rule, and the other, at which the error
/// estimate may sample): every point a field is read at.
fn sample_points(mesh: &Mesh, body: usize, section: &Section) -> Vec<([f64; 3], Point)> {
    let mut out = Vec::new();
    let mut seen = vec![false; mesh.nodes.len()];
    for (e, el) in mesh.elements.iter().enumerate() {
        if el.body != body {
            continue;
        }
        for &n in el.nodes() {
            if !std::mem::replace(&mut seen[n], true) {
                out.push((mesh.nodes[n], Point::Node(n)));
            }
        }
        for full in [true, false] {
            gauss_points(mesh, e, el.family, section, full, &mut out);
        }
    }
    out
}

/// The Gauss points of element e under the full or the reduced rule
/// (geometry checked when the model was built: an element that fails here
/// has none to add).
fn gauss_points(
    mesh: &Mesh,
    e: usize,
    family: Family,
    section: &Section,
    full: bool,
    out: &mut Vec<([f64; 3], Point)>,
) {
    match family.solid() {
        None => {
            let coords = mesh.element_coords(e);
            let rule = family.rule(full);
            if let Ok(g) = ElementGeometry::with_section(family, &coords, &rule, section) {
                out.extend((0..g.n).map(|ip| ([g.x[ip][0], g.x[ip][1], 0.0], Point::Gauss(e, ip))));
            }
        }
        Some(solid) => {
            let coords = mesh.element_coords3(e);
            let rule = solid.rule(full);
            if let Ok(g) = ElementGeometry3::new(solid, &coords[..family.nodes()], &rule) {
                out.extend((0..g.n).map(|ip| (g.x[ip], Point::Gauss(e, ip))));
            }
        }
    }
}

/// A `[[temperature]]`'s table, checked: `along` and `profile` together,
/// `along` a coordinate of the model (or r), at least two rows [coordinate,
/// factor] of finite numbers with rising coordinates that span the body.
fn profile(
    t: &TemperatureSpec,
    mesh: &Mesh,
    (body, section): (usize, &Section),
    at: &str,
) -> Result<Option<Profile>> {
    let (along, rows) = match (&t.along, &t.profile) {
        (None, None) => return Ok(None),
        (Some(a), Some(r)) => (a, r),
        (Some(_), None) => {
            return Err(Error::input(
                format!("{at} along"),
                "needs `profile` (rows [coordinate mm, factor of change]): the field it runs along",
            ))
        }
        (None, Some(_)) => return Err(Error::input(
            format!("{at} profile"),
            "needs `along` (\"x\", \"y\", \"r\" or, in 3D, \"z\"): the coordinate its rows are given at",
        )),
    };
    let dim = mesh.dim();
    let axes: &[&str] = if dim == 3 {
        &["x", "y", "z", "r"]
    } else {
        &["x", "y", "r"]
    };
    let coordinate = match along.as_str() {
        "x" => Coordinate::Axis(0),
        "y" => Coordinate::Axis(1),
        "z" if dim == 3 => Coordinate::Axis(2),
        "r" => Coordinate::Radius {
            dim,
            axisymmetric: section.axisymmetric,
        },
        _ => {
            return Err(Error::input(
                format!("{at} along"),
                format!(
                    "\"{}\" is no coordinate of this model (one of {})",
                    clip(along),
                    axes.join(", ")
                ),
            ))
        }
    };
    let key = format!("{at} profile");
    let rows = checked_rows(rows, &key)?;
    // the body's extent along the coordinate, within the rows (not
    // extrapolated): its nodes, and for r its Gauss points too (r may be
    // least inside an element)
    let tol = crate::model::consistency::tolerance(mesh);
    let mut points: Vec<[f64; 3]> = (mesh.elements.iter())
        .filter(|e| e.body == body)
        .flat_map(|e| e.nodes().iter())
        .map(|&n| mesh.nodes[n])
        .collect();
    if matches!(coordinate, Coordinate::Radius { .. }) {
        points.extend(sample_points(mesh, body, section).into_iter().map(|p| p.0));
    }
    let (lo, hi) = (points.iter())
        .map(|&x| coordinate.of(x))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
    let (r0, r1) = (rows[0][0], rows[rows.len() - 1][0]);
    if lo < r0 - tol || hi > r1 + tol {
        return Err(Error::input(
            key,
            format!("spans {along} = {r0} … {r1} mm, but the body reaches {lo} … {hi} mm: give rows that cover it (a profile is not extrapolated)"),
        ));
    }
    Ok(Some(Profile {
        along: coordinate,
        rows,
    }))
}

/// A profile's rows: two finite numbers each, at least two, the
/// coordinates rising.
fn checked_rows(rows: &[Vec<f64>], key: &str) -> Result<Vec<[f64; 2]>> {
    if let Some(i) = rows.iter().position(|r| r.len() != 2) {
        return Err(Error::input(
            key,
            format!(
                "row {i} has {} number(s): each row is [coordinate mm, factor]",
                rows[i].len()
            ),
        ));
    }
    if rows.len() < 2 {
        return Err(Error::input(
            key,
            format!("has {} row(s): give at least two", rows.len()),
        ));
    }
    let rows: Vec<[f64; 2]> = rows.iter().map(|r| [r[0], r[1]]).collect();
    for (i, &[x, f]) in rows.iter().enumerate() {
        if !(x.is_finite() && f.is_finite()) {
            return Err(Error::input(
                key,
                format!("row {i}: [{x}, {f}] is not two finite numbers"),
            ));
        }
        if i > 0 && x <= rows[i - 1][0] {
            return Err(Error::input(
                key,
                format!(
                    "row {i}: {x} mm does not rise from row {}'s {} mm",
                    i - 1,
                    rows[i - 1][0]
                ),
            ));
        }
    }
    Ok(rows)
}

/// A table's value at t, linear between its rows (t within them: checked
/// when the model is built; held at the ends otherwise): a profile along
/// its coordinate, a property table at a temperature.
pub(crate) fn interpolate(rows: &[[f64; 2]], t: f64) -> f64 {
    let k = rows.partition_point(|r| r[0] <= t);
    match k {
        0 => rows[0][1],
        k if k == rows.len() => rows[k - 1][1],
        k => {
            let ([t0, v0], [t1, v1]) = (rows[k - 1], rows[k]);
            v0 + (v1 - v0) * (t - t0) / (t1 - t0)
        }
    }
}
