//! The cell grid: `nx * ny` rectangular cells of uniform pressure (thesis ch. 1, the Hartnett /
//! boundary-element discretisation). Cell centres are the collocation points for the gap, the
//! deflection and the Reynolds equation.

/// A uniform cell-centred grid on `[x_min, x_max] x [y_min, y_max]` (m).
///
/// `ny == 1` with `y_len == f64::INFINITY` is the infinite line contact (1D in `x`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Grid {
    pub nx: usize,
    pub ny: usize,
    /// left edge of the first cell along x (m)
    pub x_min: f64,
    /// left edge of the first cell along y (m)
    pub y_min: f64,
    /// cell size along x (m)
    pub dx: f64,
    /// cell size along y (m); for an infinite line contact the nominal (unused) length
    pub dy: f64,
}

impl Grid {
    /// A grid of `nx * ny` cells covering `[x_min, x_max] x [y_min, y_max]`.
    pub fn new(nx: usize, ny: usize, x_min: f64, x_max: f64, y_min: f64, y_max: f64) -> Self {
        assert!(
            nx > 0 && ny > 0,
            "grid needs at least one cell per direction"
        );
        Grid {
            nx,
            ny,
            x_min,
            y_min,
            dx: (x_max - x_min) / nx as f64,
            dy: (y_max - y_min) / ny as f64,
        }
    }

    /// Number of cells.
    pub fn len(&self) -> usize {
        self.nx * self.ny
    }

    /// Always false: a grid has at least one cell.
    pub fn is_empty(&self) -> bool {
        false
    }

    /// x of the centre of column `i` (m).
    #[inline]
    pub fn x(&self, i: usize) -> f64 {
        self.x_min + (i as f64 + 0.5) * self.dx
    }

    /// y of the centre of row `j` (m).
    #[inline]
    pub fn y(&self, j: usize) -> f64 {
        self.y_min + (j as f64 + 0.5) * self.dy
    }

    /// Right edge along x (m).
    pub fn x_max(&self) -> f64 {
        self.x_min + self.nx as f64 * self.dx
    }

    /// Upper edge along y (m).
    pub fn y_max(&self) -> f64 {
        self.y_min + self.ny as f64 * self.dy
    }

    /// Flat index of cell `(i, j)`.
    #[inline]
    pub fn idx(&self, i: usize, j: usize) -> usize {
        j * self.nx + i
    }

    /// Area of one cell (m^2).
    pub fn cell_area(&self) -> f64 {
        self.dx * self.dy
    }

    /// Cell-centre coordinates along x.
    pub fn xs(&self) -> Vec<f64> {
        (0..self.nx).map(|i| self.x(i)).collect()
    }

    /// Cell-centre coordinates along y.
    pub fn ys(&self) -> Vec<f64> {
        (0..self.ny).map(|j| self.y(j)).collect()
    }

    /// The grid with every cell split in two along both directions (`ny == 1` stays 1).
    pub fn refined(&self) -> Grid {
        let ny = if self.ny == 1 { 1 } else { 2 * self.ny };
        Grid::new(
            2 * self.nx,
            ny,
            self.x_min,
            self.x_max(),
            self.y_min,
            self.y_max(),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn centres_and_edges() {
        let g = Grid::new(4, 2, -2.0, 2.0, 0.0, 1.0);
        assert_eq!(g.dx, 1.0);
        assert_eq!(g.x(0), -1.5);
        assert_eq!(g.y(1), 0.75);
        assert_eq!(g.idx(3, 1), 7);
        assert_eq!(g.x_max(), 2.0);
        let f = g.refined();
        assert_eq!((f.nx, f.ny), (8, 4));
        assert_eq!(f.dx, 0.5);
    }
}
