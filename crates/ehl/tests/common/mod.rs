//! Test helpers for the EHL tests: a cached Toeplitz operator (the dense kernel with its
//! coefficients computed once), the Moes / Pan-Hamrock / Hamrock-Dowson fits (local copies until
//! `reference/` has them), and case builders from the dimensionless groups.
#![allow(dead_code)]

use ehl::case::{DensityModel, Lubricant, Rheology, ViscosityModel};
use ehl::elastic::dense::DenseDeflection;
use ehl::elastic::Deflection;
use ehl::grid::Grid;
use ehl::units;
use rustfft::{num_complex::Complex, FftPlanner};
use std::sync::Arc;

/// Direct Toeplitz sum with coefficients cached from `DenseDeflection` (1D line: O(n^2) but
/// without recomputing the logarithms). Equal to `DenseDeflection::line` by construction.
pub struct ToeplitzLine {
    grid: Grid,
    dense: DenseDeflection,
    c: Vec<f64>,
}

impl ToeplitzLine {
    pub fn new(grid: Grid, e_red: f64) -> Self {
        let dense = DenseDeflection::line(grid, e_red);
        let c = (0..grid.nx)
            .map(|d| dense.coefficient(d as isize, 0))
            .collect();
        ToeplitzLine { grid, dense, c }
    }
}

impl Deflection for ToeplitzLine {
    fn grid(&self) -> &Grid {
        &self.grid
    }
    fn apply(&mut self, p: &[f64], out: &mut [f64]) {
        let n = self.grid.nx;
        for i in 0..n {
            let mut s = 0.0;
            for (k, &pk) in p.iter().enumerate() {
                s += pk * self.c[i.abs_diff(k)];
            }
            out[i] = s;
        }
    }
    fn coefficient(&self, di: isize, dj: isize) -> f64 {
        self.dense.coefficient(di, dj)
    }
}

/// Half-space operator by zero-padded FFT convolution (DC-FFT) with the rectangle coefficients
/// of `DenseDeflection` (plain complex FFT; a stand-in until the lead's operator lands).
pub struct FftHalfSpace {
    grid: Grid,
    dense: DenseDeflection,
    kf: Vec<Complex<f64>>,
    buf: Vec<Complex<f64>>,
    fwd_x: Arc<dyn rustfft::Fft<f64>>,
    inv_x: Arc<dyn rustfft::Fft<f64>>,
    fwd_y: Arc<dyn rustfft::Fft<f64>>,
    inv_y: Arc<dyn rustfft::Fft<f64>>,
    col: Vec<Complex<f64>>,
}

impl FftHalfSpace {
    pub fn new(grid: Grid, e_red: f64) -> Self {
        let dense = DenseDeflection::new(grid, e_red);
        let (mx, my) = (2 * grid.nx, 2 * grid.ny);
        let mut planner = FftPlanner::new();
        let fwd_x = planner.plan_fft_forward(mx);
        let inv_x = planner.plan_fft_inverse(mx);
        let fwd_y = planner.plan_fft_forward(my);
        let inv_y = planner.plan_fft_inverse(my);
        let mut kf = vec![Complex::new(0.0, 0.0); mx * my];
        for j in 0..my {
            let dj = if j < grid.ny {
                j as isize
            } else if j == grid.ny {
                0
            } else {
                j as isize - my as isize
            };
            for i in 0..mx {
                let di = if i < grid.nx {
                    i as isize
                } else if i == grid.nx {
                    0
                } else {
                    i as isize - mx as isize
                };
                let zero = i == grid.nx || j == grid.ny;
                kf[j * mx + i] =
                    Complex::new(if zero { 0.0 } else { dense.coefficient(di, dj) }, 0.0);
            }
        }
        let mut s = FftHalfSpace {
            grid,
            dense,
            kf: vec![],
            buf: vec![Complex::new(0.0, 0.0); mx * my],
            fwd_x,
            inv_x,
            fwd_y,
            inv_y,
            col: vec![Complex::new(0.0, 0.0); my],
        };
        s.fft2(&mut kf, true);
        let scale = 1.0 / (mx * my) as f64;
        kf.iter_mut().for_each(|v| *v *= scale);
        s.kf = kf;
        s
    }

    fn fft2(&mut self, a: &mut [Complex<f64>], forward: bool) {
        let (mx, my) = (2 * self.grid.nx, 2 * self.grid.ny);
        let (fx, fy) = if forward {
            (&self.fwd_x, &self.fwd_y)
        } else {
            (&self.inv_x, &self.inv_y)
        };
        for row in a.chunks_mut(mx) {
            fx.process(row);
        }
        for i in 0..mx {
            for j in 0..my {
                self.col[j] = a[j * mx + i];
            }
            fy.process(&mut self.col);
            for j in 0..my {
                a[j * mx + i] = self.col[j];
            }
        }
    }
}

impl Deflection for FftHalfSpace {
    fn grid(&self) -> &Grid {
        &self.grid
    }
    fn apply(&mut self, p: &[f64], out: &mut [f64]) {
        let g = self.grid;
        let mx = 2 * g.nx;
        let mut buf = std::mem::take(&mut self.buf);
        buf.iter_mut().for_each(|v| *v = Complex::new(0.0, 0.0));
        for j in 0..g.ny {
            for i in 0..g.nx {
                buf[j * mx + i] = Complex::new(p[g.idx(i, j)], 0.0);
            }
        }
        self.fft2(&mut buf, true);
        for (b, k) in buf.iter_mut().zip(&self.kf) {
            *b *= k;
        }
        self.fft2(&mut buf, false);
        for j in 0..g.ny {
            for i in 0..g.nx {
                out[g.idx(i, j)] = buf[j * mx + i].re;
            }
        }
        self.buf = buf;
    }
    fn coefficient(&self, di: isize, dj: isize) -> f64 {
        self.dense.coefficient(di, dj)
    }
}

pub fn lubricant(eta0: f64, alpha: f64, visc: ViscosityModel, dens: DensityModel) -> Lubricant {
    Lubricant {
        viscosity: eta0,
        pressure_viscosity_coefficient: alpha,
        density: 850.0,
        viscosity_model: visc,
        density_model: dens,
        rheology: Rheology::Newtonian,
    }
}

/// Moes (1992) central film for line contacts, H = (h_c/R) U^(-1/2), from M and L
/// (Venner & Lubrecht 2000 eq. 4.x; fit to Barus viscosity, constant density).
pub fn moes_line_central(m: f64, l: f64) -> f64 {
    let h_ri = 3.0 / m;
    let h_ei = 2.621 * m.powf(-0.2);
    let h_rp = 1.287 * l.powf(2.0 / 3.0);
    let h_ep = 1.311 * m.powf(-0.125) * l.powf(0.75);
    let s = 1.5 * (1.0 + (-1.2 * h_ei / h_ri).exp());
    ((h_ri.powf(7.0 / 3.0) + h_ei.powf(7.0 / 3.0)).powf(3.0 * s / 7.0)
        + (h_rp.powf(-3.5) + h_ep.powf(-3.5)).powf(-2.0 * s / 7.0))
    .powf(1.0 / s)
}

/// The thinnest film of a solution's film field (m; infinite cells, where there is no
/// material, never win).
pub fn thinnest(film: &[f64]) -> f64 {
    film.iter().copied().fold(f64::INFINITY, f64::min)
}

/// Pan & Hamrock (1989) line contact: (H_min, H_c) = (h/R) for W = w'/(E'R), U, G
/// (fit to Roelands viscosity and Dowson-Higginson density).
pub fn pan_hamrock(w: f64, u: f64, g: f64) -> (f64, f64) {
    (
        1.714 * w.powf(-0.128) * u.powf(0.694) * g.powf(0.568),
        2.922 * w.powf(-0.166) * u.powf(0.692) * g.powf(0.470),
    )
}

/// A line contact (SI) built from Moes groups by [`line_case`].
pub struct LineCase {
    pub e: f64,
    pub r: f64,
    pub w: f64,
    pub ue: f64,
    pub b: f64,
    pub ph: f64,
    pub lub: ehl::case::Lubricant,
}

/// A line contact with Moes groups (M, L) (Venner-Lubrecht definition with 2U, see
/// `reference::film::moes_line_groups`): E' = 2.2e11 Pa, R = 0.02 m, eta0 = 0.04 Pa s,
/// alpha = 20 GPa^-1 (G = 4400); U from L, W from M.
pub fn line_case(m: f64, l: f64, visc: ViscosityModel, dens: DensityModel) -> LineCase {
    let (e, r, eta0, alpha) = (2.2e11, 0.02, 0.04, 2.0e-8);
    let g = alpha * e;
    // L = G (2U)^(1/4), M = W (2U)^(-1/2)
    let u2 = (l / g).powi(4);
    let u = 0.5 * u2;
    let wd = m * u2.sqrt();
    let w = wd * e * r;
    let ue = u * e * r / eta0;
    LineCase {
        e,
        r,
        w,
        ue,
        b: units::hertz_line_half_width(w, r, e),
        ph: units::hertz_line_pressure(w, r, e),
        lub: lubricant(eta0, alpha, visc, dens),
    }
}

impl LineCase {
    /// The steady problem of this line contact on `grid` with the gap `gap` and the elastic
    /// operator `op` (callers own both: the problem borrows them).
    #[allow(dead_code)]
    pub fn problem<'a>(
        &'a self,
        grid: Grid,
        gap: &'a dyn ehl::geometry::GapSampler,
        op: &'a (dyn Fn(Grid) -> Box<dyn Deflection> + Sync),
    ) -> ehl::ehl::EhlProblem<'a> {
        ehl::ehl::EhlProblem {
            grid,
            gap,
            operator: op,
            load: self.w,
            lubricant: &self.lub,
            entrainment_speed: self.ue,
            reduced_radius: self.r,
            reduced_modulus: self.e,
            hertz_half_width: self.b,
            hertz_pressure: self.ph,
            initial_pressure: None,
        }
    }
}
