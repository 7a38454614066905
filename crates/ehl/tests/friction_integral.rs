//! The friction integral (thesis eq. 3.5, 3.8-3.10) against independent quadratures of analytic
//! fields: a Hertzian pressure, a parabolic film and Barus viscosity.

use ehl::case::Rheology;
use ehl::friction::{
    friction, slide_to_roll, surface_shear_stress, surface_speeds, Friction, FrictionInput,
};
use ehl::grid::Grid;
use std::f64::consts::PI;

// Synthetic line contact (SI): Hertzian pressure p0 sqrt(1 - x^2/b^2) on |x| < b, film
// h0 + x^2/(2R) + c x, Barus viscosity eta0 exp(alpha p). alpha p0 = 7.95, as in the thesis'
// lubricant (Table 3.7) at 0.5 GPa.
const ETA0: f64 = 0.04;
const ALPHA: f64 = 15.9e-9;
const P0: f64 = 0.5e9;
const B: f64 = 1e-4;
const R: f64 = 0.02;
const H0: f64 = 1e-7;
const UE: f64 = 8.0;

fn hertz_line(x: f64) -> f64 {
    let s = 1.0 - (x / B).powi(2);
    if s > 0.0 {
        P0 * s.sqrt()
    } else {
        0.0
    }
}

fn film(x: f64, slope: f64) -> f64 {
    H0 + x * x / (2.0 * R) + slope * x
}

struct Fields {
    grid: Grid,
    p: Vec<f64>,
    h: Vec<f64>,
    eta: Vec<f64>,
}

/// Line contact on [-2b, 2b] with nx cells (nx divisible by 4 puts x = +-b on cell edges).
fn line_fields(nx: usize, slope: f64) -> Fields {
    let grid = Grid::new(nx, 1, -2.0 * B, 2.0 * B, -0.5, 0.5);
    let xs = grid.xs();
    let p: Vec<f64> = xs.iter().map(|&x| hertz_line(x)).collect();
    let h = xs.iter().map(|&x| film(x, slope)).collect();
    let eta = p.iter().map(|&p| ETA0 * (ALPHA * p).exp()).collect();
    Fields { grid, p, h, eta }
}

fn run(f: &Fields, srr: f64, rheology: &Rheology) -> Friction {
    let (u1, u2) = surface_speeds(UE, srr);
    let load = f.p.iter().sum::<f64>() * f.grid.cell_area();
    friction(&FrictionInput {
        grid: &f.grid,
        pressure: &f.p,
        film: &f.h,
        viscosity: &f.eta,
        u1,
        u2,
        rheology,
        load,
    })
    .expect("valid fields")
}

/// Composite Simpson rule with n (even) panels.
fn simpson(f: impl Fn(f64) -> f64, a: f64, b: f64, n: usize) -> f64 {
    let h = (b - a) / n as f64;
    let mut s = f(a) + f(b);
    for k in 1..n {
        s += if k % 2 == 1 { 4.0 } else { 2.0 } * f(a + k as f64 * h);
    }
    s * h / 3.0
}

// Hurwitz zeta values zeta(-1/2, 1/2) = (2^-1/2 - 1) zeta(-1/2) and zeta(-3/2, 1/2) =
// (2^-3/2 - 1) zeta(-3/2), with zeta(-1/2) = -0.2078862249773546, zeta(-3/2) = -0.0254852018898330,
// and zeta(-1, 1/2) = 1/24: the coefficients of the generalised Euler-Maclaurin expansion of the
// midpoint rule at an endpoint where the integrand behaves like t^(1/2), t, t^(3/2) (Navot 1961).
const Z_HALF: f64 = (std::f64::consts::FRAC_1_SQRT_2 - 1.0) * -0.207_886_224_977_354_6;
const Z_ONE: f64 = 1.0 / 24.0;
const Z_THREE_HALVES: f64 = (0.353_553_390_593_273_8 - 1.0) * -0.025_485_201_889_833_0;

#[test]
fn newtonian_couette_equals_quadrature_of_the_analytic_integrand() {
    // Reference: int_{-b}^{b} eta(p(x)) du / h(x) dx, with x = b sin(theta) so that the integrand
    // is smooth in theta; Simpson with 20000 panels agrees with 4000 panels to 1e-15 relative.
    let srr = 0.02;
    let du = UE * srr;
    let integrand = |x: f64| ETA0 * (ALPHA * hertz_line(x)).exp() * du / film(x, 0.0);
    let exact = simpson(
        |t| integrand(B * t.sin()) * B * t.cos(),
        -PI / 2.0,
        PI / 2.0,
        20_000,
    );

    // The friction sum is the midpoint rule over the cells inside |x| < b. Near x = b (t = b - x)
    // the integrand is F(b)[1 + a s + a^2 s^2/2 + a^3 s^3/6 ...](1 - t/(4b) ...) with
    // s = sqrt(2t/b), a = alpha p0, F = eta0 du / h, so the midpoint error is, per endpoint,
    // zeta(-1/2,1/2) A dx^1.5 + (1/24) B dx^2 + zeta(-3/2,1/2) C dx^2.5 + O(dx^3.5) (the t^2 term
    // has zeta(-2, 1/2) = 0). The test checks the measured error against this prediction: the
    // omitted terms are O(a sqrt(2 dx / b))^2 smaller than the last one kept, measured 0.14 % of
    // the error at nx = 400; 1 % tolerance.
    let fb = ETA0 * du / film(B, 0.0);
    let dfb = -fb * fb / (ETA0 * du) * B / R; // F'(b)
    let a = ALPHA * P0;
    let q = (2.0 / B).sqrt();
    let ca = fb * a * q;
    let cb = fb * a * a / B - dfb;
    let cc = fb * (a.powi(3) * q.powi(3) / 6.0 - a * q / (4.0 * B)) - dfb * a * q;
    for nx in [400, 1600] {
        let f = line_fields(nx, 0.0);
        let fr = run(&f, srr, &Rheology::Newtonian);
        let dx = f.grid.dx;
        let predicted = 2.0
            * (Z_HALF * ca * dx.powf(1.5)
                + Z_ONE * cb * dx * dx
                + Z_THREE_HALVES * cc * dx.powf(2.5));
        let err = fr.couette_force - exact;
        eprintln!(
            "nx {nx}: couette {:.12e}, exact {exact:.12e}, error {:.3e} rel, predicted {:.3e} rel",
            fr.couette_force,
            err / exact,
            predicted / exact
        );
        assert!(
            (err - predicted).abs() < 0.01 * predicted.abs(),
            "nx {nx}: error {err:e} vs predicted {predicted:e}"
        );
        assert!(err.abs() < 3e-7 * exact);
    }
}

#[test]
fn poiseuille_part_equals_the_integrated_by_parts_form() {
    // int -(h/2) dp/dx dx = (1/2) int p dh/dx dx (p = 0 at the ends). For h = h0 + x^2/2R + c x
    // and a symmetric p this is (c/2) int p dx = (c/2) pi p0 b / 2 (Hertz).
    //
    // (1) Discrete identity: with central differences and p = 0 in the outer cells, summation
    // by parts gives sum -(h_i/2)(p_{i+1} - p_{i-1})/(2dx) dx = (1/2) sum p_i (h_{i+1} - h_{i-1})/(2dx) dx,
    // and the central difference of a quadratic is exact, so the friction sum equals
    // (1/2) sum p_i h'(x_i) dx up to round-off. Round-off: the sum cancels terms ~45x larger
    // than the result over 1600 cells, ~1e-13 relative; tolerance 1e-11.
    let c = 1e-4;
    for nx in [400, 1600] {
        let f = line_fields(nx, c);
        let fr = run(&f, 0.0, &Rheology::Newtonian);
        assert_eq!(fr.couette_force, 0.0, "no sliding, no Couette force");
        let by_parts: f64 = f
            .grid
            .xs()
            .iter()
            .zip(&f.p)
            .map(|(&x, &p)| 0.5 * p * (x / R + c))
            .sum::<f64>()
            * f.grid.dx;
        assert!(
            (fr.poiseuille_force / by_parts - 1.0).abs() < 1e-11,
            "nx {nx}: {} vs {by_parts}",
            fr.poiseuille_force
        );
        // (2) Against the analytic value: the error is (c/2) times the midpoint error of
        // int p dx, whose leading term is 2 zeta(-1/2,1/2) p0 sqrt(2/b) dx^1.5 (Hertz edges),
        // the next one (t^(3/2)) being O(dx/b) = 1 % of it at nx = 400; tolerance 2 %.
        let exact = 0.5 * c * PI * P0 * B / 2.0;
        let predicted = 0.5 * c * 2.0 * Z_HALF * P0 * (2.0 / B).sqrt() * f.grid.dx.powf(1.5);
        let err = fr.poiseuille_force - exact;
        eprintln!("nx {nx}: poiseuille {:.10e}, exact {exact:.10e}, error {err:.3e}, predicted {predicted:.3e}", fr.poiseuille_force);
        assert!((err - predicted).abs() < 0.02 * predicted.abs());
    }
}

#[test]
fn symmetric_pressure_and_film_give_zero_net_poiseuille_force() {
    // dp/dx is odd and h even: the sum cancels pairwise. Tolerance relative to the sum of the
    // magnitudes of the cell contributions: round-off only, 1e-13.
    let f = line_fields(401, 0.0); // odd count: a cell centred at x = 0
    let fr = run(&f, 0.0, &Rheology::Newtonian);
    let tau = surface_shear_stress(&FrictionInput {
        grid: &f.grid,
        pressure: &f.p,
        film: &f.h,
        viscosity: &f.eta,
        u1: UE,
        u2: UE,
        rheology: &Rheology::Newtonian,
        load: 1.0,
    })
    .unwrap();
    let scale: f64 = tau.iter().map(|t| t.abs()).sum::<f64>() * f.grid.dx;
    assert!(scale > 0.0);
    assert!(
        fr.poiseuille_force.abs() < 1e-13 * scale,
        "{} vs {scale}",
        fr.poiseuille_force
    );
    // and the shear stress field is odd about x = 0
    for i in 0..f.grid.nx {
        assert!((tau[i] + tau[f.grid.nx - 1 - i]).abs() <= 1e-12 * tau[i].abs().max(1e-30));
    }
}

#[test]
fn one_sided_differences_are_exact_for_a_linear_pressure() {
    // p = p1 + s x > 0 everywhere, h constant: central and one-sided differences are exact for a
    // linear p, so the Poiseuille force is -(h/2) s * area to round-off (1e-12).
    let grid = Grid::new(37, 5, -1e-4, 2e-4, -3e-4, 3e-4);
    let s = 2e12;
    let p: Vec<f64> = (0..grid.len())
        .map(|k| 1e9 + s * grid.x(k % grid.nx))
        .collect();
    let h = vec![2e-7; grid.len()];
    let eta = vec![1.0; grid.len()];
    let fr = friction(&FrictionInput {
        grid: &grid,
        pressure: &p,
        film: &h,
        viscosity: &eta,
        u1: 1.0,
        u2: 1.0,
        rheology: &Rheology::Newtonian,
        load: 1.0,
    })
    .unwrap();
    let area = (grid.x_max() - grid.x_min) * (grid.y_max() - grid.y_min);
    let expected = -0.5 * 2e-7 * s * area;
    assert!(
        (fr.poiseuille_force / expected - 1.0).abs() < 1e-12,
        "{} vs {expected}",
        fr.poiseuille_force
    );
    assert_eq!(fr.couette_force, 0.0);
}

#[test]
fn newtonian_friction_is_linear_in_srr_and_matches_the_slide_to_roll_definition() {
    // Isothermal Newtonian: the Reynolds equation depends on u_e only, so the fields do not
    // change with SRR and the Couette force is exactly proportional to u1 - u2 = u_e SRR; the
    // Poiseuille part does not depend on SRR. Round-off: 1e-13.
    let f = line_fields(400, 1e-4);
    let base = run(&f, 0.0, &Rheology::Newtonian);
    let r1 = run(&f, 0.01, &Rheology::Newtonian);
    for srr in [0.002, 0.005, 0.02, 0.05] {
        let r = run(&f, srr, &Rheology::Newtonian);
        assert!((r.couette_force / r1.couette_force - srr / 0.01).abs() < 1e-13);
        assert_eq!(r.poiseuille_force, base.poiseuille_force);
        assert!(
            ((r.coefficient - base.coefficient) / (r1.coefficient - base.coefficient) - srr / 0.01)
                .abs()
                < 1e-10
        );
        let (u1, u2) = surface_speeds(UE, srr);
        assert!((slide_to_roll(u1, u2).unwrap() - srr).abs() < 1e-15);
        assert!((0.5 * (u1 + u2) - UE).abs() < 1e-15);
    }
    // sign convention: SRR > 0 (body 1 faster) gives a positive Couette force on body 2,
    // and reversing the sliding reverses it exactly
    assert!(r1.couette_force > 0.0);
    assert_eq!(
        run(&f, -0.01, &Rheology::Newtonian).couette_force,
        -r1.couette_force
    );
    assert_eq!(slide_to_roll(1.0, -1.0), None);
}

#[test]
fn carreau_with_n_one_and_eyring_at_small_stress_equal_newtonian() {
    let f = line_fields(400, 1e-4);
    let srr = 0.02;
    let newton = run(&f, srr, &Rheology::Newtonian);
    // Carreau n = 1: the factor hypot(1, x)^0 is exactly 1; round-off 1e-14.
    let carreau1 = Rheology::Carreau {
        shear_modulus: 4.5e6,
        power_law_index: 1.0,
        limiting_shear_coefficient: None,
    };
    let c = run(&f, srr, &carreau1);
    assert!((c.force / newton.force - 1.0).abs() < 1e-14);
    assert!((c.couette_force / newton.couette_force - 1.0).abs() < 1e-14);

    // Eyring with a large tau_0: tau = tau_0 asinh(s) = eta gamma_dot (1 - s^2/6 + ...), s =
    // eta gamma_dot / tau_0, so the Couette force lies below Newtonian by at most s_max^2 / 6.
    let du = UE * srr;
    let s_max = f
        .eta
        .iter()
        .zip(&f.h)
        .map(|(e, h)| e * du / h)
        .fold(0.0, f64::max)
        / 1e12;
    let eyring = Rheology::Eyring {
        eyring_stress: 1e12,
        limiting_shear_coefficient: None,
    };
    let e = run(&f, srr, &eyring);
    let dev = 1.0 - e.couette_force / newton.couette_force;
    eprintln!("Eyring tau0 = 1e12: s_max = {s_max:.3e}, deviation {dev:.3e}");
    assert!(dev > 0.0 && dev <= s_max * s_max / 6.0 * (1.0 + 1e-6));

    // Carreau n = 0.57 at small SRR: tau = eta gamma_dot (1 - (1-n)/2 x^2 + ...), x = eta
    // gamma_dot / G; at SRR = 1e-9 (x_max ~ 1e-4 here) the deviation is below (1-n)/2 x_max^2.
    let carreau = Rheology::Carreau {
        shear_modulus: 4.5e6,
        power_law_index: 0.57,
        limiting_shear_coefficient: Some(0.06),
    };
    let srr = 1e-9;
    let x_max = f
        .eta
        .iter()
        .zip(&f.h)
        .map(|(e, h)| e * UE * srr / h)
        .fold(0.0, f64::max)
        / 4.5e6;
    let dev = 1.0
        - run(&f, srr, &carreau).couette_force / run(&f, srr, &Rheology::Newtonian).couette_force;
    eprintln!("Carreau SRR = 1e-9: x_max = {x_max:.3e}, deviation {dev:.3e}");
    assert!(x_max < 1e-3);
    assert!(dev > 0.0 && dev <= 0.5 * 0.43 * x_max * x_max * (1.0 + 1e-6));
}

#[test]
fn couette_traction_coefficient_tends_to_lambda() {
    // With tau_L = Lambda p the Couette stress is capped by Lambda p in every cell, so
    // couette_force <= Lambda sum p dA = Lambda F exactly (load = the pressure integral here);
    // as the sliding grows every cell saturates (Carreau: G x^n -> inf; Eyring: tau_0 ln(2s) ->
    // inf), so couette_force / F -> Lambda. Checked: monotone in SRR, never above Lambda, and
    // within 1e-3 Lambda at SRR = 2 (u2 = 0) for Carreau; Eyring grows only logarithmically, so
    // it is checked at a sliding speed of 2e4 m/s (SRR 2500 at u_e = 8 m/s; fields fixed; a
    // mathematical limit check).
    let f = line_fields(400, 1e-4);
    let lambda = 0.06;
    let models = [
        Rheology::Carreau {
            shear_modulus: 4.5e6,
            power_law_index: 0.57,
            limiting_shear_coefficient: Some(lambda),
        },
        Rheology::Eyring {
            eyring_stress: 5e6,
            limiting_shear_coefficient: Some(lambda),
        },
    ];
    for model in &models {
        let mut last = 0.0;
        let mut line = String::new();
        for srr in [1e-4, 1e-3, 0.01, 0.05, 0.1, 0.5, 1.0, 2.0, 2500.0] {
            let r = run(&f, srr, model);
            let load = f.p.iter().sum::<f64>() * f.grid.dx;
            let mu_c = r.couette_force / load;
            line += &format!(" {srr}:{mu_c:.5}");
            assert!(mu_c >= last, "not monotone at SRR {srr}");
            assert!(mu_c <= lambda * (1.0 + 1e-14));
            last = mu_c;
            if srr == 2.0 && matches!(model, Rheology::Carreau { .. }) {
                assert!(mu_c > lambda * (1.0 - 1e-3), "Carreau at SRR 2: {mu_c}");
            }
        }
        eprintln!("{model:?}: SRR:mu_couette{line}");
        assert!(last > lambda * (1.0 - 1e-3), "{model:?}: {last}");
    }
}

#[test]
fn extruded_line_contact_scales_with_length_in_2d() {
    // The same x-profile on ny rows over a length L gives L times the per-unit-length result of
    // the 1D grid (dy = 1): checks the cell area and the row-wise gradient. Round-off 1e-13.
    let one = line_fields(400, 1e-4);
    let (ny, len) = (7, 3e-3);
    let grid = Grid::new(400, ny, -2.0 * B, 2.0 * B, -0.5 * len, 0.5 * len);
    let rep = |v: &Vec<f64>| {
        (0..ny)
            .flat_map(|_| v.iter().copied())
            .collect::<Vec<f64>>()
    };
    let two = Fields {
        grid,
        p: rep(&one.p),
        h: rep(&one.h),
        eta: rep(&one.eta),
    };
    let carreau = Rheology::Carreau {
        shear_modulus: 4.5e6,
        power_law_index: 0.57,
        limiting_shear_coefficient: Some(0.06),
    };
    for model in [Rheology::Newtonian, carreau] {
        let r1 = run(&one, 0.03, &model);
        let r2 = run(&two, 0.03, &model);
        assert!((r2.couette_force / (len * r1.couette_force) - 1.0).abs() < 1e-13);
        assert!((r2.poiseuille_force / (len * r1.poiseuille_force) - 1.0).abs() < 1e-13);
        assert!((r2.coefficient / r1.coefficient - 1.0).abs() < 1e-13);
    }
}

#[test]
fn point_contact_couette_matches_polar_quadrature() {
    // Ball on flat: p = p0 sqrt(1 - r^2/a^2), h = h0 + r^2/(2R), Barus. Reference:
    // 2 pi int_0^a eta(p(r)) du / h(r) r dr with r = a sin(theta) (Simpson, 20000 panels).
    // The cell sum counts the cells whose centres lie in the disc, so it differs from the
    // reference by the staircase boundary: at most max f over the band a +- dx/sqrt2 times the
    // band's area 2 sqrt2 pi a dx, plus the interior midpoint error (O(dx^1.5) near the edge,
    // included in the band bound since it lives in the outermost cells). The band bound is
    // the tolerance; the error must also fall on the finer grid.
    let (a, p0, h0, rr, du) = (1.5e-4, 0.4e9, 1e-7, 0.0125, 0.1);
    let f = |r: f64| {
        let s = 1.0 - (r / a).powi(2);
        let p = if s > 0.0 { p0 * s.sqrt() } else { 0.0 };
        ETA0 * (ALPHA * p).exp() * du / (h0 + r * r / (2.0 * rr))
    };
    let exact = simpson(
        |t| 2.0 * PI * f(a * t.sin()) * a * t.sin() * a * t.cos(),
        0.0,
        PI / 2.0,
        20_000,
    );
    let mut errors = vec![];
    for n in [64, 128] {
        let grid = Grid::new(n, n, -1.5 * a, 1.5 * a, -1.5 * a, 1.5 * a);
        let mut p = vec![0.0; grid.len()];
        let mut h = vec![0.0; grid.len()];
        let mut eta = vec![0.0; grid.len()];
        for j in 0..n {
            for i in 0..n {
                let r = grid.x(i).hypot(grid.y(j));
                let k = grid.idx(i, j);
                let s = 1.0 - (r / a).powi(2);
                p[k] = if s > 0.0 { p0 * s.sqrt() } else { 0.0 };
                h[k] = h0 + r * r / (2.0 * rr);
                eta[k] = ETA0 * (ALPHA * p[k]).exp();
            }
        }
        let load = p.iter().sum::<f64>() * grid.cell_area();
        let fr = friction(&FrictionInput {
            grid: &grid,
            pressure: &p,
            film: &h,
            viscosity: &eta,
            u1: UE + 0.5 * du,
            u2: UE - 0.5 * du,
            rheology: &Rheology::Newtonian,
            load,
        })
        .unwrap();
        let dx = grid.dx;
        let band_max = f(a - dx / 2f64.sqrt()); // f decreases with r
        let bound = band_max * 2.0 * 2f64.sqrt() * PI * a * dx;
        let err = fr.couette_force - exact;
        eprintln!(
            "ball {n}^2: couette {:.6e}, exact {exact:.6e}, error {:.3e} rel, bound {:.3e} rel",
            fr.couette_force,
            err / exact,
            bound / exact
        );
        assert!(err.abs() < bound);
        // symmetric fields: no net pressure-flow force (round-off against |p| h / 2 scale)
        assert!(fr.poiseuille_force.abs() < 1e-12 * p0 * h0 * a);
        errors.push(err.abs());
    }
    assert!(errors[1] < errors[0]);
}
