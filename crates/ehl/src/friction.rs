//! Shear stress at the surfaces (thesis eq. 3.8) and the friction integral (eq. 3.5, 3.9, 3.10).
//!
//! # Physics and sign convention
//!
//! Body 1 is the lower surface (z = 0, speed `u1` along +x), body 2 the upper one (z = h, speed
//! `u2`); the rolling direction is +x (inlet at negative x). The isothermal Newtonian velocity
//! across the film is (thesis eq. 3.7)
//!
//! u(z) = (1 / 2 eta) dp/dx (z^2 - z h) + (1 - z/h) u1 + (z/h) u2,
//!
//! and the x-component of the shear force per unit area that the film exerts on the surface of
//! **body 2**, positive along +x, is
//!
//! tau = -(h/2) dp/dx + eta (u1 - u2) / h          (Pa)
//!
//! (the film's stress eta du/dz at z = h, with the sign of the force on the wall above it). This
//! is the integrand of thesis eq. 3.9, whose pressure term is written (h/2)(P_i - P_{i+1})/dx =
//! -(h/2) dp/dx; eq. 3.8 as printed carries the opposite sign on the pressure term. With this
//! convention a positive slide-to-roll ratio (u1 > u2: body 1 faster) gives a positive friction
//! force: the faster body 1 drags body 2 forward and is itself held back by the same Couette
//! force. The pressure-flow (Poiseuille) part -(h/2) dp/dx acts with the same sign on both
//! surfaces (it is balanced by the x-component of the pressure on the inclined surfaces); it is
//! reported separately as [`Friction::poiseuille_force`] and is the rolling-resistance part.
//!
//! # Non-Newtonian fluids
//!
//! For a Carreau or Eyring fluid, with or without a limiting shear stress
//! ([`crate::lubricant::rheology`]), the sliding (Couette) part is evaluated from the rheology at
//! the mean sliding shear rate gamma_dot = (u1 - u2) / h:
//!
//! tau_C = tau_rheology(eta(p), (u1 - u2) / h, p),
//!
//! and the pressure-flow part is kept as the Newtonian -(h/2) dp/dx. This is the usual simplified
//! "Couette-dominated" approximation of EHL traction: it neglects the interaction between the
//! pressure-flow shear and the sliding shear across the film (exact for a Newtonian fluid; for a
//! shear-thinning fluid it is accurate where sliding dominates, i.e. in the high-pressure zone
//! that carries most of the traction). The limiting shear stress caps the Couette part only.
//!
//! # Discretisation (thesis eq. 3.9, with these choices)
//!
//! F_f = sum over cells of tau_ij dx dy (the thesis' eq. 3.9 leaves out the cell area), and
//! f = F_f / F (eq. 3.10), F the applied load (N; for an infinite line contact N/m, with the
//! grid's 1 m reference length dy so that the sum is per unit length too).
//!
//! * dp/dx by central differences (second order; the thesis uses a forward difference, first
//!   order and shifted by dx/2), one-sided at the first and last column, zero when nx = 1.
//!   Negative pressure is treated as ambient (p = 0), as in the lubricant laws.
//! * The Couette part is summed over the **pressurised cells (p > 0)**: there the film is full.
//!   Cells at zero pressure are cavitated (the complementarity model p >= 0 gives no fill
//!   fraction, the film is ruptured into streamers) or ambient; they carry no Couette stress. The
//!   thesis sums over all cells, which counts the cavitated region as a full film; the difference
//!   is of order eta0 (u1 - u2) / h over the outlet, small beside the contact's traction (and
//!   zero with a limiting shear stress, since tau_L = Lambda * 0 there).
//! * The Poiseuille part is summed over **every cell with a finite film**: dp/dx vanishes where
//!   the pressure is uniformly zero, and keeping the unpressurised cells next to the pressurised
//!   zone makes the discrete sum equal, by summation by parts, to (1/2) sum p dh/dx dx dy, the
//!   discrete form of the identity int -(h/2) dp/dx dA = (1/2) int p dh/dx dA (p = 0 on the
//!   boundary).
//! * Film rules (never NaN): a cell with h = +inf (no opposing surface, e.g. beyond a roller end)
//!   carries no stress. A cell with h <= 0 carries no pressure-flow stress (h is taken as 0). A
//!   pressurised cell with h <= 0 and sliding has the h -> 0+ limit of the Couette stress: the
//!   limiting shear stress Lambda p when the rheology has one (boundary-friction-like); without a
//!   limit that limit is infinite and [`friction`] returns an error. NaN in any field, a
//!   non-finite pressure or viscosity, non-finite speeds or a load that is not positive and
//!   finite are errors too.
//!
//! Whether the underlying EHL solution converged is the caller's business: a friction figure
//! from a non-converged solution must be flagged where it is reported.

use crate::case::Rheology;
use crate::grid::Grid;
use crate::lubricant::rheology;
use crate::{Error, Result};

/// Slide-to-roll ratio SRR = (u1 - u2) / u_e with u_e = (u1 + u2)/2 (thesis eq. 3.4);
/// `None` when u1 + u2 == 0 (no entrainment).
pub fn slide_to_roll(u1: f64, u2: f64) -> Option<f64> {
    let ue = 0.5 * (u1 + u2);
    if ue == 0.0 {
        None
    } else {
        Some((u1 - u2) / ue)
    }
}

/// Surface speeds (u1, u2) (m/s) for the entrainment speed `ue` = (u1 + u2)/2 (m/s) and the
/// slide-to-roll ratio `srr` (eq. 3.4): u1 = ue (1 + srr/2), u2 = ue (1 - srr/2).
pub fn surface_speeds(ue: f64, srr: f64) -> (f64, f64) {
    (ue * (1.0 + 0.5 * srr), ue * (1.0 - 0.5 * srr))
}

/// The fields and conditions the friction integral needs. All fields are row-major on `grid`
/// (`j * nx + i`), SI units.
#[derive(Debug, Clone, Copy)]
pub struct FrictionInput<'a> {
    pub grid: &'a Grid,
    /// pressure p (Pa)
    pub pressure: &'a [f64],
    /// film thickness h (m); +inf where there is no opposing surface
    pub film: &'a [f64],
    /// low-shear viscosity eta(p) (Pa s), e.g. from [`crate::lubricant::viscosity::viscosity`]
    pub viscosity: &'a [f64],
    /// surface speed of body 1 (lower surface, z = 0) along +x (m/s)
    pub u1: f64,
    /// surface speed of body 2 (upper surface, z = h) along +x (m/s)
    pub u2: f64,
    pub rheology: &'a Rheology,
    /// applied normal load F (N; for an infinite line contact N/m)
    pub load: f64,
}

/// Friction force on body 2 along +x and its parts (see the module documentation for the sign
/// convention). Forces in N (for an infinite line contact, N/m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Friction {
    /// F_f = couette_force + poiseuille_force (eq. 3.5, 3.9)
    pub force: f64,
    /// f = F_f / F (eq. 3.10)
    pub coefficient: f64,
    /// sum of the sliding part tau_C dx dy over the pressurised cells
    pub couette_force: f64,
    /// sum of the pressure-flow part -(h/2) dp/dx dx dy over the cells with a finite film
    pub poiseuille_force: f64,
}

/// Surface shear stress on body 2 (Pa), per cell: (Couette part, Poiseuille part), following the
/// rules of the module documentation.
fn cell_stresses(input: &FrictionInput) -> Result<Vec<(f64, f64)>> {
    let g = input.grid;
    let n = g.len();
    for (name, field) in [
        ("pressure", input.pressure),
        ("film", input.film),
        ("viscosity", input.viscosity),
    ] {
        if field.len() != n {
            return Err(Error::Solver(format!(
                "friction: {name} has {} values, the grid has {n} cells",
                field.len()
            )));
        }
    }
    if !(input.u1.is_finite() && input.u2.is_finite()) {
        return Err(Error::Solver(format!(
            "friction: surface speeds must be finite (u1 = {}, u2 = {})",
            input.u1, input.u2
        )));
    }
    let cell_name = |k: usize| {
        let (i, j) = (k % g.nx, k / g.nx);
        format!(
            "cell ({i}, {j}) at x = {:.4e} m, y = {:.4e} m",
            g.x(i),
            g.y(j)
        )
    };
    for k in 0..n {
        if !input.pressure[k].is_finite()
            || !input.viscosity[k].is_finite()
            || input.film[k].is_nan()
        {
            return Err(Error::Solver(format!(
                "friction: invalid field value in {} (p = {}, h = {}, eta = {})",
                cell_name(k),
                input.pressure[k],
                input.film[k],
                input.viscosity[k]
            )));
        }
    }

    let slide = input.u1 - input.u2;
    let p = |i: usize, j: usize| input.pressure[g.idx(i, j)].max(0.0);
    let mut out = vec![(0.0, 0.0); n];
    for j in 0..g.ny {
        for i in 0..g.nx {
            let k = g.idx(i, j);
            let h = input.film[k];
            if h == f64::INFINITY {
                continue; // no opposing surface: no film, no stress
            }
            // pressure gradient along x: central inside, one-sided at the first/last column
            let dpdx = if g.nx == 1 {
                0.0
            } else if i == 0 {
                (p(1, j) - p(0, j)) / g.dx
            } else if i == g.nx - 1 {
                (p(i, j) - p(i - 1, j)) / g.dx
            } else {
                (p(i + 1, j) - p(i - 1, j)) / (2.0 * g.dx)
            };
            let poiseuille = -0.5 * h.max(0.0) * dpdx;

            let pk = input.pressure[k];
            let couette = if pk <= 0.0 || slide == 0.0 {
                0.0
            } else if h > 0.0 {
                rheology::shear_stress(input.rheology, input.viscosity[k], slide / h, pk)
            } else {
                match rheology::limiting_shear_stress(input.rheology, pk) {
                    Some(tau_l) => tau_l.copysign(slide),
                    None => {
                        return Err(Error::Solver(format!(
                            "friction: film thickness h = {h:e} m <= 0 in the pressurised {} with \
                             sliding: the shear stress is unbounded without a limiting shear stress \
                             (the film has broken down)",
                            cell_name(k)
                        )))
                    }
                }
            };
            if !couette.is_finite() || !poiseuille.is_finite() {
                return Err(Error::Solver(format!(
                    "friction: non-finite shear stress in {} (h = {h:e} m too thin for the \
                     sliding speed {slide:e} m/s?)",
                    cell_name(k)
                )));
            }
            out[k] = (couette, poiseuille);
        }
    }
    Ok(out)
}

/// Surface shear stress on body 2 along +x (Pa), per cell (row-major on the grid): the sum of
/// the Couette and Poiseuille parts of the module documentation (thesis eq. 3.8 with the sign
/// of eq. 3.9). Errors as for [`friction`] except that the load is not needed.
pub fn surface_shear_stress(input: &FrictionInput) -> Result<Vec<f64>> {
    Ok(cell_stresses(input)?
        .into_iter()
        .map(|(c, p)| c + p)
        .collect())
}

/// Shear traction along +x that the film exerts on each surface (Pa), per cell: `[body 1,
/// body 2]`. Body 2 gets the Couette and Poiseuille parts of the module documentation
/// (tau_2 = C + P); body 1 gets the film's stress at z = 0, tau_1 = P - C: the sliding part holds
/// the faster surface back and pulls the slower one forward, while the pressure-flow part acts
/// with the same sign on both. These are the tangential loads of [`crate::stress`]. Errors as for
/// [`surface_shear_stress`].
pub fn surface_tractions(input: &FrictionInput) -> Result<[Vec<f64>; 2]> {
    let parts = cell_stresses(input)?;
    Ok([
        parts.iter().map(|(c, p)| p - c).collect(),
        parts.iter().map(|(c, p)| c + p).collect(),
    ])
}

/// Friction force on body 2 and friction coefficient (thesis eq. 3.5, 3.9, 3.10): the surface
/// shear stress summed over the cells times the cell area dx dy, divided by the load.
///
/// Returns an error (never NaN) for fields of the wrong length, NaN or non-finite pressure or
/// viscosity, non-finite speeds, a load that is not positive and finite, or a pressurised cell
/// with h <= 0 under sliding when the rheology has no limiting shear stress.
///
/// ```
/// use ehl::case::Rheology;
/// use ehl::friction::{friction, surface_speeds, FrictionInput};
/// use ehl::grid::Grid;
///
/// // infinite line contact (ny = 1, dy = 1 m): uniform 1 GPa over 2 cells, film 0.1 um
/// let grid = Grid::new(2, 1, -1e-4, 1e-4, -0.5, 0.5);
/// let (u1, u2) = surface_speeds(2.0, 0.05); // u_e = 2 m/s, SRR = 0.05
/// let rheology = Rheology::Carreau {
///     shear_modulus: 4.5e6,
///     power_law_index: 0.57,
///     limiting_shear_coefficient: Some(0.06),
/// };
/// let f = friction(&FrictionInput {
///     grid: &grid,
///     pressure: &[1e9, 1e9],
///     film: &[1e-7, 1e-7],
///     viscosity: &[1e3, 1e3],
///     u1,
///     u2,
///     rheology: &rheology,
///     load: 2e5, // N/m
/// })
/// .unwrap();
/// // eta (u1 - u2) / h = 1e12 Pa: capped at Lambda p = 6e7 Pa over 2e-4 m
/// assert!((f.couette_force - 6e7 * 2e-4).abs() < 1e-6);
/// assert!((f.coefficient - 0.06).abs() < 1e-12);
/// ```
pub fn friction(input: &FrictionInput) -> Result<Friction> {
    if !(input.load.is_finite() && input.load > 0.0) {
        return Err(Error::Solver(format!(
            "friction: the load must be positive and finite (got {} N)",
            input.load
        )));
    }
    let area = input.grid.cell_area();
    let (mut couette, mut poiseuille) = (0.0, 0.0);
    for (c, p) in cell_stresses(input)? {
        couette += c;
        poiseuille += p;
    }
    let couette_force = couette * area;
    let poiseuille_force = poiseuille * area;
    let force = couette_force + poiseuille_force;
    if !force.is_finite() {
        return Err(Error::Solver(format!(
            "friction: the friction force overflowed ({force})"
        )));
    }
    Ok(Friction {
        force,
        coefficient: force / input.load,
        couette_force,
        poiseuille_force,
    })
}
