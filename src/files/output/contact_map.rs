//! The contact maps of a 3D run: per interface, `contact-<name>.svg` and
//! `.png` draw the contact pressure and the status (open, closed, stick,
//! micro-slip, macro-slip) over the interface at the run's last converged
//! state, with the numbers behind them (one row per integration point) in
//! `contact-<name>.csv`.
//!
//! An interface is drawn flat: a plane one (every point's normal within 30°
//! of the mean normal) on the coordinate plane most nearly its own (the
//! axis closest to the mean normal left out), a cylinder about the y axis
//! (every normal within 30° of the plane y = const) unrolled to
//! (r̄ (θ − θ̄), y), anything else projected on the coordinate plane of its
//! mean normal. Each face of body A's side is cut into 4 × 4 cells (a
//! triangle into 16) through its own shape functions, each cell coloured by
//! the integration point nearest its centre: with consistent weights that
//! is the cell's own Gauss point, with lumped weights its node's share.

use crate::error::{Error, Result};
use crate::files::plot::load_font;
use crate::input::mesh::{Family, Interface, Mesh};
use crate::model::interface::InterfaceModel;
use crate::model::Model;
use crate::physics::contact::Status;
use crate::solve::State;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::collections::HashMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// The header of `contact-<name>.csv`.
pub const CONTACT_MAP_HEADER: &str =
    "u_mm,v_mm,x_mm,y_mm,z_mm,area_mm2,p_n_mpa,u_n_mm,status,tangential_status\n";

/// One integration point of the map.
#[derive(Clone, Debug, PartialEq)]
pub struct MapPoint {
    /// Its place on the flat map (mm).
    pub uv: [f64; 2],
    /// Its place in space (mm).
    pub x: [f64; 3],
    /// Its area (mm²).
    pub area: f64,
    pub p_n: f64,
    pub u_n: f64,
    pub status: Status,
}

/// One cell drawn: its corners on the map and the point it shows.
#[derive(Clone, Debug, PartialEq)]
pub struct Cell {
    pub corners: Vec<[f64; 2]>,
    pub point: usize,
}

/// How an interface is laid flat.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Projection {
    /// Onto the plane of coordinate axes (i, j), the axis k left out.
    Axes { i: usize, j: usize, projected: bool },
    /// A cylinder about y unrolled about the mean direction θ̄ at radius r̄.
    Unrolled { theta: f64, r: f64 },
}

const AXES: [&str; 3] = ["x", "y", "z"];

impl Projection {
    /// The projection of points with these normals, areas and places.
    fn of(xs: &[[f64; 3]], normals: &[[f64; 3]], areas: &[f64]) -> Projection {
        let cos30 = 3f64.sqrt() / 2.0;
        let mut mean = [0.0; 3];
        for (n, a) in normals.iter().zip(areas) {
            for c in 0..3 {
                mean[c] += a * n[c];
            }
        }
        let len = crate::numbers::vec3::dot(mean, mean).sqrt();
        let plane = len > 0.0
            && normals
                .iter()
                .all(|n| crate::numbers::vec3::dot(*n, mean) >= cos30 * len);
        if !plane && normals.iter().all(|n| n[1].abs() <= 0.5) {
            let (sx, sz) = xs.iter().fold((0.0, 0.0), |(a, b), x| (a + x[0], b + x[2]));
            let r = xs.iter().map(|x| x[0].hypot(x[2])).sum::<f64>() / xs.len().max(1) as f64;
            return Projection::Unrolled {
                theta: sz.atan2(sx),
                r,
            };
        }
        // the coordinate axis closest to the mean normal is left out
        let k = (0..3)
            .max_by(|&a, &b| mean[a].abs().total_cmp(&mean[b].abs()))
            .unwrap_or(2);
        let (i, j) = match k {
            0 => (2, 1),
            1 => (0, 2),
            _ => (0, 1),
        };
        Projection::Axes {
            i,
            j,
            projected: !plane,
        }
    }

    fn uv(&self, x: [f64; 3]) -> [f64; 2] {
        match *self {
            Projection::Axes { i, j, .. } => [x[i], x[j]],
            Projection::Unrolled { theta, r } => {
                let pi = std::f64::consts::PI;
                let mut d = x[2].atan2(x[0]) - theta;
                while d > pi {
                    d -= 2.0 * pi;
                }
                while d <= -pi {
                    d += 2.0 * pi;
                }
                [r * d, x[1]]
            }
        }
    }

    /// The axes' labels (horizontal, up).
    fn labels(&self) -> (String, String) {
        match *self {
            Projection::Axes { i, j, projected } => {
                let note = if projected { " (projected)" } else { "" };
                (
                    format!("{} (mm){note}", AXES[i]),
                    format!("{} (mm){note}", AXES[j]),
                )
            }
            Projection::Unrolled { theta, r } => (
                format!(
                    "r̄ (θ − θ̄) (mm), r̄ = {} mm, θ = atan2(z, x), θ̄ = {:.1}°",
                    crate::numbers::sig(r, 4),
                    theta.to_degrees()
                ),
                "y (mm)".into(),
            ),
        }
    }
}

/// One interface's map.
#[derive(Clone, Debug, PartialEq)]
pub struct ContactMap {
    pub name: String,
    /// The axes' labels: horizontal, up.
    pub labels: (String, String),
    pub points: Vec<MapPoint>,
    pub cells: Vec<Cell>,
}

/// The maps of every interface of a 3D model at `state` (none in a plane
/// or axisymmetric model, nor for an interface without points).
pub fn contact_maps(model: &Model, state: &State) -> Vec<ContactMap> {
    if !model.node_dofs().solid() {
        return Vec::new();
    }
    let mut maps = Vec::new();
    let mut base = 0;
    for (im, iface) in model.interfaces.iter().zip(&model.mesh.interfaces) {
        let n = im.points.len();
        if n > 0 {
            let status = &state.status[base..base + n];
            maps.push(map_of(&model.mesh, iface, im, state, status));
        }
        base += n;
    }
    maps
}

fn map_of(
    mesh: &Mesh,
    iface: &Interface,
    im: &InterfaceModel,
    state: &State,
    status: &[Status],
) -> ContactMap {
    let gap = im.gap_at(state.time);
    let xs: Vec<[f64; 3]> = im.points.iter().map(|pt| im.point_position(pt)).collect();
    let normals: Vec<[f64; 3]> = im.points.iter().map(|pt| pt.normal).collect();
    let areas: Vec<f64> = im.points.iter().map(|pt| pt.area).collect();
    let proj = Projection::of(&xs, &normals, &areas);
    let points = im
        .points
        .iter()
        .enumerate()
        .map(|(k, pt)| {
            let u_n = im.point_kinematics_at(pt, &state.u, gap).0;
            MapPoint {
                uv: proj.uv(xs[k]),
                x: xs[k],
                area: pt.area,
                p_n: im.law.pressure(u_n).0,
                u_n,
                status: status[k],
            }
        })
        .collect();
    let nearest = Nearest::new(&xs, &areas);
    let faces: Vec<_> = match &iface.nonmatching_faces {
        Some(nm) => nm.slave.clone(),
        None => iface.faces.iter().map(|f| f.a.clone()).collect(),
    };
    let mut cells = Vec::new();
    for f in &faces {
        let nodes: Vec<[f64; 3]> = f.nodes().iter().map(|&n| mesh.nodes[n]).collect();
        for sub in subcells(f.family) {
            let at = |xi: [f64; 2]| -> [f64; 3] {
                let sh = f.family.shape(xi);
                std::array::from_fn(|c| (0..nodes.len()).map(|a| sh[a] * nodes[a][c]).sum())
            };
            let centre = {
                let k = sub.len() as f64;
                let s = sub.iter().fold([0.0; 2], |a, x| [a[0] + x[0], a[1] + x[1]]);
                at([s[0] / k, s[1] / k])
            };
            cells.push(Cell {
                corners: sub.iter().map(|&xi| proj.uv(at(xi))).collect(),
                point: nearest.of(centre),
            });
        }
    }
    ContactMap {
        name: im.name.clone(),
        labels: proj.labels(),
        points,
        cells,
    }
}

/// A face's cells in natural coordinates: a quadrilateral's 4 × 4 on
/// [−1, 1]², a triangle's 16 of its edges cut in four.
fn subcells(family: Family) -> Vec<Vec<[f64; 2]>> {
    const N: usize = 4;
    let mut out = Vec::with_capacity(N * N);
    if family == Family::T6 {
        let p = |i: usize, j: usize| [i as f64 / N as f64, j as f64 / N as f64];
        for j in 0..N {
            for i in 0..N - j {
                out.push(vec![p(i, j), p(i + 1, j), p(i, j + 1)]);
                if i + j + 1 < N {
                    out.push(vec![p(i + 1, j), p(i + 1, j + 1), p(i, j + 1)]);
                }
            }
        }
    } else {
        let c = |i: usize| -1.0 + 2.0 * i as f64 / N as f64;
        for j in 0..N {
            for i in 0..N {
                out.push(vec![
                    [c(i), c(j)],
                    [c(i + 1), c(j)],
                    [c(i + 1), c(j + 1)],
                    [c(i), c(j + 1)],
                ]);
            }
        }
    }
    out
}

/// The nearest of a set of points, by buckets of about a point's spacing.
struct Nearest<'a> {
    xs: &'a [[f64; 3]],
    size: f64,
    buckets: HashMap<[i64; 3], Vec<usize>>,
}

impl<'a> Nearest<'a> {
    fn new(xs: &'a [[f64; 3]], areas: &[f64]) -> Nearest<'a> {
        let mean = areas.iter().sum::<f64>() / areas.len().max(1) as f64;
        let size = mean.sqrt().max(1e-9);
        let mut buckets: HashMap<[i64; 3], Vec<usize>> = HashMap::new();
        for (k, x) in xs.iter().enumerate() {
            buckets.entry(Self::key(*x, size)).or_default().push(k);
        }
        Nearest { xs, size, buckets }
    }

    fn key(x: [f64; 3], size: f64) -> [i64; 3] {
        x.map(|c| (c / size).floor() as i64)
    }

    /// The index of the point nearest `x` (the first of equals).
    fn of(&self, x: [f64; 3]) -> usize {
        let k = Self::key(x, self.size);
        let d2 = |i: usize| {
            let d = crate::numbers::vec3::sub(self.xs[i], x);
            crate::numbers::vec3::dot(d, d)
        };
        let mut best: Option<(f64, usize)> = None;
        // rings of buckets until the best found is nearer than the next ring
        for r in 0i64.. {
            for dx in -r..=r {
                for dy in -r..=r {
                    for dz in -r..=r {
                        if dx.abs().max(dy.abs()).max(dz.abs()) != r {
                            continue;
                        }
                        for &i in self
                            .buckets
                            .get(&[k[0] + dx, k[1] + dy, k[2] + dz])
                            .into_iter()
                            .flatten()
                        {
                            let d = d2(i);
                            if best.is_none_or(|b| d < b.0 || (d == b.0 && i < b.1)) {
                                best = Some((d, i));
                            }
                        }
                    }
                }
            }
            if let Some((d, i)) = best {
                let reach = r as f64 * self.size;
                if d.sqrt() <= reach || r as usize > self.xs.len() {
                    return i;
                }
            }
            if r > 1 << 20 {
                break;
            }
        }
        best.map_or(0, |b| b.1)
    }
}

/// Keeps a name's letters, digits, `-` and `_` for a file name; any other
/// character becomes `_` (an interface name never leaves the folder).
pub fn file_stem(name: &str) -> String {
    let s: String = name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect();
    format!("contact-{s}")
}

/// `contact-<name>.csv`: one row per point, in the interface's order.
pub fn map_csv(map: &ContactMap) -> String {
    let mut s = String::from(CONTACT_MAP_HEADER);
    for p in &map.points {
        let _ = writeln!(
            s,
            "{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{},{}",
            p.uv[0],
            p.uv[1],
            p.x[0],
            p.x[1],
            p.x[2],
            p.area,
            p.p_n,
            p.u_n,
            p.status.name(),
            p.status.tangential_name()
        );
    }
    s
}

/// Writes every map's CSV and, with a font, its SVG and PNG into `dir`.
pub fn save_maps(maps: &[ContactMap], dir: &Path) -> Result<Vec<PathBuf>> {
    let pictures = !maps.is_empty() && load_font();
    let mut written = Vec::new();
    for map in maps {
        let stem = dir.join(file_stem(&map.name));
        let csv = stem.with_extension("csv");
        std::fs::write(&csv, map_csv(map)).map_err(|e| Error::io(&csv, e))?;
        written.push(csv);
        if pictures {
            let svg = stem.with_extension("svg");
            draw(SVGBackend::new(&svg, SIZE).into_drawing_area(), map)?;
            let png = stem.with_extension("png");
            draw(BitMapBackend::new(&png, SIZE).into_drawing_area(), map)?;
            written.push(svg);
            written.push(png);
        }
    }
    Ok(written)
}

const SIZE: (u32, u32) = (1300, 620);

/// The colour of a pressure: light grey at 0 (an open cell), then through yellow and orange to
/// dark red at the map's largest pressure.
fn pressure_colour(p: f64, p_max: f64) -> RGBColor {
    const STOPS: [(f64, [f64; 3]); 5] = [
        (0.0, [232.0, 232.0, 232.0]),
        (0.25, [255.0, 237.0, 160.0]),
        (0.5, [254.0, 178.0, 76.0]),
        (0.75, [240.0, 59.0, 32.0]),
        (1.0, [128.0, 0.0, 38.0]),
    ];
    let h = if p_max > 0.0 {
        (p / p_max).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let k = STOPS
        .windows(2)
        .position(|w| h <= w[1].0)
        .unwrap_or(STOPS.len() - 2);
    let (a, b) = (STOPS[k], STOPS[k + 1]);
    let f = (h - a.0) / (b.0 - a.0);
    let c = |i: usize| (a.1[i] + f * (b.1[i] - a.1[i])).round() as u8;
    RGBColor(c(0), c(1), c(2))
}

/// The status colours and names, in the legend's order.
const STATUSES: [(Status, RGBColor, &str); 5] = [
    (Status::Open, RGBColor(225, 225, 225), "open"),
    (
        Status::Closed,
        RGBColor(120, 150, 200),
        "closed (no friction law)",
    ),
    (Status::Stick, RGBColor(60, 140, 70), "stick"),
    (Status::MicroSlip, RGBColor(245, 170, 40), "micro-slip"),
    (Status::MacroSlip, RGBColor(200, 30, 30), "macro-slip"),
];

fn status_colour(s: Status) -> RGBColor {
    STATUSES
        .iter()
        .find(|t| t.0 == s)
        .map_or(RGBColor(0, 0, 0), |t| t.1)
}

/// The map's frame: mm to pixels, one scale for both axes.
struct Frame {
    origin: (i32, i32),
    size: (i32, i32),
    lo: [f64; 2],
    hi: [f64; 2],
    scale: f64,
}

impl Frame {
    /// The box of the corners given, fitted into `size` pixels at `origin`.
    fn fit<'a>(
        corners: impl Iterator<Item = &'a [f64; 2]>,
        origin: (i32, i32),
        size: (i32, i32),
    ) -> Frame {
        let mut lo = [f64::INFINITY; 2];
        let mut hi = [f64::NEG_INFINITY; 2];
        for p in corners {
            for c in 0..2 {
                lo[c] = lo[c].min(p[c]);
                hi[c] = hi[c].max(p[c]);
            }
        }
        let span = [(hi[0] - lo[0]).max(1e-12), (hi[1] - lo[1]).max(1e-12)];
        let scale = (size.0 as f64 / span[0]).min(size.1 as f64 / span[1]);
        Frame {
            origin,
            size,
            lo,
            hi,
            scale,
        }
    }

    fn contains(&self, p: &[f64; 2]) -> bool {
        let tol = 1e-9 * (self.hi[0] - self.lo[0]).max(self.hi[1] - self.lo[1]);
        (0..2).all(|c| p[c] >= self.lo[c] - tol && p[c] <= self.hi[c] + tol)
    }

    /// Pixel of a map point (v up).
    fn px(&self, p: &[f64; 2]) -> (i32, i32) {
        (
            self.origin.0 + ((p[0] - self.lo[0]) * self.scale).round() as i32,
            self.origin.1 + self.size.1 - ((p[1] - self.lo[1]) * self.scale).round() as i32,
        )
    }
}

/// The frame of a panel: the whole interface, or, where the closed part
/// spans less than half of it both ways, the closed part's box grown by a
/// half (a sphere's small contact on its large flat); with its caption.
fn panel_frame(map: &ContactMap, origin: (i32, i32), size: (i32, i32)) -> (Frame, &'static str) {
    let all = Frame::fit(map.cells.iter().flat_map(|c| &c.corners), origin, size);
    let closed = map
        .cells
        .iter()
        .filter(|c| map.points[c.point].status != Status::Open);
    let inner = Frame::fit(closed.flat_map(|c| &c.corners), origin, size);
    let span = |f: &Frame, c: usize| f.hi[c] - f.lo[c];
    let none_closed = inner.lo[0] > inner.hi[0];
    if none_closed || (0..2).any(|c| span(&inner, c) > 0.5 * span(&all, c)) {
        return (all, "");
    }
    let grow = 0.25 * span(&inner, 0).max(span(&inner, 1));
    let lo = [inner.lo[0] - grow, inner.lo[1] - grow];
    let hi = [inner.hi[0] + grow, inner.hi[1] + grow];
    let lo = [lo[0].max(all.lo[0]), lo[1].max(all.lo[1])];
    let hi = [hi[0].min(all.hi[0]), hi[1].min(all.hi[1])];
    (
        Frame::fit([lo, hi].iter(), origin, size),
        " (zoomed to the closed part)",
    )
}

fn draw<DB: DrawingBackend>(root: DrawingArea<DB, Shift>, map: &ContactMap) -> Result<()> {
    let err = |x: DrawingAreaErrorKind<DB::ErrorType>| {
        Error::Output(format!("drawing the contact map of \"{}\": {x}", map.name))
    };
    root.fill(&WHITE).map_err(err)?;
    let font = ("sans-serif", 15).into_font();
    let p_max = map.points.iter().map(|p| p.p_n).fold(0.0, f64::max);
    let (frame, zoom) = panel_frame(map, (0, 70), (560, 420));
    let title = format!(
        "Interface \"{}\": contact pressure and status, last converged state{zoom}",
        map.name
    );
    root.draw(&Text::new(title, (20, 12), ("sans-serif", 22).into_font()))
        .map_err(err)?;
    for (k, x0) in [40, 700].into_iter().enumerate() {
        let frame = Frame {
            origin: (x0, frame.origin.1),
            ..frame
        };
        root.draw(&Text::new(
            ["contact pressure p_n", "status"][k],
            (x0, 45),
            font.clone(),
        ))
        .map_err(err)?;
        for c in map
            .cells
            .iter()
            .filter(|c| c.corners.iter().all(|p| frame.contains(p)))
        {
            let p = &map.points[c.point];
            let colour = if k == 0 {
                pressure_colour(p.p_n, p_max)
            } else {
                status_colour(p.status)
            };
            let px: Vec<(i32, i32)> = c.corners.iter().map(|q| frame.px(q)).collect();
            root.draw(&Polygon::new(px, colour.filled())).map_err(err)?;
        }
        let bottom = frame.origin.1 + frame.size.1 + 14;
        let span = |c: usize| {
            format!(
                "{} … {}",
                crate::numbers::sig(frame.lo[c], 4),
                crate::numbers::sig(frame.hi[c], 4)
            )
        };
        root.draw(&Text::new(
            format!("→ {}: {}", map.labels.0, span(0)),
            (x0, bottom),
            font.clone(),
        ))
        .map_err(err)?;
        root.draw(&Text::new(
            format!("↑ {}: {}", map.labels.1, span(1)),
            (x0, bottom + 20),
            font.clone(),
        ))
        .map_err(err)?;
    }
    pressure_legend(&root, p_max, &font).map_err(err)?;
    status_legend(&root, map, &font).map_err(err)?;
    root.present().map_err(err)
}

fn pressure_legend<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    p_max: f64,
    font: &FontDesc,
) -> std::result::Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let (x0, y0, w) = (40, 570, 300);
    for i in 0..w {
        let c = pressure_colour(p_max * i as f64 / w as f64, p_max);
        root.draw(&Rectangle::new(
            [(x0 + i, y0), (x0 + i + 1, y0 + 16)],
            c.filled(),
        ))?;
    }
    root.draw(&Rectangle::new([(x0, y0), (x0 + w, y0 + 16)], BLACK))?;
    root.draw(&Text::new(
        format!("p_n: 0 … {} MPa", crate::numbers::sig(p_max, 4)),
        (x0 + w + 12, y0),
        font.clone(),
    ))
}

/// The statuses present, each with its share of the interface's area.
fn status_legend<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    map: &ContactMap,
    font: &FontDesc,
) -> std::result::Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let total: f64 = map.points.iter().map(|p| p.area).sum();
    let mut x = 700;
    for (s, c, name) in STATUSES {
        let a: f64 = map
            .points
            .iter()
            .filter(|p| p.status == s)
            .map(|p| p.area)
            .sum();
        if a == 0.0 {
            continue;
        }
        root.draw(&Rectangle::new([(x, 570), (x + 16, 586)], c.filled()))?;
        let label = format!("{name} {:.0} %", 100.0 * a / total.max(f64::MIN_POSITIVE));
        root.draw(&Text::new(label.clone(), (x + 22, 570), font.clone()))?;
        x += 40 + 8 * label.chars().count() as i32;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid(
        normal: [f64; 3],
        place: impl Fn(f64, f64) -> [f64; 3],
    ) -> (Vec<[f64; 3]>, Vec<[f64; 3]>) {
        let xs: Vec<[f64; 3]> = (0..9)
            .map(|k| place((k / 3) as f64, (k % 3) as f64))
            .collect();
        let n = xs.len();
        (xs, vec![normal; n])
    }

    #[test]
    fn a_plane_interface_is_drawn_on_its_own_coordinate_plane() {
        // the plane y = 3 facing +y: drawn on (x, z)
        let (xs, ns) = grid([0.0, 1.0, 0.0], |i, j| [i, 3.0, j]);
        let p = Projection::of(&xs, &ns, &[1.0; 9]);
        assert_eq!(p.labels(), ("x (mm)".into(), "z (mm)".into()));
        assert_eq!(p.uv(xs[5]), [xs[5][0], xs[5][2]]);
        // the plane x = 2 facing −x: drawn on (z, y)
        let (xs, ns) = grid([-1.0, 0.0, 0.0], |i, j| [2.0, i, j]);
        let p = Projection::of(&xs, &ns, &[1.0; 9]);
        assert_eq!(p.labels(), ("z (mm)".into(), "y (mm)".into()));
        assert_eq!(p.uv(xs[7]), [xs[7][2], xs[7][1]]);
    }

    #[test]
    fn a_cylinder_about_y_is_unrolled_without_a_jump() {
        // a half cylinder of radius 10 from θ = 0 through 180°: arc lengths
        // from the middle, symmetric, no wrap at ±180°
        let xs: Vec<[f64; 3]> = (0..=8)
            .map(|k| {
                let t = std::f64::consts::PI * k as f64 / 8.0;
                [10.0 * t.cos(), 1.0, 10.0 * t.sin()]
            })
            .collect();
        let ns: Vec<[f64; 3]> = xs.iter().map(|x| [x[0] / 10.0, 0.0, x[2] / 10.0]).collect();
        let p = Projection::of(&xs, &ns, &[1.0; 9]);
        assert!(p.labels().0.starts_with("r̄ (θ − θ̄)"));
        let uv: Vec<[f64; 2]> = xs.iter().map(|&x| p.uv(x)).collect();
        let quarter = 10.0 * std::f64::consts::FRAC_PI_2;
        assert!((uv[0][0] + quarter).abs() < 1e-12, "{:?}", uv[0]);
        assert!((uv[8][0] - quarter).abs() < 1e-12, "{:?}", uv[8]);
        assert!(uv.windows(2).all(|w| w[1][0] > w[0][0]));
    }

    #[test]
    fn cells_tile_a_face_and_find_their_nearest_point() {
        // 16 cells of a quadrilateral cover its area 4, 16 of a triangle its ½
        let area = |c: &Vec<[f64; 2]>| {
            let n = c.len();
            (0..n)
                .map(|i| c[i][0] * c[(i + 1) % n][1] - c[(i + 1) % n][0] * c[i][1])
                .sum::<f64>()
                / 2.0
        };
        let q: f64 = subcells(Family::Q8).iter().map(area).sum();
        let t: f64 = subcells(Family::T6).iter().map(area).sum();
        assert_eq!(subcells(Family::T6).len(), 16);
        assert!(
            (q - 4.0).abs() < 1e-14 && (t - 0.5).abs() < 1e-14,
            "{q} {t}"
        );
        assert!(subcells(Family::T6).iter().all(|c| area(c) > 0.0));
        // the nearest of a scattered cloud, against a scan
        let xs: Vec<[f64; 3]> = (0..200)
            .map(|k| {
                let f = k as f64;
                [
                    (f * 0.618).fract() * 10.0,
                    (f * 0.414).fract() * 3.0,
                    (f * 0.732).fract(),
                ]
            })
            .collect();
        let near = Nearest::new(&xs, &vec![0.1; xs.len()]);
        for probe in [
            [0.0, 0.0, 0.0],
            [5.1, 1.2, 0.4],
            [9.9, 2.9, 1.0],
            [20.0, -5.0, 3.0],
        ] {
            let d = |i: usize| {
                let v = crate::numbers::vec3::sub(xs[i], probe);
                crate::numbers::vec3::dot(v, v)
            };
            let scan = (0..xs.len())
                .min_by(|&a, &b| d(a).total_cmp(&d(b)))
                .unwrap();
            assert_eq!(d(near.of(probe)), d(scan), "{probe:?}");
        }
    }

    #[test]
    fn the_colours_run_from_grey_to_dark_red_and_names_stay_in_the_folder() {
        assert_eq!(pressure_colour(0.0, 5.0), RGBColor(232, 232, 232));
        assert_eq!(pressure_colour(5.0, 5.0), RGBColor(128, 0, 38));
        assert_eq!(pressure_colour(-1.0, 0.0), RGBColor(232, 232, 232));
        assert_eq!(file_stem("joint"), "contact-joint");
        assert_eq!(file_stem("../a b"), "contact-___a_b");
    }
}
