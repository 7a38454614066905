//! Hierarchical off-diagonal low-rank (HODLR) factorisation: an approximate inverse of a dense
//! matrix whose off-diagonal blocks are numerically of low rank, applied in O(n k log n)
//! instead of the O(n^2) of dense LU factors.
//!
//! The Jacobian of an infinite line contact is J = A + B K: A and B banded (the Reynolds
//! stencil), K the elastic log kernel, smooth away from its diagonal. Any block of J that does
//! not touch the diagonal is therefore close to a matrix of small rank, and the recursive
//! split of the matrix into two diagonal blocks and two low-rank couplings (weak
//! admissibility) holds J to a tolerance with ranks of a few tens (Ambikasaran & Darve, J. Sci.
//! Comput. 57 (2013) 477-501; Hackbusch, *Hierarchical Matrices*, 2015, ch. 3).
//!
//! At each split, A = [[A11, U1 V1^T], [U2 V2^T, A22]]. With c1 = A11^-1 b1, c2 = A22^-1 b2,
//! W1 = A11^-1 U1 and W2 = A22^-1 U2 (the children's own solves), the unknowns a = V1^T x2 and
//! s = V2^T x1 solve the small system (Sherman-Morrison-Woodbury, once per split)
//!
//! ```text
//!   [[I, V1^T W2], [V2^T W1, I]] [a; s] = [V1^T c2; V2^T c1],   x1 = c1 - W1 a,  x2 = c2 - W2 s.
//! ```
//!
//! Leaves (at most `leaf` rows) are dense LU factors in double precision. The off-diagonal
//! blocks are compressed by cross approximation with full pivoting on the explicit block (each
//! step removes the rank-one cross through the largest remaining entry, Bebendorf 2000) until
//! no entry exceeds the tolerance; the rows are first equilibrated (each scaled to a largest
//! entry of one) so that one absolute tolerance serves rows of very different size (the
//! Reynolds rows of the inlet and of the Hertzian zone differ by decades).
//!
//! The result is a preconditioner, not an exact solver: the dropped entries make
//! M^-1 A = I + E with |E| of the order of the tolerance times the condition of the
//! approximated matrix, and the Krylov iteration that uses it removes the rest.

use super::dense::{dot4 as dot, SmallLu};
use rayon::prelude::*;

/// A HODLR approximation of A^-1 (see the module docs).
#[derive(Debug, Clone)]
pub struct Hodlr {
    n: usize,
    /// 1 / (largest |entry| of each row): A x = b is solved as (D A) x = D b
    row_scale: Vec<f64>,
    root: Node,
    /// largest rank of an off-diagonal block
    max_rank: usize,
}

#[derive(Debug, Clone)]
enum Node {
    Leaf(SmallLu),
    Split(Box<Split>),
}

/// One split of a diagonal block into two halves of n1 and n2 rows.
#[derive(Debug, Clone)]
struct Split {
    n1: usize,
    left: Node,
    right: Node,
    /// A12 = U1 V1^T: V1 (n2 x k1) and W1 = A11^-1 U1 (n1 x k1), column-major
    k1: usize,
    v1: Vec<f64>,
    w1: Vec<f64>,
    /// A21 = U2 V2^T: V2 (n1 x k2) and W2 = A22^-1 U2 (n2 x k2), column-major
    k2: usize,
    v2: Vec<f64>,
    w2: Vec<f64>,
    /// the (k1 + k2) coupling system of the module docs
    s: Option<SmallLu>,
}

/// Rows from which the two halves of a split are solved on two threads.
const PARALLEL_ROWS: usize = 256;

impl Hodlr {
    /// Approximate the inverse of the row-major `n x n` matrix `a`: leaves of at most `leaf`
    /// rows, off-diagonal blocks to `tol` on the row-equilibrated matrix. None if a row is
    /// zero or not finite, or a leaf or a coupling system is singular.
    pub fn factor(a: &[f64], n: usize, leaf: usize, tol: f64) -> Option<Hodlr> {
        assert_eq!(a.len(), n * n);
        assert!(leaf >= 1 && tol >= 0.0);
        let row_scale: Vec<f64> = (0..n)
            .map(|i| {
                let row = &a[i * n..(i + 1) * n];
                let m = row.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                // (f64::max passes over NaN, so every entry is checked)
                if m > 0.0 && row.iter().all(|v| v.is_finite()) {
                    1.0 / m
                } else {
                    f64::NAN
                }
            })
            .collect();
        if row_scale.iter().any(|s| s.is_nan()) {
            return None;
        }
        let mat = Mat {
            a,
            n,
            scale: &row_scale,
        };
        let root = build(&mat, 0, n, leaf, tol)?;
        let max_rank = root.max_rank();
        Some(Hodlr {
            n,
            row_scale,
            root,
            max_rank,
        })
    }

    /// Order of the matrix.
    pub fn n(&self) -> usize {
        self.n
    }

    /// Largest rank of an off-diagonal block.
    pub fn max_rank(&self) -> usize {
        self.max_rank
    }

    /// x ~ A^-1 b (in place: `x` holds b on entry).
    pub fn solve(&self, x: &mut [f64]) {
        assert_eq!(x.len(), self.n);
        for (v, s) in x.iter_mut().zip(&self.row_scale) {
            *v *= s;
        }
        self.root.solve(x);
    }
}

/// A row-major square matrix, borrowed, with the scale of each row (the equilibration,
/// applied as blocks are copied out).
struct Mat<'a> {
    a: &'a [f64],
    n: usize,
    scale: &'a [f64],
}

impl Mat<'_> {
    /// Rows r0..r0 + m, columns c0..c0 + n, scaled, row-major.
    fn block(&self, r0: usize, m: usize, c0: usize, n: usize) -> Vec<f64> {
        let mut b = vec![0.0; m * n];
        for (i, row) in b.chunks_mut(n).enumerate() {
            let s = (r0 + i) * self.n + c0;
            let f = self.scale[r0 + i];
            for (x, y) in row.iter_mut().zip(&self.a[s..s + n]) {
                *x = f * y;
            }
        }
        b
    }
}

/// The HODLR node of rows and columns off..off + size.
fn build(m: &Mat, off: usize, size: usize, leaf: usize, tol: f64) -> Option<Node> {
    if size <= leaf {
        return SmallLu::factor(m.block(off, size, off, size), size).map(Node::Leaf);
    }
    let n1 = size / 2;
    let n2 = size - n1;
    let ((left, right), ((u1, v1, k1), (u2, v2, k2))) = rayon::join(
        || {
            rayon::join(
                || build(m, off, n1, leaf, tol),
                || build(m, off + n1, n2, leaf, tol),
            )
        },
        || {
            rayon::join(
                || cross(m, off, n1, off + n1, n2, tol),
                || cross(m, off + n1, n2, off, n1, tol),
            )
        },
    );
    let (left, right) = (left?, right?);
    let solve_columns = |node: &Node, u: Vec<f64>, rows: usize| -> Vec<f64> {
        let mut w = u;
        w.par_chunks_mut(rows).for_each(|c| node.solve(c));
        w
    };
    let (w1, w2) = rayon::join(
        || solve_columns(&left, u1, n1),
        || solve_columns(&right, u2, n2),
    );
    let k = k1 + k2;
    let s = if k > 0 {
        let mut s = vec![0.0; k * k];
        for i in 0..k {
            s[i * k + i] = 1.0;
        }
        for i in 0..k1 {
            for j in 0..k2 {
                s[i * k + k1 + j] = dot(&v1[i * n2..(i + 1) * n2], &w2[j * n2..(j + 1) * n2]);
            }
        }
        for j in 0..k2 {
            for i in 0..k1 {
                s[(k1 + j) * k + i] = dot(&v2[j * n1..(j + 1) * n1], &w1[i * n1..(i + 1) * n1]);
            }
        }
        Some(SmallLu::factor(s, k)?)
    } else {
        None
    };
    Some(Node::Split(Box::new(Split {
        n1,
        left,
        right,
        k1,
        v1,
        w1,
        k2,
        v2,
        w2,
        s,
    })))
}

/// The block of rows r0..r0 + m and columns c0..c0 + n as U V^T (U m x k, V n x k, both
/// column-major) by cross approximation with full pivoting: until no entry of the remainder
/// exceeds `tol`, subtract the cross through its largest entry (its column times its row over
/// the pivot). Returns (U, V, k).
fn cross(
    mat: &Mat,
    r0: usize,
    m: usize,
    c0: usize,
    n: usize,
    tol: f64,
) -> (Vec<f64>, Vec<f64>, usize) {
    let mut r = mat.block(r0, m, c0, n);
    let (mut u, mut v) = (Vec::new(), Vec::new());
    let mut k = 0;
    let mut best = argmax(&r);
    while k < m.min(n) {
        let (p, big) = best;
        if !(big > tol) {
            break;
        }
        let (pi, pj) = (p / n, p % n);
        let piv = r[p];
        let col: Vec<f64> = (0..m).map(|i| r[i * n + pj]).collect();
        let row: Vec<f64> = r[pi * n..(pi + 1) * n].iter().map(|x| x / piv).collect();
        // subtract the cross and find the next pivot in the same pass
        best = r
            .par_chunks_mut(n)
            .zip(&col)
            .enumerate()
            .map(|(i, (ri, &ci))| {
                let mut b = (0, 0.0f64);
                for (j, (x, y)) in ri.iter_mut().zip(&row).enumerate() {
                    *x -= ci * y;
                    if x.abs() > b.1 {
                        b = (i * n + j, x.abs());
                    }
                }
                b
            })
            .reduce(|| (0, 0.0), |a, b| if b.1 > a.1 { b } else { a });
        u.extend_from_slice(&col);
        v.extend_from_slice(&row);
        k += 1;
    }
    (u, v, k)
}

/// (index, |value|) of the largest |entry|.
fn argmax(r: &[f64]) -> (usize, f64) {
    r.iter().enumerate().fold(
        (0, 0.0f64),
        |b, (i, x)| if x.abs() > b.1 { (i, x.abs()) } else { b },
    )
}

impl Node {
    fn max_rank(&self) -> usize {
        match self {
            Node::Leaf(_) => 0,
            Node::Split(s) => {
                s.k1.max(s.k2)
                    .max(s.left.max_rank())
                    .max(s.right.max_rank())
            }
        }
    }

    fn solve(&self, x: &mut [f64]) {
        match self {
            Node::Leaf(lu) => lu.solve(x),
            Node::Split(s) => {
                let (x1, x2) = x.split_at_mut(s.n1);
                if x1.len() + x2.len() >= PARALLEL_ROWS {
                    rayon::join(|| s.left.solve(x1), || s.right.solve(x2));
                } else {
                    s.left.solve(x1);
                    s.right.solve(x2);
                }
                let Some(lu) = &s.s else { return };
                let (n1, n2) = (x1.len(), x2.len());
                let mut t: Vec<f64> = (0..s.k1)
                    .map(|i| dot(&s.v1[i * n2..(i + 1) * n2], x2))
                    .chain((0..s.k2).map(|j| dot(&s.v2[j * n1..(j + 1) * n1], x1)))
                    .collect();
                lu.solve(&mut t);
                for (i, a) in t[..s.k1].iter().enumerate() {
                    for (x, w) in x1.iter_mut().zip(&s.w1[i * n1..(i + 1) * n1]) {
                        *x -= a * w;
                    }
                }
                for (j, a) in t[s.k1..].iter().enumerate() {
                    for (x, w) in x2.iter_mut().zip(&s.w2[j * n2..(j + 1) * n2]) {
                        *x -= a * w;
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A matrix of the kind the line contact gives: a tridiagonal, non-symmetric part plus a
    /// smooth log-kernel coupling of every pair, with rows of very different size.
    fn line_like(n: usize) -> Vec<f64> {
        let mut a = vec![0.0; n * n];
        let h = 1.0 / n as f64;
        for i in 0..n {
            let row = 10f64.powf(4.0 * (i as f64 / n as f64) - 2.0);
            for j in 0..n {
                let d = (i as f64 - j as f64) * h;
                let k = -((d.abs() + 0.5 * h).ln()) * h;
                let band = match i as isize - j as isize {
                    0 => 3.0,
                    -1 => -1.2,
                    1 => -0.9,
                    _ => 0.0,
                };
                a[i * n + j] = row * (band + k);
            }
        }
        a
    }

    fn residual(a: &[f64], n: usize, x: &[f64], b: &[f64]) -> f64 {
        (0..n)
            .map(|i| {
                let r: f64 = (0..n).map(|j| a[i * n + j] * x[j]).sum::<f64>() - b[i];
                (r * 1.0
                    / a[i * n..(i + 1) * n]
                        .iter()
                        .fold(0.0f64, |m, v| m.max(v.abs())))
                .abs()
            })
            .fold(0.0, f64::max)
    }

    /// With no tolerance the HODLR form is exact: every block is kept to full rank and the
    /// solve recovers a known solution to round-off, on a ragged size (leaves of unequal
    /// size) and with pivoting needed in the leaves (a zero leading diagonal entry).
    #[test]
    fn is_exact_without_truncation() {
        let n = 203;
        let mut a = line_like(n);
        a[0] = 0.0;
        let x: Vec<f64> = (0..n).map(|i| ((i * 37) % 19) as f64 - 9.0).collect();
        let b: Vec<f64> = (0..n)
            .map(|i| (0..n).map(|j| a[i * n + j] * x[j]).sum())
            .collect();
        let h = Hodlr::factor(&a, n, 16, 0.0).expect("regular");
        let mut y = b.clone();
        h.solve(&mut y);
        let err = y
            .iter()
            .zip(&x)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        assert!(err < 1e-9, "max error {err:e}");
    }

    /// Truncated, the off-diagonal ranks stay small (the log kernel: ~log(n) log(1/tol); a
    /// full top block would be rank 512 here) and the solve is exact for a matrix whose
    /// equilibrated entries each differ by at most tol: its equilibrated residual is bounded
    /// by n tol max|x|, each entry of a row lying in exactly one dropped remainder.
    #[test]
    fn truncation_keeps_small_ranks_and_a_small_residual() {
        let n = 1024;
        let a = line_like(n);
        let b: Vec<f64> = (0..n).map(|i| ((i * 13) % 7) as f64 - 3.0).collect();
        let h = Hodlr::factor(&a, n, 64, 1e-8).expect("regular");
        assert!(h.max_rank() < 40, "rank {}", h.max_rank());
        let mut y = b.clone();
        h.solve(&mut y);
        let r = residual(&a, n, &y, &b);
        let bound = n as f64 * 1e-8 * y.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        assert!(
            r < bound,
            "equilibrated residual {r:e} > {bound:e}, rank {}",
            h.max_rank()
        );
        // and the bound is not idle: a coarser tolerance gives a larger residual
        let coarse = Hodlr::factor(&a, n, 64, 1e-4).expect("regular");
        let mut z = b.clone();
        coarse.solve(&mut z);
        assert!(residual(&a, n, &z, &b) > 10.0 * r);
    }

    /// A singular matrix (a zero row) is refused, and so is one with a NaN far from the
    /// diagonal (which the truncation would otherwise drop unseen).
    #[test]
    fn refuses_a_zero_row_or_a_nan() {
        let n = 100;
        let mut a = line_like(n);
        a[40 * n..41 * n].iter_mut().for_each(|v| *v = 0.0);
        assert!(Hodlr::factor(&a, n, 16, 1e-8).is_none());
        let mut a = line_like(n);
        a[3 * n + 90] = f64::NAN;
        assert!(Hodlr::factor(&a, n, 16, 1e-8).is_none());
    }
}
