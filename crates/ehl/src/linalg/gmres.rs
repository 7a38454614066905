//! Restarted flexible GMRES with right preconditioning (Saad, *Iterative Methods for Sparse
//! Linear Systems*, 2nd ed., alg. 9.6 (FGMRES); Saad 1993), for the Newton steps of the EHL
//! solver.
//!
//! Solves A x = b from x = 0 with A and M^-1 given as closures; minimises ||b - A x||_2 over
//! x in span{z_1 .. z_m}, z_j = M^-1 v_j, restarting every `restart` iterations. The z_j are
//! stored, so M^-1 may change from one application to the next (an inner iterative solve, as in
//! the coarse-grid correction of the EHL preconditioner); with a fixed M^-1 this is plain
//! right-preconditioned GMRES. Right preconditioning keeps the true residual norm (the one the
//! Newton line search sees) as the stopping measure. From the second cycle on, the last three
//! slots of a cycle hold the corrections of the previous cycles (LGMRES, Baker, Jessup &
//! Manteuffel 2005), which the flexible form allows at no extra storage.

use rayon::prelude::*;

/// What a GMRES solve achieved.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GmresOutcome {
    /// Krylov iterations (matrix-vector products, excluding the restart residuals)
    pub iterations: usize,
    /// matrix-vector products in all (iterations + restart residuals)
    pub products: usize,
    /// ||b - A x|| / ||b|| reached (as estimated by the Arnoldi recurrence)
    pub relative_residual: f64,
}

/// Work vectors of [`gmres`]: the Krylov basis and the preconditioned directions, kept
/// between calls so that a Newton iteration does not allocate (and page in) some hundred
/// vectors per step. They are allocated on first use, as many as the iterations need.
#[derive(Debug, Default)]
pub struct GmresWork {
    v: Vec<Vec<f64>>,
    zs: Vec<Vec<f64>>,
}

impl GmresWork {
    fn ensure(&mut self, n: usize, k: usize) {
        for list in [&mut self.v, &mut self.zs] {
            if list.first().is_some_and(|x| x.len() != n) {
                list.clear();
            }
            while list.len() <= k {
                list.push(vec![0.0; n]);
            }
        }
    }
}

/// Solve A x = b; `x` is overwritten (starts from zero). Stops at `||r|| <= rtol ||b||` or after
/// `max_iter` iterations. A breakdown or a non-finite value ends the solve with the best x so far.
/// `work` holds the Krylov vectors between calls (`GmresWork::default()` for a single solve).
#[allow(clippy::too_many_arguments)]
pub fn gmres(
    work: &mut GmresWork,
    b: &[f64],
    x: &mut [f64],
    restart: usize,
    max_iter: usize,
    rtol: f64,
    matvec: &mut dyn FnMut(&[f64], &mut [f64]),
    precond: &mut dyn FnMut(&[f64], &mut [f64]),
) -> GmresOutcome {
    let n = b.len();
    let m = restart.max(1);
    x.iter_mut().for_each(|v| *v = 0.0);
    let bnorm = norm(b);
    let mut out = GmresOutcome {
        iterations: 0,
        products: 0,
        relative_residual: 1.0,
    };
    if bnorm == 0.0 || !bnorm.is_finite() {
        out.relative_residual = if bnorm == 0.0 { 0.0 } else { f64::INFINITY };
        return out;
    }
    work.ensure(n, 0);
    let mut h = vec![vec![0.0; m]; m + 1]; // h[i][j]
    let (mut cs, mut sn, mut g) = (vec![0.0; m], vec![0.0; m], vec![0.0; m + 1]);
    let mut w = vec![0.0; n];
    let mut r = b.to_vec();
    let mut first = true;
    // LGMRES augmentation (Baker, Jessup & Manteuffel, SIAM J. Matrix Anal. Appl. 26 (2005)
    // 962-984): the corrections of the last cycles, normalised, fill the last slots of the
    // next cycle's search space, so a restart does not throw away the slow directions
    let mut aug: Vec<Vec<f64>> = Vec::new();
    let n_aug = if m > 8 { 3 } else { 0 };
    let mut dx = vec![0.0; n];
    loop {
        if !first {
            matvec(x, &mut w);
            out.products += 1;
            for i in 0..n {
                r[i] = b[i] - w[i];
            }
        }
        first = false;
        let beta = norm(&r);
        out.relative_residual = beta / bnorm;
        if !beta.is_finite() || beta <= rtol * bnorm || out.iterations >= max_iter {
            return out;
        }
        for (vi, ri) in work.v[0].iter_mut().zip(&r) {
            *vi = ri / beta;
        }
        g.iter_mut().for_each(|e| *e = 0.0);
        g[0] = beta;
        let mut k = 0;
        while k < m && out.iterations < max_iter {
            work.ensure(n, k + 1);
            let (v, zs) = (&mut work.v, &mut work.zs);
            let slot = m - aug.len();
            if k >= slot {
                zs[k].copy_from_slice(&aug[k - slot]);
            } else {
                precond(&v[k], &mut zs[k]);
            }
            matvec(&zs[k], &mut w);
            out.products += 1;
            out.iterations += 1;
            // modified Gram-Schmidt
            for i in 0..=k {
                let hij = dot(&w, &v[i]);
                h[i][k] = hij;
                axpy(&mut w, -hij, &v[i]);
            }
            let hn = norm(&w);
            h[k + 1][k] = hn;
            if !hn.is_finite() || h[..=k].iter().any(|row| !row[k].is_finite()) {
                // a non-finite product: keep what was built before it
                break;
            }
            for i in 0..k {
                let t = cs[i] * h[i][k] + sn[i] * h[i + 1][k];
                h[i + 1][k] = -sn[i] * h[i][k] + cs[i] * h[i + 1][k];
                h[i][k] = t;
            }
            let d = (h[k][k] * h[k][k] + hn * hn).sqrt();
            if d == 0.0 {
                break;
            }
            cs[k] = h[k][k] / d;
            sn[k] = hn / d;
            h[k][k] = d;
            h[k + 1][k] = 0.0;
            g[k + 1] = -sn[k] * g[k];
            g[k] *= cs[k];
            k += 1;
            let happy = hn <= 1e-14 * d;
            if g[k].abs() <= rtol * bnorm || happy {
                break;
            }
            for (vl, wl) in v[k].iter_mut().zip(&w) {
                *vl = wl / hn;
            }
        }
        if k == 0 {
            return out;
        }
        // y = H^-1 g (upper triangular k x k), x += Z y
        let mut y = vec![0.0; k];
        for i in (0..k).rev() {
            let mut s = g[i];
            for j in i + 1..k {
                s -= h[i][j] * y[j];
            }
            y[i] = s / h[i][i];
        }
        dx.iter_mut().for_each(|e| *e = 0.0);
        for (j, yj) in y.iter().enumerate() {
            axpy(&mut dx, *yj, &work.zs[j]);
        }
        for (xl, dl) in x.iter_mut().zip(&dx) {
            *xl += dl;
        }
        let dn = norm(&dx);
        if n_aug > 0 && dn > 0.0 && dn.is_finite() {
            let mut a = if aug.len() == n_aug {
                aug.pop().unwrap_or_default()
            } else {
                vec![0.0; n]
            };
            for (al, dl) in a.iter_mut().zip(&dx) {
                *al = dl / dn;
            }
            aug.insert(0, a);
        }
        out.relative_residual = g[k].abs() / bnorm;
        if out.relative_residual <= rtol || out.iterations >= max_iter {
            return out;
        }
    }
}

/// Vectors at least this long are split over the rayon pool in [`dot`] and the Gram-Schmidt
/// updates (shorter ones cost more to schedule than to compute).
const PARALLEL: usize = 1 << 15;
/// Chunk length of the parallel vector operations.
const CHUNK: usize = 1 << 13;

/// a . b. Long vectors are summed in fixed chunks, in parallel, and the chunk sums added in
/// order, so the result does not depend on the thread schedule.
pub(crate) fn dot(a: &[f64], b: &[f64]) -> f64 {
    let serial = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    if a.len() < PARALLEL {
        return serial(a, b);
    }
    let parts: Vec<f64> = a
        .par_chunks(CHUNK)
        .zip(b.par_chunks(CHUNK))
        .map(|(x, y)| serial(x, y))
        .collect();
    parts.iter().sum()
}

/// y += s x.
fn axpy(y: &mut [f64], s: f64, x: &[f64]) {
    if y.len() < PARALLEL {
        y.iter_mut().zip(x).for_each(|(a, b)| *a += s * b);
    } else {
        y.par_chunks_mut(CHUNK)
            .zip(x.par_chunks(CHUNK))
            .for_each(|(ys, xs)| ys.iter_mut().zip(xs).for_each(|(a, b)| *a += s * b));
    }
}

#[inline]
pub(crate) fn norm(a: &[f64]) -> f64 {
    dot(a, a).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A non-symmetric convection-diffusion matrix (1D, 60 unknowns): GMRES reaches the requested
    /// relative residual, and the true residual of the returned x agrees with the estimate.
    /// With an exact preconditioner (the matrix inverse via its tridiagonal solve) it converges
    /// in one iteration.
    #[test]
    fn converges_and_exact_preconditioner_is_one_step() {
        let n = 60;
        let (lo, di, up) = (-1.3, 2.5, -0.9);
        let apply = |x: &[f64], out: &mut [f64]| {
            for i in 0..x.len() {
                let mut s = di * x[i];
                if i > 0 {
                    s += lo * x[i - 1];
                }
                if i + 1 < x.len() {
                    s += up * x[i + 1];
                }
                out[i] = s;
            }
        };
        let b: Vec<f64> = (0..n).map(|i| ((i * 7) % 11) as f64 - 5.0).collect();
        let mut x = vec![0.0; n];
        let o = gmres(
            &mut GmresWork::default(),
            &b,
            &mut x,
            10,
            500,
            1e-10,
            &mut |v, o| apply(v, o),
            &mut |r, z| z.copy_from_slice(r),
        );
        let mut ax = vec![0.0; n];
        apply(&x, &mut ax);
        let true_res = norm(&ax.iter().zip(&b).map(|(a, b)| a - b).collect::<Vec<_>>()) / norm(&b);
        assert!(
            o.relative_residual <= 1e-10 && true_res < 1e-9,
            "{o:?} {true_res}"
        );
        // exact preconditioner: Thomas algorithm
        let thomas = |r: &[f64], z: &mut [f64]| {
            let mut c = vec![0.0; n];
            let mut d = vec![0.0; n];
            for i in 0..n {
                let den = di - if i > 0 { lo * c[i - 1] } else { 0.0 };
                c[i] = up / den;
                d[i] = (r[i] - if i > 0 { lo * d[i - 1] } else { 0.0 }) / den;
            }
            for i in (0..n).rev() {
                z[i] = d[i] - if i + 1 < n { c[i] * z[i + 1] } else { 0.0 };
            }
        };
        let o = gmres(
            &mut GmresWork::default(),
            &b,
            &mut x,
            10,
            500,
            1e-10,
            &mut |v, o| apply(v, o),
            &mut |r, z| thomas(r, z),
        );
        assert_eq!(o.iterations, 1, "{o:?}");
    }
}
