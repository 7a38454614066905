//! Synthetic solutions with Hertz-like fields, for testing and demonstrating the writers without
//! a solver: a dry ball on a flat, a dry finite roller with end peaks, a dry infinite line
//! contact and a lubricated ball with a horseshoe film. Only the look of the fields matters
//! here (they are not solutions of the contact problem, except the Hertz pressures and the
//! point-contact deflection, which are Johnson's 1985 closed forms, eq. 3.39-3.42 and 4.22-4.24).
//! `EHL_OUTPUT_DEMO_DIR=/some/dir cargo test -p ehl --test output_pictures` keeps the
//! pictures of all of them in that folder.

use crate::case::*;
use crate::grid::Grid;
use crate::solution::{Fields, Solution, Summary};
use crate::units;
use std::f64::consts::PI;

fn steel(shape: Shape, radius: f64, length: f64) -> Body {
    Body {
        shape,
        radius,
        radius_y: if shape == Shape::Ball {
            radius
        } else {
            f64::INFINITY
        },
        length,
        youngs_modulus: 210e9,
        poisson_ratio: 0.3,
        profile: Profile::Straight,
        axial_offset: 0.0,
    }
}

fn flat() -> Body {
    steel(Shape::Flat, f64::INFINITY, f64::INFINITY)
}

fn base_case(title: &str, body1: Body, force: f64, per_length: f64, grid: GridSpec) -> Case {
    Case {
        title: title.into(),
        kind: Kind::Dry,
        body1,
        body2: flat(),
        alignment: Alignment::default(),
        load: Load {
            force,
            force_per_length: per_length,
        },
        motion: None,
        lubricant: None,
        grid,
        solver: SolverSpec {
            tolerance: 1e-8,
            max_iterations: 200,
            mirror_levels: 0,
            free_end_correction: false,
            wedge_upwind_order: 2,
        },
        features: Vec::new(),
        output: Default::default(),
        stress: None,
        fatigue: None,
        thermal: None,
    }
}

fn summary_from(grid: &Grid, fields: &Fields, ph: f64, b: f64) -> Summary {
    let p = &fields.pressure;
    let (k, pm) =
        p.iter().enumerate().fold(
            (0, f64::NEG_INFINITY),
            |a, (k, &v)| if v > a.1 { (k, v) } else { a },
        );
    let (i, j) = (k % grid.nx, k / grid.nx);
    Summary {
        converged: true,
        termination: "synthetic fields".into(),
        iterations: 42,
        residual: Some(1e-9),
        wall_time_s: 0.01,
        load_n: p.iter().sum::<f64>() * grid.cell_area(),
        load_error: 1e-9,
        max_pressure_pa: pm,
        max_pressure_at_m: [grid.x(i), grid.y(j)],
        hertz_pressure_pa: ph,
        hertz_half_width_m: b,
        contact_area_m2: Some(p.iter().filter(|&&v| v > 0.0).count() as f64 * grid.cell_area()),
        ..Summary::default()
    }
}

/// Hertz deflection of a circular contact (both bodies, m): a^2/R - r^2/(2R) inside, Johnson
/// (1985) eq. 3.42 outside, written with E' (thesis convention).
fn point_deflection(r: f64, a: f64, rr: f64) -> f64 {
    if r <= a {
        a * a / rr - r * r / (2.0 * rr)
    } else {
        let s = r / a;
        a * a / (PI * rr) * ((2.0 - s * s) * (1.0 / s).asin() + (s * s - 1.0).sqrt())
    }
}

/// Gap outside a Hertz line contact (m): (b^2/2R)[s sqrt(s^2-1) - ln(s + sqrt(s^2-1))], s = |x|/b.
fn line_gap(x: f64, b: f64, rr: f64) -> f64 {
    let s = x.abs() / b;
    if s <= 1.0 {
        0.0
    } else {
        let q = (s * s - 1.0).sqrt();
        b * b / (2.0 * rr) * (s * q - (s + q).ln())
    }
}

/// Dry ball (R = 10 mm) on a flat, 500 N, steel: Hertz pressure, deflection and gap on 96^2 cells
/// over [-3a, 3a]^2.
pub fn dry_ball() -> (Case, Solution) {
    let (radius, force) = (10e-3, 500.0);
    let case = base_case(
        "Steel ball R = 10 mm on a flat, 500 N (synthetic Hertz fields)",
        steel(Shape::Ball, radius, f64::INFINITY),
        force,
        force,
        GridSpec {
            nx: 96,
            ny: 96,
            x_min: -3.0,
            x_max: 3.0,
            y_min: -3.0,
            y_max: 3.0,
        },
    );
    let e = case.reduced_modulus();
    let rr = case.reduced_radius();
    let h = units::hertz_point(force, rr, e);
    let a = h.a;
    let grid = Grid::new(96, 96, -3.0 * a, 3.0 * a, -3.0 * a, 3.0 * a);
    let n = grid.len();
    let (mut p, mut w, mut gap) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    for j in 0..grid.ny {
        for i in 0..grid.nx {
            let (x, y) = (grid.x(i), grid.y(j));
            let r = x.hypot(y);
            let k = grid.idx(i, j);
            p[k] = h.p0 * (1.0 - (r / a).powi(2)).max(0.0).sqrt();
            w[k] = point_deflection(r, a, rr);
            gap[k] = (r * r / (2.0 * rr) + w[k] - h.approach).max(0.0);
        }
    }
    let fields = Fields {
        pressure: p,
        deformation: w,
        film: Some(gap),
        viscosity: None,
        density: None,
    };
    let mut summary = summary_from(&grid, &fields, h.p0, a);
    summary.approach_m = Some(h.approach);
    (
        case,
        Solution {
            stress: None,
            temperature: None,
            grid,
            fields,
            summary,
            transient: None,
        },
    )
}

/// Line-contact pressure with end peaks: Hertz across x, times an axial factor that rises near
/// the roller ends (|y| -> L/2), the look of an unmodified straight roller.
fn end_peak_factor(y: f64, half_length: f64) -> f64 {
    let d = half_length - y.abs();
    if d < 0.0 {
        0.0
    } else {
        1.0 + 0.9 * (-d / (0.025 * 2.0 * half_length)).exp()
    }
}

/// Dry straight roller R = 5 mm, L = 10 mm on a flat, 5 kN: Hertz across x with end peaks, on
/// 64 x 160 cells over x in [-3b, 2b] and y over the length.
pub fn dry_roller() -> (Case, Solution) {
    let (radius, length, force) = (5e-3, 10e-3, 5000.0);
    let case = base_case(
        "Straight roller R = 5 mm, L = 10 mm on a flat, 5 kN, no crowning, no mirror images: synthetic fields with end peaks for testing the writers",
        steel(Shape::Roller, radius, length),
        force,
        force / length,
        GridSpec {
            nx: 64,
            ny: 160,
            x_min: -3.0,
            x_max: 2.0,
            y_min: -1.0,
            y_max: 1.0,
        },
    );
    let e = case.reduced_modulus();
    let rr = case.reduced_radius();
    let w1 = force / length;
    let (b, ph) = (
        units::hertz_line_half_width(w1, rr, e),
        units::hertz_line_pressure(w1, rr, e),
    );
    let grid = Grid::new(64, 160, -3.0 * b, 2.0 * b, -0.5 * length, 0.5 * length);
    let approach = 2e-6;
    let n = grid.len();
    let (mut p, mut w, mut gap) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    for j in 0..grid.ny {
        for i in 0..grid.nx {
            let (x, y) = (grid.x(i), grid.y(j));
            let k = grid.idx(i, j);
            p[k] = ph * (1.0 - (x / b).powi(2)).max(0.0).sqrt() * end_peak_factor(y, 0.5 * length);
            gap[k] = line_gap(x, b, rr);
            w[k] = gap[k] - x * x / (2.0 * rr) + approach;
        }
    }
    let fields = Fields {
        pressure: p,
        deformation: w,
        film: Some(gap),
        viscosity: None,
        density: None,
    };
    let mut summary = summary_from(&grid, &fields, ph, b);
    summary.approach_m = Some(approach);
    (
        case,
        Solution {
            stress: None,
            temperature: None,
            grid,
            fields,
            summary,
            transient: None,
        },
    )
}

/// Dry infinite line contact, R = 10 mm on a flat, 1e6 N/m: the Hertz profile on 200 cells over
/// [-3b, 2b] (`ny == 1`, the 1 m reference length).
pub fn dry_infinite_line() -> (Case, Solution) {
    let (radius, w1) = (10e-3, 1e6);
    let case = base_case(
        "Infinite line contact R = 10 mm, 1000 N/mm (synthetic Hertz)",
        steel(Shape::Roller, radius, f64::INFINITY),
        w1,
        w1,
        GridSpec {
            nx: 200,
            ny: 1,
            x_min: -3.0,
            x_max: 2.0,
            y_min: -0.5,
            y_max: 0.5,
        },
    );
    let e = case.reduced_modulus();
    let rr = case.reduced_radius();
    let (b, ph) = (
        units::hertz_line_half_width(w1, rr, e),
        units::hertz_line_pressure(w1, rr, e),
    );
    let grid = Grid::new(200, 1, -3.0 * b, 2.0 * b, -0.5, 0.5);
    let approach = 5e-6;
    let xs = grid.xs();
    let p = xs
        .iter()
        .map(|x| ph * (1.0 - (x / b).powi(2)).max(0.0).sqrt())
        .collect();
    let gap: Vec<f64> = xs.iter().map(|x| line_gap(*x, b, rr)).collect();
    let w = xs
        .iter()
        .zip(&gap)
        .map(|(x, g)| g - x * x / (2.0 * rr) + approach)
        .collect();
    let fields = Fields {
        pressure: p,
        deformation: w,
        film: Some(gap),
        viscosity: None,
        density: None,
    };
    let mut summary = summary_from(&grid, &fields, ph, b);
    summary.approach_m = Some(approach);
    (
        case,
        Solution {
            stress: None,
            temperature: None,
            grid,
            fields,
            summary,
            transient: None,
        },
    )
}

/// Lubricated ball R = 12.5 mm on a flat, 15 N: Hertz-like pressure with an outlet spike, a
/// horseshoe film (central ~ 0.22 µm, minimum ~ 0.13 µm at the sides), Roelands-like viscosity
/// and Dowson-Higginson density, on 96^2 cells over [-3a, 3a]^2. `ny1` gives the same case as an
/// infinite line contact profile (1D) instead.
pub fn ehl_ball(ny1: bool) -> (Case, Solution) {
    let (radius, force) = (12.5e-3, 15.0);
    let mut case = base_case(
        "Ball R = 12.5 mm on glass, 15 N, 0.09 m/s (synthetic EHL fields)",
        steel(Shape::Ball, radius, f64::INFINITY),
        force,
        force,
        GridSpec {
            nx: 96,
            ny: 96,
            x_min: -3.0,
            x_max: 3.0,
            y_min: -3.0,
            y_max: 3.0,
        },
    );
    case.kind = Kind::Ehl;
    case.motion = Some(Motion {
        entrainment_speed: 0.09,
        slide_to_roll: 0.0,
        travel: None,
    });
    case.lubricant = Some(Lubricant {
        viscosity: 0.25,
        pressure_viscosity_coefficient: 22e-9,
        density: 870.0,
        viscosity_model: ViscosityModel::Roelands,
        density_model: DensityModel::DowsonHigginson,
        rheology: Rheology::Newtonian,
    });
    let e = case.reduced_modulus();
    let rr = case.reduced_radius();
    let h = units::hertz_point(force, rr, e);
    let a = h.a;
    let grid = if ny1 {
        case.title = "Line contact (synthetic EHL fields)".into();
        case.body1 = steel(Shape::Roller, radius, f64::INFINITY);
        case.grid.ny = 1;
        Grid::new(192, 1, -3.0 * a, 3.0 * a, -0.5, 0.5)
    } else {
        Grid::new(96, 96, -3.0 * a, 3.0 * a, -3.0 * a, 3.0 * a)
    };
    let (hc, n) = (225e-9, grid.len());
    let mut f = Fields {
        pressure: vec![0.0; n],
        deformation: vec![0.0; n],
        film: Some(vec![0.0; n]),
        viscosity: Some(vec![0.0; n]),
        density: Some(vec![0.0; n]),
    };
    for j in 0..grid.ny {
        for i in 0..grid.nx {
            let (x, y) = (grid.x(i), if ny1 { 0.0 } else { grid.y(j) });
            let r = x.hypot(y);
            let k = grid.idx(i, j);
            // inlet build-up and outlet spike on a Hertz dome
            let dome = (1.0 - (r / a).powi(2)).max(0.0).sqrt();
            let inlet = 0.08 * (-((r - a) / (0.3 * a)).powi(2)).exp() * (x < 0.0) as u8 as f64;
            let spike = 0.35 * (-((x - 0.85 * a) / (0.05 * a)).powi(2)).exp() * dome.sqrt();
            let p = h.p0 * (dome + inlet + spike);
            // horseshoe: thinner towards the outlet and the sides, rising outside as the dry gap
            let rim =
                (-((r - 0.9 * a) / (0.12 * a)).powi(2)).exp() * (0.5 + 0.5 * x / r.max(1e-12));
            let film = hc * (1.0 - 0.45 * rim)
                + (r * r / (2.0 * rr) + point_deflection(r, a, rr) - h.approach).max(0.0);
            f.pressure[k] = p;
            f.deformation[k] = point_deflection(r, a, rr);
            f.film.as_mut().unwrap()[k] = film;
            f.viscosity.as_mut().unwrap()[k] = 0.25 * (22e-9 * p).exp();
            f.density.as_mut().unwrap()[k] = 870.0 * (1.0 + 0.6e-9 * p / (1.0 + 1.7e-9 * p));
        }
    }
    let mut summary = summary_from(&grid, &f, h.p0, a);
    summary.contact_area_m2 = None;
    let film = f.film.as_ref().unwrap();
    let (kmin, hmin) =
        film.iter().enumerate().fold(
            (0, f64::INFINITY),
            |acc, (k, &v)| if v < acc.1 { (k, v) } else { acc },
        );
    let kc = grid.idx(grid.nx / 2, grid.ny / 2);
    summary.central_film_m = Some(film[kc]);
    summary.min_film_m = Some(hmin);
    summary.min_film_at_m = Some([grid.x(kmin % grid.nx), grid.y(kmin / grid.nx)]);
    summary.friction_coefficient = Some(0.004);
    summary.friction_force_n = Some(0.06);
    (
        case,
        Solution {
            stress: None,
            temperature: None,
            grid,
            fields: f,
            summary,
            transient: None,
        },
    )
}
