//! The picture of the undeformed mesh, as inline SVG: in the plane every
//! element's outline (through its midside nodes), filled by body, with the
//! interfaces' edges drawn over it in red; in 3D the boundary faces in an
//! isometric view from (1, 1, 1), back faces dropped and the rest painted
//! far to near, shaded by their normal (no other hidden-line removal).

use super::vtu::Grid;
use std::collections::HashMap;
use std::fmt::Write as _;

/// Light fills, one per body (repeated beyond eight bodies).
pub(super) const BODY_COLOURS: [&str; 8] = [
    "#9ecae1", "#fdd0a2", "#c7e9c0", "#dadaeb", "#fcbba1", "#fee391", "#c6dbef", "#d9d9d9",
];
/// The interfaces' colour.
pub(super) const INTERFACE_COLOUR: &str = "#d62728";
/// Width of the picture, px.
const WIDTH: f64 = 820.0;
/// Most height, px.
const HEIGHT: f64 = 620.0;
const MARGIN: f64 = 12.0;
/// Most cells drawn one by one; a larger plane mesh is drawn by its bodies'
/// outlines.
const MOST_CELLS: usize = 20_000;

/// The SVG of the mesh and a sentence on what it shows.
pub(super) struct Picture {
    pub svg: String,
    pub caption: String,
}

/// The picture of `grid`: plane or 3D.
pub(super) fn picture(grid: &Grid) -> Picture {
    if grid.solid() {
        solid(grid)
    } else {
        plane(grid)
    }
}

/// Maps model coordinates (already projected to the picture's plane, y up)
/// to pixels, the whole `points` fitted in the frame with one scale.
struct Frame {
    x0: f64,
    y0: f64,
    scale: f64,
    height: f64,
}

impl Frame {
    fn fit(points: impl Iterator<Item = [f64; 2]>) -> Frame {
        let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
        for [x, y] in points.filter(|p| p[0].is_finite() && p[1].is_finite()) {
            (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
        }
        if x0 > x1 {
            (x0, x1, y0, y1) = (0.0, 1.0, 0.0, 1.0);
        }
        let span = |a: f64, b: f64| (b - a).max(1e-12 * a.abs().max(b.abs())).max(1e-300);
        let scale =
            ((WIDTH - 2.0 * MARGIN) / span(x0, x1)).min((HEIGHT - 2.0 * MARGIN) / span(y0, y1));
        Frame {
            x0,
            y0,
            scale,
            height: (y1 - y0) * scale + 2.0 * MARGIN,
        }
    }

    /// `x,y` of a point in pixels, to 0.1 px.
    fn px(&self, [x, y]: [f64; 2]) -> String {
        let sx = MARGIN + (x - self.x0) * self.scale;
        let sy = self.height - MARGIN - (y - self.y0) * self.scale;
        format!("{sx:.1},{sy:.1}")
    }

    fn open(&self, title: &str) -> String {
        format!(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{WIDTH}\" height=\"{h:.0}\" viewBox=\"0 0 {WIDTH} {h:.0}\" role=\"img\"><title>{title}</title>",
            h = self.height
        )
    }
}

/// A closed path through `points` (pixels).
fn path(frame: &Frame, points: impl Iterator<Item = [f64; 2]>) -> String {
    let mut d = String::new();
    for (i, p) in points.enumerate() {
        d.push(if i == 0 { 'M' } else { 'L' });
        d.push_str(&frame.px(p));
    }
    d.push('Z');
    d
}

/// The plane mesh: element outlines filled by body (the bodies' free edges
/// alone beyond [`MOST_CELLS`]), interface edges in red.
fn plane(grid: &Grid) -> Picture {
    let xy = |n: usize| [grid.points[n][0], grid.points[n][1]];
    let frame = Frame::fit(grid.points.iter().map(|p| [p[0], p[1]]));
    let mut svg = frame.open("the undeformed mesh");
    let each = grid.cells.len() <= MOST_CELLS;
    if each {
        for c in 0..grid.cells.len() {
            let nodes = grid.nodes(c);
            let outline = grid.cells[c]
                .0
                .edges()
                .iter()
                .flat_map(|e| [xy(nodes[e[0]]), xy(nodes[e[1]])]);
            let fill = BODY_COLOURS[grid.body[c] % BODY_COLOURS.len()];
            let _ = write!(
                svg,
                "<path d=\"{}\" fill=\"{fill}\" stroke=\"#4d4d4d\" stroke-width=\"0.6\"/>",
                path(&frame, outline)
            );
        }
    }
    for ([a, m, b], _) in free_edges(grid) {
        let interface = [a, m, b].iter().all(|&n| grid.on_interface[n]);
        if !each || interface {
            let (colour, width) = if interface {
                (INTERFACE_COLOUR, 2.5)
            } else {
                ("#4d4d4d", 1.0)
            };
            let _ = write!(
                svg,
                "<polyline points=\"{} {} {}\" fill=\"none\" stroke=\"{colour}\" stroke-width=\"{width}\"/>",
                frame.px(xy(a)),
                frame.px(xy(m)),
                frame.px(xy(b)),
            );
        }
    }
    svg.push_str("</svg>");
    let drawn = if each {
        "every element's outline"
    } else {
        "the bodies' outlines (too many elements to draw one by one)"
    };
    Picture {
        svg,
        caption: format!("{drawn}, through the midside nodes; interface edges in red"),
    }
}

/// The edges of the plane mesh that belong to one element only ([end, mid,
/// end] global nodes, with that element): the bodies' outlines, the two
/// sides of an interface included.
fn free_edges(grid: &Grid) -> Vec<([usize; 3], usize)> {
    let mut seen: HashMap<[usize; 3], Option<([usize; 3], usize)>> = HashMap::new();
    let mut order = Vec::new();
    for c in 0..grid.cells.len() {
        let nodes = grid.nodes(c);
        for e in grid.cells[c].0.edges() {
            let edge = [nodes[e[0]], nodes[e[1]], nodes[e[2]]];
            let key = [edge[0].min(edge[2]), edge[1], edge[0].max(edge[2])];
            match seen.get_mut(&key) {
                Some(slot) => *slot = None,
                None => {
                    seen.insert(key, Some((edge, c)));
                    order.push(key);
                }
            }
        }
    }
    order.into_iter().filter_map(|k| seen[&k]).collect()
}

/// The isometric view's axes: right, up and towards the viewer.
const RIGHT: [f64; 3] = [
    std::f64::consts::FRAC_1_SQRT_2,
    0.0,
    -std::f64::consts::FRAC_1_SQRT_2,
];
const UP: [f64; 3] = [
    -0.408_248_290_463_863,
    0.816_496_580_927_726,
    -0.408_248_290_463_863,
];
const VIEW: [f64; 3] = [
    0.577_350_269_189_626,
    0.577_350_269_189_626,
    0.577_350_269_189_626,
];

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The 3D mesh's boundary faces seen from (1, 1, 1), y up.
fn solid(grid: &Grid) -> Picture {
    let faces = boundary_faces(grid);
    let project = |n: usize| [dot(grid.points[n], RIGHT), dot(grid.points[n], UP)];
    let mut visible: Vec<(f64, f64, &Vec<usize>, usize)> = faces
        .iter()
        .filter_map(|(outline, c)| {
            let normal = newell(outline.iter().map(|&n| grid.points[n]));
            let length = dot(normal, normal).sqrt();
            let facing = dot(normal, VIEW) / length;
            let depth = outline
                .iter()
                .map(|&n| dot(grid.points[n], VIEW))
                .sum::<f64>()
                / outline.len() as f64;
            let light = dot(normal, [0.27, 0.8, 0.53]) / length;
            (facing > 1e-9).then_some((depth, 0.62 + 0.38 * light.max(0.0), outline, *c))
        })
        .collect();
    visible.sort_by(|a, b| a.0.total_cmp(&b.0));
    let frame = Frame::fit(faces.iter().flat_map(|f| f.0.iter()).map(|&n| project(n)));
    let mut svg = frame.open("the undeformed mesh, isometric view");
    for (_, shade, outline, c) in &visible {
        let fill = shaded(BODY_COLOURS[grid.body[*c] % BODY_COLOURS.len()], *shade);
        let _ = write!(
            svg,
            "<path d=\"{}\" fill=\"{fill}\" stroke=\"#333333\" stroke-width=\"0.5\" stroke-linejoin=\"round\"/>",
            path(&frame, outline.iter().map(|&n| project(n)))
        );
    }
    triad(&mut svg, frame.height);
    svg.push_str("</svg>");
    Picture {
        svg,
        caption: format!(
            "{} of {} boundary faces seen from the direction (1, 1, 1), y up (isometric, not to a perspective); faces turned away are not drawn, the others painted from far to near",
            visible.len(),
            faces.len()
        ),
    }
}

/// The faces that belong to one cell only, each as its outline (corner,
/// midside, corner, …) of global nodes, with the cell.
fn boundary_faces(grid: &Grid) -> Vec<(Vec<usize>, usize)> {
    let mut seen: HashMap<Vec<usize>, Option<(Vec<usize>, usize)>> = HashMap::new();
    let mut order = Vec::new();
    for c in 0..grid.cells.len() {
        let Some(shape) = grid.cells[c].0.solid() else {
            continue;
        };
        let nodes = grid.nodes(c);
        for face in shape.faces() {
            let k = face.len() / 2;
            let outline: Vec<usize> = (0..k)
                .flat_map(|i| [nodes[face[i]], nodes[face[k + i]]])
                .collect();
            let mut key: Vec<usize> = face[..k].iter().map(|&i| nodes[i]).collect();
            key.sort_unstable();
            match seen.get_mut(&key) {
                Some(slot) => *slot = None,
                None => {
                    seen.insert(key.clone(), Some((outline, c)));
                    order.push(key);
                }
            }
        }
    }
    order
        .into_iter()
        .filter_map(|k| seen.remove(&k).flatten())
        .collect()
}

/// The normal of a polygon by Newell's rule (its length twice the area of
/// a plane polygon), outward for a face walked counter-clockwise from
/// outside.
fn newell(points: impl Iterator<Item = [f64; 3]>) -> [f64; 3] {
    let p: Vec<[f64; 3]> = points.collect();
    let mut n = [0.0; 3];
    for (i, a) in p.iter().enumerate() {
        let b = p[(i + 1) % p.len()];
        n[0] += (a[1] - b[1]) * (a[2] + b[2]);
        n[1] += (a[2] - b[2]) * (a[0] + b[0]);
        n[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
    n
}

/// `#rrggbb` darkened to `shade` (0 to 1).
fn shaded(colour: &str, shade: f64) -> String {
    let channel = |i: usize| u8::from_str_radix(&colour[1 + 2 * i..3 + 2 * i], 16).unwrap_or(200);
    let s = |i: usize| (f64::from(channel(i)) * shade).round().clamp(0.0, 255.0) as u8;
    format!("#{:02x}{:02x}{:02x}", s(0), s(1), s(2))
}

/// The directions x, y, z drawn small in the lower left corner.
fn triad(svg: &mut String, height: f64) {
    let (ox, oy) = (40.0, height - 40.0);
    for (axis, label) in [
        ([1.0, 0.0, 0.0], "x"),
        ([0.0, 1.0, 0.0], "y"),
        ([0.0, 0.0, 1.0], "z"),
    ] {
        let (dx, dy) = (28.0 * dot(axis, RIGHT), -28.0 * dot(axis, UP));
        let _ = write!(
            svg,
            "<line x1=\"{ox}\" y1=\"{oy}\" x2=\"{:.1}\" y2=\"{:.1}\" stroke=\"#000000\" stroke-width=\"1.5\"/><text x=\"{:.1}\" y=\"{:.1}\" font-family=\"sans-serif\" font-size=\"13\">{label}</text>",
            ox + dx,
            oy + dy,
            ox + 1.3 * dx - 4.0,
            oy + 1.3 * dy + 4.0
        );
    }
}

/// Section 2: the picture with its legend (bodies by name, as summary.json
/// `peaks` lists them in mesh order), or why there is none.
pub(super) fn section(page: &mut super::html::Page, f: &super::read::Folder) {
    use super::html::esc;
    page.section("mesh", "The mesh");
    let (rel, grid) = match &f.mesh {
        Ok(m) => m,
        Err(why) => {
            page.absent(&format!("No mesh picture: {why}."));
            return;
        }
    };
    let names: Vec<String> = f
        .summary
        .get("peaks")
        .and_then(serde_json::Value::as_array)
        .map(|a| {
            a.iter()
                .map(|p| super::text(p, "body").unwrap_or_default())
                .collect()
        })
        .unwrap_or_default();
    let mut bodies: Vec<usize> = grid.body.clone();
    bodies.sort_unstable();
    bodies.dedup();
    let mut legend = String::from("<p>");
    for b in bodies.iter().take(BODY_COLOURS.len()) {
        let name = names
            .get(*b)
            .cloned()
            .unwrap_or_else(|| format!("body {b}"));
        let _ = write!(
            legend,
            "<span class=\"swatch\" style=\"background:{}\"></span>{}",
            BODY_COLOURS[b % BODY_COLOURS.len()],
            esc(&name)
        );
    }
    if !grid.solid() && grid.on_interface.iter().any(|&i| i) {
        let _ = write!(
            legend,
            "<span class=\"swatch\" style=\"background:{INTERFACE_COLOUR}\"></span>interfaces"
        );
    }
    legend.push_str("</p>");
    let pic = picture(grid);
    let caption = format!(
        "The undeformed mesh from {rel}: {} elements, {} nodes; {}.{}",
        grid.cells.len(),
        grid.points.len(),
        pic.caption,
        if f.summary.get("plane").and_then(serde_json::Value::as_str) == Some("axisymmetric") {
            " Axisymmetric: x is the radius r, y the axis z."
        } else {
            ""
        }
    );
    page.figure(&pic.svg, &caption);
    page.raw(&legend);
}
