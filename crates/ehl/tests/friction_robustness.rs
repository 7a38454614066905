//! Rheology laws and the friction integral over random and degenerate inputs: the limiting shear
//! stress is never exceeded, the laws are odd and monotone, and no input gives NaN (either a
//! finite figure or a typed error).

use ehl::case::Rheology;
use ehl::friction::{friction, surface_shear_stress, FrictionInput};
use ehl::grid::Grid;
use ehl::lubricant::rheology::{effective_viscosity, limiting_shear_stress, shear_stress};

/// A small deterministic generator (64-bit LCG, Knuth's constants; top 53 bits) so the test is
/// reproducible without a dependency.
struct Lcg(u64);
impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    /// log-uniform in [lo, hi]
    fn log(&mut self, lo: f64, hi: f64) -> f64 {
        (lo.ln() + self.next() * (hi.ln() - lo.ln())).exp()
    }
    fn sign(&mut self) -> f64 {
        if self.next() < 0.5 {
            -1.0
        } else {
            1.0
        }
    }
}

fn random_model(rng: &mut Lcg, limit: bool) -> Rheology {
    let lambda = if limit {
        Some(rng.log(0.01, 0.1))
    } else {
        None
    };
    match (rng.next() * 3.0) as usize {
        0 if !limit => Rheology::Newtonian,
        0 | 1 => Rheology::Carreau {
            shear_modulus: rng.log(1e5, 1e8),
            power_law_index: 0.2 + 0.8 * rng.next(),
            limiting_shear_coefficient: lambda,
        },
        _ => Rheology::Eyring {
            eyring_stress: rng.log(1e5, 1e8),
            limiting_shear_coefficient: lambda,
        },
    }
}

#[test]
fn random_inputs_respect_the_limit_and_are_odd_and_monotone() {
    // |tau| <= Lambda max(p, 0) exactly (the cap returns tau_L itself), tau odd in gamma_dot,
    // non-decreasing in |gamma_dot|, finite, and eta_eff = tau / gamma_dot <= eta (all three
    // laws thin or stay Newtonian for n <= 1). 20000 random draws over eta 1e-3..1e8 Pa s,
    // |gamma_dot| 1e-3..1e12 1/s, p -1e8..3e9 Pa.
    let mut rng = Lcg(0x5eed);
    for _ in 0..20_000 {
        let limit = rng.next() < 0.7;
        let model = random_model(&mut rng, limit);
        let eta = rng.log(1e-3, 1e8);
        let gd = rng.sign() * rng.log(1e-3, 1e12);
        let p = -1e8 + rng.next() * 3.1e9;
        let tau = shear_stress(&model, eta, gd, p);
        assert!(tau.is_finite(), "{model:?} eta {eta} gd {gd} p {p}");
        assert!(tau == 0.0 || tau.signum() == gd.signum());
        assert_eq!(shear_stress(&model, eta, -gd, p), -tau, "odd");
        if let Some(tau_l) = limiting_shear_stress(&model, p) {
            assert!(tau.abs() <= tau_l, "{model:?}: |tau| {tau} > tau_L {tau_l}");
        }
        let more = shear_stress(&model, eta, 1.5 * gd, p);
        assert!(more.abs() >= tau.abs(), "monotone: {model:?} {tau} {more}");
        let eff = effective_viscosity(&model, eta, gd, p);
        assert!(eff.is_finite() && eff >= 0.0 && eff <= eta * (1.0 + 1e-12));
    }
}

fn grid_fields(rng: &mut Lcg, grid: &Grid) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let n = grid.len();
    let mut p = vec![0.0; n];
    let mut h = vec![0.0; n];
    let mut eta = vec![0.0; n];
    for k in 0..n {
        let u = rng.next();
        // a mix of pressurised, cavitated, negative-pressure, zero-film and no-material cells
        p[k] = if u < 0.2 {
            0.0
        } else if u < 0.25 {
            -1e6
        } else {
            rng.next() * 2e9
        };
        let v = rng.next();
        h[k] = if v < 0.05 {
            0.0
        } else if v < 0.08 {
            f64::INFINITY
        } else {
            rng.log(1e-9, 1e-5)
        };
        eta[k] = rng.log(1e-3, 1e6);
    }
    (p, h, eta)
}

#[test]
fn random_fields_with_a_limit_give_finite_friction_below_lambda() {
    // With a limiting shear stress every Couette cell stress is at most Lambda p, so
    // |couette_force| <= Lambda sum max(p, 0) dA; zero-film and infinite-film cells must not
    // produce NaN. 200 random 2D fields.
    let mut rng = Lcg(42);
    for _ in 0..200 {
        let grid = Grid::new(
            1 + (rng.next() * 20.0) as usize,
            1 + (rng.next() * 5.0) as usize,
            -1e-4,
            1e-4,
            -1e-4,
            1e-4,
        );
        let (p, h, eta) = grid_fields(&mut rng, &grid);
        let model = random_model(&mut rng, true);
        let lambda = limiting_shear_stress(&model, 1.0).unwrap();
        let input = FrictionInput {
            grid: &grid,
            pressure: &p,
            film: &h,
            viscosity: &eta,
            u1: rng.sign() * rng.log(1e-3, 30.0),
            u2: rng.log(1e-3, 30.0),
            rheology: &model,
            load: 1e3,
        };
        let fr = friction(&input).expect("finite with a limit");
        assert!(fr.force.is_finite() && fr.coefficient.is_finite());
        let cap = lambda * p.iter().map(|&p| p.max(0.0)).sum::<f64>() * grid.cell_area();
        assert!(
            fr.couette_force.abs() <= cap * (1.0 + 1e-12),
            "{} > {cap}",
            fr.couette_force
        );
        let tau = surface_shear_stress(&input).unwrap();
        assert!(tau.iter().all(|t| t.is_finite()));
    }
}

fn one_cell_input<'a>(
    grid: &'a Grid,
    p: &'a [f64],
    h: &'a [f64],
    eta: &'a [f64],
    model: &'a Rheology,
) -> FrictionInput<'a> {
    FrictionInput {
        grid,
        pressure: p,
        film: h,
        viscosity: eta,
        u1: 2.0,
        u2: 1.0,
        rheology: model,
        load: 1.0,
    }
}

#[test]
fn degenerate_films_follow_the_documented_rules() {
    let grid = Grid::new(3, 1, -1.5e-4, 1.5e-4, -0.5, 0.5);
    let eta = [1.0; 3];
    let newton = Rheology::Newtonian;
    let limited = Rheology::Eyring {
        eyring_stress: 5e6,
        limiting_shear_coefficient: Some(0.05),
    };

    // zero pressure everywhere (cavitated or unloaded) with zero film: no stress, no NaN
    let p0 = [0.0; 3];
    let h0 = [0.0; 3];
    let fr = friction(&one_cell_input(&grid, &p0, &h0, &eta, &newton)).unwrap();
    assert_eq!(
        (fr.force, fr.couette_force, fr.poiseuille_force),
        (0.0, 0.0, 0.0)
    );

    // a pressurised cell with h = 0 under sliding: unbounded for Newtonian -> typed error
    let p = [0.0, 1e9, 0.0];
    let h = [1e-7, 0.0, 1e-7];
    let err = friction(&one_cell_input(&grid, &p, &h, &eta, &newton)).unwrap_err();
    assert!(err.to_string().contains("h = 0e0 m <= 0"), "{err}");
    // ... but with a limit the h -> 0+ limit is tau_L = Lambda p on that cell (its pressure-flow
    // stress is zero because h = 0; the neighbours carry -(h/2) dp/dx = -(1e-7/2)(+-1e9/(2 dx)),
    // which cancel)
    let fr = friction(&one_cell_input(&grid, &p, &h, &eta, &limited)).unwrap();
    assert_eq!(fr.couette_force, 0.05 * 1e9 * grid.cell_area());
    assert!(fr.poiseuille_force.abs() < 1e-12 * 1e-7 * 1e9);
    // ... and without sliding there is no Couette stress at all
    let mut input = one_cell_input(&grid, &p, &h, &eta, &newton);
    input.u2 = input.u1;
    assert_eq!(friction(&input).unwrap().couette_force, 0.0);

    // h = +inf (no opposing surface): no stress at all in that cell
    let h = [f64::INFINITY, 1e-7, f64::INFINITY];
    let tau = surface_shear_stress(&one_cell_input(&grid, &[1e9; 3], &h, &eta, &newton)).unwrap();
    assert_eq!(tau[0], 0.0);
    assert_eq!(tau[2], 0.0);
    assert_eq!(tau[1], 1.0 * 1.0 / 1e-7); // eta du / h, dp/dx = 0

    // negative pressure is ambient: no Couette stress, gradient taken on max(p, 0)
    let p = [-1e6, -1e6, -1e6];
    let fr = friction(&one_cell_input(&grid, &p, &[1e-7; 3], &eta, &newton)).unwrap();
    assert_eq!(fr.force, 0.0);
}

#[test]
fn invalid_inputs_are_typed_errors() {
    let grid = Grid::new(3, 1, -1.5e-4, 1.5e-4, -0.5, 0.5);
    let (p, h, eta) = ([1e8; 3], [1e-7; 3], [1.0; 3]);
    let m = Rheology::Newtonian;
    let ok = one_cell_input(&grid, &p, &h, &eta, &m);
    assert!(friction(&ok).is_ok());

    let mut bad = ok;
    bad.load = 0.0;
    assert!(friction(&bad).unwrap_err().to_string().contains("load"));
    bad = ok;
    bad.load = f64::NAN;
    assert!(friction(&bad).is_err());
    bad = ok;
    bad.u1 = f64::INFINITY;
    assert!(friction(&bad).unwrap_err().to_string().contains("speeds"));

    let short = [1e8; 2];
    bad = ok;
    bad.pressure = &short;
    assert!(friction(&bad)
        .unwrap_err()
        .to_string()
        .contains("pressure has 2 values"));

    let nan_p = [1e8, f64::NAN, 1e8];
    bad = ok;
    bad.pressure = &nan_p;
    assert!(friction(&bad)
        .unwrap_err()
        .to_string()
        .contains("cell (1, 0)"));
    let nan_h = [1e-7, f64::NAN, 1e-7];
    bad = ok;
    bad.film = &nan_h;
    assert!(friction(&bad).is_err());
    let inf_eta = [1.0, f64::INFINITY, 1.0];
    bad = ok;
    bad.viscosity = &inf_eta;
    assert!(friction(&bad).is_err());

    // a film so thin that the Newtonian stress overflows: an error, not inf
    let thin = [1e-7, 1e-310, 1e-7];
    bad = ok;
    bad.film = &thin;
    let big_eta = [1.0, 1e300, 1.0];
    bad.viscosity = &big_eta;
    assert!(friction(&bad).is_err());
}

/// The summary of the thesis Table 3.7 line (`examples/ehl_friction_line.toml`) with `sets`.
fn solve_table_3_7_line(sets: &[&str]) -> ehl::solution::Summary {
    let path = format!(
        "{}/../../examples/ehl_friction_line.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    let case = ehl::case::load_file(std::path::Path::new(&path), &sets).unwrap();
    ehl::run::solve(&case, &ehl::run::Silent).unwrap().summary
}

/// A friction coefficient no lubricated contact shows is said in the summary: the thesis Table
/// 3.7 line made Newtonian at SRR 0.5 and G = 5000 gives f ~ 356 and a warning naming the
/// rheology; the example's Carreau oil with its limiting shear stress gives 0.011 and none.
#[test]
fn an_unphysical_friction_coefficient_is_warned() {
    let solve = solve_table_3_7_line;
    let s = solve(&[
        "grid.nx=128",
        "lubricant.rheology={model=\"newtonian\"}",
        "motion.slide_to_roll=0.5",
        "lubricant.dimensionless_material=5000",
    ]);
    let f = s.friction_coefficient.unwrap();
    assert!(f > ehl::run::FRICTION_WARNING, "{f}");
    assert!(
        s.warnings
            .iter()
            .any(|w| w.contains("friction coefficient") && w.contains("Newtonian")),
        "{:?}",
        s.warnings
    );
    let s = solve(&["grid.nx=128"]);
    assert!(s.friction_coefficient.unwrap() < 0.05);
    assert!(
        !s.warnings
            .iter()
            .any(|w| w.contains("friction coefficient")),
        "{:?}",
        s.warnings
    );
}

/// A light line contact (M = 0.96) on the default inlet of 4 b: its film is starved and the
/// summary says so, naming grid.x_min; with the inlet at -20 b the film is 29 % thicker and the
/// warning goes. The thesis Table 3.7 line (M = 10.8) on the default inlet is not warned.
#[test]
fn a_starved_light_contact_is_warned() {
    let solve = solve_table_3_7_line;
    let light = [
        "lubricant.viscosity=1.0",
        "motion={entrainment_speed=40, slide_to_roll=0.02}",
    ];
    let inlet = |w: &[String]| w.iter().any(|w| w.contains("grid.x_min"));
    let short = solve(&[&light[..], &["grid.nx=256"]].concat());
    assert!(inlet(&short.warnings), "{:?}", short.warnings);
    let long = solve(&[&light[..], &["grid.nx=512", "grid.x_min=-20"]].concat());
    assert!(!inlet(&long.warnings), "{:?}", long.warnings);
    assert!(long.central_film_m.unwrap() > 1.2 * short.central_film_m.unwrap());
    let table_3_7 = solve(&["grid.nx=256"]);
    assert!(!inlet(&table_3_7.warnings), "{:?}", table_3_7.warnings);
}

/// The same check at a heavier load (M above `LONG_INLET_M`), where the inlet is short but can
/// still be cut: the EHL-FBNS ball (M = 64) with its inlet at -1 a on 32^2 cells gave 53 nm
/// against the 207 nm of its own default grid, without a word (a scan). It is now warned,
/// naming grid.x_min and grid.nx; the example's own inlet (at -3 a), run here on 64^2 cells,
/// is not.
#[test]
fn a_cut_inlet_at_high_load_is_warned() {
    let path = format!(
        "{}/../../examples/ehl_ball_on_glass.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let solve = |sets: &[&str]| {
        let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
        let case = ehl::case::load_file(std::path::Path::new(&path), &sets).unwrap();
        ehl::run::solve(&case, &ehl::run::Silent).unwrap().summary
    };
    let warned = |s: &ehl::solution::Summary| {
        s.warnings
            .iter()
            .any(|w| w.contains("grid.x_min") && w.contains("grid.nx"))
    };
    let cut = solve(&[
        "grid.x_min=-1.0",
        "grid.x_max=1.0",
        "grid.nx=32",
        "grid.ny=32",
    ]);
    assert!(warned(&cut), "{:?}", cut.warnings);
    let whole = solve(&["grid.nx=64", "grid.ny=64"]);
    assert!(!warned(&whole), "{:?}", whole.warnings);
    assert!(whole.central_film_m.unwrap() > 2.0 * cut.central_film_m.unwrap());
}
