//! The discrete Reynolds operator against exact results: Poiseuille and Couette parts on
//! polynomials they must reproduce, and the flux form's conservation law (the sum of the cell
//! residuals over the pressurised cells equals inflow - outflow - side leakage).
use ehl::reynolds::residual::{mass_flow, residual, Fields, ReynoldsGrid};

fn grid(nx: usize, ny: usize, second_order: bool) -> ReynoldsGrid {
    ReynoldsGrid {
        nx,
        ny,
        dx: 0.1,
        dy: 0.2,
        second_order,
    }
}

/// Interior cells: central differences with constant eps reproduce a quadratic exactly, so
/// L(P) = eps (d2P/dX2 + d2P/dY2) to round-off (1e-9 relative). No Couette flow (H = 0).
#[test]
fn poiseuille_exact_on_quadratics() {
    let g = grid(12, 9, true);
    let n = g.nx * g.ny;
    let (mut p, h, rho, eps, act) = (
        vec![0.0; n],
        vec![0.0; n],
        vec![1.0; n],
        vec![2.5; n],
        vec![true; n],
    );
    for j in 0..g.ny {
        for i in 0..g.nx {
            let (x, y) = ((i as f64 + 0.5) * g.dx, (j as f64 + 0.5) * g.dy);
            p[j * g.nx + i] = 3.0 * x * x - 2.0 * y * y + x * y + 1.0;
        }
    }
    let f = Fields {
        p: &p,
        rho: &rho,
        h: &h,
        eps: &eps,
        active: &act,
        couette_shift: None,
    };
    let mut r = vec![0.0; n];
    residual(&g, &f, None, None, &mut r);
    for j in 1..g.ny - 1 {
        for i in 1..g.nx - 1 {
            // r = -L = -eps (6 - 4)
            let expect = -2.5 * (6.0 - 4.0);
            assert!(
                (r[j * g.nx + i] - expect).abs() < 1e-9 * expect.abs(),
                "{}",
                r[j * g.nx + i]
            );
        }
    }
}

/// Couette part: for rho H linear in X both upwind orders give d(rho H)/dX exactly (away from
/// the inlet cells where the scheme falls back to first order with zero inflow gradient);
/// for rho H quadratic only the second-order scheme is exact (it is second order), and the
/// first-order one gives its backward difference, 3 dX below the derivative of 1 + 2X + 3X^2
/// (so a first-order flag that were ignored fails too).
#[test]
fn couette_upwind_orders() {
    for &(second, quad) in &[(false, false), (true, false), (true, true), (false, true)] {
        let g = grid(16, 1, second);
        let n = g.nx;
        let (p, rho, eps, act) = (vec![0.0; n], vec![1.0; n], vec![0.0; n], vec![true; n]);
        let h: Vec<f64> = (0..n)
            .map(|i| {
                let x = (i as f64 + 0.5) * g.dx;
                if quad {
                    1.0 + 2.0 * x + 3.0 * x * x
                } else {
                    1.0 + 2.0 * x
                }
            })
            .collect();
        let f = Fields {
            p: &p,
            rho: &rho,
            h: &h,
            eps: &eps,
            active: &act,
            couette_shift: None,
        };
        let mut r = vec![0.0; n];
        residual(&g, &f, None, None, &mut r);
        for i in 2..n {
            let x = (i as f64 + 0.5) * g.dx;
            let exact = match (quad, second) {
                (false, _) => 2.0,
                (true, true) => 2.0 + 6.0 * x,
                // (h_i - h_i-1) / dX = 2 + 3 (x_i + x_i-1)
                (true, false) => 2.0 + 6.0 * x - 3.0 * g.dx,
            };
            // r = -L = +d(rho H)/dX
            assert!(
                (r[i] - exact).abs() < 1e-9,
                "second {second} quad {quad} i {i}: {} vs {exact}",
                r[i]
            );
        }
    }
}

/// Conservation: with arbitrary positive fields, some cavitated cells (P = 0) and one cell
/// without material, sum over pressurised cells of -r dX dY = inflow - outflow - side leakage
/// to round-off (1e-10 relative to the total flow). This is what makes the mass-balance diagnostic
/// of the solver meaningful.
#[test]
fn flux_form_conserves_mass() {
    let g = grid(10, 7, true);
    let n = g.nx * g.ny;
    let mut s: u64 = 12345;
    let mut rnd = || {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (s >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut p: Vec<f64> = (0..n).map(|_| 0.1 + rnd()).collect();
    let h: Vec<f64> = (0..n).map(|_| 0.5 + rnd()).collect();
    let rho: Vec<f64> = (0..n).map(|_| 1.0 + 0.3 * rnd()).collect();
    let eps: Vec<f64> = (0..n).map(|_| rnd()).collect();
    let mut act = vec![true; n];
    for &k in &[23usize, 24, 45, 8] {
        p[k] = 0.0;
    }
    act[33] = false;
    p[33] = 0.0;
    let f = Fields {
        p: &p,
        rho: &rho,
        h: &h,
        eps: &eps,
        active: &act,
        couette_shift: None,
    };
    let mut r = vec![0.0; n];
    residual(&g, &f, None, None, &mut r);
    let net: f64 = (0..n)
        .filter(|&k| act[k] && p[k] > 0.0)
        .map(|k| -r[k] * g.dx * g.dy)
        .sum();
    let m = mass_flow(&g, &f);
    let bal = m.inflow - m.outflow - m.side_leakage;
    let scale = m.inflow.abs() + m.outflow.abs() + m.side_leakage.abs();
    // every flow is non-trivial, so the identity is not 0 = 0
    assert!(
        m.inflow.abs() > 1e-3 * scale && m.side_leakage.abs() > 1e-3 * scale,
        "{m:?}"
    );
    assert!((net - bal).abs() < 1e-10 * scale, "{net} vs {bal} ({m:?})");
}
