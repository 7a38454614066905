//! Thermal EHL against independent references (issue 13): the isothermal limit, the energy
//! balance, the classical inlet-heating reduction of the film and the shape of the traction
//! curve. The solid's moving heat source has its exact limits in `thermal::solid`'s unit tests,
//! the film's exact Couette solution in `thermal::film_energy`'s.
//!
//! Each case is the thesis Table 3.7 line contact (`examples/ehl_friction_line.toml`) on a
//! coarse grid (256 cells) so that the suite stays fast; the grid dependence is in
//! docs/thermal.md.

use ehl::case::{parse_str, Case};
use ehl::solution::{Solution, Summary};

const LINE: &str = include_str!("../../../examples/ehl_friction_line.toml");
const THERMAL: &str = include_str!("../../../examples/ehl_thermal_line.toml");

fn case(extra: &str, sets: &[&str]) -> Case {
    let text = format!("{LINE}\n{extra}");
    let mut all: Vec<String> = vec!["grid.nx=256".into()];
    all.extend(sets.iter().map(|s| s.to_string()));
    parse_str(&text, "thermal.toml", &all).unwrap()
}

/// The text of `examples/{file}`.
fn example(file: &str) -> String {
    let path = format!("{}/../../examples/{file}", env!("CARGO_MANIFEST_DIR"));
    std::fs::read_to_string(&path).unwrap()
}

/// Solves `c`; a converged steady solve must end on a Reynolds solution to the case's own
/// tolerance (the fixed point's Newton solves before the end are looser).
fn solve(c: &Case) -> Solution {
    let s = match ehl::run::solve(c, &ehl::run::Silent) {
        Ok(s) => s,
        Err(e) => panic!("{e}"),
    };
    let m = &s.summary;
    if m.converged && s.transient.is_none() {
        let tol = c.solver.tolerance;
        let res = m.residual.expect("a converged solve states its residual");
        assert!(
            res <= tol && m.load_error.abs() <= tol,
            "converged with residual {res:e}, load error {:e} (tolerance {tol:e})",
            m.load_error
        );
    }
    s
}

/// Newton's method on the coupled problem (`a`) and the fixed point alone (`b`) on the same
/// line: the films and friction within `rel` of each other, the largest film temperature
/// within `kelvin`.
fn assert_methods_agree(
    a: &ehl::solution::Summary,
    b: &ehl::solution::Summary,
    figures: &[&str],
    rel: f64,
    kelvin: f64,
) {
    for &name in figures {
        let (x, y) = match name {
            "central film" => (a.central_film_m, b.central_film_m),
            "minimum film" => (a.min_film_m, b.min_film_m),
            "friction" => (a.friction_coefficient, b.friction_coefficient),
            _ => panic!("no figure {name}"),
        };
        let (x, y) = (x.unwrap(), y.unwrap());
        assert!(
            (x / y - 1.0).abs() < rel,
            "{name}: Newton {x:.7e}, fixed point {y:.7e}"
        );
    }
    let (ta, tb) = (
        a.max_film_temperature_k.unwrap(),
        b.max_film_temperature_k.unwrap(),
    );
    assert!(
        (ta - tb).abs() < kelvin,
        "largest film temperature {ta} against {tb} K"
    );
}

/// A Newtonian, isothermal-looking film: rheology Newtonian (the thermal run uses the full
/// velocity profile, the isothermal one the Newtonian Reynolds equation: the same law).
const NEWTONIAN: &str = "lubricant.rheology={ model = \"newtonian\" }";

/// With an oil and bodies that conduct heat away almost perfectly (k = 1e6 W/(m K) in the oil,
/// 1e7 times an oil's, and 1e10 in the bodies) the temperatures stay at the inlet's (measured
/// rise 3e-4 K) and the thermal solver must give the isothermal film
/// and pressure: the generalized Reynolds factors are then 1 up to the collocation's
/// round-off, so the difference is the Newton tolerance (1e-6 relative residual), not a model
/// difference. Tolerance 1e-4 relative on the films: a residual of 1e-6 moves H0 by ~1e-5.
#[test]
fn a_perfectly_conducting_oil_gives_the_isothermal_solution() {
    let iso = solve(&case("", &[NEWTONIAN, "motion.slide_to_roll=0.3"]));
    let th = solve(&case(
        "[thermal]\nconductivity = 1e6\n",
        &[
            NEWTONIAN,
            "motion.slide_to_roll=0.3",
            "body1.conductivity=1e10",
            "body2.conductivity=1e10",
        ],
    ));
    assert!(
        iso.summary.converged && th.summary.converged,
        "{}",
        th.summary.termination
    );
    let rise = th.summary.max_film_temperature_k.unwrap() - 313.0;
    assert!(rise < 1e-3, "rise {rise} K");
    for (a, b, what) in [
        (
            iso.summary.central_film_m.unwrap(),
            th.summary.central_film_m.unwrap(),
            "central film",
        ),
        (
            iso.summary.min_film_m.unwrap(),
            th.summary.min_film_m.unwrap(),
            "minimum film",
        ),
        (
            iso.summary.max_pressure_pa,
            th.summary.max_pressure_pa,
            "max pressure",
        ),
    ] {
        assert!(
            (b / a - 1.0).abs() < 1e-4,
            "{what}: thermal {b} vs isothermal {a}"
        );
    }
    // the friction: the same Newtonian film, integrated from the profile (thermal) or the
    // closed-form Couette + Poiseuille stress (isothermal), both exact for a Newtonian film:
    // what parts them is the film, within 1e-4 (above), the Couette stress going as 1/h, and
    // the 3e-4 K rise (beta dT ~ 1e-5 on the viscosity): 2e-4 (measured 1.5e-5)
    let (fi, ft) = (
        iso.summary.friction_coefficient.unwrap(),
        th.summary.friction_coefficient.unwrap(),
    );
    assert!(
        (ft / fi - 1.0).abs() < 2e-4,
        "friction thermal {ft} vs isothermal {fi}"
    );
}

/// Pure rolling, a Newtonian oil at low speed (U = 7.3e-12, a tenth of the table's; thermal
/// loading L = eta0 beta u_e^2 / k_f = 0.0075 with the Roelands beta at the inlet, 0.041 1/K):
/// the issue asks the film to change by well under 1 %. The thermal film is thinner, never
/// thicker; by less than 1 %; by no more than Murch & Wilson's fit says (1.2 % here: our
/// reduction is below the fits', docs/thermal.md "Known disagreement"); and by at least half
/// of what an independent Grubin inlet analysis with the exact local thermal Poiseuille
/// column gives at the same L (`reference::thermal::grubin_thermal_ratio`, heated
/// everywhere). Measured: 0.64 % against the fit's 1.2 % and the Grubin's 0.15 %. Under that
/// analysis's own assumptions our solver lies within a quarter of its reduction at L = 0.13
/// and 0.55 (`film_reduction_against_a_thermal_grubin_inlet`), and the physics it adds here
/// (Roelands, compression and expansion, warming surfaces) adds reduction there; here ours is
/// 4.3 times the Grubin's (1.4-1.7 times at L = 0.13 and 0.55), which those measurements do
/// not explain. The bound is a floor only, so that a thermal solve that left the film alone
/// fails.
#[test]
fn pure_rolling_at_low_speed_changes_the_film_by_well_under_one_percent() {
    let sets = [
        NEWTONIAN,
        "motion.slide_to_roll=0.0",
        "motion.dimensionless_speed=7.3e-12",
    ];
    let iso = solve(&case("", &sets));
    let c = case("[thermal]\n", &sets);
    let th = solve(&c);
    assert!(th.summary.converged, "{}", th.summary.termination);
    let (a, b) = (
        iso.summary.central_film_m.unwrap(),
        th.summary.central_film_m.unwrap(),
    );
    let r = b / a;
    let l = ehl::reference::check::case_thermal_loading(&c).unwrap();
    let mw = ehl::reference::thermal::murch_wilson(l);
    let grubin = grubin_for(&c, None);
    println!("low speed: L {l:.4}, ours {r:.5}, Murch-Wilson {mw:.5}, Grubin {grubin:.5}");
    assert!(
        r <= 1.0 + 1e-6 && 1.0 - r < 0.01 && 1.0 - r <= 1.0 - mw,
        "L {l:.4}: thermal / isothermal central film {r}, Murch-Wilson {mw}"
    );
    assert!(
        1.0 - r >= 0.5 * (1.0 - grubin),
        "L {l:.4}: thermal / isothermal central film {r}, Grubin inlet {grubin}"
    );
}

/// Energy: heat generated (shear + compression) = heat into the two bodies + heat convected out,
/// within 1 % at a converged solution (issue 13), here the example `ehl_thermal_line.toml`
/// (SRR 0.3, the thesis' Carreau oil with its index varying with temperature), where 97 % of
/// the heat goes into the bodies. The film's discrete balance telescopes with its
/// consistent wall fluxes (`thermal::film_energy`), so what remains is the fixed point's
/// tolerance: measured 2e-4.
#[test]
fn the_heat_generated_leaves_through_the_bodies_and_the_oil() {
    let c = parse_str(
        THERMAL,
        "ehl_thermal_line.toml",
        &["grid.nx=256".to_string()],
    )
    .unwrap();
    let s = solve(&c);
    let m = &s.summary;
    assert!(m.converged, "{}", m.termination);
    let err = m.energy_balance_error.unwrap();
    assert!(err.abs() < 1e-2, "energy balance {err}");
    let g = m.heat_generated_w.unwrap();
    let [b1, b2] = m.heat_to_body_w.unwrap();
    assert!(g > 0.0 && b1 > 0.0 && b2 > 0.0 && m.heat_convected_w.unwrap() > 0.0);
    // the film is hotter than both surfaces, which are hotter than the inlet
    let [s1, s2] = m.max_surface_temperature_k.unwrap();
    let tf = m.max_film_temperature_k.unwrap();
    assert!(tf > s1.max(s2) && s1.min(s2) > 313.0, "{tf} {s1} {s2}");
}

/// The traction curve of the thesis Table 3.7 line (the example `ehl_thermal_line.toml`, 256
/// cells), thermal against isothermal, at SRR 0.01, 0.1, 0.3 and 1.0 (issue 13's "Traction"):
/// * at SRR 0.01 the two coincide within 2 % (the issue's tolerance; measured 1.2 %): the film
///   there is 11 K warmer than the inlet, which lowers f by about that much;
/// * the thermal curve rises, then falls past its peak: f(0.01) < f(0.1) > f(0.3) > f(1.0)
///   (measured 0.0067, 0.0176, 0.0148, 0.0088), as measured traction curves do, while the
///   isothermal one, capped by the limiting shear stress, never falls (0.0278, 0.0481,
///   0.0553);
/// * every point converges, SRR 1.0 included (before the damped coupling it did not: the
///   factors' fixed point oscillated at the Hertz outlet and ran away).
#[test]
fn the_thermal_traction_curve_peaks_and_falls() {
    let mut thermal = Vec::new();
    let mut iso = Vec::new();
    for srr in [0.01, 0.1, 0.3, 1.0] {
        let set = [
            format!("motion.slide_to_roll={srr}"),
            "grid.nx=256".to_string(),
        ];
        let t = solve(&parse_str(THERMAL, "ehl_thermal_line.toml", &set).unwrap());
        assert!(t.summary.converged, "SRR {srr}: {}", t.summary.termination);
        let i = solve(&case("", &[set[0].as_str()]));
        assert!(i.summary.converged, "SRR {srr}: {}", i.summary.termination);
        thermal.push(t.summary.friction_coefficient.unwrap());
        iso.push(i.summary.friction_coefficient.unwrap());
    }
    println!("traction: thermal {thermal:?}, isothermal {iso:?}");
    let low = thermal[0] / iso[0] - 1.0;
    assert!(
        low.abs() < 0.02,
        "SRR 0.01: thermal {} vs isothermal {}",
        thermal[0],
        iso[0]
    );
    assert!(
        thermal[0] < thermal[1] && thermal[1] > thermal[2] && thermal[2] > thermal[3],
        "thermal f at SRR 0.01, 0.1, 0.3, 1.0 must rise, then fall: {thermal:?}"
    );
    assert!(
        iso.windows(2).all(|w| w[1] >= w[0]),
        "isothermal f must not fall: {iso:?}"
    );
}

/// Grid convergence of the thermal solution (the Table 3.7 line at SRR 0.3, Carreau with n(T)):
/// 256, 512 and 1024 cells all converge (1024 did not before the thick inlet's cross-film
/// Peclet number was bounded: the film temperature oscillated to -900 K there), and the friction
/// coefficient and central film converge: each halving of dx must at least halve the change
/// (measured: f 0.0148265, 0.0147519, 0.0147309, 0.0147249 at 2048, ratio ~3.5 per halving;
/// central film 1.03229, 1.03666, 1.03759, 1.03774 um, ratio 4.7-6.5), and the 512-1024 change
/// must be below 0.5 % (measured 0.14 % in f, 0.09 % in the film).
#[test]
fn the_thermal_line_converges_with_the_grid() {
    let mut f = Vec::new();
    let mut hc = Vec::new();
    for nx in [256, 512, 1024] {
        let set = [format!("grid.nx={nx}")];
        let t = solve(&parse_str(THERMAL, "ehl_thermal_line.toml", &set).unwrap());
        assert!(t.summary.converged, "{nx} cells: {}", t.summary.termination);
        f.push(t.summary.friction_coefficient.unwrap());
        hc.push(t.summary.central_film_m.unwrap());
    }
    for (name, v) in [("friction", &f), ("central film", &hc)] {
        let (d1, d2) = ((v[1] - v[0]).abs(), (v[2] - v[1]).abs());
        assert!(d2 < 0.5 * d1, "{name}: {v:?}");
        assert!(d2 < 5e-3 * v[2], "{name}: {v:?}");
    }
}

/// The thermal reduction of the central film in pure rolling against the classical
/// inlet-heating factors (Barus-exponential oil, beta = 0.03 1/K, Newtonian; the speed sets the
/// thermal loading L = eta0 beta u_e^2 / k_f). Printed for docs/thermal.md:
/// `cargo test --release -p ehl --test thermal -- --ignored --nocapture`.
#[test]
#[ignore = "long validation: cargo test --release -p ehl --test thermal -- --ignored"]
fn film_reduction_sweep() {
    for u in [3.6e-11, 7.3e-11, 1.1e-10, 1.55e-10, 2.2e-10, 3.1e-10] {
        for nx in [256, 512] {
            let (r, l, mw, gu, _) = reduction(u, nx);
            println!(
                "U {u:e} nx {nx}: L {l:.3}: thermal/isothermal {r:.4}, Murch-Wilson {mw:.4}, Gupta {gu:.4}"
            );
        }
    }
}

/// A steady thermal solve whose temperature solve fails is solved again with 11 points across
/// the film, and the run says so: pure rolling on the Barus line at U = 2.2e-10 (L = 5.0,
/// 256 cells), where 7 points let the thick inlet's film temperature run away (a negative
/// density); the warning says why the first attempt failed. The retry starts afresh, so it
/// must give what a run asking for 11 points gives (to 1e-9: the same arithmetic, summed in
/// parallel), and that run warns of nothing.
#[test]
fn a_failed_temperature_solve_is_solved_again_with_more_points() {
    let run = |extra: &[&str]| {
        let mut sets = vec![
            NEWTONIAN,
            "motion.slide_to_roll=0.0",
            "motion.dimensionless_speed=2.2e-10",
            "lubricant.viscosity_model=\"barus\"",
        ];
        sets.extend(extra);
        let s = solve(&case("[thermal]\nviscosity_beta = 0.03\n", &sets));
        assert!(s.summary.converged, "{extra:?}: {}", s.summary.termination);
        s.summary
    };
    let retried = run(&[]);
    let warned = |w: &[String]| {
        w.iter().any(|w| {
            // the warning says why the first attempt failed, in parentheses
            w.contains("failed with thermal.points_across_film = 7 (")
                && w.contains("solved again with 11 points")
        })
    };
    assert!(warned(&retried.warnings), "{:?}", retried.warnings);
    let direct = run(&["thermal.points_across_film=11"]);
    assert!(
        !direct.warnings.iter().any(|w| w.contains("solved again")),
        "{:?}",
        direct.warnings
    );
    for (name, a, b) in [
        (
            "central film",
            retried.central_film_m,
            direct.central_film_m,
        ),
        ("minimum film", retried.min_film_m, direct.min_film_m),
        (
            "film temperature",
            retried.max_film_temperature_k,
            direct.max_film_temperature_k,
        ),
    ] {
        let (a, b) = (a.unwrap(), b.unwrap());
        assert!(
            (a / b - 1.0).abs() < 1e-9,
            "{name}: retried {a:e}, direct {b:e}"
        );
    }
}

/// Pure rolling at high thermal loading settles on the finer grid too: the Barus line at
/// U = 2.2e-10 (L = 5.0) on 512 cells converges, with its energy balance within 1 %, and gives
/// the 256-cell film reduction to 2e-3 (measured 0.6521 against 0.6513; the grid's own
/// change, as at lower L). Before the film's temperature floor left room for the outlet's
/// adiabatic expansion cooling (38 K below the surfaces here), this run cycled for its 80 outer
/// iterations against a floor 30 K below the surfaces.
#[test]
fn pure_rolling_at_high_loading_settles_on_the_finer_grid() {
    let (r256, ..) = reduction(2.2e-10, 256);
    let (r512, ..) = reduction(2.2e-10, 512);
    assert!(
        (r512 - r256).abs() < 2e-3,
        "h_t/h_i {r256:.4} (256), {r512:.4} (512)"
    );
    let sets = [
        NEWTONIAN,
        "motion.slide_to_roll=0.0",
        "motion.dimensionless_speed=2.2e-10",
        "lubricant.viscosity_model=\"barus\"",
        "grid.nx=512",
    ];
    let s = solve(&case("[thermal]\nviscosity_beta = 0.03\n", &sets)).summary;
    assert!(s.converged, "{}", s.termination);
    let balance = s.energy_balance_error.unwrap();
    assert!(balance.abs() < 0.01, "energy balance {balance}");
}

/// Newton's method on the coupled problem of pressure, film and surface temperatures
/// (`thermal.coupled_newton`, on by default for line contacts; `ehl::ehl::thermal_newton`)
/// settles the Roelands-Carreau example line at SRR 1 and U = 2.2e-10 (L = 6.8, 512 cells),
/// which the fixed point alone does not settle in 80 outer iterations
/// (`a_thermal_run_beyond_the_known_loading_says_so`): it must converge, in fewer than 30
/// outer iterations (measured 15, and 6 Newton steps), its energy balance within the 1 %
/// the issue asks (measured 0.006 %). Where both settle they must agree, being the same
/// discrete equations solved by two methods: SRR 1 at U = 1.512e-10 (L = 3.2, the fixed
/// point alone 62 outer iterations, with Newton 21 and 3 Newton steps): central and minimum
/// film and friction within 1e-4, the fixed point's own stop (measured 3.5e-6, 3.6e-6,
/// 3.5e-6), the largest film temperature within 0.05 K, its temperature stop (measured
/// 2e-4 K).
/// ~2 s.
#[test]
fn newton_settles_the_sliding_line_the_fixed_point_did_not() {
    let run = |u: &str, newton: bool| {
        let sets = [
            "motion.slide_to_roll=1.0".to_string(),
            format!("motion.dimensionless_speed={u}"),
            format!("thermal.coupled_newton={newton}"),
        ];
        let s = solve(&parse_str(THERMAL, "ehl_thermal_line.toml", &sets).unwrap()).summary;
        assert!(s.converged, "U {u}, Newton {newton}: {}", s.termination);
        s
    };
    let (a, b) = (run("1.512e-10", true), run("1.512e-10", false));
    // (the agreement below is of two methods: the line must have been handed to Newton)
    let steps = a.thermal_newton_steps.unwrap();
    assert!(steps > 0, "{steps} Newton steps");
    assert_time_split("sliding line, Newton", &a, Some(true));
    assert_time_split("sliding line, fixed point", &b, Some(false));
    assert_methods_agree(
        &a,
        &b,
        &["central film", "minimum film", "friction"],
        1e-4,
        0.05,
    );

    let c = run("2.2e-10", true);
    let outer = c.thermal_iterations.unwrap();
    assert!(outer < 30, "{outer} outer iterations");
    let balance = c.energy_balance_error.unwrap();
    assert!(balance.abs() < 0.01, "energy balance {balance}");
}

/// A sliding line whose film is held by its limiting shear stress settles with Newton's method on
/// (the default) as with the fixed point alone, on the same solution: the example line loaded to
/// p_h = 2 GPa (W = 5e-4) at U = 1e-11 (1.1 m/s), Lambda = 0.06, SRR 0.5, 256 cells. The cap holds:
/// its friction coefficient is at least 5 % under the same line's without a limit (measured 0.0514
/// against 0.0568). Both must converge, with Newton in under 20 outer iterations (measured 14 and 5
/// Newton steps; the fixed point alone 20), and agree on friction and central film within 1e-5 and
/// the largest film temperature within 0.01 K, well inside the fixed point's stops on the factors
/// (1e-4) and temperatures (0.05 K) (measured 2.5e-6, 1.3e-6, 2.4e-4 K; all these figures at
/// bdf83d4). Until 2026-12-05 the case was Lambda = 0.04 (13 outer iterations and 2 Newton steps,
/// the fixed point alone 16 at the last measurement, 37 in an older one): since the surface
/// temperatures' linear solve is preconditioned (`ThermalContact::update_surfaces`) its fixed point
/// settles in 15 outer iterations and the polish is never asked for, which this test must exercise;
/// a faster fixed point may take this case from it again. Before the fixed point's columns matched
/// their flux with the capped profile, the two methods solved different equations where the cap
/// held (the columns' gradient a_capped / a_free times the pressure's): handed to Newton, the line
/// was polished again every outer iteration to the limit of 80 (measured on SRR 0.2 to 1 at Lambda
/// 0.04 and 0.06), and the fixed point's friction was 1.1 % lower (0.03791).
/// ~1 s.
#[test]
fn a_line_held_by_its_limiting_shear_stress_settles_on_one_solution() {
    let run = |lambda: Option<f64>, newton: bool| {
        let limit = lambda
            .map(|l| format!(", limiting_shear_coefficient = {l}"))
            .unwrap_or_default();
        let sets = [
            "load.dimensionless_load=5e-4".to_string(),
            "motion.dimensionless_speed=1e-11".to_string(),
            "motion.slide_to_roll=0.5".to_string(),
            format!(
                "lubricant.rheology={{ model = \"carreau\", shear_modulus = 4.5e6, power_law_index = [[313.0, 0.57], [373.0, 0.993]]{limit} }}"
            ),
            "grid.nx=256".to_string(),
            format!("thermal.coupled_newton={newton}"),
        ];
        let s = solve(&parse_str(THERMAL, "ehl_thermal_line.toml", &sets).unwrap()).summary;
        assert!(
            s.converged,
            "Lambda {lambda:?}, Newton {newton}: {}",
            s.termination
        );
        s
    };
    let (a, b) = (run(Some(0.06), true), run(Some(0.06), false));
    let steps = a.thermal_newton_steps.unwrap();
    let outer = a.thermal_iterations.unwrap();
    assert!(
        steps > 0 && outer < 20,
        "{outer} outer iterations, {steps} Newton steps"
    );
    assert_methods_agree(&a, &b, &["central film", "friction"], 1e-5, 0.01);
    let free = run(None, true).friction_coefficient.unwrap();
    let held = a.friction_coefficient.unwrap();
    assert!(held < 0.95 * free, "friction {held} held, {free} free");
}

/// A thermal run that fails above the loading below which the solver converged at every
/// slide-to-roll ratio measured says so: the Roelands-Carreau example line at U = 2.2e-10
/// (L = 6.8) and SRR 1 on its 512 cells does not settle in its 80 outer iterations with the
/// fixed point alone (`thermal.coupled_newton = false`; ~4 s; on 256 cells it does; with the
/// coupled Newton method it settles, `newton_settles_the_sliding_line_the_fixed_point_did_not`),
/// and its reason names the loading, the limit and the factors' residual;
/// `ehl check` notes it beforehand. The same line at U = 7.3e-11 (L = 0.75) converges and neither says anything.
#[test]
fn a_thermal_run_beyond_the_known_loading_says_so() {
    let line = |u: &str| {
        let sets = [
            "motion.slide_to_roll=1.0".to_string(),
            format!("motion.dimensionless_speed={u}"),
            "thermal.coupled_newton=false".to_string(),
        ];
        parse_str(THERMAL, "ehl_thermal_line.toml", &sets).unwrap()
    };
    let c = line("2.2e-10");
    let l = ehl::reference::check::case_thermal_loading(&c).unwrap();
    assert!((l - 6.77).abs() < 0.01, "L {l}");
    let s = solve(&c);
    assert!(!s.summary.converged);
    let why = &s.summary.termination;
    assert!(
        why.contains("thermal loading L = eta0 beta u_e^2/k_f is 6.77, above 2.5")
            && why.contains("the Reynolds factors by"),
        "{why}"
    );
    let note = ehl::reference::check::check_report(&c).to_string();
    assert!(note.contains("note: L is above 2.5"), "{note}");
    assert!(
        note.contains("7 points across the film lose accuracy at high L"),
        "{note}"
    );

    let c = line("7.3e-11");
    let s = solve(&c);
    assert!(s.summary.converged, "{}", s.summary.termination);
    assert!(!s.summary.termination.contains("thermal loading"));
    let note = ehl::reference::check::check_report(&c).to_string();
    assert!(!note.contains("note: L is above"), "{note}");
}

/// A thermal run with the Eyring law that fails says what the robustness scan found
/// (docs/thermal.md, "Robustness beyond the examples"): the example line with an Eyring oil,
/// stopped after 2 outer iterations so that it cannot settle (~0.1 s), with Newton's method on
/// the coupled problem (a line's default) or without, names the Eyring law and the Carreau law
/// that settled; the same run with its Carreau oil, and the Eyring run once settled (the
/// example's speed and load, 256 cells), say nothing of it. The hint itself: only for a
/// failed, not cancelled, thermal Eyring run. `ehl check` notes beforehand an Eyring case at
/// 1 GPa whose solution rests on the fixed point alone (`eyring_without_newton`: a line or a
/// ball with `thermal.coupled_newton = false`, a transient run), not at 0.5 GPa, and not a
/// steady line or ball with the coupled Newton method (the scan's 7 such lines at 1-2 GPa and
/// its 4 balls at 0.77 GPa all settle).
#[test]
fn a_failed_thermal_eyring_run_names_the_known_limit() {
    let eyring = r#"lubricant.rheology={model="eyring",eyring_stress=5e6}"#;
    let alone = "thermal.coupled_newton=false";
    let line = |sets: &[&str]| {
        let mut all: Vec<String> = vec!["grid.nx=256".into()];
        all.extend(sets.iter().map(|s| s.to_string()));
        parse_str(THERMAL, "ehl_thermal_line.toml", &all).unwrap()
    };
    let hint = "thermal runs with the Eyring law did not settle on the thermal fixed point alone";
    for sets in [
        &[eyring, "thermal.max_iterations=2"][..],
        &[eyring, alone, "thermal.max_iterations=2"][..],
    ] {
        let s = solve(&line(sets));
        assert!(!s.summary.converged);
        assert!(
            s.summary.termination.contains(hint),
            "{sets:?}: {}",
            s.summary.termination
        );
    }
    let s = solve(&line(&["thermal.max_iterations=2"]));
    assert!(!s.summary.converged);
    assert!(
        !s.summary.termination.contains(hint),
        "{}",
        s.summary.termination
    );
    let c = line(&[eyring]);
    let s = solve(&c);
    assert!(s.summary.converged, "{}", s.summary.termination);
    assert!(
        !s.summary.termination.contains(hint),
        "{}",
        s.summary.termination
    );
    use ehl::reference::check::eyring_without_newton;
    use ehl::run::thermal::rheology_hint;
    assert!(rheology_hint(&c, false, "thermal fixed point not settled").is_some());
    assert!(rheology_hint(&c, true, "converged").is_none());
    assert!(rheology_hint(&c, false, "cancelled").is_none());
    let carreau = parse_str(THERMAL, "ehl_thermal_line.toml", &[]).unwrap();
    assert!(rheology_hint(&carreau, false, "thermal fixed point not settled").is_none());
    // which contacts rest on the fixed point alone
    let c_alone = line(&[eyring, alone]);
    assert!(eyring_without_newton(&c_alone) && !eyring_without_newton(&c));
    assert!(!eyring_without_newton(&carreau));
    let ball = parse_str(
        include_str!("../../../examples/ehl_thermal_ball.toml"),
        "ehl_thermal_ball.toml",
        &[eyring.to_string()],
    )
    .unwrap();
    assert!(!eyring_without_newton(&ball));
    let ball_alone = parse_str(
        include_str!("../../../examples/ehl_thermal_ball.toml"),
        "ehl_thermal_ball.toml",
        &[eyring.to_string(), alone.to_string()],
    )
    .unwrap();
    assert!(eyring_without_newton(&ball_alone));
    let passage = parse_str(
        include_str!("../../../examples/ehl_thermal_transient_groove.toml"),
        "ehl_thermal_transient_groove.toml",
        &[eyring.to_string()],
    )
    .unwrap();
    assert!(passage.grid.ny == 1 && eyring_without_newton(&passage));
    // and `ehl check` notes it beforehand, from EYRING_NOTE_PRESSURE on (the example line's
    // Hertz pressure is 1.0 GPa)
    let note = |c: &Case| ehl::reference::check::check_report(c).to_string();
    let said = "note: thermal runs with the Eyring law did not settle";
    assert!(note(&c_alone).contains(said), "{}", note(&c_alone));
    assert!(!note(&c).contains(said), "{}", note(&c));
    assert!(!note(&carreau).contains(said));
    let low = line(&[eyring, alone, "load.dimensionless_load=3.25e-5"]); // 0.5 GPa
    assert!(!note(&low).contains(said), "{}", note(&low));
}

/// Eyring lines far past tau_0 settle (docs/thermal.md, "Robustness beyond the examples": the
/// scan's line, R = 20 mm steel rollers at p_h = 1 GPa and 5 m/s, eta0 = 0.05 Pa s, alpha =
/// 20 /GPa, tau_0 = 5 MPa, 256 cells; before 2026-12-01 SRR 0.1 ended with its film temperature
/// running away to ~4000 K and SRR 0.5 unsettled after 80 outer iterations). At the outlet's
/// spike the column's Poiseuille stress is several tau_0 and its flux-driven gradient has
/// more than one root (`film_energy`'s `UNSTABLE_FLUX_SLOPE`); the fixed point wanders and is
/// handed to Newton's method on the coupled problem. Checked: settled within the default
/// limit of 80 outer iterations (measured 21 each), the energy balance within the 1 % the
/// issue asks (measured 3e-5 and 2e-5), and the friction falling with sliding past SRR 0.1
/// as an Eyring film's does at a stress far past tau_0 (tau ~ tau_0 asinh(eta u_s / (tau_0
/// h)) grows only logarithmically with the sliding speed while the heat it makes thins the
/// oil: measured 0.0278 at SRR 0.1, 0.0201 at 0.5). And the scan's line on Barus's law
/// (beta = 0.03 /K) at SRR 0.3, whose Reynolds solve failed at its 17th outer iteration before
/// a polish was due, settles when that failure is handed to the coupled Newton method
/// (measured: 19 outer iterations, balance 6e-5, f 0.0580). ~3 s.
#[test]
fn eyring_lines_far_past_the_eyring_stress_settle() {
    let text = format!(
        "{}{SCAN_OIL}{OIL}",
        r#"title = "an Eyring line at 1 GPa"
kind = "ehl"

[body1]
shape = "roller"
radius = 0.02
length = inf
youngs_modulus = 206e9
poisson_ratio = 0.3

[body2]
shape = "roller"
radius = 0.02
length = inf
youngs_modulus = 206e9
poisson_ratio = 0.3

[load]
max_hertz_pressure = 1.0e9

[motion]
entrainment_speed = 5.0
slide_to_roll = 0.1

[grid]
nx = 256
ny = 1
x_min = -4.0
x_max = 1.5

"#
    );
    let mut friction = Vec::new();
    for srr in ["0.1", "0.5"] {
        let c = parse_str(
            &text,
            "eyring_line.toml",
            &[format!("motion.slide_to_roll={srr}")],
        )
        .unwrap();
        let s = solve(&c);
        assert!(s.summary.converged, "SRR {srr}: {}", s.summary.termination);
        let balance = s
            .summary
            .energy_balance_error
            .expect("a thermal run states its energy balance");
        assert!(
            balance.abs() < 0.01,
            "SRR {srr}: energy balance {balance:e}"
        );
        // (settled by the coupled Newton method: the fixed point alone wanders here)
        assert!(
            s.summary.thermal_newton_steps.is_some_and(|n| n > 0),
            "SRR {srr}: {:?}",
            s.summary.thermal_newton_steps
        );
        friction.push(
            s.summary
                .friction_coefficient
                .expect("a friction coefficient"),
        );
    }
    assert!(
        friction[0] > friction[1] && friction[1] > 0.0,
        "friction {friction:?}"
    );
    let barus = text.replace("viscosity_temperature = 1.1", "viscosity_beta = 0.03");
    assert_ne!(barus, text);
    let c = parse_str(
        &barus,
        "eyring_barus_line.toml",
        &[
            "lubricant.viscosity_model=\"barus\"".to_string(),
            "motion.slide_to_roll=0.3".to_string(),
        ],
    )
    .unwrap();
    let s = solve(&c);
    assert!(s.summary.converged, "Barus: {}", s.summary.termination);
    let balance = s.summary.energy_balance_error.unwrap();
    assert!(balance.abs() < 0.01, "Barus: energy balance {balance:e}");
    assert!(s.summary.thermal_newton_steps.is_some_and(|n| n > 0));
}

/// The fixed point stops within the tolerance it states: on the Roelands-Carreau example line
/// (`ehl_thermal_line.toml`: 512 cells, SRR 0.3) at its own speed (L = 0.75) and at
/// U = 2.2e-10 (L = 6.8), the default stop (0.05 K, films and the Reynolds factors' residual
/// 1e-4) against a tightly converged run (0.002 K, 1e-6, up to 400 outer iterations): central
/// and minimum film and friction within the film tolerance, 1e-4. Measured 1.5e-6 and 1.2e-5
/// on the central film. The stop before the factors' residual (an estimate from the change
/// between outer iterations) left them 1.1e-4 and 5.2e-4 off. ~8 s.
#[test]
fn the_thermal_fixed_point_stops_within_its_tolerance() {
    for speed in ["7.3e-11", "2.2e-10"] {
        let run = |extra: &[&str]| {
            let mut sets = vec![
                "motion.slide_to_roll=0.3".to_string(),
                format!("motion.dimensionless_speed={speed}"),
            ];
            sets.extend(extra.iter().map(|s| s.to_string()));
            let s = solve(&parse_str(THERMAL, "ehl_thermal_line.toml", &sets).unwrap());
            assert!(
                s.summary.converged,
                "U {speed} {extra:?}: {}",
                s.summary.termination
            );
            s.summary
        };
        let d = run(&[]);
        let t = run(&[
            "thermal.tolerance=0.002",
            "thermal.film_tolerance=1e-6",
            "thermal.max_iterations=400",
        ]);
        assert_within_film_tolerance(&format!("U {speed}"), &d, &t);
    }
}

/// The central and minimum film and the friction coefficient of `d` (a run to the default
/// stop) within the film tolerance, 1e-4 relative, of `t` (the same run converged tightly).
fn assert_within_film_tolerance(label: &str, d: &Summary, t: &Summary) {
    for (name, a, b) in [
        ("central film", d.central_film_m, t.central_film_m),
        ("minimum film", d.min_film_m, t.min_film_m),
        ("friction", d.friction_coefficient, t.friction_coefficient),
    ] {
        let (a, b) = (a.unwrap(), b.unwrap());
        assert!(
            (a / b - 1.0).abs() < 1e-4,
            "{label}: {name}: default {a:.7e}, tight {b:.7e}"
        );
    }
}

/// (h_thermal / h_isothermal, L, Murch-Wilson, Gupta) at the dimensionless speed `u`.
/// The Grubin inlet's h_thermal / h_isothermal (`reference::thermal::grubin_thermal_ratio`)
/// for the line contact `c` at its thermal loading: W, U and G from the case (W = w / (E' R),
/// U = eta0 u_e / (E' R), G = alpha E'); `x_heat` as there.
fn grubin_for(c: &Case, x_heat: Option<f64>) -> f64 {
    let (e, r) = (c.reduced_modulus(), c.reduced_radius());
    let lub = c.lubricant.as_ref().unwrap();
    let u = lub.viscosity * c.motion.as_ref().unwrap().entrainment_speed / (e * r);
    ehl::reference::thermal::grubin_thermal_ratio(
        c.load.force_per_length / (e * r),
        u,
        lub.pressure_viscosity_coefficient * e,
        ehl::reference::check::case_thermal_loading(c).unwrap(),
        x_heat,
    )
}

fn reduction(u: f64, nx: usize) -> (f64, f64, f64, f64, Case) {
    let sets = [
        NEWTONIAN.to_string(),
        "motion.slide_to_roll=0.0".to_string(),
        format!("motion.dimensionless_speed={u:e}"),
        "lubricant.viscosity_model=\"barus\"".to_string(),
        format!("grid.nx={nx}"),
    ];
    let sets: Vec<&str> = sets.iter().map(|s| s.as_str()).collect();
    let iso = solve(&case("", &sets));
    let c = case("[thermal]\nviscosity_beta = 0.03\n", &sets);
    let th = solve(&c);
    assert!(
        iso.summary.converged && th.summary.converged,
        "{}",
        th.summary.termination
    );
    let l = ehl::reference::check::case_thermal_loading(&c).unwrap();
    let ph_e = iso.summary.hertz_pressure_pa / c.reduced_modulus();
    (
        th.summary.central_film_m.unwrap() / iso.summary.central_film_m.unwrap(),
        l,
        ehl::reference::thermal::murch_wilson(l),
        ehl::reference::thermal::gupta(l, 0.0, ph_e),
        c,
    )
}

/// In pure rolling the thermal film is thinner than the isothermal one, more so as L grows,
/// as Murch & Wilson's and Gupta et al.'s factors say. **Known disagreement**, decomposed in
/// docs/thermal.md: our reduction 1 - h_t/h_i is 0.50 and 0.66 of the two fits' mean at L = 0.13
/// and 0.55. It does not change with the inlet extent, the points across the film or the grid.
/// A study (not in the suite) finds:
/// * our local flow factor is within 1 % of the exact local thermal Poiseuille solution;
/// * the fits' thermal Reynolds factor overstates it by ~50 %;
/// * a Grubin inlet with the exact factor gives half of Murch-Wilson's reduction (now
///   `reference::thermal::grubin_thermal_ratio`: `film_reduction_against_a_thermal_grubin_inlet`).
///
/// At L = 5.0 and 9.95 (U = 2.2e-10 and 3.1e-10, where the runs are solved again with 11
/// points across the film) it is 0.81 of the fits' mean at both.
///
/// The bounds below record the present state: 0.45..1.1 of the fits' mean. A closer agreement
/// keeps the test passing; losing half of the present reduction fails it. At L = 0.13 and
/// 0.55, where the Grubin inlet is checked against our solver under its own assumptions, the
/// reduction must also be at least 0.75 of that Grubin's (heated for x > -2 b): under those
/// assumptions ours is within a quarter of it (`film_reduction_against_a_thermal_grubin_inlet`),
/// and the physics added here (compression, expansion, warming surfaces) adds reduction
/// (measured 3.7 % and 10.5 % against 2.2 % and 7.4 %).
#[test]
fn film_reduction_against_the_inlet_heating_fits() {
    let all: Vec<_> = [3.6e-11, 7.3e-11, 2.2e-10, 3.1e-10]
        .iter()
        .map(|&u| reduction(u, 256))
        .collect();
    for (r, l, _, _, c) in all.iter().take(2) {
        let grubin = grubin_for(c, Some(-2.0));
        assert!(
            1.0 - r >= 0.75 * (1.0 - grubin),
            "L {l:.3}: reduction {:.4} against the Grubin inlet's {:.4}",
            1.0 - r,
            1.0 - grubin
        );
    }
    for w in all.windows(2) {
        let ((r1, l1, ..), (r2, l2, ..)) = (&w[0], &w[1]);
        assert!(
            l1 < l2 && r2 < r1 && *r1 < 1.0,
            "L {l1:.3} {l2:.3}: h_t/h_i {r1:.4} {r2:.4}"
        );
    }
    for (r, l, mw, gu, _) in all {
        let ratio = (1.0 - r) / (1.0 - 0.5 * (mw + gu));
        assert!(
            (0.45..1.1).contains(&ratio),
            "L {l:.3}: reduction {:.4} is {ratio:.2} of the fits' mean (MW {mw:.4}, Gupta {gu:.4})",
            1.0 - r
        );
    }
}

/// Our solver under the Grubin reference's own assumptions (no thermal expansion, bodies at T0
/// through conductivities 1e9 W/(m K); pure rolling, Newtonian, Barus, beta = 0.03 1/K, 256
/// cells) against `reference::thermal::grubin_thermal_ratio` heated for x > -2b (a Grubin inlet,
/// rigid Hertzian gap, exact local conduction-only Poiseuille factor), at L = 0.134 and 0.552.
/// Measured: ours 0.9805 and 0.9307, the reference 0.9781 and 0.9264 (heated everywhere:
/// 0.9754 and 0.9117). What parts them: convection, which carries the far inlet's (x < -2b)
/// heat downstream only weakly (film Peclet number ~100) and which the local column lacks
/// altogether (the heated-everywhere Grubin is the thinner by 1.7 % at L = 0.552), and Grubin's
/// idealisation (rigid Hertzian gap, infinite pressure at -b, incompressible). The tolerance,
/// 0.25 of the reference's reduction 1 - h_t/h_i (0.0055 and 0.018 in the ratio), covers the
/// measured 0.0024 and 0.0043 (our reduction 11 % and 6 % smaller than the reference's) and
/// fails if our reduction moves by a quarter from that of the local model.
#[test]
fn film_reduction_against_a_thermal_grubin_inlet() {
    for u in [3.6e-11, 7.3e-11] {
        let sets = [
            NEWTONIAN.to_string(),
            "motion.slide_to_roll=0.0".to_string(),
            format!("motion.dimensionless_speed={u:e}"),
            "lubricant.viscosity_model=\"barus\"".to_string(),
            "body1.conductivity=1e9".to_string(),
            "body2.conductivity=1e9".to_string(),
        ];
        let sets: Vec<&str> = sets.iter().map(|s| s.as_str()).collect();
        let iso = solve(&case("", &sets));
        let c = case(
            "[thermal]\nviscosity_beta = 0.03\nthermal_expansion = 0.0\n",
            &sets,
        );
        let th = solve(&c);
        assert!(
            iso.summary.converged && th.summary.converged,
            "{}",
            th.summary.termination
        );
        let ours = th.summary.central_film_m.unwrap() / iso.summary.central_film_m.unwrap();
        let l = ehl::reference::check::case_thermal_loading(&c).unwrap();
        let grubin = grubin_for(&c, Some(-2.0));
        println!("L {l:.4}: ours {ours:.4}, Grubin heated for x > -2b {grubin:.4}");
        assert!(
            (ours - grubin).abs() < 0.25 * (1.0 - grubin),
            "L {l:.3}: ours {ours:.4} vs Grubin (x > -2b) {grubin:.4}"
        );
    }
}

/// A conductivity growing with pressure (`thermal.conductivity_pressure = [1.7e-9, 0.5e-9]`
/// 1/Pa, 2.1 times k0 at the 0.99 GPa maximum) on the Table 3.7 line at SRR 0.3 (256 cells).
/// In the Hertz zone the film conducts its heat across to the walls, so its excess over the
/// walls' mean scales as the heating over the conductivity: the excess at the pressure maximum
/// must fall by k0 / k(p) times the rise of the heating, taken as the friction's (the cooler
/// film is more viscous). Within 10 %: the local heating at the maximum need not follow the
/// friction integral exactly, and convection carries a part (measured 3.3 %: 51.5 to 32.6 K
/// against 33.7 K predicted). The energy balance still closes (1e-3).
#[test]
fn a_conductivity_growing_with_pressure_cools_the_film_as_conduction_says() {
    let run = |extra: &[&str]| {
        let mut sets = vec!["grid.nx=256".to_string()];
        sets.extend(extra.iter().map(|s| s.to_string()));
        let s = solve(&parse_str(THERMAL, "ehl_thermal_line.toml", &sets).unwrap());
        assert!(s.summary.converged, "{}", s.summary.termination);
        let err = s.summary.energy_balance_error.unwrap();
        assert!(err.abs() < 1e-3, "energy balance {err}");
        let p = &s.fields.pressure;
        let i = (0..p.len()).fold(0, |m, k| if p[k] > p[m] { k } else { m });
        let t = s.temperature.as_ref().unwrap();
        let nx = p.len();
        let top = (0..t.nz)
            .map(|z| t.film_section[z * nx + i])
            .fold(f64::NEG_INFINITY, f64::max);
        let excess = top - 0.5 * (t.surface_1[i] + t.surface_2[i]);
        (excess, s.summary.friction_coefficient.unwrap(), p[i])
    };
    let (e0, f0, _) = run(&[]);
    let (e1, f1, pmax) = run(&["thermal.conductivity_pressure=[1.7e-9, 0.5e-9]"]);
    let k_ratio = 1.0 + 1.7e-9 * pmax / (1.0 + 0.5e-9 * pmax);
    let predicted = e0 * (f1 / f0) / k_ratio;
    println!(
        "excess at the pressure maximum: {e0:.2} K with k0, {e1:.2} K with k(p) = {k_ratio:.3} k0, \
         predicted {predicted:.2} K (friction {f0:.5} -> {f1:.5})"
    );
    assert!(e1 < e0 / 1.3, "the film must cool: {e0} -> {e1} K");
    assert!(
        (e1 - predicted).abs() < 0.1 * predicted,
        "{e1} K against {predicted} K"
    );
}

/// The side flow (v dT/dy) on the thesis roller, 128 x 64 cells, SRR 0.3, with and without it
/// (`thermal.side_flow`). The side flow runs out through the roller ends and vanishes on the
/// centre line by symmetry, so:
/// * the centre rows' film temperature must not move (1e-3 K; measured 5e-5), the end rows'
///   must (more than 0.05 K; measured 0.23 K where the film rises by ~1 K);
/// * the oil leaving through the ends carries enthalpy out: the heat convected grows (measured
///   0.3456 -> 0.3491 W), by less than c x the side leakage x the end rows' largest mid-film
///   rise (1.5 W), which no oil leaving there can exceed: a physical ceiling, not a
///   tolerance (most of the leakage leaves from the cool inlet); the energy balance below is
///   the close check;
/// * the contact's energy balance still closes (1 %; measured 1.5e-4).
///
/// Without the side flow wired into the contact, the first two fail.
#[test]
fn the_side_flow_moves_heat_at_the_roller_ends_only() {
    let file = "ehl_thesis_ch2_roller.toml";
    let text = format!("{}\n{OIL}", example(file));
    let run = |side: bool| {
        let sets: Vec<String> = [
            "grid.nx=128",
            "grid.ny=64",
            "motion.slide_to_roll=0.3",
            &format!("thermal.side_flow={side}"),
        ]
        .iter()
        .map(|s| s.to_string())
        .collect();
        let s = solve(&parse_str(&text, file, &sets).unwrap());
        settled(&s, &format!("side flow {side}"));
        s
    };
    let (with, without) = (run(true), run(false));
    let (a, b) = (
        &with.temperature.as_ref().unwrap().mid_film,
        &without.temperature.as_ref().unwrap().mid_film,
    );
    let (nx, ny) = (128, 64);
    let row_change = |j: usize| {
        (0..nx)
            .map(|i| (a[j * nx + i] - b[j * nx + i]).abs())
            .filter(|d| d.is_finite())
            .fold(0.0f64, f64::max)
    };
    let centre = row_change(ny / 2 - 1).max(row_change(ny / 2));
    let ends = row_change(0).max(row_change(ny - 1));
    let (cw, co) = (
        with.summary.heat_convected_w.unwrap(),
        without.summary.heat_convected_w.unwrap(),
    );
    let leak = with.summary.side_leakage_kg_s.unwrap();
    // the oil leaving through the ends is at most as warm as the end rows' mid-film
    let end_rise = [0, ny - 1]
        .iter()
        .flat_map(|&j| (0..nx).map(move |i| a[j * nx + i] - 313.0))
        .filter(|d| d.is_finite())
        .fold(0.0f64, f64::max);
    let cp = parse_str(&text, file, &[])
        .unwrap()
        .thermal
        .unwrap()
        .lubricant
        .heat_capacity;
    let ceiling = cp * leak * end_rise;
    println!(
        "side flow: centre rows {centre:.1e} K, end rows {ends:.3} K; heat convected {co:.4} -> \
         {cw:.4} W (ceiling {ceiling:.2} W)"
    );
    assert!(centre < 1e-3, "centre rows moved by {centre} K");
    assert!(ends > 0.05, "end rows moved by {ends} K only");
    assert!(cw > co, "heat convected {co} -> {cw} W");
    assert!(cw - co < ceiling, "{co} -> {cw} W, ceiling {ceiling} W");
}

/// The film-body iteration of a finite roller (the thesis chapter 2 rollers, 64 x 256 cells,
/// SRR 0.3, the isothermal film held) with the side flow's lines swept along y in blocks
/// ([`ehl::thermal::contact::ContactOptions::sweep_lines`], 8 by default) and with every line
/// on its neighbours' last iterate (1, a Jacobi iteration), each started, as an outer
/// iteration is, from the film-body fixed point of a pressure 2 % lower. Both iterate to one
/// fixed point: after 25 film-body iterations their surface and mid-film temperatures agree
/// within 1e-4 K (the iterations' own stop, `surface_tol`, is 1e-3 K; measured 3e-11 K).
/// After 5 the swept one is at least 5 times nearer to it (measured 4.4e-4 against 5.2e-3 K;
/// after 8, 1.7e-5 against 7.2e-4 K: the lagged side flow's error contracts by ~0.55 a step,
/// the swept one's by ~0.35). Without the sweep (every block's lines on the last iterate) the
/// second check fails; with a sweep that took a neighbour's temperatures at the wrong cells or
/// rows, the first. (The side flow's coupling grows with 1/dy: on 64 rows it barely slows the
/// iteration.)
#[test]
fn the_side_flow_sweep_reaches_the_lagged_fixed_point_sooner() {
    let file = "ehl_thesis_ch2_roller.toml";
    let sets: Vec<String> = ["grid.nx=64", "grid.ny=256", "motion.slide_to_roll=0.3"]
        .iter()
        .map(|s| s.to_string())
        .collect();
    let iso = solve(&parse_str(&example(file), file, &sets).unwrap());
    let case = parse_str(&format!("{}\n{OIL}", example(file)), file, &sets).unwrap();
    let p = &iso.fields.pressure;
    let film = iso.fields.film.as_ref().unwrap();
    let active: Vec<bool> = film.iter().map(|h| h.is_finite() && *h > 0.0).collect();
    let h: Vec<f64> = film
        .iter()
        .zip(&active)
        .map(|(&h, &a)| if a { h } else { f64::INFINITY })
        .collect();
    // the temperatures after `iterations` film-body iterations with blocks of `block` lines,
    // from the film-body fixed point of a pressure 2 % lower (as an outer iteration starts
    // from the last one's temperatures)
    let lower: Vec<f64> = p.iter().map(|v| 0.98 * v).collect();
    let run = |block: usize, iterations: usize| {
        let mut c = ehl::run::thermal::contact_for(&case, iso.grid).unwrap();
        c.options.sweep_lines = block;
        c.options.surface_tol = 0.0;
        c.options.max_surface_iterations = 25;
        c.update(&lower, &h, &active, None).unwrap();
        c.options.max_surface_iterations = iterations;
        c.update(p, &h, &active, None).unwrap();
        c.fields(&h)
    };
    let gap = |a: &ehl::solution::TemperatureFields, b: &ehl::solution::TemperatureFields| {
        [
            (&a.surface_1, &b.surface_1),
            (&a.surface_2, &b.surface_2),
            (&a.mid_film, &b.mid_film),
        ]
        .iter()
        .flat_map(|(x, y)| x.iter().zip(y.iter()).map(|(u, v)| (u - v).abs()))
        .filter(|d| d.is_finite())
        .fold(0.0f64, f64::max)
    };
    let (swept, lagged) = (run(8, 25), run(1, 25));
    let apart = gap(&swept, &lagged);
    let (swept5, lagged5) = (run(8, 5), run(1, 5));
    let (e_swept, e_lagged) = (gap(&swept5, &swept), gap(&lagged5, &swept));
    println!(
        "fixed points apart by {apart:.1e} K; after 5 film-body iterations {e_swept:.1e} K \
         (swept) against {e_lagged:.1e} K (lagged)"
    );
    assert!(apart < 1e-4, "the two fixed points differ by {apart} K");
    assert!(
        e_swept < e_lagged / 5.0,
        "swept {e_swept} K against lagged {e_lagged} K"
    );
}

/// A finite roller (the thesis chapter 2 rollers, 128 x 64 cells, pure rolling) and a ball on
/// glass run thermally on 2D grids, the grid lines exchanging heat through the side flow
/// (v dT/dy): the exchanges cancel between lines up to the lag of one film iteration, so the
/// whole contact's balance holds within 1 % (measured 2.3e-4 and 2.8e-5). The film is
/// thinner than the isothermal one, by no more than Murch & Wilson's factor says (their
/// reduction being the larger, as on the line: docs/thermal.md): the roller (L = 0.085) 3.3 %
/// against 5.2 %, the ball (L ~ 1e-4) ~0.
#[test]
fn finite_roller_and_ball_run_thermally() {
    for (file, sets) in [
        ("ehl_thesis_ch2_roller.toml", ["grid.nx=128", "grid.ny=64"]),
        ("ehl_ball_on_glass.toml", ["grid.nx=64", "grid.ny=64"]),
    ] {
        let text = example(file);
        let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
        let iso = solve(&parse_str(&text, file, &sets).unwrap());
        let th = solve(&parse_str(&format!("{text}\n[thermal]\n"), file, &sets).unwrap());
        let m = &th.summary;
        assert!(m.converged, "{file}: {}", m.termination);
        let err = m.energy_balance_error.unwrap();
        println!("{file}: energy balance {err:.1e}");
        assert!(err.abs() < 1e-2, "{file}: energy balance {err}");
        let r = m.central_film_m.unwrap() / iso.summary.central_film_m.unwrap();
        let c = parse_str(&format!("{text}\n[thermal]\n"), file, &sets).unwrap();
        let (lub, mo, tl) = (
            c.lubricant.unwrap(),
            c.motion.unwrap(),
            c.thermal.unwrap().lubricant,
        );
        let l = ehl::reference::thermal::thermal_loading(
            lub.viscosity,
            tl.viscosity_temperature.beta,
            mo.entrainment_speed,
            tl.conductivity,
        );
        let mw = ehl::reference::thermal::murch_wilson(l);
        assert!(
            r <= 1.0 + 1e-6 && 1.0 - r <= 1.0 - mw + 1e-4,
            "{file}: L {l:.3e}: thermal / isothermal central film {r}, Murch-Wilson {mw}"
        );
        assert!(th.temperature.is_some());
    }
}

/// A weak coupling settles as soon as its outer map allows: the thesis chapter 2 rollers in
/// pure rolling with the examples' thermal table (`OIL`), 256 x 128 cells, where the
/// temperatures rise by ~1.7 K and the factors' residual falls 8.4e-2 -> 2.2e-2 -> 6.6e-4 ->
/// 4.0e-5 against its 1e-4 stop (6.4e-4 and 3.6e-5 on 2026-12-05, ninth session, with the 2D
/// contacts' outer Reynolds solves to a tenth of the residual: 6 Newton steps). Each update's
/// film iteration stops at 0.1 K per unit of the residual it is expected to leave
/// (`film_stop`): with the stop taken from the last residual,
/// the third update ran its film to 2.2e-3 K, whose own error held the fourth residual at
/// 1.27e-4 and cost a fifth update and a fourth Reynolds solve (measured 2026-12-05; a thin
/// margin: the test guards against the film's own error coming back, not a wide gap). So at
/// most 4 outer iterations; and the film and friction it stops at lie within the film
/// tolerance (1e-4) of a run to a 1e-7 factors' stop (measured 1.6e-6 central, 1.9e-6
/// minimum, 4e-6 friction; on 2026-12-05, eighth session, 1.7e-7, 2.2e-6 and 3.7e-7, ninth
/// 1.5e-7, 2.1e-6 and 2.3e-7: a loose guard on the stop's accuracy).
#[test]
fn a_weakly_coupled_roller_settles_at_its_fourth_update() {
    let file = "ehl_thesis_ch2_roller.toml";
    let text = format!("{}\n{OIL}", example(file));
    let sets = ["grid.nx=256", "grid.ny=128"];
    settles_within_outer(&text, file, &sets, 4, "roller 256 x 128");
}

/// The glass-disc ball example (`ehl_thermal_ball.toml`, 129^2) settles at its third update:
/// its factors' residuals fall 0.16 -> 5.2e-3 -> 5.4e-5, so after the second the next is
/// expected at 1.6e-4, within 3 times the 1e-4 stop, and that outer iteration's Reynolds solve
/// goes to the case's tolerance (`ehl::thermal`'s `near_end`); its third update, after cells
/// solved for the first time at the second, changed the film temperatures by 1.0e-3 K, which
/// the residuals' ratio (0.01) estimates, not 0.99 (a fourth update). Before 2026-12-05 (eighth
/// session) it took 4. And what it stops at lies within the film tolerance (1e-4) of a run to a
/// 1e-7 factors' stop (measured 3.3e-6 central, 6.2e-6 minimum film, 1.4e-5 friction; the
/// tight run 11 outer iterations). ~2 s.
#[test]
fn the_ball_example_settles_at_its_third_update() {
    let file = "ehl_thermal_ball.toml";
    let text = include_str!("../../../examples/ehl_thermal_ball.toml");
    settles_within_outer(text, file, &[], 3, "ball example");
}

/// The case `text` (named `file`) with `sets` settles in at most `most` outer iterations, and
/// its central and minimum film and friction lie within the film tolerance (1e-4) of the same
/// case run to a 1e-7 factors' stop and 1e-5 K (`label` names it in the messages).
fn settles_within_outer(text: &str, file: &str, sets: &[&str], most: usize, label: &str) {
    let run = |extra: &[&str]| {
        let all: Vec<String> = sets.iter().chain(extra).map(|s| s.to_string()).collect();
        let s = solve(&parse_str(text, file, &all).unwrap());
        assert!(
            s.summary.converged,
            "{label} {extra:?}: {}",
            s.summary.termination
        );
        s.summary
    };
    let d = run(&[]);
    let outer = d.thermal_iterations.unwrap();
    assert!(outer <= most, "{label}: {outer} outer iterations");
    assert_time_split(label, &d, Some(false));
    let t = run(&["thermal.film_tolerance=1e-7", "thermal.tolerance=1e-5"]);
    println!(
        "{label}: {outer} outer (tight {}): central {:.2e}, minimum {:.2e}, friction {:.2e}",
        t.thermal_iterations.unwrap(),
        d.central_film_m.unwrap() / t.central_film_m.unwrap() - 1.0,
        d.min_film_m.unwrap() / t.min_film_m.unwrap() - 1.0,
        d.friction_coefficient.unwrap() / t.friction_coefficient.unwrap() - 1.0,
    );
    assert_within_film_tolerance(label, &d, &t);
}

/// The summary's `thermal_time` of a converged run: every phase finite, the film's energy
/// equation, the bodies, the Reynolds factors and solves and the isothermal start each took
/// time, the coupled Newton method took time exactly where `polished` says a polish was tried
/// (None: not known, as for a transient run, whose summary counts no polish), and the rest of
/// the fixed point is not negative: the phases are disjoint spans of it, and a phase counted
/// twice (such as the updates inside a coupled Newton polish counted as film time as well)
/// would leave a negative rest. The start and the phases, disjoint spans of the run, add up to
/// no more than its `wall_time_s`.
fn assert_time_split(label: &str, s: &Summary, polished: Option<bool>) {
    let t = s.thermal_time.expect("thermal_time");
    let phases = [
        t.isothermal_start_s,
        t.film_energy_s,
        t.body_temperature_s,
        t.reynolds_factors_s,
        t.reynolds_s,
        t.coupled_newton_s,
    ];
    assert!(
        phases.iter().all(|v| v.is_finite() && *v >= 0.0) && t.other_s.is_finite(),
        "{label}: {t:?}"
    );
    assert!(
        phases[..5].iter().all(|v| *v > 0.0),
        "{label}: a phase without time: {t:?}"
    );
    if let Some(polished) = polished {
        assert_eq!(t.coupled_newton_s > 0.0, polished, "{label}: {t:?}");
    }
    assert!(t.other_s >= 0.0, "{label}: a phase counted twice: {t:?}");
    let sum = phases.iter().sum::<f64>() + t.other_s;
    assert!(
        sum <= s.wall_time_s,
        "{label}: phases {sum} s of {} s: {t:?}",
        s.wall_time_s
    );
}

/// The EHL-FBNS ball (0.09 m/s, 0.2 um film) with sliding, 64 x 64 cells. Its bodies are slow
/// and its film thin: the film's conductance k_f / h is ~70 times the bodies' under the
/// contact, and the plain film-body iteration (each surface taking the bodies' response to
/// the film's last fluxes) oscillated with growing amplitude: at SRR 0.05, 0.5 and 1 the
/// surface temperatures ran to -150 degC and the run failed. With the film's conduction in the
/// surface update (`ThermalContact::update_surfaces`) it must converge, and:
/// * the contact's energy balance closes within 1e-3 (measured 1e-5);
/// * the temperatures are symmetric about y = 0 (the contact is; the side flow's upwinding
///   follows the sign of v): 1e-6 of the largest rise;
/// * the heat generated is the sliding work F (u1 - u2) plus what pure rolling dissipates
///   (the pressure flow's work, taken from the SRR 0 run): the shear heating integrated
///   across the film is the surfaces' traction work less the pressure work. Within 3 % of the
///   heat (measured 1.2 % and 0.7 %): the rolling part is taken from another run, whose film
///   and viscosity differ by the heating.
#[test]
fn a_slow_ball_with_sliding_runs_thermally() {
    let file = "ehl_ball_on_glass.toml";
    let text = format!("{}\n{OIL}", example(file));
    let run = |srr: f64| {
        let sets = vec![
            "grid.nx=64".to_string(),
            "grid.ny=64".to_string(),
            format!("motion.slide_to_roll={srr}"),
        ];
        let c = parse_str(&text, file, &sets).unwrap();
        let ue = c.motion.as_ref().unwrap().entrainment_speed;
        let s = solve(&c);
        assert!(s.summary.converged, "SRR {srr}: {}", s.summary.termination);
        let err = s.summary.energy_balance_error.unwrap();
        assert!(err.abs() < 1e-3, "SRR {srr}: energy balance {err}");
        let t = s.temperature.as_ref().unwrap();
        let (nx, ny) = (64, 64);
        let t0 = 313.0;
        let top = t
            .max_film
            .iter()
            .filter(|v| v.is_finite())
            .fold(0.0f64, |m, v| m.max(v - t0));
        for field in [&t.mid_film, &t.surface_1, &t.surface_2] {
            for j in 0..ny / 2 {
                for i in 0..nx {
                    let (a, b) = (field[j * nx + i], field[(ny - 1 - j) * nx + i]);
                    if a.is_finite() || b.is_finite() {
                        assert!(
                            (a - b).abs() <= 1e-6 * top,
                            "SRR {srr}: row {j} cell {i}: {a} against {b} (rise {top})"
                        );
                    }
                }
            }
        }
        let sliding = s.summary.friction_force_n.unwrap() * ue * srr;
        let heat = s.summary.heat_generated_w.unwrap();
        println!("SRR {srr}: heat {heat:.4e} W, sliding work {sliding:.4e} W, rise {top:.3} K, balance {err:.1e}");
        (heat, sliding)
    };
    let (rolling, _) = run(0.0);
    for srr in [0.5, 1.0] {
        let (heat, sliding) = run(srr);
        assert!(
            (heat - sliding - rolling).abs() < 0.03 * heat,
            "SRR {srr}: heat {heat} W, sliding work {sliding} W + rolling {rolling} W"
        );
    }
}

/// Asserts that a thermal solution converged and that its energy balance closes within the
/// 1 % issue 13 asks of every converged solution; returns the balance (relative).
fn settled(s: &Solution, what: &str) -> f64 {
    let m = &s.summary;
    assert!(m.converged, "{what}: {}", m.termination);
    let err = m.energy_balance_error.unwrap();
    assert!(err.abs() < 1e-2, "{what}: energy balance {err}");
    err
}

/// The glass-disc ball example (`ehl_thermal_ball.toml`) on an n x n grid at the entrainment
/// speed `u` (m/s) and slide-to-roll ratio `srr`, with `oil` (a `lubricant.rheology` value)
/// in place of its Newtonian oil when given.
fn glass_disc_ball(n: usize, u: f64, srr: f64, oil: Option<&str>) -> Solution {
    let mut sets = vec![
        format!("grid.nx={n}"),
        format!("grid.ny={n}"),
        format!("motion.entrainment_speed={u}"),
        format!("motion.slide_to_roll={srr}"),
    ];
    sets.extend(oil.map(|o| format!("lubricant.rheology={o}")));
    let text = include_str!("../../../examples/ehl_thermal_ball.toml");
    solve(&parse_str(text, "ehl_thermal_ball.toml", &sets).unwrap())
}

/// Carreau with a limiting shear stress (thesis Table 3.7's G and n at 313 K, Lambda = 0.07).
const CARREAU_LIMITED: &str = "{ model = \"carreau\", shear_modulus = 4.5e6, power_law_index = 0.57, limiting_shear_coefficient = 0.07 }";

/// The glass-disc ball example at 1 m/s with a shear-thinning oil and a limiting shear stress
/// (Carreau, Lambda = 0.07), SRR 0.5, 1 and 1.5, and at 3 m/s, SRR 1, 64^2 cells: each settles,
/// its energy balance within the issue's 1 % (measured 2.3e-4 to 3.5e-4 at 1 m/s, 1.4e-3 at
/// 3 m/s on this coarse grid). At 1 m/s and SRR 1 the flow factors of a few columns whose
/// pressure-flow stress range came near the limit cycled by 0.15 (log) for 80 outer
/// iterations, the limit switching on and off at the threshold; it is now phased in
/// (`film_energy::line_coefficients`). At 3 m/s the surfaces oscillated until the film-body
/// update took the heating's temperature slope into account (`update_surfaces`). All of them
/// failed outright before the film-body update (ab4e2b5).
#[test]
fn a_faster_ball_with_a_limiting_shear_stress_settles() {
    for (u, srr) in [(1.0, 0.5), (1.0, 1.0), (1.0, 1.5), (3.0, 1.0)] {
        let s = glass_disc_ball(64, u, srr, Some(CARREAU_LIMITED));
        let err = settled(&s, &format!("{u} m/s, SRR {srr}"));
        println!(
            "u_e {u} m/s, SRR {srr}: f {:.4}, outer iterations {}, balance {err:.1e}",
            s.summary.friction_coefficient.unwrap(),
            s.summary.thermal_iterations.unwrap()
        );
    }
}

/// Fast sliding on the glass-disc ball example (64^2 cells), the cases that failed before the
/// film-body update took the film's own answer to its surfaces (`film_energy::wall_response`)
/// and the film iteration its heating's fall with temperature (`LineOptions::
/// linearise_heating`): the disc at rest (SRR 2) at 1 m/s with the example's Newtonian oil and
/// with Carreau and a limiting shear stress, the Newtonian oil at 3 m/s (SRR 1; its isothermal
/// friction coefficient is 0.19) and the Carreau oil at 3 m/s, SRR 1.5. Each settles with its
/// energy balance within the issue's 1 % (measured 1.5e-3 at most), and:
/// * with the disc at rest, the heat goes into the moving steel ball, not the glass (the
///   steel at 2 m/s takes it away far faster than a glass disc at rest conducts it: measured
///   98.6 % of the heat into the ball); the glass surface is the hotter one;
/// * the Newtonian oil at 3 m/s heats until its friction falls far below the isothermal
///   0.19 (measured 0.014): a thermal friction below 0.05 is asked.
#[test]
fn a_fast_sliding_ball_settles_with_either_oil() {
    for (u, srr, oil) in [
        (1.0, 2.0, None),
        (1.0, 2.0, Some(CARREAU_LIMITED)),
        (3.0, 1.0, None),
        (3.0, 1.5, Some(CARREAU_LIMITED)),
    ] {
        let name = if oil.is_some() {
            "Carreau"
        } else {
            "Newtonian"
        };
        let s = glass_disc_ball(64, u, srr, oil);
        let err = settled(&s, &format!("{name}, {u} m/s, SRR {srr}"));
        let m = &s.summary;
        let f = m.friction_coefficient.unwrap();
        let bodies = m.heat_to_body_w.unwrap();
        let surfaces = m.max_surface_temperature_k.unwrap();
        println!(
            "{name}, u_e {u} m/s, SRR {srr}: f {f:.4}, outer iterations {}, balance {err:.1e}, \
             heat into ball / disc {:.3} / {:.3} W, hottest surfaces {:.1} / {:.1} K",
            m.thermal_iterations.unwrap(),
            bodies[0],
            bodies[1],
            surfaces[0],
            surfaces[1]
        );
        if srr == 2.0 {
            assert!(bodies[0] > 10.0 * bodies[1], "{name}: {bodies:?}");
            assert!(surfaces[1] > surfaces[0], "{name}: {surfaces:?}");
        }
        if oil.is_none() && u == 3.0 {
            assert!(f < 0.05, "{f}");
        }
    }
}

/// A steel ball on a steel flat under the Eyring law far past tau_0 (the robustness scan's ball
/// of docs/thermal.md: R = 12.7 mm, 30 N, p_h 0.77 GPa, 1 m/s, SRR 0.5, eta0 = 0.05 Pa s,
/// alpha = 20 /GPa, tau_0 = 5 MPa; 49^2 cells here, 97^2 in the scan). Its fixed point stalled:
/// the factors' residual, the largest of a few columns', stayed at one value for up to 5 outer
/// iterations in a row, because the Reynolds solve after each step of the factors found the
/// whole film's mass imbalance already within its loose tolerance, took no Newton step, and
/// left the next update the same pressure (measured before 2026-12-02: 39 outer iterations on
/// this grid, and unsettled after 80 on the scan's 97^2). Each solve now removes at least
/// 90 % of the imbalance the new factors leave, or down to the case's tolerance
/// (`ehl::thermal`, `REYNOLDS_REDUCTION`):
/// measured 11 outer iterations, the central film within 4e-8 and the friction within 5e-7 of
/// the stalled run's. Asked: settled, the energy balance within the issue's 1 %, and at most
/// 20 outer iterations (the stalled run's 39 fail it; twice the measured 11 leaves room for
/// another machine's rounding).
#[test]
fn an_eyring_ball_is_not_stalled_by_a_pressure_that_does_not_move() {
    let text = SCAN_BALL_CASE;
    let s = solve(&parse_str(text, "scan_ball.toml", &[]).unwrap());
    let err = settled(&s, "Eyring ball, SRR 0.5");
    let outer = s.summary.thermal_iterations.unwrap();
    println!(
        "outer iterations {outer}, balance {err:.1e}, f {:.4}, central film {:.4e} m",
        s.summary.friction_coefficient.unwrap(),
        s.summary.central_film_m.unwrap()
    );
    assert!(outer <= 20, "{outer} outer iterations");
}

/// The robustness scan's ball at 1 m/s and SRR 0.5 (see the test above), 49^2 cells, with
/// `SCAN_OIL`'s Eyring oil and `OIL`'s thermal table.
const SCAN_BALL_CASE: &str = include_str!("data/thermal_scan_ball.toml");

/// The scan's Eyring ball at 5 m/s (p_h 0.77 GPa, SRR 0.5, tau_0 = 5 MPa; docs/thermal.md,
/// "Robustness beyond the examples"): on the fixed point alone its outer map expands
/// (contraction estimates 1.3-5), and on 81^2 and the scan's 97^2 cells it was unsettled
/// after 80 outer iterations (measured 2026-12-02). A ball or finite roller slow at its 20th
/// outer iteration is handed to Newton's method on the coupled problem (`ehl::thermal_newton`,
/// the 2D coupled residual of `thermal::contact`): 81^2 then settles in 21 (the polish at the
/// 20th from a factors' residual of 0.71: 3 Newton steps, 41 GMRES iterations), 97^2 in 22.
/// Here 65^2 cells, where the fixed point alone still settles, slowly (52 outer iterations):
/// the polished run settles in 21 and lands on the same solution (measured: central film
/// within 3e-7, friction within 1e-9, the largest film temperature within 2.4e-4 K). Asked:
/// both settled with the energy balance within the issue's 1 %; the polished run in at most
/// 30 outer iterations with Newton steps counted (the fixed point alone takes 52, so the test
/// fails without the 2D polish); the two within what each run's stop leaves of its fixed
/// point, twice: the film 2e-4 (2 x 1e-4 of the film tolerance), the largest film
/// temperature 0.1 K (2 x 0.05 K), the friction 1e-3 (an Eyring stress far past tau_0 moves
/// as beta / ln(2 eta u_s / (tau_0 h)), ~6e-3 per K here, over 0.1 K). ~8 s.
#[test]
fn an_eyring_ball_whose_fixed_point_expands_settles_with_newton() {
    let text = SCAN_BALL_CASE;
    let run = |newton: bool| {
        let sets = [
            "grid.nx=65".to_string(),
            "grid.ny=65".to_string(),
            "motion.entrainment_speed=5.0".to_string(),
            format!("thermal.coupled_newton={newton}"),
        ];
        solve(&parse_str(text, "scan_ball.toml", &sets).unwrap())
    };
    let (a, b) = (run(true), run(false));
    settled(&a, "Eyring ball at 5 m/s, polished");
    settled(&b, "Eyring ball at 5 m/s, the fixed point alone");
    let (ma, mb) = (&a.summary, &b.summary);
    let outer = (
        ma.thermal_iterations.unwrap(),
        mb.thermal_iterations.unwrap(),
    );
    let film = ma.central_film_m.unwrap() / mb.central_film_m.unwrap() - 1.0;
    let f = ma.friction_coefficient.unwrap() / mb.friction_coefficient.unwrap() - 1.0;
    let t = ma.max_film_temperature_k.unwrap() - mb.max_film_temperature_k.unwrap();
    println!(
        "outer iterations {outer:?}, Newton steps {:?}: film {film:.1e}, friction {f:.1e}, \
         largest film temperature {t:.1e} K",
        ma.thermal_newton_steps
    );
    assert!(outer.0 <= 30, "{outer:?}");
    assert!(ma.thermal_newton_steps.unwrap() > 0);
    assert!(film.abs() < 2e-4 && f.abs() < 1e-3 && t.abs() < 0.1);
}

/// A steel ball at 10 m/s (the scan's ball, R = 12.7 mm, 30 N, p_h 0.77 GPa, eta0 = 0.05 Pa s,
/// alpha = 20 /GPa, Roelands, thermal expansion 6.5e-4 /K, here with a Newtonian oil; 97^2
/// cells). Its outlet carries a pressure spike (isothermal: 1.27 GPa), and the oil leaving it
/// expands and cools, as the compression work -(T / rho)(d rho / dT) u dp/dx says:
/// * pure rolling: the coldest film point on the centre line lies below the inlet temperature
///   (measured 274.7 K, 38 K below T0, at mid-film, x = 0.8 a), yet above
///   T_c exp(-eps p_max / (rho0 c)) with T_c the colder of T0 and the coldest wall (215 K
///   here). Below T0 this density law (Dowson-Higginson times 1 - eps (T - T0)) cools oil
///   that expands without losing heat at d ln T / dp = eps / (rho0 DH(p) c (1 - eps (T -
///   T0))^2), at most eps / (rho0 c); the oil's pressure falls by at most p_max while it is
///   below T0; walls no colder than T_c and the shear heating only add heat;
/// * SRR 0.3 settles (measured 22 outer iterations, balance 2.2e-4). Before expanding oil
///   took the smaller of its column's two pressure gradients in the compression work
///   (`film_energy::compression_gradient`) it did not: the film's own iteration left
///   residuals of 5-100 K at the cells leaving the spike, and after 80 outer iterations the
///   film's extent was still moving (checked: with the old gradient this test fails there;
///   docs/thermal.md, "Fast balls"). Pure rolling at 10 m/s settled before too.
///
/// Both: the energy balance within the issue's 1 %. ~10 s.
#[test]
fn a_fast_ball_cools_its_oil_leaving_the_spike_and_settles() {
    let sets = |srr: &str| {
        vec![
            "grid.nx=97".to_string(),
            "grid.ny=97".to_string(),
            "motion.entrainment_speed=10.0".to_string(),
            format!("motion.slide_to_roll={srr}"),
            "lubricant.rheology={model=\"newtonian\"}".to_string(),
        ]
    };
    let rolling = solve(&parse_str(SCAN_BALL_CASE, "scan_ball.toml", &sets("0.0")).unwrap());
    settled(&rolling, "ball at 10 m/s, pure rolling");
    let t = rolling.temperature.as_ref().unwrap();
    let coldest = t
        .film_section
        .iter()
        .cloned()
        .filter(|v| v.is_finite())
        .fold(f64::INFINITY, f64::min);
    let p_max = rolling.summary.max_pressure_pa;
    let (eps, rho0, c) = (6.5e-4, 870.0, 2000.0);
    let coldest_wall = t
        .surface_1
        .iter()
        .chain(&t.surface_2)
        .cloned()
        .filter(|v| v.is_finite())
        .fold(t.inlet, f64::min);
    let adiabatic = coldest_wall * (-eps * p_max / (rho0 * c)).exp();
    println!(
        "pure rolling: coldest film point on the centre line {coldest:.1} K (T0 {:.1} K, \
         coldest wall {coldest_wall:.2} K, bound {adiabatic:.1} K at p_max {:.3} GPa), {} outer \
         iterations",
        t.inlet,
        p_max / 1e9,
        rolling.summary.thermal_iterations.unwrap()
    );
    assert!(coldest < t.inlet - 10.0, "{coldest}");
    assert!(coldest > adiabatic, "{coldest} against {adiabatic}");
    let sliding = solve(&parse_str(SCAN_BALL_CASE, "scan_ball.toml", &sets("0.3")).unwrap());
    let err = settled(&sliding, "ball at 10 m/s, SRR 0.3");
    println!(
        "SRR 0.3: {} outer iterations, balance {err:.1e}, f {:.4}",
        sliding.summary.thermal_iterations.unwrap(),
        sliding.summary.friction_coefficient.unwrap()
    );
}

/// The same ball at 15 m/s in pure rolling (L = 3.4): its fixed point wanders (the factors'
/// residual 0.1-2, a cooled pocket at the side of the outlet spike) and is handed to Newton's
/// method on the coupled problem at its 20th outer iteration. Each polish reaches a solution
/// whose film extent, frozen in it, is one cell short there (the residual's cell moving
/// diagonally from (79, 42) to (83, 46)), and the update after it lowers the factors'
/// residual about tenfold (0.50, 3.5e-2, 4.2e-3, 4.3e-4, 2.0e-5). Polishes that make such
/// progress no longer count towards the three after which a contact goes back to the fixed
/// point (`PolishSchedule::seen`): it settles after the fourth (measured 24 outer
/// iterations). Before, it went back after the third, whose fixed point expands at that
/// solution, and was still moving after 80 outer iterations (checked: with the progress rule
/// off this test fails there).
///
/// At 20 m/s and SRR 0.3 (L = 6) the first polish, at the 20th outer iteration, starts from a
/// residual of 2.9 and fails. A finite contact whose polish failed was not polished again, and
/// this one's fixed point wandered at 0.6-2.3 to the 80th outer iteration; it is now polished
/// again 5 outer iterations after a failure, twice as long after each further one
/// (`POLISH_EVERY_FINITE`), and settles (measured 42 outer iterations; checked: unsettled
/// after 80 without the retries). Both: the energy balance within the issue's 1 %.
///
/// And the polished solution is a thermal film, not just a settled one: in pure rolling its
/// central film lies below the isothermal one (inlet heating thins it) and above the
/// isothermal one times Murch & Wilson's factor 1 / (1 + 0.254 L^0.62) (0.650 at L = 3.37):
/// our reduction is weaker than the classical fits' wherever we compared them (docs/thermal.md,
/// "Known disagreement": 0.8 of it on the line from L = 2.5 to 10). Measured 1.358 um against
/// 1.682 um isothermal, a ratio of 0.807. ~25 s.
#[test]
fn fast_balls_polished_towards_their_film_end_settle() {
    for (u, srr) in [("15.0", "0.0"), ("20.0", "0.3")] {
        let sets = [
            "grid.nx=97".to_string(),
            "grid.ny=97".to_string(),
            format!("motion.entrainment_speed={u}"),
            format!("motion.slide_to_roll={srr}"),
            "lubricant.rheology={model=\"newtonian\"}".to_string(),
        ];
        let case = parse_str(SCAN_BALL_CASE, "scan_ball.toml", &sets).unwrap();
        let s = solve(&case);
        let what = format!("ball at {u} m/s, SRR {srr}");
        let err = settled(&s, &what);
        let m = &s.summary;
        println!(
            "{what}: {} outer iterations, {} coupled Newton steps, balance {err:.1e}",
            m.thermal_iterations.unwrap(),
            m.thermal_newton_steps.unwrap()
        );
        assert!(m.thermal_newton_steps.unwrap() > 0, "{what}: not polished");
        if srr == "0.0" {
            let l = ehl::reference::check::case_thermal_loading(&case).unwrap();
            let mw = ehl::reference::thermal::murch_wilson(l);
            let mut iso_case = case.clone();
            iso_case.thermal = None;
            let iso = solve(&iso_case);
            assert!(iso.summary.converged, "{what}, isothermal");
            let r = m.central_film_m.unwrap() / iso.summary.central_film_m.unwrap();
            println!(
                "{what}: L {l:.2}, thermal / isothermal central film {r:.4}, Murch-Wilson {mw:.4}"
            );
            assert!(
                r < 1.0 && r > mw,
                "{what}: film ratio {r}, Murch-Wilson {mw}"
            );
        }
    }
}

/// The glass-disc ball example at 5 m/s with the disc at rest (SRR 2, L = 2.3, below the loading
/// above which `ehl check` adds a note), on the example's 129^2 grid. It ended "not settled" after
/// 80 outer iterations: the film had settled to 7.6e-9 of its thinnest, but one cell of the grid's
/// edge row held a pressure of 0 and 8-19 Pa on alternate outer iterations, its row's film ended
/// one cell later on every other one, and the Reynolds factors' residual cycled at 8-13e-4 there
/// against its 1e-4 stop. Past the cells the last update counted as pressurised, a cell now counts
/// only above 1e-6 of the peak (`thermal::contact::PRESSURISED_FRACTION`): measured 27 outer
/// iterations, energy balance -0.58 %. Asked: settled, the balance within the issue's 1 %, and, as
/// at 1 m/s (`a_fast_sliding_ball_settles_with_either_oil`), the heat into the moving steel ball,
/// not the glass at rest.
#[test]
fn a_fast_ball_on_a_glass_disc_at_rest_settles() {
    let s = glass_disc_ball(129, 5.0, 2.0, None);
    let err = settled(&s, "5 m/s, SRR 2");
    let m = &s.summary;
    let bodies = m.heat_to_body_w.unwrap();
    println!(
        "5 m/s, SRR 2: {} outer iterations, balance {err:.1e}, heat into ball / disc {:.3} / \
         {:.3} W",
        m.thermal_iterations.unwrap(),
        bodies[0],
        bodies[1]
    );
    assert!(bodies[0] > 10.0 * bodies[1], "{bodies:?}");
}

/// Swapping the surface speeds (SRR -> -SRR) of two identical bodies mirrors the thermal
/// problem across the film (z -> h - z): the films and the largest film temperature are the
/// same, and the two bodies exchange their surface temperatures and heat. The Table 3.7 line
/// (both rollers steel, R = 40 mm), 256 cells, SRR +-0.3 and +-1: measured within 9e-5 of a
/// film, 2e-3 K on the film's largest temperature and 0.034 K on the surfaces'. Asked: 5e-4
/// of a film, 0.1 K and 1e-3 of the heat. Each run stops within the outer iteration's
/// 0.05 K and 1e-4 of a film of its own fixed point (estimated from the contraction), so
/// two runs may differ by twice that. The friction coefficient is not mirrored (it is the
/// shear on one surface, whose rolling part keeps its sign), so it is not compared.
#[test]
fn swapping_the_surface_speeds_mirrors_the_thermal_solution() {
    for srr in [0.3, 1.0] {
        let run = |s: f64| {
            let sets = vec![
                "grid.nx=256".to_string(),
                format!("motion.slide_to_roll={s}"),
            ];
            solve(&parse_str(THERMAL, "ehl_thermal_line.toml", &sets).unwrap()).summary
        };
        let (a, b) = (run(srr), run(-srr));
        assert!(a.converged && b.converged, "SRR +-{srr}");
        let rel = |x: f64, y: f64| (x - y).abs() / x.abs();
        let (hc, hm) = (a.central_film_m.unwrap(), a.min_film_m.unwrap());
        assert!(
            rel(hc, b.central_film_m.unwrap()) < 5e-4,
            "SRR +-{srr}: central film"
        );
        assert!(
            rel(hm, b.min_film_m.unwrap()) < 5e-4,
            "SRR +-{srr}: minimum film"
        );
        let (ta, tb) = (
            a.max_film_temperature_k.unwrap(),
            b.max_film_temperature_k.unwrap(),
        );
        assert!((ta - tb).abs() < 0.1, "SRR +-{srr}: {ta} K against {tb} K");
        let (sa, sb) = (
            a.max_surface_temperature_k.unwrap(),
            b.max_surface_temperature_k.unwrap(),
        );
        let (qa, qb) = (a.heat_to_body_w.unwrap(), b.heat_to_body_w.unwrap());
        for k in 0..2 {
            assert!(
                (sa[k] - sb[1 - k]).abs() < 0.1,
                "SRR +-{srr}: surfaces {sa:?} against {sb:?}"
            );
            assert!(
                rel(qa[k], qb[1 - k]) < 1e-3,
                "SRR +-{srr}: heat {qa:?} against {qb:?}"
            );
        }
        // not a mirror of itself: the faster surface is the cooler one
        assert!((sa[0] - sa[1]).abs() > 1.0, "SRR {srr}: {sa:?}");
        println!(
            "SRR +-{srr}: central film {:.3e}, max film T {:.2e} K, surfaces {:.2e} / {:.2e} K apart",
            rel(hc, b.central_film_m.unwrap()),
            (ta - tb).abs(),
            (sa[0] - sb[1]).abs(),
            (sa[1] - sb[0]).abs()
        );
    }
}

/// A steel line (R = 20 mm rollers, 5 m/s) under a mineral oil (Roelands, alpha = 20 /GPa,
/// eta0 = 0.05 Pa s at 313 K) at p_h = 1 GPa, the robustness scan's line
/// (`docs/scripts/thermal_scan.py`).
const STEEL_LINE: &str = "title = \"1 GPa line\"\nkind = \"ehl\"\n\
    [body1]\nshape = \"roller\"\nradius = 0.02\nlength = inf\nyoungs_modulus = 206e9\npoisson_ratio = 0.3\n\
    [body2]\nshape = \"roller\"\nradius = 0.02\nlength = inf\nyoungs_modulus = 206e9\npoisson_ratio = 0.3\n\
    [load]\nmax_hertz_pressure = 1.0e9\n\
    [motion]\nentrainment_speed = 5.0\nslide_to_roll = 0.0\n\
    [lubricant]\nviscosity = 0.05\npressure_viscosity_coefficient = 2.0e-8\ndensity = 870.0\n\
    viscosity_model = \"roelands\"\ndensity_model = \"dowson-higginson\"\n\
    [grid]\nnx = 256\nny = 1\nx_min = -4.0\nx_max = 1.5\n\
    [solver]\ntolerance = 1e-6\nmax_iterations = 200\n\
    [thermal]\ninlet_temperature = 313.0\nviscosity_temperature = 1.1\nthermal_expansion = 6.5e-4\n\
    conductivity = 0.14\nheat_capacity = 2000.0\npoints_across_film = 7\n";

/// A line at p_h = 1 GPa and 5 m/s (R = 20 mm, steel, eta0 = 0.05 Pa s, alpha = 20 /GPa,
/// Roelands with S0 = 1.1; 256 cells, L = 0.37): its pressure spike is one or two cells wide.
/// Before the compression work capped its gradient (`film_energy::compression_gradient`),
/// the spike's cells ran hot or cold by hundreds of kelvin between outer iterations and these
/// runs ended with a failed temperature solve: the Newtonian oil at SRR 0.5 and Carreau
/// (G = 4.5 MPa, n = 0.57, Lambda = 0.06) at SRR -0.5, whose mirror +0.5 settled. Now each
/// settles, closes its energy balance within the 1 % of issue 13, and the Carreau pair is
/// one solution mirrored: the same films (5e-4, the order of the fixed point's film
/// tolerance of 1e-4 over its contraction) and the surfaces' temperatures and heat swapped
/// (0.1 K, 1e-3; as `swapping_the_surface_speeds_mirrors_the_thermal_solution`).
#[test]
fn a_line_at_one_gigapascal_settles_with_a_sharp_pressure_spike() {
    let base = STEEL_LINE;
    let carreau = "lubricant.rheology={model=\"carreau\",shear_modulus=4.5e6,power_law_index=0.57,limiting_shear_coefficient=0.06}";
    let run = |srr: f64, oil: Option<&str>| {
        let mut sets = vec![format!("motion.slide_to_roll={srr}")];
        sets.extend(oil.map(String::from));
        let s = solve(&parse_str(base, "line.toml", &sets).unwrap()).summary;
        assert!(s.converged, "SRR {srr}, {oil:?}: {}", s.termination);
        let balance = s.energy_balance_error.unwrap();
        assert!(
            balance.abs() < 0.01,
            "SRR {srr}, {oil:?}: balance {balance}"
        );
        s
    };
    run(0.5, None);
    let (a, b) = (run(0.5, Some(carreau)), run(-0.5, Some(carreau)));
    let rel = |x: f64, y: f64| (x - y).abs() / x.abs();
    for (x, y) in [
        (a.central_film_m, b.central_film_m),
        (a.min_film_m, b.min_film_m),
    ] {
        assert!(rel(x.unwrap(), y.unwrap()) < 5e-4, "{x:?} against {y:?}");
    }
    let (sa, sb) = (
        a.max_surface_temperature_k.unwrap(),
        b.max_surface_temperature_k.unwrap(),
    );
    let (qa, qb) = (a.heat_to_body_w.unwrap(), b.heat_to_body_w.unwrap());
    for k in 0..2 {
        assert!((sa[k] - sb[1 - k]).abs() < 0.1, "{sa:?} against {sb:?}");
        assert!(rel(qa[k], qb[1 - k]) < 1e-3, "{qa:?} against {qb:?}");
    }
}

/// The same line at 1.5 to 3 GPa with a Newtonian oil and sliding: the isothermal start's
/// shear heating is many orders above the solution's (6e12 W/m^2 into the surfaces at 1.5 GPa
/// and SRR 0.5), and the surfaces' first linearised update took one of them 128 K below the
/// inlet; the next film solve overflowed the viscosity law, the run was retried with 11
/// points across the film and failed again. The surfaces' update is now bounded by the film's
/// range and a margin (the maximum principle of the bodies' conduction,
/// `ThermalContact::update_surfaces`),
/// and each run settles with its 7 points (no retry, no warning), closes its energy balance
/// within the 1 % of issue 13 (the independent check: the heat generated against the heat
/// conducted into the bodies and convected out), both bodies take heat, and the film is far
/// above the inlet's 313 K.
#[test]
fn a_newtonian_line_sliding_at_high_pressure_settles_hot() {
    for (ph, srr) in [(1.5e9, 0.5), (3.0e9, 1.0)] {
        let sets = [
            format!("load.max_hertz_pressure={ph}"),
            format!("motion.slide_to_roll={srr}"),
        ];
        let s = solve(&parse_str(STEEL_LINE, "line.toml", &sets).unwrap()).summary;
        let what = format!("p_h {ph:e} Pa, SRR {srr}");
        assert!(s.converged, "{what}: {}", s.termination);
        assert!(s.warnings.is_empty(), "{what}: {:?}", s.warnings);
        let balance = s.energy_balance_error.unwrap();
        assert!(balance.abs() < 0.01, "{what}: balance {balance}");
        let film = s.max_film_temperature_k.unwrap();
        assert!(film > 450.0, "{what}: largest film temperature {film} K");
        let bodies = s.heat_to_body_w.unwrap();
        assert!(
            bodies.iter().all(|&q| q > 0.0),
            "{what}: heat to the bodies {bodies:?}"
        );
    }
}

/// A converged thermal solution whose energy balance stays open by more than the 1 % issue 13
/// asks (the discretisation's doing on a coarse grid) says so in the summary's warnings: the
/// glass-disc ball at 3 m/s with the disc at rest closes to 2.0 % on 32^2 cells (warned) and
/// to 0.8 % on 64^2 (not warned).
#[test]
fn an_open_energy_balance_is_warned() {
    for (n, warned) in [(32, true), (64, false)] {
        let s = glass_disc_ball(n, 3.0, 2.0, None).summary;
        assert!(s.converged, "{n}^2: {}", s.termination);
        let err = s.energy_balance_error.unwrap().abs();
        let said = s.warnings.iter().any(|w| w.contains("energy balance"));
        assert_eq!(err > 0.01, warned, "{n}^2: balance {err}");
        assert_eq!(
            said, warned,
            "{n}^2: balance {err}, warnings {:?}",
            s.warnings
        );
    }
}

/// `temperature.png` of a 2D grid carries the three maps (film, surface 1, surface 2) below
/// the centre-line panels; a line contact has the panels only. Checked by the PNG's size and
/// that each is a real picture (well above an empty frame's bytes). The ball at 32^2 and the
/// Table 3.7 line at 128 cells (about a second each).
#[test]
fn temperature_png_has_maps_on_a_2d_grid() {
    use ehl::output::temperature::{LINE_PANELS, MAP_HEIGHT};
    let dir = tempfile::tempdir().unwrap();
    let ball = format!(
        "{}\n{OIL}",
        include_str!("../../../examples/ehl_ball_on_glass.toml")
    );
    for (name, text, sets, height) in [
        (
            "ball",
            ball.as_str(),
            vec!["grid.nx=32", "grid.ny=32"],
            LINE_PANELS + 3 * MAP_HEIGHT,
        ),
        ("line", THERMAL, vec!["grid.nx=128"], LINE_PANELS),
    ] {
        let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
        let c = parse_str(text, name, &sets).unwrap();
        let s = solve(&c);
        let out = dir.path().join(name);
        ehl::output::write_all(&out, &c, &s).unwrap();
        let png = std::fs::read(out.join("temperature.png")).unwrap();
        let be = |k: usize| u32::from_be_bytes([png[k], png[k + 1], png[k + 2], png[k + 3]]);
        assert_eq!(&png[12..16], b"IHDR");
        assert_eq!((be(16), be(20)), (1000, height), "{name}");
        assert!(png.len() > 50_000, "{name}: {} bytes", png.len());
    }
}

// ------------------------------------------------------------------ transient thermal runs

const GROOVE: &str = include_str!("../../../examples/ehl_transient_line_groove.toml");

/// The robustness scan's oil (docs/scripts/thermal_scan.py; eta0 = 0.05 Pa s, alpha =
/// 20 /GPa, Roelands, Dowson-Higginson) with the Eyring law at tau_0 = 5 MPa, and its solver
/// table; with [`OIL`] for its thermal properties.
const SCAN_OIL: &str = r#"[lubricant]
viscosity = 0.05
pressure_viscosity_coefficient = 2.0e-8
density = 870.0
viscosity_model = "roelands"
density_model = "dowson-higginson"
rheology = { model = "eyring", eyring_stress = 5e6 }

[solver]
tolerance = 1e-6
max_iterations = 200

"#;

/// The thermal table of the examples (thermal.md's typical mineral oil).
const OIL: &str = "[thermal]\ninlet_temperature = 313.0\nviscosity_temperature = 1.1\nthermal_expansion = 6.5e-4\nconductivity = 0.14\nheat_capacity = 2000.0\n";

/// The groove example (thesis Table 3.6 line, a 0.38 mm x 0.25 um groove on body 1) with
/// `extra` appended, on 128 cells, the groove travelling from -0.6 to +0.6 mm in 60 steps
/// (one cell per step, the step the issue asks for).
fn groove_case(extra: &str, sets: &[&str]) -> Case {
    let text = format!("{GROOVE}\n{extra}");
    let mut all: Vec<String> = vec![
        "grid.nx=128".into(),
        "motion.travel={ from = -0.6e-3, to = 0.6e-3, steps = 60 }".into(),
        "output.snapshots=[]".into(),
    ];
    all.extend(sets.iter().map(|s| s.to_string()));
    parse_str(&text, "groove.toml", &all).unwrap()
}

/// A transient thermal run whose steady start fails above the known thermal loading says so
/// too: the groove line at SRR 1 and U = 3e-10 (L = 28) on the example's 256 cells, 2 steps,
/// the fixed point alone (with the coupled Newton method the start settles; ~1.5 s). A run that converges above the limit says nothing: the hint is added to failures
/// only (the example at U = 1.3e-10 and SRR 0.3, L = 5.3, converges:
/// `a_groove_passes_through_the_thermal_line`).
#[test]
fn a_transient_thermal_run_beyond_the_known_loading_says_so() {
    let c = groove_case(
        OIL,
        &[
            "grid.nx=256",
            "motion.slide_to_roll=1.0",
            "motion.dimensionless_speed=3e-10",
            "motion.travel={ from = -0.6e-3, to = -0.58e-3, steps = 2 }",
            "thermal.coupled_newton=false",
        ],
    );
    let s = solve(&c);
    assert!(!s.summary.converged);
    let why = &s.summary.termination;
    assert!(
        why.contains("is 28.3") && why.contains("above 2.5"),
        "{why}"
    );
}

fn timeline(s: &Solution) -> &[ehl::solution::StepRecord] {
    &s.transient.as_ref().expect("a transient run").timeline
}

/// The isothermal limit of a transient run: with an oil and bodies that conduct heat away
/// almost perfectly (as `a_perfectly_conducting_oil_gives_the_isothermal_solution`) and a
/// Newtonian oil, the thermal groove passage at SRR 0.3 must follow the isothermal one step by
/// step: the factors are 1 to round-off, so the squeeze term with the thermal density, the
/// film's time derivatives and the per-step passes must leave pressure and film alone.
/// Tolerances as in the steady test: 1e-4 on the films (the Newton tolerance), 2e-4 on the
/// friction (the Couette stress goes as 1/h; measured 8.5e-7 at worst over the steps), the
/// largest film temperature within 1e-2 K of the inlet's.
#[test]
fn a_perfectly_conducting_transient_follows_the_isothermal_one() {
    let sets = [NEWTONIAN, "motion.slide_to_roll=0.3"];
    let iso = solve(&groove_case("", &sets));
    let cool = "[thermal]\nconductivity = 1e6\n";
    let th = solve(&groove_case(
        cool,
        &[
            NEWTONIAN,
            "motion.slide_to_roll=0.3",
            "body1.conductivity=1e10",
            "body2.conductivity=1e10",
        ],
    ));
    assert!(iso.summary.converged, "{}", iso.summary.termination);
    assert!(th.summary.converged, "{}", th.summary.termination);
    let (a, b) = (timeline(&iso), timeline(&th));
    assert_eq!(a.len(), b.len());
    for (i, t) in a.iter().zip(b) {
        let tt = t.thermal.expect("thermal columns");
        assert!(
            tt.max_film_temperature_k - 313.0 < 1e-2,
            "step {}: {tt:?}",
            t.step
        );
        for (x, y, what) in [
            (i.central_film_m, t.central_film_m, "central film"),
            (i.min_film_m, t.min_film_m, "minimum film"),
            (i.max_pressure_pa, t.max_pressure_pa, "max pressure"),
        ] {
            assert!(
                (y / x - 1.0).abs() < 1e-4,
                "step {}: {what} thermal {y} vs isothermal {x}",
                t.step
            );
        }
        let (fi, ft) = (
            i.friction_coefficient.unwrap(),
            t.friction_coefficient.unwrap(),
        );
        assert!(
            (ft / fi - 1.0).abs() < 2e-4,
            "step {}: friction thermal {ft} vs isothermal {fi}",
            t.step
        );
    }
}

/// Without features the thermal transient must stay on its steady start: every step's film,
/// friction and film temperature equal step 0's. The time terms (the film's h rho c dT/dt and
/// d(h rho)/dt, the squeeze term with the thermal density at both levels) vanish only if they
/// are consistent with the steady equations. Tolerances: the per-step fixed point stops at a
/// change of 0.05 K (`ThermalParams::tolerance_k`), so the film temperature is held to 0.1 K;
/// 0.1 K moves the viscosity by ~0.3 % (Roelands S0 = 1.1 at 313 K) and the film, set in the
/// inlet, by a fraction of that: 1e-3 on the films, 3e-3 on the friction.
#[test]
fn a_smooth_thermal_transient_stays_on_its_steady_start() {
    let sets = [
        "motion.slide_to_roll=0.3",
        "motion.travel={ duration = 2e-5, steps = 10 }",
        "grid.nx=128",
    ];
    let c = parse_str(THERMAL, "ehl_thermal_line.toml", &sets.map(String::from)).unwrap();
    let s = solve(&c);
    assert!(s.summary.converged, "{}", s.summary.termination);
    let t = timeline(&s);
    let r = &t[0];
    let r0 = r.thermal.unwrap();
    for k in &t[1..] {
        let th = k.thermal.unwrap();
        assert!(
            (th.max_film_temperature_k - r0.max_film_temperature_k).abs() < 0.1,
            "step {}: {} K vs {} K",
            k.step,
            th.max_film_temperature_k,
            r0.max_film_temperature_k
        );
        assert!(
            (k.central_film_m / r.central_film_m - 1.0).abs() < 1e-3,
            "step {}",
            k.step
        );
        assert!(
            (k.min_film_m / r.min_film_m - 1.0).abs() < 1e-3,
            "step {}",
            k.step
        );
        let (f, f0) = (
            k.friction_coefficient.unwrap(),
            r.friction_coefficient.unwrap(),
        );
        assert!(
            (f / f0 - 1.0).abs() < 3e-3,
            "step {}: f {f} vs {f0}",
            k.step
        );
        assert!(th.energy_balance_error.abs() < 1e-2, "step {}", k.step);
    }
}

/// The groove passing through the thermal line at SRR 0.3 (Carreau, the example's oil):
/// * every step converges, and its energy balance (generated = into the bodies + convected +
///   stored in the film) closes within 1 % (issue 13; measured 0.27 % at worst on these 128 cells);
/// * so does its mass balance, the steady start's included, within 1e-4 (the Newton and the
///   factors' tolerances; measured 4e-7 on the steps; the start's, taken with the isothermal
///   coefficients before 2026-11-26, was 0.8 % off);
/// * the thermal friction is below the isothermal one at every step (measured 0.87-0.92 of
///   it over the passage);
/// * the film's enthalpy changes while the groove is in the contact (`heat_stored_w` above
///   1e-3 of the heat generated at some step; measured 4.2e-2) and the film temperature moves
///   with it (its largest value by more than 1 K over the passage; measured 349.5-352.0 K).
#[test]
fn a_groove_passes_through_the_thermal_line() {
    let sets = ["motion.slide_to_roll=0.3"];
    let th = solve(&groove_case(OIL, &sets));
    let iso = solve(&groove_case("", &sets));
    assert!(th.summary.converged, "{}", th.summary.termination);
    let (a, b) = (timeline(&iso), timeline(&th));
    let mut stored = 0.0f64;
    let (mut tmin, mut tmax) = (f64::INFINITY, 0.0f64);
    for (i, t) in a.iter().zip(b) {
        let tt = t.thermal.unwrap();
        assert!(t.converged, "step {}", t.step);
        assert!(
            t.mass_balance.abs() < 1e-4,
            "step {}: mass balance {}",
            t.step,
            t.mass_balance
        );
        assert!(
            tt.energy_balance_error.abs() < 1e-2,
            "step {}: {tt:?}",
            t.step
        );
        let (fi, ft) = (
            i.friction_coefficient.unwrap(),
            t.friction_coefficient.unwrap(),
        );
        assert!(
            ft < fi,
            "step {}: thermal f {ft} vs isothermal {fi}",
            t.step
        );
        stored = stored.max(tt.heat_stored_w.abs() / tt.heat_generated_w);
        tmin = tmin.min(tt.max_film_temperature_k);
        tmax = tmax.max(tt.max_film_temperature_k);
    }
    eprintln!("groove: stored/generated {stored:.3e}, film T {tmin:.2}..{tmax:.2} K, worst balance {:.2e}", th.summary.max_energy_balance_error.unwrap());
    assert!(stored > 1e-3, "largest stored / generated {stored}");
    assert!(tmax - tmin > 1.0, "film temperature {tmin}..{tmax} K");
    let m = &th.summary;
    assert!(m.max_film_temperature_over_travel_k.unwrap() >= tmax - 1e-9);
    // the time split sums the steady start's phases and every step's
    assert_time_split("groove", m, None);
    // the step fields carry the thermal viscosity (at the mid-film temperature, ~37 K above the
    // inlet in the Hertz zone): well below the isothermal law's at the pressure maximum (the
    // isothermal law there would give a ratio near 1: the pressures differ by a few %)
    let at = |s: &Solution| {
        let p = &s.fields.pressure;
        let k = (0..p.len()).fold(0, |m, k| if p[k] > p[m] { k } else { m });
        s.fields.viscosity.as_ref().unwrap()[k]
    };
    let ratio = at(&th) / at(&iso);
    assert!(
        ratio < 0.5,
        "thermal / isothermal viscosity at the pressure maximum {ratio}"
    );
    assert!(m.max_energy_balance_error.unwrap() < 1e-2);
}

/// A thermal solve that did not settle says in a warning that its temperatures are no solution
/// (a scan found an unsettled thermal roller reporting absurd temperatures with only
/// `converged = false` to flag them); a settled one does not.
#[test]
fn an_unsettled_thermal_solve_warns_of_its_temperatures() {
    let text = THERMAL.to_string();
    let said = |s: &Solution| {
        s.summary
            .warnings
            .iter()
            .any(|w| w.contains("did not settle: not a solution"))
    };
    let short = solve(
        &parse_str(
            &text,
            "thermal.toml",
            &["grid.nx=128".into(), "thermal.max_iterations=2".into()],
        )
        .unwrap(),
    );
    assert!(!short.summary.converged);
    assert!(
        short.summary.max_film_temperature_k.is_some() && said(&short),
        "{:?}",
        short.summary.warnings
    );
    let settled = solve(&parse_str(&text, "thermal.toml", &["grid.nx=128".into()]).unwrap());
    assert!(
        settled.summary.converged && !said(&settled),
        "{:?}",
        settled.summary.warnings
    );
}

/// A thermal time step that does not settle in its passes is handed to Newton's method on the
/// coupled problem of the step (`ehl::transient`, `STEP_POLISH_CHECKS`). The groove line with
/// the scan's Eyring oil (tau_0 = 5 MPa) at p_h 2 GPa (W = 5.44e-4) and SRR 1, 128 cells, the
/// groove from 0.5 to 0.83 mm in 30 steps (its trailing edge leaving the contact): on the
/// fixed point alone steps 17 and 22 end unsettled after their 20 passes (measured: the
/// temperatures settled to 1e-3 K but the film still moving by 2-3e-4 of its thinnest a pass,
/// against the step's 1e-4); polished (4 Newton steps each, ~110 GMRES iterations) the next
/// pass finds each settled by the step's own test. Asked: with the coupled method every step
/// converged with the energy balance within the issue's 1 %; without it some step not (so
/// that the test exercises the polish: measured steps 17 and 22); and at the steps the fixed
/// point left unsettled the polished central and minimum films within 1e-3 of its last
/// iterate (a few passes of its creep of 2-3e-4 of a film a pass; measured 5.1e-5; an
/// unsettled step reports no friction). ~1 s.
#[test]
fn an_unsettled_thermal_time_step_is_finished_by_newton() {
    let eyring = "lubricant.rheology={model=\"eyring\",eyring_stress=5e6}";
    let run = |newton: bool| {
        let newton = format!("thermal.coupled_newton={newton}");
        solve(&groove_case(
            OIL,
            &[
                eyring,
                "motion.slide_to_roll=1.0",
                "load.dimensionless_load=5.44e-4",
                "motion.travel={ from = 0.5e-3, to = 0.83e-3, steps = 30 }",
                &newton,
            ],
        ))
    };
    let (a, b) = (run(true), run(false));
    let (ta, tb) = (timeline(&a), timeline(&b));
    let unsettled: Vec<usize> = tb.iter().filter(|t| !t.converged).map(|t| t.step).collect();
    let mut worst = 0.0f64;
    for (t, u) in ta.iter().zip(tb) {
        let th = t.thermal.unwrap();
        assert!(t.converged, "step {}", t.step);
        assert!(
            th.energy_balance_error.abs() < 1e-2,
            "step {}: {th:?}",
            t.step
        );
        if !u.converged {
            let rel = |x: f64, y: f64| (x / y - 1.0).abs();
            let d = rel(t.central_film_m, u.central_film_m).max(rel(t.min_film_m, u.min_film_m));
            worst = worst.max(d);
        }
    }
    println!("unsettled without Newton: {unsettled:?}; polished against them: {worst:.1e}");
    assert!(a.summary.converged, "{}", a.summary.termination);
    assert!(
        !unsettled.is_empty(),
        "the fixed point alone settled every step"
    );
    assert!(worst < 1e-3, "{worst:.2e}");
}
