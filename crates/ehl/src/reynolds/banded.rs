//! A small banded LU factorisation with partial pivoting (the scheme of LAPACK `dgbtrf` /
//! `dgbtrs`, written row-wise): the line solver of the EHL preconditioner.
//!
//! A matrix with `kl` sub- and `ku` super-diagonals is stored row by row, each row `i` holding
//! the columns `i - kl ..= i + kl + ku` (the extra `kl` columns receive the fill-in of row
//! interchanges). Factorisation costs O(n kl (kl + ku)), a solve O(n (2 kl + ku)).

/// Banded matrix and, after [`Banded::factor`], its LU factors.
#[derive(Debug, Clone)]
pub struct Banded {
    n: usize,
    kl: usize,
    ku: usize,
    w: usize,
    a: Vec<f64>,
    piv: Vec<usize>,
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
        }
    }

    /// Order of the matrix.
    pub fn n(&self) -> usize {
        self.n
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

    /// A[i, j] (before factorisation), 0 outside the band.
    pub fn get(&self, i: usize, j: usize) -> f64 {
        if self.in_band(i, j) {
            self.a[self.at(i, j)]
        } else {
            0.0
        }
    }

    /// In-place LU with partial pivoting. Returns false if a pivot is exactly zero or not finite
    /// (the matrix is then unusable).
    pub fn factor(&mut self) -> bool {
        let (n, kl, ku) = (self.n, self.kl, self.ku);
        for k in 0..n {
            let last = (k + kl).min(n - 1);
            // pivot search in column k, rows k..=last
            let mut p = k;
            let mut best = self.a[self.at(k, k)].abs();
            for r in k + 1..=last {
                let v = self.a[self.at(r, k)].abs();
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
                    self.a.swap(x, y);
                }
            }
            let pivot = self.a[self.at(k, k)];
            for r in k + 1..=last {
                let irk = self.at(r, k);
                let l = self.a[irk] / pivot;
                self.a[irk] = l;
                if l != 0.0 {
                    for j in k + 1..=jend {
                        let (x, y) = (self.at(r, j), self.at(k, j));
                        self.a[x] -= l * self.a[y];
                    }
                }
            }
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
            if bk != 0.0 {
                for r in k + 1..=(k + kl).min(n - 1) {
                    b[r] -= self.a[self.at(r, k)] * bk;
                }
            }
        }
        for k in (0..n).rev() {
            let mut s = b[k];
            for j in k + 1..=(k + kl + ku).min(n - 1) {
                s -= self.a[self.at(k, j)] * b[j];
            }
            b[k] = s / self.a[self.at(k, k)];
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
            assert!(m.factor());
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
}
