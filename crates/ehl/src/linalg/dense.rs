//! Dense LU factorisation with partial pivoting: the fallback preconditioner of a transient
//! infinite line contact, whose Jacobian is dense (the elastic log kernel couples every pair of
//! cells; its usual form is [`super::hodlr`]), and [`SmallLu`], kept double-precision factors
//! of small systems.
//!
//! Right-looking blocked LU, the scheme of LAPACK `dgetrf` (Golub & Van Loan, *Matrix
//! Computations*, 4th ed., alg. 3.4.2 with the block update of sec. 3.2.9): for each panel of
//! `BLOCK` columns, an unblocked factorisation of the panel with partial pivoting (whole rows
//! interchanged), the triangular solve for the block row of U, and the trailing update
//! A22 -= L21 U12 as a matrix product (`matrixmultiply::dgemm`, split over the rayon pool by
//! rows). Row-major storage, L unit lower triangular and U in place. Factorisation costs
//! 2 n^3 / 3 flops (2048 unknowns: 5.7 Gflop), a solve 2 n^2.

use rayon::prelude::*;

/// Panel width of the blocked factorisation.
const BLOCK: usize = 64;

/// The LU factors P A = L U of a dense n x n matrix.
#[derive(Debug, Clone)]
pub struct DenseLu {
    n: usize,
    /// row-major, L below the diagonal (unit diagonal implied), U on and above it; rounded to
    /// single precision for the solves (see [`DenseLu::solve`])
    lu: Vec<f32>,
    /// row interchanges in order: row k was swapped with row piv[k] >= k
    piv: Vec<usize>,
    /// 1 / U[k][k]
    inv_diag: Vec<f64>,
}

impl DenseLu {
    /// Factor the row-major `n x n` matrix `a` (consumed: the factors overwrite it). None if
    /// a pivot is zero or not finite.
    pub fn factor(mut a: Vec<f64>, n: usize) -> Option<DenseLu> {
        assert_eq!(a.len(), n * n);
        let mut piv = vec![0; n];
        let mut k0 = 0;
        while k0 < n {
            let kb = BLOCK.min(n - k0);
            let k1 = k0 + kb;
            // panel: columns k0..k1, rows k0..n, unblocked right-looking with whole-row swaps
            for j in k0..k1 {
                let mut p = j;
                let mut best = a[j * n + j].abs();
                for i in j + 1..n {
                    let v = a[i * n + j].abs();
                    if v > best {
                        best = v;
                        p = i;
                    }
                }
                if best == 0.0 || !best.is_finite() {
                    return None;
                }
                piv[j] = p;
                if p != j {
                    let (top, bot) = a.split_at_mut(p * n);
                    top[j * n..(j + 1) * n].swap_with_slice(&mut bot[..n]);
                }
                let d = 1.0 / a[j * n + j];
                let (top, bot) = a.split_at_mut((j + 1) * n);
                let pivot_row = &top[j * n + j + 1..j * n + k1];
                for row in bot.chunks_exact_mut(n) {
                    let l = row[j] * d;
                    row[j] = l;
                    if l != 0.0 {
                        for (x, &u) in row[j + 1..k1].iter_mut().zip(pivot_row) {
                            *x -= l * u;
                        }
                    }
                }
            }
            if k1 < n {
                // U12 = L11^-1 A12 (rows k0..k1, columns k1..n)
                for j in k0..k1 {
                    let (top, bot) = a.split_at_mut((j + 1) * n);
                    let urow = &top[j * n + k1..(j + 1) * n];
                    for row in bot[..(k1 - j - 1) * n].chunks_exact_mut(n) {
                        let l = row[j];
                        if l != 0.0 {
                            for (x, &u) in row[k1..].iter_mut().zip(urow) {
                                *x -= l * u;
                            }
                        }
                    }
                }
                // A22 -= L21 U12
                let (top, bot) = a.split_at_mut(k1 * n);
                let u12 = &top[k0 * n..];
                let m = n - k1;
                let rows_per = m.div_ceil(rayon::current_num_threads().max(1)).max(BLOCK);
                bot.par_chunks_mut(rows_per * n).for_each(|c| {
                    let rows = c.len() / n;
                    let ptr = c.as_mut_ptr();
                    // SAFETY: within this chunk of whole rows, L21 (columns k0..k1) is only read
                    // and A22 (columns k1..n) only written: disjoint elements of one allocation;
                    // U12 lies in the rows above, borrowed shared. Strides are the row length n.
                    unsafe {
                        matrixmultiply::dgemm(
                            rows,
                            kb,
                            m,
                            -1.0,
                            ptr.add(k0) as *const f64,
                            n as isize,
                            1,
                            u12.as_ptr().add(k1),
                            n as isize,
                            1,
                            1.0,
                            ptr.add(k1),
                            n as isize,
                            1,
                        );
                    }
                });
            }
            k0 = k1;
        }
        let inv_diag: Vec<f64> = (0..n).map(|k| 1.0 / a[k * n + k]).collect();
        if inv_diag.iter().any(|v| !v.is_finite()) {
            return None;
        }
        Some(DenseLu {
            n,
            lu: a.iter().map(|&v| v as f32).collect(),
            piv,
            inv_diag,
        })
    }

    /// Order of the matrix.
    pub fn n(&self) -> usize {
        self.n
    }

    /// x ~ A^-1 b (in place: `x` holds b on entry), with the factors rounded to single
    /// precision and the sums in double: the solve of a preconditioner, memory-bound (n^2
    /// factor entries read once per solve: at n = 2049, 16 MB in f32 stay in a 32 MB L3 where
    /// 32 MB in f64 did not; measured 6.9 ms per solve in f64, serial). The residual of the
    /// solve is ~1e-7 cond(A) relative. Blocks of `SOLVE_BLOCK` rows: their product with the
    /// part already solved is split over the rayon pool, the triangle within a block is serial.
    pub fn solve(&self, x: &mut [f64]) {
        let n = self.n;
        assert_eq!(x.len(), n);
        for (k, &p) in self.piv.iter().enumerate() {
            x.swap(k, p);
        }
        let lu = &self.lu[..];
        let mut t = vec![0.0; SOLVE_BLOCK];
        // L y = P b (unit lower)
        let mut r0 = 0;
        while r0 < n {
            let r1 = (r0 + SOLVE_BLOCK).min(n);
            if r0 > 0 {
                let done = &x[..r0];
                t[..r1 - r0]
                    .par_iter_mut()
                    .with_min_len(SOLVE_BLOCK / 2)
                    .enumerate()
                    .for_each(|(o, v)| {
                        let i = r0 + o;
                        *v = dot(&lu[i * n..i * n + r0], done);
                    });
            }
            for i in r0..r1 {
                let s = if r0 > 0 { t[i - r0] } else { 0.0 };
                x[i] -= s + dot(&lu[i * n + r0..i * n + i], &x[r0..i]);
            }
            r0 = r1;
        }
        // U x = y, blocks from the bottom
        let mut r1 = n;
        while r1 > 0 {
            let r0 = r1.saturating_sub(SOLVE_BLOCK);
            if r1 < n {
                let done = &x[r1..];
                t[..r1 - r0]
                    .par_iter_mut()
                    .with_min_len(SOLVE_BLOCK / 2)
                    .enumerate()
                    .for_each(|(o, v)| {
                        let i = r0 + o;
                        *v = dot(&lu[i * n + r1..(i + 1) * n], done);
                    });
            }
            for i in (r0..r1).rev() {
                let s = if r1 < n { t[i - r0] } else { 0.0 };
                let s = s + dot(&lu[i * n + i + 1..i * n + r1], &x[i + 1..r1]);
                x[i] = (x[i] - s) * self.inv_diag[i];
            }
            r1 = r0;
        }
    }
}

/// Rows per block of [`DenseLu::solve`].
const SOLVE_BLOCK: usize = 256;

/// a . b (a in single precision, rounded up to double) with eight independent partial sums in
/// a fixed order (the result does not depend on the machine's threads or instruction set). The
/// portable build targets SSE2; where the CPU has AVX2, the same code compiled for it (runtime
/// detection) runs ~2x faster on the memory-bound solves.
#[inline]
fn dot(a: &[f32], b: &[f64]) -> f64 {
    #[cfg(target_arch = "x86_64")]
    {
        if std::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU supports AVX2 (checked just above)
            return unsafe { dot_avx2(a, b) };
        }
    }
    dot_portable(a, b)
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn dot_avx2(a: &[f32], b: &[f64]) -> f64 {
    dot_portable(a, b)
}

#[inline(always)]
fn dot_portable(a: &[f32], b: &[f64]) -> f64 {
    let mut s = [0.0; 8];
    let (ca, cb) = (a.chunks_exact(8), b.chunks_exact(8));
    let (ra, rb) = (ca.remainder(), cb.remainder());
    for (x, y) in ca.zip(cb) {
        for l in 0..8 {
            s[l] += x[l] as f64 * y[l];
        }
    }
    let mut t = ((s[0] + s[1]) + (s[2] + s[3])) + ((s[4] + s[5]) + (s[6] + s[7]));
    for (x, y) in ra.iter().zip(rb) {
        t += *x as f64 * y;
    }
    t
}

/// Dense LU factors P A = L U with partial pivoting in double precision, kept for repeated
/// solves of small systems: the leaves and coupling systems of [`super::hodlr`], and (through
/// [`solve_small`]) the few-unknown least-squares systems of Anderson mixing
/// ([`super::anderson`]), where [`DenseLu`]'s single-precision factors would be too coarse and
/// its blocking pointless. (The film's Newton step across z, which used it too, is now solved
/// in O(n): `thermal::film::newton_step`.) Row-major; the
/// multipliers of L are stored below the diagonal of the whole-row-swapped matrix (as LAPACK's
/// `dgetf2`).
#[derive(Debug, Clone)]
pub struct SmallLu {
    n: usize,
    lu: Vec<f64>,
    piv: Vec<usize>,
}

impl SmallLu {
    /// Factor the row-major `n x n` matrix `a` (consumed); None if a pivot is zero or not
    /// finite.
    pub fn factor(mut a: Vec<f64>, n: usize) -> Option<SmallLu> {
        let mut piv = vec![0; n];
        factor_in_place(&mut a, n, &mut piv).then_some(SmallLu { n, lu: a, piv })
    }

    /// x = A^-1 b (in place: `x` holds b on entry).
    pub fn solve(&self, x: &mut [f64]) {
        solve_factored(&self.lu, self.n, &self.piv, x);
    }
}

/// [`SmallLu`]'s factorisation in place, into caller-owned storage (for many small systems in
/// a loop, without an allocation each): the row-major `n x n` matrix `a` becomes its factors
/// and `piv` (n values) the row swaps; false if a pivot is zero or not finite (`a` and `piv`
/// then hold a partial factorisation, not to be used).
pub fn factor_small(a: &mut [f64], n: usize, piv: &mut [usize]) -> bool {
    factor_in_place(a, n, piv)
}

/// x = A^-1 b with the factors of [`factor_small`] (in place: `x` holds b on entry).
pub fn solve_factored_small(lu: &[f64], n: usize, piv: &[usize], x: &mut [f64]) {
    solve_factored(lu, n, piv, x)
}

fn factor_in_place(a: &mut [f64], n: usize, piv: &mut [usize]) -> bool {
    for c in 0..n {
        let p = (c..n)
            .max_by(|&i, &j| a[i * n + c].abs().total_cmp(&a[j * n + c].abs()))
            .unwrap();
        if !(a[p * n + c].abs() > 0.0 && a[p * n + c].is_finite()) {
            return false;
        }
        piv[c] = p;
        if p != c {
            for j in 0..n {
                a.swap(c * n + j, p * n + j);
            }
        }
        for r in c + 1..n {
            let f = a[r * n + c] / a[c * n + c];
            a[r * n + c] = f;
            if f != 0.0 {
                for j in c + 1..n {
                    a[r * n + j] -= f * a[c * n + j];
                }
            }
        }
    }
    true
}

fn solve_factored(lu: &[f64], n: usize, piv: &[usize], x: &mut [f64]) {
    for (k, &p) in piv.iter().enumerate() {
        x.swap(k, p);
    }
    for i in 0..n {
        let s = dot4(&lu[i * n..i * n + i], &x[..i]);
        x[i] -= s;
    }
    for i in (0..n).rev() {
        let s = dot4(&lu[i * n + i + 1..(i + 1) * n], &x[i + 1..]);
        x[i] = (x[i] - s) / lu[i * n + i];
    }
}

/// a . b with four independent partial sums in a fixed order (the result does not depend on
/// the machine; the compiler keeps them in one vector register, where one running sum is a
/// chain of dependent additions: the HODLR solves ran ~10 % slower with it).
pub(crate) fn dot4(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len().min(b.len());
    let (a, b) = (&a[..n], &b[..n]);
    let mut s = [0.0; 4];
    let (ca, cb) = (a.chunks_exact(4), b.chunks_exact(4));
    let (ra, rb) = (ca.remainder(), cb.remainder());
    for (x, y) in ca.zip(cb) {
        for k in 0..4 {
            s[k] += x[k] * y[k];
        }
    }
    let tail: f64 = ra.iter().zip(rb).map(|(x, y)| x * y).sum();
    (s[0] + s[2]) + (s[1] + s[3]) + tail
}

/// Solves a small dense system A x = b in place with [`SmallLu`]'s factorisation (A row-major
/// n x n, overwritten by its factors; b becomes x); false if A is singular or not finite.
pub fn solve_small(a: &mut [f64], b: &mut [f64], n: usize) -> bool {
    // the pivots on the stack up to 64 unknowns: the systems are small (Anderson mixing's
    // history, 4-5) and solved often (every film iteration of every grid line)
    let mut stack = [0usize; 64];
    let mut heap = Vec::new();
    let piv: &mut [usize] = if n <= stack.len() {
        &mut stack[..n]
    } else {
        heap.resize(n, 0);
        &mut heap
    };
    if !factor_in_place(a, n, piv) {
        return false;
    }
    solve_factored(a, n, piv, b);
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A known 3 x 3 system that needs a row interchange (zero leading pivot):
    /// [[0, 2, 1], [1, 1, 1], [2, 1, 3]] x = [7, 6, 13] has x = [1, 2, 3].
    #[test]
    fn solves_a_small_system_with_pivoting() {
        let a = vec![0.0, 2.0, 1.0, 1.0, 1.0, 1.0, 2.0, 1.0, 3.0];
        let lu = DenseLu::factor(a, 3).expect("regular");
        let mut x = vec![7.0, 6.0, 13.0];
        lu.solve(&mut x);
        for (v, e) in x.iter().zip([1.0, 2.0, 3.0]) {
            assert!((v - e).abs() < 1e-6, "{x:?}");
        }
    }

    /// Several panels and a ragged last one (n = 2 BLOCK + 37): a non-symmetric, not
    /// diagonally dominant matrix (pivoting does work) times a known x gives b; the solve
    /// recovers x to round-off, and a singular matrix (a zero column, which stays exactly zero
    /// through the elimination) is refused.
    #[test]
    fn recovers_a_known_solution_across_panels() {
        let n = 2 * BLOCK + 37;
        let mut a = vec![0.0; n * n];
        for i in 0..n {
            for j in 0..n {
                let h = ((i * 131 + j * 71 + 7) % 97) as f64 / 97.0 - 0.5;
                a[i * n + j] =
                    h + if i == j { 0.3 } else { 0.0 } + 1.0 / (1.0 + i.abs_diff(j) as f64);
            }
        }
        let x: Vec<f64> = (0..n).map(|i| ((i * 37) % 19) as f64 - 9.0).collect();
        let b: Vec<f64> = (0..n)
            .map(|i| (0..n).map(|j| a[i * n + j] * x[j]).sum())
            .collect();
        let lu = DenseLu::factor(a.clone(), n).expect("regular");
        let mut y = b.clone();
        lu.solve(&mut y);
        // single-precision factors: ~1e-7 cond(A) relative
        let err = y
            .iter()
            .zip(&x)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        assert!(err < 1e-4, "max error {err:e}");
        let mut s = a;
        for i in 0..n {
            s[i * n + BLOCK + 5] = 0.0;
        }
        assert!(DenseLu::factor(s, n).is_none());
    }

    /// The kept double-precision factors solve several right-hand sides of a system that
    /// needs pivoting (zero leading entry) to round-off, as the one-shot `solve_small` does,
    /// and a singular matrix is refused by both.
    #[test]
    fn small_lu_solves_repeatedly_and_matches_solve_small() {
        let a = vec![0.0, 2.0, 1.0, 1.0, 1.0, 1.0, 2.0, 1.0, 3.0];
        let lu = SmallLu::factor(a.clone(), 3).expect("regular");
        for (b, x) in [
            ([7.0, 6.0, 13.0], [1.0, 2.0, 3.0]),
            ([4.0, 2.0, 5.0], [-1.0, 1.0, 2.0]),
        ] {
            let mut y = b;
            lu.solve(&mut y);
            let (mut a2, mut z) = (a.clone(), b);
            assert!(solve_small(&mut a2, &mut z, 3));
            for k in 0..3 {
                assert!((y[k] - x[k]).abs() < 1e-14 && y[k] == z[k], "{y:?} {z:?}");
            }
        }
        let s = vec![1.0, 2.0, 2.0, 4.0];
        assert!(SmallLu::factor(s.clone(), 2).is_none());
        assert!(!solve_small(&mut s.clone(), &mut [1.0, 1.0], 2));
    }
}
