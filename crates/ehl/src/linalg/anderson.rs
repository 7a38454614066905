//! Anderson acceleration of a fixed-point iteration x = G(x) (Anderson 1965; in the form of
//! Walker & Ni, "Anderson acceleration for fixed-point iterations", SIAM J. Numer. Anal. 49
//! (2011) 1715): the film temperature of a line in [`crate::thermal::film_energy`]. Generic:
//! nothing here knows the physics.

/// Anderson mixing (type II, Walker & Ni 2011) of a fixed point x = G(x) with residual
/// f = G(x) - x: from the differences of the last m iterates and residuals,
/// gamma = argmin |f_k - dF gamma|, x_{k+1} = x_k + beta f_k - (dX + beta dF) gamma. With m = 0
/// (or an empty history) the relaxed step x_k + beta f_k.
pub struct Anderson {
    depth: usize,
    last: Option<(Vec<f64>, Vec<f64>)>,
    dx: std::collections::VecDeque<Vec<f64>>,
    df: std::collections::VecDeque<Vec<f64>>,
}

impl Anderson {
    /// Mixing of depth `depth` (0: the relaxed iteration).
    pub fn new(depth: usize) -> Self {
        Anderson {
            depth,
            last: None,
            dx: Default::default(),
            df: Default::default(),
        }
    }

    /// Drops the history (e.g. when the residual grows).
    pub fn clear(&mut self) {
        self.last = None;
        self.dx.clear();
        self.df.clear();
    }

    /// The next iterate from the current one `x` and its residual `f` = G(x) - x, with the
    /// mixing (relaxation) parameter `beta`; the pair joins the history.
    pub fn next(&mut self, x: &[f64], f: &[f64], beta: f64) -> Vec<f64> {
        let mut out: Vec<f64> = x.iter().zip(f).map(|(a, b)| a + beta * b).collect();
        if self.depth == 0 {
            return out;
        }
        if let Some((xl, fl)) = self.last.take() {
            self.dx
                .push_back(x.iter().zip(&xl).map(|(a, b)| a - b).collect());
            self.df
                .push_back(f.iter().zip(&fl).map(|(a, b)| a - b).collect());
            if self.dx.len() > self.depth {
                self.dx.pop_front();
                self.df.pop_front();
            }
        }
        self.last = Some((x.to_vec(), f.to_vec()));
        let m = self.df.len();
        if m == 0 {
            return out;
        }
        // normal equations (dF^T dF + eps) gamma = dF^T f, eps a relative Tikhonov term that
        // keeps nearly dependent differences from blowing gamma up
        let mut a = vec![0.0; m * m];
        let mut b = vec![0.0; m];
        for i in 0..m {
            for j in 0..=i {
                let d: f64 = self.df[i].iter().zip(&self.df[j]).map(|(p, q)| p * q).sum();
                a[i * m + j] = d;
                a[j * m + i] = d;
            }
            b[i] = self.df[i].iter().zip(f).map(|(p, q)| p * q).sum();
        }
        let scale = (0..m).fold(0.0f64, |s, i| s.max(a[i * m + i]));
        if !(scale > 0.0 && scale.is_finite()) {
            return out;
        }
        for i in 0..m {
            a[i * m + i] += 1e-10 * scale;
        }
        if !super::dense::solve_small(&mut a, &mut b, m) || b.iter().any(|g| !g.is_finite()) {
            self.clear();
            return out;
        }
        for (i, g) in b.iter().enumerate() {
            for ((o, dx), df) in out.iter_mut().zip(&self.dx[i]).zip(&self.df[i]) {
                *o -= g * (dx + beta * df);
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Anderson mixing on a linear fixed point x = M x + c (M diagonal, 40 contractions spread
    /// over 0 to 0.98, exact solution c / (1 - m)): the plain relaxed iteration (beta 0.4, the
    /// film's) contracts by 0.992 per step and needs ~3000 steps to 1e-10; depth 4 (measured:
    /// 216; a GMRES(4)-like rate on 40 distinct eigenvalues) must be at least 5x faster, and
    /// both must land on the exact point.
    #[test]
    fn anderson_mixing_accelerates_a_linear_fixed_point() {
        let n = 40;
        let m: Vec<f64> = (0..n).map(|i| 0.98 * i as f64 / (n - 1) as f64).collect();
        let c: Vec<f64> = (0..n).map(|i| 1.0 + (i % 7) as f64).collect();
        let exact: Vec<f64> = m.iter().zip(&c).map(|(m, c)| c / (1.0 - m)).collect();
        let run = |depth: usize| {
            let mut mix = Anderson::new(depth);
            let mut x = vec![0.0; n];
            for k in 1..=5000 {
                let f: Vec<f64> = (0..n).map(|i| m[i] * x[i] + c[i] - x[i]).collect();
                if f.iter().fold(0.0f64, |a, v| a.max(v.abs())) < 1e-10 {
                    return (k, x);
                }
                x = mix.next(&x, &f, 0.4);
            }
            (usize::MAX, x)
        };
        let (fast, xa) = run(4);
        let (slow, xp) = run(0);
        assert!(
            slow > 2000 && 5 * fast < slow,
            "Anderson {fast}, plain {slow}"
        );
        for ((a, p), e) in xa.iter().zip(&xp).zip(&exact) {
            assert!((a - e).abs() < 1e-8 * e && (p - e).abs() < 1e-8 * e);
        }
    }
}
