//! The O(N^2) direct sum of the rectangle (or strip) influence coefficients. Slow; kept as the
//! reference the FFT operators are tested against (as RustFFT tests every algorithm against a
//! naive DFT).

use super::operator::{images, BodyCompliance};
use super::{kernel, Deflection};
use crate::grid::Grid;

/// Deflection by direct summation over all cell pairs, plain half-space (no mirror images).
/// For `grid.ny == 1` with `line == true` it uses the plane-strain strip kernel (infinite line).
#[derive(Debug, Clone)]
pub struct DenseDeflection {
    grid: Grid,
    compliance: f64,
    line: bool,
    /// explicit images: (sign, shift, weight * body compliance)
    images: Vec<(f64, f64, f64)>,
}

impl DenseDeflection {
    /// Half-space operator on `grid` with reduced modulus `e_red` (Pa).
    pub fn new(grid: Grid, e_red: f64) -> Self {
        DenseDeflection {
            grid,
            compliance: kernel::compliance(e_red),
            line: false,
            images: Vec::new(),
        }
    }

    /// Half-space with every mirror image enumerated explicitly (the reference for
    /// [`super::FftDeflection::with_images`]).
    pub fn with_images(grid: Grid, bodies: &[BodyCompliance]) -> Self {
        let mut all = Vec::new();
        for b in bodies {
            if let Some(img) = &b.images {
                for (s, t, w) in images(img) {
                    all.push((s, t, w * b.compliance));
                }
            }
        }
        DenseDeflection {
            grid,
            compliance: bodies.iter().map(|b| b.compliance).sum(),
            line: false,
            images: all,
        }
    }

    /// Plane-strain (infinite line contact) operator on a grid with `ny == 1`.
    pub fn line(grid: Grid, e_red: f64) -> Self {
        assert_eq!(grid.ny, 1, "line operator needs ny == 1");
        DenseDeflection {
            grid,
            compliance: kernel::compliance(e_red),
            line: true,
            images: Vec::new(),
        }
    }
}

impl Deflection for DenseDeflection {
    fn grid(&self) -> &Grid {
        &self.grid
    }

    fn apply(&mut self, p: &[f64], out: &mut [f64]) {
        let g = self.grid;
        for j in 0..g.ny {
            for i in 0..g.nx {
                let mut s = 0.0;
                for l in 0..g.ny {
                    for k in 0..g.nx {
                        let pk = p[g.idx(k, l)];
                        if pk == 0.0 {
                            continue;
                        }
                        s +=
                            pk * self.coefficient(i as isize - k as isize, j as isize - l as isize);
                        let (x, y) = (g.x(i) - g.x(k), g.y(j));
                        for &(sign, shift, w) in &self.images {
                            let yl = sign * g.y(l) + shift;
                            s += pk * w * kernel::rectangle(x, y - yl, 0.5 * g.dx, 0.5 * g.dy);
                        }
                    }
                }
                out[g.idx(i, j)] = s;
            }
        }
    }

    fn coefficient(&self, di: isize, dj: isize) -> f64 {
        let g = &self.grid;
        let x = di as f64 * g.dx;
        if self.line {
            self.compliance * kernel::strip(x, 0.5 * g.dx)
        } else {
            let y = dj as f64 * g.dy;
            self.compliance * kernel::rectangle(x, y, 0.5 * g.dx, 0.5 * g.dy)
        }
    }
}
