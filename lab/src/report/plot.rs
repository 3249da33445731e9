//! How the figures draw: log-log panels of at most eight series, each
//! series told apart by colour and marker (and a dash for every other one),
//! with the legend beside the data rather than on it, and faded markers for
//! points that are shown but were not used (rungs outside a fitted window).

use plotters::coord::Shift;
use plotters::prelude::*;

/// At most this many series share a panel: the palette's size, so that no
/// two series of a panel share a colour or a marker.
pub const MAX_SERIES: usize = 8;

/// The colour of the `i`-th series of a panel (or of a figure of one panel).
pub fn colour(i: usize) -> RGBColor {
    PALETTE[i % MAX_SERIES]
}

/// Okabe and Ito's palette for colour-blind readers (its yellow darkened to
/// stand out on white), one colour a series of a panel.
const PALETTE: [RGBColor; MAX_SERIES] = [
    RGBColor(0, 0, 0),
    RGBColor(230, 159, 0),
    RGBColor(86, 180, 233),
    RGBColor(0, 158, 115),
    RGBColor(180, 160, 0),
    RGBColor(0, 114, 178),
    RGBColor(213, 94, 0),
    RGBColor(204, 121, 167),
];

/// The marker shapes, paired with the palette so that a series differs from
/// every other of its panel in both.
#[derive(Clone, Copy)]
enum Marker {
    Circle,
    Triangle,
    Square,
    Diamond,
    Cross,
    Plus,
    InvertedTriangle,
    Star,
}

const MARKERS: [Marker; MAX_SERIES] = [
    Marker::Circle,
    Marker::Triangle,
    Marker::Square,
    Marker::Diamond,
    Marker::Cross,
    Marker::Plus,
    Marker::InvertedTriangle,
    Marker::Star,
];

/// One point of a series; `used` false draws its marker faded.
#[derive(Clone, Copy, Debug)]
pub struct Point {
    /// The abscissa.
    pub x: f64,
    /// The ordinate.
    pub y: f64,
    /// Part of what was fitted or judged.
    pub used: bool,
}

/// A named line of points.
#[derive(Clone, Debug)]
pub struct Series {
    /// The legend's text.
    pub name: String,
    /// The points, in the order the line joins them.
    pub points: Vec<Point>,
}

impl Series {
    /// A series whose points all count.
    pub fn plain(name: impl Into<String>, points: impl IntoIterator<Item = (f64, f64)>) -> Self {
        Series {
            name: name.into(),
            points: points
                .into_iter()
                .map(|(x, y)| Point { x, y, used: true })
                .collect(),
        }
    }
}

/// One panel: a title and its series.
#[derive(Clone, Debug)]
pub struct Panel {
    /// Drawn above the panel.
    pub title: String,
    /// At most [`MAX_SERIES`].
    pub series: Vec<Series>,
}

/// The plotting library's error as text: figures are best effort for the
/// caller, who reports a failure as an I/O problem of the figure file.
pub fn drawing<E: std::fmt::Debug>(e: E) -> std::io::Error {
    std::io::Error::other(format!("{e:?}"))
}

/// Width of one panel's plot, and of its legend beside it, in pixels.
const PLOT_WIDTH: u32 = 520;
const LEGEND_WIDTH: u32 = 250;
const PANEL_HEIGHT: u32 = 420;
const TITLE_HEIGHT: u32 = 40;
const MARKER_SIZE: i32 = 4;
/// At most this many markers on one series.
const MAX_MARKERS: usize = 24;

/// Log-log panels in a grid of two columns under one title, every panel on
/// its own axes; non-positive and non-finite points are left out. A panel
/// with more than [`MAX_SERIES`] series is refused, so no figure can fall
/// back to sharing colours.
pub fn log_log_panels(
    title: &str,
    x_desc: &str,
    y_desc: &str,
    panels: &[Panel],
) -> Result<String, std::io::Error> {
    if let Some(p) = panels.iter().find(|p| p.series.len() > MAX_SERIES) {
        return Err(std::io::Error::other(format!(
            "panel \"{}\" has {} series, more than {MAX_SERIES}",
            p.title,
            p.series.len()
        )));
    }
    let columns = panels.len().clamp(1, 2) as u32;
    let rows = panels.len().div_ceil(2).max(1) as u32;
    let size = (
        columns * (PLOT_WIDTH + LEGEND_WIDTH),
        TITLE_HEIGHT + rows * PANEL_HEIGHT,
    );
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, size).into_drawing_area();
        root.fill(&WHITE).map_err(drawing)?;
        let root = root.titled(title, ("sans-serif", 22)).map_err(drawing)?;
        let cells = root.split_evenly((rows as usize, columns as usize));
        for (panel, cell) in panels.iter().zip(&cells) {
            let (plot, legend) = cell.split_horizontally(PLOT_WIDTH);
            draw_panel(&plot, panel, x_desc, y_desc)?;
            draw_legend(&legend, &panel.series)?;
        }
        root.present().map_err(drawing)?;
    }
    Ok(svg)
}

/// The range of the finite positive values, widened by `pad` on a log
/// scale; a fixed decade when there is nothing to show.
fn log_range(values: impl Iterator<Item = f64>, pad: f64) -> std::ops::Range<f64> {
    let (lo, hi) = values
        .filter(|v| v.is_finite() && *v > 0.0)
        .fold((f64::MAX, f64::MIN), |(lo, hi), v| (lo.min(v), hi.max(v)));
    if lo >= hi {
        return 1e-3..1.0;
    }
    lo / pad..hi * pad
}

fn shown(p: &Point) -> bool {
    p.x.is_finite() && p.y.is_finite() && p.x > 0.0 && p.y > 0.0
}

fn draw_panel(
    area: &DrawingArea<SVGBackend, Shift>,
    panel: &Panel,
    x_desc: &str,
    y_desc: &str,
) -> Result<(), std::io::Error> {
    let points = || {
        panel
            .series
            .iter()
            .flat_map(|s| &s.points)
            .filter(|p| shown(p))
    };
    let mut chart = ChartBuilder::on(area)
        .caption(&panel.title, ("sans-serif", 16))
        .margin(10)
        .x_label_area_size(40)
        .y_label_area_size(62)
        .build_cartesian_2d(
            log_range(points().map(|p| p.x), 1.5).log_scale(),
            log_range(points().map(|p| p.y), 3.0).log_scale(),
        )
        .map_err(drawing)?;
    chart
        .configure_mesh()
        .x_desc(x_desc)
        .y_desc(y_desc)
        .x_label_formatter(&|x| format!("{x:.0e}"))
        .y_label_formatter(&|y| format!("{y:.0e}"))
        .light_line_style(WHITE.mix(0.0))
        .draw()
        .map_err(drawing)?;
    for (i, series) in panel.series.iter().enumerate() {
        let colour = PALETTE[i];
        let line: Vec<(f64, f64)> = series
            .points
            .iter()
            .filter(|p| shown(p))
            .map(|p| (p.x, p.y))
            .collect();
        if i % 2 == 1 {
            chart
                .draw_series(DashedLineSeries::new(line, 8, 5, colour.stroke_width(2)))
                .map_err(drawing)?;
        } else {
            chart
                .draw_series(LineSeries::new(line, colour.stroke_width(2)))
                .map_err(drawing)?;
        }
        // a dense series (a long run's samples) gets a marker every few
        // points, enough to tell it apart, not so many that they merge
        let shown_points: Vec<&Point> = series.points.iter().filter(|p| shown(p)).collect();
        let stride = shown_points.len().div_ceil(MAX_MARKERS).max(1);
        for p in shown_points.into_iter().step_by(stride) {
            // a point outside what was fitted keeps its marker, faded
            let style = if p.used {
                colour.filled()
            } else {
                colour.mix(0.3).filled()
            };
            for (closed, outline) in marker_pieces(MARKERS[i]) {
                let at = EmptyElement::at((p.x, p.y));
                if closed {
                    chart.draw_series(std::iter::once(at + Polygon::new(outline, style)))
                } else {
                    chart.draw_series(std::iter::once(
                        at + PathElement::new(outline, style.stroke_width(2)),
                    ))
                }
                .map_err(drawing)?;
            }
        }
    }
    Ok(())
}

/// The legend beside a panel: for each series its line (dashed where the
/// panel's line is), its marker and its name.
fn draw_legend(
    area: &DrawingArea<SVGBackend, Shift>,
    series: &[Series],
) -> Result<(), std::io::Error> {
    let top = 50;
    for (i, s) in series.iter().enumerate() {
        let colour = PALETTE[i];
        let y = top + 22 * i as i32;
        if i % 2 == 1 {
            for x in [4, 16] {
                area.draw(&PathElement::new(
                    vec![(x, y), (x + 8, y)],
                    colour.stroke_width(2),
                ))
                .map_err(drawing)?;
            }
        } else {
            area.draw(&PathElement::new(
                vec![(4, y), (28, y)],
                colour.stroke_width(2),
            ))
            .map_err(drawing)?;
        }
        for (closed, outline) in marker_pieces(MARKERS[i]) {
            let moved: Vec<(i32, i32)> =
                outline.iter().map(|&(dx, dy)| (16 + dx, y + dy)).collect();
            if closed {
                area.draw(&Polygon::new(moved, colour.filled()))
            } else {
                area.draw(&PathElement::new(moved, colour.stroke_width(2)))
            }
            .map_err(drawing)?;
        }
        area.draw(&Text::new(
            s.name.clone(),
            (36, y - 7),
            ("sans-serif", 13).into_font().color(&BLACK),
        ))
        .map_err(drawing)?;
    }
    Ok(())
}

/// The pieces of a marker around its centre, in pixels: closed outlines
/// (filled by the style) and open strokes.
fn marker_pieces(shape: Marker) -> Vec<(bool, Vec<(i32, i32)>)> {
    let r = MARKER_SIZE;
    let d = r + 1;
    match shape {
        Marker::Circle => {
            let ring = (0..12)
                .map(|k| {
                    let a = std::f64::consts::PI * f64::from(k) / 6.0;
                    (
                        (f64::from(r) * a.cos()).round() as i32,
                        (f64::from(r) * a.sin()).round() as i32,
                    )
                })
                .collect();
            vec![(true, ring)]
        }
        Marker::Triangle => vec![(true, vec![(0, -d), (d, r), (-d, r)])],
        Marker::InvertedTriangle => vec![(true, vec![(0, d), (d, -r), (-d, -r)])],
        Marker::Square => vec![(true, vec![(-r, -r), (r, -r), (r, r), (-r, r)])],
        Marker::Diamond => vec![(true, vec![(0, -d), (d, 0), (0, d), (-d, 0)])],
        Marker::Cross => vec![
            (false, vec![(-r, -r), (r, r)]),
            (false, vec![(-r, r), (r, -r)]),
        ],
        Marker::Plus => vec![
            (false, vec![(-d, 0), (d, 0)]),
            (false, vec![(0, -d), (0, d)]),
        ],
        Marker::Star => {
            let (o, n) = (r + 2, r / 2);
            vec![(
                true,
                vec![
                    (0, -o),
                    (n, -n),
                    (o, 0),
                    (n, n),
                    (0, o),
                    (-n, n),
                    (-o, 0),
                    (-n, -n),
                ],
            )]
        }
    }
}
