//! Ball on flat (circular point contact): film against EHL-FBNS and Hamrock-Dowson.
mod common;
use common::*;
use ehl::case::{DensityModel, Lubricant, ViscosityModel};
use ehl::ehl::{solve_steady, EhlParams, EhlProblem, EhlResult};
use ehl::elastic::{Deflection, FftDeflection};
use ehl::grid::Grid;
use ehl::units;

/// The EHL-FBNS lubricant (eta0 = 0.25 Pa s, alpha = 22 GPa^-1) with the given laws.
fn fbns_oil(v: ViscosityModel, d: DensityModel) -> Lubricant {
    lubricant(0.25, 22e-9, v, d)
}

/// Ball R = 12.5 mm on a flat, E' = 110 GPa, F = 15 N, u_e = 0.09 m/s (the EHL-FBNS case) with
/// the lubricant `lub`, on n x n cells over [-3a, 3a]^2, with the given solver settings.
fn solve_ball(lub: &Lubricant, n: usize, params: &EhlParams) -> (EhlResult, Grid, f64, f64) {
    let (r, e, f, ue) = (0.0125, 110e9, 15.0, 0.09);
    let hz = units::hertz_point(f, r, e);
    let a = hz.a;
    let grid = Grid::new(n, n, -3.0 * a, 3.0 * a, -3.0 * a, 3.0 * a);
    let gap = move |x: f64, y: f64| (x * x + y * y) / (2.0 * r);
    let op = move |g: Grid| -> Box<dyn Deflection> { Box::new(FftDeflection::half_space(g, e)) };
    let prob = EhlProblem {
        grid,
        gap: &gap,
        operator: &op,
        load: f,
        lubricant: lub,
        entrainment_speed: ue,
        reduced_radius: r,
        reduced_modulus: e,
        hertz_half_width: a,
        hertz_pressure: hz.p0,
        initial_pressure: None,
    };
    (solve_steady(&prob, params), grid, a, hz.p0)
}

/// Issue 3 reference: EHL-FBNS (Hansen et al., Tribol. Lett. 70 (2022) 80; finite volumes with
/// JFO cavitation; Roelands + Dowson-Higginson) for a ball R = 12.5 mm on glass, E' = 110 GPa,
/// F = 15 N, u_m = 0.09 m/s, eta0 = 0.25 Pa s, alpha = 22 GPa^-1, 129^2 cells on [-3a, 3a]^2
/// (a = 136.5 um): h_c = 225.8 nm, h_min = 125.5 nm, p_max = 0.388 GPa. The issue set 3 % (h_c)
/// and 6 % (h_min); asserted 0.5 % (below).
///
/// EHL-FBNS discretises the Couette (wedge) term with first-order upwinding (its published
/// source, `construct_FBNS_G_matr`: "Discretization of Couette terms with UPWIND scheme", the
/// west face taking the upstream cell's rho h). The comparison is therefore run with the same
/// scheme (`wedge_upwind_order = 1`): measured 225.7 / 125.6 nm, p_max 0.3878 GPa (-0.04 %,
/// +0.08 %, -0.05 %). With our default second-order rule the same grid gives 207.1 / 116.7 nm;
/// the two schemes approach each other as the grid is refined (first order 232.8 / 225.7 /
/// 219.9 nm, second order 191.3 / 207.1 / 211.2 nm on 65^2 / 129^2 / 257^2, the latter
/// extrapolating to 212.6 nm, which agrees with Mourier et al. 2006's multigrid plateau of
/// 209-212 nm; see `ball_against_mourier_simulation`). So the 6 % gap of the default scheme to
/// the reference is the reference's first-order discretisation error at 129^2, not a
/// difference in the physics: the test pins both the scheme and the laws.
#[test]
fn ball_on_glass_against_ehl_fbns() {
    let params = EhlParams {
        wedge_upwind_order: 1,
        ..EhlParams::default()
    };
    let (res, grid, a, _p0) = solve_ball(
        &fbns_oil(ViscosityModel::Roelands, DensityModel::DowsonHigginson),
        129,
        &params,
    );
    assert!(res.converged, "{}", res.termination);
    let kc = grid.idx(grid.nx / 2, grid.ny / 2);
    let hc = res.fields.film[kc];
    let hmin = thinnest(&res.fields.film);
    let pmax = res.fields.pressure.iter().cloned().fold(0.0, f64::max);
    println!(
        "a = {:.1} um: h_c {:.1} nm (225.8), h_min {:.1} nm (125.5), p_max {:.4} GPa (0.388)",
        a * 1e6,
        hc * 1e9,
        hmin * 1e9,
        pmax / 1e9
    );
    // the issue asked 3 % and 6 %; with the reference's own scheme, laws and grid only the
    // cavitation treatment (JFO against complementarity) and the solver tolerances differ, so
    // 0.5 % (measured 0.04, 0.08 and 0.05 %)
    assert!((hc / 225.8e-9 - 1.0).abs() < 0.005, "h_c {hc}");
    assert!((hmin / 125.5e-9 - 1.0).abs() < 0.005, "h_min {hmin}");
    assert!((pmax / 0.388e9 - 1.0).abs() < 0.005, "p_max {pmax}");
}

/// The same ball against Hamrock & Dowson (1977) (Roelands + Dowson-Higginson, the laws of the
/// fit), 129^2 cells: central and minimum film within 15 % (the fit's scatter against its own
/// data is 5-8 %, plus the discretisation error of the coarse grid, which thins the film by
/// ~3 % between 256^2 and 129^2; measured -7.1 % and -10.6 %). Load balance 1e-6, symmetric
/// about y = 0 to 1e-6 relative.
#[test]
fn ball_against_hamrock_dowson() {
    let (r, e, f, ue, eta0, alpha): (f64, f64, f64, f64, f64, f64) =
        (0.0125, 110e9, 15.0, 0.09, 0.25, 22e-9);
    let (res, grid, _a, _p0) = solve_ball(
        &fbns_oil(ViscosityModel::Roelands, DensityModel::DowsonHigginson),
        129,
        &EhlParams::default(),
    );
    assert!(res.converged, "{}", res.termination);
    // the load the returned pressure carries, integrated here over its cells (the rectangle
    // rule the solver balances: a check that the returned field is the balanced one, at the
    // solve's tolerance)
    let carried = res.fields.pressure.iter().sum::<f64>() * grid.dx * grid.dy;
    assert!(
        (carried / f - 1.0).abs() < 1e-6,
        "carried {carried} N of {f}"
    );
    let (w, u, g) = (f / (e * r * r), eta0 * ue / (e * r), alpha * e);
    let hc_ref = ehl::reference::film::hamrock_dowson_central(w, u, g, 1.0) * r;
    let hm_ref = ehl::reference::film::hamrock_dowson_min(w, u, g, 1.0) * r;
    let hc = res.fields.film[grid.idx(grid.nx / 2, grid.ny / 2)];
    let hmin = thinnest(&res.fields.film);
    println!(
        "h_c {:.1} nm vs HD {:.1}; h_min {:.1} nm vs HD {:.1}",
        hc * 1e9,
        hc_ref * 1e9,
        hmin * 1e9,
        hm_ref * 1e9
    );
    assert!((hc / hc_ref - 1.0).abs() < 0.15);
    assert!((hmin / hm_ref - 1.0).abs() < 0.15);
    let pmax = res.fields.pressure.iter().cloned().fold(0.0, f64::max);
    for j in 0..grid.ny / 2 {
        for i in 0..grid.nx {
            let (a, b) = (
                res.fields.pressure[grid.idx(i, j)],
                res.fields.pressure[grid.idx(i, grid.ny - 1 - j)],
            );
            assert!(
                (a - b).abs() < 1e-6 * pmax,
                "asymmetric at ({i}, {j}): {a} vs {b}"
            );
        }
    }
}

/// Centreline index of the cell nearest to (0, 0) and its row.
fn centre(grid: &Grid) -> usize {
    let i = (0..grid.nx)
        .min_by(|&a, &b| grid.x(a).abs().total_cmp(&grid.x(b).abs()))
        .unwrap();
    let j = (0..grid.ny)
        .min_by(|&a, &b| grid.y(a).abs().total_cmp(&grid.y(b).abs()))
        .unwrap();
    grid.idx(i, j)
}

/// The EHL-FBNS ball against an independent simulation of the same case: Mourier, Mazuyer,
/// Lubrecht & Donnet, Tribol. Int. 39 (2006) 1745-1756 (Venner-Lubrecht multigrid code, Roelands +
/// Dowson-Higginson, u_m = 0.09 m/s), the smooth part of their simulated centreline film profile:
/// plateau 209-212 nm (210.5 taken), centreline minimum 175-176 nm (175.5 taken).
/// Tolerance 4 %: ~1 % for reading the values off a figure plus the discretisation error of
/// 129^2 cells, 2.6 % on h_c (65^2 / 129^2 / 257^2 give 191.3 / 207.1 / 211.2 nm, second order,
/// extrapolated 212.6 nm).
#[test]
fn ball_against_mourier_simulation() {
    let (res, grid, _a, _p0) = solve_ball(
        &fbns_oil(ViscosityModel::Roelands, DensityModel::DowsonHigginson),
        129,
        &EhlParams::default(),
    );
    assert!(res.converged, "{}", res.termination);
    let kc = centre(&grid);
    let hc = res.fields.film[kc];
    let row = kc / grid.nx;
    let hcl = (0..grid.nx)
        .map(|i| res.fields.film[grid.idx(i, row)])
        .fold(f64::INFINITY, f64::min);
    println!(
        "h_c {:.1} nm (Mourier 210.5), centreline h_min {:.1} nm (Mourier 175.5)",
        hc * 1e9,
        hcl * 1e9
    );
    assert!((hc / 210.5e-9 - 1.0).abs() < 0.04, "h_c {hc}");
    assert!(
        (hcl / 175.5e-9 - 1.0).abs() < 0.04,
        "centreline h_min {hcl}"
    );
}

/// Grid-converged against grid-converged (issue 9, aside): EHL-FBNS's own refinement of this
/// case (first-order wedge term; 65^2 / 129^2 / 257^2: h_c 232.9 / 225.8 / 219.9 nm) converges
/// slowly: its differences 7.1 and 5.9 nm fall by 1.2 only, not yet the factor 2 of a
/// first-order scheme in its asymptotic range, so its limit is not well determined: 214-218 nm
/// if the next differences fall at order 1 to 2 (216 taken), lower if they keep falling as
/// slowly; Mourier et al. 2006's multigrid plateau of 209-212 nm for the same case sits just
/// below (`ball_against_mourier_simulation`). Ours, second order, on 129^2 and 257^2,
/// Richardson-extrapolated with the observed order 2 (65^2 / 129^2 / 257^2 give differences
/// 15.8 and 4.1 nm, ratio 3.9): h_ext = h_257 + (h_257 - h_129) / 3, measured 212.5-212.6 nm.
/// Tolerance 2.5 % about 216 nm (210.6-221.4 nm): the reference's order-1-to-2 range (+-1 %),
/// ours about 1 % (order 2 against the observed 1.95), and the lower end reaching Mourier's
/// plateau. The coarse 129^2 value alone is 4 % low, outside it: the test needs the
/// refinement.
#[test]
fn ball_grid_converged_against_ehl_fbns_extrapolated() {
    let lub = fbns_oil(ViscosityModel::Roelands, DensityModel::DowsonHigginson);
    let hc = |n: usize| {
        let (res, grid, _a, _p0) = solve_ball(&lub, n, &EhlParams::default());
        assert!(res.converged, "{n}: {}", res.termination);
        res.fields.film[centre(&grid)]
    };
    let (h1, h2) = (hc(129), hc(257));
    let ext = h2 + (h2 - h1) / 3.0;
    println!(
        "h_c 129^2 {:.1} nm, 257^2 {:.1} nm, extrapolated {:.1} nm (EHL-FBNS ~216)",
        h1 * 1e9,
        h2 * 1e9,
        ext * 1e9
    );
    assert!((ext / 216e-9 - 1.0).abs() < 0.025, "extrapolated h_c {ext}");
    assert!(h2 > h1, "the film thickens with the grid");
}

/// The 2D scaling check the film of the ball rests on (deflection and gap in H = h R / a^2,
/// load dX dY sum P = 2 pi / 3, inlet, y-Poiseuille): with the laws of the fit (Barus,
/// incompressible) the central film of the FBNS ball (M = 63.8, L = 5.79) is within 4 % of
/// Nijenbanning's fit (measured -1.3 % at 129^2): the fit's stated accuracy is a few per cent,
/// and 129^2 cells thin the film by ~2.6 % (grid study above). A wrong factor in any of those
/// scalings moves the film by far more (e.g. E' off by 2 changes h_c by ~10 %).
#[test]
fn ball_barus_incompressible_against_nijenbanning() {
    let (r, e, f, ue, eta0, alpha): (f64, f64, f64, f64, f64, f64) =
        (0.0125, 110e9, 15.0, 0.09, 0.25, 22e-9);
    let lub = fbns_oil(ViscosityModel::Barus, DensityModel::Constant);
    let (res, grid, _a, _p0) = solve_ball(&lub, 129, &EhlParams::default());
    assert!(res.converged, "{}", res.termination);
    let (w, u, g) = (f / (e * r * r), eta0 * ue / (e * r), alpha * e);
    let (m, l) = (w * (2.0 * u).powf(-0.75), g * (2.0 * u).powf(0.25));
    let href = ehl::reference::film::nijenbanning_circular_central(m, l) * (2.0 * u).sqrt() * r;
    let hc = res.fields.film[centre(&grid)];
    println!(
        "M {m:.2} L {l:.3}: h_c {:.1} nm vs Nijenbanning {:.1} nm (Newton {}, GMRES {})",
        hc * 1e9,
        href * 1e9,
        res.iterations,
        res.linear_iterations
    );
    assert!((hc / href - 1.0).abs() < 0.04);
}
