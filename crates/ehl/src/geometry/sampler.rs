//! The undeformed gap as the solvers see it: values on the cells of a grid.
//!
//! The solvers work on several grids (nested dry levels, EHL grid sequencing), so they do not
//! take a gap array but a [`GapSampler`] that fills one for any grid. A smooth gap (a closure
//! g(x, y), m) is sampled at the cell centres; a gap with surface features
//! ([`super::GapWithFeatures`]) adds each feature's exact cell average, so that a feature moving
//! by part of a cell changes the sampled gap continuously.

use crate::grid::Grid;

/// The undeformed gap g (m) on the cells of any grid; `f64::INFINITY` where a body has no
/// material. Values may be negative where a feature (a bump, negative depth) rises above the
/// smooth surfaces: nothing clips them.
pub trait GapSampler: Sync {
    /// The smooth gap (without features) at a point (m): used to classify the contact.
    fn at(&self, x: f64, y: f64) -> f64;

    /// Fills `out` (row-major, `grid.len()` values) with the gap of each cell. The default
    /// samples [`GapSampler::at`] at the cell centres (y = 0 on a one-row grid, the infinite
    /// line contact).
    fn sample(&self, grid: &Grid, out: &mut [f64]) {
        use rayon::prelude::*;
        assert_eq!(out.len(), grid.len(), "gap buffer of the wrong length");
        out.par_chunks_mut(grid.nx)
            .enumerate()
            .for_each(|(j, row)| {
                let y = if grid.ny == 1 { 0.0 } else { grid.y(j) };
                for (i, v) in row.iter_mut().enumerate() {
                    *v = self.at(grid.x(i), y);
                }
            });
    }

    /// [`GapSampler::sample`] into a new vector.
    fn sampled(&self, grid: &Grid) -> Vec<f64> {
        let mut out = vec![0.0; grid.len()];
        self.sample(grid, &mut out);
        out
    }
}

impl<F: Fn(f64, f64) -> f64 + Sync> GapSampler for F {
    fn at(&self, x: f64, y: f64) -> f64 {
        self(x, y)
    }
}

/// A smooth gap plus the surface features of the bodies, each body's features shifted along x
/// by the distance its surface has travelled: g = g_smooth + d_1(x - s_1, y) + d_2(x - s_2, y),
/// with d_k the cell-averaged depth of body k's features ([`crate::surface::Surface`]; depth > 0
/// opens the gap). Cells without material stay infinite. Feature positions are in contact
/// coordinates (x rolling, y along body 1's axis).
pub struct GapWithFeatures<'a> {
    /// the gap of the smooth bodies
    pub smooth: &'a dyn GapSampler,
    /// each body's features and the shift of its surface along x (m)
    pub surfaces: Vec<(&'a crate::surface::Surface, f64)>,
}

impl GapSampler for GapWithFeatures<'_> {
    fn at(&self, x: f64, y: f64) -> f64 {
        self.smooth.at(x, y)
    }

    fn sample(&self, grid: &Grid, out: &mut [f64]) {
        self.smooth.sample(grid, out);
        let mut depth = vec![0.0; grid.len()];
        for (surface, shift) in &self.surfaces {
            surface.cell_averages(grid, *shift, &mut depth);
            for (g, d) in out.iter_mut().zip(&depth) {
                if g.is_finite() {
                    *g += d;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::surface::{Feature, FeatureShape, Surface};

    #[test]
    fn closure_is_sampled_at_cell_centres() {
        let g = Grid::new(4, 3, -1.0, 1.0, 0.0, 3.0);
        let v = (|x: f64, y: f64| x + 10.0 * y).sampled(&g);
        assert_eq!(v[g.idx(0, 0)], -0.75 + 5.0);
        assert_eq!(v[g.idx(3, 2)], 0.75 + 25.0);
        // one row: y = 0 (the infinite line contact)
        let line = Grid::new(4, 1, -1.0, 1.0, -0.5, 0.5);
        assert!((|x: f64, y: f64| x + 10.0 * y)
            .sampled(&line)
            .iter()
            .zip(line.xs())
            .all(|(v, x)| *v == x));
    }

    #[test]
    fn features_add_their_cell_averages_and_leave_no_material_alone() {
        let g = Grid::new(8, 4, -2e-3, 2e-3, -1e-3, 1e-3);
        let smooth = |x: f64, y: f64| if y > 0.5e-3 { f64::INFINITY } else { x * x };
        // a pit of depth 1 um exactly covering cells i = 3..5, j = 0..4 (both directions),
        // and a bump of body 2 half a cell wide, shifted by a quarter cell
        let pit = Surface::new(vec![Feature::new(
            FeatureShape::Pit {
                width: 1e-3,
                length: 2e-3,
                depth: 1e-6,
            },
            (0.0, 0.0),
        )]);
        let bump = Surface::new(vec![Feature::new(
            FeatureShape::Pit {
                width: 0.25e-3,
                length: f64::INFINITY,
                depth: -2e-7,
            },
            (-1.375e-3, 0.0),
        )]);
        let gap = GapWithFeatures {
            smooth: &smooth,
            surfaces: vec![(&pit, 0.0), (&bump, 0.125e-3)],
        };
        let v = gap.sampled(&g);
        let base = smooth.sampled(&g);
        for j in 0..g.ny {
            for i in 0..g.nx {
                let k = g.idx(i, j);
                if !base[k].is_finite() {
                    assert!(v[k].is_infinite(), "no material stays infinite");
                    continue;
                }
                let want = match i {
                    3 | 4 => 1e-6,
                    // the bump (0.25 mm wide) centred at -1.25 mm: half of cell 1
                    1 => -1e-7,
                    _ => 0.0,
                };
                assert!(
                    (v[k] - base[k] - want).abs() < 1e-18,
                    "({i}, {j}): {}",
                    v[k] - base[k]
                );
            }
        }
        // the bump closes the gap: nothing clips it
        assert!(v[g.idx(1, 0)] < base[g.idx(1, 0)]);
    }
}
