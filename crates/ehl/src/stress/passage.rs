//! The stress history of a transient run in the material frame of a moving body: what each
//! material point of the body sees while it passes through the contact (issue 12, item 3).
//!
//! # Material frame
//!
//! Body k's surface moves along +x at its speed u_k (m/s). A material point at contact-frame x at
//! time t (t = 0 the steady start of the run) has the body coordinate
//!
//! xi = x - u_k t,
//!
//! so that at t = 0 the two frames coincide; `features[0]`'s centre, if on this body, sits at
//! xi = x_p(0). The body-frame grid has the contact grid's spacing dx and is the contact grid
//! extended against the motion by the travel |u_k| T (T the run's duration):
//! `nx_body = nx + ceil(|u_k| T / dx - 1/2)` columns, each material column within half a cell
//! of the contact grid at some evaluated time of the run (the last, t = T, at the latest). y and z are the contact grid's rows and the window's layers.
//!
//! At an evaluation time t the stress of material point m sits at contact-frame position
//! x = xi_m + u_k t, between contact cells: its tensor is interpolated linearly between the two
//! nearest contact cell centres (componentwise; the derived measures are formed from the
//! interpolated tensor). Within half a cell of the grid's ends the end cell's value is taken;
//! beyond, the point is outside the solved domain and is not sampled at that time (the
//! domain's ends are far from the loaded zone, where the stress is negligible).
//!
//! # Accumulated per material point and layer (bounded memory)
//!
//! Only running accumulators are kept, never the volume history: their size is
//! `nx_body * ny * layers` points times 3 f32 (plus 13 with Dang Van), independent of the
//! number of steps ([`bytes`]).
//!
//! * **max von Mises** over the passage (Pa).
//! * **range of tau_xz** over the passage, max - min (Pa): the orthogonal shear range of
//!   Lundberg & Palmgren (1947); a smooth Hertz line contact gives 2 x 0.250 p0 at z = 0.5 b
//!   (Johnson 1985 sec. 4.2).
//! * **Dang Van** (Dang Van et al. 1989, in *Biaxial and Multiaxial Fatigue*, EGF 3, 459-478):
//!
//!   DV = max_t [ tau_a(t) + alpha sigma_H(t) ] / beta,
//!
//!   sigma_H = (s_xx + s_yy + s_zz)/3 the hydrostatic stress, **tension positive** (the
//!   criterion's own convention: compression lowers the indicator; in a rolling contact sigma_H
//!   is mostly negative), tau_a(t) = Tresca((S(t) - M)) = (l_1 - l_3)/2 of the deviator S(t)
//!   relative to the mid-value M of the passage (the mesoscopic shear). DV > 1: the fatigue
//!   limit is crossed. alpha = 3 tau_w / sigma_w - 3/2 and beta = tau_w from the fully reversed
//!   torsion (tau_w) and bending (sigma_w) fatigue limits.
//!
//!   The mid-value M is the centre of the smallest axis-aligned box enclosing the deviatoric
//!   path, M_c = (max_t S_c + min_t S_c) / 2 per component (the "prismatic hull" centre,
//!   Mamiya, Araujo & Castro 2009, Int. J. Fatigue 31, 1144-1153), in place of Dang Van's centre
//!   of the smallest enclosing hypersphere (Desimone, Bernasconi & Beretta 2006, Wear 260,
//!   567-572, compute that centre for rolling contact); both coincide for a path symmetric
//!   about its centre (reversed shear; a Hertz rolling pass's tau_xz). M is known only once
//!   the passage is over, and the maximum over t needs every instant again: the indicator is
//!   formed in a **second pass** over the same evaluation instants ([`Passage::dang_van_pass`]),
//!   the first pass ([`Passage::accumulate`]) collecting the extremes. The run keeps the surface
//!   loads of each evaluation (f32) for that pass and recomputes the fields
//!   (`crate::run::stress::PassageRun`): exact for the box mid-value, at twice the stress cost
//!   and one surface per evaluation in memory (1/(3 layers) of the volume history). Cheaper
//!   one-pass shortcuts were measured against the full history on a smooth rolling line and
//!   rejected: the tensors at the instants of largest von Mises, tau_xz and sigma_H miss the
//!   maximum by up to 18 % (it falls on the flanks of the passage), and "half-range amplitude +
//!   largest sigma_H" (Crossland-like) overestimates it by up to 60 %.

use super::derived;
use super::field::StressField;
use crate::grid::Grid;
use rayon::prelude::*;
use serde::Serialize;

/// The two parameters of the Dang Van criterion (`fatigue.dang_van`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct DangVan {
    /// alpha (dimensionless) = 3 tau_w / sigma_w - 3/2
    pub alpha: f64,
    /// beta (Pa) = tau_w, the torsion fatigue limit
    pub beta: f64,
}

impl Default for DangVan {
    /// alpha = 0.3 (tau_w / sigma_w = 0.6) and beta = 450 MPa: the values of the case-file
    /// contract (interface.md), an order of magnitude for hardened bearing steel, not a
    /// calibration; set them for the steel at hand.
    fn default() -> Self {
        DangVan {
            alpha: 0.3,
            beta: 4.5e8,
        }
    }
}

/// Running accumulators of one material point: von Mises and tau_xz.
#[derive(Debug, Clone, Copy)]
struct Base {
    vm_max: f32,
    txz_max: f32,
    txz_min: f32,
}

const BASE0: Base = Base {
    vm_max: f32::NEG_INFINITY,
    txz_max: f32::NEG_INFINITY,
    txz_min: f32::INFINITY,
};

/// Running accumulators of one material point for Dang Van: the deviator's extremes per
/// component (first pass) and the indicator (second pass).
#[derive(Debug, Clone, Copy)]
struct Dv {
    dev_max: [f32; 6],
    dev_min: [f32; 6],
    /// max_t [Tresca(S - M) + alpha sigma_H] / beta
    dv: f32,
}

const DV0: Dv = Dv {
    dev_max: [f32::NEG_INFINITY; 6],
    dev_min: [f32::INFINITY; 6],
    dv: f32::NEG_INFINITY,
};

/// Bytes of the accumulators of one body: `points = nx_body * ny * layers`, with or without
/// Dang Van (3 or 3 + 13 f32 per point).
pub fn bytes(points: usize, dang_van: bool) -> f64 {
    let per = std::mem::size_of::<Base>()
        + if dang_van {
            std::mem::size_of::<Dv>()
        } else {
            0
        };
    (points * per) as f64
}

/// Number of body-frame columns for a body moving at `speed` (m/s) during `duration` (s) over a
/// contact grid of `nx` cells of `dx` (m): the contact grid and the columns that come within
/// half a cell of its end cell by the last instant, t = `duration` (always evaluated). With
/// ceil(|u| T / dx) columns added, the first was left half a cell to a cell short of the grid
/// whenever the travel was not near a whole number of cells, a column never sampled (NaN in
/// every map; found by a scan).
pub fn body_columns(nx: usize, dx: f64, speed: f64, duration: f64) -> usize {
    let ext = (speed.abs() * duration / dx - 0.5 - 1e-9).ceil().max(0.0);
    nx + ext as usize
}

/// The passage accumulators of one body.
#[derive(Debug, Clone)]
pub struct Passage {
    /// 1 or 2
    pub body: u8,
    /// u_k, the body's surface speed (m/s)
    pub speed: f64,
    pub dang_van: Option<DangVan>,
    /// the contact grid
    pub grid: Grid,
    /// depths of the window's layers (m)
    pub z: Vec<f64>,
    /// body-frame columns
    pub nx_body: usize,
    /// body-frame column m sits at xi_m = grid.x(0) + (m + offset) dx (cells)
    offset: isize,
    base: Vec<Base>,
    dv: Vec<Dv>,
    /// per column: contact-frame x at the first and last sampled time (NaN: never sampled)
    pub contact_span: Vec<[f64; 2]>,
    /// evaluations accumulated
    pub evaluations: usize,
}

/// The maps of a finished passage, each `(layer * ny + j) * nx_body + m` (Pa; Dang Van
/// dimensionless); NaN where a column was never sampled.
#[derive(Debug, Clone)]
pub struct PassageMaps {
    pub max_von_mises: Vec<f32>,
    pub tau_xz_range: Vec<f32>,
    pub dang_van: Option<Vec<f32>>,
}

impl Passage {
    /// Accumulators for body `body` moving at `speed` (m/s) over `grid` during `duration` (s),
    /// on the window layers `z` (m).
    pub fn new(
        body: u8,
        grid: &Grid,
        speed: f64,
        duration: f64,
        z: &[f64],
        dang_van: Option<DangVan>,
    ) -> Self {
        let nx_body = body_columns(grid.nx, grid.dx, speed, duration);
        let offset = if speed > 0.0 {
            -((nx_body - grid.nx) as isize)
        } else {
            0
        };
        let points = nx_body * grid.ny * z.len();
        Passage {
            body,
            speed,
            dang_van,
            grid: *grid,
            z: z.to_vec(),
            nx_body,
            offset,
            base: vec![BASE0; points],
            dv: if dang_van.is_some() {
                vec![DV0; points]
            } else {
                Vec::new()
            },
            contact_span: vec![[f64::NAN; 2]; nx_body],
            evaluations: 0,
        }
    }

    /// Body coordinate xi (m) of column m.
    pub fn x_body(&self, m: usize) -> f64 {
        self.grid.x(0) + (m as isize + self.offset) as f64 * self.grid.dx
    }

    /// All body coordinates (m).
    pub fn xs_body(&self) -> Vec<f64> {
        (0..self.nx_body).map(|m| self.x_body(m)).collect()
    }

    /// Bytes held by the accumulators ([`bytes`]).
    pub fn memory_bytes(&self) -> f64 {
        bytes(self.base.len(), self.dang_van.is_some())
    }

    /// The columns sampled at time `t` (s): `(c, lo, hi)`, column m at contact cell position
    /// m + c (cells from cell 0's centre) for m in lo..=hi; None when no column is in the grid.
    fn columns_at(&self, t: f64) -> Option<(f64, usize, usize)> {
        let nx = self.grid.nx;
        let c = self.offset as f64 + self.speed * t / self.grid.dx;
        let lo = (-0.5 - c).ceil().max(0.0) as usize;
        let hi_f = (nx as f64 - 0.5 - c).floor();
        if hi_f < 0.0 || lo >= self.nx_body {
            return None;
        }
        let hi = (hi_f as usize).min(self.nx_body - 1);
        (lo <= hi).then_some((c, lo, hi))
    }

    /// First pass: adds the field `field` (on the contact grid, the window's layers) of time
    /// `t` (s) to the von Mises and tau_xz maps and, with Dang Van, to the deviator's extremes.
    pub fn accumulate(&mut self, field: &StressField, t: f64) {
        let (nx, ny, nxb) = (self.grid.nx, self.grid.ny, self.nx_body);
        assert_eq!(
            (field.nx, field.ny, field.z.len()),
            (nx, ny, self.z.len()),
            "passage field shape"
        );
        let Some((c, lo, hi)) = self.columns_at(t) else {
            return;
        };
        for m in lo..=hi {
            let x = self.x_body(m) + self.speed * t;
            let span = &mut self.contact_span[m];
            if span[0].is_nan() {
                span[0] = x;
            }
            span[1] = x;
        }
        let comps = &field.components;
        let work = |row: usize, base: &mut [Base], dv: Option<&mut [Dv]>| {
            let mut dv = dv;
            for m in lo..=hi {
                let s = sample(comps, nx, row, m as f64 + c);
                let vm = derived::von_mises(&s) as f32;
                let txz = s[4] as f32;
                let b = &mut base[m];
                b.vm_max = b.vm_max.max(vm);
                b.txz_max = b.txz_max.max(txz);
                b.txz_min = b.txz_min.min(txz);
                if let Some(dv) = dv.as_deref_mut() {
                    let d = &mut dv[m];
                    let dev = deviator(&s);
                    for q in 0..6 {
                        d.dev_max[q] = d.dev_max[q].max(dev[q] as f32);
                        d.dev_min[q] = d.dev_min[q].min(dev[q] as f32);
                    }
                }
            }
        };
        let min_len = (4096 / nxb).max(1);
        if self.dang_van.is_some() {
            self.base
                .par_chunks_mut(nxb)
                .zip(self.dv.par_chunks_mut(nxb))
                .enumerate()
                .with_min_len(min_len)
                .for_each(|(row, (b, d))| work(row, b, Some(d)));
        } else {
            self.base
                .par_chunks_mut(nxb)
                .enumerate()
                .with_min_len(min_len)
                .for_each(|(row, b)| work(row, b, None));
        }
        self.evaluations += 1;
    }

    /// Second pass (Dang Van only; after every [`Self::accumulate`]): the same field of time `t`
    /// again, now with the mid-value M of each point known: DV = max over the instants of
    /// [Tresca(S - M) + alpha sigma_H] / beta.
    pub fn dang_van_pass(&mut self, field: &StressField, t: f64) {
        let Some(p) = self.dang_van else {
            return;
        };
        let (nx, ny, nxb) = (self.grid.nx, self.grid.ny, self.nx_body);
        assert_eq!(
            (field.nx, field.ny, field.z.len()),
            (nx, ny, self.z.len()),
            "passage field shape"
        );
        let Some((c, lo, hi)) = self.columns_at(t) else {
            return;
        };
        let comps = &field.components;
        self.dv
            .par_chunks_mut(nxb)
            .enumerate()
            .with_min_len((4096 / nxb).max(1))
            .for_each(|(row, dv)| {
                for m in lo..=hi {
                    let s = sample(comps, nx, row, m as f64 + c);
                    let d = &mut dv[m];
                    let mid: [f64; 6] =
                        std::array::from_fn(|q| 0.5 * (d.dev_max[q] as f64 + d.dev_min[q] as f64));
                    let v = indicator(&s, &mid, &p) as f32;
                    d.dv = d.dv.max(v);
                }
            });
    }

    /// The maps over the passage so far.
    pub fn maps(&self) -> PassageMaps {
        let finite = |v: f32| if v.is_finite() { v } else { f32::NAN };
        let max_von_mises = self.base.iter().map(|b| finite(b.vm_max)).collect();
        let tau_xz_range = self
            .base
            .iter()
            .map(|b| finite(b.txz_max - b.txz_min))
            .collect();
        let dang_van = self
            .dang_van
            .map(|_| self.dv.iter().map(|d| finite(d.dv)).collect());
        PassageMaps {
            max_von_mises,
            tau_xz_range,
            dang_van,
        }
    }
}

/// The tensor (Voigt, f64) at contact position `s` (cells from cell 0's centre) of `row`
/// (`layer * ny + j`): linear between the two nearest cell centres, the end cell's value
/// within half a cell beyond them.
#[inline]
fn sample(comps: &[Vec<f32>; 6], nx: usize, row: usize, s: f64) -> [f64; 6] {
    let s = s.clamp(0.0, (nx - 1) as f64);
    let i0 = (s.floor() as usize).min(nx.saturating_sub(2));
    let w = if nx > 1 { s - i0 as f64 } else { 0.0 };
    let i1 = (i0 + 1).min(nx - 1);
    let (k0, k1) = (row * nx + i0, row * nx + i1);
    std::array::from_fn(|q| {
        let a = comps[q][k0] as f64;
        a + w * (comps[q][k1] as f64 - a)
    })
}

/// The deviator of a tensor (Voigt).
#[inline]
fn deviator(s: &[f64; 6]) -> [f64; 6] {
    let h = derived::hydrostatic(s);
    [s[0] - h, s[1] - h, s[2] - h, s[3], s[4], s[5]]
}

/// [Tresca(S - M) + alpha sigma_H] / beta of one instant: `s` the stress, `mid` the deviator's
/// mid-value M.
#[inline]
fn indicator(s: &[f64; 6], mid: &[f64; 6], p: &DangVan) -> f64 {
    let d = deviator(s);
    let rel: [f64; 6] = std::array::from_fn(|q| d[q] - mid[q]);
    (derived::max_shear(&rel) + p.alpha * derived::hydrostatic(s)) / p.beta
}

/// Dang Van over a whole stored history of tensors (Voigt, Pa), box mid-value: the reference
/// the two-pass accumulator is checked against (tests); a run never holds the history.
pub fn dang_van_of_history(history: &[[f64; 6]], p: &DangVan) -> f64 {
    let mut lo = [f64::INFINITY; 6];
    let mut hi = [f64::NEG_INFINITY; 6];
    for s in history {
        let d = deviator(s);
        for q in 0..6 {
            lo[q] = lo[q].min(d[q]);
            hi[q] = hi[q].max(d[q]);
        }
    }
    let mid: [f64; 6] = std::array::from_fn(|q| 0.5 * (lo[q] + hi[q]));
    history
        .iter()
        .map(|s| indicator(s, &mid, p))
        .fold(f64::NEG_INFINITY, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A standing body (u = 0) on a 1-cell, 1-layer grid: the accumulators see the tensors
    /// exactly as given.
    fn point(history: &[[f64; 6]], p: DangVan) -> (PassageMaps, usize) {
        let grid = Grid::new(1, 1, -0.5, 0.5, -0.5, 0.5);
        let mut acc = Passage::new(1, &grid, 0.0, 1.0, &[1.0], Some(p));
        let field = |s: &[f64; 6]| StressField {
            nx: 1,
            ny: 1,
            z: vec![1.0],
            components: std::array::from_fn(|q| vec![s[q] as f32]),
        };
        for (n, s) in history.iter().enumerate() {
            acc.accumulate(&field(s), n as f64);
        }
        for (n, s) in history.iter().enumerate() {
            acc.dang_van_pass(&field(s), n as f64);
        }
        (acc.maps(), acc.memory_bytes() as usize)
    }

    /// Pure reversed shear tau_xz = tau_a sin(w t), no hydrostatic stress: the box mid-value is
    /// 0, the mesoscopic shear amplitude tau_a, so DV = tau_a / beta exactly (to f32 storage of
    /// the tensor, 6e-8 relative); the range of tau_xz is 2 tau_a, the von Mises maximum
    /// sqrt(3) tau_a.
    #[test]
    fn reversed_shear_gives_tau_a_over_beta() {
        let tau_a = 3.0e8;
        let p = DangVan {
            alpha: 0.3,
            beta: 4.5e8,
        };
        let history: Vec<[f64; 6]> = (0..=40)
            .map(|n| {
                let w = 2.0 * std::f64::consts::PI * n as f64 / 40.0;
                [0.0, 0.0, 0.0, 0.0, tau_a * w.sin(), 0.0]
            })
            .collect();
        let (maps, _) = point(&history, p);
        let dv = maps.dang_van.unwrap()[0] as f64;
        assert!((dv - tau_a / p.beta).abs() < 1e-6 * dv, "{dv}");
        assert!((dv - dang_van_of_history(&history, &p)).abs() < 1e-6 * dv);
        assert!((maps.tau_xz_range[0] as f64 - 2.0 * tau_a).abs() < 1e-6 * tau_a);
        assert!((maps.max_von_mises[0] as f64 - 3f64.sqrt() * tau_a).abs() < 1e-6 * tau_a);
    }

    /// A pulsating compression (hydrostatic and deviatoric): the hydrostatic term enters with
    /// its sign (tension positive): the maximum is at the unloaded instant (sigma_H = 0), not
    /// at the peak, and the two-pass accumulator agrees with the whole history.
    #[test]
    fn hydrostatic_term_has_the_criterion_sign() {
        let p = DangVan {
            alpha: 0.5,
            beta: 1.0,
        };
        // s = -q (1, 1, 3)/... with q from 0 to 1: mean -5q/3, deviator q(2/3, 2/3, -4/3)
        let history: Vec<[f64; 6]> = (0..=10)
            .map(|n| {
                let q = n as f64 / 10.0;
                [-q, -q, -3.0 * q, 0.0, 0.0, 0.0]
            })
            .collect();
        let exact = dang_van_of_history(&history, &p);
        let (maps, _) = point(&history, p);
        let dv = maps.dang_van.unwrap()[0] as f64;
        // mid = deviator at q = 1/2; at q = 0: Tresca of -(1/2)(2/3, 2/3, -4/3) = 1/2, sigma_H = 0
        assert!((exact - 0.5).abs() < 1e-12, "{exact}");
        assert!((dv - exact).abs() < 1e-6, "{dv} vs {exact}");
    }

    /// The accumulators' size depends on the grid and the layers only, not on the steps.
    #[test]
    fn memory_does_not_grow_with_the_steps() {
        let p = DangVan::default();
        let short = point(&[[1.0; 6]; 3], p).1;
        let long = point(&vec![[1.0; 6]; 3000], p).1;
        assert_eq!(short, long);
        assert_eq!(short, bytes(1, true) as usize);
    }

    /// The squared tensor norm S : S of a deviator difference (Voigt: shear terms twice).
    fn norm2(a: &[f64; 6], b: &[f64; 6]) -> f64 {
        (0..6)
            .map(|q| {
                let d = a[q] - b[q];
                if q < 3 {
                    d * d
                } else {
                    2.0 * d * d
                }
            })
            .sum()
    }

    /// The centre of the smallest ball enclosing `points` in the tensor norm, by Badoiu &
    /// Clarkson's iteration (2003): step towards the farthest point by 1/(k + 1). After K
    /// steps the radius is within R / sqrt(K) of the smallest (a reference for the tests, not
    /// a solver: 2e5 steps).
    fn enclosing_ball(points: &[[f64; 6]]) -> ([f64; 6], f64) {
        let mut c = points[0];
        for k in 1..=100_000usize {
            let far = points
                .iter()
                .max_by(|a, b| norm2(a, &c).total_cmp(&norm2(b, &c)))
                .unwrap();
            let w = 1.0 / (k as f64 + 1.0);
            for q in 0..6 {
                c[q] += w * (far[q] - c[q]);
            }
        }
        let r = points
            .iter()
            .map(|p| norm2(p, &c))
            .fold(0.0f64, f64::max)
            .sqrt();
        (c, r)
    }

    /// How far the box mid-value used for Dang Van's mesoscopic stress (the centre of the
    /// smallest axis-aligned box around the deviatoric path) is from Dang Van's own, the
    /// centre of the smallest enclosing hypersphere, on the paths the solver meets: material
    /// points passing under a Hertz line contact (McEwen / Smith & Liu closed form, 401
    /// samples from x = -4b to 4b), at depths 0.25 to 1 b, frictionless and with a traction
    /// mu = 0.1 and 0.3 (alpha = 0.3, beta = p0 / 2).
    ///
    /// First the reference itself: the ball of a circular shear path (tau_xz, tau_xy) =
    /// tau_a (cos, sin) is centred at 0 with radius sqrt(2) tau_a in the tensor norm, and a
    /// segment's at its middle (both within 1e-3). On the Hertz paths the reference is good
    /// to about 1 % (2001 samples and 2e5 steps moved its indicator by at most 0.7 %).
    ///
    /// Measured: the box's indicator is the larger everywhere, by 8.6-10.0 % frictionless,
    /// 1.7-6.5 % at mu = 0.1 and 0.1-2.3 % at mu = 0.3, the gap growing with depth. The
    /// rolling path leaves the origin (far from the contact) to a compressive extreme and
    /// back, with the shear reversing on the way: the box centres it at half the compressive
    /// extreme, the ball nearer the middle of the loop. Asserted: the box's indicator at least
    /// the ball's less 1 % (the reference's accuracy) and at most 12 % above it. So the box
    /// mid-value in use is a conservative stand-in, up to 10 % high on a smooth rolling pass;
    /// docs/stress.md says so.
    #[test]
    fn box_mid_value_against_the_enclosing_hypersphere_on_hertz_passes() {
        let circle: Vec<[f64; 6]> = (0..360)
            .map(|d| {
                let t = (d as f64).to_radians();
                [0.0, 0.0, 0.0, 0.0, t.cos(), t.sin()]
            })
            .collect();
        let (c, r) = enclosing_ball(&circle);
        assert!(
            c.iter().all(|v| v.abs() < 1e-3) && (r - 2f64.sqrt()).abs() < 1e-3,
            "{c:?} {r}"
        );
        let segment = [
            [1.0, -0.5, -0.5, 0.0, 0.0, 0.0],
            [-1.0, 0.5, 0.5, 0.0, 2.0, 0.0],
        ];
        let (c, _) = enclosing_ball(&segment);
        let mid = [0.0, 0.0, 0.0, 0.0, 1.0, 0.0];
        assert!(norm2(&c, &mid).sqrt() < 1e-3, "{c:?}");

        let (b, p0, nu) = (1.0, 1.0, 0.3);
        let p = DangVan {
            alpha: 0.3,
            beta: 0.5 * p0,
        };
        for mu in [0.0, 0.1, 0.3] {
            for z in [0.25, 0.5, 0.786, 1.0] {
                let history: Vec<[f64; 6]> = (0..=400)
                    .map(|i| {
                        let x = -4.0 * b + 8.0 * b * i as f64 / 400.0;
                        crate::reference::subsurface::hertz_line_stress(x, z * b, b, p0, mu, nu)
                    })
                    .collect();
                let boxed = dang_van_of_history(&history, &p);
                let devs: Vec<[f64; 6]> = history.iter().map(deviator).collect();
                let (centre, _) = enclosing_ball(&devs);
                let ball = history
                    .iter()
                    .map(|s| indicator(s, &centre, &p))
                    .fold(f64::NEG_INFINITY, f64::max);
                let rel = (boxed - ball) / ball;
                let pct = 100.0 * rel;
                eprintln!(
                    "mu {mu}, z {z} b: DV box {boxed:.4}, hypersphere {ball:.4} ({pct:+.2} %)"
                );
                assert!(
                    rel > -0.01 && rel < 0.12,
                    "mu {mu}, z {z}: {boxed} against {ball}"
                );
            }
        }
    }
}
