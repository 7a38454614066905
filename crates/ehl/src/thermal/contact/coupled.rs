//! The temperature rows of the coupled steady thermal problem of a line contact: the film's
//! energy equation and both surfaces' moving-heat-source relation as residuals of the film
//! and surface temperatures at a given pressure and film, for the Newton method that solves
//! pressure and temperature together (`crate::ehl::thermal_newton`).
//!
//! The unknowns are the film temperature at the interior collocation points of every cell of
//! the line's film (its extent frozen at the last [`ThermalContact::update`]) and both surface
//! temperatures at every cell. The residuals, in K:
//!
//! * film: T - S(T), S(T) the linear solve of the energy equation with its coefficients
//!   (laws, velocity profiles, heating) taken at T ([`film_energy::solve_line_linear`]): the
//!   film's fixed point, whose root is the converged film;
//! * surfaces: T_b - T0 - R_b q_b, q_b the consistent heat flux from the film into body b
//!   ([`film_energy::line_energy`]) and R_b its moving-heat-source operator (Jaeger).
//!
//! With them come the generalized Reynolds factors of the same profiles, so that the Reynolds
//! rows of the coupled system see the temperatures it solves. The columns take the line's
//! pressure gradient as given (not the flux-driven form of [`ThermalContact::update`]): the two
//! agree where the factors are those of the profiles, which is what the coupled system solves
//! (the flux-driven columns match their flux with the profile the factors are taken from, the
//! one the limiting shear stress capped, and blend the cap in by the same gradient at a
//! settled column: `film_energy`'s `capped_profile`).

use super::*;
use crate::thermal::film_energy::{
    line_coefficients_from, line_energy, solve_line_linear, LineCoefficients,
};

/// The frozen frame of the coupled residual: the film's extent on the line and where its
/// columns' shear-thinning iterations start (the same start every evaluation, so that the
/// residual is a function of the temperatures alone).
#[derive(Debug, Clone)]
pub(crate) struct CoupledFrame {
    /// the film's first cell and one past its last
    start: usize,
    end: usize,
    thinning: Vec<f64>,
    poiseuille: Vec<f64>,
}

impl CoupledFrame {
    /// film cells
    fn cells(&self) -> usize {
        self.end - self.start
    }
}

impl ThermalContact {
    /// The frame of the coupled residual at the last update: `Some` for a steady line contact
    /// (one grid line) whose film was solved, else `None`.
    pub(crate) fn coupled_frame(&self) -> Option<CoupledFrame> {
        if self.grid.ny != 1 || self.step.is_some() {
            return None;
        }
        let s = self.lines[0].as_ref()?;
        let nz = self.nz();
        let start = self.start[0];
        let end = start + s.t.len() / nz;
        if end <= start {
            return None;
        }
        Some(CoupledFrame {
            start,
            end,
            thinning: s.thinning.clone(),
            poiseuille: s.poiseuille.clone(),
        })
    }

    /// Unknowns of the coupled temperature rows: the film's interior points, then both
    /// surfaces.
    pub(crate) fn coupled_len(&self, f: &CoupledFrame) -> usize {
        f.cells() * (self.nz() - 2) + 2 * self.grid.len()
    }

    /// The present temperatures as the coupled unknowns (K).
    pub(crate) fn coupled_unknowns(&self, f: &CoupledFrame, x: &mut [f64]) {
        let nz = self.nz();
        let mut at = 0;
        for i in f.start..f.end {
            for z in 1..nz - 1 {
                x[at] = self.film[0][i * nz + z];
                at += 1;
            }
        }
        for b in 0..2 {
            x[at..at + self.grid.len()].copy_from_slice(&self.surface[b]);
            at += self.grid.len();
        }
    }

    /// Takes the coupled unknowns `x` (K) as the contact's temperatures.
    pub(crate) fn set_coupled(&mut self, f: &CoupledFrame, x: &[f64]) {
        let (nz, n) = (self.nz(), self.grid.len());
        let m = f.cells() * (nz - 2);
        for b in 0..2 {
            self.surface[b].copy_from_slice(&x[m + b * n..m + (b + 1) * n]);
        }
        let mut at = 0;
        for i in f.start..f.end {
            self.film[0][i * nz] = self.surface[0][i];
            for z in 1..nz - 1 {
                self.film[0][i * nz + z] = x[at];
                at += 1;
            }
            self.film[0][i * nz + nz - 1] = self.surface[1][i];
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
        let thick = (0..nx)
            .filter(|&k| active[k] && h[k].is_finite())
            .map(|k| h[k])
            .fold(0.0f64, f64::max)
            .max(1e-6);
        let ok: Vec<bool> = (0..n).map(|k| active[k] && h[k].is_finite()).collect();
        let hh: Vec<f64> = (0..n)
            .map(|k| if ok[k] { h[k].max(1e-9) } else { thick })
            .collect();
        let pp: Vec<f64> = (0..n)
            .map(|k| if ok[k] { p[k].max(0.0) } else { 0.0 })
            .collect();
        let (dpdx, dpdy) = gradients(&g, &pp);
        let m = f.cells() * (nz - 2);
        let (s1, s2) = (x[m..m + n].to_vec(), x[m + n..m + 2 * n].to_vec());
        let mut t = vec![0.0; f.cells() * nz];
        let mut at = 0;
        for (c, i) in (f.start..f.end).enumerate() {
            t[c * nz] = s1[i];
            for z in 1..nz - 1 {
                t[c * nz + z] = x[at];
                at += 1;
            }
            t[c * nz + nz - 1] = s2[i];
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

    /// The film's line of the fields `c`: the columns take the pressure gradient as given.
    fn coupled_line<'a>(&self, f: &CoupledFrame, c: &'a CoupledFields) -> Line<'a> {
        let r = f.start..f.end;
        Line {
            dx: self.grid.dx,
            h: &c.hh[r.clone()],
            p: &c.pp[r.clone()],
            dpdx: &c.dpdx[r.clone()],
            dpdy: &c.dpdy[r.clone()],
            u1: self.u1,
            u2: self.u2,
            t1: &c.s1[r.clone()],
            t2: &c.s2[r],
            t_in: self.t0(),
            poiseuille_flux_x: None,
            transient: None,
            side: None,
        }
    }

    /// The coefficients of the film at the temperatures `t` (the frame's column starts).
    fn coupled_coefficients(
        &self,
        f: &CoupledFrame,
        line: &Line,
        t: &[f64],
    ) -> Result<(LineCoefficients, Vec<FilmProfile>)> {
        let mut opts = self.options.line;
        opts.linearise_heating = false;
        let mut thinning = f.thinning.clone();
        let mut poiseuille = f.poiseuille.clone();
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
        let (nz, n) = (self.nz(), self.grid.len());
        let t0 = self.t0();
        let c = self.coupled_fields(f, p, h, active, x);
        let line = self.coupled_line(f, &c);
        let (coef, profiles) = self.coupled_coefficients(f, &line, &c.t)?;
        let solved = solve_line_linear(&self.rule, &self.oil, &line, &coef).map_err(film_error)?;
        let energy = line_energy(&self.rule, &self.oil, &line, &coef, &solved);
        let mut at = 0;
        for cell in 0..f.cells() {
            for z in 1..nz - 1 {
                r[at] = c.t[cell * nz + z] - solved[cell * nz + z];
                at += 1;
            }
        }
        let m = at;
        let mut q = vec![0.0; n];
        let mut rise = vec![0.0; n];
        for b in 0..2 {
            q.iter_mut().for_each(|v| *v = 0.0);
            let qb = if b == 0 { &energy.q1 } else { &energy.q2 };
            for (cell, i) in (f.start..f.end).enumerate() {
                if c.ok[i] {
                    q[i] = qb[cell];
                }
            }
            self.solids[b].temperature_rise(&q, &mut rise);
            let s = if b == 0 { &c.s1 } else { &c.s2 };
            for k in 0..n {
                r[m + b * n + k] = s[k] - t0 - rise[k];
            }
        }
        self.factors_of(
            &c.pp,
            active,
            |k| (k >= f.start && k < f.end && c.ok[k]).then(|| &profiles[k - f.start]),
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
    /// the film's temperature, the surfaces included (cells * nz)
    t: Vec<f64>,
}
