//! Line charts as SVG and PNG (plotters), with the numbers behind each in CSV.
//!
//! Text needs a font: [`load_font`] registers DejaVu Sans (or Liberation Sans)
//! from the system at run time, so the build needs no system library. Without a
//! font the CSV files are still written and the pictures are skipped.

use crate::error::{Error, Result};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

pub struct Series {
    pub label: String,
    pub points: Vec<(f64, f64)>,
}

/// A chart: lines, plus horizontal/vertical reference lines and labelled marks
/// (the paper's quoted numbers).
#[derive(Default)]
pub struct Chart {
    pub title: String,
    pub(crate) x_label: String,
    pub(crate) y_label: String,
    pub series: Vec<Series>,
    pub(crate) hlines: Vec<(f64, String)>,
    pub(crate) vlines: Vec<(f64, String)>,
    pub marks: Vec<(f64, f64, String)>,
    /// Legend in the lower left instead of the upper left.
    pub(crate) legend_low: bool,
}

/// Registers a sans-serif font found on the system (once per process: later
/// calls return the first answer); false if none.
pub fn load_font() -> bool {
    static LOADED: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
    *LOADED.get_or_init(register_font)
}

fn register_font() -> bool {
    let candidates = [
        "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
        "/usr/share/fonts/TTF/DejaVuSans.ttf",
        "/usr/share/fonts/dejavu/DejaVuSans.ttf",
        "/usr/share/fonts/truetype/liberation/LiberationSans-Regular.ttf",
    ];
    for c in candidates {
        if let Ok(bytes) = std::fs::read(c) {
            let bytes: &'static [u8] = Box::leak(bytes.into_boxed_slice());
            if plotters::style::register_font("sans-serif", FontStyle::Normal, bytes).is_ok() {
                return true;
            }
        }
    }
    false
}

/// Writes `<stem>.csv` and, with a font, `<stem>.svg` and `<stem>.png`.
pub fn save(chart: &Chart, stem: &Path, pictures: bool) -> Result<Vec<PathBuf>> {
    let mut csv = String::from("series,x,y\n");
    for s in &chart.series {
        for (x, y) in &s.points {
            let _ = writeln!(csv, "\"{}\",{x:.9e},{y:.9e}", s.label);
        }
    }
    for (y, l) in &chart.hlines {
        let _ = writeln!(csv, "\"reference: {l}\",,{y:.9e}");
    }
    for (x, l) in &chart.vlines {
        let _ = writeln!(csv, "\"reference: {l}\",{x:.9e},");
    }
    let mut written = vec![stem.with_extension("csv")];
    std::fs::write(&written[0], csv).map_err(|e| Error::io(&written[0], e))?;
    save_pictures(chart, stem, pictures)?;
    if pictures {
        written.push(stem.with_extension("svg"));
        written.push(stem.with_extension("png"));
    }
    Ok(written)
}

/// Writes `<stem>.svg` and `<stem>.png` when `pictures` (a font was found),
/// without the CSV of [`save`] (for callers that write their own data file).
pub(crate) fn save_pictures(chart: &Chart, stem: &Path, pictures: bool) -> Result<()> {
    if pictures {
        let svg = stem.with_extension("svg");
        draw(SVGBackend::new(&svg, (900, 600)).into_drawing_area(), chart)?;
        let png = stem.with_extension("png");
        draw(
            BitMapBackend::new(&png, (900, 600)).into_drawing_area(),
            chart,
        )?;
    }
    Ok(())
}

/// The chart as an SVG document of `size` pixels, in memory (for a page
/// that holds its pictures inline). Needs a font ([`load_font`]) to lay out
/// its text; the text itself is written as SVG `<text>` in `sans-serif`.
pub fn svg(chart: &Chart, size: (u32, u32)) -> Result<String> {
    let mut out = String::new();
    draw(
        SVGBackend::with_string(&mut out, size).into_drawing_area(),
        chart,
    )?;
    Ok(out)
}

/// The chart's data extent (series, marks and guide lines) and a 4 % pad.
struct Extent {
    x: (f64, f64),
    y: (f64, f64),
    pad: (f64, f64),
}

impl Extent {
    fn of(c: &Chart) -> Extent {
        let pts = c.series.iter().flat_map(|s| s.points.iter().copied());
        let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
        let finite = |p: &(f64, f64)| p.0.is_finite() && p.1.is_finite();
        for (x, y) in pts.chain(c.marks.iter().map(|m| (m.0, m.1))).filter(finite) {
            (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
        }
        if x0 > x1 {
            (x0, x1, y0, y1) = (0.0, 1.0, 0.0, 1.0);
        }
        for (y, _) in &c.hlines {
            (y0, y1) = (y0.min(*y), y1.max(*y));
        }
        for (x, _) in &c.vlines {
            (x0, x1) = (x0.min(*x), x1.max(*x));
        }
        // a range narrower than 1e-6 of its magnitude (or none) gets a pad
        // of 4 % of the magnitude: tick steps below the values' ulp never end
        let pad = |a: f64, b: f64| {
            let size = a.abs().max(b.abs());
            if b > a && b - a > 1e-6 * size {
                0.04 * (b - a)
            } else if size > 0.0 && size.is_finite() {
                0.04 * size
            } else {
                1.0
            }
        };
        Extent {
            x: (x0, x1),
            y: (y0, y1),
            pad: (pad(x0, x1), pad(y0, y1)),
        }
    }
}

/// A chart's drawing context on linear axes.
type Axes<'a, DB> = ChartContext<
    'a,
    DB,
    Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
>;

fn draw<DB: DrawingBackend>(root: DrawingArea<DB, Shift>, c: &Chart) -> Result<()> {
    let e = |m: String| Error::Output(format!("drawing \"{}\": {m}", c.title));
    root.fill(&WHITE).map_err(|x| e(x.to_string()))?;
    let ext = Extent::of(c);
    let ((x0, x1), (y0, y1), (px, py)) = (ext.x, ext.y, ext.pad);
    let mut chart = ChartBuilder::on(&root)
        .caption(&c.title, ("sans-serif", 22))
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d((x0 - px)..(x1 + px), (y0 - py)..(y1 + py))
        .map_err(|x| e(x.to_string()))?;
    chart
        .configure_mesh()
        .x_desc(&c.x_label)
        .y_desc(&c.y_label)
        .label_style(("sans-serif", 15))
        .draw()
        .map_err(|x| e(x.to_string()))?;
    draw_series(&mut chart, c).map_err(e)?;
    draw_guides(&mut chart, c, &ext).map_err(e)?;
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font(("sans-serif", 15))
        .position(if c.legend_low {
            SeriesLabelPosition::LowerLeft
        } else {
            SeriesLabelPosition::UpperLeft
        })
        .draw()
        .map_err(|x| e(x.to_string()))?;
    root.present().map_err(|x| e(x.to_string()))
}

/// Each series as a line with its points and a legend entry.
fn draw_series<DB: DrawingBackend>(
    chart: &mut Axes<'_, DB>,
    c: &Chart,
) -> std::result::Result<(), String> {
    for (i, s) in c.series.iter().enumerate() {
        let color = Palette99::pick(i).stroke_width(2);
        chart
            .draw_series(LineSeries::new(s.points.iter().copied(), color))
            .map_err(|x| x.to_string())?
            .label(&s.label)
            .legend(move |(x, y)| {
                PathElement::new(
                    vec![(x, y), (x + 20, y)],
                    Palette99::pick(i).stroke_width(2),
                )
            });
        chart
            .draw_series(
                s.points
                    .iter()
                    .map(|&p| Circle::new(p, 2, Palette99::pick(i).filled())),
            )
            .map_err(|x| x.to_string())?;
    }
    Ok(())
}

/// The labelled horizontal and vertical guide lines and the marks.
fn draw_guides<DB: DrawingBackend>(
    chart: &mut Axes<'_, DB>,
    c: &Chart,
    ext: &Extent,
) -> std::result::Result<(), String> {
    let ((x0, x1), (y0, y1), (px, py)) = (ext.x, ext.y, ext.pad);
    let grey = RGBColor(90, 90, 90);
    let text = |l: &str, at: (f64, f64), color: RGBColor| {
        Text::new(
            l.to_string(),
            at,
            ("sans-serif", 14).into_font().color(&color),
        )
    };
    for (k, (y, l)) in c.hlines.iter().enumerate() {
        chart
            .draw_series(LineSeries::new(
                vec![(x0 - px, *y), (x1 + px, *y)],
                grey.stroke_width(1),
            ))
            .map_err(|x| x.to_string())?;
        // labels staggered along x so that close lines stay readable
        let lx = x0 + (0.3 + 0.35 * k as f64) * (x1 - x0);
        chart
            .draw_series(std::iter::once(text(l, (lx, *y), grey)))
            .map_err(|x| x.to_string())?;
    }
    for (x, l) in &c.vlines {
        chart
            .draw_series(LineSeries::new(
                vec![(*x, y0 - py), (*x, y1 + py)],
                grey.stroke_width(1),
            ))
            .map_err(|x| x.to_string())?;
        chart
            .draw_series(std::iter::once(text(l, (*x, y1), grey)))
            .map_err(|x| x.to_string())?;
    }
    for (x, y, l) in &c.marks {
        chart
            .draw_series(std::iter::once(Cross::new(
                (*x, *y),
                6,
                RED.stroke_width(2),
            )))
            .map_err(|x| x.to_string())?;
        chart
            .draw_series(std::iter::once(text(l, (*x, *y), RED)))
            .map_err(|x| x.to_string())?;
    }
    Ok(())
}

/// A grid of cells (rows × columns), each green (ok) or red (failed) with a short
/// text: the stability map.
pub(crate) struct Grid {
    pub title: String,
    pub(crate) x_label: String,
    pub columns: Vec<String>,
    pub rows: Vec<String>,
    /// cells[row][column] = (ok, text); text lines separated by '\n'
    pub cells: Vec<Vec<(bool, String)>>,
    /// A cell drawn with a heavy frame (the program's default), with its caption.
    pub marked: Option<(usize, usize, String)>,
}

/// Writes `<stem>.csv` and, with a font, `<stem>.svg` and `<stem>.png`.
pub(crate) fn save_grid(g: &Grid, stem: &Path, pictures: bool) -> Result<Vec<PathBuf>> {
    let mut csv = String::from("row,column,ok,text\n");
    for (r, row) in g.cells.iter().enumerate() {
        for (c, (ok, t)) in row.iter().enumerate() {
            let t = t.replace('\n', "; ");
            let _ = writeln!(csv, "\"{}\",\"{}\",{ok},\"{t}\"", g.rows[r], g.columns[c]);
        }
    }
    let mut written = vec![stem.with_extension("csv")];
    std::fs::write(&written[0], csv).map_err(|e| Error::io(&written[0], e))?;
    if pictures {
        let h = 150 + 62 * g.rows.len() as u32;
        let w = (250 + 135 * g.columns.len() as u32).max(1000);
        let svg = stem.with_extension("svg");
        draw_grid(SVGBackend::new(&svg, (w, h)).into_drawing_area(), g)?;
        let png = stem.with_extension("png");
        draw_grid(BitMapBackend::new(&png, (w, h)).into_drawing_area(), g)?;
        written.push(svg);
        written.push(png);
    }
    Ok(written)
}

fn draw_grid<DB: DrawingBackend>(root: DrawingArea<DB, Shift>, g: &Grid) -> Result<()> {
    let e = |m: String| Error::Output(format!("drawing \"{}\": {m}", g.title));
    root.fill(&WHITE).map_err(|x| e(x.to_string()))?;
    let (w, h) = root.dim_in_pixel();
    let (left, top) = (230i32, 60i32);
    let cw = (w as i32 - left - 20) / g.columns.len().max(1) as i32;
    let ch = (h as i32 - top - 80) / g.rows.len().max(1) as i32;
    let font = ("sans-serif", 15).into_font();
    root.draw(&Text::new(
        g.title.clone(),
        (20, 15),
        ("sans-serif", 22).into_font(),
    ))
    .map_err(|x| e(x.to_string()))?;
    for (c, col) in g.columns.iter().enumerate() {
        root.draw(&Text::new(
            col.clone(),
            (left + c as i32 * cw + 10, top - 22),
            font.clone(),
        ))
        .map_err(|x| e(x.to_string()))?;
    }
    root.draw(&Text::new(
        g.x_label.clone(),
        (20, h as i32 - 58),
        font.clone(),
    ))
    .map_err(|x| e(x.to_string()))?;
    if let Some((_, _, caption)) = &g.marked {
        root.draw(&Text::new(
            caption.clone(),
            (20, h as i32 - 32),
            font.clone(),
        ))
        .map_err(|x| e(x.to_string()))?;
    }
    for (r, row) in g.rows.iter().enumerate() {
        let y = top + r as i32 * ch;
        root.draw(&Text::new(row.clone(), (10, y + ch / 2 - 8), font.clone()))
            .map_err(|x| e(x.to_string()))?;
        for (c, (ok, text)) in g.cells[r].iter().enumerate() {
            let x = left + c as i32 * cw;
            let color = if *ok {
                RGBColor(170, 220, 170)
            } else {
                RGBColor(235, 150, 150)
            };
            root.draw(&Rectangle::new(
                [(x + 2, y + 2), (x + cw - 2, y + ch - 2)],
                color.filled(),
            ))
            .map_err(|x| e(x.to_string()))?;
            let lines: Vec<&str> = text.lines().collect();
            let y0 = y + ch / 2 - 8 * lines.len() as i32;
            for (i, line) in lines.iter().enumerate() {
                root.draw(&Text::new(
                    line.to_string(),
                    (x + 8, y0 + 16 * i as i32),
                    ("sans-serif", 13).into_font(),
                ))
                .map_err(|x| e(x.to_string()))?;
            }
            if g.marked.as_ref().is_some_and(|m| (m.0, m.1) == (r, c)) {
                for k in 0..3 {
                    root.draw(&Rectangle::new(
                        [(x + 2 + k, y + 2 + k), (x + cw - 2 - k, y + ch - 2 - k)],
                        BLACK.stroke_width(1),
                    ))
                    .map_err(|x| e(x.to_string()))?;
                }
            }
        }
    }
    root.present().map_err(|x| e(x.to_string()))
}
