//! Validation of the TOML tree and resolution into a [`Case`]: defaults filled, load and
//! dimensionless forms converted to SI, grid extents checked against the Hertz half-width.
//! The defaults are listed in the documentation of [`super`].

use super::model::*;
use super::read::{case_err, choose, describe, fmt_num, Sec, R};
use crate::units;
use crate::Error;
use std::f64::consts::FRAC_PI_2;
use toml::{Table, Value};

/// Default cells per direction when `grid.nx` / `grid.ny` are absent.
pub const DEFAULT_CELLS: usize = 128;
/// Fewest cells across the Hertz contact width 2b (2a for a ball) along x, and along the contact
/// in y, that resolve the pressure: with fewer, the Hertz ellipse is sampled by a handful of
/// points and maximum pressure, approach and film are off by many per cent.
pub const MIN_CELLS_ACROSS_CONTACT: f64 = 8.0;
/// Largest grid accepted (cells): 2^26 cells hold 0.5 GB per field.
pub const MAX_CELLS: usize = 1 << 26;
/// Default `solver.max_iterations` for dry contact. The constrained conjugate-gradient methods
/// need O(100) iterations on fine grids (Polonsky-Keer: ~95 at 512^2), more for rough or
/// strongly misaligned cases; the cap is only a safety net.
pub const DEFAULT_DRY_ITERATIONS: usize = 500;
/// Default `solver.max_iterations` for EHL (multigrid cycles or Newton steps, the outer
/// load-balance iterations).
pub const DEFAULT_EHL_ITERATIONS: usize = 200;

/// Smallest Young's modulus accepted (Pa): soft elastomers.
pub const MIN_MODULUS: f64 = 1e6;
/// Largest Young's modulus accepted (Pa): ten times diamond.
pub const MAX_MODULUS: f64 = 1e13;

/// Range of the dimensionless speed U = eta0 u_e / (E' R) accepted for EHL (see `motion`).
pub const MIN_SPEED_PARAMETER: f64 = 1e-16;
/// See [`MIN_SPEED_PARAMETER`].
pub const MAX_SPEED_PARAMETER: f64 = 1e-7;

/// Whether `v` lies in [lo, hi], allowing the round-off of a quantity derived back from the one
/// the case gives (relative 1e-9): `dimensionless_speed = 1e-16` becomes u_e and comes back as
/// U = 9.999999999999999e-17, which a plain comparison refused at its own documented bound.
fn within_derived(lo: f64, hi: f64, v: f64) -> bool {
    v >= lo * (1.0 - 1e-9) && v <= hi * (1.0 + 1e-9)
}

const SHAPES: &[&str] = &["roller", "ball", "flat"];
const PROFILE_KINDS: &[&str] = &[
    "straight",
    "crowned",
    "logarithmic",
    "rounded-edge",
    "chamfer",
];
const RHEOLOGY_MODELS: &[&str] = &["newtonian", "carreau", "eyring"];
const FEATURE_KINDS: &[&str] = &["pit", "dent", "waviness", "height-map"];
const LOAD_FORMS: &[&str] = &[
    "force",
    "max_hertz_pressure",
    "force_per_length",
    "dimensionless_load",
];

fn forbid(s: &Sec, k: &str, why: &str) -> R<()> {
    if s.has(k) {
        Err(s.err(k, why.to_string()))
    } else {
        Ok(())
    }
}

fn required<T>(v: Option<T>, s: &Sec, k: &str, what: &str) -> R<T> {
    v.ok_or_else(|| s.missing(k, what))
}

/// A required table of the top level.
fn sub<'a>(top: &Sec<'a>, k: &str, what: &str) -> R<Option<&'a Table>> {
    top.table(k, what)
}

fn mm(v: f64) -> String {
    fmt_num(v * 1e3)
}

/// Sizes of a body (radius, radius_y, finite length), m: from 1 um (a colloidal probe) to 1 km
/// (beyond, a body is a plane at any contact size: use shape = "flat"). Outside, the Hertz scales
/// underflow or overflow and the grid loses its meaning.
pub const BODY_SIZE_RANGE: (f64, f64) = (1e-6, 1e3);

fn body_size(s: &Sec, k: &str, v: f64) -> R<()> {
    let (lo, hi) = BODY_SIZE_RANGE;
    if v.is_finite() && !(lo..=hi).contains(&v) {
        return Err(s.err(
            k,
            format!(
                "{} m is outside the sizes this program models, {} to {} m (for a plane use shape = \"flat\")",
                fmt_num(v),
                fmt_num(lo),
                fmt_num(hi)
            ),
        ));
    }
    Ok(())
}

/// `[body1]` / `[body2]`.
fn body(top: &Sec, name: &str) -> R<Body> {
    let t = sub(top, name, "the body's shape, size and elastic constants")?.ok_or_else(|| {
        top.missing(
            name,
            &format!("a [{name}] table with shape, radius, youngs_modulus and poisson_ratio"),
        )
    })?;
    let s = Sec {
        file: top.file,
        path: name,
        table: t,
    };
    let shape = match s.choice("shape", SHAPES)? {
        Some("roller") => Shape::Roller,
        Some("ball") => Shape::Ball,
        Some(_) => Shape::Flat,
        None => return Err(s.missing("shape", "shape = \"roller\", \"ball\" or \"flat\"")),
    };
    let youngs_modulus = s.required_positive(
        "youngs_modulus",
        "Pa",
        "Young's modulus in Pa, e.g. youngs_modulus = 210e9 for steel",
    )?;
    // 1 MPa (soft elastomers) .. 10 TPa (ten times diamond, the stiffest solid at ~1.2 TPa):
    // outside, no solid is meant, and E' enters the Hertz scales as E'^(-1/2..-1/3) where
    // 1e-300 or 1e300 overflow the deflection arithmetic
    if !(MIN_MODULUS..=MAX_MODULUS).contains(&youngs_modulus) {
        return Err(s.err(
            "youngs_modulus",
            format!(
                "{} Pa is outside the range of solids, {} .. {} Pa (soft elastomers to ten times diamond); give Young's modulus in Pa, e.g. 210e9 for steel",
                fmt_num(youngs_modulus),
                fmt_num(MIN_MODULUS),
                fmt_num(MAX_MODULUS)
            ),
        ));
    }
    let nu = s.required_num(
        "poisson_ratio",
        "dimensionless",
        "Poisson's ratio, e.g. poisson_ratio = 0.3 for steel",
    )?;
    if !(nu > -1.0 && nu < 0.5) {
        return Err(s.err(
            "poisson_ratio",
            format!(
                "must lie strictly between -1 and 0.5 for an isotropic elastic solid (0.5 is incompressible, where the half-space model breaks down); found {}",
                fmt_num(nu)
            ),
        ));
    }

    let radius_of = |s: &Sec| -> R<f64> {
        let r = s.required_num(
            "radius",
            "m",
            "the radius in the rolling plane in m, e.g. radius = 0.03",
        )?;
        if r.is_infinite() && r > 0.0 {
            return Err(s.err(
                "radius",
                "a curved body needs a finite radius; for a plane use shape = \"flat\"",
            ));
        }
        if !(r > 0.0 && r.is_finite()) {
            return Err(s.err(
                "radius",
                format!(
                    "must be a positive, finite number (m), found {}",
                    fmt_num(r)
                ),
            ));
        }
        body_size(s, "radius", r)?;
        Ok(r)
    };

    let mut b = Body {
        shape,
        radius: f64::INFINITY,
        radius_y: f64::INFINITY,
        length: f64::INFINITY,
        youngs_modulus,
        poisson_ratio: nu,
        profile: Profile::Straight,
        axial_offset: 0.0,
    };
    match shape {
        Shape::Roller => {
            b.radius = radius_of(&s)?;
            forbid(
                &s,
                "radius_y",
                "is for balls only (the ellipsoid's radius in the axial plane); a roller's axial shape is set by length and profile",
            )?;
            let len = s.required_num("length", "m", "the roller's axial length in m, e.g. length = 9.5e-3 (length = inf gives an infinite line contact)")?;
            if len.is_nan() || len <= 0.0 {
                return Err(s.err(
                    "length",
                    format!(
                        "must be positive (m; inf for an infinite line contact), found {}",
                        fmt_num(len)
                    ),
                ));
            }
            body_size(&s, "length", len)?;
            b.length = len;
            b.profile = profile(&s, len)?;
        }
        Shape::Ball => {
            b.radius = radius_of(&s)?;
            b.radius_y = s.positive("radius_y", "m")?.unwrap_or(b.radius);
            body_size(&s, "radius_y", b.radius_y)?;
            forbid(
                &s,
                "length",
                "a ball has no axial length (for an ellipsoid give radius_y instead)",
            )?;
            forbid(
                &s,
                "profile",
                "is for rollers only (the axial profile of a roller)",
            )?;
        }
        Shape::Flat => {
            forbid(
                &s,
                "radius",
                "a flat is a plane and has no radius; leave the key out",
            )?;
            forbid(&s, "radius_y", "is for balls only; a flat is a plane")?;
            forbid(
                &s,
                "length",
                "a flat is unbounded along y; for a disc of finite width use shape = \"roller\" with the disc radius",
            )?;
            forbid(
                &s,
                "profile",
                "is for rollers only (the axial profile of a roller)",
            )?;
        }
    }
    if name == "body2" {
        b.axial_offset = s.finite("axial_offset", "m")?.unwrap_or(0.0);
    }
    Ok(b)
}

/// A tagged table (`{ kind = ..., params }`, `{ model = ..., params }`) may hold only its tag
/// and the parameters of the chosen variant: anything else is an error naming the key and
/// listing the variant's parameters.
fn only_params(p: &Sec, t: &Table, tag: &str, what: &str, variant: &str, params: &[&str]) -> R<()> {
    for k in t.keys() {
        if k != tag && !params.contains(&k.as_str()) {
            let list = if params.is_empty() {
                "none".to_string()
            } else {
                params.join(", ")
            };
            return Err(p.err(
                k,
                format!("is not a parameter of {what} \"{variant}\" (its parameters: {list})"),
            ));
        }
    }
    Ok(())
}

/// A tagged table: `field = { <tag> = "<variant>", params... }`, or the bare word of the one
/// variant without parameters (`profile = "straight"`, `rheology = "newtonian"`).
struct Tagged {
    /// the key in the parent table: "profile", "rheology"
    field: &'static str,
    /// the key naming the variant: "kind", "model"
    tag: &'static str,
    variants: &'static [&'static str],
    /// the variant without parameters, the only one a bare word may name
    bare: &'static str,
    /// how messages name a variant: "profile kind", "rheology model"
    what: &'static str,
    /// the parameters each variant takes
    params: fn(&str) -> &'static [&'static str],
    /// a complete example of each variant, for the messages
    example: fn(&str) -> &'static str,
    /// the variant whose example the wrong-type message shows
    shown: &'static str,
}

impl Tagged {
    /// The table and the chosen variant; None when the field is absent or the bare word names
    /// the parameterless variant. Any other variant, an unknown tag, a foreign key in the table
    /// or a value of the wrong type is an error naming the key.
    fn read<'a>(&self, s: &Sec<'a>, key: &'a str) -> R<Option<(Sec<'a>, &'static str)>> {
        match s.get(self.field) {
            None => Ok(None),
            Some(Value::String(w)) => {
                let v = choose(w, self.variants).map_err(|m| s.err(self.field, m))?;
                if v != self.bare {
                    return Err(s.err(
                        self.field,
                        format!(
                            "{} \"{v}\" needs its parameters: write it as a table, e.g. {}",
                            self.field,
                            (self.example)(v)
                        ),
                    ));
                }
                Ok(None)
            }
            Some(Value::Table(t)) => {
                let p = Sec {
                    file: s.file,
                    path: key,
                    table: t,
                };
                let list = self
                    .variants
                    .iter()
                    .map(|v| format!("\"{v}\""))
                    .collect::<Vec<_>>()
                    .join(", ");
                let v = required(
                    p.choice(self.tag, self.variants)?,
                    &p,
                    self.tag,
                    &format!("the {}: one of {list}", self.what),
                )?;
                only_params(&p, t, self.tag, self.what, v, (self.params)(v))?;
                Ok(Some((p, v)))
            }
            Some(v) => Err(s.err(
                self.field,
                format!(
                    "expected a table such as {}, found {}",
                    (self.example)(self.shown),
                    describe(v)
                ),
            )),
        }
    }

    /// The positive parameter `k` (in `unit`) of variant `v`, required.
    fn need(&self, p: &Sec, v: &str, k: &str, unit: &str) -> R<f64> {
        let what = format!(
            "{k} ({unit}) for {} \"{v}\", e.g. {}",
            self.what,
            (self.example)(v)
        );
        p.required_positive(k, unit, &what)
    }
}

const PROFILE: Tagged = Tagged {
    field: "profile",
    tag: "kind",
    variants: PROFILE_KINDS,
    bare: "straight",
    what: "profile kind",
    params: |kind| match kind {
        "crowned" => &["crown_radius"],
        "logarithmic" => &["load"],
        "rounded-edge" => &["edge_length", "edge_radius"],
        "chamfer" => &["edge_length", "angle"],
        _ => &[],
    },
    example: profile_example,
    shown: "crowned",
};

const RHEOLOGY: Tagged = Tagged {
    field: "rheology",
    tag: "model",
    variants: RHEOLOGY_MODELS,
    bare: "newtonian",
    what: "rheology model",
    params: |model| match model {
        "carreau" => &[
            "shear_modulus",
            "power_law_index",
            "limiting_shear_coefficient",
        ],
        "eyring" => &["eyring_stress", "limiting_shear_coefficient"],
        _ => &[],
    },
    example: rheology_example,
    shown: "carreau",
};

/// `bodyN.profile`: a table `{ kind = ..., params }` or the bare word "straight".
fn profile(s: &Sec, length: f64) -> R<Profile> {
    let key = s.key("profile");
    let p = match PROFILE.read(s, &key)? {
        None => Profile::Straight,
        Some((p, kind)) => {
            let need = |k: &str, unit: &str| PROFILE.need(&p, kind, k, unit);
            let edge = |p: &Sec, e: f64| -> R<f64> {
                if length.is_finite() && e >= 0.5 * length {
                    return Err(p.err(
                        "edge_length",
                        format!(
                            "each roller end's edge zone must be shorter than half the roller length ({} mm), found {} mm",
                            mm(0.5 * length),
                            mm(e)
                        ),
                    ));
                }
                Ok(e)
            };
            match kind {
                "straight" => Profile::Straight,
                "crowned" => {
                    let crown_radius = need("crown_radius", "m")?;
                    // the crown is an arc of this radius along the axis: it cannot span a
                    // roller longer than its diameter
                    if length.is_finite() && crown_radius < 0.5 * length {
                        return Err(p.err(
                            "crown_radius",
                            format!(
                                "a crown of radius {} mm cannot span the roller: it must be at least half the roller length ({} mm); crowns are usually metres",
                                mm(crown_radius),
                                mm(0.5 * length)
                            ),
                        ));
                    }
                    Profile::Crowned { crown_radius }
                }
                "logarithmic" => Profile::Logarithmic {
                    load: need("load", "N")?,
                },
                "rounded-edge" => {
                    let edge_length = edge(&p, need("edge_length", "m")?)?;
                    let edge_radius = need("edge_radius", "m")?;
                    // an arc tangent to the straight part cannot turn through more than a
                    // quarter circle over the edge zone
                    if edge_radius < edge_length {
                        return Err(p.err(
                            "edge_radius",
                            format!(
                                "an edge radius of {} mm cannot round an edge zone of {} mm: it must be at least edge_length",
                                mm(edge_radius),
                                mm(edge_length)
                            ),
                        ));
                    }
                    Profile::RoundedEdge {
                        edge_length,
                        edge_radius,
                    }
                }
                _ => {
                    let edge_length = edge(&p, need("edge_length", "m")?)?;
                    let angle = need("angle", "rad")?;
                    if angle >= FRAC_PI_2 {
                        return Err(p.err(
                            "angle",
                            format!(
                                "a chamfer angle must lie between 0 and pi/2 rad, found {}",
                                fmt_num(angle)
                            ),
                        ));
                    }
                    Profile::Chamfer { edge_length, angle }
                }
            }
        }
    };
    if length.is_infinite() && p != Profile::Straight {
        return Err(s.err(
            "profile",
            "an infinite roller (length = inf) has no ends and no crown: its profile must be straight",
        ));
    }
    Ok(p)
}

fn profile_example(kind: &str) -> &'static str {
    match kind {
        "crowned" => "profile = { kind = \"crowned\", crown_radius = 0.5 }",
        "logarithmic" => "profile = { kind = \"logarithmic\", load = 8000.0 }",
        "rounded-edge" => {
            "profile = { kind = \"rounded-edge\", edge_length = 1e-3, edge_radius = 0.01 }"
        }
        "chamfer" => "profile = { kind = \"chamfer\", edge_length = 0.5e-3, angle = 0.01 }",
        _ => "profile = { kind = \"straight\" }",
    }
}

/// What kind of contact the two bodies make.
#[derive(Debug, Clone, Copy)]
enum Contact {
    /// Line contact (roller on roller or on flat): `len` contact length (inf for an infinite
    /// line), `lo..hi` the axial overlap, `ulo..uhi` the union of the finite bodies' extents (m).
    Line {
        len: f64,
        lo: f64,
        hi: f64,
        ulo: f64,
        uhi: f64,
    },
    /// Point contact (ball on flat or ball on ball); `circular` when R_x == R_y; `ry` the
    /// reduced radius in the axial plane (m).
    Point { circular: bool, ry: f64 },
}

fn contact(top: &Sec, b1: &Body, b2: &Body) -> R<Contact> {
    use Shape::*;
    let file = top.file;
    let offset_given = top
        .get("body2")
        .and_then(|v| v.as_table())
        .is_some_and(|t| t.contains_key("axial_offset"));
    if offset_given && !(b1.shape == Roller && b2.shape == Roller) {
        return Err(case_err(
            file,
            "body2.axial_offset",
            "only shifts one roller against another; it has no meaning when a body is a ball or a flat",
        ));
    }
    match (b1.shape, b2.shape) {
        (Flat, Flat) => Err(case_err(
            file,
            "body2.shape",
            "two flats make no contact: one body must be a roller or a ball",
        )),
        (Ball, Roller) | (Roller, Ball) => {
            let k = if b1.shape == Roller {
                "body1.shape"
            } else {
                "body2.shape"
            };
            Err(Error::Unsupported {
                file: file.to_string(),
                key: k.to_string(),
                message: "a ball against a roller is not built yet; a ball on a flat (with radius_y for an elliptical contact) or on another ball is".into(),
            })
        }
        (Ball, _) | (_, Ball) => {
            let rx = units::reduced_radius(b1.radius, b2.radius);
            let ry = units::reduced_radius(b1.radius_y, b2.radius_y);
            // R_y / R_x far from 1 makes a contact ellipse so slender that it is a line contact
            // in all but name (ellipticity ~ (R_y/R_x)^0.64: 19 at 100); its grid would need
            // cells of aspect ratio ~ k^2 to resolve both semi-axes
            let ratio = ry / rx;
            if !(1e-2..=1e2).contains(&ratio) {
                let k = if b1.shape == Ball && b1.radius_y != b1.radius {
                    "body1.radius_y"
                } else if b2.shape == Ball && b2.radius_y != b2.radius {
                    "body2.radius_y"
                } else {
                    "body1.radius_y"
                };
                return Err(case_err(
                    file,
                    k,
                    format!(
                        "the reduced radii R_y / R_x = {} / {} m = {} must lie between 0.01 and 100: beyond, the contact ellipse (ellipticity about (R_y/R_x)^0.64) is so slender that it is a line contact (use rollers) or needs a grid far finer along one axis than the other",
                        fmt_num(ry), fmt_num(rx), fmt_num(ratio)
                    ),
                ));
            }
            Ok(Contact::Point {
                circular: (rx - ry).abs() <= 1e-12 * rx,
                ry,
            })
        }
        _ => {
            let ext = |b: &Body, c: f64| -> (f64, f64) {
                if b.shape == Flat || b.length.is_infinite() {
                    (f64::NEG_INFINITY, f64::INFINITY)
                } else {
                    (c - 0.5 * b.length, c + 0.5 * b.length)
                }
            };
            let e1 = ext(b1, 0.0);
            let e2 = ext(b2, b2.axial_offset);
            let lo = e1.0.max(e2.0);
            let hi = e1.1.min(e2.1);
            if hi <= lo {
                return Err(case_err(
                    file,
                    "body2.axial_offset",
                    format!(
                        "the rollers do not overlap along the axis: body1 spans y = {} .. {} mm and body2 (shifted by {} mm) spans y = {} .. {} mm",
                        mm(e1.0), mm(e1.1), mm(b2.axial_offset), mm(e2.0), mm(e2.1)
                    ),
                ));
            }
            let fin = [e1, e2].into_iter().filter(|e| e.0.is_finite());
            let (mut ulo, mut uhi) = (f64::INFINITY, f64::NEG_INFINITY);
            for e in fin {
                ulo = ulo.min(e.0);
                uhi = uhi.max(e.1);
            }
            Ok(Contact::Line {
                len: hi - lo,
                lo,
                hi,
                ulo,
                uhi,
            })
        }
    }
}

/// Largest Hertz pressure over reduced modulus accepted. The half-width is b = 4 R p_h / E'
/// (line) and a = pi R p0 / E' (point), so p_h / E' <= 0.1 keeps the contact within 0.3-0.4 R,
/// where the parabolic gap x^2/(2R) of the Hertz and half-space models is within a few per cent
/// of the circle and strains (~ p/E') are still small; beyond, linear elasticity ends (steel
/// yields at p_h / E' ~ 0.02).
pub const MAX_PRESSURE_OVER_MODULUS: f64 = 0.1;
/// Smallest p_h / E' accepted: below, the deflections (~ b p_h / E') are 1e-12 of the contact
/// size and vanish in the round-off of the gap.
pub const MIN_PRESSURE_OVER_MODULUS: f64 = 1e-9;

/// `[load]` -> (Load, Hertz half-width b or semi-axis a_x in m, semi-axis along y over it:
/// a_y / a_x for a point contact, NaN for a line contact).
fn load(top: &Sec, c: Contact, r: f64, e_red: f64) -> R<(Load, f64, f64)> {
    let what = "a [load] table with one of force (N), max_hertz_pressure (Pa), force_per_length (N/m) or dimensionless_load";
    let t = sub(top, "load", "the applied load")?.ok_or_else(|| top.missing("load", what))?;
    let s = Sec {
        file: top.file,
        path: "load",
        table: t,
    };
    let given: Vec<&str> = LOAD_FORMS.iter().copied().filter(|k| s.has(k)).collect();
    match given.len() {
        0 => return Err(top.missing("load", what)),
        1 => {}
        _ => {
            return Err(s.err(
                given[1],
                format!(
                    "give exactly one form of the load, found both `load.{}` and `load.{}`",
                    given[0], given[1]
                ),
            ))
        }
    }
    let form = given[0];
    let units_of = |k: &str| match k {
        "force" => "N",
        "max_hertz_pressure" => "Pa",
        "force_per_length" => "N/m",
        _ => "dimensionless",
    };
    let v = s.positive(form, units_of(form))?.expect("present");
    // the Hertz pressure against E': checked before anything is derived from the load
    let check_ph = |ph: f64| -> R<()> {
        let ratio = ph / e_red;
        if within_derived(MIN_PRESSURE_OVER_MODULUS, MAX_PRESSURE_OVER_MODULUS, ratio) {
            return Ok(());
        }
        Err(s.err(
            form,
            format!(
                "{} = {} gives a Hertz pressure of {} Pa, {} times the reduced modulus E' = {} Pa (from body1/body2.youngs_modulus and poisson_ratio) at the reduced radius R = {} m (from body1/body2.radius, and length for rollers); the contact models hold for p_h / E' between {} and {} (above: the contact is no longer small against the radius and linear elasticity ends; below: the deflection is lost in round-off)",
                form, fmt_num(v), fmt_num(ph), fmt_num(ratio), fmt_num(e_red), fmt_num(r),
                fmt_num(MIN_PRESSURE_OVER_MODULUS), fmt_num(MAX_PRESSURE_OVER_MODULUS)
            ),
        ))
    };
    match c {
        Contact::Point { circular, ry } => {
            let f = match form {
                "force" => v,
                "max_hertz_pressure" if circular => units::point_load_for_pressure(v, r, e_red),
                "max_hertz_pressure" => {
                    return Err(Error::Unsupported {
                        file: top.file.to_string(),
                        key: "load.max_hertz_pressure".into(),
                        message: "the load for a given Hertz pressure of an elliptical contact (radius_y != radius) is not built yet; give load.force".into(),
                    })
                }
                "force_per_length" => {
                    return Err(s.err(
                        form,
                        "a ball makes a point contact, which has no load per unit length: give load.force (N), max_hertz_pressure (Pa) or dimensionless_load (W = F/(E' R^2))",
                    ))
                }
                // W = F / (E' R^2)
                _ => v * e_red * r * r,
            };
            let (a, ky, p0) = if circular {
                let h = units::hertz_point(f, r, e_red);
                (h.a, 1.0, h.p0)
            } else {
                let h = crate::reference::hertz::hertz_elliptical(f, r, ry, e_red);
                (h.a_x, h.a_y / h.a_x, h.p0)
            };
            check_ph(p0)?;
            Ok((
                Load {
                    force: f,
                    force_per_length: f / (2.0 * a),
                },
                a,
                ky,
            ))
        }
        Contact::Line { len, .. } => {
            let w = match form {
                "force" if len.is_infinite() => {
                    return Err(s.err(
                        form,
                        "an infinite line contact (length = inf) has no total load: give load.force_per_length (N/m) instead (or max_hertz_pressure or dimensionless_load)",
                    ))
                }
                "force" => v / len,
                "max_hertz_pressure" => units::line_load_for_pressure(v, r, e_red),
                "force_per_length" => v,
                // W = w' / (E' R)
                _ => v * e_red * r,
            };
            check_ph(units::hertz_line_pressure(w, r, e_red))?;
            let l = if len.is_finite() { len } else { 1.0 };
            Ok((
                Load {
                    force: w * l,
                    force_per_length: w,
                },
                units::hertz_line_half_width(w, r, e_red),
                f64::NAN,
            ))
        }
    }
}

/// `[lubricant]` (ehl only).
fn lubricant(top: &Sec, e_red: f64) -> R<(Lubricant, RheologyTables)> {
    let t = sub(top, "lubricant", "the lubricant's properties")?.ok_or_else(|| {
        top.missing(
            "lubricant",
            "a [lubricant] table for kind = \"ehl\" (viscosity, pressure_viscosity_coefficient, density)",
        )
    })?;
    let s = Sec {
        file: top.file,
        path: "lubricant",
        table: t,
    };
    let viscosity = s.required_positive(
        "viscosity",
        "Pa s",
        "the viscosity at ambient pressure in Pa s, e.g. viscosity = 0.04",
    )?;
    let alpha = match (
        s.has("pressure_viscosity_coefficient"),
        s.has("dimensionless_material"),
    ) {
        (true, true) => {
            return Err(s.err(
                "dimensionless_material",
                "give either pressure_viscosity_coefficient (alpha, 1/Pa) or dimensionless_material (G = alpha E'), not both",
            ))
        }
        (false, false) => {
            return Err(s.missing(
                "pressure_viscosity_coefficient",
                "the pressure-viscosity coefficient alpha in 1/Pa, e.g. pressure_viscosity_coefficient = 15.9e-9 (or dimensionless_material = G)",
            ))
        }
        (true, false) => {
            let a = s
                .non_negative("pressure_viscosity_coefficient", "1/Pa")?
                .expect("present");
            if a > 1e-6 {
                return Err(s.err(
                    "pressure_viscosity_coefficient",
                    format!(
                        "alpha = {} 1/Pa is far above any lubricant (mineral oils: 1e-8 to 3e-8 1/Pa); it is given in 1/Pa, so 15.9 GPa^-1 is written 15.9e-9",
                        fmt_num(a)
                    ),
                ));
            }
            a
        }
        (false, true) => {
            // G = alpha E'
            s.non_negative("dimensionless_material", "dimensionless")?
                .expect("present")
                / e_red
        }
    };
    let density = s.required_positive(
        "density",
        "kg/m^3",
        "the density at ambient pressure in kg/m^3, e.g. density = 846",
    )?;
    let viscosity_model = match s.choice("viscosity_model", &["roelands", "barus"])? {
        Some("barus") => ViscosityModel::Barus,
        _ => ViscosityModel::Roelands,
    };
    let density_model = match s.choice("density_model", &["dowson-higginson", "constant"])? {
        Some("constant") => DensityModel::Constant,
        _ => DensityModel::DowsonHigginson,
    };
    let (rheology, tables) = rheology(&s)?;
    Ok((
        Lubricant {
            viscosity,
            pressure_viscosity_coefficient: alpha,
            density,
            viscosity_model,
            density_model,
            rheology,
        },
        tables,
    ))
}

fn rheology(s: &Sec) -> R<(Rheology, RheologyTables)> {
    let key = s.key("rheology");
    let Some((p, model)) = RHEOLOGY.read(s, &key)? else {
        return Ok((Rheology::Newtonian, RheologyTables::default()));
    };
    // a parameter given as [[T, value], ...] pairs varies with temperature ([thermal]): its
    // first value stands in until the inlet temperature is known (`thermal`)
    let mut tables = RheologyTables::default();
    let mut param = |k: &str, unit: &str, required: bool| -> R<Option<f64>> {
        if let Some(t) = temperature_pairs(&p, k, unit)? {
            let v = t.0[0].1;
            match k {
                "shear_modulus" => tables.shear_modulus = Some(t),
                "power_law_index" => tables.power_law_index = Some(t),
                "eyring_stress" => tables.eyring_stress = Some(t),
                _ => tables.limiting_shear_coefficient = Some(t),
            }
            return Ok(Some(v));
        }
        if required {
            RHEOLOGY.need(&p, model, k, unit).map(Some)
        } else {
            p.positive(k, unit)
        }
    };
    let lsc = param(
        "limiting_shear_coefficient",
        "dimensionless, tau_L / p",
        false,
    )?;
    let rheology = match model {
        "carreau" => {
            let shear_modulus = param("shear_modulus", "Pa", true)?.unwrap_or(f64::NAN);
            let n = param("power_law_index", "dimensionless", true)?.unwrap_or(f64::NAN);
            let ns = tables
                .power_law_index
                .as_ref()
                .map_or(vec![n], |t| t.0.iter().map(|v| v.1).collect());
            if let Some(n) = ns.into_iter().find(|&n| n > 1.0) {
                return Err(p.err(
                    "power_law_index",
                    format!("the Carreau power-law index of a shear-thinning lubricant lies in (0, 1], found {}", fmt_num(n)),
                ));
            }
            Rheology::Carreau {
                shear_modulus,
                power_law_index: n,
                limiting_shear_coefficient: lsc,
            }
        }
        "eyring" => Rheology::Eyring {
            eyring_stress: param("eyring_stress", "Pa", true)?.unwrap_or(f64::NAN),
            limiting_shear_coefficient: lsc,
        },
        _ => Rheology::Newtonian,
    };
    Ok((rheology, tables))
}

/// `thermal.conductivity_pressure = [a, b]` (1/Pa, each >= 0 and finite): the oil's
/// conductivity k0 (1 + a p / (1 + b p)); [0, 0] when absent.
fn conductivity_pressure(s: &Sec) -> R<[f64; 2]> {
    let k = "conductivity_pressure";
    let Some(v) = s.get(k) else {
        return Ok([0.0; 2]);
    };
    let hint = "give [a, b] in 1/Pa, the conductivity being conductivity * (1 + a p / (1 + b p)), e.g. [1.7e-9, 0.5e-9] for a conductivity that doubles by about 1 GPa";
    let num = |v: &Value| match v {
        Value::Float(f) => Some(*f),
        Value::Integer(i) => Some(*i as f64),
        _ => None,
    };
    let pair = match v {
        Value::Array(a) if a.len() == 2 => (num(&a[0]), num(&a[1])),
        other => return Err(s.err(k, format!("found {}; {hint}", describe(other)))),
    };
    match pair {
        (Some(a), Some(b)) if a >= 0.0 && b >= 0.0 && a.is_finite() && b.is_finite() => Ok([a, b]),
        (Some(a), Some(b)) => Err(s.err(
            k,
            format!(
                "a and b must be finite and not negative (a conductivity that stays positive and grows with pressure), found [{}, {}]; {hint}",
                fmt_num(a),
                fmt_num(b)
            ),
        )),
        _ => Err(s.err(k, format!("a and b must be numbers; {hint}"))),
    }
}

/// A rheology parameter given at several temperatures, `k = [[T (K), value], ...]`: None when
/// the value is not an array. Temperatures positive and increasing, values positive.
fn temperature_pairs(s: &Sec, k: &str, unit: &str) -> R<Option<TemperatureTable>> {
    let Some(Value::Array(items)) = s.get(k) else {
        return Ok(None);
    };
    let bad = |why: String| {
        s.err(
            k,
            format!("{why}; a parameter that varies with temperature is given as [temperature K, value] pairs, e.g. {k} = [[313.0, 0.57], [373.0, 0.993]] ({unit})"),
        )
    };
    let num = |v: &Value| match v {
        Value::Float(f) => Some(*f),
        Value::Integer(i) => Some(*i as f64),
        _ => None,
    };
    let mut pairs = Vec::with_capacity(items.len());
    for (i, it) in items.iter().enumerate() {
        let pair = match it {
            Value::Array(a) if a.len() == 2 => (num(&a[0]), num(&a[1])),
            other => return Err(bad(format!("entry {i} is {}, not a pair", describe(other)))),
        };
        let (Some(t), Some(v)) = pair else {
            return Err(bad(format!("entry {i} is not a pair of numbers")));
        };
        if !(t > 0.0 && t.is_finite()) {
            return Err(bad(format!(
                "entry {i}: the temperature must be a positive number of K, found {}",
                fmt_num(t)
            )));
        }
        if !(v > 0.0 && v.is_finite()) {
            return Err(bad(format!(
                "entry {i}: the value must be positive and finite, found {}",
                fmt_num(v)
            )));
        }
        if let Some(&(t0, _)) = pairs.last() {
            if t <= t0 {
                return Err(bad(format!(
                    "the temperatures must increase, found {} after {}",
                    fmt_num(t),
                    fmt_num(t0)
                )));
            }
        }
        pairs.push((t, v));
    }
    if pairs.is_empty() {
        return Err(bad("the list is empty".into()));
    }
    Ok(Some(TemperatureTable(pairs)))
}

fn rheology_example(model: &str) -> &'static str {
    match model {
        "carreau" => "rheology = { model = \"carreau\", shear_modulus = 4.5e6, power_law_index = 0.57, limiting_shear_coefficient = 0.06 }",
        "eyring" => "rheology = { model = \"eyring\", eyring_stress = 5e6, limiting_shear_coefficient = 0.06 }",
        _ => "rheology = { model = \"newtonian\" }",
    }
}

/// `[motion]` (ehl only), with `motion.travel` when given.
fn motion(top: &Sec, e_red: f64, r: f64, eta0: f64) -> R<Motion> {
    let t = sub(top, "motion", "the surface speeds")?.ok_or_else(|| {
        top.missing(
            "motion",
            "a [motion] table for kind = \"ehl\" (entrainment_speed in m/s, slide_to_roll)",
        )
    })?;
    let s = Sec {
        file: top.file,
        path: "motion",
        table: t,
    };
    let u_e = match (s.has("entrainment_speed"), s.has("dimensionless_speed")) {
        (true, true) => {
            return Err(s.err(
                "dimensionless_speed",
                "give either entrainment_speed (m/s) or dimensionless_speed (U = eta0 u_e/(E' R)), not both",
            ))
        }
        (false, false) => {
            return Err(s.missing(
                "entrainment_speed",
                "the entrainment speed u_e = (u1 + u2)/2 in m/s, e.g. entrainment_speed = 2.7 (or dimensionless_speed = U)",
            ))
        }
        (true, false) => s.positive("entrainment_speed", "m/s")?.expect("present"),
        // U = eta0 u_e / (E' R)
        (false, true) => {
            s.positive("dimensionless_speed", "dimensionless")?.expect("present") * e_red * r / eta0
        }
    };
    // U = eta0 u_e / (E' R): EHL solutions and film formulas are established for U from about
    // 1e-14 (Moes' charts reach M, L for U ~ 1e-14) to 1e-8; outside 1e-16 .. 1e-7 the film
    // is either far below any surface roughness (h/R ~ U^0.7 < 1e-11) or so thick that the
    // contact is hydrodynamic (no elastic flattening) and the flows overflow
    let u_dim = units::speed_parameter(eta0, u_e, e_red, r);
    if !within_derived(MIN_SPEED_PARAMETER, MAX_SPEED_PARAMETER, u_dim) {
        let k = if s.has("entrainment_speed") {
            "entrainment_speed"
        } else {
            "dimensionless_speed"
        };
        return Err(s.err(
            k,
            format!(
                "gives the dimensionless speed U = eta0 u_e/(E' R) = {} (u_e = {} m/s, eta0 = {} Pa s from lubricant.viscosity, E' = {} Pa, R = {} m); the EHL solver is meaningful for U between {} and {}",
                fmt_num(u_dim), fmt_num(u_e), fmt_num(eta0), fmt_num(e_red), fmt_num(r),
                fmt_num(MIN_SPEED_PARAMETER), fmt_num(MAX_SPEED_PARAMETER)
            ),
        ));
    }
    let srr = s.finite("slide_to_roll", "dimensionless")?.unwrap_or(0.0);
    if srr.abs() > 2.0 {
        return Err(s.err(
            "slide_to_roll",
            format!(
                "SRR = (u1 - u2)/u_e lies between -2 and 2 while both surfaces move in the entrainment direction (2: body 2 at rest); found {}",
                fmt_num(srr)
            ),
        ));
    }
    let travel = match s.table(
        "travel",
        "the span of a transient run: { from, to, steps } or { duration, steps }",
    )? {
        None => None,
        Some(tt) => Some(travel(&s, tt)?),
    };
    Ok(Motion {
        entrainment_speed: u_e,
        slide_to_roll: srr,
        travel,
    })
}

/// Most time steps of a transient run (`motion.travel.steps`), as a sweep has at most 100 000
/// points: each step is a full EHL solve and a row of timeline.csv (and, kept, a frame of
/// frames.npz), so time and memory grow with the count; checked before anything is allocated.
pub const MAX_TRAVEL_STEPS: usize = 100_000;

/// `motion.travel`: `{ from, to, steps }` (the path of `features[0]`'s centre x_p, m) or
/// `{ duration, steps }` (s). What needs the features (the path form needs `features[0]` on a
/// moving body) is checked by [`check_travel`] once they are read.
fn travel(s: &Sec, tt: &Table) -> R<Travel> {
    let key = s.key("travel");
    let p = Sec {
        file: s.file,
        path: &key,
        table: tt,
    };
    let path_keys: Vec<&str> = ["from", "to"].into_iter().filter(|k| p.has(k)).collect();
    let timed = p.has("duration");
    if timed && !path_keys.is_empty() {
        return Err(p.err(
            "duration",
            format!(
                "give the travel either as a path of features[0]'s centre, {{ from, to, steps }} (m), or in time, {{ duration, steps }} (s), not both: found duration with motion.travel.{}",
                path_keys[0]
            ),
        ));
    }
    if !timed && path_keys.is_empty() {
        return Err(s.err(
            "travel",
            "gives neither form of the travel: write motion.travel = { from = -1e-3, to = 1e-3, steps = 200 } (the path of features[0]'s centre x_p, m) or motion.travel = { duration = 2e-4, steps = 200 } (s)",
        ));
    }
    // the form with its values; steps (read last, so that a missing `to` is named first) is
    // filled in below
    let form = if timed {
        Travel::Duration {
            duration: p.required_positive(
                "duration",
                "s",
                "the simulated time in s, e.g. duration = 2e-4",
            )?,
            steps: 0,
        }
    } else {
        let from = p.required_finite(
            "from",
            "m",
            "the start position x_p of features[0]'s centre in m, e.g. from = -1e-3",
        )?;
        let to = p.required_finite(
            "to",
            "m",
            "the end position x_p of features[0]'s centre in m, e.g. to = 1e-3",
        )?;
        if !(to > from) {
            return Err(p.err(
                "to",
                format!(
                    "must lie downstream of motion.travel.from (to > from): the surfaces move in +x (u1 = u_e (1 + SRR/2) and u2 = u_e (1 - SRR/2) are >= 0), so features[0]'s centre travels towards larger x; found from = {} m, to = {} m",
                    fmt_num(from),
                    fmt_num(to)
                ),
            ));
        }
        Travel::Path { from, to, steps: 0 }
    };
    let steps = required(
        p.count("steps", "time steps", 1)?,
        &p,
        "steps",
        "the number of time steps, e.g. steps = 200",
    )?;
    if steps > MAX_TRAVEL_STEPS {
        return Err(p.err(
            "steps",
            format!(
                "{steps} time steps is more than the {MAX_TRAVEL_STEPS} a transient run may have: each step is a full EHL solve and a row of the timeline (and a frame of frames.npz), so time and memory grow with the count; use fewer, longer steps"
            ),
        ));
    }
    Ok(match form {
        Travel::Path { from, to, .. } => Travel::Path { from, to, steps },
        Travel::Duration { duration, .. } => {
            if !(duration / steps as f64 > 0.0) {
                return Err(p.err(
                    "duration",
                    format!(
                        "{} s in {steps} steps gives a time step that rounds to 0 s",
                        fmt_num(duration)
                    ),
                ));
            }
            Travel::Duration { duration, steps }
        }
    })
}

/// The x_p range of a travel: `features[0]`'s centre goes from `start` to `end`; a snapshot may lie
/// half a step beyond; `source` says where the range comes from, for messages.
struct Span {
    start: f64,
    end: f64,
    half_step: f64,
    source: String,
}

/// The speed of body `body`'s surface (m/s) and its formula, for messages.
fn body_speed(m: &Motion, body: u8) -> (f64, &'static str) {
    if body == 1 {
        (m.u1(), "u1 = u_e (1 + SRR/2)")
    } else {
        (m.u2(), "u2 = u_e (1 - SRR/2)")
    }
}

/// The checks of `motion.travel` that need the features: the path form moves the centre of
/// `features[0]`, which must exist and ride on a moving body; the time step must be positive and
/// finite. Returns the x_p range of the travel when it is known (`features[0]` exists).
fn check_travel(file: &str, m: &Motion, t: Travel, features: &[FeatureSpec]) -> R<Option<Span>> {
    match t {
        Travel::Path { from, to, steps } => {
            let Some(f0) = features.first() else {
                return Err(case_err(
                    file,
                    "motion.travel.from",
                    "the path form { from, to, steps } moves the centre x_p of features[0], but the case has no [[features]]; for smooth surfaces give the travel in time: motion.travel = { duration = 2e-4, steps = 200 } (s)",
                ));
            };
            let (u, formula) = body_speed(m, f0.body);
            if !(u > 0.0) {
                return Err(case_err(
                    file,
                    "motion.travel",
                    format!(
                        "features[0] is on body {}, which stands still ({formula} = {} m/s at motion.slide_to_roll = {}), so its centre cannot travel from motion.travel.from to motion.travel.to; give the travel in time instead: motion.travel = {{ duration = 2e-4, steps = 200 }} (s)",
                        f0.body,
                        fmt_num(u),
                        fmt_num(m.slide_to_roll)
                    ),
                ));
            }
            let dt = (to - from) / steps as f64 / u;
            if !(dt > 0.0 && dt.is_finite()) {
                return Err(case_err(
                    file,
                    "motion.travel",
                    format!(
                        "the time step (to - from) / steps / {formula} = ({} - {}) m / {steps} / {} m/s = {} s is not a positive, finite time",
                        fmt_num(to), fmt_num(from), fmt_num(u), fmt_num(dt)
                    ),
                ));
            }
            Ok(Some(Span {
                start: from,
                end: to,
                half_step: 0.5 * (to - from) / steps as f64,
                source: "motion.travel.from .. to".into(),
            }))
        }
        Travel::Duration { duration, steps } => {
            let Some(f0) = features.first() else {
                return Ok(None);
            };
            let (u, formula) = body_speed(m, f0.body);
            let x0 = f0.feature.centre.0;
            let span = u * duration;
            Ok(Some(Span {
                start: x0,
                end: x0 + span,
                half_step: 0.5 * span / steps as f64,
                source: format!(
                    "features[0].x + {} t over motion.travel.duration = {} s, with body {} at {formula} = {} m/s",
                    if f0.body == 1 { "u1" } else { "u2" },
                    fmt_num(duration),
                    f0.body,
                    fmt_num(u)
                ),
            }))
        }
    }
}

/// `[alignment]`.
fn alignment(top: &Sec, point: bool) -> R<Alignment> {
    let Some(t) = sub(top, "alignment", "tilt and skew in rad")? else {
        return Ok(Alignment::default());
    };
    let s = Sec {
        file: top.file,
        path: "alignment",
        table: t,
    };
    let mut a = Alignment::default();
    for (k, slot) in [("tilt", &mut a.tilt), ("skew", &mut a.skew)] {
        let v = s.finite(k, "rad")?.unwrap_or(0.0);
        if v.abs() >= FRAC_PI_2 {
            return Err(s.err(
                k,
                format!(
                    "a misalignment angle must be smaller than pi/2 rad in size, found {}",
                    fmt_num(v)
                ),
            ));
        }
        if point && v != 0.0 {
            return Err(s.err(
                k,
                "misalignment applies to rollers; a ball contact has no axis to tilt or skew",
            ));
        }
        *slot = v;
    }
    Ok(a)
}

/// Checks the array size a .npy file's header declares (its shape times the item size of its
/// `descr`) against the bytes the file holds, before the reader allocates it: a header may
/// declare any shape, and a crafted 128-byte file declaring 10^12 values made the reader ask
/// for 8 TB and abort the program. Errors that the reader reports itself (a bad magic string,
/// a wrong type) are left to it.
fn npy_declared_size_fits(path: &std::path::Path) -> Result<(), String> {
    use std::io::Read;
    let len = std::fs::metadata(path).map_err(|e| e.to_string())?.len();
    let mut head = Vec::new();
    std::fs::File::open(path)
        .map_err(|e| e.to_string())?
        .take(1 << 16)
        .read_to_end(&mut head)
        .map_err(|e| e.to_string())?;
    if head.len() < 10 || &head[..6] != b"\x93NUMPY" {
        return Ok(());
    }
    let (start, header_len) = if head[6] == 1 {
        (10usize, u16::from_le_bytes([head[8], head[9]]) as usize)
    } else if head.len() >= 12 {
        (
            12,
            u32::from_le_bytes([head[8], head[9], head[10], head[11]]) as usize,
        )
    } else {
        return Ok(());
    };
    let Some(text) = head.get(start..start + header_len) else {
        return Ok(());
    };
    let text = String::from_utf8_lossy(text);
    let field = |key: &str| -> Option<String> {
        let at = text.find(&format!("'{key}'"))? + key.len() + 2;
        let rest = text[at..].trim_start().strip_prefix(':')?.trim_start();
        Some(rest.to_string())
    };
    let Some(shape) = field("shape").and_then(|r| {
        let r = r.strip_prefix('(')?;
        Some(r[..r.find(')')?].to_string())
    }) else {
        return Ok(());
    };
    let item = field("descr")
        .and_then(|r| {
            let r = r.strip_prefix('\'')?;
            let d = &r[..r.find('\'')?];
            d.trim_start_matches(|c: char| !c.is_ascii_digit())
                .parse::<u64>()
                .ok()
        })
        .unwrap_or(1);
    let mut count: u64 = 1;
    for dim in shape.split(',').map(str::trim).filter(|d| !d.is_empty()) {
        let Ok(n) = dim.parse::<u64>() else {
            return Ok(());
        };
        count = count
            .checked_mul(n)
            .ok_or_else(|| format!("its header declares a shape ({shape}) too large to hold"))?;
    }
    let need = count
        .checked_mul(item)
        .and_then(|b| b.checked_add((start + header_len) as u64))
        .ok_or_else(|| format!("its header declares a shape ({shape}) too large to hold"))?;
    if need > len {
        return Err(format!(
            "its header declares a shape ({shape}) of {count} values, {need} bytes with the header, but the file holds {len} bytes"
        ));
    }
    Ok(())
}

/// A skew leaves a line contact only while the skewed roller's length projected on body 1's
/// axis is longer than the contact is wide. Near pi/2 the axes cross and the contact becomes a
/// point contact of crossed cylinders, which the line-contact model (its Hertz line scales and
/// axial grid over the projected overlap) cannot represent: the projected length then goes to 0
/// and the line load per unit length, hence p_h, without bound. Refused when the projected
/// overlap `l_c` is shorter than the Hertz width 2 b_c at the load per unit of `l_c`
/// (b_c = b sqrt(l / l_c), b the half-width at the unprojected overlap l).
fn skew_keeps_a_line(
    top: &Sec,
    c: Contact,
    body1: &Body,
    body2: &Body,
    a: &Alignment,
    b: f64,
) -> R<()> {
    let Contact::Line { len, .. } = c else {
        return Ok(());
    };
    if a.skew == 0.0 || !len.is_finite() {
        return Ok(());
    }
    let half = |body: &Body, proj: f64| 0.5 * body.length * proj;
    let cos = a.skew.cos().abs();
    let (h1, h2) = (half(body1, 1.0), half(body2, cos));
    let off = body2.axial_offset;
    let mut lc = ((h1).min(off + h2) - (-h1).max(off - h2)).max(0.0);
    if !body2.length.is_finite() {
        // an endless body 2 overlaps body 1 whole at any skew: the crossing shows in body 1's
        // length projected on body 2's axis instead (a review)
        lc = lc.min(2.0 * h1 * cos);
    }
    let bc = if lc > 0.0 {
        b * (len / lc).sqrt()
    } else {
        f64::INFINITY
    };
    if lc >= 2.0 * bc {
        return Ok(());
    }
    Err(case_err(
        top.file,
        "alignment.skew",
        format!(
            "a skew of {} rad crosses the rollers' axes so far that body 2's length projected on body 1's axis overlaps it over only {} mm, shorter than the contact's Hertz width there ({} mm): the contact is then a point contact of crossed cylinders, which the finite line-contact model does not represent; keep the skew smaller (here the projected overlap must stay above the width, i.e. well below pi/2)",
            fmt_num(a.skew),
            fmt_num(lc * 1e3),
            fmt_num(2.0 * bc * 1e3)
        ),
    ))
}

/// `[grid]`, in units of the Hertz half-width `b` (contact radius a for balls).
/// `ky`: the Hertz semi-axis along y over the one along x (point contacts; NaN for lines).
fn grid(top: &Sec, kind: Kind, c: Contact, b: f64, ky: f64) -> R<GridSpec> {
    let empty = Table::new();
    let t = sub(top, "grid", "cell counts and extents")?.unwrap_or(&empty);
    let s = Sec {
        file: top.file,
        path: "grid",
        table: t,
    };
    let (half, width) = match c {
        Contact::Point { .. } => ("a", "contact diameter 2a"),
        _ => ("b", "contact width 2b"),
    };
    let infinite = matches!(c, Contact::Line { len, .. } if len.is_infinite());
    let nx = s.count("nx", "cells along x", 1)?.unwrap_or(DEFAULT_CELLS);
    let x_min = s
        .finite("x_min", "Hertz half-widths")?
        .unwrap_or(if kind == Kind::Dry { -1.5 } else { -4.0 });
    let x_max = s.finite("x_max", "Hertz half-widths")?.unwrap_or(1.5);
    let bstr = format!("{half} = {} mm", mm(b));
    if x_min >= x_max {
        return Err(s.err(
            "x_max",
            format!(
                "must be greater than grid.x_min; found x_min = {} and x_max = {} (both in Hertz half-widths, {bstr})",
                fmt_num(x_min),
                fmt_num(x_max)
            ),
        ));
    }
    if x_min > -1.0 {
        return Err(s.err(
            "x_min",
            format!("the grid must contain the whole Hertz contact, x from -{half} to {half}: x_min is in Hertz half-widths ({bstr}) and must be -1 or less, found {}", fmt_num(x_min)),
        ));
    }
    if x_max < 1.0 {
        return Err(s.err(
            "x_max",
            format!("the grid must contain the whole Hertz contact, x from -{half} to {half}: x_max is in Hertz half-widths ({bstr}) and must be 1 or more, found {}", fmt_num(x_max)),
        ));
    }
    let across = 2.0 * nx as f64 / (x_max - x_min);
    if across < MIN_CELLS_ACROSS_CONTACT {
        let need = (MIN_CELLS_ACROSS_CONTACT * (x_max - x_min) / 2.0).ceil();
        return Err(s.err(
            "nx",
            format!(
                "grid too coarse to resolve the Hertz contact: nx = {nx} cells over x = {} .. {} {half} put only {:.1} cells across the Hertz {width} = {} mm; at least {} are needed. Raise grid.nx to {need} or more, or narrow x_min .. x_max",
                fmt_num(x_min),
                fmt_num(x_max),
                across,
                mm(2.0 * b),
                MIN_CELLS_ACROSS_CONTACT
            ),
        ));
    }

    let (ny, y_min, y_max) = if infinite {
        if let Some(ny) = s.int("ny", "cells along y")? {
            if ny != 1 {
                return Err(s.err(
                    "ny",
                    format!("an infinite line contact (length = inf) is solved in 1D: grid.ny must be 1 or left out, found {ny}"),
                ));
            }
        }
        for k in ["y_min", "y_max"] {
            forbid(&s, k, "is not used for an infinite line contact (length = inf, solved in 1D); leave it out")?;
        }
        // the 1 m reference length of the library's convention, in units of b
        (1, -0.5 / b, 0.5 / b)
    } else {
        let ny = s.count("ny", "cells along y", 2)?.unwrap_or(DEFAULT_CELLS);
        let (dlo, dhi) = match c {
            Contact::Line { ulo, uhi, .. } => (ulo / b, uhi / b),
            // three semi-axes of the Hertz ellipse each side (the circle: -3 .. 3 a)
            Contact::Point { .. } => (-3.0 * ky, 3.0 * ky),
        };
        let y_min = s.finite("y_min", "Hertz half-widths")?.unwrap_or(dlo);
        let y_max = s.finite("y_max", "Hertz half-widths")?.unwrap_or(dhi);
        if y_min >= y_max {
            return Err(s.err(
                "y_max",
                format!(
                    "must be greater than grid.y_min; found y_min = {} and y_max = {} (both in Hertz half-widths, {bstr})",
                    fmt_num(y_min),
                    fmt_num(y_max)
                ),
            ));
        }
        match c {
            Contact::Line { lo, hi, len, .. } => {
                let tol = 1e-9 * len / b;
                if y_min > lo / b + tol || y_max < hi / b - tol {
                    let k = if y_min > lo / b + tol {
                        "y_min"
                    } else {
                        "y_max"
                    };
                    return Err(s.err(
                        k,
                        format!(
                            "the grid must cover the whole contact length: the rollers touch over y = {} .. {} mm = {} .. {} b ({bstr}), but the grid covers y = {} .. {} b",
                            mm(lo), mm(hi), fmt_num(lo / b), fmt_num(hi / b), fmt_num(y_min), fmt_num(y_max)
                        ),
                    ));
                }
                let along = ny as f64 * (len / b) / (y_max - y_min);
                if along < MIN_CELLS_ACROSS_CONTACT {
                    return Err(s.err(
                        "ny",
                        format!(
                            "grid too coarse along the roller: ny = {ny} cells over y = {} .. {} b put only {:.1} cells along the contact length {} mm; at least {} are needed",
                            fmt_num(y_min), fmt_num(y_max), along, mm(len), MIN_CELLS_ACROSS_CONTACT
                        ),
                    ));
                }
            }
            Contact::Point { .. } => {
                // the Hertz ellipse spans y = -a_y .. a_y = -ky .. ky in units of a = a_x
                let tol = 1e-9 * ky;
                if y_min > -ky + tol || y_max < ky - tol {
                    let k = if y_min > -ky + tol { "y_min" } else { "y_max" };
                    return Err(s.err(
                        k,
                        format!("the grid must contain the whole Hertz contact, y from -a_y to a_y = {} mm = {} a: y_min must be -{} or less and y_max {} or more (in units of the semi-axis along x, {bstr}); found {} .. {}", mm(ky * b), fmt_num(ky), fmt_num(ky), fmt_num(ky), fmt_num(y_min), fmt_num(y_max)),
                    ));
                }
                let across = 2.0 * ky * ny as f64 / (y_max - y_min);
                if across < MIN_CELLS_ACROSS_CONTACT {
                    let need = (MIN_CELLS_ACROSS_CONTACT * (y_max - y_min) / (2.0 * ky)).ceil();
                    return Err(s.err(
                        "ny",
                        format!(
                            "grid too coarse to resolve the Hertz contact: ny = {ny} cells over y = {} .. {} a put only {:.1} cells across the Hertz contact length 2a_y = {} mm; at least {} are needed. Raise grid.ny to {need} or more",
                            fmt_num(y_min), fmt_num(y_max), across, mm(2.0 * ky * b), MIN_CELLS_ACROSS_CONTACT
                        ),
                    ));
                }
            }
        }
        (ny, y_min, y_max)
    };
    if nx.saturating_mul(ny) > MAX_CELLS {
        return Err(s.err(
            "nx",
            format!("nx * ny = {nx} * {ny} cells is more than the {MAX_CELLS} cells (0.5 GB per field) this program accepts"),
        ));
    }
    Ok(GridSpec {
        nx,
        ny,
        x_min,
        x_max,
        y_min,
        y_max,
    })
}

/// `[solver]`.
fn solver(top: &Sec, kind: Kind) -> R<SolverSpec> {
    let empty = Table::new();
    let t = sub(top, "solver", "solver settings")?.unwrap_or(&empty);
    let s = Sec {
        file: top.file,
        path: "solver",
        table: t,
    };
    let tolerance = s.positive("tolerance", "relative")?.unwrap_or(1e-6);
    if tolerance >= 1.0 {
        return Err(s.err(
            "tolerance",
            format!(
                "a relative tolerance must be below 1 (e.g. 1e-6), found {}",
                fmt_num(tolerance)
            ),
        ));
    }
    Ok(SolverSpec {
        tolerance,
        max_iterations: s
            .count("max_iterations", "iterations", 1)?
            .unwrap_or(match kind {
                Kind::Dry => DEFAULT_DRY_ITERATIONS,
                Kind::Ehl => DEFAULT_EHL_ITERATIONS,
            }),
        mirror_levels: match s
            .count("mirror_levels", "mirror levels at each roller end", 0)?
            .unwrap_or(1)
        {
            l if l > crate::run::MAX_MIRROR_LEVELS => {
                return Err(s.err(
                    "mirror_levels",
                    format!(
                        "at most {} mirror levels, found {l}: from level 12 on one more level changes the maximum pressure by less than 1e-4 relative (the images move one roller length further out per level), while each level costs one more kernel table",
                        crate::run::MAX_MIRROR_LEVELS
                    ),
                ))
            }
            l => l,
        },
        free_end_correction: s.boolean("free_end_correction")?.unwrap_or(true),
        wedge_upwind_order: match s.count("wedge_upwind_order", "upwind order", 1)? {
            None | Some(2) => 2,
            Some(1) => 1,
            Some(o) => {
                return Err(s.err(
                    "wedge_upwind_order",
                    format!(
                        "the wedge term is discretised by first- or second-order upwinding: 1 or 2, found {o}"
                    ),
                ))
            }
        },
    })
}

/// `[[features]]`: validated, loaded (a height map's `.npy` file, relative to the case file's
/// folder) and checked to lie inside the grid.
fn features(
    top: &Sec,
    g: &GridSpec,
    b: f64,
    r: f64,
    infinite: bool,
    travel: bool,
) -> R<Vec<FeatureSpec>> {
    use crate::surface::{Feature, FeatureShape, HeightMap, Pattern};
    let Some(v) = top.get("features") else {
        return Ok(Vec::new());
    };
    let items = match v {
        Value::Array(items) => items,
        Value::Table(_) => {
            return Err(top.err(
                "features",
                "write each feature as its own [[features]] table (double brackets: an array of tables)",
            ))
        }
        other => {
            return Err(top.err(
                "features",
                format!("expected [[features]] tables, found {}", describe(other)),
            ))
        }
    };
    let (xlo, xhi) = (g.x_min * b, g.x_max * b);
    let (ylo, yhi) = (g.y_min * b, g.y_max * b);
    let mut out = Vec::with_capacity(items.len());
    for (i, item) in items.iter().enumerate() {
        let path = format!("features[{i}]");
        let Value::Table(t) = item else {
            return Err(case_err(
                top.file,
                &path,
                format!("expected a [[features]] table, found {}", describe(item)),
            ));
        };
        let s = Sec {
            file: top.file,
            path: &path,
            table: t,
        };
        let kind = required(
            s.choice("kind", FEATURE_KINDS)?,
            &s,
            "kind",
            "the feature kind: \"pit\", \"dent\", \"waviness\" or \"height-map\"",
        )?;
        let body = match s.int("body", "1 or 2")? {
            None => 1,
            Some(b @ (1 | 2)) => b as u8,
            Some(b) => {
                return Err(s.err(
                    "body",
                    format!("must be 1 or 2 (the body that carries the feature), found {b}"),
                ))
            }
        };
        let x = s.finite("x", "m")?.unwrap_or(0.0);
        let y = s.finite("y", "m")?.unwrap_or(0.0);
        // a length along y may be inf (a groove); widths and lengths are positive
        let extent = |k: &str, allow_inf: bool, what: &str| -> R<f64> {
            let v = s.required_num(k, "m", what)?;
            if !(v > 0.0) || (v.is_infinite() && !allow_inf) {
                return Err(s.err(
                    k,
                    format!(
                        "must be a positive{} length in m, found {}",
                        if allow_inf { " (or inf)" } else { ", finite" },
                        fmt_num(v)
                    ),
                ));
            }
            Ok(v)
        };
        let shape = match kind {
            "height-map" => {
                for k in ["width", "length", "depth", "amplitude", "wavelength"] {
                    forbid(
                        &s,
                        k,
                        "is not used by a height-map feature (it has file, dx, dy, x, y and an optional pattern)",
                    )?;
                }
                let name = required(
                    s.string("file", "path of a .npy height map")?,
                    &s,
                    "file",
                    "the height map file (.npy, a 2D array of depths in m, rows along y)",
                )?;
                let dx = s.required_positive("dx", "m", "the height map's spacing along x in m")?;
                let dy = s.required_positive("dy", "m", "the height map's spacing along y in m")?;
                let base = std::path::Path::new(top.file)
                    .parent()
                    .unwrap_or(std::path::Path::new(""));
                let at = base.join(name);
                npy_declared_size_fits(&at).map_err(|e| {
                    s.err(
                        "file",
                        format!("cannot read `{}` as a .npy height map: {e}", at.display()),
                    )
                })?;
                let depths: ndarray::Array2<f64> = ndarray_npy::read_npy(&at).map_err(|e| {
                    s.err(
                        "file",
                        format!(
                            "cannot read `{}` as a 2D .npy array of float64 depths (m): {e}",
                            at.display()
                        ),
                    )
                })?;
                FeatureShape::HeightMap(HeightMap { depths, dx, dy })
            }
            "waviness" => {
                for k in ["width", "length", "depth", "pattern", "file", "dx", "dy"] {
                    forbid(
                        &s,
                        k,
                        "is not used by a waviness (it covers the whole body: amplitude, wavelength, x)",
                    )?;
                }
                FeatureShape::Waviness {
                    amplitude: s.required_finite(
                        "amplitude",
                        "m",
                        "the waviness amplitude in m, e.g. amplitude = 0.1e-6",
                    )?,
                    wavelength: s.required_positive(
                        "wavelength",
                        "m",
                        "the waviness wavelength in m, e.g. wavelength = 0.5e-3",
                    )?,
                }
            }
            _ => {
                for k in ["file", "dx", "dy", "amplitude", "wavelength"] {
                    forbid(
                        &s,
                        k,
                        "is used only by kind = \"height-map\" or \"waviness\"",
                    )?;
                }
                let width = extent("width", false, "the feature's width along x in m")?;
                let length = if kind == "dent" && !s.has("length") {
                    width
                } else {
                    extent(
                        "length",
                        true,
                        "the feature's length along y in m (inf for a transverse groove)",
                    )?
                };
                let depth = s.required_finite(
                    "depth",
                    "m",
                    "the feature's depth in m (positive: a pit; negative: a bump)",
                )?;
                if kind == "pit" {
                    FeatureShape::Pit {
                        width,
                        length,
                        depth,
                    }
                } else {
                    FeatureShape::Dent {
                        width,
                        length,
                        depth,
                    }
                }
            }
        };
        // the gap model is parabolic (small slopes): a feature deeper than a hundredth of the
        // reduced radius is outside it (and a pit that deep is a hole, not a surface feature)
        let (depth_key, depth) = match &shape {
            FeatureShape::Pit { depth, .. } | FeatureShape::Dent { depth, .. } => ("depth", *depth),
            FeatureShape::Waviness { amplitude, .. } => ("amplitude", *amplitude),
            FeatureShape::HeightMap(m) => {
                ("file", m.depths.iter().fold(0.0f64, |a, d| a.max(d.abs())))
            }
        };
        if !(depth.abs() <= 0.01 * r) {
            return Err(s.err(
                depth_key,
                format!(
                    "a feature {} {} mm deep is outside the small-slope gap model: at most 1 % of the reduced radius R = {} mm, i.e. {} mm",
                    if depth_key == "file" { "whose map is up to" } else { "of" },
                    mm(depth.abs()),
                    mm(r),
                    mm(0.01 * r)
                ),
            ));
        }
        let (mut hx, mut hy) = match &shape {
            FeatureShape::Pit { width, length, .. } | FeatureShape::Dent { width, length, .. } => {
                (0.5 * width, 0.5 * length)
            }
            FeatureShape::HeightMap(m) => (
                0.5 * (m.depths.ncols().max(1) - 1) as f64 * m.dx,
                0.5 * (m.depths.nrows().max(1) - 1) as f64 * m.dy,
            ),
            FeatureShape::Waviness { .. } => (0.0, 0.0),
        };
        let mut pattern = None;
        if let Some(pt) = s.table("pattern", "{ rows, columns, row_pitch, column_pitch }")? {
            let key = s.key("pattern");
            let p = Sec {
                file: top.file,
                path: &key,
                table: pt,
            };
            let rows = p.count("rows", "features along x", 1)?.unwrap_or(1);
            let cols = p.count("columns", "features along y", 1)?.unwrap_or(1);
            let rp = p.positive("row_pitch", "m")?;
            let cp = p.positive("column_pitch", "m")?;
            if rows > 1 && rp.is_none() {
                return Err(p.missing(
                    "row_pitch",
                    "the centre-to-centre spacing of the rows along x in m",
                ));
            }
            if cols > 1 && cp.is_none() {
                return Err(p.missing(
                    "column_pitch",
                    "the centre-to-centre spacing of the columns along y in m",
                ));
            }
            if rows.saturating_mul(cols) > 10_000 {
                return Err(p.err(
                    "rows",
                    format!("a pattern of {rows} x {cols} copies is more than the 10000 this program accepts"),
                ));
            }
            hx += 0.5 * (rows - 1) as f64 * rp.unwrap_or(0.0);
            hy += 0.5 * (cols - 1) as f64 * cp.unwrap_or(0.0);
            pattern = Some(Pattern {
                rows,
                columns: cols,
                row_pitch: rp.unwrap_or(0.0),
                column_pitch: cp.unwrap_or(0.0),
            });
        }
        // an infinite line contact is solved in 1D on a 1 m reference strip: a feature of finite
        // extent along y would be averaged over that strip (a 0.5 mm pit as 1/2000 of its
        // depth); only features uniform along y have a 1D meaning
        if infinite {
            let uniform = match &shape {
                FeatureShape::Pit { length, .. } | FeatureShape::Dent { length, .. } => {
                    length.is_infinite()
                }
                FeatureShape::Waviness { .. } => true,
                FeatureShape::HeightMap(_) => false,
            };
            if !uniform {
                let k = if kind == "height-map" {
                    "kind"
                } else {
                    "length"
                };
                return Err(s.err(
                    k,
                    "an infinite line contact (length = inf) is solved in 1D, where a feature must be uniform along y: give length = inf (a transverse groove) or use a waviness; for a finite pit use finite rollers",
                ));
            }
        }
        let localized = !matches!(shape, FeatureShape::Waviness { .. });
        if localized && !travel && (x - hx < xlo || x + hx > xhi) {
            return Err(s.err(
                "x",
                format!(
                    "the feature must lie wholly inside the grid in a steady run: it spans x = {} .. {} mm but the grid covers x = {} .. {} mm (grid.x_min .. x_max = {} .. {} Hertz half-widths of {} mm)",
                    mm(x - hx), mm(x + hx), mm(xlo), mm(xhi), fmt_num(g.x_min), fmt_num(g.x_max), mm(b)
                ),
            ));
        }
        if localized && hy.is_finite() && !infinite && (y - hy < ylo || y + hy > yhi) {
            return Err(s.err(
                "y",
                format!(
                    "the feature must lie wholly inside the grid: it spans y = {} .. {} mm but the grid covers y = {} .. {} mm",
                    mm(y - hy), mm(y + hy), mm(ylo), mm(yhi)
                ),
            ));
        }
        let mut feature = Feature::new(shape, (x, y));
        if let Some(p) = pattern {
            feature = feature.with_pattern(p);
        }
        // a height map's own faults (its nodes, its depths) are its file's
        let faulty = if matches!(feature.shape, FeatureShape::HeightMap(_)) {
            "file"
        } else {
            "kind"
        };
        feature.check().map_err(|m| s.err(faulty, m))?;
        let mut table = t.clone();
        table.insert("body".into(), Value::Integer(body as i64));
        out.push(FeatureSpec {
            table,
            body,
            feature,
        });
    }
    Ok(out)
}

/// `[output]` (optional; its keys matter only for transient runs). `span`: the x_p range of the
/// travel, when known: every snapshot must lie within it.
fn output(top: &Sec, span: Option<Span>) -> R<OutputSpec> {
    let Some(t) = sub(top, "output", "the outputs of a transient run")? else {
        return Ok(OutputSpec::default());
    };
    let s = Sec {
        file: top.file,
        path: "output",
        table: t,
    };
    let frames_every = s.count("frames_every", "keep every k-th step in frames.npz", 1)?;
    let animation = s.boolean("animation")?.unwrap_or(true);
    let example = "e.g. snapshots = [-0.5e-3, 0.0, 0.5e-3]";
    let snapshots = match s.get("snapshots") {
        None => Vec::new(),
        Some(Value::Array(items)) => {
            let mut v = Vec::with_capacity(items.len());
            for (i, item) in items.iter().enumerate() {
                let x = match item {
                    Value::Float(f) => *f,
                    Value::Integer(n) => *n as f64,
                    other => {
                        return Err(s.err(
                            "snapshots",
                            format!(
                                "expected x_p values in m, {example}; snapshots[{i}] is {}",
                                describe(other)
                            ),
                        ))
                    }
                };
                if !x.is_finite() {
                    return Err(s.err(
                        "snapshots",
                        format!(
                            "snapshots[{i}] must be a finite x_p in m, found {}",
                            fmt_num(x)
                        ),
                    ));
                }
                v.push(x);
            }
            v
        }
        Some(other) => {
            return Err(s.err(
                "snapshots",
                format!(
                    "expected an array of x_p values in m, {example}; found {}",
                    describe(other)
                ),
            ))
        }
    };
    if let Some(Span {
        start,
        end,
        half_step,
        source,
    }) = span
    {
        let (lo, hi) = (start.min(end), start.max(end));
        let tol = half_step.abs();
        for (i, &x) in snapshots.iter().enumerate() {
            if x < lo - tol || x > hi + tol {
                return Err(s.err(
                    "snapshots",
                    format!(
                        "x_p = {} m (snapshots[{i}]) lies outside the travel of features[0]'s centre, x_p = {} .. {} m ({source}), give or take half a step ({} m): a snapshot is written at the step whose x_p is nearest, so it must lie within the travel",
                        fmt_num(x),
                        fmt_num(start),
                        fmt_num(end),
                        fmt_num(tol)
                    ),
                ));
            }
        }
    }
    Ok(OutputSpec {
        frames_every,
        snapshots,
        animation,
    })
}

/// `[stress]` (optional). `b`: the Hertz half-width (m) that `depth` is given in.
/// `transient`: the case has a `motion.travel` (the passage maps need one).
fn stress(top: &Sec, kind: Kind, b: f64, transient: bool) -> R<Option<StressSpec>> {
    let Some(t) = sub(top, "stress", "the stress below the surface")? else {
        return Ok(None);
    };
    let s = Sec {
        file: top.file,
        path: "stress",
        table: t,
    };
    let bodies = match s.get("body") {
        None => vec![1, 2],
        Some(Value::Integer(1)) => vec![1],
        Some(Value::Integer(2)) => vec![2],
        Some(Value::String(v)) if v == "both" => vec![1, 2],
        Some(other) => {
            return Err(s.err(
                "body",
                format!(
                    "expected 1, 2 or \"both\" (the body whose stress is computed), found {}",
                    describe(other)
                ),
            ))
        }
    };
    let depth_m = match (s.positive("depth", "Hertz half-widths b")?, s.positive("depth_m", "m")?) {
        (Some(_), Some(_)) => {
            return Err(s.err(
                "depth_m",
                "give the deepest layer once: depth (in Hertz half-widths b) or depth_m (in m), not both",
            ))
        }
        (Some(d), None) => d * b,
        (None, Some(d)) => d,
        (None, None) => 3.0 * b,
    };
    let layers = s
        .count("layers", "the number of depth layers", 1)?
        .unwrap_or(48);
    if layers > 1024 {
        return Err(s.err(
            "layers",
            format!("{layers} layers is more than 1024; the cost grows with the layers"),
        ));
    }
    let spacing = match s.choice("spacing", &["geometric", "uniform"])? {
        Some("uniform") => DepthSpacing::Uniform,
        _ => DepthSpacing::Geometric,
    };
    let friction = s
        .non_negative("friction", "Coulomb coefficient")?
        .unwrap_or(0.0);
    if friction != 0.0 && kind == Kind::Ehl {
        return Err(s.err(
            "friction",
            "stress.friction is for dry runs; in an EHL run the surface shear comes from the lubricant's rheology (the friction integral's shear stress)",
        ));
    }
    // the passage maps of a transient run keep the layers down to the window (in b)
    let window_m = match s.positive("window", "Hertz half-widths b")? {
        None => None,
        Some(_) if !transient => {
            return Err(s.err(
                "window",
                "stress.window limits the depth of the passage maps of a transient run (motion.travel); a steady run has no passage: leave the key out, or add motion.travel",
            ))
        }
        Some(w) if w * b > depth_m * (1.0 + 1e-9) => {
            return Err(s.err(
                "window",
                format!(
                    "the window ({} b = {} m) reaches below the deepest layer of the depth grid ({} m = {} b): give a window <= the depth",
                    fmt_num(w),
                    fmt_num(w * b),
                    fmt_num(depth_m),
                    fmt_num(depth_m / b)
                ),
            ))
        }
        Some(w) => Some(w * b),
    };
    Ok(Some(StressSpec {
        bodies,
        depth_m,
        layers,
        spacing,
        friction,
        window_m,
    }))
}

/// `[fatigue]` (optional; needs `[stress]`).
/// `transient`: the case has a `motion.travel` (Dang Van needs the passage).
fn fatigue(top: &Sec, has_stress: bool, transient: bool) -> R<Option<FatigueSpec>> {
    let Some(t) = sub(top, "fatigue", "the fatigue indicator")? else {
        return Ok(None);
    };
    let s = Sec {
        file: top.file,
        path: "fatigue",
        table: t,
    };
    if !has_stress {
        return Err(case_err(
            top.file,
            "fatigue",
            "[fatigue] needs the stress below the surface: add a [stress] table (e.g. [stress] with depth = 3.0, layers = 48)",
        ));
    }
    use crate::stress::fatigue::Criterion;
    let criterion = match s.choice("criterion", &["von-mises", "orthogonal-shear", "max-shear"])? {
        Some("orthogonal-shear") => Criterion::OrthogonalShear,
        Some("max-shear") => Criterion::MaxShear,
        _ => Criterion::VonMises,
    };
    let fatigue_limit = s.non_negative("fatigue_limit", "Pa")?.unwrap_or(0.0);
    let weibull_slope = s.positive("weibull_slope", "dimensionless")?.unwrap_or(1.1);
    let stress_exponent = s
        .positive("stress_exponent", "dimensionless")?
        .unwrap_or(31.0 / 3.0);
    let depth_exponent = s
        .non_negative("depth_exponent", "dimensionless")?
        .unwrap_or(0.0);
    let dang_van = match s.table(
        "dang_van",
        "the Dang Van indicator over the passage: { alpha = 0.3, beta = 4.5e8 }",
    )? {
        None => None,
        Some(_) if !transient => {
            return Err(s.err(
                "dang_van",
                "the Dang Van indicator needs the stress history of each material point over a passage through the contact, which only a transient run (motion.travel) has; leave fatigue.dang_van out of a steady run",
            ))
        }
        Some(t) => {
            let key = s.key("dang_van");
            let d = Sec {
                file: s.file,
                path: &key,
                table: t,
            };
            let def = crate::stress::passage::DangVan::default();
            Some(crate::stress::passage::DangVan {
                alpha: d.non_negative("alpha", "dimensionless")?.unwrap_or(def.alpha),
                beta: d.positive("beta", "Pa")?.unwrap_or(def.beta),
            })
        }
    };
    Ok(Some(FatigueSpec {
        criterion,
        fatigue_limit,
        weibull_slope,
        stress_exponent,
        depth_exponent,
        dang_van,
    }))
}

/// `[thermal]` (optional, ehl only) with the bodies' thermal properties (`[body1]`, `[body2]`:
/// conductivity, heat_capacity, density; steel by default). Rheology parameters given at several
/// temperatures (`tables`) need it; with it, `lub.rheology` holds their values at the inlet
/// temperature (what the isothermal parts of a run use).
fn thermal(top: &Sec, lub: &mut Lubricant, tables: RheologyTables) -> R<Option<ThermalSpec>> {
    let Some(t) = sub(top, "thermal", "the temperature in the film and the bodies")? else {
        if !tables.is_empty() {
            let k = [
                (tables.shear_modulus.is_some(), "shear_modulus"),
                (tables.power_law_index.is_some(), "power_law_index"),
                (tables.eyring_stress.is_some(), "eyring_stress"),
                (
                    tables.limiting_shear_coefficient.is_some(),
                    "limiting_shear_coefficient",
                ),
            ]
            .into_iter()
            .find(|v| v.0)
            .map_or("", |v| v.1);
            return Err(case_err(
                top.file,
                &format!("lubricant.rheology.{k}"),
                "a parameter given at several temperatures needs a [thermal] table (an isothermal run has one temperature: give one number)",
            ));
        }
        return Ok(None);
    };
    let s = Sec {
        file: top.file,
        path: "thermal",
        table: t,
    };
    let t0 = s.positive("inlet_temperature", "K")?.unwrap_or(313.0);
    if t0 <= 138.0 + 1.0 {
        return Err(s.err(
            "inlet_temperature",
            format!("{} K is at or below Roelands' pole of 138 K; give the inlet temperature in K (e.g. 313.0 for 40 degC)", fmt_num(t0)),
        ));
    }
    let eta0 = lub.viscosity;
    let vt = match (
        s.non_negative("viscosity_temperature", "Roelands S0, dimensionless")?,
        s.non_negative("viscosity_beta", "1/K")?,
    ) {
        (Some(_), Some(_)) => {
            return Err(s.err(
                "viscosity_beta",
                "give the viscosity's temperature dependence once: viscosity_temperature (Roelands S0) or viscosity_beta (1/K), not both",
            ))
        }
        (Some(s0), None) => ViscosityTemperature::from_s0(s0, eta0, t0),
        (None, Some(b)) => ViscosityTemperature::from_beta(b, eta0, t0),
        // S0 = 1.1, a typical mineral oil (Roelands 1966; Habchi et al. 2008)
        (None, None) => ViscosityTemperature::from_s0(1.1, eta0, t0),
    };
    let thermal_expansion = s
        .non_negative("thermal_expansion", "1/K")?
        .unwrap_or(6.5e-4);
    if thermal_expansion * 500.0 >= 1.0 {
        return Err(s.err(
            "thermal_expansion",
            format!("{} 1/K would make the density vanish within 500 K of the inlet; oils expand by about 6.5e-4 1/K", fmt_num(thermal_expansion)),
        ));
    }
    let conductivity = s.positive("conductivity", "W/(m K)")?.unwrap_or(0.14);
    let conductivity_pressure = conductivity_pressure(&s)?;
    let heat_capacity = s.positive("heat_capacity", "J/(kg K)")?.unwrap_or(2000.0);
    let points = s
        .count(
            "points_across_film",
            "collocation points across the film",
            3,
        )?
        .unwrap_or(7);
    if points > 33 {
        return Err(s.err(
            "points_across_film",
            format!("{points} points across the film is more than 33; 5 to 9 carry the profile (see docs/thermal.md)"),
        ));
    }
    let body = |name: &str| -> R<BodyThermal> {
        let Some(bt) = top.get(name).and_then(|v| v.as_table()) else {
            return Ok(BodyThermal::steel());
        };
        let b = Sec {
            file: top.file,
            path: if name == "body1" { "body1" } else { "body2" },
            table: bt,
        };
        let steel = BodyThermal::steel();
        Ok(BodyThermal {
            conductivity: b
                .positive("conductivity", "W/(m K)")?
                .unwrap_or(steel.conductivity),
            heat_capacity: b
                .positive("heat_capacity", "J/(kg K)")?
                .unwrap_or(steel.heat_capacity),
            density: b.positive("density", "kg/m^3")?.unwrap_or(steel.density),
        })
    };
    let bodies = [body("body1")?, body("body2")?];
    let spec = ThermalLubricant {
        inlet_temperature: t0,
        viscosity_temperature: vt,
        thermal_expansion,
        conductivity,
        conductivity_pressure,
        heat_capacity,
        points_across_film: points,
        rheology: tables,
    };
    lub.rheology = spec.rheology.at(&lub.rheology, t0);
    let defaults = crate::ehl::thermal::ThermalParams::default();
    let tolerance_k = s
        .positive("tolerance", "K")?
        .unwrap_or(defaults.tolerance_k);
    let film_tolerance = s
        .positive("film_tolerance", "relative")?
        .unwrap_or(defaults.film_tolerance);
    if film_tolerance >= 0.1 {
        return Err(s.err(
            "film_tolerance",
            format!(
                "a film tolerance relative to the thinnest film must be below 0.1 (e.g. 1e-4), found {}",
                fmt_num(film_tolerance)
            ),
        ));
    }
    let max_iterations = s
        .count("max_iterations", "outer iterations", 1)?
        .unwrap_or(defaults.max_outer);
    let side_flow = s.boolean("side_flow")?.unwrap_or(true);
    let coupled_newton = s.boolean("coupled_newton")?.unwrap_or(true);
    Ok(Some(ThermalSpec {
        lubricant: spec,
        bodies,
        tolerance_k,
        film_tolerance,
        max_iterations,
        side_flow,
        coupled_newton,
    }))
}

/// Validates the whole tree (unknown keys already rejected) into a [`Case`].
pub(crate) fn resolve(root: &Table, file: &str) -> R<Case> {
    let top = Sec {
        file,
        path: "",
        table: root,
    };
    let title = top.string("title", "free text")?.unwrap_or("").to_string();
    let kind = match top.choice("kind", &["dry", "ehl"])? {
        Some("dry") => Kind::Dry,
        Some(_) => Kind::Ehl,
        None => {
            return Err(top.missing(
                "kind",
                "kind = \"dry\" (contact without lubricant) or kind = \"ehl\" (lubricated)",
            ))
        }
    };
    let body1 = body(&top, "body1")?;
    let body2 = body(&top, "body2")?;
    let c = contact(&top, &body1, &body2)?;
    let e_red = units::reduced_modulus(
        body1.youngs_modulus,
        body1.poisson_ratio,
        body2.youngs_modulus,
        body2.poisson_ratio,
    );
    let r = units::reduced_radius(body1.radius, body2.radius);
    let alignment = alignment(&top, matches!(c, Contact::Point { .. }))?;
    let (load, b, ky) = load(&top, c, r, e_red)?;
    skew_keeps_a_line(&top, c, &body1, &body2, &alignment, b)?;

    let (motion, lubricant) = if kind == Kind::Ehl {
        for (k, what) in [
            ("motion", "a [motion] table for kind = \"ehl\" (entrainment_speed in m/s, slide_to_roll)"),
            ("lubricant", "a [lubricant] table for kind = \"ehl\" (viscosity, pressure_viscosity_coefficient, density)"),
        ] {
            if !top.has(k) {
                return Err(top.missing(k, what));
            }
        }
        let (lub, tables) = lubricant(&top, e_red)?;
        let m = motion(&top, e_red, r, lub.viscosity)?;
        (Some(m), Some((lub, tables)))
    } else {
        // [motion] is ignored for a dry contact, but a travel asks for a transient run that a
        // dry contact does not have: refused rather than silently solved at one position
        let travel_given = top
            .get("motion")
            .and_then(|v| v.as_table())
            .is_some_and(|t| t.contains_key("travel"));
        if travel_given {
            return Err(case_err(
                file,
                "motion.travel",
                "a transient run is for kind = \"ehl\" (a lubricated contact); a dry contact has no time and is solved at one position: to move a feature through it, vary the feature's position, e.g. ehl sweep CASE.toml --vary features[0].x=-1e-3:1e-3:21",
            ));
        }
        (None, None)
    };
    let travel = motion.as_ref().and_then(|m| m.travel);
    let (lubricant, thermal) = match lubricant {
        Some((mut lub, tables)) => {
            let th = thermal(&top, &mut lub, tables)?;
            (Some(lub), th)
        }
        None => {
            if top.has("thermal") {
                return Err(case_err(
                    file,
                    "thermal",
                    "[thermal] is for kind = \"ehl\": a dry contact has no film to heat (the flash temperature of dry sliding is not modelled)",
                ));
            }
            (None, None)
        }
    };

    let grid = grid(&top, kind, c, b, ky)?;
    let solver = solver(&top, kind)?;
    let infinite = matches!(c, Contact::Line { len, .. } if len.is_infinite());
    if let (Some(m), Some(_), true) = (&motion, &thermal, infinite) {
        // an infinite line contact's bodies conduct in 2D, where a line source standing still
        // on a half-plane heats it without end (the temperature grows as log t); the solver
        // would stop at the body's temperature, the error naming no key
        for body in [1, 2] {
            let (u, formula) = body_speed(m, body);
            if u == 0.0 {
                return Err(case_err(
                    file,
                    "motion.slide_to_roll",
                    format!(
                        "a thermal infinite line contact needs both surfaces moving, but body {body} stands still ({formula} = 0): the heat of a line source at rest on a half-plane has no steady temperature (it grows as log t). Use |slide_to_roll| < 2, or finite rollers (a finite length), whose bodies conduct in 3D"
                    ),
                ));
            }
        }
    }
    let features = features(&top, &grid, b, r, infinite, travel.is_some())?;
    let mut span = None;
    if let Some(m) = &motion {
        match travel {
            // a steady run is exact only for features on a body that stands still
            None => {
                for (i, f) in features.iter().enumerate() {
                    let (u, formula) = body_speed(m, f.body);
                    if u != 0.0 {
                        return Err(case_err(
                            file,
                            &format!("features[{i}].body"),
                            format!(
                                "a feature on a moving surface (body {} moves at {formula} = {} m/s) makes the film transient: add motion.travel = {{ from = -1e-3, to = 1e-3, steps = 200 }} (the path of features[0]'s centre, m) or {{ duration = 2e-4, steps = 200 }} (s) for a transient run; a steady run with features is exact only when their body stands still: slide_to_roll = 2 stops body 2, -2 stops body 1",
                                f.body,
                                fmt_num(u)
                            ),
                        ));
                    }
                }
            }
            Some(t) => span = check_travel(file, m, t, &features)?,
        }
    }
    let output = output(&top, span)?;
    let stress = stress(&top, kind, b, travel.is_some())?;
    let fatigue = fatigue(&top, stress.is_some(), travel.is_some())?;
    let case = Case {
        title,
        kind,
        body1,
        body2,
        alignment,
        load,
        motion,
        lubricant,
        grid,
        solver,
        features,
        output,
        stress,
        fatigue,
        thermal,
    };
    let (limit, source) = crate::run::memory_limit();
    crate::run::check_memory(&case, limit, &source).map_err(|(k, m)| case_err(file, &k, m))?;
    Ok(case)
}
