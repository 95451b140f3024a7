//! The `.png` picture of one slice of a grid: its cells drawn to scale (a cell's width
//! and height in pixels in the ratio of its sizes), a colour legend of the fractions,
//! the slice's coordinate, and the two in-plane axes with their names and ranges.
//!
//! ```text
//!   z = 1.125 (k = 4)                 fraction
//!  ┌──────────────────────────┐       ┌──┐ 1
//! 2.5                         │       │  │
//! y │        cells            │       │  │ 0.5
//!  0│                         │       │  │
//!   └──────────────────────────┘       └──┘ 0
//!   0            x            5
//! ```
//!
//! The slice's coordinate is the centre of its layer of cells. The plot's longer side is
//! about 512 pixels, more where cells would be narrower than a pixel, and no side is
//! longer than 4096 (cells are then sampled, nearest).

use std::io::{self, Write};

use meshvol::grid::Grid;

use super::font;
use super::{check_len, Slice};

/// Axis names, and the names of the cell indices along them.
const AXES: [&str; 3] = ["x", "y", "z"];
const INDICES: [&str; 3] = ["i", "j", "k"];
/// The plot's longer side, in pixels, when cells are not too small for it.
const TARGET_SIDE: f64 = 512.0;
/// Largest plot side, in pixels.
const MAX_SIDE: usize = 4096;
/// Screen pixels per font pixel: the 5 × 7 glyphs at twice their size are readable.
const TEXT_SCALE: usize = 2;
/// Cells at least this many pixels wide and high get a darker border line.
const BORDER_CELL: f64 = 6.0;
const MARGIN: usize = 12;
const GAP: usize = 6;
const BAR_WIDTH: usize = 20;
/// The legend bar is as high as the plot, and at least this.
const BAR_MIN_HEIGHT: usize = 128;
const WHITE: [u8; 3] = [255, 255, 255];
const INK: [u8; 3] = [0, 0, 0];

/// An RGB image, white at first.
struct Canvas {
    width: usize,
    height: usize,
    pixels: Vec<u8>,
}

impl Canvas {
    fn new(width: usize, height: usize) -> Canvas {
        Canvas { width, height, pixels: WHITE.repeat(width * height) }
    }

    /// Sets a pixel; pixels outside the image are left out.
    fn set(&mut self, x: usize, y: usize, rgb: [u8; 3]) {
        if x < self.width && y < self.height {
            self.pixels[(y * self.width + x) * 3..][..3].copy_from_slice(&rgb);
        }
    }

    /// A one-pixel outline around the `w` × `h` rectangle at (x, y), outside it.
    fn frame(&mut self, x: usize, y: usize, w: usize, h: usize) {
        for i in x - 1..=x + w {
            self.set(i, y - 1, INK);
            self.set(i, y + h, INK);
        }
        for j in y - 1..=y + h {
            self.set(x - 1, j, INK);
            self.set(x + w, j, INK);
        }
    }

    /// `text` with its top left at (x, y).
    fn text(&mut self, x: usize, y: usize, text: &str) {
        font::draw(text, |fx, fy| {
            for dy in 0..TEXT_SCALE {
                for dx in 0..TEXT_SCALE {
                    self.set(x + fx * TEXT_SCALE + dx, y + fy * TEXT_SCALE + dy, INK);
                }
            }
        });
    }
}

/// The width of `text` on the canvas.
fn text_width(text: &str) -> usize {
    font::width(text) * TEXT_SCALE
}

const TEXT_HEIGHT: usize = font::HEIGHT * TEXT_SCALE;

/// A number for a label: four significant digits, trailing zeros dropped; very large
/// and very small ones in exponent form.
fn number(x: f64) -> String {
    let a = x.abs();
    if a == 0.0 || !x.is_finite() {
        return "0".to_string();
    }
    let trim = |s: String| {
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        }
    };
    if (1e-3..1e6).contains(&a) {
        let decimals = (3 - a.log10().floor() as i32).clamp(0, 6) as usize;
        let s = trim(format!("{x:.decimals$}"));
        if s == "-0" {
            "0".to_string()
        } else {
            s
        }
    } else {
        let s = format!("{x:.3e}");
        let (mantissa, exponent) = s.split_once('e').unwrap_or((&s, "0"));
        format!("{}e{exponent}", trim(mantissa.to_string()))
    }
}

/// The plot's size in pixels for a slice `w` × `h` long of cells `du` × `dv`: the longer
/// side [`TARGET_SIDE`], or more so that every cell is a pixel at least, at most
/// [`MAX_SIDE`]; the shorter side in proportion.
fn plot_size(w: f64, h: f64, du: f64, dv: f64) -> (usize, usize) {
    let longer = w.max(h);
    let per_unit = (TARGET_SIDE / longer).max(1.0 / du.min(dv)).min(MAX_SIDE as f64 / longer);
    let side = |length: f64| ((length * per_unit).round() as usize).clamp(1, MAX_SIDE);
    (side(w), side(h))
}

/// What a picture of values says about them: the title above the plot, the legend's
/// name, and the value drawn in full colour (its negative in full red).
#[derive(Clone, Debug, PartialEq)]
pub struct Legend {
    pub title: String,
    pub name: String,
    pub full: f64,
}

/// A `.png` of the fractions in one slice (see the module docs of [`super`] for the
/// colours, and of this file for the layout).
pub fn png(out: &mut impl Write, grid: &Grid, volumes: &[f64], slice: Slice) -> io::Result<()> {
    check_slice(grid, volumes, slice)?;
    let centre = grid.origin[slice.axis] + (slice.index as f64 + 0.5) * grid.cell[slice.axis];
    let title = format!(
        "{} = {} ({} = {})",
        AXES[slice.axis],
        number(centre),
        INDICES[slice.axis],
        slice.index
    );
    let legend = Legend { title, name: "fraction".to_string(), full: grid.cell_volume() };
    draw(out, grid, volumes, slice, &legend, 1.0)
}

/// A `.png` of any `values` in one slice, coloured as fractions of `legend.full`, its
/// legend's ticks labelled in the values' units.
pub fn png_map(
    out: &mut impl Write,
    grid: &Grid,
    values: &[f64],
    slice: Slice,
    legend: &Legend,
) -> io::Result<()> {
    check_slice(grid, values, slice)?;
    draw(out, grid, values, slice, legend, legend.full)
}

fn check_slice(grid: &Grid, volumes: &[f64], slice: Slice) -> io::Result<()> {
    check_len(grid, volumes)?;
    if slice.axis > 2 || slice.index >= grid.counts[slice.axis.min(2)] {
        let axis = AXES.get(slice.axis).copied().unwrap_or("?");
        return Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            format!(
                "slice {axis}={} is outside the grid (0 to {})",
                slice.index,
                grid.counts[slice.axis.min(2)].saturating_sub(1)
            ),
        ));
    }
    Ok(())
}

/// The picture: cells coloured by value / `legend.full`, the legend's ticks (at −1, 0
/// and 1 of the ramp, or 0, 1/2 and 1) labelled times `tick_unit`.
fn draw(
    out: &mut impl Write,
    grid: &Grid,
    values: &[f64],
    slice: Slice,
    legend: &Legend,
    tick_unit: f64,
) -> io::Result<()> {
    // In-plane axes: (u, v) = (y, z) for an x slice, (x, z) for y, (x, y) for z.
    let (u, v) = match slice.axis {
        0 => (1, 2),
        1 => (0, 2),
        _ => (0, 1),
    };
    let (nu, nv) = (grid.counts[u], grid.counts[v]);
    let (du, dv) = (grid.cell[u], grid.cell[v]);
    let (pw, ph) = plot_size(nu as f64 * du, nv as f64 * dv, du, dv);
    let fraction_at = |a: usize, b: usize| {
        let mut ijk = [0; 3];
        ijk[slice.axis] = slice.index;
        ijk[u] = a;
        ijk[v] = b;
        values[grid.index(ijk)] / legend.full
    };
    let negative = (0..nu).any(|a| (0..nv).any(|b| fraction_at(a, b) < 0.0));
    let low = if negative { -1.0 } else { 0.0 };

    // Labels.
    let title = &legend.title;
    let (u_low, u_high) = (number(grid.origin[u]), number(grid.origin[u] + nu as f64 * du));
    let (v_low, v_high) = (number(grid.origin[v]), number(grid.origin[v] + nv as f64 * dv));
    let ticks: Vec<f64> = if negative { vec![-1.0, 0.0, 1.0] } else { vec![0.0, 0.5, 1.0] };
    let tick_labels: Vec<String> = ticks.iter().map(|&t| number(t * tick_unit)).collect();

    // Layout, left to right: the v axis name, its range, the plot, the legend.
    let v_labels = text_width(&v_low).max(text_width(&v_high));
    let left = MARGIN + text_width(AXES[v]) + GAP + v_labels + GAP;
    let top = MARGIN + TEXT_HEIGHT + 2 * GAP;
    let bar_height = ph.max(BAR_MIN_HEIGHT);
    let bar_left = left + pw.max(text_width(&u_low) + text_width(&u_high) + GAP) + 4 * GAP;
    let legend_labels = tick_labels.iter().map(|l| text_width(l)).max().unwrap_or(0);
    let width = (bar_left + BAR_WIDTH + GAP + legend_labels)
        .max(bar_left + text_width(&legend.name))
        .max(left + text_width(title))
        + MARGIN;
    let below = top + ph + GAP;
    let height = (below + 2 * TEXT_HEIGHT + GAP).max(top + bar_height + TEXT_HEIGHT) + MARGIN;
    let mut canvas = Canvas::new(width, height);

    // The cells. Each pixel shows the cell under its centre; up is +v.
    let cell_of = |pixel: usize, pixels: usize, cells: usize| {
        (((pixel as f64 + 0.5) / pixels as f64 * cells as f64) as usize).min(cells - 1)
    };
    let borders = pw as f64 / nu as f64 >= BORDER_CELL && ph as f64 / nv as f64 >= BORDER_CELL;
    for y in 0..ph {
        let up = ph - 1 - y;
        let b = cell_of(up, ph, nv);
        let b_edge = up == 0 || cell_of(up - 1, ph, nv) != b;
        for x in 0..pw {
            let a = cell_of(x, pw, nu);
            let edge = x == 0 || cell_of(x - 1, pw, nu) != a || b_edge;
            canvas.set(left + x, top + y, colour(fraction_at(a, b), borders && edge));
        }
    }
    canvas.frame(left, top, pw, ph);

    // The title, and the axes: names and ranges.
    canvas.text(left, MARGIN, title);
    canvas.text(left, below, &u_low);
    canvas.text(left + pw.saturating_sub(text_width(&u_high)), below, &u_high);
    canvas.text(left + pw / 2, below + TEXT_HEIGHT + GAP, AXES[u]);
    let v_right = left - GAP;
    canvas.text(v_right - text_width(&v_high), top, &v_high);
    canvas.text(v_right - text_width(&v_low), top + ph.saturating_sub(TEXT_HEIGHT), &v_low);
    canvas.text(MARGIN, top + ph.saturating_sub(TEXT_HEIGHT) / 2, AXES[v]);

    // The legend: the colour ramp from `low` (bottom) to 1 (top), with ticks.
    let level = |f: f64| top + ((1.0 - f) / (1.0 - low) * (bar_height - 1) as f64).round() as usize;
    for y in 0..bar_height {
        let f = 1.0 - (1.0 - low) * y as f64 / (bar_height - 1) as f64;
        for x in 0..BAR_WIDTH {
            canvas.set(bar_left + x, top + y, colour(f, false));
        }
    }
    canvas.frame(bar_left, top, BAR_WIDTH, bar_height);
    canvas.text(bar_left, MARGIN, &legend.name);
    for (&t, label) in ticks.iter().zip(&tick_labels) {
        let y = level(t);
        for x in 0..GAP / 2 {
            canvas.set(bar_left + BAR_WIDTH + 1 + x, y, INK);
        }
        let label_top = y.saturating_sub(TEXT_HEIGHT / 2);
        canvas.text(bar_left + BAR_WIDTH + GAP, label_top, label);
    }

    let mut encoder = ::png::Encoder::new(out, width as u32, height as u32);
    encoder.set_color(::png::ColorType::Rgb);
    encoder.set_depth(::png::BitDepth::Eight);
    let mut writer = encoder.write_header().map_err(io::Error::other)?;
    writer.write_image_data(&canvas.pixels).map_err(io::Error::other)?;
    writer.finish().map_err(io::Error::other)
}

/// White at 0, dark blue at 1, dark red at −1; borders slightly darker.
pub(super) fn colour(fraction: f64, border: bool) -> [u8; 3] {
    let f = if fraction.is_finite() { fraction.clamp(-1.0, 1.0) } else { 0.0 };
    let (target, t) = if f >= 0.0 { ([24.0, 64.0, 160.0], f) } else { ([170.0, 30.0, 30.0], -f) };
    let shade = if border { 0.85 } else { 1.0 };
    target.map(|c: f64| ((255.0 + (c - 255.0) * t) * shade).round() as u8)
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;

    /// The ramp's ends and middle as the module docs of [`super::super`] give them:
    /// white, dark blue (24, 64, 160), and half way between (rounded).
    const FULL: [u8; 3] = [24, 64, 160];
    const HALF: [u8; 3] = [140, 160, 208];

    /// A decoded RGB picture.
    pub struct Image {
        pub width: usize,
        pub height: usize,
        rgb: Vec<u8>,
    }

    impl Image {
        pub fn decode(png: &[u8]) -> Image {
            let decoder = ::png::Decoder::new(std::io::Cursor::new(png));
            let mut reader = decoder.read_info().unwrap();
            let mut rgb = vec![0; reader.output_buffer_size().unwrap()];
            let info = reader.next_frame(&mut rgb).unwrap();
            assert_eq!(info.color_type, ::png::ColorType::Rgb);
            Image { width: info.width as usize, height: info.height as usize, rgb }
        }

        pub fn at(&self, x: usize, y: usize) -> [u8; 3] {
            let i = (y * self.width + x) * 3;
            [self.rgb[i], self.rgb[i + 1], self.rgb[i + 2]]
        }

        /// The first pixel of colour `rgb` scanning columns left to right: the plot's,
        /// which is left of the legend.
        fn leftmost(&self, matches: impl Fn([u8; 3]) -> bool) -> (usize, usize) {
            (0..self.width)
                .find_map(|x| (0..self.height).find(|&y| matches(self.at(x, y))).map(|y| (x, y)))
                .expect("a pixel of that colour")
        }

        /// The run of pixels matching from (x, y) to the right and down: (x, y, w, h).
        fn block(
            &self,
            (x, y): (usize, usize),
            matches: impl Fn([u8; 3]) -> bool,
        ) -> (usize, usize, usize, usize) {
            let w = (x..self.width).take_while(|&i| matches(self.at(i, y))).count();
            let h = (y..self.height).take_while(|&j| matches(self.at(x, j))).count();
            (x, y, w, h)
        }

        /// The plot of a slice whose cells are all full: the leftmost block of blue
        /// (cell borders are a darker blue).
        pub fn plot_box(&self) -> (usize, usize, usize, usize) {
            let blue =
                |c: [u8; 3]| c[2] > c[0].saturating_add(60) && c[2] > c[1].saturating_add(40);
            self.block(self.leftmost(blue), blue)
        }
    }

    #[test]
    fn cells_are_drawn_to_scale() {
        // A 5 × 2.5 part in 30 × 30 × 10 cells: cells twice as wide as high.
        let g = Grid::new([0.0, 0.0, 0.0], [5.0 / 30.0, 2.5 / 30.0, 0.1], [30, 30, 10]).unwrap();
        let full = vec![g.cell_volume(); g.cell_count()];
        let mut out = Vec::new();
        png(&mut out, &g, &full, Slice { axis: 2, index: 4 }).unwrap();
        let image = Image::decode(&out);
        let (_, _, w, h) = image.plot_box();
        assert!((w as f64 / h as f64 - 2.0).abs() < 0.01, "{w} × {h}");
        assert!((500..=520).contains(&w), "{w}");
        // An x slice of the same grid: y across (2.5), z up (1.0).
        let mut out = Vec::new();
        png(&mut out, &g, &full, Slice { axis: 0, index: 0 }).unwrap();
        let (_, _, w, h) = Image::decode(&out).plot_box();
        assert!((w as f64 / h as f64 - 2.5).abs() < 0.02, "{w} × {h}");
    }

    #[test]
    fn cell_colours_show_fractions_and_the_legend_shows_the_ramp() {
        // 4 × 2 cells of 1 × 1 in the slice z = 0: (0, 0) half full, (3, 1) full.
        let g = Grid::new([0.0; 3], [1.0; 3], [4, 2, 1]).unwrap();
        let mut v = vec![0.0; g.cell_count()];
        v[g.index([0, 0, 0])] = 0.5;
        v[g.index([3, 1, 0])] = 1.0;
        let mut out = Vec::new();
        png(&mut out, &g, &v, Slice { axis: 2, index: 0 }).unwrap();
        let image = Image::decode(&out);
        // The half cell: a square (borders aside) at the plot's bottom left.
        let (x, y, w, h) = image.block(image.leftmost(|c| c == HALF), |c| c == HALF);
        assert!(w == h && w > 100, "{w} × {h}");
        let cell = w + 1; // with its border line
        let (cx, cy) = (x + w / 2, y + h / 2);
        assert_eq!(image.at(cx + cell, cy), WHITE, "cell (1, 0) is empty");
        assert_eq!(image.at(cx + 3 * cell, cy - cell), FULL, "cell (3, 1) is full");
        assert_eq!(image.at(cx, cy - cell), WHITE, "cell (0, 1) is empty");
        let plot_right = x + 4 * cell;
        // Above the plot: the title; left of it and below it: the axes' labels.
        let ink = |xs: std::ops::Range<usize>, ys: std::ops::Range<usize>| {
            xs.into_iter().any(|i| ys.clone().any(|j| image.at(i, j) == INK))
        };
        assert!(ink(x..plot_right, 0..y - cell - 1));
        assert!(ink(x..plot_right, y + h + 2..image.height));
        assert!(ink(0..x - 2, 0..image.height));
        // The legend, right of the plot: a column running from the full colour at the
        // top through the half colour to white at the bottom, inside a frame.
        let (lx, top) = (plot_right + 2..image.width)
            .find_map(|i| (0..image.height).find(|&j| image.at(i, j) == FULL).map(|j| (i, j)))
            .expect("the legend's full end");
        let bottom = (top..image.height).find(|&j| image.at(lx, j) == INK).unwrap() - 1;
        assert_eq!(image.at(lx, bottom), WHITE, "the legend's empty end");
        let middle = image.at(lx, (top + bottom) / 2);
        assert!(middle.iter().zip(HALF).all(|(&a, b)| a.abs_diff(b) <= 2), "{middle:?}");
    }

    #[test]
    fn labels() {
        assert_eq!(number(1.125), "1.125");
        assert_eq!(number(-2.5), "-2.5");
        assert_eq!(number(5.0), "5");
        assert_eq!(number(0.0), "0");
        assert_eq!(number(1.0 / 3.0), "0.3333");
        assert_eq!(number(500000.125), "500000");
        assert_eq!(number(6000000.5), "6e6");
        assert_eq!(number(1.25e-5), "1.25e-5");
        assert_eq!(plot_size(5.0, 2.5, 5.0 / 30.0, 2.5 / 30.0), (512, 256));
        // Tiny cells: one pixel each at least.
        assert_eq!(plot_size(1000.0, 10.0, 1.0, 1.0), (1000, 10));
    }
}
