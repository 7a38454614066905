//! FAS multigrid for the steady EHL problem (Venner & Lubrecht, *Multilevel Methods in
//! Lubrication*, 2000, ch. 3-8), on the cell grid.
//!
//! Unknowns: the dimensionless pressure P on every level and the film constant H0 (one scalar).
//! Equations: the discrete Reynolds equation [`super::residual`] with the film
//! H = H0 + G + K P (thesis eq. 2.3) and the load balance A sum(P) = W.
//!
//! * **Relaxation** (one sweep): the film, density and eps are computed from P (one application of
//!   the elastic operator). Rows j are visited in order; in each row the residual is computed with
//!   the current P. Cells where eps/dX^2 is large (the inlet/outlet, Poiseuille-dominated) are
//!   relaxed by Gauss-Seidel *lines* along x: the tridiagonal system of the Poiseuille stencil plus
//!   the local elastic part of the wedge term (coefficients K(0), K(±1) of the kernel,
//!   `Deflection::coefficient`), solved and applied at once. Cells where eps/dX^2 is small (the
//!   high-pressure zone, where the problem is an integral equation) are relaxed by Jacobi
//!   distributive changes: delta_i is spread as delta_i - c sum(neighbours) (c = 1/2 in 1D, 1/4
//!   in 2D) so that the change in the film stays local; they are applied after the sweep.
//!   Cavitation: P = max(P, 0) after every change (projected relaxation).
//! * **Coarse grids** (FAS): P restricted by cell averaging (which conserves the load), the
//!   residual restricted by averaging (zero on cavitated cells), the coarse right-hand side
//!   f_H = L_H(I P_h) + I r_h, the load target carries the fine load defect. The coarse film uses
//!   the elastic operator built on the coarse grid. Corrections are interpolated bilinearly and
//!   not applied on cavitated cells.
//! * **Load balance**: H0 is updated on the coarsest grid after every sweep,
//!   H0 += k H_c (A sum P - W)/W, where H_c is the film at the pressure maximum.
//! * **Full multigrid**: the initial pressure is restricted to the coarsest grid, solved there,
//!   interpolated up with a V-cycle on each level, then V-cycles on the finest grid until the
//!   residual and the load error are below the tolerance.

use super::residual::{self, Fields, ReynoldsGrid};
use crate::case::{DensityModel, Lubricant};
use crate::elastic::Deflection;
use crate::grid::Grid;
use crate::lubricant::{density, viscosity};

/// Dimensionless lubricant laws: rho(P)/rho0, eta(P)/eta0, at p = p_h P.
#[derive(Debug, Clone)]
pub struct Physics {
    pub lubricant: Lubricant,
    /// Hertz pressure p_h (Pa)
    pub ph: f64,
    /// lambda = 12 u_e eta0 R^2 / (b^3 p_h)
    pub lambda: f64,
}

impl Physics {
    #[inline]
    pub fn rho(&self, p: f64) -> f64 {
        density::relative_density(self.lubricant.density_model, self.ph * p)
    }
    /// d(rho/rho0)/dP
    #[inline]
    pub fn drho(&self, p: f64) -> f64 {
        match self.lubricant.density_model {
            DensityModel::Constant => 0.0,
            m => self.ph * density::relative_density_derivative(m, self.ph * p),
        }
    }
    /// eta/eta0
    #[inline]
    pub fn eta(&self, p: f64) -> f64 {
        viscosity::log_relative_viscosity(&self.lubricant, self.ph * p).exp()
    }
}

/// Relaxation and cycle parameters (dimensionless; the defaults are not tuned per case).
#[derive(Debug, Clone, Copy)]
pub struct MgParams {
    /// Gauss-Seidel lines where eps/dX^2 >= this, Jacobi distributive below
    pub switch: f64,
    pub omega_gs: f64,
    pub omega_jd: f64,
    pub pre_sweeps: usize,
    pub post_sweeps: usize,
    pub coarse_sweeps: usize,
    /// h0 relaxation factor k
    pub h0_factor: f64,
    /// smallest number of cells along x on the coarsest grid
    pub min_cells: usize,
    /// second-order upwind Couette term on the finest grid (coarse grids use first order)
    pub second_order: bool,
}

impl Default for MgParams {
    fn default() -> Self {
        MgParams {
            switch: 0.3,
            omega_gs: 0.7,
            omega_jd: 0.3,
            pre_sweeps: 2,
            post_sweeps: 1,
            coarse_sweeps: 20,
            h0_factor: 0.05,
            min_cells: 32,
            second_order: true,
        }
    }
}

/// One grid level: geometry, operator, fields.
pub struct Level {
    pub grid: Grid,
    pub rg: ReynoldsGrid,
    op: Box<dyn Deflection>,
    /// dimensionless deflection per dimensionless pressure: R p_h / b^2 (times the SI operator)
    kscale: f64,
    /// local kernel K(di, dj), di, dj in -2..=2, dimensionless
    kc: [[f64; 5]; 5],
    pub gap: Vec<f64>,
    pub active: Vec<bool>,
    pub p: Vec<f64>,
    pub h: Vec<f64>,
    pub def: Vec<f64>,
    pub rho: Vec<f64>,
    pub eps: Vec<f64>,
    /// FAS right-hand side (zero on the finest level)
    pub rhs: Vec<f64>,
    /// load target: A sum(P) = load (A = dX dY)
    pub load: f64,
    r: Vec<f64>,
    delta: Vec<f64>,
    psi: Vec<f64>,
    p_old: Vec<f64>,
}

impl Level {
    /// Build a level on `grid` (SI) with dimensionless scales `b` (m), `r` (m), `ph` (Pa).
    pub fn new(
        grid: Grid,
        op: Box<dyn Deflection>,
        gap: &(dyn Fn(f64, f64) -> f64 + Sync),
        b: f64,
        r: f64,
        ph: f64,
    ) -> Level {
        let n = grid.len();
        let kscale = r * ph / (b * b);
        let mut kc = [[0.0; 5]; 5];
        for (a, row) in kc.iter_mut().enumerate() {
            for (c, v) in row.iter_mut().enumerate() {
                let (di, dj) = (a as isize - 2, c as isize - 2);
                *v = if grid.ny == 1 && dj != 0 {
                    0.0
                } else {
                    kscale * op.coefficient(di, dj)
                };
            }
        }
        let mut g = vec![0.0; n];
        let mut active = vec![true; n];
        for j in 0..grid.ny {
            for i in 0..grid.nx {
                let k = grid.idx(i, j);
                let v = gap(grid.x(i), if grid.ny == 1 { 0.0 } else { grid.y(j) });
                if v.is_finite() {
                    g[k] = v * r / (b * b);
                } else {
                    active[k] = false;
                }
            }
        }
        let rg = ReynoldsGrid {
            nx: grid.nx,
            ny: grid.ny,
            dx: grid.dx / b,
            dy: grid.dy / b,
            second_order: false,
        };
        Level {
            grid,
            rg,
            op,
            kscale,
            kc,
            gap: g,
            active,
            p: vec![0.0; n],
            h: vec![0.0; n],
            def: vec![0.0; n],
            rho: vec![1.0; n],
            eps: vec![0.0; n],
            rhs: vec![0.0; n],
            load: 0.0,
            r: vec![0.0; n],
            delta: vec![0.0; n],
            psi: vec![0.0; n],
            p_old: vec![0.0; n],
        }
    }

    #[inline]
    fn k(&self, di: isize, dj: isize) -> f64 {
        if di.abs() > 2 || dj.abs() > 2 {
            return 0.0;
        }
        self.kc[(di + 2) as usize][(dj + 2) as usize]
    }

    pub fn area(&self) -> f64 {
        self.rg.dx * self.rg.dy
    }

    /// A sum(P) (dimensionless load carried).
    pub fn carried(&self) -> f64 {
        self.p.iter().sum::<f64>() * self.area()
    }

    /// Film H = H0 + G + K P, density and eps from the current pressure (thesis eq. 2.3).
    pub fn update_film(&mut self, h0: f64, phys: &Physics) {
        for (s, &p) in self.psi.iter_mut().zip(&self.p) {
            *s = p * phys.ph;
        }
        self.op.apply(&self.psi, &mut self.def);
        let hscale = self.kscale / phys.ph;
        for k in 0..self.p.len() {
            self.def[k] *= hscale;
            if self.active[k] {
                let p = self.p[k];
                let h = h0 + self.gap[k] + self.def[k];
                let rho = phys.rho(p);
                self.h[k] = h;
                self.rho[k] = rho;
                let hp = h.max(0.0);
                self.eps[k] = rho * hp * hp * hp / (phys.eta(p) * phys.lambda);
            } else {
                self.h[k] = 0.0;
                self.rho[k] = 1.0;
                self.eps[k] = 0.0;
            }
        }
    }

    fn fields(&self) -> Fields<'_> {
        Fields {
            p: &self.p,
            rho: &self.rho,
            h: &self.h,
            eps: &self.eps,
            active: &self.active,
        }
    }

    /// Residual r = rhs - L(P) into `self.r` (film must be current); zero on cavitated cells.
    fn compute_residual(&mut self) {
        let mut r = std::mem::take(&mut self.r);
        residual::residual(&self.rg, &self.fields(), Some(&self.rhs), None, &mut r);
        for (rk, &p) in r.iter_mut().zip(&self.p) {
            if p <= 0.0 {
                *rk = 0.0;
            }
        }
        self.r = r;
    }

    /// L(P) into `out` (film must be current).
    fn operator(&self, out: &mut [f64]) {
        residual::residual(&self.rg, &self.fields(), None, None, out);
        for v in out.iter_mut() {
            *v = -*v;
        }
    }

    /// Relative residual norm: sum |r| over pressurised cells / sum |d(rho H)/dX| over active cells
    /// (the residual as a fraction of the Couette mass flux change); film must be current.
    pub fn residual_norm(&mut self) -> f64 {
        self.compute_residual();
        let f = self.fields();
        let mut num = 0.0;
        let mut den = 0.0;
        for j in 0..self.rg.ny {
            for i in 0..self.rg.nx {
                let k = j * self.rg.nx + i;
                if !self.active[k] {
                    continue;
                }
                num += self.r[k].abs();
                den += ((residual::couette_east(&self.rg, &f, i, j)
                    - residual::couette_west(&self.rg, &f, i, j))
                    / self.rg.dx)
                    .abs();
            }
        }
        if den > 0.0 {
            num / den
        } else {
            num
        }
    }

    /// One relaxation sweep (film recomputed first).
    pub fn relax(&mut self, h0: f64, phys: &Physics, mp: &MgParams) {
        self.update_film(h0, phys);
        let rg = self.rg;
        let (nx, ny) = (rg.nx, rg.ny);
        let (dx2, dy2) = (rg.dx * rg.dx, rg.dy * rg.dy);
        let c_dist = if ny == 1 { 0.5 } else { 0.25 };
        // neighbour offsets used by the distribution
        let dist: &[(isize, isize)] = if ny == 1 {
            &[(-1, 0), (1, 0)]
        } else {
            &[(-1, 0), (1, 0), (0, -1), (0, 1)]
        };
        let ktil = |lv: &Level, di: isize, dj: isize| -> f64 {
            let mut v = lv.k(di, dj);
            for &(si, sj) in dist {
                v -= c_dist * lv.k(di - si, dj - sj);
            }
            v
        };
        let kt0 = ktil(self, 0, 0);
        let ktm = ktil(self, -1, 0);
        let (k0, k1, k2) = (self.k(0, 0), self.k(1, 0), self.k(2, 0));
        for d in self.delta.iter_mut() {
            *d = 0.0;
        }
        let mut lo = vec![0.0; nx];
        let mut di = vec![0.0; nx];
        let mut up = vec![0.0; nx];
        let mut rr = vec![0.0; nx];
        let mut gs = vec![false; nx];
        for j in 0..ny {
            // residual and coefficients of row j with the current P
            for i in 0..nx {
                let k = j * nx + i;
                gs[i] = false;
                if !self.active[k] {
                    continue;
                }
                let f = self.fields();
                rr[i] = self.rhs[k] - residual::operator_at(&rg, &f, None, i, j);
                let nb = residual::neighbours(&rg, i, j);
                let mut cf = [0.0; 4];
                let mut diag = 0.0;
                let mut xi: f64 = 0.0;
                for d in 0..(if ny == 1 { 2 } else { 4 }) {
                    let (c, _) = residual::face(&f, k, nb[d], if d < 2 { dx2 } else { dy2 });
                    diag -= c;
                    if matches!(nb[d], Some(n) if self.active[n]) {
                        cf[d] = c;
                    }
                    if d < 2 {
                        xi = xi.max(c);
                    }
                }
                let west_ok = i > 0 && self.active[k - 1];
                let rho_i = self.rho[k];
                let rho_w = if west_ok { self.rho[k - 1] } else { 0.0 };
                if xi >= mp.switch {
                    gs[i] = true;
                    // dW_i/dP_m = (rho_i K(i-m) - rho_{i-1} K(i-1-m)) / dX, first-order wedge
                    let dw_w = (rho_i * k1 - rho_w * k0) / rg.dx;
                    let dw_c = (rho_i * k0 - rho_w * k1) / rg.dx
                        + self.drho_h(k, phys) / rg.dx;
                    let dw_e = (rho_i * k1 - rho_w * k2) / rg.dx;
                    lo[i] = cf[0] - dw_w;
                    di[i] = diag - dw_c;
                    up[i] = cf[1] - dw_e;
                } else {
                    let sum_nb: f64 = cf.iter().sum();
                    let pois = diag - c_dist * sum_nb;
                    let dw = (rho_i * kt0 - rho_w * ktm) / rg.dx + self.drho_h(k, phys) / rg.dx;
                    let a = pois - dw;
                    let mut d = if a < 0.0 { rr[i] / a } else { 0.0 };
                    if self.p[k] <= 0.0 && d < 0.0 {
                        d = 0.0;
                    }
                    self.delta[k] = d;
                }
            }
            // Gauss-Seidel lines: maximal runs of GS cells
            let mut i = 0;
            while i < nx {
                if !gs[i] {
                    i += 1;
                    continue;
                }
                let s = i;
                while i < nx && gs[i] {
                    i += 1;
                }
                let e = i; // run s..e
                thomas(&mut lo[s..e], &mut di[s..e], &mut up[s..e], &mut rr[s..e]);
                for m in s..e {
                    let k = j * nx + m;
                    let v = self.p[k] + mp.omega_gs * rr[m];
                    self.p[k] = if v.is_finite() { v.max(0.0) } else { 0.0 };
                }
            }
        }
        // Jacobi distributive changes
        let w = mp.omega_jd;
        for j in 0..ny {
            for i in 0..nx {
                let k = j * nx + i;
                let d = self.delta[k];
                if d == 0.0 {
                    continue;
                }
                self.p[k] += w * d;
                for &(si, sj) in dist {
                    let (a, b) = (i as isize + si, j as isize + sj);
                    if a < 0 || b < 0 || a >= nx as isize || b >= ny as isize {
                        continue;
                    }
                    let n = b as usize * nx + a as usize;
                    if self.active[n] {
                        self.p[n] -= w * c_dist * d;
                    }
                }
            }
        }
        for (p, &a) in self.p.iter_mut().zip(&self.active) {
            if !a || !p.is_finite() || *p < 0.0 {
                *p = 0.0;
            }
        }
    }

    #[inline]
    fn drho_h(&self, k: usize, phys: &Physics) -> f64 {
        phys.drho(self.p[k]) * self.h[k]
    }

    /// Index of the maximum pressure.
    pub fn argmax(&self) -> usize {
        let mut best = 0;
        for (k, &p) in self.p.iter().enumerate() {
            if p > self.p[best] {
                best = k;
            }
        }
        best
    }
}

/// Thomas algorithm for a tridiagonal system (lower, diagonal, upper; rhs replaced by the solution).
fn thomas(lo: &mut [f64], di: &mut [f64], up: &mut [f64], r: &mut [f64]) {
    let n = di.len();
    if n == 0 {
        return;
    }
    for i in 1..n {
        let m = if di[i - 1] != 0.0 { lo[i] / di[i - 1] } else { 0.0 };
        di[i] -= m * up[i - 1];
        r[i] -= m * r[i - 1];
    }
    r[n - 1] = if di[n - 1] != 0.0 { r[n - 1] / di[n - 1] } else { 0.0 };
    for i in (0..n - 1).rev() {
        r[i] = if di[i] != 0.0 { (r[i] - up[i] * r[i + 1]) / di[i] } else { 0.0 };
    }
}

/// Average of the 2 (1D) or 4 (2D) fine cells of each coarse cell.
pub fn restrict(fine: &Grid, coarse: &Grid, v: &[f64], out: &mut [f64]) {
    if fine.ny == 1 {
        for i in 0..coarse.nx {
            out[i] = 0.5 * (v[2 * i] + v[2 * i + 1]);
        }
    } else {
        for j in 0..coarse.ny {
            for i in 0..coarse.nx {
                let a = fine.idx(2 * i, 2 * j);
                let b = fine.idx(2 * i, 2 * j + 1);
                out[coarse.idx(i, j)] = 0.25 * (v[a] + v[a + 1] + v[b] + v[b + 1]);
            }
        }
    }
}

/// Bilinear cell-centred interpolation coarse -> fine, zero on the domain edges (ghost = -value).
pub fn interpolate(coarse: &Grid, fine: &Grid, v: &[f64], out: &mut [f64]) {
    let (cx, cy) = (coarse.nx as isize, coarse.ny as isize);
    let at = |i: isize, j: isize| -> f64 {
        // mirror with sign change outside: zero on the edge faces
        let (mut s, mut ii, mut jj) = (1.0, i, j);
        if ii < 0 {
            ii = 0;
            s = -s;
        }
        if ii >= cx {
            ii = cx - 1;
            s = -s;
        }
        if jj < 0 {
            jj = 0;
            s = -s;
        }
        if jj >= cy {
            jj = cy - 1;
            s = -s;
        }
        s * v[(jj * cx + ii) as usize]
    };
    for j in 0..fine.ny {
        for i in 0..fine.nx {
            let ic = (i / 2) as isize;
            let io = if i % 2 == 0 { ic - 1 } else { ic + 1 };
            let val = if fine.ny == 1 {
                0.75 * at(ic, 0) + 0.25 * at(io, 0)
            } else {
                let jc = (j / 2) as isize;
                let jo = if j % 2 == 0 { jc - 1 } else { jc + 1 };
                0.5625 * at(ic, jc) + 0.1875 * (at(io, jc) + at(ic, jo)) + 0.0625 * at(io, jo)
            };
            out[fine.idx(i, j)] = val;
        }
    }
}

/// The multigrid hierarchy and the shared unknown H0.
pub struct Hierarchy {
    /// levels[0] is the finest
    pub levels: Vec<Level>,
    pub h0: f64,
    pub phys: Physics,
    pub mp: MgParams,
    /// relaxation sweeps done, counted in fine-grid work units
    pub work: f64,
}

impl Hierarchy {
    /// Coarse grids of `fine` while both directions halve evenly (ny == 1 stays 1) and at least
    /// `min_cells` cells remain along x.
    pub fn grids(fine: Grid, min_cells: usize) -> Vec<Grid> {
        let mut out = vec![fine];
        loop {
            let g = *out.last().unwrap();
            let x_ok = g.nx % 2 == 0 && g.nx / 2 >= min_cells;
            let y_ok = g.ny == 1 || (g.ny % 2 == 0 && g.ny / 2 >= 4);
            if !(x_ok && y_ok) {
                break;
            }
            let ny = if g.ny == 1 { 1 } else { g.ny / 2 };
            let c = Grid::new(g.nx / 2, ny, g.x_min, g.x_max(), g.y_min, g.y_max());
            out.push(c);
        }
        out
    }

    fn h_center(&self, l: usize) -> f64 {
        let lv = &self.levels[l];
        lv.h[lv.argmax()]
    }

    /// Load balance update of H0 on level `l` (film must be current).
    fn update_h0(&mut self, l: usize) {
        let lv = &self.levels[l];
        let err = (lv.carried() - lv.load) / lv.load;
        let hc = self.h_center(l).abs().max(1e-12);
        let step = self.mp.h0_factor * hc * err.clamp(-1.0, 1.0);
        self.h0 += step;
    }

    fn relax(&mut self, l: usize) {
        let (h0, phys, mp) = (self.h0, &self.phys, &self.mp);
        self.levels[l].relax(h0, phys, mp);
        self.work += 1.0 / (1usize << (l * if self.levels[0].rg.ny == 1 { 1 } else { 2 })) as f64;
    }

    /// Relax on the coarsest level with an H0 update after every sweep.
    pub fn coarse_solve(&mut self, sweeps: usize) {
        let l = self.levels.len() - 1;
        for _ in 0..sweeps {
            self.relax(l);
            let (h0, phys) = (self.h0, &self.phys);
            self.levels[l].update_film(h0, phys);
            self.update_h0(l);
        }
    }

    /// One FAS V-cycle starting at level `l`.
    pub fn vcycle(&mut self, l: usize) {
        if l + 1 == self.levels.len() {
            let s = self.mp.coarse_sweeps;
            self.coarse_solve(s);
            return;
        }
        for _ in 0..self.mp.pre_sweeps {
            self.relax(l);
        }
        let (h0, phys) = (self.h0, self.phys.clone());
        let (fine_part, coarse_part) = self.levels.split_at_mut(l + 1);
        let fine = &mut fine_part[l];
        let coarse = &mut coarse_part[0];
        fine.update_film(h0, &phys);
        fine.compute_residual();
        restrict(&fine.grid, &coarse.grid, &fine.p, &mut coarse.p);
        coarse.p_old.copy_from_slice(&coarse.p);
        coarse.update_film(h0, &phys);
        let mut lc = std::mem::take(&mut coarse.rhs);
        coarse.operator(&mut lc);
        restrict(&fine.grid, &coarse.grid, &fine.r, &mut coarse.r);
        for k in 0..lc.len() {
            lc[k] += if coarse.active[k] { coarse.r[k] } else { 0.0 };
        }
        coarse.rhs = lc;
        coarse.load = coarse.carried() + (fine.load - fine.carried());
        self.vcycle(l + 1);
        let (fine_part, coarse_part) = self.levels.split_at_mut(l + 1);
        let fine = &mut fine_part[l];
        let coarse = &mut coarse_part[0];
        for k in 0..coarse.p.len() {
            coarse.r[k] = coarse.p[k] - coarse.p_old[k];
        }
        interpolate(&coarse.grid, &fine.grid, &coarse.r, &mut fine.delta);
        for k in 0..fine.p.len() {
            if fine.p[k] > 0.0 && fine.active[k] {
                fine.p[k] = (fine.p[k] + fine.delta[k]).max(0.0);
            }
        }
        for _ in 0..self.mp.post_sweeps {
            self.relax(l);
        }
    }

    /// Full multigrid start: the finest level's P (the initial guess) restricted down, solved on
    /// the coarsest level, interpolated up with one V-cycle per level.
    pub fn fmg(&mut self, coarse_sweeps: usize) {
        let nl = self.levels.len();
        for l in 0..nl - 1 {
            let (a, b) = self.levels.split_at_mut(l + 1);
            restrict(&a[l].grid, &b[0].grid, &a[l].p, &mut b[0].p);
            b[0].load = a[l].load;
            b[0].rhs.iter_mut().for_each(|v| *v = 0.0);
        }
        self.coarse_solve(coarse_sweeps);
        for l in (0..nl - 1).rev() {
            let (a, b) = self.levels.split_at_mut(l + 1);
            let (fine, coarse) = (&mut a[l], &b[0]);
            interpolate(&coarse.grid, &fine.grid, &coarse.p, &mut fine.p);
            for (p, &act) in fine.p.iter_mut().zip(&fine.active) {
                if !act || *p < 0.0 {
                    *p = 0.0;
                }
            }
            self.vcycle(l);
        }
    }
}
