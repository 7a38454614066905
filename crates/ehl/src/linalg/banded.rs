//! A small banded LU factorisation with partial pivoting (the scheme of LAPACK `dgbtrf` /
//! `dgbtrs`, written row-wise): the line solver of the EHL preconditioner.
//!
//! A matrix with `kl` sub- and `ku` super-diagonals is stored row by row, each row `i` holding
//! the columns `i - kl ..= i + kl + ku` (the extra `kl` columns receive the fill-in of row
//! interchanges during the factorisation, which works on a copy: the matrix itself stays
//! available for products). The factors are kept column by column for the solves.
//! Factorisation costs O(n kl (kl + ku)), a solve O(n (2 kl + ku)); [`solve_batch`] solves
//! several systems of the same shape at once.

thread_local! {
    /// Work copy of the matrix during [`Banded::factor`] (reused: no allocation per line).
    static LU: std::cell::RefCell<Vec<f64>> = const { std::cell::RefCell::new(Vec::new()) };
}

/// Banded matrix and, after [`Banded::factor`], its LU factors.
#[derive(Debug, Clone)]
pub struct Banded {
    n: usize,
    kl: usize,
    ku: usize,
    w: usize,
    a: Vec<f64>,
    piv: Vec<usize>,
    /// after factorisation: the multipliers of column k, rows k+1 ..= k+kl, at k kl ..
    lower: Vec<f64>,
    /// after factorisation: column k of U above the diagonal, rows k-1, k-2, ..., k-kl-ku,
    /// at k (kl + ku) ..
    upper: Vec<f64>,
    /// reciprocals of the diagonal of U
    inv_diag: Vec<f64>,
}

impl Banded {
    /// Zero `n x n` matrix with `kl` sub- and `ku` super-diagonals.
    pub fn new(n: usize, kl: usize, ku: usize) -> Self {
        let w = 2 * kl + ku + 1;
        Banded {
            n,
            kl,
            ku,
            w,
            a: vec![0.0; n * w],
            piv: vec![0; n],
            lower: Vec::new(),
            upper: Vec::new(),
            inv_diag: Vec::new(),
        }
    }

    /// Makes this the zero `n x n` matrix with `kl` sub- and `ku` super-diagonals, keeping the
    /// allocations (a scratch matrix reused for many systems: the film's line solves allocated
    /// ~0.3 MB a solve, and the page faults and TLB shootdowns of returning it were ~5 % of a
    /// thermal run's samples).
    pub fn reset(&mut self, n: usize, kl: usize, ku: usize) {
        let w = 2 * kl + ku + 1;
        (self.n, self.kl, self.ku, self.w) = (n, kl, ku, w);
        self.a.clear();
        self.a.resize(n * w, 0.0);
        self.piv.clear();
        self.piv.resize(n, 0);
    }

    /// Order of the matrix.
    pub fn n(&self) -> usize {
        self.n
    }

    /// Number of sub-diagonals.
    pub fn kl(&self) -> usize {
        self.kl
    }

    /// Number of super-diagonals.
    pub fn ku(&self) -> usize {
        self.ku
    }

    /// y -= A x (the matrix as assembled, also after factorisation).
    pub fn sub_product(&self, x: &[f64], y: &mut [f64]) {
        let (n, kl, ku) = (self.n, self.kl, self.ku);
        for (i, yi) in y.iter_mut().enumerate().take(n) {
            let lo = i.saturating_sub(kl);
            let hi = (i + ku).min(n - 1);
            let row = &self.a[self.at(i, lo)..=self.at(i, hi)];
            *yi -= row.iter().zip(&x[lo..=hi]).map(|(a, b)| a * b).sum::<f64>();
        }
    }

    /// Reset to zero (keeps the allocation).
    pub fn clear(&mut self) {
        self.a.iter_mut().for_each(|v| *v = 0.0);
    }

    #[inline]
    fn at(&self, i: usize, j: usize) -> usize {
        i * self.w + (j + self.kl - i)
    }

    /// Whether (i, j) lies inside the band `-kl <= j - i <= ku`.
    #[inline]
    pub fn in_band(&self, i: usize, j: usize) -> bool {
        i < self.n && j < self.n && j + self.kl >= i && j <= i + self.ku
    }

    /// A[i, j] += v; entries outside the band are dropped (the caller truncates on purpose).
    #[inline]
    pub fn add(&mut self, i: usize, j: usize, v: f64) {
        if self.in_band(i, j) {
            let k = self.at(i, j);
            self.a[k] += v;
        }
    }

    /// A[i, j] as assembled (also after factorisation), 0 outside the band.
    pub fn get(&self, i: usize, j: usize) -> f64 {
        if self.in_band(i, j) {
            self.a[self.at(i, j)]
        } else {
            0.0
        }
    }

    /// LU with partial pivoting (into the factors; the matrix is kept). Returns false if a
    /// pivot is exactly zero or not finite (the factors are then unusable).
    pub fn factor(&mut self) -> bool {
        LU.with(|cell| {
            let mut w = cell.borrow_mut();
            w.clear();
            w.extend_from_slice(&self.a);
            self.factor_from(&mut w)
        })
    }

    /// LU of the matrix copied into `w` (same layout as `a`, which stays the original).
    fn factor_from(&mut self, w: &mut [f64]) -> bool {
        let (n, kl, ku) = (self.n, self.kl, self.ku);
        for k in 0..n {
            let last = (k + kl).min(n - 1);
            // pivot search in column k, rows k..=last
            let mut p = k;
            let mut best = w[self.at(k, k)].abs();
            for r in k + 1..=last {
                let v = w[self.at(r, k)].abs();
                if v > best {
                    best = v;
                    p = r;
                }
            }
            if best == 0.0 || !best.is_finite() {
                return false;
            }
            self.piv[k] = p;
            let jend = (k + kl + ku).min(n - 1);
            if p != k {
                for j in k..=jend {
                    let (x, y) = (self.at(k, j), self.at(p, j));
                    w.swap(x, y);
                }
            }
            let pivot = w[self.at(k, k)];
            // row k's entries right of the diagonal, k + 1 ..= jend, are contiguous, and so are
            // row r's (r > k) further on: one split gives both as slices, an axpy the compiler
            // vectorises (the indexed loop it did not: the thesis roller with [thermal], where
            // film and Reynolds line factorisations were 8 % of the samples)
            let len = jend - k;
            let from = self.at(k, k + 1);
            for r in k + 1..=last {
                let irk = self.at(r, k);
                let l = w[irk] / pivot;
                w[irk] = l;
                if l != 0.0 && len > 0 {
                    let (head, tail) = w.split_at_mut(irk + 1);
                    let pivot_row = &head[from..from + len];
                    for (x, y) in tail[..len].iter_mut().zip(pivot_row) {
                        *x -= l * y;
                    }
                }
            }
        }
        // contiguous copies for the solves, column by column: both triangular solves are then
        // axpy updates without a serial reduction (measured 2x faster than row-wise dots)
        let wu = kl + ku;
        for (v, len) in [
            (&mut self.lower, n * kl),
            (&mut self.upper, n * wu),
            (&mut self.inv_diag, n),
        ] {
            v.clear();
            v.resize(len, 0.0);
        }
        for k in 0..n {
            for r in k + 1..=(k + kl).min(n - 1) {
                self.lower[k * kl + r - k - 1] = w[self.at(r, k)];
            }
            for r in k.saturating_sub(wu)..k {
                self.upper[k * wu + k - 1 - r] = w[self.at(r, k)];
            }
            self.inv_diag[k] = 1.0 / w[self.at(k, k)];
        }
        true
    }

    /// Solve A x = b in place (after a successful [`Banded::factor`]).
    pub fn solve(&self, b: &mut [f64]) {
        let (n, kl, ku) = (self.n, self.kl, self.ku);
        for k in 0..n {
            let p = self.piv[k];
            if p != k {
                b.swap(k, p);
            }
            let bk = b[k];
            let m = kl.min(n - 1 - k);
            if bk != 0.0 && m > 0 {
                let l = &self.lower[k * kl..k * kl + m];
                for (br, lr) in b[k + 1..k + 1 + m].iter_mut().zip(l) {
                    *br -= lr * bk;
                }
            }
        }
        let wu = kl + ku;
        for k in (0..n).rev() {
            let xk = b[k] * self.inv_diag[k];
            b[k] = xk;
            let m = wu.min(k);
            if xk != 0.0 && m > 0 {
                let u = &self.upper[k * wu..k * wu + m];
                for (br, ur) in b[k - m..k].iter_mut().rev().zip(u) {
                    *br -= ur * xk;
                }
            }
        }
    }
}

/// Solve `B` systems of the same shape at once (`mats[q]` x_q = `bs[q]`, in place): the
/// triangular recurrences are interleaved so that their latency chains overlap (measured on
/// 256-row lines with 6 + 5 diagonals: 1.8x the throughput of one-by-one solves for B = 2).
pub fn solve_batch<const B: usize>(mats: [&Banded; B], mut bs: [&mut [f64]; B]) {
    let (n, kl, ku) = (mats[0].n, mats[0].kl, mats[0].ku);
    debug_assert!(mats.iter().all(|m| m.n == n && m.kl == kl && m.ku == ku));
    let mut xk = [0.0; B];
    for k in 0..n {
        for q in 0..B {
            let p = mats[q].piv[k];
            if p != k {
                bs[q].swap(k, p);
            }
            xk[q] = bs[q][k];
        }
        let m = kl.min(n - 1 - k);
        let l: [&[f64]; B] = mats.map(|a| &a.lower[k * kl..k * kl + m]);
        let s: [&mut [f64]; B] = bs.each_mut().map(|b| &mut b[k + 1..k + 1 + m]);
        for t in 0..m {
            for q in 0..B {
                s[q][t] -= l[q][t] * xk[q];
            }
        }
    }
    let wu = kl + ku;
    for k in (0..n).rev() {
        for q in 0..B {
            xk[q] = bs[q][k] * mats[q].inv_diag[k];
            bs[q][k] = xk[q];
        }
        let m = wu.min(k);
        let u: [&[f64]; B] = mats.map(|a| &a.upper[k * wu..k * wu + m]);
        let s: [&mut [f64]; B] = bs.each_mut().map(|b| &mut b[k - m..k]);
        for t in 0..m {
            for q in 0..B {
                s[q][m - 1 - t] -= u[q][t] * xk[q];
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Against a dense product: random banded matrices with small diagonals (so pivoting is
    /// exercised), A x recomputed from the solution equals b to 1e-10.
    #[test]
    fn solves_with_pivoting() {
        let mut s: u64 = 7;
        let mut rnd = || {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (s >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        for &(n, kl, ku) in &[(1, 0, 0), (5, 1, 1), (40, 6, 4), (33, 2, 5), (8, 7, 7)] {
            let mut m = Banded::new(n, kl, ku);
            let mut dense = vec![0.0; n * n];
            for i in 0..n {
                for j in 0..n {
                    if m.in_band(i, j) {
                        let v = if i == j { 0.01 * rnd() } else { rnd() };
                        m.add(i, j, v);
                        dense[i * n + j] = v;
                    }
                }
            }
            let b: Vec<f64> = (0..n).map(|_| rnd()).collect();
            let mut x = b.clone();
            let before: Vec<f64> = (0..n * n).map(|k| m.get(k / n, k % n)).collect();
            assert!(m.factor());
            // the factorisation works on a copy: the matrix is still there for products
            assert!((0..n * n).all(|k| m.get(k / n, k % n) == before[k]));
            m.solve(&mut x);
            for i in 0..n {
                let ax: f64 = (0..n).map(|j| dense[i * n + j] * x[j]).sum();
                assert!(
                    (ax - b[i]).abs() < 1e-10 * (1.0 + x.iter().map(|v| v.abs()).sum::<f64>()),
                    "n {n}"
                );
            }
        }
    }

    /// A matrix reset to another shape and refilled (the film's reused line system) solves as
    /// a fresh one, bit for bit: nothing of the last system (entries, pivots, factors) leaks.
    #[test]
    fn a_reset_matrix_solves_as_a_fresh_one() {
        let fill = |m: &mut Banded, q: usize| {
            let (n, kl, ku) = (m.n(), m.kl(), m.ku());
            for i in 0..n {
                for j in i.saturating_sub(kl)..=(i + ku).min(n - 1) {
                    let v = ((i * 29 + j * 11 + q * 5) % 19) as f64 - 9.0;
                    m.add(i, j, if i == j { 0.05 * v } else { v });
                }
            }
        };
        let mut reused = Banded::new(0, 0, 0);
        // larger, smaller, then larger again than the last (shrinking keeps stale capacity)
        for (q, &(n, kl, ku)) in [(50, 5, 5), (12, 2, 3), (64, 6, 4)].iter().enumerate() {
            let mut fresh = Banded::new(n, kl, ku);
            fill(&mut fresh, q);
            reused.reset(n, kl, ku);
            fill(&mut reused, q);
            assert!(fresh.factor() && reused.factor());
            let rhs: Vec<f64> = (0..n).map(|i| ((i * 7 + q) % 5) as f64 - 2.0).collect();
            let (mut a, mut b) = (rhs.clone(), rhs);
            fresh.solve(&mut a);
            reused.solve(&mut b);
            assert_eq!(a, b, "shape {n} {kl} {ku}");
        }
    }

    /// A batch solve gives bit for bit the results of the one-by-one solves (same operations,
    /// only interleaved), with pivoting exercised.
    #[test]
    fn batch_equals_single_solves() {
        let (n, kl, ku) = (37, 6, 5);
        let mats: Vec<Banded> = (0..4)
            .map(|q| {
                let mut m = Banded::new(n, kl, ku);
                for i in 0..n {
                    for j in i.saturating_sub(kl)..=(i + ku).min(n - 1) {
                        let v = ((i * 31 + j * 17 + q * 7) % 23) as f64 - 11.0;
                        m.add(i, j, if i == j { 0.1 * v } else { v });
                    }
                }
                assert!(m.factor());
                m
            })
            .collect();
        let rhs: Vec<Vec<f64>> = (0..4)
            .map(|q| (0..n).map(|i| ((i * 13 + q) % 7) as f64 - 3.0).collect())
            .collect();
        let mut single = rhs.clone();
        for (m, b) in mats.iter().zip(&mut single) {
            m.solve(b);
        }
        let mut batch = rhs.clone();
        let [a, b, c, d] = &mut batch[..] else {
            unreachable!()
        };
        solve_batch([&mats[0], &mats[1], &mats[2], &mats[3]], [a, b, c, d]);
        assert_eq!(batch, single);
    }
}
