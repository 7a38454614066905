//! Surface features on a body (pits, dents, waviness, measured height maps) and their sampling on
//! the cell grid as **cell averages**: the first brick of transient EHL with pits (thesis ch. 3).
//!
//! # Sign convention (stated once)
//!
//! A feature's **depth** `d(x, y)` (m) is how far the surface lies *below* the body's smooth
//! surface: `d > 0` opens the gap (a pit), `d < 0` closes it (a bump, a ridge). The total depth of
//! a [`Surface`] is the sum of its features' depths (overlapping features superpose). A caller
//! that wants the gap adds the sampled depth to the smooth gap.
//!
//! Coordinates as in the rest of the crate: `x` the rolling direction (inlet at negative `x`),
//! `y` the roller axis, SI units. A feature sits at its `centre` `(x_c, y_c)` at `t = 0`; at a
//! later time its body has carried it a distance `s` (m) along `x`, the `shift` argument of the
//! samplers, so the sampled field is `d(x - s, y)`.
//!
//! # Shapes (`xi = x - s - x_c`, `eta = y - y_c`)
//!
//! * [`FeatureShape::Pit`] — the thesis' flat-bottomed notch (thesis fig. 3.4):
//!   `d = depth` for `|xi| <= width/2` and `|eta| <= length/2`, `0` outside.
//!   `length = f64::INFINITY` is a transverse groove (uniform along `y`); a negative depth is a
//!   ridge.
//! * [`FeatureShape::Dent`] — smooth cosine dent (user contract):
//!   `d = depth (1 + cos(pi r)) / 2` for `r < 1`, `r = sqrt((2 xi / width)^2 + (2 eta / length)^2)`,
//!   `0` outside; `length = f64::INFINITY` is a smooth transverse groove. Its volume is
//!   `V = depth * width * length * pi/8 * (1 - 4/pi^2)`: with `u = 2 xi / w`, `v = 2 eta / l`,
//!   `V = d (w l / 4) * int_0^1 (1 + cos(pi r)) / 2 * 2 pi r dr = d (w l / 4) pi (1/2 - 2/pi^2)`,
//!   since `int_0^1 r cos(pi r) dr = -2/pi^2`. A groove carries `d * width / 2` per unit length.
//! * [`FeatureShape::Waviness`] — harmonic over the whole body, crests along `y` (user contract):
//!   `d = amplitude * cos(2 pi xi / wavelength)`.
//! * [`FeatureShape::HeightMap`] — measured depths (m) on a node lattice centred on
//!   `(x_c, y_c)`, bilinear between the nodes, zero outside the lattice (user contract: "a 2D
//!   .npy array of depths in m"); like every depth here, positive opens the gap. A measured
//!   height profile z(x, y) enters as its negative.
//!
//! Any localized shape (all but waviness) may be repeated on a rectangular [`Pattern`] centred on
//! `(x_c, y_c)`: rows along `x`, columns along `y`, pitches centre to centre (the thesis' 3-pit and
//! 9-pit layouts).
//!
//! # Cell averages and their accuracy
//!
//! [`Surface::cell_averages`] writes, for each cell, `(1/(dx dy)) int int_cell d(x - s, y) dx dy`.
//! A feature moving by part of a cell therefore changes the sampled field continuously in `s`
//! (by at most `|depth| * |ds| / dx` for a pit), where a point sample at the centres jumps by the
//! full depth when an edge crosses a centre.
//!
//! * pit and groove: **exact** (overlap length along `x` times overlap length along `y`, times
//!   the depth); a cell inside the pit gets exactly `depth`, a cell outside exactly `0`.
//! * waviness: **exact**, the average of a cosine over the cell,
//!   `A cos(k (x_i - x_c - s)) sinc(k dx / 2)`, `k = 2 pi / wavelength`, `sinc z = sin z / z`.
//! * height map: **exact** (round-off): the bilinear interpolant is bilinear on each lattice
//!   panel, and the average of a bilinear function over a rectangle is its value at the
//!   rectangle's centre, so each cell sums `overlap area * value at the overlap centre` over the
//!   panels it overlaps.
//! * dent: Gauss-Legendre, nested, on pieces where the integrand is analytic: the outer
//!   variable `v = sin(theta)` is split where the dent's boundary crosses the cell's edges, the
//!   inner one is clipped to the chord `|u| <= cos(theta)`, and both are cut into panels no
//!   longer than 0.25 (in units of the half-width, resp. radians) with 6 points each, or one
//!   4-point panel below 1/16 (fine grids). The integrand is analytic on
//!   every piece, so the error is at round-off: about 1e-16 of the dent volume summed over
//!   cells from 0.1 to 1.2 half-widths (panels of 0.5 gave 4e-12); the volume test checks
//!   1e-13, the comparison with a brute-force average 1e-6 of the depth. The transverse dent
//!   groove is exact (closed-form antiderivative).
//!
//! # Cost
//!
//! A localized feature visits only the cells of its bounding box (plus one cell of margin);
//! waviness touches every cell but costs one cosine per column. Nothing is allocated per cell.
//!
//! # Panics
//!
//! The samplers panic on a feature that [`Feature::check`] rejects (non-finite or non-positive
//! sizes, a pattern on waviness, ...) and on an output slice whose length is not `grid.len()`.

use std::f64::consts::PI;
use std::ops::Range;

use ndarray::Array2;

use crate::grid::Grid;

#[cfg(test)]
mod tests;

/// Everything on one body's surface: the sum of its features' depths.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Surface {
    pub features: Vec<Feature>,
}

/// One feature (or a pattern of identical ones) at `centre = (x_c, y_c)` (m) at `t = 0`.
#[derive(Debug, Clone, PartialEq)]
pub struct Feature {
    pub shape: FeatureShape,
    /// `(x_c, y_c)` (m): the feature's centre, the pattern's centre, the waviness' crest at
    /// `t = 0`, or the height map's centre.
    pub centre: (f64, f64),
    /// Repeat a localized shape on a rectangular pattern centred on `centre`.
    pub pattern: Option<Pattern>,
}

/// The shape of a feature. All lengths in m; see the module documentation for the formulas.
#[derive(Debug, Clone, PartialEq)]
pub enum FeatureShape {
    /// Flat-bottomed notch (thesis fig. 3.4): `width` along `x`, `length` along `y`
    /// (`f64::INFINITY`: transverse groove), `depth` (negative: ridge).
    Pit { width: f64, length: f64, depth: f64 },
    /// Cosine dent `depth (1 + cos(pi r)) / 2` on the ellipse of axes `width` (x) and `length`
    /// (y) (`f64::INFINITY`: smooth transverse groove).
    Dent { width: f64, length: f64, depth: f64 },
    /// `amplitude * cos(2 pi (x - s - x_c) / wavelength)` over the whole body.
    Waviness { amplitude: f64, wavelength: f64 },
    /// Measured surface depths, bilinear between nodes (positive below the smooth surface).
    HeightMap(HeightMap),
}

/// Surface depths (m) on a lattice of nodes centred on the feature's centre: node `(j, i)`
/// (row `j` along `y`, column `i` along `x`) sits at
/// `(x_c + (i - (ncols - 1)/2) dx, y_c + (j - (nrows - 1)/2) dy)`. Positive depths lower the
/// surface (open the gap), as every feature depth.
#[derive(Debug, Clone, PartialEq)]
pub struct HeightMap {
    /// `depths[[j, i]]`: rows along `y`, columns along `x` (m).
    pub depths: Array2<f64>,
    /// node spacing along `x` (m)
    pub dx: f64,
    /// node spacing along `y` (m)
    pub dy: f64,
}

/// A rectangular arrangement: `rows` copies along `x` spaced `row_pitch`, `columns` copies along
/// `y` spaced `column_pitch` (m, centre to centre), centred on the feature's centre.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pattern {
    pub rows: usize,
    pub columns: usize,
    pub row_pitch: f64,
    pub column_pitch: f64,
}

impl Pattern {
    /// Offsets `(dx, dy)` (m) of the copies from the pattern centre.
    pub fn offsets(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        let (r0, c0) = (
            0.5 * (self.rows as f64 - 1.0),
            0.5 * (self.columns as f64 - 1.0),
        );
        (0..self.rows).flat_map(move |r| {
            (0..self.columns).map(move |c| {
                (
                    (r as f64 - r0) * self.row_pitch,
                    (c as f64 - c0) * self.column_pitch,
                )
            })
        })
    }
}

impl HeightMap {
    /// Depth (m, positive lowers the surface) at `(xi, eta)` relative to the map's centre:
    /// bilinear between the nodes, zero outside the lattice.
    pub fn depth(&self, xi: f64, eta: f64) -> f64 {
        let (ny, nx) = self.depths.dim();
        if nx < 2 || ny < 2 {
            return 0.0;
        }
        let tx = xi / self.dx + 0.5 * (nx - 1) as f64;
        let ty = eta / self.dy + 0.5 * (ny - 1) as f64;
        if !(0.0..=(nx - 1) as f64).contains(&tx) || !(0.0..=(ny - 1) as f64).contains(&ty) {
            return 0.0;
        }
        let p = (tx.floor() as usize).min(nx - 2);
        let q = (ty.floor() as usize).min(ny - 2);
        self.bilinear(p, q, tx - p as f64, ty - q as f64)
    }

    /// The bilinear interpolant on panel `(p, q)` (columns `p, p+1`, rows `q, q+1`) at local
    /// coordinates `t, u` in `[0, 1]`.
    #[inline]
    fn bilinear(&self, p: usize, q: usize, t: f64, u: f64) -> f64 {
        let h = &self.depths;
        let lo = h[[q, p]] + t * (h[[q, p + 1]] - h[[q, p]]);
        let hi = h[[q + 1, p]] + t * (h[[q + 1, p + 1]] - h[[q + 1, p]]);
        lo + u * (hi - lo)
    }

    /// Half extents `(x, y)` of the lattice (m).
    fn half_extent(&self) -> (f64, f64) {
        let (ny, nx) = self.depths.dim();
        (
            0.5 * (nx.max(1) - 1) as f64 * self.dx,
            0.5 * (ny.max(1) - 1) as f64 * self.dy,
        )
    }
}

impl FeatureShape {
    /// Depth (m, positive below the smooth surface) at `(xi, eta)` relative to the centre of one
    /// copy.
    pub fn depth(&self, xi: f64, eta: f64) -> f64 {
        match self {
            FeatureShape::Pit {
                width,
                length,
                depth,
            } => {
                if xi.abs() <= 0.5 * width && eta.abs() <= 0.5 * length {
                    *depth
                } else {
                    0.0
                }
            }
            FeatureShape::Dent {
                width,
                length,
                depth,
            } => {
                let (u, v) = (2.0 * xi / width, 2.0 * eta / length);
                let r = (u * u + v * v).sqrt();
                if r < 1.0 {
                    depth * 0.5 * (1.0 + (PI * r).cos())
                } else {
                    0.0
                }
            }
            FeatureShape::Waviness {
                amplitude,
                wavelength,
            } => amplitude * (2.0 * PI * xi / wavelength).cos(),
            FeatureShape::HeightMap(m) => m.depth(xi, eta),
        }
    }

    /// Volume (m^3) of one copy, signed as the depth (material missing below the smooth
    /// surface); `None` where it is infinite or undefined (waviness, grooves).
    pub fn volume(&self) -> Option<f64> {
        match self {
            FeatureShape::Pit {
                width,
                length,
                depth,
            } if length.is_finite() => Some(depth * width * length),
            FeatureShape::Dent {
                width,
                length,
                depth,
            } if length.is_finite() => {
                Some(depth * width * length * PI / 8.0 * (1.0 - 4.0 / (PI * PI)))
            }
            FeatureShape::HeightMap(m) => {
                // trapezoidal rule is exact for the bilinear interpolant
                let (ny, nx) = m.depths.dim();
                if nx < 2 || ny < 2 {
                    return Some(0.0);
                }
                let mut v = 0.0;
                for ((j, i), h) in m.depths.indexed_iter() {
                    let wx = if i == 0 || i == nx - 1 { 0.5 } else { 1.0 };
                    let wy = if j == 0 || j == ny - 1 { 0.5 } else { 1.0 };
                    v += wx * wy * h;
                }
                Some(v * m.dx * m.dy)
            }
            _ => None,
        }
    }
}

fn finite_positive(v: f64) -> bool {
    v.is_finite() && v > 0.0
}

impl Feature {
    /// A single feature (no pattern) at `centre`.
    pub fn new(shape: FeatureShape, centre: (f64, f64)) -> Self {
        Feature {
            shape,
            centre,
            pattern: None,
        }
    }

    /// The same feature repeated on `pattern`.
    pub fn with_pattern(mut self, pattern: Pattern) -> Self {
        self.pattern = Some(pattern);
        self
    }

    /// Checks the parameters: finite centre and depths, positive finite sizes (a pit's or a
    /// dent's `length` may be `f64::INFINITY`), at least 2 x 2 finite depths on a height map,
    /// a pattern with at least one row and column, finite non-negative pitches (positive where
    /// there is more than one copy), and no pattern on waviness (it is not localized).
    pub fn check(&self) -> Result<(), String> {
        if !(self.centre.0.is_finite() && self.centre.1.is_finite()) {
            return Err(format!("centre must be finite, found {:?}", self.centre));
        }
        match &self.shape {
            FeatureShape::Pit {
                width,
                length,
                depth,
            }
            | FeatureShape::Dent {
                width,
                length,
                depth,
            } => {
                if !finite_positive(*width) {
                    return Err(format!(
                        "width must be positive and finite, found {width} m"
                    ));
                }
                if length.is_nan() || *length <= 0.0 {
                    return Err(format!(
                        "length must be positive (infinite for a groove), found {length} m"
                    ));
                }
                if !depth.is_finite() {
                    return Err(format!("depth must be finite, found {depth} m"));
                }
            }
            FeatureShape::Waviness {
                amplitude,
                wavelength,
            } => {
                if !amplitude.is_finite() {
                    return Err(format!("amplitude must be finite, found {amplitude} m"));
                }
                if !finite_positive(*wavelength) {
                    return Err(format!(
                        "wavelength must be positive and finite, found {wavelength} m"
                    ));
                }
                if self.pattern.is_some() {
                    return Err(
                        "a pattern repeats a localized feature; waviness covers the whole body"
                            .into(),
                    );
                }
            }
            FeatureShape::HeightMap(m) => {
                if !(finite_positive(m.dx) && finite_positive(m.dy)) {
                    return Err(format!(
                        "height map spacings must be positive and finite, found dx = {} m, dy = {} m",
                        m.dx, m.dy
                    ));
                }
                let (ny, nx) = m.depths.dim();
                if nx < 2 || ny < 2 {
                    return Err(format!(
                        "a height map needs at least 2 x 2 nodes, found {ny} rows x {nx} columns"
                    ));
                }
                if m.depths.iter().any(|h| !h.is_finite()) {
                    return Err("height map has a non-finite depth".into());
                }
            }
        }
        if let Some(p) = &self.pattern {
            if p.rows == 0 || p.columns == 0 {
                return Err(format!(
                    "a pattern needs at least one row and one column, found {} x {}",
                    p.rows, p.columns
                ));
            }
            for (name, pitch, n) in [
                ("row_pitch", p.row_pitch, p.rows),
                ("column_pitch", p.column_pitch, p.columns),
            ] {
                if !pitch.is_finite() || pitch < 0.0 || (n > 1 && pitch == 0.0) {
                    return Err(format!(
                        "{name} must be finite and positive, found {pitch} m"
                    ));
                }
            }
        }
        Ok(())
    }

    /// The range of y (m) the feature covers, all copies of a pattern included; `None` when it
    /// is unbounded along y (a transverse groove, a waviness).
    pub fn y_span(&self) -> Option<(f64, f64)> {
        self.span(1)
    }

    /// The range of x (m) the feature covers at its start position, all copies of a pattern
    /// included; `None` for a waviness (it covers the whole body).
    pub fn x_span(&self) -> Option<(f64, f64)> {
        self.span(0)
    }

    /// The range along x (`axis` 0) or y (1) of [`Self::x_span`] and [`Self::y_span`].
    fn span(&self, axis: usize) -> Option<(f64, f64)> {
        let half = match &self.shape {
            FeatureShape::Pit { width, length, .. } | FeatureShape::Dent { width, length, .. } => {
                let size = if axis == 0 { *width } else { *length };
                size.is_finite().then_some(0.5 * size)?
            }
            FeatureShape::Waviness { .. } => return None,
            FeatureShape::HeightMap(map) => {
                let h = map.half_extent();
                if axis == 0 {
                    h.0
                } else {
                    h.1
                }
            }
        };
        let (lo, hi) = self
            .copies()
            .iter()
            .map(|&(ox, oy)| if axis == 0 { ox } else { oy })
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), o| {
                (a.min(o), b.max(o))
            });
        let c = if axis == 0 {
            self.centre.0
        } else {
            self.centre.1
        };
        Some((c + lo - half, c + hi + half))
    }

    /// Offsets of the copies from `centre` (one `(0, 0)` without a pattern).
    fn copies(&self) -> Vec<(f64, f64)> {
        match &self.pattern {
            Some(p) => p.offsets().collect(),
            None => vec![(0.0, 0.0)],
        }
    }

    /// Point value of the depth (m) at `(x, y)` after the body has travelled `shift` (m).
    pub fn depth_at(&self, x: f64, y: f64, shift: f64) -> f64 {
        self.copies()
            .into_iter()
            .map(|(ox, oy)| {
                self.shape
                    .depth(x - shift - self.centre.0 - ox, y - self.centre.1 - oy)
            })
            .sum()
    }

    /// Volume (m^3, signed as the depth) of all copies; `None` for waviness and grooves.
    pub fn volume(&self) -> Option<f64> {
        let n = self.pattern.map_or(1, |p| p.rows * p.columns);
        self.shape.volume().map(|v| v * n as f64)
    }

    /// Adds this feature's cell averages (m) after a travel `shift` (m) to `out` (row-major on
    /// `grid`). Accuracy per shape in the module documentation.
    ///
    /// # Panics
    /// If [`Feature::check`] fails or `out.len() != grid.len()`.
    pub fn add_cell_averages(&self, grid: &Grid, shift: f64, out: &mut [f64]) {
        assert_eq!(out.len(), grid.len(), "output length must be grid.len()");
        if let Err(e) = self.check() {
            panic!("invalid surface feature: {e}");
        }
        assert!(shift.is_finite(), "shift must be finite, found {shift}");
        for (ox, oy) in self.copies() {
            let c = (self.centre.0 + shift + ox, self.centre.1 + oy);
            match &self.shape {
                FeatureShape::Pit {
                    width,
                    length,
                    depth,
                } => add_pit(grid, c, *width, *length, *depth, out),
                FeatureShape::Dent {
                    width,
                    length,
                    depth,
                } => add_dent(grid, c, *width, *length, *depth, out),
                FeatureShape::Waviness {
                    amplitude,
                    wavelength,
                } => add_waviness(grid, c.0, *amplitude, *wavelength, out),
                FeatureShape::HeightMap(m) => add_height_map(grid, c, m, out),
            }
        }
    }
}

impl Surface {
    /// A surface carrying `features` (an empty list: the smooth surface).
    pub fn new(features: Vec<Feature>) -> Self {
        Surface { features }
    }

    /// Checks every feature; the error names the feature's index.
    pub fn check(&self) -> Result<(), String> {
        for (k, f) in self.features.iter().enumerate() {
            f.check().map_err(|e| format!("feature {k}: {e}"))?;
        }
        Ok(())
    }

    /// Point value of the total depth (m) at `(x, y)` after a travel `shift` (m).
    pub fn depth_at(&self, x: f64, y: f64, shift: f64) -> f64 {
        self.features.iter().map(|f| f.depth_at(x, y, shift)).sum()
    }

    /// Overwrites `out` (length `grid.len()`, row-major `j * nx + i`) with the cell average of
    /// the total depth (m) over each cell, the features shifted by `shift` (m) along `x`:
    /// `out[idx(i, j)] = (1/(dx dy)) int int_cell d(x - shift, y) dx dy`.
    ///
    /// # Panics
    /// If a feature fails [`Feature::check`] or `out.len() != grid.len()`.
    pub fn cell_averages(&self, grid: &Grid, shift: f64, out: &mut [f64]) {
        assert_eq!(out.len(), grid.len(), "output length must be grid.len()");
        out.fill(0.0);
        for f in &self.features {
            f.add_cell_averages(grid, shift, out);
        }
    }
}

// ---------------------------------------------------------------------------------------------
// samplers

/// Cells `i` along one direction whose interval `[o + i h, o + (i+1) h]` may meet `[lo, hi]`
/// (one cell of margin against round-off), clamped to `0..n`.
fn cell_range(lo: f64, hi: f64, origin: f64, h: f64, n: usize) -> Range<usize> {
    let a = ((lo - origin) / h).floor() - 1.0;
    let b = ((hi - origin) / h).ceil() + 1.0;
    let clamp = |t: f64| {
        if t.is_nan() || t <= 0.0 {
            0
        } else if t >= n as f64 {
            n
        } else {
            t as usize
        }
    };
    clamp(a)..clamp(b)
}

/// Fraction of the cell `[c0, c1]` (size `h`) covered by `[lo, hi]`; exactly 1 when covered.
#[inline]
fn cover(lo: f64, hi: f64, c0: f64, c1: f64, h: f64) -> f64 {
    if lo <= c0 && hi >= c1 {
        1.0
    } else {
        (hi.min(c1) - lo.max(c0)).max(0.0) / h
    }
}

/// Edges of cell `i` along x and of row `j` along y.
#[inline]
fn x_edges(g: &Grid, i: usize) -> (f64, f64) {
    (g.x_min + i as f64 * g.dx, g.x_min + (i + 1) as f64 * g.dx)
}
#[inline]
fn y_edges(g: &Grid, j: usize) -> (f64, f64) {
    (g.y_min + j as f64 * g.dy, g.y_min + (j + 1) as f64 * g.dy)
}

/// Rows touched by a copy centred at `yc` with half length `hy` (all rows when infinite).
fn rows_of(g: &Grid, yc: f64, hy: f64) -> Range<usize> {
    if hy.is_finite() {
        cell_range(yc - hy, yc + hy, g.y_min, g.dy, g.ny)
    } else {
        0..g.ny
    }
}

/// Pit: exact overlap areas.
fn add_pit(g: &Grid, c: (f64, f64), w: f64, l: f64, d: f64, out: &mut [f64]) {
    let (x0, x1) = (c.0 - 0.5 * w, c.0 + 0.5 * w);
    let (y0, y1) = (c.1 - 0.5 * l, c.1 + 0.5 * l);
    let cols = cell_range(x0, x1, g.x_min, g.dx, g.nx);
    for j in rows_of(g, c.1, 0.5 * l) {
        let fy = if l.is_finite() {
            let (e0, e1) = y_edges(g, j);
            cover(y0, y1, e0, e1, g.dy)
        } else {
            1.0
        };
        if fy == 0.0 {
            continue;
        }
        for i in cols.clone() {
            let (e0, e1) = x_edges(g, i);
            let fx = cover(x0, x1, e0, e1, g.dx);
            if fx != 0.0 {
                out[g.idx(i, j)] += d * (fx * fy);
            }
        }
    }
}

/// Waviness: exact average of the cosine over each column.
fn add_waviness(g: &Grid, xc: f64, a: f64, lambda: f64, out: &mut [f64]) {
    let k = 2.0 * PI / lambda;
    let z = 0.5 * k * g.dx;
    let sinc = if z.abs() < 1e-4 {
        1.0 - z * z / 6.0
    } else {
        z.sin() / z
    };
    let col: Vec<f64> = (0..g.nx)
        .map(|i| a * (k * (g.x(i) - xc)).cos() * sinc)
        .collect();
    for row in out.chunks_exact_mut(g.nx) {
        for (v, w) in row.iter_mut().zip(&col) {
            *v += w;
        }
    }
}

/// 6-point Gauss-Legendre nodes and weights on [-1, 1].
const GL6: [(f64, f64); 6] = [
    (-0.932_469_514_203_152, 0.171_324_492_379_170_35),
    (-0.661_209_386_466_264_5, 0.360_761_573_048_138_6),
    (-0.238_619_186_083_196_9, 0.467_913_934_572_691),
    (0.238_619_186_083_196_9, 0.467_913_934_572_691),
    (0.661_209_386_466_264_5, 0.360_761_573_048_138_6),
    (0.932_469_514_203_152, 0.171_324_492_379_170_35),
];

/// 4-point Gauss-Legendre nodes and weights on [-1, 1].
const GL4: [(f64, f64); 4] = [
    (-0.861_136_311_594_052_6, 0.347_854_845_137_453_9),
    (-0.339_981_043_584_856_3, 0.652_145_154_862_546_1),
    (0.339_981_043_584_856_3, 0.652_145_154_862_546_1),
    (0.861_136_311_594_052_6, 0.347_854_845_137_453_9),
];

/// Longest panel (in half-widths, resp. radians) one GL6 rule is applied to.
const PANEL: f64 = 0.25;

/// Intervals up to this length (in half-widths, resp. radians) take one GL4 panel: its error
/// bound `L^9 (4!)^4 / (9 (8!)^3) pi^8` is below 1e-16 of `L` there.
const SHORT: f64 = 1.0 / 16.0;

/// Gauss-Legendre on `[a, b]`: one GL4 panel when `b - a <= SHORT`, else composite GL6 with
/// panels no longer than [`PANEL`].
#[inline]
fn gl(a: f64, b: f64, mut f: impl FnMut(f64) -> f64) -> f64 {
    if b <= a {
        return 0.0;
    }
    let (m, h) = (0.5 * (a + b), 0.5 * (b - a));
    if b - a <= SHORT {
        return h * GL4.iter().map(|&(t, w)| w * f(m + h * t)).sum::<f64>();
    }
    let n = ((b - a) / PANEL).ceil() as usize;
    let h = (b - a) / n as f64;
    let mut sum = 0.0;
    for p in 0..n {
        let m = a + (p as f64 + 0.5) * h;
        let mut s = 0.0;
        for (t, w) in GL6 {
            s += w * f(m + 0.5 * h * t);
        }
        sum += 0.5 * h * s;
    }
    sum
}

/// `int int (1 + cos(pi r)) / 2` over `[u0, u1] x [v0, v1]` intersected with the unit disk,
/// in normalized coordinates (the dent spans `r < 1`).
fn dent_cell_integral(u0: f64, u1: f64, v0: f64, v1: f64) -> f64 {
    let bump = |u: f64, v2: f64| 0.5 * (1.0 + (PI * (u * u + v2).sqrt()).cos());
    if u0.abs().max(u1.abs()).powi(2) + v0.abs().max(v1.abs()).powi(2) <= 1.0 {
        // the whole cell inside the dent: plain tensor rule
        return gl(v0, v1, |v| gl(u0, u1, |u| bump(u, v * v)));
    }
    let (va, vb) = (v0.max(-1.0), v1.min(1.0));
    if vb <= va {
        return 0.0;
    }
    // breakpoints of the outer integrand: where the chord end sqrt(1 - v^2) meets u0 or u1
    let mut cuts = [va, vb, va, va, va, va];
    let mut n = 2;
    for u in [u0, u1] {
        if u.abs() < 1.0 {
            let v = (1.0 - u * u).sqrt();
            for vv in [-v, v] {
                if vv > va && vv < vb {
                    cuts[n] = vv;
                    n += 1;
                }
            }
        }
    }
    let cuts = &mut cuts[..n];
    cuts.sort_by(|a, b| a.total_cmp(b));
    let inner = |theta: f64| {
        let (v, c) = (theta.sin(), theta.cos());
        let (a, b) = (u0.max(-c), u1.min(c));
        let v2 = v * v;
        gl(a, b, |u| bump(u, v2)) * c
    };
    let mut total = 0.0;
    for w in cuts.windows(2) {
        total += gl(w[0].asin(), w[1].asin(), &inner);
    }
    total
}

/// Antiderivative of `(1 + cos(pi u)) / 2` on [-1, 1], clamped outside.
fn dent_1d_primitive(u: f64) -> f64 {
    let u = u.clamp(-1.0, 1.0);
    0.5 * (u + (PI * u).sin() / PI)
}

/// Dent: nested GL6 on analytic pieces (groove: closed form).
fn add_dent(g: &Grid, c: (f64, f64), w: f64, l: f64, d: f64, out: &mut [f64]) {
    let (hw, hl) = (0.5 * w, 0.5 * l);
    let cols = cell_range(c.0 - hw, c.0 + hw, g.x_min, g.dx, g.nx);
    if !l.is_finite() {
        // uniform along y: one value per column
        for i in cols {
            let (e0, e1) = x_edges(g, i);
            let v = d * hw / g.dx
                * (dent_1d_primitive((e1 - c.0) / hw) - dent_1d_primitive((e0 - c.0) / hw));
            if v != 0.0 {
                for j in 0..g.ny {
                    out[g.idx(i, j)] += v;
                }
            }
        }
        return;
    }
    let scale = d * hw * hl / (g.dx * g.dy);
    for j in rows_of(g, c.1, hl) {
        let (e0, e1) = y_edges(g, j);
        let (v0, v1) = ((e0 - c.1) / hl, (e1 - c.1) / hl);
        if v1 <= -1.0 || v0 >= 1.0 {
            continue;
        }
        for i in cols.clone() {
            let (f0, f1) = x_edges(g, i);
            let (u0, u1) = ((f0 - c.0) / hw, (f1 - c.0) / hw);
            // nearest point of the cell to the centre outside the disk: nothing there
            let un = u0.max(0.0).min(u1);
            let vn = v0.max(0.0).min(v1);
            if un * un + vn * vn >= 1.0 {
                continue;
            }
            out[g.idx(i, j)] += scale * dent_cell_integral(u0, u1, v0, v1);
        }
    }
}

/// Height map: exact (bilinear averaged over each cell/panel overlap at its centre).
fn add_height_map(g: &Grid, c: (f64, f64), m: &HeightMap, out: &mut [f64]) {
    let (ny_m, nx_m) = m.depths.dim();
    if nx_m < 2 || ny_m < 2 {
        return;
    }
    let (hx, hy) = m.half_extent();
    let (mx0, my0) = (c.0 - hx, c.1 - hy);
    // per direction: for each grid cell, the (panel, local coordinate of the overlap centre,
    // covered fraction of the cell) triples, stored flat with offsets
    let along = |lo0: f64, h_m: f64, n_m: usize, origin: f64, h: f64, n: usize| {
        let cells = cell_range(lo0, lo0 + (n_m - 1) as f64 * h_m, origin, h, n);
        let mut start = Vec::with_capacity(cells.len() + 1);
        let mut items: Vec<(usize, f64, f64)> = Vec::new();
        for i in cells.clone() {
            start.push(items.len());
            let (e0, e1) = (origin + i as f64 * h, origin + (i + 1) as f64 * h);
            let p0 = (((e0 - lo0) / h_m).floor().max(0.0) as usize).min(n_m - 2);
            let p1 = (((e1 - lo0) / h_m).ceil().max(0.0) as usize).min(n_m - 1);
            for p in p0..p1 {
                let (a, b) = (lo0 + p as f64 * h_m, lo0 + (p + 1) as f64 * h_m);
                let (s0, s1) = (a.max(e0), b.min(e1));
                if s1 > s0 {
                    let t = (0.5 * (s0 + s1) - a) / h_m;
                    items.push((p, t, (s1 - s0) / h));
                }
            }
        }
        start.push(items.len());
        (cells, start, items)
    };
    let (cols, xs, xi) = along(mx0, m.dx, nx_m, g.x_min, g.dx, g.nx);
    let (rows, ys, yi) = along(my0, m.dy, ny_m, g.y_min, g.dy, g.ny);
    for (jj, j) in rows.enumerate() {
        let ylist = &yi[ys[jj]..ys[jj + 1]];
        if ylist.is_empty() {
            continue;
        }
        for (ii, i) in cols.clone().enumerate() {
            let xlist = &xi[xs[ii]..xs[ii + 1]];
            let mut sum = 0.0;
            for &(q, u, fy) in ylist {
                for &(p, t, fx) in xlist {
                    sum += fx * fy * m.bilinear(p, q, t, u);
                }
            }
            if sum != 0.0 {
                out[g.idx(i, j)] += sum;
            }
        }
    }
}
