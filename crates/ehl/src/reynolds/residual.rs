//! The discrete compressible Reynolds equation on the cell grid, in the dimensionless form of
//! Venner & Lubrecht (*Multilevel Methods in Lubrication*, 2000, ch. 4 and 8):
//!
//! ```text
//!   d/dX (eps dP/dX) + d/dY (eps dP/dY) - d(rho H)/dX - d(rho H)/dT = f        (thesis eq. 2.1, 3.1)
//!   eps = rho H^3 / (eta lambda),   lambda = 12 u_e eta0 R^2 / (b^3 p_h)
//! ```
//!
//! with X = x/b, Y = y/b, P = p/p_h, H = h R/b^2, rho = rho/rho0, eta = eta/eta0 and the time
//! scaled by b/u_e (T = t u_e / b). `f` is a right-hand side (zero for the
//! plain equation).
//!
//! Finite volumes on the cell grid: each cell balances the mass fluxes through its four faces.
//! * Poiseuille: `eps` at a face is the arithmetic mean of the two cells (Venner & Lubrecht);
//!   at the edge of the domain (and next to a cell without material, gap = inf) the pressure is
//!   ambient (P = 0) *on the face*, half a cell from the centre.
//! * Couette (wedge): the face value of rho H is taken upwind, second order
//!   (`1.5 q_i - 0.5 q_{i-1}`, which gives the classical `(3 q_i - 4 q_{i-1} + q_{i-2}) / (2 dX)`),
//!   first order where the second upstream cell is missing; the inlet face takes the first cell's
//!   value (zero gradient into the domain). With `ReynoldsGrid::second_order = false` the rule is
//!   first order everywhere (`q_{i-1}` on the west face, `(q_i - q_{i-1}) / dX`), as in EHL-FBNS
//!   (Hansen et al., Tribol. Lett. 70 (2022) 80); the case key `solver.wedge_upwind_order = 1`
//!   selects it. It is more diffusive: +9 % central film on the EHL-FBNS ball at 129^2 against
//!   the second-order rule, the two converging toward each other with the grid.
//!
//! Written as fluxes, the sum of the cell residuals over any set of cells is the net flow through
//! the set's boundary, which is how [`mass_flow`] measures inflow, outflow and side leakage.
//!
//! **Squeeze term** (transient runs, thesis eq. 3.1 with d(rho H)/dT kept whole): with
//! [`Transient`] `{ c0, history }` each cell adds `c0 (rho H)_k - history_k` to its flow balance,
//! the BDF rule of the time loop (`ehl::transient`): backward Euler c0 = 1/dT, history =
//! (rho H)^{n-1}/dT; BDF2 c0 = 3/(2 dT), history = (4 (rho H)^{n-1} - (rho H)^{n-2})/(2 dT).
//! A surface feature moving with its body changes only the film H the caller passes in.

/// Dimensionless grid for the Reynolds operator: `nx * ny` cells of size `dx * dy` (in b).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReynoldsGrid {
    pub nx: usize,
    pub ny: usize,
    pub dx: f64,
    pub dy: f64,
    /// second-order upwind Couette term (else first order)
    pub second_order: bool,
}

/// The squeeze term d(rho H)/dT of a time step, written as `c0 (rho H)_k - history_k` with the
/// earlier levels folded into `history` (T = t u_e / b, the dimensionless time):
///
/// * backward Euler (BDF1): c0 = 1/dT, history = (rho H)^{n-1} / dT;
/// * BDF2 (constant step): c0 = 3/(2 dT), history = (4 (rho H)^{n-1} - (rho H)^{n-2}) / (2 dT).
///
/// Thesis eq. 3.1 keeps d(rho h)/dt whole here: the density's time variation and the film's
/// (elastic and rigid, h0) are in it, not only the pit's motion (eq. 3.2-3.3), so that the
/// discrete equation conserves mass.
#[derive(Debug, Clone, Copy)]
pub struct Transient<'a> {
    pub c0: f64,
    pub history: &'a [f64],
}

/// The per-cell state the operator needs. `active[k] == false` marks a cell without material
/// (gap = inf): P = 0 there, and it acts as an ambient boundary for its neighbours.
#[derive(Debug, Clone, Copy)]
pub struct Fields<'a> {
    pub p: &'a [f64],
    pub rho: &'a [f64],
    pub h: &'a [f64],
    pub eps: &'a [f64],
    pub active: &'a [bool],
}

/// Upwind Couette face value of rho H on the inlet (west) face of cell `(i, j)`.
#[inline]
pub(crate) fn couette_west(g: &ReynoldsGrid, f: &Fields, i: usize, j: usize) -> f64 {
    let k = j * g.nx + i;
    let q = |k: usize| f.rho[k] * f.h[k];
    if i == 0 || !f.active[k - 1] {
        // inlet face: zero gradient
        q(k)
    } else if !g.second_order || i == 1 || !f.active[k - 2] {
        q(k - 1)
    } else {
        1.5 * q(k - 1) - 0.5 * q(k - 2)
    }
}

/// Upwind Couette face value of rho H on the outlet (east) face of cell `(i, j)`.
#[inline]
pub(crate) fn couette_east(g: &ReynoldsGrid, f: &Fields, i: usize, j: usize) -> f64 {
    let k = j * g.nx + i;
    let q = |k: usize| f.rho[k] * f.h[k];
    if !g.second_order || i == 0 || !f.active[k - 1] {
        q(k)
    } else {
        1.5 * q(k) - 0.5 * q(k - 1)
    }
}

/// Derivative of the Couette term `(east - west) / dX` of cell `(i, j)` with respect to
/// `q = rho H` of the cells `k`, `k - 1`, `k - 2` (same upwind rules as [`couette_east`] and
/// [`couette_west`]): the wedge part of the Jacobian row.
#[inline]
pub(crate) fn couette_stencil(g: &ReynoldsGrid, active: &[bool], i: usize, j: usize) -> [f64; 3] {
    let k = j * g.nx + i;
    let mut a = [0.0; 3];
    let first_cell = i == 0 || !active[k - 1];
    if !g.second_order || first_cell {
        a[0] += 1.0;
    } else {
        a[0] += 1.5;
        a[1] -= 0.5;
    }
    if first_cell {
        a[0] -= 1.0;
    } else if !g.second_order || i == 1 || !active[k - 2] {
        a[1] -= 1.0;
    } else {
        a[1] -= 1.5;
        a[2] += 0.5;
    }
    [a[0] / g.dx, a[1] / g.dx, a[2] / g.dx]
}

/// Poiseuille coefficient of the face between cell `k` and its neighbour `n` (None: domain edge),
/// divided by the squared distance to where the neighbour's pressure sits; returns
/// `(coefficient, neighbour pressure)`.
#[inline]
pub(crate) fn face(f: &Fields, k: usize, n: Option<usize>, d2: f64) -> (f64, f64) {
    match n {
        Some(n) if f.active[n] => (0.5 * (f.eps[k] + f.eps[n]) / d2, f.p[n]),
        // ambient pressure on the face, half a cell away
        _ => (2.0 * f.eps[k] / d2, 0.0),
    }
}

/// Neighbour indices (west, east, south, north) of cell `(i, j)`, None at the domain edge.
#[inline]
pub(crate) fn neighbours(g: &ReynoldsGrid, i: usize, j: usize) -> [Option<usize>; 4] {
    let k = j * g.nx + i;
    [
        (i > 0).then(|| k - 1),
        (i + 1 < g.nx).then(|| k + 1),
        (j > 0).then(|| k - g.nx),
        (j + 1 < g.ny).then(|| k + g.nx),
    ]
}

/// L(P) at one active cell: Poiseuille minus Couette (minus squeeze), per unit area.
#[inline]
pub(crate) fn operator_at(
    g: &ReynoldsGrid,
    f: &Fields,
    transient: Option<&Transient>,
    i: usize,
    j: usize,
) -> f64 {
    let k = j * g.nx + i;
    let nb = neighbours(g, i, j);
    let (dx2, dy2) = (g.dx * g.dx, g.dy * g.dy);
    let pk = f.p[k];
    let mut pois = 0.0;
    for (d, &n) in nb.iter().enumerate() {
        if d >= 2 && g.ny == 1 {
            break;
        }
        let (c, pn) = face(f, k, n, if d < 2 { dx2 } else { dy2 });
        pois += c * (pn - pk);
    }
    let couette = (couette_east(g, f, i, j) - couette_west(g, f, i, j)) / g.dx;
    let squeeze = transient.map_or(0.0, |t| t.c0 * f.rho[k] * f.h[k] - t.history[k]);
    pois - couette - squeeze
}

/// Residual r = rhs - L(P) of the discrete Reynolds equation on every cell (0 on inactive cells).
/// `rhs` is None for the plain equation (f = 0). Cells with P = 0 are included: the caller
/// decides how to treat cavitated cells (complementarity: P >= 0, r <= 0 there... see solver).
pub fn residual(
    g: &ReynoldsGrid,
    f: &Fields,
    rhs: Option<&[f64]>,
    transient: Option<&Transient>,
    out: &mut [f64],
) {
    use rayon::prelude::*;
    out.par_chunks_mut(g.nx)
        .with_min_len(crate::elastic::operator::min_len(g.nx))
        .enumerate()
        .for_each(|(j, row)| {
            for (i, o) in row.iter_mut().enumerate() {
                let k = j * g.nx + i;
                *o = if f.active[k] {
                    rhs.map_or(0.0, |r| r[k]) - operator_at(g, f, transient, i, j)
                } else {
                    0.0
                };
            }
        });
}

/// Dimensionless mass flows (rho H u / (u_e) per unit dimensionless width, integrated over the
/// boundary; multiply by rho0 u_e b^3/R for kg/s) through the boundary of the pressurised
/// region (the active cells with P > 0):
///
/// * `inflow`: through the inlet faces (x_min) of pressurised cells;
/// * `outflow`: through the outlet faces (x_max) and into cavitated cells (P = 0) along x;
/// * `side_leakage`: through faces along y into ambient (domain edge, cells without material,
///   or cavitated cells).
///
/// Because the discretisation is conservative, inflow - outflow - side_leakage equals the sum
/// of the residuals over the pressurised cells (times the cell area), so it vanishes as the
/// solver converges: the mass balance test.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct MassFlow {
    pub inflow: f64,
    pub outflow: f64,
    pub side_leakage: f64,
}

/// Mass flows of the steady equation (see [`MassFlow`]).
pub fn mass_flow(g: &ReynoldsGrid, f: &Fields) -> MassFlow {
    let mut m = MassFlow::default();
    let wet = |k: usize| f.active[k] && f.p[k] > 0.0;
    let (dx2, dy2) = (g.dx * g.dx, g.dy * g.dy);
    // line contact: a 1 m reference length is dY = dy, the flows are per that width
    for j in 0..g.ny {
        for i in 0..g.nx {
            let k = j * g.nx + i;
            if !wet(k) {
                continue;
            }
            let nb = neighbours(g, i, j);
            let pk = f.p[k];
            // x faces: flux = q_couette - eps dP/dX, positive along +x
            let west_out = match nb[0] {
                Some(n) if wet(n) => None,
                _ => {
                    let (c, pn) = face(f, k, nb[0], dx2);
                    // flux entering through the west face (along +x)
                    Some(couette_west(g, f, i, j) - c * g.dx * (pk - pn))
                }
            };
            if let Some(q) = west_out {
                if i == 0 {
                    m.inflow += q * g.dy;
                } else {
                    m.outflow -= q * g.dy;
                }
            }
            if !matches!(nb[1], Some(n) if wet(n)) {
                let (c, pn) = face(f, k, nb[1], dx2);
                let q = couette_east(g, f, i, j) - c * g.dx * (pn - pk);
                m.outflow += q * g.dy;
            }
            if g.ny > 1 {
                for d in 2..4 {
                    if !matches!(nb[d], Some(n) if wet(n)) {
                        let (c, pn) = face(f, k, nb[d], dy2);
                        // flux leaving through this y face
                        m.side_leakage += -c * g.dy * (pn - pk) * g.dx;
                    }
                }
            }
        }
    }
    m
}
