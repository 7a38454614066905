//! Gap of the undeformed bodies g(x, y): roller profiles, misalignment, unequal radii, balls.
//!
//! # Model
//!
//! Each body k has a surface drop z_k(x, y) >= 0 below the common tangent plane (thesis eq.
//! 1.1-1.2, 2.4-2.8), in the parabolic (small-slope) approximation of the thesis:
//!
//! * roller: x_k^2 / (2 R_k) + P_k(u_k), with x_k the distance across its axis and u_k the axial
//!   coordinate measured from its mid-length; P_k the axial profile drop ([`profile_drop`]);
//!   no material (g = +inf) where |u_k| > L_k / 2;
//! * ball: x^2 / (2 R) + y^2 / (2 R_y) (an ellipsoid when `radius_y != radius`);
//! * flat: 0.
//!
//! Body 1 lies along y with its mid-length at the origin: x_1 = x, u_1 = y. Body 2 has its
//! mid-length at (0, axial_offset) and is rotated by the skew angle s about the z axis (axes
//! crossed in the contact plane): with dy = y - axial_offset,
//! x_2 = x cos s + dy sin s,  u_2 = -x sin s + dy cos s.
//!
//! Tilt t (misalignment perpendicular to the contact plane; thesis fig. 1.12 a) turns body 2's
//! axis in the y-z plane. Sign convention: a positive tilt lifts body 2's end at positive y, so
//! the gap grows by tan(t) * u_2 (linear in y for s = 0); the contact then concentrates at the
//! negative-y end. The change of projected length (cos t) is neglected (t << 1).
//!
//! g = z_1 + z_2 + tan(t) u_2 - g_min, where g_min is the minimum of the sum over the region where
//! both bodies have material, so that the bodies just touch (min g = 0). The sum is jointly convex
//! in (x, y) (every profile drop is convex in u and u, x_k are linear in x, y), so g_min is found
//! by nested golden-section search; its accuracy is ~1e-12 of the gap scale.
//!
//! Hertz scales ([`HertzScales`]): finite line contact w' = F / contact length; infinite line
//! contact w' = `load.force_per_length`; circular ball [`crate::units::hertz_point`]; elliptical
//! ball [`crate::reference::hertz::hertz_elliptical`] (exact, elliptic integrals by AGM).

use crate::case::{Body, Case, Profile, Shape};
use crate::grid::Grid;
use crate::reference::hertz::hertz_elliptical;
use crate::units;

/// Axial profile drop P(u) (m) of a roller of length `len` at axial coordinate `u` measured from
/// its mid-length; `f64::INFINITY` beyond the ends (|u| > len/2). `log` carries what the
/// logarithmic profile needs ([`LogProfile`]).
///
/// * straight: 0
/// * crowned, crown radius R_c: R_c - sqrt(R_c^2 - u^2)
/// * rounded edge, edge length l_e and radius r: 0 for |u| <= len/2 - l_e, else
///   r - sqrt(r^2 - t^2) with t = |u| - (len/2 - l_e) (an arc tangent to the straight part)
/// * chamfer, edge length l_e and angle a: t tan(a) over the same end zones
/// * logarithmic: see [`LogProfile::drop`]
pub fn profile_drop(profile: &Profile, len: f64, u: f64, log: Option<&LogProfile>) -> f64 {
    let half = 0.5 * len;
    let au = u.abs();
    if au > half * (1.0 + 1e-12) {
        return f64::INFINITY;
    }
    match *profile {
        Profile::Straight => 0.0,
        Profile::Crowned { crown_radius } => {
            if au >= crown_radius {
                f64::INFINITY
            } else {
                // R - sqrt(R^2 - u^2) written without cancellation
                u * u / (crown_radius + (crown_radius * crown_radius - u * u).sqrt())
            }
        }
        Profile::RoundedEdge {
            edge_length,
            edge_radius,
        } => {
            let t = au - (half - edge_length);
            if t <= 0.0 {
                0.0
            } else if t >= edge_radius {
                f64::INFINITY
            } else {
                t * t / (edge_radius + (edge_radius * edge_radius - t * t).sqrt())
            }
        }
        Profile::Chamfer { edge_length, angle } => {
            let t = au - (half - edge_length);
            if t <= 0.0 {
                0.0
            } else {
                t * angle.tan()
            }
        }
        Profile::Logarithmic { .. } => match log {
            Some(l) => l.drop(u),
            None => 0.0,
        },
    }
}

/// Lundberg's logarithmic profile with the Johns & Gohar finite end drop.
///
/// Lundberg (1939, Forschung Ing.-Wes. 10, 201-211) showed that a uniformly loaded strip of
/// length l on a half-space sinks by (2 w'/(pi E')) ln(1 - (2u/l)^2) + const (w' = Q/l the load
/// per unit length, E' the reduced modulus, compliance 2/(pi E') as in thesis eq. 1.6), so the
/// profile that gives a uniform axial pressure under the design load Q is
///
/// P(u) = (2 Q / (pi l E')) ln[ 1 / (1 - (2u/l)^2) ],
///
/// infinite at the ends. Johns & Gohar (1981, Tribology Int. 14, 131-136) keep it finite:
///
/// P(u) = (2 Q / (pi l E')) ln[ 1 / (1 - (1 - 0.3033 * 2b/l) (2u/l)^2) ],
///
/// with b = sqrt(8 w' R / (pi E')) the Hertz half-width under Q; the end drop is then
/// (2 Q / (pi l E')) ln(l / (0.3033 * 2b)). This is the form used here (the whole drop is put on
/// the profiled body; E' and R are those of the contact pair).
/// ISO/TS 16281:2008 uses the same Lundberg law with the drop scaled as 0.00035 D_w ln(...)
/// for its reference profile, which corresponds to a design contact stress of about 3000 MPa.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LogProfile {
    /// 2 Q / (pi l E')  (m)
    pub scale: f64,
    /// 1 - 0.3033 * 2b/l (clamped to [0, 1))
    pub end_factor: f64,
    /// roller length l (m)
    pub length: f64,
}

impl LogProfile {
    /// Profile for design load `q` (N) on a roller of length `len` (m) in a contact of reduced
    /// radius `r` (m) and reduced modulus `e_red` (Pa).
    pub fn new(q: f64, len: f64, r: f64, e_red: f64) -> Self {
        let w = q / len;
        let b = units::hertz_line_half_width(w, r, e_red);
        LogProfile {
            scale: 2.0 * q / (std::f64::consts::PI * len * e_red),
            end_factor: (1.0 - 0.3033 * 2.0 * b / len).clamp(0.0, 1.0 - 1e-12),
            length: len,
        }
    }

    /// Drop P(u) (m), u from mid-length; infinite beyond the ends.
    pub fn drop(&self, u: f64) -> f64 {
        let s = 2.0 * u / self.length;
        if s.abs() > 1.0 + 1e-12 {
            return f64::INFINITY;
        }
        let s2 = (s * s).min(1.0);
        -self.scale * (1.0 - self.end_factor * s2).ln()
    }
}

/// Hertz scales of the nominal contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HertzScales {
    /// true for point (ball) contacts
    pub point: bool,
    /// reduced modulus E' (Pa)
    pub e_red: f64,
    /// reduced radius in the rolling plane R = R_x (m)
    pub r: f64,
    /// reduced radius in the axial plane R_y (m); infinite for line contacts
    pub r_y: f64,
    /// Hertz half-width (semi-axis) along x (m)
    pub b: f64,
    /// semi-axis along y (m): point contact a_y; finite line contact length/2; infinite line inf
    pub a_y: f64,
    /// maximum Hertz pressure (Pa)
    pub ph: f64,
    /// total load F (N) (infinite line: the load on the 1 m reference length)
    pub force: f64,
    /// load per unit length w' (N/m) for line contacts; NaN for point contacts
    pub force_per_length: f64,
    /// Hertz rigid-body approach (m) for point contacts; NaN for line contacts (undefined
    /// for a half-space under a 2D load)
    pub approach: f64,
    /// ellipticity k = a_y / b (point contacts), NaN for line contacts
    pub ellipticity: f64,
    /// contact length (m) for line contacts (inf for the infinite line), NaN for point contacts
    pub contact_length: f64,
}

#[derive(Debug, Clone, Copy, PartialEq)]
struct BodyGeom {
    shape: Shape,
    r: f64,
    r_y: f64,
    len: f64,
    log: Option<LogProfile>,
}

/// The undeformed gap of a case (see the module documentation for the model and conventions).
#[derive(Debug, Clone)]
pub struct Geometry {
    b1: BodyGeom,
    b2: BodyGeom,
    p1: Profile,
    p2: Profile,
    offset: f64,
    cos_s: f64,
    sin_s: f64,
    tan_t: f64,
    g_min: f64,
    hertz: HertzScales,
    spec: crate::case::GridSpec,
    infinite_line: bool,
}

fn finite_len(body: &Body) -> Option<f64> {
    (body.shape == Shape::Roller && body.length.is_finite()).then_some(body.length)
}

impl Geometry {
    /// Builds the gap and the Hertz scales of a validated case.
    pub fn new(case: &Case) -> Geometry {
        let e_red = case.reduced_modulus();
        let r = case.reduced_radius();
        let offset = case.body2.axial_offset;
        let (sin_s, cos_s) = case.alignment.skew.sin_cos();
        let tan_t = case.alignment.tilt.tan();
        let infinite_line = case.is_infinite_line();
        let point = case.is_point();

        // contact length: overlap of the bodies' axial extents (body 2 projected on y)
        let ext = |b: &Body, centre: f64, proj: f64| match finite_len(b) {
            Some(l) => (centre - 0.5 * l * proj, centre + 0.5 * l * proj),
            None => (f64::NEG_INFINITY, f64::INFINITY),
        };
        let e1 = ext(&case.body1, 0.0, 1.0);
        let e2 = ext(&case.body2, offset, cos_s.abs());
        let overlap = (e1.0.max(e2.0), e1.1.min(e2.1));
        let contact_length = (overlap.1 - overlap.0).max(0.0);

        let ry_of = |b: &Body| {
            if b.shape == Shape::Ball {
                b.radius_y
            } else {
                f64::INFINITY
            }
        };
        let r_y = units::reduced_radius(ry_of(&case.body1), ry_of(&case.body2));

        let hertz = if point {
            let f = case.load.force;
            let h = if (r_y / r - 1.0).abs() < 1e-12 {
                let c = units::hertz_point(f, r, e_red);
                (c.a, c.a, c.p0, c.approach)
            } else {
                let e = hertz_elliptical(f, r, r_y, e_red);
                (e.a_x, e.a_y, e.p0, e.approach)
            };
            HertzScales {
                point: true,
                e_red,
                r,
                r_y,
                b: h.0,
                a_y: h.1,
                ph: h.2,
                force: f,
                force_per_length: f64::NAN,
                approach: h.3,
                ellipticity: h.1 / h.0,
                contact_length: f64::NAN,
            }
        } else {
            let (w, len, f) = if infinite_line || !contact_length.is_finite() {
                let w = case.load.force_per_length;
                (w, f64::INFINITY, w)
            } else {
                (
                    case.load.force / contact_length,
                    contact_length,
                    case.load.force,
                )
            };
            HertzScales {
                point: false,
                e_red,
                r,
                r_y: f64::INFINITY,
                b: units::hertz_line_half_width(w, r, e_red),
                a_y: 0.5 * len,
                ph: units::hertz_line_pressure(w, r, e_red),
                force: f,
                force_per_length: w,
                approach: f64::NAN,
                ellipticity: f64::NAN,
                contact_length: len,
            }
        };

        let geom = |b: &Body| BodyGeom {
            shape: b.shape,
            r: b.radius,
            r_y: b.radius_y,
            len: if b.shape == Shape::Roller {
                b.length
            } else {
                f64::INFINITY
            },
            log: match (b.shape, &b.profile) {
                (Shape::Roller, Profile::Logarithmic { load }) if b.length.is_finite() => {
                    Some(LogProfile::new(*load, b.length, r, e_red))
                }
                _ => None,
            },
        };
        let mut g = Geometry {
            b1: geom(&case.body1),
            b2: geom(&case.body2),
            p1: case.body1.profile.clone(),
            p2: case.body2.profile.clone(),
            offset,
            cos_s,
            sin_s,
            tan_t,
            g_min: 0.0,
            hertz,
            spec: case.grid,
            infinite_line,
        };
        if !infinite_line {
            g.g_min = g.find_min(overlap);
        }
        g
    }

    /// Sum of both bodies' drops plus the tilt term, before the shift (m).
    fn raw(&self, x: f64, y: f64) -> f64 {
        let z1 = drop_of(&self.b1, &self.p1, x, y);
        if z1.is_infinite() {
            return f64::INFINITY;
        }
        let dy = y - self.offset;
        let x2 = x * self.cos_s + dy * self.sin_s;
        let u2 = -x * self.sin_s + dy * self.cos_s;
        let z2 = drop_of(&self.b2, &self.p2, x2, u2);
        let tilt = if self.tan_t != 0.0 {
            self.tan_t * u2
        } else {
            0.0
        };
        z1 + z2 + tilt
    }

    /// Minimum of [`Self::raw`] over the region where both bodies have material.
    fn find_min(&self, overlap: (f64, f64)) -> f64 {
        // a bracket for y: the overlap of the axial extents, or the grid's y range when a body
        // is unbounded; for x: wide enough to hold the minimiser of crossed parabolas.
        let b = self.hertz.b;
        let (mut ylo, mut yhi) = overlap;
        if !ylo.is_finite() {
            ylo = (self.spec.y_min * b).min(-b);
        }
        if !yhi.is_finite() {
            yhi = (self.spec.y_max * b).max(b);
        }
        if yhi <= ylo {
            return 0.0;
        }
        let xr = 2.0 * (ylo.abs().max(yhi.abs()) + self.offset.abs())
            + (self.spec.x_min.abs().max(self.spec.x_max.abs()) * b);
        let inner = |y: f64| -> f64 {
            // feasible x interval from body 2's length limits (skewed strip)
            let (mut xlo, mut xhi) = (-xr, xr);
            if self.b2.shape == Shape::Roller && self.b2.len.is_finite() && self.sin_s != 0.0 {
                let dy = y - self.offset;
                let h = 0.5 * self.b2.len;
                let p = (dy * self.cos_s - h) / self.sin_s;
                let q = (dy * self.cos_s + h) / self.sin_s;
                xlo = xlo.max(p.min(q));
                xhi = xhi.min(p.max(q));
            }
            if xhi < xlo {
                return f64::INFINITY;
            }
            golden(|x| self.raw(x, y), xlo, xhi).1
        };
        let (_, v) = golden(inner, ylo, yhi);
        if v.is_finite() {
            v
        } else {
            0.0
        }
    }

    /// Undeformed separation g(x, y) >= 0 (m); `f64::INFINITY` where one body has no material.
    pub fn gap(&self, x: f64, y: f64) -> f64 {
        if self.infinite_line {
            return x * x / (2.0 * self.hertz.r);
        }
        let v = self.raw(x, y) - self.g_min;
        if v.is_finite() {
            v.max(0.0)
        } else {
            f64::INFINITY
        }
    }

    /// The case grid in metres (`case.grid` is in Hertz half-widths b along both directions).
    /// An infinite line contact (`ny == 1`, infinite lengths) gets the 1 m reference length:
    /// y_min = -0.5, dy = 1 (COMMON.md).
    pub fn grid(&self) -> Grid {
        let s = self.spec;
        let b = self.hertz.b;
        if self.infinite_line {
            Grid::new(s.nx.max(1), 1, s.x_min * b, s.x_max * b, -0.5, 0.5)
        } else {
            Grid::new(
                s.nx.max(1),
                s.ny.max(1),
                s.x_min * b,
                s.x_max * b,
                s.y_min * b,
                s.y_max * b,
            )
        }
    }

    /// Hertz scales of the nominal contact.
    pub fn hertz(&self) -> HertzScales {
        self.hertz
    }

    /// y (m) of the two free ends of finite roller `body` (1 or 2) in contact coordinates
    /// (body 2: its mid-length at `axial_offset`, half-length projected by cos(skew));
    /// `None` for a ball, a flat, an infinite roller or another body number.
    pub fn body_ends(&self, body: usize) -> Option<(f64, f64)> {
        let (bg, centre, proj) = match body {
            1 => (&self.b1, 0.0, 1.0),
            2 => (&self.b2, self.offset, self.cos_s.abs()),
            _ => return None,
        };
        (bg.shape == Shape::Roller && bg.len.is_finite())
            .then_some((centre - 0.5 * bg.len * proj, centre + 0.5 * bg.len * proj))
    }

    /// Overlap of the rollers' axial extents along y (m); infinite for an infinite line contact,
    /// NaN for point contacts.
    pub fn contact_length(&self) -> f64 {
        self.hertz.contact_length
    }

    /// The gap as the closure the solvers take (COMMON.md).
    pub fn gap_fn(&self) -> impl Fn(f64, f64) -> f64 + Sync + '_ {
        move |x, y| self.gap(x, y)
    }
}

/// Drop of one body at its own coordinates (x across its axis, u along it from mid-length).
fn drop_of(b: &BodyGeom, profile: &Profile, x: f64, u: f64) -> f64 {
    match b.shape {
        Shape::Flat => 0.0,
        Shape::Ball => {
            let ry = if b.r_y.is_finite() && b.r_y > 0.0 {
                b.r_y
            } else {
                b.r
            };
            x * x / (2.0 * b.r) + u * u / (2.0 * ry)
        }
        Shape::Roller => {
            let p = if b.len.is_finite() {
                profile_drop(profile, b.len, u, b.log.as_ref())
            } else {
                0.0
            };
            if p.is_infinite() {
                f64::INFINITY
            } else {
                x * x / (2.0 * b.r) + p
            }
        }
    }
}

/// Golden-section search for the minimum of a convex function on [lo, hi]; returns (x, f(x)).
/// Also evaluates the end points (the minimum of a convex function on an interval may sit there).
fn golden(f: impl Fn(f64) -> f64, lo: f64, hi: f64) -> (f64, f64) {
    let inv_phi = 0.5 * (5f64.sqrt() - 1.0);
    let (mut a, mut b) = (lo, hi);
    let mut c = b - inv_phi * (b - a);
    let mut d = a + inv_phi * (b - a);
    let (mut fc, mut fd) = (f(c), f(d));
    for _ in 0..200 {
        if (b - a).abs() <= 1e-14 * (1.0 + a.abs().max(b.abs())) {
            break;
        }
        if fc <= fd {
            b = d;
            d = c;
            fd = fc;
            c = b - inv_phi * (b - a);
            fc = f(c);
        } else {
            a = c;
            c = d;
            fc = fd;
            d = a + inv_phi * (b - a);
            fd = f(d);
        }
    }
    let mut best = if fc <= fd { (c, fc) } else { (d, fd) };
    for x in [lo, hi] {
        let v = f(x);
        if v < best.1 {
            best = (x, v);
        }
    }
    best
}

mod sampler;
pub use sampler::{GapSampler, GapWithFeatures};

#[cfg(test)]
mod tests;
