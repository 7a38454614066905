//! Aggregation multigrid with line relaxation for the local part of the linearised Reynolds
//! operator: the preconditioner of the 2D EHL Newton steps.
//!
//! The Newton preconditioner keeps, of the EHL Jacobian, what couples a cell to its
//! neighbourhood: the Poiseuille five-point stencil (along x and y) and the wedge term with the
//! elastic coupling within a band along x. Written row-major (k = j nx + i) that is one banded
//! block per grid line j plus the couplings to the cells directly below and above
//! ([`LineOperator`]). Line solves alone (block Jacobi) miss the y coupling: in the inlet,
//! where eps = rho H^3 / (eta lambda) is large and the equation is a Poisson problem, the
//! error modes smooth in y are then damped only by the outer GMRES, at ~ny iterations.
//!
//! [`LineMultigrid`] solves the operator approximately by one V-cycle:
//!
//! * relaxation: red-black line Gauss-Seidel (even lines, then odd lines, each line solved
//!   exactly by its banded LU; lines of one colour are independent and solved in parallel),
//!   one sweep before the coarse correction and one in reverse order after it, so the cycle is
//!   a fixed linear operator (a valid preconditioner for GMRES, also for the Schur complement
//!   of H0);
//! * coarse grids by aggregation of 2 x 2 cells (piecewise-constant prolongation P, restriction
//!   P^T) with the Galerkin operator A_c = P^T A P, which keeps the line structure: one banded
//!   block per coarse line plus vertical couplings (Vanek, Mandel & Brezina 1996; Notay 2010
//!   for aggregation AMG on convection-diffusion, where it keeps the M-matrix sign pattern of
//!   a first-order upwind term). The EHL wedge term acting through the elastic kernel is not
//!   of that kind, so the caller can restrict the coarse grids to a mask of fine cells (the
//!   EHL preconditioner keeps the Poiseuille-dominated ones);
//! * the coarsest grid (at most [`COARSEST`] cells, or a single line) is solved exactly by a
//!   banded LU of the whole operator (bandwidth nx).
//!
//! Unsmoothed aggregation is a weaker coarse correction than geometric interpolation (it
//! misjudges the smooth-mode eigenvalues of a Laplacian by about a factor 2 per level); the
//! cycle is meant as a preconditioner, and the outer Krylov method absorbs the rest (an
//! over-correction of 1.5, Braess 1995, gave no fewer EHL iterations).

use super::banded::{solve_batch, Banded};
use crate::elastic::operator::min_len;
use rayon::prelude::*;
use std::sync::Mutex;

/// Largest grid solved directly at the bottom of the V-cycle.
pub const COARSEST: usize = 400;

/// A matrix on an `nx x ny` cell grid (k = j nx + i): one banded block per grid line j (the
/// coupling along x) and the coupling of each cell to the cell below (`south`, column k - nx)
/// and above (`north`, column k + nx).
#[derive(Debug, Clone)]
pub struct LineOperator {
    pub nx: usize,
    pub ny: usize,
    /// line blocks A_jj (factored in place by [`LineMultigrid::new`], which keeps A_jj)
    pub lines: Vec<Banded>,
    /// A[k, k - nx] (ignored on the first line)
    pub south: Vec<f64>,
    /// A[k, k + nx] (ignored on the last line)
    pub north: Vec<f64>,
}

impl LineOperator {
    /// r = b - A x.
    pub fn residual(&self, b: &[f64], x: &[f64], r: &mut [f64]) {
        self.residual_on(b, x, r, None);
    }

    /// r = b - A x on the lines j = colour (mod 2) (all lines for None), 0 on the others.
    fn residual_on(&self, b: &[f64], x: &[f64], r: &mut [f64], colour: Option<usize>) {
        let (nx, ny) = (self.nx, self.ny);
        r.par_chunks_mut(nx)
            .with_min_len(min_len(nx))
            .enumerate()
            .for_each(|(j, rj)| {
                if colour.is_some_and(|c| j % 2 != c) {
                    rj.iter_mut().for_each(|v| *v = 0.0);
                    return;
                }
                let o = j * nx;
                rj.copy_from_slice(&b[o..o + nx]);
                self.lines[j].sub_product(&x[o..o + nx], rj);
                for (i, ri) in rj.iter_mut().enumerate() {
                    let k = o + i;
                    if j > 0 {
                        *ri -= self.south[k] * x[k - nx];
                    }
                    if j + 1 < ny {
                        *ri -= self.north[k] * x[k + nx];
                    }
                }
            });
    }

    /// Aggregation factors (x, y) of the next coarser grid.
    fn factors(&self) -> (usize, usize) {
        (
            if self.nx >= 8 { 2 } else { 1 },
            if self.ny >= 2 { 2 } else { 1 },
        )
    }

    /// The Galerkin operator P^T A P for the aggregation `factors()`, P restricted to the cells
    /// with `mask` true (None: all cells); an aggregate without such cells gets an identity row.
    fn coarsen(&self, mask: Option<&[bool]>, spare: Option<LineOperator>) -> LineOperator {
        let on = |k: usize| mask.is_none_or(|m| m[k]);
        let (cx, cy) = self.factors();
        let (nx, ny) = (self.nx, self.ny);
        let (ncx, ncy) = (nx.div_ceil(cx), ny.div_ceil(cy));
        let kl = self.lines[0].kl().div_ceil(cx);
        let ku = self.lines[0].ku().div_ceil(cx);
        let (kl, ku) = (kl.min(ncx.max(1) - 1), ku.min(ncx.max(1) - 1));
        let mut op = LineOperator::zero(ncx, ncy, kl, ku, spare);
        op.lines
            .par_iter_mut()
            .zip(op.south.par_chunks_mut(ncx))
            .zip(op.north.par_chunks_mut(ncx))
            .enumerate()
            .for_each(|(jc, ((m, south), north))| {
                let mut used = vec![false; ncx];
                for j in cy * jc..(cy * jc + cy).min(ny) {
                    let line = &self.lines[j];
                    for i in 0..nx {
                        let k = j * nx + i;
                        if !on(k) {
                            continue;
                        }
                        let ic = i / cx;
                        used[ic] = true;
                        let lo = i.saturating_sub(line.kl());
                        let hi = (i + line.ku()).min(nx - 1);
                        for l in lo..=hi {
                            let v = line.get(i, l);
                            if v != 0.0 && on(j * nx + l) {
                                m.add(ic, l / cx, v);
                            }
                        }
                        if j > 0 && on(k - nx) {
                            if (j - 1) / cy == jc {
                                m.add(ic, ic, self.south[k]);
                            } else {
                                south[ic] += self.south[k];
                            }
                        }
                        if j + 1 < ny && on(k + nx) {
                            if (j + 1) / cy == jc {
                                m.add(ic, ic, self.north[k]);
                            } else {
                                north[ic] += self.north[k];
                            }
                        }
                    }
                }
                for (ic, &u) in used.iter().enumerate() {
                    if !u {
                        m.add(ic, ic, 1.0);
                    }
                }
            });
        op
    }

    /// The zero operator on `nx x ny` cells with line blocks of `kl + ku + 1` diagonals, in the
    /// storage of `spare` when its shape matches (no allocation in a Newton iteration).
    pub fn zero(nx: usize, ny: usize, kl: usize, ku: usize, spare: Option<LineOperator>) -> Self {
        match spare {
            Some(mut op)
                if op.nx == nx
                    && op.ny == ny
                    && op
                        .lines
                        .first()
                        .is_some_and(|m| m.kl() == kl && m.ku() == ku) =>
            {
                op.lines.par_iter_mut().for_each(|m| m.clear());
                op.south.iter_mut().for_each(|v| *v = 0.0);
                op.north.iter_mut().for_each(|v| *v = 0.0);
                op
            }
            _ => LineOperator {
                nx,
                ny,
                lines: (0..ny).map(|_| Banded::new(nx, kl, ku)).collect(),
                south: vec![0.0; nx * ny],
                north: vec![0.0; nx * ny],
            },
        }
    }

    /// The whole operator as one banded matrix (bandwidth nx), factored; None if singular.
    fn factor_whole(&self) -> Option<Banded> {
        let (nx, ny) = (self.nx, self.ny);
        let n = nx * ny;
        let kl = if ny > 1 { nx } else { self.lines[0].kl() };
        let ku = if ny > 1 { nx } else { self.lines[0].ku() };
        let mut m = Banded::new(n, kl.min(n - 1), ku.min(n - 1));
        for (j, line) in self.lines.iter().enumerate() {
            let o = j * nx;
            for i in 0..nx {
                let lo = i.saturating_sub(line.kl());
                let hi = (i + line.ku()).min(nx - 1);
                for l in lo..=hi {
                    m.add(o + i, o + l, line.get(i, l));
                }
                if j > 0 {
                    m.add(o + i, o + i - nx, self.south[o + i]);
                }
                if j + 1 < ny {
                    m.add(o + i, o + i + nx, self.north[o + i]);
                }
            }
        }
        m.factor().then_some(m)
    }
}

/// One grid of the hierarchy: the operator (its line blocks factored) and the work vectors of
/// a cycle (kept to avoid allocating a few MB per application).
struct Level {
    op: LineOperator,
    /// (residual / line right-hand sides, coarse residual, coarse correction)
    work: Mutex<(Vec<f64>, Vec<f64>, Vec<f64>)>,
}

/// One V-cycle of line-relaxation aggregation multigrid for a [`LineOperator`] (see the module
/// documentation).
pub struct LineMultigrid {
    levels: Vec<Level>,
    /// factored whole operator of the last level
    bottom: Banded,
    /// fine-grid cells the coarse correction acts on (None: all)
    mask: Option<Vec<bool>>,
}

impl LineMultigrid {
    /// Build the hierarchy; None if a line block or the coarsest operator is singular. The
    /// coarse grids see only the fine cells where `mask` is true (None: all).
    pub fn new(op: LineOperator, mask: Option<Vec<bool>>) -> Option<LineMultigrid> {
        Self::reusing(op, mask, Vec::new())
    }

    /// [`LineMultigrid::new`] with the coarse operators built in the storage of `spare` (the
    /// coarse levels of an earlier hierarchy, see [`LineMultigrid::into_operators`]).
    pub fn reusing(
        op: LineOperator,
        mask: Option<Vec<bool>>,
        spare: Vec<LineOperator>,
    ) -> Option<LineMultigrid> {
        let mut spare = spare.into_iter();
        let mut levels = Vec::new();
        let mut op = op;
        loop {
            let last = op.nx * op.ny <= COARSEST || op.ny == 1 || op.factors() == (1, 1);
            if last {
                let bottom = op.factor_whole()?;
                return Some(LineMultigrid {
                    levels,
                    bottom,
                    mask,
                });
            }
            let coarse = op.coarsen(
                if levels.is_empty() {
                    mask.as_deref()
                } else {
                    None
                },
                spare.next(),
            );
            if !op.lines.par_iter_mut().all(|m| m.factor()) {
                return None;
            }
            let nc = coarse.nx * coarse.ny;
            let work = Mutex::new((vec![0.0; op.nx * op.ny], vec![0.0; nc], vec![0.0; nc]));
            levels.push(Level { op, work });
            op = coarse;
        }
    }

    /// The operators of all levels but the coarsest, finest first (their storage can be
    /// reused for the next hierarchy).
    pub fn into_operators(self) -> Vec<LineOperator> {
        self.levels.into_iter().map(|l| l.op).collect()
    }

    /// Number of grids (including the coarsest).
    pub fn depth(&self) -> usize {
        self.levels.len() + 1
    }

    /// x = M^-1 b: one V-cycle from x = 0.
    pub fn apply(&self, b: &[f64], x: &mut [f64]) {
        self.cycle(0, b, x);
    }

    fn cycle(&self, l: usize, b: &[f64], x: &mut [f64]) {
        let Some(level) = self.levels.get(l) else {
            x.copy_from_slice(b);
            self.bottom.solve(x);
            return;
        };
        let op = &level.op;
        let (nx, ny) = (op.nx, op.ny);
        x.iter_mut().for_each(|v| *v = 0.0);
        let mut guard = level.work.lock().unwrap_or_else(|e| e.into_inner());
        let (t, rc, xc) = &mut *guard;
        self.half_sweep(level, b, x, t, 0);
        self.half_sweep(level, b, x, t, 1);
        // coarse-grid correction; the lines solved last (odd) satisfy their equations exactly
        op.residual_on(b, x, t, Some(0));
        let (cx, cy) = op.factors();
        let ncx = nx.div_ceil(cx);
        let mask = if l == 0 { self.mask.as_deref() } else { None };
        let on = |k: usize| mask.is_none_or(|m| m[k]);
        // restriction: each coarse row sums its fine rows (in the same order as one serial
        // pass, so the result does not depend on the threads)
        rc.par_chunks_mut(ncx)
            .with_min_len(min_len(nx * cy))
            .enumerate()
            .for_each(|(jc, row)| {
                row.iter_mut().for_each(|v| *v = 0.0);
                for j in jc * cy..((jc + 1) * cy).min(ny) {
                    for i in 0..nx {
                        if on(j * nx + i) {
                            row[i / cx] += t[j * nx + i];
                        }
                    }
                }
            });
        self.cycle(l + 1, rc, xc);
        x.par_chunks_mut(nx)
            .with_min_len(min_len(nx))
            .enumerate()
            .for_each(|(j, xj)| {
                let row = &xc[(j / cy) * ncx..(j / cy + 1) * ncx];
                for (i, v) in xj.iter_mut().enumerate() {
                    if on(j * nx + i) {
                        *v += row[i / cx];
                    }
                }
            });
        self.half_sweep(level, b, x, t, 1);
        self.half_sweep(level, b, x, t, 0);
    }

    /// Line Gauss-Seidel on the lines j = colour (mod 2): x_j = A_jj^-1 (b_j - S x_j-1 - N x_j+1).
    fn half_sweep(&self, level: &Level, b: &[f64], x: &mut [f64], t: &mut [f64], colour: usize) {
        let op = &level.op;
        let (nx, ny) = (op.nx, op.ny);
        {
            let xs: &[f64] = x;
            t.par_chunks_mut(nx)
                .with_min_len(min_len(nx))
                .enumerate()
                .filter(|(j, _)| j % 2 == colour)
                .for_each(|(j, tj)| {
                    let o = j * nx;
                    for (i, v) in tj.iter_mut().enumerate() {
                        let k = o + i;
                        let mut s = b[k];
                        if j > 0 {
                            s -= op.south[k] * xs[k - nx];
                        }
                        if j + 1 < ny {
                            s -= op.north[k] * xs[k + nx];
                        }
                        *v = s;
                    }
                });
        }
        // the line solves, four lines of the colour at a time (8 grid lines of memory)
        t.par_chunks_mut(BATCH * 2 * nx)
            .with_min_len(min_len(BATCH * 2 * nx))
            .enumerate()
            .for_each(|(g, chunk)| {
                let j0 = g * BATCH * 2;
                let mut rows: Vec<(usize, &mut [f64])> = chunk
                    .chunks_mut(nx)
                    .enumerate()
                    .filter(|(d, _)| (j0 + d) % 2 == colour)
                    .map(|(d, r)| (j0 + d, r))
                    .collect();
                if rows.len() == BATCH {
                    let f = &level.op.lines;
                    let mut it = rows.iter_mut();
                    let mut next = || it.next().map(|(j, r)| (*j, &mut **r));
                    let (a, b, c, d) = (next(), next(), next(), next());
                    if let (Some(a), Some(b), Some(c), Some(d)) = (a, b, c, d) {
                        solve_batch([&f[a.0], &f[b.0], &f[c.0], &f[d.0]], [a.1, b.1, c.1, d.1]);
                    }
                } else {
                    for (j, r) in rows {
                        level.op.lines[j].solve(r);
                    }
                }
            });
        x.par_chunks_mut(nx)
            .zip(t.par_chunks(nx))
            .with_min_len(min_len(nx))
            .enumerate()
            .filter(|(j, _)| j % 2 == colour)
            .for_each(|(_, (xj, tj))| xj.copy_from_slice(tj));
    }
}

/// Lines solved together by [`solve_batch`].
const BATCH: usize = 4;

#[cfg(test)]
mod tests {
    use super::*;

    /// An anisotropic convection-diffusion operator on nx x ny cells (the structure of the
    /// Reynolds rows: Poiseuille five-point stencil plus a first-order upwind x derivative).
    fn model(nx: usize, ny: usize, ay: f64, conv: f64) -> LineOperator {
        let mut lines = Vec::new();
        for _ in 0..ny {
            let mut m = Banded::new(nx, 1, 1);
            for i in 0..nx {
                m.add(i, i, 2.0 + 2.0 * ay + conv);
                if i > 0 {
                    m.add(i, i - 1, -1.0 - conv);
                }
                if i + 1 < nx {
                    m.add(i, i + 1, -1.0);
                }
            }
            lines.push(m);
        }
        LineOperator {
            nx,
            ny,
            lines,
            south: vec![-ay; nx * ny],
            north: vec![-ay; nx * ny],
        }
    }

    /// A[k, m] of a line operator as a dense matrix.
    fn entry(op: &LineOperator, k: usize, m: usize) -> f64 {
        let nx = op.nx;
        let (i, j, l, jm) = (k % nx, k / nx, m % nx, m / nx);
        if j == jm {
            op.lines[j].get(i, l)
        } else if jm + 1 == j && i == l {
            op.south[k]
        } else if jm == j + 1 && i == l {
            op.north[k]
        } else {
            0.0
        }
    }

    /// The coarse operator is P^T A P: checked against the product formed entry by entry with
    /// the dense matrices (exact to round-off), on odd sizes so partial aggregates occur.
    #[test]
    fn galerkin_coarse_operator() {
        let op = model(9, 5, 0.3, 0.7);
        let c = op.coarsen(None, None);
        let (nx, ny, ncx) = (op.nx, op.ny, c.nx);
        let n = nx * ny;
        let agg = |k: usize| (k / nx / 2) * ncx + (k % nx) / 2;
        let nc = c.nx * c.ny;
        let mut ac = vec![0.0; nc * nc];
        for k in 0..n {
            for m in 0..n {
                ac[agg(k) * nc + agg(m)] += entry(&op, k, m);
            }
        }
        for kc in 0..nc {
            for mc in 0..nc {
                let got = entry(&c, kc, mc);
                assert!((got - ac[kc * nc + mc]).abs() < 1e-12, "({kc}, {mc})");
            }
        }
    }

    /// As a preconditioner of GMRES on a 128 x 128 anisotropic convection-diffusion problem the
    /// V-cycle needs a small iteration count that hardly grows with the grid, where line
    /// relaxation alone (one level) needs several times more.
    #[test]
    fn vcycle_preconditions_independently_of_grid() {
        let count = |nx: usize, multilevel: bool| {
            let op = model(nx, nx, 0.3, 0.5);
            let b: Vec<f64> = (0..nx * nx)
                .map(|k| ((k * 7919) % 13) as f64 - 6.0)
                .collect();
            let mg = LineMultigrid::new(op.clone(), None).unwrap();
            // halving down to at most COARSEST cells: 64^2 -> 32^2 -> 16^2, one grid more per
            // doubling
            assert_eq!(mg.depth(), 3 + (nx / 64).ilog2() as usize);
            let lines = {
                let mut f = op.lines.clone();
                f.iter_mut().for_each(|m| assert!(m.factor()));
                f
            };
            let mut x = vec![0.0; b.len()];
            let out = crate::linalg::gmres::gmres(
                &mut crate::linalg::gmres::GmresWork::default(),
                &b,
                &mut x,
                60,
                600,
                1e-8,
                &mut |v, o| {
                    let z = vec![0.0; v.len()];
                    op.residual(&z, v, o);
                    o.iter_mut().for_each(|e| *e = -*e);
                },
                &mut |r, z| {
                    if multilevel {
                        mg.apply(r, z)
                    } else {
                        z.copy_from_slice(r);
                        z.chunks_mut(nx).zip(&lines).for_each(|(s, m)| m.solve(s));
                    }
                },
            );
            assert!(out.relative_residual <= 1e-8, "{out:?}");
            out.iterations
        };
        let (m64, m128) = (count(64, true), count(128, true));
        let l128 = count(128, false);
        assert!(m128 <= 25 && m128 <= m64 + 6, "{m64} {m128}");
        assert!(l128 >= 3 * m128, "lines {l128}, multigrid {m128}");
    }
}
