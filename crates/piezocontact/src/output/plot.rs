//! Figures drawn by the program with plotters, as PNG and SVG. Text uses DejaVu Sans
//! embedded in the binary (the `dejavu` crate), so labels render on machines without fonts.

use super::files::write_atomic;
use crate::algorithm::ContactSolution;
use crate::contact::{ContactModel, Foundation, NodeStatus};
use crate::error::{Error, Result};
use crate::problem::Problem;
use crate::report::Row;
use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use std::path::Path;
use std::sync::Once;

/// The font family every figure uses.
const FONT: &str = "sans-serif";

/// Registers the embedded font once per process.
fn fonts() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        let _ = plotters::style::register_font(FONT, FontStyle::Normal, dejavu::sans::regular());
        let _ = plotters::style::register_font(FONT, FontStyle::Bold, dejavu::sans::bold());
    });
}

/// Distinct colours for curves.
pub const PALETTE: [RGBColor; 7] = [
    RGBColor(0, 0, 0),
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
    RGBColor(140, 86, 75),
];

/// One curve.
pub struct Series {
    pub label: String,
    pub points: Vec<(f64, f64)>,
    pub color: RGBColor,
    /// Mark the points as well as joining them.
    pub markers: bool,
}

/// A line plot.
pub struct LinePlot {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub series: Vec<Series>,
    /// Logarithmic axes (both).
    pub log_log: bool,
    /// Where the legend goes; linear plots get head room above the data for it.
    pub legend: SeriesLabelPosition,
}

fn err<E: std::fmt::Debug>(e: E) -> Error {
    Error::Io { what: "drawing a figure failed".into(), cause: format!("{e:?}") }
}

/// Writes `stem.png` and `stem.svg` for a drawing function generic over the back end.
macro_rules! both_backends {
    ($stem:expr, $size:expr, $draw:expr) => {{
        fonts();
        let stem: &Path = $stem;
        let size: (u32, u32) = $size;
        let mut svg = String::new();
        {
            let root = SVGBackend::with_string(&mut svg, size).into_drawing_area();
            $draw(&root)?;
            root.present().map_err(err)?;
        }
        write_atomic(&stem.with_extension("svg"), svg.as_bytes())?;
        // plotters encodes the PNG into a file: a temporary one, renamed when complete.
        let png = stem.with_extension("png");
        let tmp = super::files::temporary(&png);
        {
            let root = BitMapBackend::new(&tmp, size).into_drawing_area();
            $draw(&root)?;
            root.present().map_err(err)?;
        }
        super::files::commit(&tmp, &png)
    }};
}

/// Axis range with a margin; never empty.
fn range(values: impl Iterator<Item = f64>, margin: f64) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| (a.min(v), b.max(v)));
    if !lo.is_finite() {
        return (0.0, 1.0);
    }
    let pad = if hi > lo { margin * (hi - lo) } else { lo.abs().max(1.0) * 0.5 };
    (lo - pad, hi + pad)
}

/// A tick label on an axis from `lo` to `hi`: plain decimals, as many as the span needs,
/// or powers of ten for values far from 1.
fn tick(v: f64, lo: f64, hi: f64) -> String {
    let span = (hi - lo).abs().max(f64::MIN_POSITIVE);
    let size = lo.abs().max(hi.abs());
    if !(1e-3..1e5).contains(&size) {
        let digits = ((size / span).log10().ceil().max(0.0) as usize + 1).min(6);
        return format!("{v:.digits$e}");
    }
    let decimals = (1.0 - span.log10().floor()).clamp(0.0, 8.0) as usize;
    format!("{v:.decimals$}")
}

/// Draws a line plot.
pub fn line_plot(plot: &LinePlot, stem: &Path) -> Result<()> {
    both_backends!(stem, (900, 560), |root: &DrawingArea<_, Shift>| draw_lines(root, plot))
}

/// Draws line plots side by side in one figure.
pub fn panels(plots: &[LinePlot], stem: &Path) -> Result<()> {
    let width = 620 * plots.len().max(1) as u32;
    both_backends!(stem, (width, 520), |root: &DrawingArea<_, Shift>| {
        let areas = root.split_evenly((1, plots.len().max(1)));
        plots.iter().zip(&areas).try_for_each(|(plot, area)| draw_lines(area, plot))
    })
}

fn draw_lines<DB: DrawingBackend>(root: &DrawingArea<DB, Shift>, plot: &LinePlot) -> Result<()> {
    root.fill(&WHITE).map_err(err)?;
    let xs = plot.series.iter().flat_map(|s| s.points.iter().map(|p| p.0));
    let ys = plot.series.iter().flat_map(|s| s.points.iter().map(|p| p.1));
    let mut builder = ChartBuilder::on(root);
    builder.caption(&plot.title, (FONT, 22)).margin(14).x_label_area_size(50).y_label_area_size(80);
    if plot.log_log {
        let positive = |v: &f64| *v > 0.0;
        let (x0, x1) = range(xs.filter(positive).map(f64::log10), 0.05);
        let (y0, y1) = range(ys.filter(positive).map(f64::log10), 0.08);
        let mut chart = builder
            .build_cartesian_2d(
                (10f64.powf(x0)..10f64.powf(x1)).log_scale(),
                (10f64.powf(y0)..10f64.powf(y1)).log_scale(),
            )
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_desc(&plot.x_label)
            .y_desc(&plot.y_label)
            .x_label_formatter(&|v| format!("{v:.0e}"))
            .y_label_formatter(&|v| format!("{v:.0e}"))
            .label_style((FONT, 15))
            .axis_desc_style((FONT, 17))
            .draw()
            .map_err(err)?;
        for s in &plot.series {
            let pts: Vec<(f64, f64)> =
                s.points.iter().copied().filter(|p| p.0 > 0.0 && p.1 > 0.0).collect();
            draw_series(&mut chart, s, pts)?;
        }
        legend(&mut chart, plot.legend.clone())
    } else {
        let (x0, x1) = range(xs, 0.02);
        let (y0, y1) = range(ys, 0.08);
        // Head room for the legend: one line of 4 % of the height per series.
        let y1 = y1 + (y1 - y0) * (0.06 + 0.055 * plot.series.len() as f64);
        let mut chart = builder.build_cartesian_2d(x0..x1, y0..y1).map_err(err)?;
        chart
            .configure_mesh()
            .x_desc(&plot.x_label)
            .y_desc(&plot.y_label)
            .x_label_formatter(&|v| tick(*v, x0, x1))
            .y_label_formatter(&|v| tick(*v, y0, y1))
            .label_style((FONT, 15))
            .axis_desc_style((FONT, 17))
            .draw()
            .map_err(err)?;
        for s in &plot.series {
            draw_series(&mut chart, s, s.points.clone())?;
        }
        legend(&mut chart, plot.legend.clone())
    }
}

fn draw_series<'a, DB: DrawingBackend + 'a, CT: CoordTranslate<From = (f64, f64)>>(
    chart: &mut ChartContext<'a, DB, CT>,
    s: &Series,
    pts: Vec<(f64, f64)>,
) -> Result<()> {
    let color = s.color;
    chart
        .draw_series(LineSeries::new(pts.clone(), color.stroke_width(2)))
        .map_err(err)?
        .label(&s.label)
        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 24, y)], color.stroke_width(2)));
    if s.markers {
        chart
            .draw_series(pts.into_iter().map(|p| Circle::new(p, 3, color.filled())))
            .map_err(err)?;
    }
    Ok(())
}

fn legend<'a, DB: DrawingBackend + 'a, CT: CoordTranslate>(
    chart: &mut ChartContext<'a, DB, CT>,
    position: SeriesLabelPosition,
) -> Result<()> {
    chart
        .configure_series_labels()
        .label_font((FONT, 14))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .position(position)
        .draw()
        .map_err(err)
}

/// A blue–white–red style map of t ∈ [0, 1] (viridis-like anchors).
pub fn colormap(t: f64) -> RGBColor {
    const ANCHORS: [(f64, [f64; 3]); 5] = [
        (0.0, [68.0, 1.0, 84.0]),
        (0.25, [59.0, 82.0, 139.0]),
        (0.5, [33.0, 145.0, 140.0]),
        (0.75, [94.0, 201.0, 98.0]),
        (1.0, [253.0, 231.0, 37.0]),
    ];
    let t = t.clamp(0.0, 1.0);
    let k = ANCHORS.iter().position(|a| a.0 >= t).unwrap_or(4).max(1);
    let (a, b) = (ANCHORS[k - 1], ANCHORS[k]);
    let s = (t - a.0) / (b.0 - a.0);
    let c = |i: usize| (a.1[i] + s * (b.1[i] - a.1[i])).round() as u8;
    RGBColor(c(0), c(1), c(2))
}

/// What the figures of a contact solution draw: the problem's mesh and Γ3, the model's stop
/// and foundation, the solution and its Γ3 rows.
pub struct ContactView<'a> {
    /// The problem solved.
    pub problem: &'a Problem,
    /// Its contact model (at the step drawn, on a loading path).
    pub model: &'a ContactModel,
    /// The solution.
    pub solution: &'a ContactSolution,
    /// Its Γ3 rows.
    pub rows: &'a [Row],
}

/// Labels of the body figure.
pub struct BodyLabels<'a> {
    pub title: &'a str,
    pub length: &'a str,
    pub stress: &'a str,
    pub potential: &'a str,
}

/// The deformed body (displacements to scale) coloured by ϕ with a colour bar, the contact
/// force on Γ3 as arrows, the rigid stop, and for PV2 the stick and slip nodes.
pub fn body_plot(view: &ContactView, labels: &BodyLabels, stem: &Path) -> Result<()> {
    both_backends!(stem, (1200, 520), |root: &DrawingArea<_, Shift>| draw_body(root, view, labels))
}

fn draw_body<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    view: &ContactView,
    labels: &BodyLabels,
) -> Result<()> {
    root.fill(&WHITE).map_err(err)?;
    let (problem, solution) = (&view.problem, &view.solution);
    let mesh = &problem.mesh;
    let (dofs, x) = (&solution.dofs, &solution.x);
    let deformed =
        |n: usize| (mesh.node(n)[0] + x[dofs.u(n, 0)], mesh.node(n)[1] + x[dofs.u(n, 1)]);
    let phi: Vec<f64> = (0..mesh.n_nodes()).map(|n| x[dofs.phi(n)]).collect();
    let (phi_lo, phi_hi) =
        phi.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| (a.min(v), b.max(v)));
    let span = if phi_hi > phi_lo { phi_hi - phi_lo } else { 1.0 };
    let surface = &solution.surface;
    // The rigid stop along each normal; nodes that cannot touch the foundation draw none.
    let stop: Vec<(f64, f64)> = (0..surface.len())
        .filter_map(|i| {
            let (p, rho) =
                (surface.position(problem, i), view.model.compliance.stop(surface.gap[i]));
            rho.is_finite()
                .then(|| (p[0] + rho * surface.normal[i][0], p[1] + rho * surface.normal[i][1]))
        })
        .collect();
    let (main, bar) = root.split_horizontally(1060);
    let all = (0..mesh.n_nodes()).map(deformed).chain(stop.iter().copied());
    let pts: Vec<(f64, f64)> = all.collect();
    let (x0, x1, y0, y1) = equal_scales(&pts, (1060.0 - 140.0, 520.0 - 120.0));
    let mut chart = ChartBuilder::on(&main)
        .caption(labels.title, (FONT, 22))
        .margin(14)
        .x_label_area_size(45)
        .y_label_area_size(60)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(err)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc(format!("x + u_x [{}]", labels.length))
        .y_desc(format!("y + u_y [{}]", labels.length))
        .label_style((FONT, 14))
        .axis_desc_style((FONT, 16))
        .draw()
        .map_err(err)?;
    chart
        .draw_series((0..mesh.n_cells()).map(|c| {
            let cell = mesh.cell(c);
            let mean = cell.iter().map(|&n| phi[n]).sum::<f64>() / 3.0;
            Polygon::new(
                cell.iter().map(|&n| deformed(n)).collect::<Vec<_>>(),
                colormap((mean - phi_lo) / span).filled(),
            )
        }))
        .map_err(err)?;
    draw_stop(&mut chart, view, stop, labels.length)?;
    let peak = view.rows.iter().map(|r| r.sigma_nu.abs().hypot(r.sigma_tau[0])).fold(0.0, f64::max);
    let arrow_length = 0.12 * (y1 - y0) / peak.max(f64::MIN_POSITIVE);
    draw_forces(&mut chart, view, &deformed, arrow_length)?;
    if view.model.friction.is_some() {
        draw_statuses(&mut chart, view, &deformed)?;
    }
    force_legend(&mut chart, (x0, y0), &format!("{peak:.3} {}", labels.stress))?;
    colour_bar(&bar, (phi_lo, phi_hi), &format!("ϕ [{}]", labels.potential), false)
}

/// The rigid stop as a line through `stop`, with its legend entry.
fn draw_stop<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    view: &ContactView,
    stop: Vec<(f64, f64)>,
    length: &str,
) -> Result<()> {
    let compliance = &view.model.compliance;
    let label = match view.model.foundation {
        Foundation::ConstantGap => {
            format!("rigid stop (gap + penetration = {} {length})", compliance.stop(compliance.gap))
        }
        _ => "rigid stop (foundation + penetration)".to_string(),
    };
    chart
        .draw_series(LineSeries::new(stop, BLACK.stroke_width(2)))
        .map_err(err)?
        .label(label)
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 24, y)], BLACK.stroke_width(2)));
    Ok(())
}

/// The legend entry of the force arrows (their `peak` with its unit), drawn by an invisible
/// series at `corner`, and the legend box.
fn force_legend<'a, DB: DrawingBackend + 'a>(
    chart: &mut Chart<'a, DB>,
    corner: (f64, f64),
    peak: &str,
) -> Result<()> {
    chart
        .draw_series(std::iter::once(PathElement::new(vec![corner, corner], RGBColor(200, 0, 0))))
        .map_err(err)?
        .label(format!("contact force on Γ3 (peak {peak})"))
        .legend(|(x, y)| {
            let red = RGBColor(200, 0, 0).stroke_width(2);
            PathElement::new(
                vec![(x, y), (x + 24, y), (x + 18, y - 4), (x + 24, y), (x + 18, y + 4)],
                red,
            )
        });
    chart
        .configure_series_labels()
        .label_font((FONT, 14))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .position(SeriesLabelPosition::UpperRight)
        .draw()
        .map_err(err)?;
    Ok(())
}

/// The plot ranges that hold `points` with equal scales on both axes, in a plot area of
/// `(width, height)` pixels.
fn equal_scales(points: &[(f64, f64)], (w, h): (f64, f64)) -> (f64, f64, f64, f64) {
    let (x0, x1) = range(points.iter().map(|p| p.0), 0.03);
    let (y0, y1) = range(points.iter().map(|p| p.1), 0.25);
    let scale = ((x1 - x0) / w).max((y1 - y0) / h);
    let (cx, cy) = ((x0 + x1) / 2.0, (y0 + y1) / 2.0);
    (cx - scale * w / 2.0, cx + scale * w / 2.0, cy - scale * h / 2.0, cy + scale * h / 2.0)
}

/// A 2D chart in plot coordinates.
type Chart<'a, DB> = ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// The contact force on the body, t = σ_ν ν + σ_τ, as arrows drawn from the foundation side
/// at every few Γ3 nodes, `arrow_length` per unit of stress.
fn draw_forces<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    view: &ContactView,
    deformed: &dyn Fn(usize) -> (f64, f64),
    arrow_length: f64,
) -> Result<()> {
    let surface = &view.solution.surface;
    let step = (surface.len() / 24).max(1);
    for i in (0..surface.len()).step_by(step) {
        let (row, n) = (&view.rows[i], surface.normal[i]);
        let t = surface.tangent(i);
        let force = (
            row.sigma_nu * n[0] + row.sigma_tau[0] * t[0],
            row.sigma_nu * n[1] + row.sigma_tau[0] * t[1],
        );
        if force.0.hypot(force.1) == 0.0 {
            continue;
        }
        let head = deformed(surface.nodes[i]);
        let tail = (head.0 - arrow_length * force.0, head.1 - arrow_length * force.1);
        chart.draw_series(std::iter::once(arrow(tail, head, RGBColor(200, 0, 0)))).map_err(err)?;
    }
    Ok(())
}

/// The stick and slip nodes of Γ3 as dots, with their legend entries.
fn draw_statuses<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    view: &ContactView,
    deformed: &dyn Fn(usize) -> (f64, f64),
) -> Result<()> {
    let surface = &view.solution.surface;
    for (status, color, name) in [
        (NodeStatus::Stick, RGBColor(31, 119, 180), "stick"),
        (NodeStatus::Slip, RGBColor(255, 127, 14), "slip"),
    ] {
        let nodes: Vec<(f64, f64)> = (0..surface.len())
            .filter(|&i| view.rows[i].status == status)
            .map(|i| deformed(surface.nodes[i]))
            .collect();
        chart
            .draw_series(nodes.into_iter().map(move |p| Circle::new(p, 4, color.filled())))
            .map_err(err)?
            .label(format!("{name} nodes"))
            .legend(move |(x, y)| Circle::new((x + 12, y), 4, color.filled()));
    }
    Ok(())
}

/// An arrow from `tail` to `head` in chart coordinates.
fn arrow(tail: (f64, f64), head: (f64, f64), color: RGBColor) -> PathElement<(f64, f64)> {
    let (dx, dy) = (head.0 - tail.0, head.1 - tail.1);
    let (a, b) = (0.25 * dx, 0.25 * dy);
    let left = (head.0 - a - 0.5 * b, head.1 - b + 0.5 * a);
    let right = (head.0 - a + 0.5 * b, head.1 - b - 0.5 * a);
    PathElement::new(vec![tail, head, left, head, right], color.stroke_width(2))
}

/// Labels of the Γ3 map.
pub struct MapLabels<'a> {
    pub title: &'a str,
    pub length: &'a str,
    pub stress: &'a str,
}

/// The contact face of a 3D run seen along its mean normal: the contact pressure −σ_ν as a
/// field over the Γ3 triangles (left, with its colour bar in the case's units) and the
/// status of each Γ3 node (right: separated, stick or contact, slip).
pub fn contact_map(view: &ContactView, labels: &MapLabels, stem: &Path) -> Result<()> {
    both_backends!(stem, (1300, 640), |root: &DrawingArea<_, Shift>| draw_map(root, view, labels))
}

/// A number as people read it: three significant digits, plain decimals between 1e−3 and
/// 1e5 ("11.3", "0.0452"), else a power of ten ("1.13e-5").
pub fn readable(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let exponent = v.abs().log10().floor() as i32;
    if (-3..5).contains(&exponent) {
        let decimals = (2 - exponent).max(0) as usize;
        format!("{v:.decimals$}")
    } else {
        format!("{v:.2e}")
    }
}

/// `text` cut to at most `width` pixels of a font of `size` pixels (about half the size per
/// character), with an ellipsis where it was cut.
fn fitted(text: &str, width: u32, size: u32) -> String {
    let room = (2 * width / size.max(1)) as usize;
    if text.chars().count() <= room {
        return text.to_string();
    }
    let kept: String = text.chars().take(room.saturating_sub(1)).collect();
    format!("{kept}…")
}

/// The Γ3 nodes projected on the plane of the mean normal's tangents.
fn map_points(view: &ContactView) -> Vec<(f64, f64)> {
    let surface = &view.solution.surface;
    let mut mean = [0.0; 3];
    surface.normal.iter().for_each(|n| (0..3).for_each(|k| mean[k] += n[k]));
    let norm = mean.iter().map(|v| v * v).sum::<f64>().sqrt().max(f64::MIN_POSITIVE);
    let frame = crate::contact::frame(mean.map(|v| v / norm), 3);
    let along = |x: [f64; 3], t: [f64; 3]| (0..3).map(|k| x[k] * t[k]).sum::<f64>();
    view.rows.iter().map(|r| (along(r.x, frame[1]), along(r.x, frame[2]))).collect()
}

/// The Γ3 triangles as triples of Γ3 node indices (the facets of the contact parts).
fn map_triangles(view: &ContactView) -> Vec<[usize; 3]> {
    let nodes = &view.solution.surface.nodes;
    let index: std::collections::HashMap<usize, usize> =
        nodes.iter().enumerate().map(|(i, &n)| (n, i)).collect();
    let mesh = &view.problem.mesh;
    view.problem
        .boundary
        .contact
        .iter()
        .flat_map(|&p| mesh.part_facets(p))
        .filter_map(|f| Some([*index.get(&f[0])?, *index.get(&f[1])?, *index.get(f.get(2)?)?]))
        .collect()
}

/// Fills each triangle with `value` interpolated linearly: the triangle cut into
/// `SUBDIVISIONS`² small ones, each filled with the colour at its centre.
fn fill_triangles<DB: DrawingBackend>(
    chart: &mut ChartContext<DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    (points, values): (&[(f64, f64)], &[f64]),
    triangles: &[[usize; 3]],
) -> Result<()> {
    const SUBDIVISIONS: usize = 4;
    let k = SUBDIVISIONS as f64;
    let mut polygons = Vec::new();
    for t in triangles {
        let at = |i: f64, j: f64| {
            let (a, b, c) = (points[t[0]], points[t[1]], points[t[2]]);
            let (wb, wc) = (i / k, j / k);
            let wa = 1.0 - wb - wc;
            let p = (wa * a.0 + wb * b.0 + wc * c.0, wa * a.1 + wb * b.1 + wc * c.1);
            (p, wa * values[t[0]] + wb * values[t[1]] + wc * values[t[2]])
        };
        for i in 0..SUBDIVISIONS {
            for j in 0..SUBDIVISIONS - i {
                let (i, j) = (i as f64, j as f64);
                let mut small = vec![[at(i, j), at(i + 1.0, j), at(i, j + 1.0)]];
                if i + j + 1.0 < k {
                    small.push([at(i + 1.0, j), at(i + 1.0, j + 1.0), at(i, j + 1.0)]);
                }
                for corners in small {
                    let value = corners.iter().map(|c| c.1).sum::<f64>() / 3.0;
                    let color = colormap(value).filled();
                    polygons.push(Polygon::new(corners.map(|c| c.0).to_vec(), color));
                }
            }
        }
    }
    chart.draw_series(polygons).map_err(err)?;
    Ok(())
}

fn draw_map<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    view: &ContactView,
    labels: &MapLabels,
) -> Result<()> {
    root.fill(&WHITE).map_err(err)?;
    let width = root.dim_in_pixel().0;
    let title = root.titled(&fitted(labels.title, width - 40, 20), (FONT, 20)).map_err(err)?;
    let points = map_points(view);
    let (x0, x1) = range(points.iter().map(|p| p.0), 0.05);
    let (y0, y1) = range(points.iter().map(|p| p.1), 0.05);
    let peak = view.rows.iter().map(|r| -r.sigma_nu).fold(0.0, f64::max).max(f64::MIN_POSITIVE);
    let (field, right) = title.split_horizontally(560);
    let (bar, status) = right.split_horizontally(130);
    let chart = |area: &DrawingArea<DB, Shift>, caption: &str| {
        ChartBuilder::on(area)
            .caption(caption, (FONT, 16))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(err)
    };
    let axes = |chart: &mut ChartContext<DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>| {
        chart
            .configure_mesh()
            .x_desc(format!("τ1 [{}]", labels.length))
            .y_desc(format!("τ2 [{}]", labels.length))
            .x_label_formatter(&|v| tick(*v, x0, x1))
            .y_label_formatter(&|v| tick(*v, y0, y1))
            .label_style((FONT, 13))
            .draw()
            .map_err(err)
    };
    let mut left = chart(
        &field,
        &format!("contact pressure −σ_ν, up to {} {}", readable(peak), labels.stress),
    )?;
    axes(&mut left)?;
    let values: Vec<f64> = view.rows.iter().map(|r| (-r.sigma_nu / peak).clamp(0.0, 1.0)).collect();
    fill_triangles(&mut left, (&points, &values), &map_triangles(view))?;
    colour_bar(&bar, (0.0, peak), &format!("−σ_ν [{}]", labels.stress), true)?;
    let mut right =
        chart(&status, "status: separated (grey), stick or contact (blue), slip (red)")?;
    axes(&mut right)?;
    let color = |r: &crate::report::Row| match r.status {
        NodeStatus::Separated => RGBColor(190, 190, 190),
        NodeStatus::Slip => PALETTE[2],
        _ => PALETTE[1],
    };
    right
        .draw_series(
            points.iter().zip(view.rows).map(|(&p, r)| Circle::new(p, 3, color(r).filled())),
        )
        .map_err(err)?;
    Ok(())
}

/// A vertical colour bar of [`colormap`] from `lo` to `hi` with its `label`, the ticks on the
/// right or on the left of the bar.
fn colour_bar<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    (lo, hi): (f64, f64),
    label: &str,
    right: bool,
) -> Result<()> {
    let hi = if hi > lo { hi } else { lo + 1.0 };
    let (left_size, right_size, margin) = if right { (0, 60, 60) } else { (70, 0, 10) };
    let mut chart = ChartBuilder::on(area)
        .margin_top(50)
        .margin_bottom(56)
        .margin_right(margin)
        .y_label_area_size(left_size)
        .right_y_label_area_size(right_size)
        .build_cartesian_2d(0.0..1.0, lo..hi)
        .map_err(err)?;
    chart
        .configure_mesh()
        .disable_x_mesh()
        .disable_y_mesh()
        .disable_x_axis()
        .y_desc(label)
        .y_label_formatter(&|v| tick(*v, lo, hi))
        .label_style((FONT, 13))
        .axis_desc_style((FONT, 15))
        .draw()
        .map_err(err)?;
    const STEPS: usize = 64;
    let band = |k: usize| {
        let (a, b) = (k as f64 / STEPS as f64, (k + 1) as f64 / STEPS as f64);
        let (y0, y1) = (lo + a * (hi - lo), lo + b * (hi - lo));
        Rectangle::new([(0.0, y0), (1.0, y1)], colormap((a + b) / 2.0).filled())
    };
    chart.draw_series((0..STEPS).map(band)).map_err(err)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Text renders from the embedded font: the caption area of a figure has dark pixels.
    #[test]
    fn text_renders_without_system_fonts() {
        fonts();
        let size = (400, 120);
        let mut pixels = vec![0u8; 400 * 120 * 3];
        {
            let root = BitMapBackend::with_buffer(&mut pixels, size).into_drawing_area();
            root.fill(&WHITE).unwrap();
            root.draw(&Text::new(
                "σ_ν on Γ3 [GPa]",
                (10, 40),
                (FONT, 30).into_font().color(&BLACK),
            ))
            .unwrap();
            root.present().unwrap();
        }
        let dark = pixels.chunks(3).filter(|p| p.iter().all(|&c| c < 100)).count();
        assert!(dark > 300, "only {dark} dark pixels: the text did not render");
    }

    #[test]
    fn numbers_and_titles_read_at_a_glance() {
        assert_eq!(readable(11.3), "11.3");
        assert_eq!(readable(11.2999), "11.3");
        assert_eq!(readable(0.045213), "0.0452");
        assert_eq!(readable(2.0), "2.00");
        assert_eq!(readable(-350.0), "-350");
        assert_eq!(readable(1.13e-5), "1.13e-5");
        assert_eq!(readable(123456.0), "1.23e5");
        assert_eq!(readable(0.0), "0");
        let long = "Indentation of a PZT-5A block by a rigid ball, with a very long title indeed";
        assert_eq!(fitted(long, 2000, 20), long);
        let cut = fitted(long, 400, 20);
        assert_eq!(cut.chars().count(), 40);
        assert!(cut.ends_with('…') && long.starts_with(cut.trim_end_matches('…')));
    }

    #[test]
    fn line_plots_write_png_and_svg() {
        let dir = std::env::temp_dir().join(format!("piezocontact-plot-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let plot = LinePlot {
            title: "test".into(),
            x_label: "µ = k_e [-]".into(),
            y_label: "distance [-]".into(),
            series: vec![Series {
                label: "slope 1".into(),
                points: vec![(1e-3, 1e-3), (1e-1, 1e-1)],
                color: PALETTE[1],
                markers: true,
            }],
            log_log: true,
            legend: SeriesLabelPosition::LowerRight,
        };
        line_plot(&plot, &dir.join("loglog")).unwrap();
        let svg = std::fs::read_to_string(dir.join("loglog.svg")).unwrap();
        assert!(
            svg.starts_with("<svg")
                && svg.trim_end().ends_with("</svg>")
                && svg.contains("slope 1")
        );
        let png = std::fs::read(dir.join("loglog.png")).unwrap();
        assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
        assert!(png.len() > 5000);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
