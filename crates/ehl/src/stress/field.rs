//! The stress field on a depth grid by zero-padded FFT convolution of the surface loads with the
//! closed-form influence coefficients of [`super::kernel`] (DC-FFT: Liu, Wang & Liu 2000, Wear 243;
//! Liu & Wang 2002, J. Tribol. 124): exact for piecewise-constant loads on the cells, with no
//! periodic images (each direction padded to at least 2 n - 1).
//!
//! The FFTs run in single precision (the influence coefficients and the loads are formed in double
//! precision): the round-off, ~1e-6 of the largest stress, is far below the discretisation error
//! of piecewise-constant loads (1e-3 p0 on a Hertz contact of 128 cells per width, see the
//! tests), and it halves both the time and the memory of the transforms.
//!
//! Cost per layer: the influence tables (14 closed-form functions on one quadrant of cell
//! corners), the forward FFTs of the kernels and 6 products and inverse FFTs; the 2 load FFTs are
//! shared by all layers. Of the 12 kernels 11 are distinct (the tangential sigma_zz is the normal
//! tau_xz). Each padded kernel table is exactly even or odd in x and in y on the FFT's period,
//! so its spectrum is real (parities alike) or imaginary (parities opposite): one real FFT of
//! the sum of a real-spectrum and an imaginary-spectrum kernel gives both (6 FFTs per layer, 4
//! without a traction), and a spectrum is kept as one f32 per bin over ky <= py/2.
//! [`StressKernels`] keeps these spectra across evaluations of one grid and layers (a
//! transient passage: 2 load FFTs and 6 inverse FFTs per layer and step). Layers run in
//! parallel (rayon), each with its own FFT buffers.

use super::kernel::{LayerKernel, KERNEL_PARITY};
use crate::grid::Grid;
use rayon::prelude::*;
use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
use rustfft::num_complex::Complex;
use rustfft::{Fft, FftPlanner};
use std::sync::Arc;

/// Stress components on a depth grid below a cell grid, in the body's own frame: x along the
/// rolling direction, y along the axis, z depth into the body (> 0). Tension positive.
#[derive(Debug, Clone)]
pub struct StressField {
    pub nx: usize,
    pub ny: usize,
    /// depths of the layers (m), increasing, all > 0
    pub z: Vec<f64>,
    /// sigma_xx, sigma_yy, sigma_zz, tau_yz, tau_xz, tau_xy (Voigt order), each
    /// `z.len() * ny * nx` values (Pa), index `(k * ny + j) * nx + i`; f32 to halve the memory
    /// of a volume (7 significant digits, far below the discretisation error)
    pub components: [Vec<f32>; 6],
}

impl StressField {
    /// Number of points of one component.
    pub fn len(&self) -> usize {
        self.z.len() * self.ny * self.nx
    }

    /// True when there are no points.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The six components at flat index `n` (f64, Voigt order).
    #[inline]
    pub fn tensor(&self, n: usize) -> [f64; 6] {
        std::array::from_fn(|c| self.components[c][n] as f64)
    }
}

/// Bytes of a [`StressField`] of `layers` layers on `cells` cells, with its `derived` extra
/// fields of the same size (f32).
pub fn field_bytes(cells: usize, layers: usize, derived: usize) -> f64 {
    (cells * layers * (6 + derived) * 4) as f64
}

/// Rows transformed (forward) or gathered (inverse) together: the spectrum is stored
/// column-major, so a row's bins are py complex apart (4 KiB at py = 512, one L1 set); a block of
/// rows writes or reads each column's entries contiguously.
const ROW_BLOCK: usize = 16;

/// 2D real FFT of a zero-padded px x py array; spectra stored column-major, [kx][ky]
/// (hx = px / 2 + 1 columns of py).
#[derive(Clone)]
struct Fft2 {
    nx: usize,
    ny: usize,
    px: usize,
    py: usize,
    hx: usize,
    r2c: Arc<dyn RealToComplex<f32>>,
    c2r: Arc<dyn ComplexToReal<f32>>,
    fwd: Arc<dyn Fft<f32>>,
    inv: Arc<dyn Fft<f32>>,
}

/// Per-thread buffers of [`Fft2`].
struct Buffers {
    real: Vec<f32>,
    /// ROW_BLOCK rows of hx bins
    block: Vec<Complex<f32>>,
    scratch_r: Vec<Complex<f32>>,
    scratch_c: Vec<Complex<f32>>,
}

impl Fft2 {
    fn new(nx: usize, ny: usize) -> Self {
        let px = crate::elastic::operator::fast_len(2 * nx - 1).max(2);
        let py = if ny == 1 {
            1
        } else {
            crate::elastic::operator::fast_len(2 * ny - 1)
        };
        let mut rp = RealFftPlanner::<f32>::new();
        let mut cp = FftPlanner::<f32>::new();
        Fft2 {
            nx,
            ny,
            px,
            py,
            hx: px / 2 + 1,
            r2c: rp.plan_fft_forward(px),
            c2r: rp.plan_fft_inverse(px),
            fwd: cp.plan_fft_forward(py),
            inv: cp.plan_fft_inverse(py),
        }
    }

    fn spectrum_len(&self) -> usize {
        self.hx * self.py
    }

    /// ky bins kept of a kernel spectrum (its parity in y gives the others): 0..=py/2.
    fn hy(&self) -> usize {
        self.py / 2 + 1
    }

    /// Values of one reduced kernel spectrum ([`Self::hy`] bins of each of the hx columns).
    fn reduced_len(&self) -> usize {
        self.hx * self.hy()
    }

    fn buffers(&self) -> Buffers {
        let sr = self.r2c.get_scratch_len().max(self.c2r.get_scratch_len());
        let sc = self
            .fwd
            .get_inplace_scratch_len()
            .max(self.inv.get_inplace_scratch_len());
        Buffers {
            real: vec![0.0f32; self.px],
            block: vec![Complex::default(); ROW_BLOCK * self.hx],
            scratch_r: vec![Complex::default(); sr],
            scratch_c: vec![Complex::default(); sc],
        }
    }

    /// Spectrum of the padded array whose row r (0..py) `fill` writes into a zeroed row
    /// (returning false for an all-zero row, which is skipped).
    fn forward(
        &self,
        b: &mut Buffers,
        out: &mut [Complex<f32>],
        mut fill: impl FnMut(usize, &mut [f32]) -> bool,
    ) {
        let (py, hx) = (self.py, self.hx);
        let out = &mut out[..hx * py];
        let mut r0 = 0;
        while r0 < py {
            let rows = ROW_BLOCK.min(py - r0);
            for rr in 0..rows {
                let dst = &mut b.block[rr * hx..(rr + 1) * hx];
                b.real.iter_mut().for_each(|v| *v = 0.0);
                if fill(r0 + rr, &mut b.real) {
                    self.r2c
                        .process_with_scratch(&mut b.real, dst, &mut b.scratch_r)
                        .expect("row FFT sizes");
                } else {
                    dst.iter_mut().for_each(|v| *v = Complex::default());
                }
            }
            for (kx, col) in out.chunks_mut(py).enumerate() {
                for (rr, d) in col[r0..r0 + rows].iter_mut().enumerate() {
                    *d = b.block[rr * hx + kx];
                }
            }
            r0 += rows;
        }
        if py > 1 {
            self.fwd.process_with_scratch(out, &mut b.scratch_c);
        }
    }

    /// Inverse of a spectrum (destroyed), scaled by 1 / (px py), into the first ny x nx entries:
    /// `store(j, row)` receives row j (nx values).
    fn inverse(
        &self,
        b: &mut Buffers,
        spec: &mut [Complex<f32>],
        mut store: impl FnMut(usize, &[f32]),
    ) {
        let (py, hx, nx) = (self.py, self.hx, self.nx);
        let spec = &mut spec[..hx * py];
        if py > 1 {
            self.inv.process_with_scratch(spec, &mut b.scratch_c);
        }
        let scale = 1.0 / (self.px * self.py) as f32;
        let even = self.px.is_multiple_of(2);
        let mut j0 = 0;
        while j0 < self.ny {
            let rows = ROW_BLOCK.min(self.ny - j0);
            for (kx, col) in spec.chunks(py).enumerate() {
                for (rr, v) in col[j0..j0 + rows].iter().enumerate() {
                    b.block[rr * hx + kx] = v * scale;
                }
            }
            for rr in 0..rows {
                let row = &mut b.block[rr * hx..(rr + 1) * hx];
                row[0].im = 0.0;
                if even {
                    row[hx - 1].im = 0.0;
                }
                self.c2r
                    .process_with_scratch(row, &mut b.real, &mut b.scratch_r)
                    .expect("row FFT sizes");
                store(j0 + rr, &b.real[..nx]);
            }
            j0 += rows;
        }
    }

    /// Spectrum of a grid field (ny x nx, row-major), zero padded.
    fn field_spectrum(&self, b: &mut Buffers, f: &[f64]) -> Vec<Complex<f32>> {
        let mut out = vec![Complex::default(); self.spectrum_len()];
        let (nx, ny) = (self.nx, self.ny);
        self.forward(b, &mut out, |r, row| {
            if r >= ny {
                return false;
            }
            row[..nx]
                .iter_mut()
                .zip(&f[r * nx..(r + 1) * nx])
                .for_each(|(d, v)| *d = *v as f32);
            true
        });
        out
    }
}

/// The distinct kernels of a layer: the 12 of [`LayerKernel`] less the tangential sigma_zz,
/// which is the normal tau_xz (both -z I_xzzz / 2 pi, Johnson's reciprocity; plane strain:
/// z^2 / (pi r^2) both; bit for bit the same table, checked in `kernel.rs`). Slot s holds kernel
/// `SLOT_KERNEL[s]`.
const SLOT_KERNEL: [usize; 11] = [0, 1, 2, 3, 4, 5, 6, 7, 9, 10, 11];

/// Slot of kernel k (0..12) in [`SLOT_KERNEL`].
const fn slot_of(k: usize) -> usize {
    match k {
        0..=7 => k,
        8 => 4,
        _ => k - 1,
    }
}

/// A kernel's spectrum is real when its parities in x and y agree (even-even, odd-odd), purely
/// imaginary otherwise (the padded table is exactly (anti)symmetric on the FFT's period).
fn imaginary(k: usize) -> bool {
    let (sx, sy) = KERNEL_PARITY[k];
    sx * sy < 0.0
}

/// The forward transforms that give the spectra of `slots`: pairs of one real and one
/// imaginary kernel share one real FFT (of their sum: the real part is the one's, the
/// imaginary part the other's), the rest go alone.
fn schedule(slots: &[usize]) -> Vec<(usize, Option<usize>)> {
    let (im, re): (Vec<usize>, Vec<usize>) =
        slots.iter().partition(|&&s| imaginary(SLOT_KERNEL[s]));
    let n = re.len().max(im.len());
    (0..n)
        .map(|i| match (re.get(i), im.get(i)) {
            (Some(&a), b) => (a, b.copied()),
            (None, Some(&b)) => (b, None),
            (None, None) => unreachable!(),
        })
        .collect()
}

/// Memory of the cached spectra: bytes per layer (f32, 11 kernels x hx x (py/2 + 1)) on an
/// `nx` x `ny` grid.
pub fn layer_spectra_bytes(nx: usize, ny: usize) -> usize {
    let f = Fft2::new(nx, ny);
    SLOT_KERNEL.len() * f.reduced_len() * std::mem::size_of::<f32>()
}

/// Default memory for the cached kernel spectra of a transient run (all bodies together):
/// 256 MiB, 92 layers of a 256 x 256 grid (2.9 MB each), 23 of a 512 x 512 grid (11.6 MB).
pub const DEFAULT_CACHE_BYTES: usize = 256 << 20;

/// The planned FFTs and the kernel spectra of the layers of one body (grid, Poisson ratio,
/// depths): built once per run, each [`Self::field`] then costs 2 load FFTs and 6 inverse FFTs
/// per layer. The spectra of the first layers that fit the memory budget are kept; the others
/// are formed again at every evaluation (tables and 6 forward FFTs per layer, 4 without a
/// traction). A budget of 0 keeps none: one evaluation, no memory beyond the threads' buffers.
#[derive(Clone)]
pub struct StressKernels {
    nx: usize,
    ny: usize,
    dx: f64,
    /// infinite: plane strain
    dy: f64,
    nu: f64,
    z: Vec<f64>,
    fft: Fft2,
    /// per layer: the reduced spectra of the 11 slots, slot s at s * reduced_len (None: not kept)
    cached: Vec<Option<Vec<f32>>>,
}

impl std::fmt::Debug for StressKernels {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("StressKernels")
            .field("nx", &self.nx)
            .field("ny", &self.ny)
            .field("nu", &self.nu)
            .field("layers", &self.z.len())
            .field("cached_layers", &self.cached_layers())
            .field("bytes", &self.bytes())
            .finish()
    }
}

impl StressKernels {
    /// The kernels of a half-space of Poisson ratio `nu` below `grid` at depths `z` (m, each
    /// greater than 0; `plane_strain` as in [`stress_field`]), keeping the spectra of as many
    /// layers as fit `budget_bytes` ([`layer_spectra_bytes`] each).
    pub fn new(grid: &Grid, nu: f64, z: &[f64], plane_strain: bool, budget_bytes: usize) -> Self {
        let (nx, ny) = (grid.nx, grid.ny);
        let fft = Fft2::new(nx, ny);
        let per = layer_spectra_bytes(nx, ny);
        let keep = (budget_bytes / per.max(1)).min(z.len());
        let mut k = StressKernels {
            nx,
            ny,
            dx: grid.dx,
            dy: if plane_strain { f64::INFINITY } else { grid.dy },
            nu,
            z: z.to_vec(),
            fft,
            cached: vec![None; z.len()],
        };
        let all: Vec<usize> = (0..SLOT_KERNEL.len()).collect();
        let kept: Vec<Option<Vec<f32>>> = z[..keep]
            .par_iter()
            .map_init(
                || {
                    (
                        k.fft.buffers(),
                        vec![Complex::default(); k.fft.spectrum_len()],
                    )
                },
                |(b, work), &depth| {
                    let mut spec = vec![0.0f32; SLOT_KERNEL.len() * k.fft.reduced_len()];
                    k.layer_spectra(depth, &all, b, work, &mut spec);
                    Some(spec)
                },
            )
            .collect();
        for (c, s) in k.cached.iter_mut().zip(kept) {
            *c = s;
        }
        k
    }

    /// Whether these kernels are those of `grid`, `nu`, `z`, `plane_strain`.
    pub fn matches(&self, grid: &Grid, nu: f64, z: &[f64], plane_strain: bool) -> bool {
        let dy = if plane_strain { f64::INFINITY } else { grid.dy };
        (self.nx, self.ny, self.dx, self.dy, self.nu) == (grid.nx, grid.ny, grid.dx, dy, nu)
            && self.z == z
    }

    /// Layers whose spectra are kept.
    pub fn cached_layers(&self) -> usize {
        self.cached.iter().filter(|c| c.is_some()).count()
    }

    /// Bytes of the kept spectra.
    pub fn bytes(&self) -> usize {
        self.cached
            .iter()
            .flatten()
            .map(|s| s.len() * std::mem::size_of::<f32>())
            .sum()
    }

    /// The depths (m).
    pub fn depths(&self) -> &[f64] {
        &self.z
    }

    /// The reduced spectra of `slots` at depth `depth` into `spec` (slot s at s * reduced_len):
    /// the influence tables, then one real FFT per pair of [`schedule`].
    fn layer_spectra(
        &self,
        depth: f64,
        slots: &[usize],
        b: &mut Buffers,
        work: &mut [Complex<f32>],
        spec: &mut [f32],
    ) {
        let (nx, ny, py, hx) = (self.nx, self.ny, self.fft.py, self.fft.hx);
        let (hy, rl) = (self.fft.hy(), self.fft.reduced_len());
        let kernel = LayerKernel::new(nx, ny, self.dx, self.dy, depth, self.nu);
        for (a, pair) in schedule(slots) {
            let ks: Vec<usize> = std::iter::once(a)
                .chain(pair)
                .map(|s| SLOT_KERNEL[s])
                .collect();
            self.fft.forward(b, work, |r, row| {
                let dj = if r < ny {
                    r as isize
                } else if r + ny > py {
                    r as isize - py as isize
                } else {
                    return false;
                };
                // the sum of a pair is formed in f64 and rounded once
                let (q0, (sx0, sy0)) = kernel.quadrant(ks[0]);
                let src0 = &q0[dj.unsigned_abs() * nx..][..nx];
                let s0 = if dj < 0 { sy0 } else { 1.0 };
                let px = self.fft.px;
                match ks.get(1) {
                    None => {
                        for di in 0..nx {
                            row[di] = (s0 * src0[di]) as f32;
                        }
                        for di in 1..nx {
                            row[px - di] = (s0 * sx0 * src0[di]) as f32;
                        }
                    }
                    Some(&k1) => {
                        let (q1, (sx1, sy1)) = kernel.quadrant(k1);
                        let src1 = &q1[dj.unsigned_abs() * nx..][..nx];
                        let s1 = if dj < 0 { sy1 } else { 1.0 };
                        for di in 0..nx {
                            row[di] = (s0 * src0[di] + s1 * src1[di]) as f32;
                        }
                        for di in 1..nx {
                            row[px - di] = (s0 * sx0 * src0[di] + s1 * sx1 * src1[di]) as f32;
                        }
                    }
                }
                true
            });
            for (n, &k) in ks.iter().enumerate() {
                let slot = if n == 0 { a } else { pair.unwrap() };
                let dst = &mut spec[slot * rl..(slot + 1) * rl];
                let im = imaginary(k);
                for kx in 0..hx {
                    let col = &work[kx * py..kx * py + hy];
                    for (d, v) in dst[kx * hy..(kx + 1) * hy].iter_mut().zip(col) {
                        *d = if im { v.im } else { v.re };
                    }
                }
            }
        }
    }

    /// The stress field of `pressure` and `traction` (as in [`stress_field`]) on this grid and
    /// these layers.
    pub fn field(&self, pressure: &[f64], traction: Option<&[f64]>) -> StressField {
        let (nx, ny) = (self.nx, self.ny);
        let fft = &self.fft;
        let mut b = fft.buffers();
        let p_hat = fft.field_spectrum(&mut b, pressure);
        let q_hat = traction
            .filter(|q| q.iter().any(|&v| v != 0.0))
            .map(|q| fft.field_spectrum(&mut b, q));
        let plane = ny * nx;
        let z = &self.z;
        let mut components: [Vec<f32>; 6] = std::array::from_fn(|_| vec![0.0f32; z.len() * plane]);
        // one layer per task; each task writes its own slice of every component
        let mut slices: Vec<Vec<&mut [f32]>> =
            (0..z.len()).map(|_| Vec::with_capacity(6)).collect();
        for comp in components.iter_mut() {
            for (k, s) in comp.chunks_mut(plane).enumerate() {
                slices[k].push(s);
            }
        }
        // the slots a recomputed layer needs
        let needed: Vec<usize> = if q_hat.is_some() {
            (0..SLOT_KERNEL.len()).collect()
        } else {
            (0..6).collect()
        };
        let (py, hx, hy, rl) = (fft.py, fft.hx, fft.hy(), fft.reduced_len());
        slices
            .par_iter_mut()
            .zip(z.par_iter().zip(self.cached.par_iter()))
            .for_each_init(
                || {
                    (
                        fft.buffers(),
                        vec![Complex::default(); fft.spectrum_len()],
                        Vec::<f32>::new(),
                    )
                },
                |(b, acc, own), (out, (&depth, cached))| {
                    let spec: &[f32] = match cached {
                        Some(s) => s,
                        None => {
                            own.resize(SLOT_KERNEL.len() * rl, 0.0);
                            self.layer_spectra(depth, &needed, b, acc, own);
                            own
                        }
                    };
                    for (c, dst) in out.iter_mut().enumerate() {
                        let terms =
                            std::iter::once((c, &p_hat)).chain(q_hat.as_ref().map(|q| (6 + c, q)));
                        for (n, (k, hat)) in terms.enumerate() {
                            let ks = &spec[slot_of(k) * rl..(slot_of(k) + 1) * rl];
                            let sy = KERNEL_PARITY[k].1 as f32;
                            multiply(acc, ks, hat, imaginary(k), sy, n == 0, (hx, py, hy));
                        }
                        fft.inverse(b, acc, |j, row| {
                            dst[j * nx..(j + 1) * nx].copy_from_slice(row);
                        });
                    }
                },
            );
        StressField {
            nx,
            ny,
            z: z.to_vec(),
            components,
        }
    }
}

/// acc (=, first; += otherwise) the product of a kernel's reduced spectrum `ks` (real values,
/// times i when `imaginary`; ky beyond py/2 from its mirror py - ky times the y parity `sy`) and
/// a load spectrum `hat`, both [kx][ky].
#[inline]
fn multiply(
    acc: &mut [Complex<f32>],
    ks: &[f32],
    hat: &[Complex<f32>],
    imaginary: bool,
    sy: f32,
    first: bool,
    (hx, py, hy): (usize, usize, usize),
) {
    for kx in 0..hx {
        let k = &ks[kx * hy..(kx + 1) * hy];
        let h = &hat[kx * py..(kx + 1) * py];
        let a = &mut acc[kx * py..(kx + 1) * py];
        let term = |ky: usize| {
            let v = if ky < hy { k[ky] } else { sy * k[py - ky] };
            let h = h[ky];
            if imaginary {
                Complex::new(-v * h.im, v * h.re)
            } else {
                Complex::new(v * h.re, v * h.im)
            }
        };
        if first {
            for (ky, d) in a.iter_mut().enumerate() {
                *d = term(ky);
            }
        } else {
            for (ky, d) in a.iter_mut().enumerate() {
                *d += term(ky);
            }
        }
    }
}

/// The stress field in a half-space of Poisson ratio `nu` below `grid` at the depths `z` (m,
/// each > 0) from the surface pressure `pressure` (Pa, compression positive) and the surface
/// traction `traction` along +x acting on this body (Pa; `None` when there is none), both
/// piecewise constant on the cells. `plane_strain`: the grid is an infinite line contact
/// (ny = 1, loads uniform along y).
///
/// Exact for the piecewise-constant loads (to FFT round-off, ~1e-13 of the load): see
/// [`super::kernel`] for the influence coefficients and their sources. One evaluation: the
/// kernel spectra are formed and dropped layer by layer; a run that evaluates the same grid
/// and layers again keeps them in a [`StressKernels`].
pub fn stress_field(
    grid: &Grid,
    pressure: &[f64],
    traction: Option<&[f64]>,
    nu: f64,
    z: &[f64],
    plane_strain: bool,
) -> StressField {
    StressKernels::new(grid, nu, z, plane_strain, 0).field(pressure, traction)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Smooth but asymmetric loads on a grid (no parity for the FFT to lean on).
    fn loads(grid: &Grid) -> (Vec<f64>, Vec<f64>) {
        let (nx, ny) = (grid.nx, grid.ny);
        let p: Vec<f64> = (0..nx * ny)
            .map(|k| {
                let (x, y) = (grid.x(k % nx), grid.y(k / nx));
                (1.0 - (x - 0.1).powi(2) - 0.7 * y * y).max(0.0).sqrt() * (1.0 + 0.3 * x)
            })
            .collect();
        let q = p
            .iter()
            .enumerate()
            .map(|(k, v)| v * (0.1 + 0.05 * ((k % 7) as f64 - 3.0)))
            .collect();
        (p, q)
    }

    fn largest(f: &StressField) -> f64 {
        f.components
            .iter()
            .flatten()
            .fold(0.0_f64, |m, v| m.max(v.abs() as f64))
    }

    /// The kept spectra give the field of the spectra formed at each evaluation, whatever part
    /// of the layers fits the budget (the same arithmetic: equal to 1e-6 of the largest stress,
    /// in fact bit for bit), with and without a traction, 3D and plane strain.
    #[test]
    fn cached_kernels_equal_the_uncached_path() {
        let z = [0.05, 0.2, 0.45, 0.9];
        for (grid, line) in [
            (Grid::new(40, 30, -1.5, 1.5, -1.2, 1.2), false),
            (Grid::new(64, 1, -2.0, 2.0, -0.5, 0.5), true),
        ] {
            let (p, q) = loads(&grid);
            let per = layer_spectra_bytes(grid.nx, grid.ny);
            for traction in [Some(q.as_slice()), None] {
                let reference = stress_field(&grid, &p, traction, 0.3, &z, line);
                let scale = largest(&reference);
                for budget in [usize::MAX, 2 * per + per / 2, 0] {
                    let kernels = StressKernels::new(&grid, 0.3, &z, line, budget);
                    assert_eq!(kernels.cached_layers(), (budget / per).min(z.len()));
                    assert_eq!(kernels.bytes(), kernels.cached_layers() * per);
                    // twice: the kept spectra are not consumed
                    for _ in 0..2 {
                        let f = kernels.field(&p, traction);
                        for c in 0..6 {
                            for (a, b) in f.components[c].iter().zip(&reference.components[c]) {
                                assert!(
                                    ((a - b).abs() as f64) <= 1e-6 * scale,
                                    "component {c}: {a} vs {b}"
                                );
                            }
                        }
                    }
                }
            }
        }
    }

    /// The FFT field (kernel pairs sharing a transform, reduced spectra, the reciprocity
    /// sigma_zz(tangential) = tau_xz(normal)) against the direct sum over the cells of the
    /// influence tables, to single-precision round-off (1e-6 of the largest stress).
    #[test]
    fn fft_field_is_the_direct_sum() {
        let grid = Grid::new(13, 9, -1.3, 1.3, -0.8, 1.0);
        let (nx, ny) = (grid.nx, grid.ny);
        let (p, q) = loads(&grid);
        let z = [0.03, 0.3, 1.1];
        let f = stress_field(&grid, &p, Some(&q), 0.27, &z, false);
        let scale = largest(&f);
        for (l, &depth) in z.iter().enumerate() {
            let k = LayerKernel::new(nx, ny, grid.dx, grid.dy, depth, 0.27);
            for j in 0..ny {
                for i in 0..nx {
                    let mut s = [0.0; 6];
                    for jj in 0..ny {
                        for ii in 0..nx {
                            let (di, dj) = (i as isize - ii as isize, j as isize - jj as isize);
                            for (c, v) in s.iter_mut().enumerate() {
                                *v += k.get(c, di, dj) * p[jj * nx + ii]
                                    + k.get(6 + c, di, dj) * q[jj * nx + ii];
                            }
                        }
                    }
                    let n = (l * ny + j) * nx + i;
                    for (c, want) in s.iter().enumerate() {
                        let got = f.components[c][n] as f64;
                        assert!(
                            (got - want).abs() < 1e-6 * scale,
                            "c {c} at ({i}, {j}, {l}): {got} vs {want}"
                        );
                    }
                }
            }
        }
    }

    /// Which kernels share a forward transform: every slot once, a real and an imaginary one
    /// in each pair.
    #[test]
    fn pairs_cover_every_slot_once() {
        for slots in [(0..11).collect::<Vec<_>>(), (0..6).collect()] {
            let s = schedule(&slots);
            let mut seen: Vec<usize> = s
                .iter()
                .flat_map(|&(a, b)| std::iter::once(a).chain(b))
                .collect();
            seen.sort();
            assert_eq!(seen, slots);
            for (a, b) in s {
                if let Some(b) = b {
                    assert!(!imaginary(SLOT_KERNEL[a]) && imaginary(SLOT_KERNEL[b]));
                }
            }
        }
        assert_eq!(schedule(&(0..11).collect::<Vec<_>>()).len(), 6);
        assert_eq!(schedule(&(0..6).collect::<Vec<_>>()).len(), 4);
        for k in 0..12 {
            assert_eq!(SLOT_KERNEL[slot_of(k)], if k == 8 { 4 } else { k });
        }
    }
}
