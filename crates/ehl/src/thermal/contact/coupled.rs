//! The temperature rows of the coupled thermal problem (steady, or one time step): the film's
//! energy equation (in a time step with its time derivatives against the step's previous
//! level) and both surfaces' moving-heat-source relation as residuals of the film and surface
//! temperatures at a given pressure and film, for the Newton method that solves pressure and
//! temperature together (`crate::ehl::thermal_newton`). A line contact has one grid line; a
//! finite contact (a ball, a finite roller) has a film line per grid row, coupled along y by
//! the side flow.
//!
//! The unknowns are the film temperature at the interior collocation points of every cell of
//! every row's film (the extents frozen at the last [`ThermalContact::update`]) and both
//! surface temperatures at every cell. The residuals, in K:
//!
//! * film: T - S(T), S(T) the linear solve of each row's energy equation with its
//!   coefficients (laws, velocity profiles, heating) taken at T
//!   ([`film_energy::solve_line_linear`]) and, in a finite contact, its side flow
//!   (v dT/dy, `film_energy::SideFlow`) with the y mass fluxes of the profiles at T and the
//!   neighbouring rows' temperatures T: the film's fixed point, whose root is the converged
//!   film (the update's film-body iteration reaches the same root by sweeping the rows,
//!   [`ThermalContact::update`]);
//! * surfaces: T_b - T0 - R_b q_b, q_b the consistent heat flux from the film into body b
//!   ([`film_energy::line_energy`]) and R_b its moving-heat-source operator (Jaeger).
//!
//! With them come the generalized Reynolds factors of the same profiles, so that the Reynolds
//! rows of the coupled system see the temperatures it solves. The columns take the pressure
//! gradient as given (not the flux-driven form of [`ThermalContact::update`]): the two agree
//! where the factors are those of the profiles, which is what the coupled system solves (the
//! flux-driven columns match their flux with the profile the factors are taken from, the one
//! the limiting shear stress capped, and blend the cap in by the same gradient at a settled
//! column: `film_energy`'s `capped_profile`).

use super::*;
use crate::thermal::film_energy::{
    line_coefficients_from, line_energy, solve_line_linear, LineCoefficients,
};
use rayon::prelude::*;

/// One grid row's film in the frozen frame: its first cell, one past its last, and where its
/// columns' shear-thinning iterations start (the same start every evaluation, so that the
/// residual is a function of the temperatures alone).
#[derive(Debug, Clone)]
struct RowFrame {
    j: usize,
    start: usize,
    end: usize,
    thinning: Vec<f64>,
    poiseuille: Vec<f64>,
}

impl RowFrame {
    /// film cells
    fn cells(&self) -> usize {
        self.end - self.start
    }
}

/// The frozen frame of the coupled residual: the rows' film extents at the last update.
#[derive(Debug, Clone)]
pub(crate) struct CoupledFrame {
    rows: Vec<RowFrame>,
    /// the cells with a film (the last update's)
    wet: Vec<bool>,
}

impl ThermalContact {
    /// The frame of the coupled residual at the last update: `Some` for a contact whose film
    /// was solved (steady, or a time step in progress: the film's time derivatives against
    /// the step's previous level, [`ThermalContact::begin_step`]), else `None`.
    pub(crate) fn coupled_frame(&self) -> Option<CoupledFrame> {
        let nz = self.nz();
        let rows: Vec<RowFrame> = self
            .lines
            .iter()
            .enumerate()
            .filter_map(|(j, s)| {
                let s = s.as_ref()?;
                let start = self.start[j];
                let end = start + s.t.len() / nz;
                (end > start).then(|| RowFrame {
                    j,
                    start,
                    end,
                    thinning: s.thinning.clone(),
                    poiseuille: s.poiseuille.clone(),
                })
            })
            .collect();
        if rows.is_empty() {
            return None;
        }
        Some(CoupledFrame {
            rows,
            wet: self.active.clone(),
        })
    }

    /// Unknowns of the coupled temperature rows: the film's interior points, row by row, then
    /// both surfaces.
    pub(crate) fn coupled_len(&self, f: &CoupledFrame) -> usize {
        f.rows.iter().map(RowFrame::cells).sum::<usize>() * (self.nz() - 2) + 2 * self.grid.len()
    }

    /// The present temperatures as the coupled unknowns (K).
    pub(crate) fn coupled_unknowns(&self, f: &CoupledFrame, x: &mut [f64]) {
        let nz = self.nz();
        let mut at = 0;
        for r in &f.rows {
            for i in r.start..r.end {
                for z in 1..nz - 1 {
                    x[at] = self.film[r.j][i * nz + z];
                    at += 1;
                }
            }
        }
        for b in 0..2 {
            x[at..at + self.grid.len()].copy_from_slice(&self.surface[b]);
            at += self.grid.len();
        }
    }

    /// Takes the coupled unknowns `x` (K) as the contact's temperatures.
    pub(crate) fn set_coupled(&mut self, f: &CoupledFrame, x: &[f64]) {
        let (nx, nz, n) = (self.grid.nx, self.nz(), self.grid.len());
        let m = self.coupled_len(f) - 2 * n;
        for b in 0..2 {
            self.surface[b].copy_from_slice(&x[m + b * n..m + (b + 1) * n]);
        }
        let mut at = 0;
        for r in &f.rows {
            for i in r.start..r.end {
                let k = r.j * nx + i;
                self.film[r.j][i * nz] = self.surface[0][k];
                for z in 1..nz - 1 {
                    self.film[r.j][i * nz + z] = x[at];
                    at += 1;
                }
                self.film[r.j][i * nz + nz - 1] = self.surface[1][k];
            }
        }
    }

    /// The fields of the film at the pressure `p` (Pa), film `h` (m) and unknowns `x` (K), as
    /// [`ThermalContact::update`] forms them.
    fn coupled_fields(
        &self,
        f: &CoupledFrame,
        p: &[f64],
        h: &[f64],
        active: &[bool],
        x: &[f64],
    ) -> CoupledFields {
        let g = self.grid;
        let (nx, nz, n) = (g.nx, self.nz(), g.len());
        let ok: Vec<bool> = (0..n).map(|k| active[k] && h[k].is_finite()).collect();
        let (hh, pp) = film_fields(&g, p, h, active);
        let (dpdx, dpdy) = gradients(&g, &pp);
        let m = self.coupled_len(f) - 2 * n;
        let (s1, s2) = (x[m..m + n].to_vec(), x[m + n..m + 2 * n].to_vec());
        let mut t = Vec::with_capacity(f.rows.len());
        let mut at = 0;
        for r in &f.rows {
            let mut tr = vec![0.0; r.cells() * nz];
            for (c, i) in (r.start..r.end).enumerate() {
                let k = r.j * nx + i;
                tr[c * nz] = s1[k];
                for z in 1..nz - 1 {
                    tr[c * nz + z] = x[at];
                    at += 1;
                }
                tr[c * nz + nz - 1] = s2[k];
            }
            t.push(tr);
        }
        CoupledFields {
            ok,
            hh,
            pp,
            dpdx,
            dpdy,
            s1,
            s2,
            t,
        }
    }

    /// Row `r`'s film line of the fields `c`: the columns take the pressure gradient as given;
    /// no side flow yet; in a time step, the film's previous level.
    fn coupled_line<'a>(&'a self, r: &RowFrame, c: &'a CoupledFields) -> Line<'a> {
        let (nx, nz) = (self.grid.nx, self.nz());
        let cells = r.j * nx + r.start..r.j * nx + r.end;
        Line {
            dx: self.grid.dx,
            h: &c.hh[cells.clone()],
            p: &c.pp[cells.clone()],
            dpdx: &c.dpdx[cells.clone()],
            dpdy: &c.dpdy[cells.clone()],
            u1: self.u1,
            u2: self.u2,
            t1: &c.s1[cells.clone()],
            t2: &c.s2[cells],
            t_in: self.t0(),
            poiseuille_flux_x: None,
            transient: self.step.as_ref().map(|s| {
                let at = r.start * nz..r.end * nz;
                LineTransient {
                    inv_dt: s.inv_dt,
                    t_old: &s.t_old[r.j][at.clone()],
                    rho_h_old: &s.rho_h_old[r.j][at],
                }
            }),
            side: None,
        }
    }

    /// The coefficients of row `r`'s film at its temperatures `t` (the frame's column starts).
    fn coupled_coefficients(
        &self,
        r: &RowFrame,
        line: &Line,
        t: &[f64],
        parallel_columns: bool,
    ) -> Result<(LineCoefficients, Vec<FilmProfile>)> {
        let mut opts = self.options.line;
        opts.linearise_heating = false;
        opts.parallel_columns = parallel_columns;
        let mut thinning = r.thinning.clone();
        let mut poiseuille = r.poiseuille.clone();
        let (coef, profiles, _) = line_coefficients_from(
            &self.rule,
            &self.laws,
            line,
            t,
            &opts,
            &mut thinning,
            &mut poiseuille,
        )
        .map_err(film_error)?;
        Ok((coef, profiles))
    }

    /// The coupled temperature residuals (K) at the unknowns `x` (K), the pressure `p` (Pa)
    /// and film `h` (m; infinite without material) into `r` (as long as `x`), and the
    /// generalized Reynolds factors of the same profiles into `flow`, `couette` (as
    /// [`ThermalContact::reynolds_factors`] forms them).
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn coupled_residual(
        &mut self,
        f: &CoupledFrame,
        p: &[f64],
        h: &[f64],
        active: &[bool],
        x: &[f64],
        r: &mut [f64],
        flow: &mut [f64],
        couette: &mut [f64],
    ) -> Result<()> {
        let g = self.grid;
        let (nx, nz, n) = (g.nx, self.nz(), g.len());
        let t0 = self.t0();
        let c = self.coupled_fields(f, p, h, active, x);
        // the rows' columns in parallel where the rows alone do not keep the threads busy
        let parallel_columns =
            self.options.line.parallel_columns && f.rows.len() < 2 * rayon::current_num_threads();
        let coefs = f
            .rows
            .par_iter()
            .zip(&c.t)
            .map(|(row, t)| {
                let line = self.coupled_line(row, &c);
                self.coupled_coefficients(row, &line, t, parallel_columns)
            })
            .collect::<Result<Vec<_>>>()?;
        // the side flow of a finite contact: the y mass fluxes of the profiles at T, and the
        // neighbouring rows' temperatures T (the last update's outside the frame)
        let side = (self.options.side_flow && g.ny > 1).then(|| {
            let mut my = vec![f64::NAN; n * nz];
            for (row, (coef, profiles)) in f.rows.iter().zip(&coefs) {
                let first = row.j * nx + row.start;
                row_side_mass_flux(&mut my, nz, first, &c.hh, &coef.density, profiles);
            }
            let mut film = self.film.clone();
            for (row, t) in f.rows.iter().zip(&c.t) {
                film[row.j][row.start * nz..row.end * nz].copy_from_slice(t);
            }
            f.rows
                .iter()
                .map(|row| self.side_arrays(row.j, row.start, row.end, &f.wet, &my, &film, None))
                .collect::<Vec<_>>()
        });
        let dy = g.dy;
        let solved = f
            .rows
            .par_iter()
            .enumerate()
            .map(|(at, row)| {
                let mut line = self.coupled_line(row, &c);
                if let Some(a) = side.as_ref().map(|s| &s[at]) {
                    line.side = Some(SideFlow {
                        inv_dy: 1.0 / dy,
                        north: &a.north,
                        south: &a.south,
                        t_north: &a.t_north,
                        t_south: &a.t_south,
                    });
                }
                let coef = &coefs[at].0;
                let t =
                    solve_line_linear(&self.rule, &self.oil, &line, coef).map_err(film_error)?;
                let e = line_energy(&self.rule, &self.oil, &line, coef, &t);
                Ok((t, e.q1, e.q2))
            })
            .collect::<Result<Vec<_>>>()?;
        let mut at = 0;
        let mut q = [vec![0.0; n], vec![0.0; n]];
        for ((row, t), (s, q1, q2)) in f.rows.iter().zip(&c.t).zip(&solved) {
            for cell in 0..row.cells() {
                for z in 1..nz - 1 {
                    r[at] = t[cell * nz + z] - s[cell * nz + z];
                    at += 1;
                }
                let k = row.j * nx + row.start + cell;
                if c.ok[k] {
                    q[0][k] = q1[cell];
                    q[1][k] = q2[cell];
                }
            }
        }
        let m = at;
        let mut rise = vec![0.0; n];
        for b in 0..2 {
            self.solids[b].temperature_rise(&q[b], &mut rise);
            let s = if b == 0 { &c.s1 } else { &c.s2 };
            for k in 0..n {
                r[m + b * n + k] = s[k] - t0 - rise[k];
            }
        }
        // each cell's row in the frame, for its profile
        let mut row_of = vec![usize::MAX; g.ny];
        for (at, row) in f.rows.iter().enumerate() {
            row_of[row.j] = at;
        }
        self.factors_of(
            &c.pp,
            active,
            |k| {
                let (i, j) = (k % nx, k / nx);
                let at = row_of[j];
                let row = f.rows.get(at)?;
                (i >= row.start && i < row.end && c.ok[k]).then(|| &coefs[at].1[i - row.start])
            },
            flow,
            couette,
        );
        Ok(())
    }
}

fn film_error(e: crate::thermal::film::FilmError) -> Error {
    Error::Solver(format!("film temperature: {e}"))
}

/// The fields of the coupled residual at one state (see `ThermalContact::coupled_fields`).
struct CoupledFields {
    ok: Vec<bool>,
    hh: Vec<f64>,
    pp: Vec<f64>,
    dpdx: Vec<f64>,
    dpdy: Vec<f64>,
    s1: Vec<f64>,
    s2: Vec<f64>,
    /// per frame row, the film's temperature, the surfaces included (cells * nz)
    t: Vec<Vec<f64>>,
}

#[cfg(test)]
mod tests {
    use crate::case::parse_str;
    use crate::run::thermal::contact_for;

    /// The robustness scan's steel ball on a steel flat (docs/thermal.md), here at 1 m/s and
    /// SRR 0.1 under its oil made Newtonian.
    const BALL: &str = include_str!("../../../tests/data/thermal_scan_ball.toml");
    const BALL_SETS: [&str; 2] = [
        "motion.slide_to_roll=0.1",
        "lubricant.rheology=\"newtonian\"",
    ];

    /// The coupled residual of a finite contact has the same root as the update's film-body
    /// iteration, which sweeps the rows along y (each taking the row solved just before it)
    /// where the residual takes every neighbour at the unknowns' temperatures. On a prescribed
    /// pressure (p_h (1 - r^2/a^2), 0.3 GPa, a = 0.2 mm, so that dp/dy drives a side flow) and
    /// a parabolic film (0.5 um at the centre), updates are repeated with a tight film and body
    /// tolerance (1e-9 K), the Reynolds factors of each update's profiles fed into the next
    /// (so that the flux-driven columns end on the pressure's own gradient, the residual's),
    /// until one changes the film by less than 1e-7 K (44 updates, contraction ~0.66 each; the
    /// film 30 K above the inlet). Then the residual's film rows (the film's fixed point,
    /// T - S(T)) and surface rows (T_b - T0 - R_b q_b) are measured at 5.5e-8 and 2.4e-8 K and
    /// the Reynolds factors equal the update's to 3e-11. Asked: 1e-5 K (the updates' own
    /// distance to their fixed point is ~2e-7 K: the last change over 1 - 0.66; a hundred times
    /// that for another machine's rounding) and 1e-6. With the side flow left out of the
    /// residual its film rows are 17 K off and its surface rows 5.5 K (measured): the test sees
    /// the side flow.
    #[test]
    fn the_coupled_residual_vanishes_on_a_settled_finite_film() {
        let sets = BALL_SETS.map(String::from);
        let case = parse_str(BALL, "thermal_scan_ball.toml", &sets).unwrap();
        let (a, hc, ph, r) = (2.0e-4, 5.0e-7, 0.3e9, 0.0127);
        let grid = crate::grid::Grid::new(32, 24, -2.0 * a, 1.2 * a, -1.2 * a, 1.2 * a);
        let mut contact = contact_for(&case, grid).unwrap();
        contact.options.surface_tol = 1e-9;
        contact.options.max_surface_iterations = 40;
        contact.options.line.tol = 1e-9;
        contact.options.line.max_iter = 60;
        let n = grid.len();
        let (p, h) = crate::thermal::contact::tests::hertzian_fields(grid, a, ph, hc, r);
        let active = vec![true; n];
        let (mut flow, mut couette) = (vec![1.0; n], vec![1.0; n]);
        let mut change = f64::INFINITY;
        let mut updates = 0;
        while change > 1e-7 && updates < 80 {
            change = contact
                .update(&p, &h, &active, Some((&flow, &couette)))
                .unwrap();
            contact.reynolds_factors(&p, &active, &mut flow, &mut couette);
            updates += 1;
        }
        println!("{updates} updates, the last changed the film by {change:.1e} K");
        let frame = contact.coupled_frame().expect("a solved steady film");
        assert!(
            frame.rows.len() > 10,
            "{} rows with a film",
            frame.rows.len()
        );
        let len = contact.coupled_len(&frame);
        let mut x = vec![0.0; len];
        contact.coupled_unknowns(&frame, &mut x);
        let mut res = vec![0.0; len];
        let (mut f2, mut c2) = (vec![0.0; n], vec![0.0; n]);
        contact
            .coupled_residual(&frame, &p, &h, &active, &x, &mut res, &mut f2, &mut c2)
            .unwrap();
        let m = len - 2 * n;
        let worst = |v: &[f64]| v.iter().fold(0.0f64, |w, r| w.max(r.abs()));
        let (film, surfaces) = (worst(&res[..m]), worst(&res[m..]));
        let factors = (0..n).fold(0.0f64, |w, k| {
            w.max((f2[k] / flow[k] - 1.0).abs())
                .max((c2[k] / couette[k] - 1.0).abs())
        });
        let rise = contact.extremes().0 - 313.0;
        println!(
            "rows {}, unknowns {len}: film rows {film:.2e} K, surface rows {surfaces:.2e} K, \
             factors {factors:.2e}, film rise {rise:.1} K",
            frame.rows.len()
        );
        assert!(rise > 1.0, "the film must heat: {rise} K");
        assert!(film < 1e-5 && surfaces < 1e-5, "{film:.2e} {surfaces:.2e}");
        assert!(factors < 1e-6, "{factors:.2e}");
    }
}
