//! Test and bench support for the dry solver: a plain zero-padded FFT convolution (DC-FFT) whose
//! kernel is taken from `DenseDeflection::coefficient`, so it equals the dense sum to rounding
//! (checked in `dry_hertz.rs`). A stand-in until the lead's `elastic::operator` lands; it is not
//! part of the library.
#![allow(dead_code)]

use ehl::elastic::dense::DenseDeflection;
use ehl::elastic::Deflection;
use ehl::grid::Grid;
use rayon::prelude::*;
use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
use rustfft::num_complex::Complex;
use rustfft::{Fft, FftPlanner};
use std::sync::Arc;

pub struct FftOp {
    grid: Grid,
    dense: DenseDeflection,
    mx: usize,
    my: usize,
    /// kernel spectrum, layout [kx][ky] (kx in 0..=mx/2, ky in 0..my), scaled by 1/(mx my)
    kernel: Vec<Complex<f64>>,
    r2c: Arc<dyn RealToComplex<f64>>,
    c2r: Arc<dyn ComplexToReal<f64>>,
    fwd: Arc<dyn Fft<f64>>,
    inv: Arc<dyn Fft<f64>>,
    rows: Vec<Complex<f64>>, // ny x (mx/2+1) row spectra
    cols: Vec<Complex<f64>>, // (mx/2+1) x my column data
}

impl FftOp {
    pub fn new(dense: DenseDeflection) -> Self {
        let grid = *dense.grid();
        let mx = 2 * grid.nx;
        let my = if grid.ny == 1 { 1 } else { 2 * grid.ny };
        let mut rp = RealFftPlanner::<f64>::new();
        let r2c = rp.plan_fft_forward(mx);
        let c2r = rp.plan_fft_inverse(mx);
        let mut cp = FftPlanner::<f64>::new();
        let fwd = cp.plan_fft_forward(my);
        let inv = cp.plan_fft_inverse(my);
        let hx = mx / 2 + 1;
        let mut op = FftOp {
            grid,
            dense,
            mx,
            my,
            kernel: vec![Complex::new(0.0, 0.0); hx * my],
            r2c,
            c2r,
            fwd,
            inv,
            rows: vec![Complex::new(0.0, 0.0); my * hx],
            cols: vec![Complex::new(0.0, 0.0); hx * my],
        };
        // circulant kernel: k[(di mod mx, dj mod my)] = coefficient(di, dj), zero at di = nx
        let mut kr = vec![0.0; mx * my];
        for jj in 0..my {
            let dj = if grid.ny == 1 { 0 } else if jj < grid.ny { jj as isize } else if jj == grid.ny { continue } else { jj as isize - my as isize };
            for ii in 0..mx {
                let di = if ii < grid.nx { ii as isize } else if ii == grid.nx { continue } else { ii as isize - mx as isize };
                kr[jj * mx + ii] = op.dense.coefficient(di, dj);
            }
        }
        let spec = op.forward(&kr, my);
        let scale = 1.0 / (mx * my) as f64;
        op.kernel = spec.iter().map(|c| c * scale).collect();
        op
    }

    /// 2D forward transform of `rows_in` real rows of length mx (padded to my rows with zeros);
    /// returns [kx][ky].
    fn forward(&mut self, data: &[f64], rows_in: usize) -> Vec<Complex<f64>> {
        let (mx, my) = (self.mx, self.my);
        let hx = mx / 2 + 1;
        let mut rows = vec![Complex::new(0.0, 0.0); my * hx];
        for j in 0..rows_in {
            let mut buf = data[j * mx..(j + 1) * mx].to_vec();
            self.r2c.process(&mut buf, &mut rows[j * hx..(j + 1) * hx]).unwrap();
        }
        let mut cols = vec![Complex::new(0.0, 0.0); hx * my];
        for kx in 0..hx {
            for j in 0..my {
                cols[kx * my + j] = rows[j * hx + kx];
            }
        }
        self.fwd.process(&mut cols);
        cols
    }
}

impl Deflection for FftOp {
    fn grid(&self) -> &Grid {
        &self.grid
    }

    fn apply(&mut self, p: &[f64], out: &mut [f64]) {
        let (nx, ny, mx, my) = (self.grid.nx, self.grid.ny, self.mx, self.my);
        let hx = mx / 2 + 1;
        let r2c = &self.r2c;
        // rows: real FFT of the first ny rows (zero padded)
        self.rows[..ny * hx]
            .par_chunks_mut(hx)
            .zip(p.par_chunks(nx))
            .for_each_init(
                || (vec![0.0; mx], r2c.make_scratch_vec()),
                |(buf, scr), (row, pr)| {
                    buf[..nx].copy_from_slice(pr);
                    buf[nx..].iter_mut().for_each(|v| *v = 0.0);
                    r2c.process_with_scratch(buf, row, scr).unwrap();
                },
            );
        // columns: transpose, FFT, multiply, inverse FFT
        let rows = &self.rows;
        let (fwd, inv, kernel) = (&self.fwd, &self.inv, &self.kernel);
        self.cols.par_chunks_mut(my).enumerate().for_each_init(
            || vec![Complex::new(0.0, 0.0); fwd.get_inplace_scratch_len().max(inv.get_inplace_scratch_len())],
            |scr, (kx, col)| {
                for j in 0..ny {
                    col[j] = rows[j * hx + kx];
                }
                col[ny..].iter_mut().for_each(|v| *v = Complex::new(0.0, 0.0));
                fwd.process_with_scratch(col, scr);
                for (c, k) in col.iter_mut().zip(&kernel[kx * my..(kx + 1) * my]) {
                    *c *= k;
                }
                inv.process_with_scratch(col, scr);
            },
        );
        let cols = &self.cols;
        let c2r = &self.c2r;
        self.rows[..ny * hx]
            .par_chunks_mut(hx)
            .zip(out.par_chunks_mut(nx))
            .enumerate()
            .for_each_init(
                || (vec![0.0; mx], c2r.make_scratch_vec()),
                |(buf, scr), (j, (row, o))| {
                    for kx in 0..hx {
                        row[kx] = cols[kx * my + j];
                    }
                    row[0].im = 0.0;
                    row[hx - 1].im = 0.0;
                    c2r.process_with_scratch(row, buf, scr).unwrap();
                    o.copy_from_slice(&buf[..nx]);
                },
            );
    }

    fn coefficient(&self, di: isize, dj: isize) -> f64 {
        self.dense.coefficient(di, dj)
    }
}

/// Half-space FFT operator factory for reduced modulus `e_red`.
pub fn half_space(e_red: f64) -> impl Fn(Grid) -> Box<dyn Deflection> + Sync {
    move |g: Grid| Box::new(FftOp::new(DenseDeflection::new(g, e_red))) as Box<dyn Deflection>
}

/// Plane-strain line-contact FFT operator factory (grids with ny == 1).
pub fn line(e_red: f64) -> impl Fn(Grid) -> Box<dyn Deflection> + Sync {
    move |g: Grid| Box::new(FftOp::new(DenseDeflection::line(g, e_red))) as Box<dyn Deflection>
}
