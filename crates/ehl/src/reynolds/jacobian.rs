//! The rows of the Reynolds Jacobian dF/dP, F = -L(P) of [`super::residual`], written from the
//! residual's own rules: the Poiseuille faces of [`residual::face_weights`] (linear in eps) and
//! the Couette upwind rule of [`residual::couette_rule`], with the squeeze term's c0 on
//! the cell itself. The Newton solver's preconditioners (`crate::ehl::system`) and its
//! diagonal scaling take their entries from [`reynolds_row`]; the exact Jacobian product
//! (`System::directional`) evaluates the residual itself on the linearised fields. One stencil,
//! three uses: a change of the discretisation in `residual.rs` reaches all of them.
//!
//! The film enters through eps = rho H^3 / (eta lambda) and q = rho H, with
//! H = H0 + G + D(P): a pressure change at cell l moves the film of every cell m by
//! Khat(|m - l|) (the elastic kernel in dimensionless form), so each row has local entries (the
//! direct dependence on P_m through rho(P_m), eta(P_m) and the Poiseuille difference) and
//! kernel entries (through H_m):
//!
//! ```text
//!   d eps_m / dP_l = eps_m [(rho'/rho - (ln eta)')_m delta_ml + 3 Khat(m - l) / H_m]
//!   d q_m / dP_l   = rho'_m H_m delta_ml + rho_m Khat(m - l)
//! ```
//!
//! (the Couette term's q carries the features' shift: d(rho (H + s))/dP_m = rho'_m (H_m + s_m)
//! locally, the squeeze term's rho H does not).

use super::residual::{self, Fields, ReynoldsGrid};

/// What a Jacobian entry comes from (the diagonal scaling and the preconditioner's coarse
/// grids weigh the terms apart).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Term {
    /// the Poiseuille flux with eps frozen: c (P_n - P_k)
    Poiseuille,
    /// the Poiseuille flux through eps's dependence on P
    PoiseuilleEps,
    /// the wedge (Couette) and squeeze terms on rho H
    Wedge,
}

/// Receives the entries of one row of dF/dP.
pub(crate) trait RowSink {
    /// dF_k / dP_m += v (the direct dependence on the pressure of cell m)
    fn local(&mut self, term: Term, m: usize, v: f64);
    /// dF_k / dP_l += a Khat(|m - l|) for every cell l (through the film of cell m)
    fn kernel(&mut self, term: Term, m: usize, a: f64);
    /// whether the sink takes the [`Term::PoiseuilleEps`] entries (false: they are not formed)
    fn wants_eps(&self) -> bool {
        true
    }
}

/// The state a row is linearised at: the residual's fields (with the features' Couette
/// shift), the pressure derivatives of the laws and the squeeze coefficient.
#[derive(Clone, Copy)]
pub(crate) struct Linearisation<'a> {
    pub f: Fields<'a>,
    /// rho'(P) per cell (with the thermal Couette factor where the run is thermal)
    pub drho: &'a [f64],
    /// (ln eta)'(P) per cell
    pub dlneta: &'a [f64],
    /// c0 of the squeeze term (0 when steady)
    pub c0: f64,
}

/// The entries of row k = (i, j) of dF/dP at `lin` (an active cell), sent to `sink`.
#[inline]
pub(crate) fn reynolds_row(
    g: &ReynoldsGrid,
    lin: &Linearisation,
    i: usize,
    j: usize,
    sink: &mut impl RowSink,
) {
    let f = &lin.f;
    let k = j * g.nx + i;
    let pk = f.p[k];
    // F = -sum_faces (w_k eps_k + w_n eps_n) (P_n - P_k) + couette + squeeze
    let mut eps_self = 0.0; // dF_k / d eps_k
    for (_, n, d2) in residual::faces(g, i, j) {
        let (wk, wn, n) = residual::face_weights(f.active, n, d2);
        let pn = n.map_or(0.0, |n| f.p[n]);
        let c = wk * f.eps[k] + n.map_or(0.0, |n| wn * f.eps[n]);
        sink.local(Term::Poiseuille, k, c);
        eps_self -= wk * (pn - pk);
        if let Some(n) = n {
            sink.local(Term::Poiseuille, n, -c);
            if sink.wants_eps() {
                eps_through(lin, n, -wn * (pn - pk), sink);
            }
        }
    }
    if sink.wants_eps() {
        eps_through(lin, k, eps_self, sink);
    }
    // couette (east - west) / dX on rho (H + shift) and squeeze c0 rho H
    let a = residual::couette_stencil(g, f.active, i, j);
    for (o, &ao) in a.iter().enumerate() {
        let couette = ao;
        let total = if o == 0 { ao + lin.c0 } else { ao };
        if total == 0.0 {
            continue;
        }
        let m = k - o;
        let shift = f.couette_shift.map_or(0.0, |s| s[m]);
        sink.local(
            Term::Wedge,
            m,
            lin.drho[m] * (f.h[m] * total + shift * couette),
        );
        sink.kernel(Term::Wedge, m, total * f.rho[m]);
    }
}

/// dF_k / d eps_m = `g` sent on through eps_m's dependence on P (see the module doc).
#[inline(always)]
fn eps_through(lin: &Linearisation, m: usize, g: f64, sink: &mut impl RowSink) {
    let f = &lin.f;
    let e = f.eps[m];
    if g == 0.0 || e == 0.0 {
        return;
    }
    sink.local(
        Term::PoiseuilleEps,
        m,
        g * e * (lin.drho[m] / f.rho[m] - lin.dlneta[m]),
    );
    let hm = f.h[m];
    if hm > 0.0 {
        sink.kernel(Term::PoiseuilleEps, m, g * e * 3.0 / hm);
    }
}

/// The (Poiseuille, wedge) parts of the diagonal dF_k / dP_k with eps frozen: the Poiseuille
/// face coefficients and the wedge and squeeze terms through rho' and the kernel's
/// Khat(|m - k|) (`khat`, Khat(0), Khat(1), ...). What [`crate::ehl`]'s scaling
/// c_k = 1 / (Poiseuille + |wedge|) is built from.
pub(crate) fn diagonal(
    g: &ReynoldsGrid,
    lin: &Linearisation,
    khat: &[f64],
    i: usize,
    j: usize,
) -> (f64, f64) {
    struct Diagonal<'a> {
        k: usize,
        khat: &'a [f64],
        pois: f64,
        wedge: f64,
    }
    impl RowSink for Diagonal<'_> {
        fn local(&mut self, term: Term, m: usize, v: f64) {
            if m == self.k {
                match term {
                    Term::Poiseuille => self.pois += v,
                    Term::Wedge => self.wedge += v,
                    Term::PoiseuilleEps => {}
                }
            }
        }
        fn kernel(&mut self, term: Term, m: usize, a: f64) {
            let d = m.abs_diff(self.k);
            if term == Term::Wedge && d < self.khat.len() {
                self.wedge += a * self.khat[d];
            }
        }
        fn wants_eps(&self) -> bool {
            false
        }
    }
    let mut d = Diagonal {
        k: j * g.nx + i,
        khat,
        pois: 0.0,
        wedge: 0.0,
    };
    reynolds_row(g, lin, i, j, &mut d);
    (d.pois, d.wedge)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reynolds::residual::Transient;

    /// A small 2D problem with every branch of the stencil: cells without material (an inner
    /// one, one on the inlet edge and one on the south edge), the domain edges, the squeeze term, a Couette shift, and
    /// a film that depends on every pressure through a 2D kernel K(m, l).
    struct Problem {
        g: ReynoldsGrid,
        active: Vec<bool>,
        gap: Vec<f64>,
        shift: Vec<f64>,
        history: Vec<f64>,
        c0: f64,
    }

    impl Problem {
        fn new(second_order: bool) -> Self {
            let (nx, ny) = (7, 5);
            let n = nx * ny;
            let active: Vec<bool> = (0..n)
                .map(|k| k != 3 && k != 2 * nx + 5 && k != 4 * nx)
                .collect();
            Problem {
                g: ReynoldsGrid {
                    nx,
                    ny,
                    dx: 0.3,
                    dy: 0.4,
                    second_order,
                },
                active,
                gap: (0..n).map(|k| 0.2 + 0.05 * ((k * 7) % 11) as f64).collect(),
                shift: (0..n).map(|k| 0.1 * ((k % 5) as f64 - 2.0)).collect(),
                history: (0..n).map(|k| 1.0 + 0.1 * (k % 3) as f64).collect(),
                c0: 2.5,
            }
        }

        fn kernel(&self, m: usize, l: usize) -> f64 {
            let nx = self.g.nx;
            let (dx, dy) = ((m % nx).abs_diff(l % nx), (m / nx).abs_diff(l / nx));
            0.03 / (1.0 + (dx * dx + dy * dy) as f64)
        }

        /// (rho, drho, h, eps, dlneta) of the laws rho = 1 + 0.6 P / (1 + 1.7 P),
        /// eta = exp(1.3 P), lambda = 1, at the pressures `p`.
        #[allow(clippy::type_complexity)]
        fn fields(&self, p: &[f64]) -> (Vec<f64>, Vec<f64>, Vec<f64>, Vec<f64>, Vec<f64>) {
            let n = p.len();
            let (mut rho, mut drho, mut h, mut eps, mut dl) = (
                vec![1.0; n],
                vec![0.0; n],
                vec![0.0; n],
                vec![0.0; n],
                vec![0.0; n],
            );
            for m in 0..n {
                if !self.active[m] {
                    continue;
                }
                let pm = p[m];
                rho[m] = 1.0 + 0.6 * pm / (1.0 + 1.7 * pm);
                drho[m] = 0.6 / ((1.0 + 1.7 * pm) * (1.0 + 1.7 * pm));
                h[m] = 0.1 + self.gap[m] + (0..n).map(|l| self.kernel(m, l) * p[l]).sum::<f64>();
                dl[m] = 1.3;
                eps[m] = rho[m] * h[m].powi(3) / (1.3 * pm).exp();
            }
            (rho, drho, h, eps, dl)
        }

        /// F = -L(P) of the residual module (rhs 0), on every cell.
        fn residual(&self, p: &[f64]) -> Vec<f64> {
            let (rho, _, h, eps, _) = self.fields(p);
            let f = Fields {
                p,
                rho: &rho,
                h: &h,
                eps: &eps,
                active: &self.active,
                couette_shift: Some(&self.shift),
            };
            let tr = Transient {
                c0: self.c0,
                history: &self.history,
            };
            let mut out = vec![0.0; p.len()];
            residual::residual(&self.g, &f, None, Some(&tr), &mut out);
            // residual() gives rhs - L = -L = F
            out
        }
    }

    /// A whole row of dF/dP: local entries, and the kernel entries spread by K(m, l); with
    /// `only`, the entries of that term alone.
    struct Dense<'a> {
        pb: &'a Problem,
        row: Vec<f64>,
        only: Option<Term>,
    }

    impl RowSink for Dense<'_> {
        fn local(&mut self, t: Term, m: usize, v: f64) {
            if self.only.is_none_or(|o| o == t) {
                self.row[m] += v;
            }
        }
        fn kernel(&mut self, t: Term, m: usize, a: f64) {
            if self.only.is_some_and(|o| o != t) {
                return;
            }
            for l in 0..self.row.len() {
                if self.pb.active[l] {
                    self.row[l] += a * self.pb.kernel(m, l);
                }
            }
        }
    }

    /// The rows of [`reynolds_row`] are the derivative of the residual module's F = -L(P):
    /// every entry of every row on a 7 x 5 grid against central differences of F (step 1e-6,
    /// truncation ~1e-12 relative, round-off ~1e-10), both upwind orders. Agreement to 1e-7 of
    /// the largest entry: far below any slip of a stencil term (each is of the order of the
    /// entries).
    #[test]
    fn rows_are_the_derivative_of_the_residual() {
        for second in [true, false] {
            let pb = Problem::new(second);
            let n = pb.active.len();
            let p: Vec<f64> = (0..n)
                .map(|k| {
                    if pb.active[k] {
                        0.2 + 0.7 * ((k * 13) % 17) as f64 / 17.0
                    } else {
                        0.0
                    }
                })
                .collect();
            let (rho, drho, h, eps, dlneta) = pb.fields(&p);
            let lin = Linearisation {
                f: Fields {
                    p: &p,
                    rho: &rho,
                    h: &h,
                    eps: &eps,
                    active: &pb.active,
                    couette_shift: Some(&pb.shift),
                },
                drho: &drho,
                dlneta: &dlneta,
                c0: pb.c0,
            };
            let step = 1e-6;
            let mut fd = vec![vec![0.0; n]; n]; // fd[k][l] = dF_k / dP_l
            for l in (0..n).filter(|&l| pb.active[l]) {
                let (mut up, mut down) = (p.clone(), p.clone());
                up[l] += step;
                down[l] -= step;
                let (fu, fdn) = (pb.residual(&up), pb.residual(&down));
                for k in 0..n {
                    fd[k][l] = (fu[k] - fdn[k]) / (2.0 * step);
                }
            }
            let scale = fd.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
            assert!(scale > 1.0, "{scale}");
            for k in (0..n).filter(|&k| pb.active[k]) {
                let (i, j) = (k % pb.g.nx, k / pb.g.nx);
                let row_of = |only: Option<Term>| {
                    let mut sink = Dense {
                        pb: &pb,
                        row: vec![0.0; n],
                        only,
                    };
                    reynolds_row(&pb.g, &lin, i, j, &mut sink);
                    sink.row
                };
                let row = row_of(None);
                for l in 0..n {
                    // the columns of cells without material are not unknowns: no entry there
                    let want = if pb.active[l] { fd[k][l] } else { 0.0 };
                    assert!(
                        (row[l] - want).abs() < 1e-7 * scale,
                        "second order {second}, row {k}, column {l}: {} against {want}",
                        row[l],
                    );
                }
                // the diagonal with eps frozen: the whole derivative less the entries through
                // eps, with the kernel along the row (what `diagonal` is given)
                let khat: Vec<f64> = (0..pb.g.nx).map(|d| pb.kernel(0, d)).collect();
                let through_eps = row_of(Some(Term::PoiseuilleEps))[k];
                let (pois, wedge) = diagonal(&pb.g, &lin, &khat, i, j);
                assert!(
                    (pois + wedge + through_eps - fd[k][k]).abs() < 1e-7 * scale,
                    "second order {second}, diagonal {k}: {pois} + {wedge} + {through_eps} against {}",
                    fd[k][k]
                );
                // and its Poiseuille part is the sum of the faces' coefficients
                let faces: f64 = residual::faces(&pb.g, i, j)
                    .map(|(_, nb, d2)| residual::face(&lin.f, k, nb, d2).0)
                    .sum();
                assert!((pois - faces).abs() < 1e-12 * faces, "{pois} {faces}");
                assert_eq!(pois, row_of(Some(Term::Poiseuille))[k]);
            }
        }
    }
}
