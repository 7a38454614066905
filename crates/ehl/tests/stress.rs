//! Stress below the surface (crate::stress) against the closed-form Hertz fields.

use ehl::grid::Grid;
use ehl::reference::subsurface::{
    hertz_circle_axis_stress, hertz_circle_stress, hertz_line_stress,
};
use ehl::stress::derived::von_mises;
use ehl::stress::field::stress_field;

/// Largest difference over the field between the DC-FFT stress of a Hertz line pressure
/// (traction mu p along +x) on `nx` cells over [-2b, 2b] and the McEwen / Smith-Liu closed form,
/// at every cell centre and depth, in units of p0.
fn line_error(nx: usize, mu: f64, depths: &[f64]) -> f64 {
    let (b, p0, nu) = (1.0, 1.0, 0.3);
    let grid = Grid::new(nx, 1, -2.0 * b, 2.0 * b, -0.5, 0.5);
    // cell averages of the Hertz pressure (exact: the integral of sqrt(1 - x^2))
    let prim = |x: f64| {
        let x = x.clamp(-1.0, 1.0);
        0.5 * (x * (1.0 - x * x).sqrt() + x.asin())
    };
    let p: Vec<f64> = (0..nx)
        .map(|i| {
            let x0 = grid.x_min + i as f64 * grid.dx;
            p0 * (prim(x0 + grid.dx) - prim(x0)) / grid.dx
        })
        .collect();
    let q: Vec<f64> = p.iter().map(|v| mu * v).collect();
    let f = stress_field(&grid, &p, Some(&q), nu, depths, true);
    let mut worst = 0.0_f64;
    for (k, &z) in depths.iter().enumerate() {
        for i in 0..nx {
            let exact = hertz_line_stress(grid.x(i), z, b, p0, mu, nu);
            let got = f.tensor(k * nx + i);
            for c in 0..6 {
                worst = worst.max((got[c] - exact[c]).abs());
            }
        }
    }
    worst
}

/// The whole field, all six components, every cell and 60 depths from 0.05 b to 3 b, frictionless
/// and sliding (mu = 0.2). The loads are exact cell averages, so the only error is the
/// piecewise-constant representation of p: O(dx^2) where z >> dx, measured 1.3e-3 p0 on 256 cells
/// (dx = b/64, worst at the shallowest layer, z = 3.2 dx) and 3.3e-4 p0 on 512. The test asks for
/// < 2e-3 p0 and second-order convergence (ratio > 3.5); a sign or coefficient error in any
/// kernel gives errors of order 0.1 p0.
#[test]
fn hertz_line_field_point_by_point() {
    let depths: Vec<f64> = (1..=60).map(|k| 0.05 * k as f64).collect();
    for mu in [0.0, 0.2] {
        let e1 = line_error(256, mu, &depths);
        let e2 = line_error(512, mu, &depths);
        eprintln!("mu {mu}: error {e1:.2e} (256), {e2:.2e} (512)");
        assert!(e1 < 2e-3, "mu {mu}: {e1}");
        assert!(e1 / e2 > 3.5, "mu {mu}: not second order: {e1} / {e2}");
    }
}

/// Depth of the von Mises maximum on the axis region of a sliding Hertz line contact (DC-FFT
/// field), in b, and the value in p0.
fn von_mises_peak(mu: f64) -> (f64, f64) {
    let nx = 256;
    let grid = Grid::new(nx, 1, -2.0, 2.0, -0.5, 0.5);
    let p: Vec<f64> = (0..nx)
        .map(|i| (1.0 - grid.x(i).powi(2)).max(0.0).sqrt())
        .collect();
    let q: Vec<f64> = p.iter().map(|v| mu * v).collect();
    let depths: Vec<f64> = (1..=100).map(|k| 0.01 * k as f64).collect();
    let f = stress_field(&grid, &p, Some(&q), 0.3, &depths, true);
    let mut best = (0.0, 0.0);
    for (k, &z) in depths.iter().enumerate() {
        for i in 0..nx {
            let v = von_mises(&f.tensor(k * nx + i));
            if v > best.1 {
                best = (z, v);
            }
        }
    }
    best
}

/// Johnson sec. 7.1: with friction the von Mises maximum moves up and reaches the surface for mu
/// around 0.25-0.3. Frictionless: 0.557 p0 at 0.70 b (grid step 0.016 b, depth step 0.01 b:
/// +-0.01 b, +-2e-3 p0).
#[test]
fn sliding_moves_the_von_mises_maximum_to_the_surface() {
    let (z0, v0) = von_mises_peak(0.0);
    assert!(
        (z0 - 0.70).abs() <= 0.011 && (v0 - 0.557).abs() < 2e-3,
        "{z0} {v0}"
    );
    let (z2, _) = von_mises_peak(0.2);
    assert!(z2 > 0.2 && z2 < z0, "mu 0.2: peak at {z2}");
    let (z4, _) = von_mises_peak(0.4);
    assert!(z4 <= 0.02, "mu 0.4: peak at {z4}");
    // the closed form agrees on where the maximum is
    let m4 = (1..=100)
        .map(|k| 0.01 * k as f64)
        .map(|z| {
            (0..=400)
                .map(|i| {
                    von_mises(&hertz_line_stress(
                        -2.0 + 0.01 * i as f64,
                        z,
                        1.0,
                        1.0,
                        0.4,
                        0.3,
                    ))
                })
                .fold(0.0, f64::max)
        })
        .collect::<Vec<f64>>();
    assert!(m4[0] >= m4.iter().cloned().fold(0.0, f64::max) - 1e-12);
}

/// Stress on the axis of a Hertz circle (3D kernels) against Huber's closed form, on an odd
/// grid (a cell centre on the axis) with loads averaged over 8 x 8 sub-points per cell. Two
/// domains with the same cells: [-1.5 a, 1.5 a]^2 and about [-3 a, 3 a]^2. A periodic (spectral) solver
/// has image errors that grow as the domain shrinks; the zero-padded one must give the same
/// answer on both (the loads are zero outside the contact). The axis error, 4.7e-4 p0 measured
/// (cells of a/20, the circle's edge cut by square cells), is asked below 3e-3 p0.
#[test]
fn hertz_circle_axis_and_no_image_error() {
    let (a, p0, nu) = (1.0, 1.0, 0.3);
    let depths: Vec<f64> = (1..=40).map(|k| 0.05 * k as f64).collect();
    let axis = |half: f64, n: usize| {
        let grid = Grid::new(n, n, -half, half, -half, half);
        let (p, _) = sliding_circle_loads(&grid, 0.0);
        let f = stress_field(&grid, &p, None, nu, &depths, false);
        let c = (n / 2) * n + n / 2;
        depths
            .iter()
            .enumerate()
            .map(|(k, _)| f.tensor(k * n * n + c))
            .collect::<Vec<_>>()
    };
    let small = axis(1.5, 61);
    let large = axis(1.5 * 121.0 / 61.0, 121); // same cells, twice the width
    let mut worst = 0.0_f64;
    let mut domain = 0.0_f64;
    for (k, &z) in depths.iter().enumerate() {
        let (sr, sz) = hertz_circle_axis_stress(z, a, p0, nu);
        let s = small[k];
        worst = worst
            .max((s[2] - sz).abs())
            .max((s[0] - sr).abs())
            .max((s[1] - sr).abs());
        // symmetry on the axis: no shear, to the single-precision FFT round-off (~1e-6 p0)
        assert!(s[3].abs() < 1e-5 && s[4].abs() < 1e-5 && s[5].abs() < 1e-5);
        for c in 0..6 {
            domain = domain.max((s[c] - large[k][c]).abs());
        }
    }
    eprintln!("circle axis: error {worst:.2e} p0, domain change {domain:.2e} p0");
    assert!(worst < 3e-3, "{worst}");
    // identical cells and loads: only the single-precision FFT round-off (~1e-6 p0) may differ;
    // a periodic image of the contact 3 a away would change sigma_zz at z = a by ~1e-2 p0
    assert!(domain < 1e-5, "{domain}");
}

/// Hertz circle pressure p0 sqrt(1 - r^2/a^2) with a sliding traction mu p along +x, averaged
/// over 8 x 8 sub-points of each of `n` x `n` cells on [-half, half]^2 (a = p0 = 1).
fn sliding_circle_loads(grid: &Grid, mu: f64) -> (Vec<f64>, Vec<f64>) {
    let (nx, ny, sub) = (grid.nx, grid.ny, 8);
    let mut p = vec![0.0; nx * ny];
    for j in 0..ny {
        for i in 0..nx {
            let mut acc = 0.0;
            for v in 0..sub {
                for u in 0..sub {
                    let x = grid.x_min + (i as f64 + (u as f64 + 0.5) / sub as f64) * grid.dx;
                    let y = grid.y_min + (j as f64 + (v as f64 + 0.5) / sub as f64) * grid.dy;
                    acc += (1.0 - (x * x + y * y)).max(0.0).sqrt();
                }
            }
            p[j * nx + i] = acc / (sub * sub) as f64;
        }
    }
    let q = p.iter().map(|v| mu * v).collect();
    (p, q)
}

/// The whole 3D field below a sliding Hertz circle (the sliding sphere of Hamilton & Goodman
/// 1966 and Hamilton 1983), all six components, against the reference by quadrature of the
/// exact point-load fields (`hertz_circle_stress`, which shares nothing with the rectangle
/// coefficients or the FFT). mu = 0.25 and 0.5, on every third cell centre of [-1.5 a, 1.5 a]^2
/// (inside and outside the contact) at depths 0.1 a to 1.5 a.
///
/// The error is the discretisation's: cell-wise constant loads, the circle's edge cut by square
/// cells. Measured on cells of a/20: 4.3e-3 p0 at z = 0.1 a (two cells deep, below the edge),
/// under 1e-3 p0 from 0.25 a down; on cells of a/60 (the same points) 5.2e-4 p0 (a fall of 8.3,
/// near second order's 9). Asked: better than order 1.5 (the error falls by more than
/// 3^1.5 = 5.2 when the cells shrink three times; first order would give 3, second 9), below
/// 1e-3 p0 on a/60 cells, and below 1.5e-3 p0 from 0.25 a down on a/20 cells (where the kernel
/// is smooth over a cell).
#[test]
fn sliding_hertz_circle_whole_field() {
    let nu = 0.3;
    let depths = [0.1, 0.25, 0.5, 0.75, 1.0, 1.5];
    // the largest error over the sampled points and components, per depth, in units of p0
    let field_error = |n: usize, mu: f64, stride: usize| {
        let grid = Grid::new(n, n, -1.5, 1.5, -1.5, 1.5);
        let (p, q) = sliding_circle_loads(&grid, mu);
        let f = stress_field(&grid, &p, Some(&q), nu, &depths, false);
        let mut worst = vec![0.0_f64; depths.len()];
        for (k, &z) in depths.iter().enumerate() {
            for j in (stride / 2..n).step_by(stride) {
                for i in (stride / 2..n).step_by(stride) {
                    let (x, y) = (grid.x(i), grid.y(j));
                    let want = hertz_circle_stress(x, y, z, 1.0, 1.0, mu, nu, 64);
                    let got = f.tensor((k * n + j) * n + i);
                    for c in 0..6 {
                        worst[k] = worst[k].max((got[c] - want[c]).abs());
                    }
                }
            }
        }
        worst
    };
    let max = |v: &[f64]| v.iter().cloned().fold(0.0, f64::max);
    for mu in [0.25, 0.5] {
        let coarse = field_error(61, mu, 3);
        let fine = field_error(183, mu, 9); // the same points: every third coarse cell centre
        let show = |v: &[f64]| {
            v.iter()
                .map(|e| format!("{e:.1e}"))
                .collect::<Vec<_>>()
                .join(" ")
        };
        eprintln!(
            "sliding circle, mu {mu}: error by depth {} p0 on a/20 cells; {} on a/60",
            show(&coarse),
            show(&fine)
        );
        assert!(
            max(&coarse) / max(&fine) > 5.2,
            "mu {mu}: {coarse:?} -> {fine:?}"
        );
        assert!(max(&fine) < 1e-3, "mu {mu}: {fine:?}");
        assert!(max(&coarse[1..]) < 1.5e-3, "mu {mu}: {coarse:?}");
    }
}

// ------------------------------------------------------------------ [stress] and [fatigue] runs

use ehl::case::parse_str;
use ehl::run::{solve, Silent};

/// A dry steel line contact at peak pressure `p0` with `[stress]` and `[fatigue]` (`extra` is
/// appended: features, other keys).
fn line_case(p0: f64, extra: &str) -> String {
    format!(
        r#"
kind = "dry"
[body1]
shape = "roller"
radius = 0.02
length = inf
youngs_modulus = 210e9
poisson_ratio = 0.3
[body2]
shape = "flat"
youngs_modulus = 210e9
poisson_ratio = 0.3
[load]
max_hertz_pressure = {p0:e}
[grid]
nx = 256
ny = 1
x_min = -2.0
x_max = 2.0
[solver]
tolerance = 1e-11
max_iterations = 500
[stress]
body = 1
depth = 2.0
layers = 24
{extra}
"#
    )
}

fn run(text: &str) -> ehl::solution::Solution {
    let case = parse_str(text, "case.toml", &[]).expect("valid case");
    solve(&case, &Silent).expect("solved")
}

fn groove(depth: f64) -> String {
    format!(
        "[[features]]\nkind = \"pit\"\nbody = 1\nwidth = 40e-6\nlength = inf\ndepth = {depth:e}\nx = 0.0\ny = 0.0\n"
    )
}

/// The smooth line contact's integral scales as p0^c b^2 (h = 0, no limit): the field is
/// self-similar in x/b, z/b with the grid and the depths given in b. Two loads give c back to
/// 1e-3 (the dry solver's tolerance and the f32 storage are far below that), at the default
/// c = 31/3 and at c = 40, where the integral in Pa^c overflowed (a scan: the run failed after
/// its solve with "summary figure 'fatigue_integral' is not finite").
#[test]
fn smooth_line_integral_scales_as_p0_to_the_c_times_b_squared() {
    for c in [31.0 / 3.0, 40.0] {
        let fatigue = format!("[fatigue]\ncriterion = \"von-mises\"\nstress_exponent = {c}\n");
        let a = run(&line_case(1.0e9, &fatigue));
        let b = run(&line_case(2.0e9, &fatigue));
        let (ia, ib) = (
            a.summary.fatigue_integral.unwrap(),
            b.summary.fatigue_integral.unwrap(),
        );
        assert!(ia.is_finite() && ib.is_finite() && ia > 0.0, "{ia} {ib}");
        let (ba, bb) = (a.summary.hertz_half_width_m, b.summary.hertz_half_width_m);
        let (pa, pb) = (a.summary.max_pressure_pa, b.summary.max_pressure_pa);
        let c_est = ((ib / ia) / (bb / ba).powi(2)).ln() / (pb / pa).ln();
        assert!((c_est - c).abs() < 1e-3, "c = {c_est} against {c}");
    }
    let fatigue = "[fatigue]\ncriterion = \"von-mises\"\n";
    let a = run(&line_case(1.0e9, fatigue));
    let (ba, pa) = (a.summary.hertz_half_width_m, a.summary.max_pressure_pa);
    // the peak is the frictionless Hertz one: 0.557 p0 at 0.70 b (24 geometric layers to 2 b:
    // the layer nearest 0.70 b is within 0.06 b; the value within 1 %)
    let v = a.summary.max_von_mises_pa.unwrap() / pa;
    let z = a.summary.max_von_mises_at_m.unwrap()[2] / ba;
    assert!(
        (v - 0.557).abs() < 0.006 && (z - 0.70).abs() < 0.07,
        "{v} p0 at {z} b"
    );
}

/// Life ratio 1 for a feature of zero depth; non-increasing with the depth of a groove at fixed
/// load once the groove is deep enough to open; the integral is exactly zero when the fatigue
/// limit exceeds the stress everywhere.
///
/// Measured on this grid (40 um groove, p0 = 1.5 GPa, dry): 0.2 um -> 1.015 (a shallow groove that
/// stays partly closed unloads the centre of the contact: the peak von Mises falls from 835 to
/// 832 MPa), 0.5 um -> 0.980, 1 um -> 0.337, 2 um -> 0.337. Once the groove is open (no contact in
/// it) its depth no longer changes a dry contact: the last two are equal, as they must be.
#[test]
fn fatigue_logic() {
    let fatigue = "[fatigue]\ncriterion = \"von-mises\"\n";
    let zero = run(&line_case(1.5e9, &format!("{fatigue}{}", groove(0.0))));
    assert_eq!(zero.summary.life_ratio, Some(1.0));
    let lives: Vec<f64> = [0.5e-6, 1.0e-6, 2.0e-6]
        .iter()
        .map(|&d| {
            run(&line_case(1.5e9, &format!("{fatigue}{}", groove(d))))
                .summary
                .life_ratio
                .unwrap()
        })
        .collect();
    assert!(lives[0] < 1.0 && lives[1] < lives[0], "{lives:?}");
    assert!(
        (lives[2] - lives[1]).abs() < 1e-9,
        "an open groove's depth does not matter dry: {lives:?}"
    );
    let limited = run(&line_case(1.5e9, "[fatigue]\nfatigue_limit = 2e9\n"));
    assert_eq!(limited.summary.fatigue_integral, Some(0.0));
}

/// With mu = 0.4 the von Mises maximum is at the surface: it lands on the first layer and the
/// summary warns (Johnson sec. 7.1).
#[test]
fn surface_maximum_is_flagged() {
    let s = run(&line_case(1.5e9, "friction = 0.4\n"));
    assert!(
        s.summary
            .warnings
            .iter()
            .any(|w| w.contains("von Mises maximum of body 1 lies on the first layer")),
        "{:?}",
        s.summary.warnings
    );
    let s = run(&line_case(1.5e9, ""));
    assert!(s.summary.warnings.is_empty(), "{:?}", s.summary.warnings);
}

#[test]
fn bad_stress_input_names_the_key() {
    let text = line_case(1.5e9, "").replace("[stress]\nbody = 1", "[stress]\nbody = 3");
    let e = parse_str(&text, "case.toml", &[]).unwrap_err().to_string();
    assert!(e.contains("stress.body"), "{e}");
    let text = line_case(1.5e9, "").replace(
        "[stress]\nbody = 1\ndepth = 2.0\nlayers = 24\n",
        "[fatigue]\n",
    );
    let e = parse_str(&text, "case.toml", &[]).unwrap_err().to_string();
    assert!(e.contains("fatigue") && e.contains("[stress]"), "{e}");
    let text = line_case(1.5e9, "layers = 0\n");
    assert!(parse_str(&text, "case.toml", &[]).is_err());
}

// ------------------------------------------------------------------ timing (ignored)

/// Where the time of one steady evaluation goes: 256 x 256 cells x 64 layers, Hertz circle with
/// traction 0.1 p (the bench's case). Medians of `STRESS_PROFILE_RUNS` (default 3) runs. Ignored
/// (seconds); `cargo test --release -p ehl --test stress -- --ignored --nocapture profile`.
#[test]
#[ignore]
fn profile_steady_256_squared_64_layers() {
    use ehl::stress::kernel::LayerKernel;
    use rayon::prelude::*;
    use std::time::Instant;
    let runs: usize = std::env::var("STRESS_PROFILE_RUNS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(3);
    let n = 256;
    let grid = Grid::new(n, n, -2.0, 2.0, -2.0, 2.0);
    let p: Vec<f64> = (0..n * n)
        .map(|k| {
            let (x, y) = (grid.x(k % n), grid.y(k / n));
            (1.0 - x * x - y * y).max(0.0).sqrt()
        })
        .collect();
    let q: Vec<f64> = p.iter().map(|v| 0.1 * v).collect();
    let z: Vec<f64> = (1..=64).map(|k| 0.05 * k as f64).collect();
    let median = |f: &mut dyn FnMut()| {
        let mut t: Vec<f64> = (0..runs)
            .map(|_| {
                let s = Instant::now();
                f();
                s.elapsed().as_secs_f64()
            })
            .collect();
        t.sort_by(f64::total_cmp);
        t[runs / 2]
    };
    // each layer's tables dropped once built, as the field does (keeping all 64, 400 MB, would
    // time the page faults)
    let tables = median(&mut || {
        z.par_iter().for_each(|&d| {
            std::hint::black_box(LayerKernel::new(n, n, grid.dx, grid.dy, d, 0.3));
        })
    });
    let shear = median(&mut || {
        std::hint::black_box(stress_field(&grid, &p, Some(&q), 0.3, &z, false));
    });
    let normal = median(&mut || {
        std::hint::black_box(stress_field(&grid, &p, None, 0.3, &z, false));
    });
    let window = median(&mut || {
        std::hint::black_box(stress_field(&grid, &p, Some(&q), 0.3, &z[..24], false));
    });
    eprintln!(
        "256^2 x 64 layers ({runs} runs, medians, wall s): pressure+shear {shear:.3}, pressure only {normal:.3}, \
         influence tables alone (all layers, parallel) {tables:.3}; 24 layers with shear {window:.3}"
    );
    profile_cached(&grid, &p, &q, &z, &median);
}

/// The cached path of the same case: building the kernel spectra once (tables + forward FFTs),
/// then one evaluation from them (2 load FFTs + 6 products and inverse FFTs per layer), and
/// the 24-layer window of the passage target.
fn profile_cached(
    grid: &Grid,
    p: &[f64],
    q: &[f64],
    z: &[f64],
    median: &dyn Fn(&mut dyn FnMut()) -> f64,
) {
    use ehl::stress::field::StressKernels;
    for z in [z, &z[..24]] {
        let mut kernels = None;
        let build =
            median(&mut || kernels = Some(StressKernels::new(grid, 0.3, z, false, usize::MAX)));
        let kernels = kernels.unwrap();
        let eval = median(&mut || {
            std::hint::black_box(kernels.field(p, Some(q)));
        });
        let eval_p = median(&mut || {
            std::hint::black_box(kernels.field(p, None));
        });
        eprintln!(
            "cached, {} layers: build (tables + 6 kernel FFTs per layer) {build:.3} s, {:.1} MB; evaluation with shear {eval:.3} s, pressure only {eval_p:.3} s",
            z.len(),
            kernels.bytes() as f64 / 1e6
        );
    }
}

/// The thesis single pit (Table 3.6, SRR 0.02) passing through the straight rollers: the life
/// ratio is taken at the worst pit position (the kept frame of largest fatigue integral), so it
/// is below 1 and falls with the pit's depth (issue 12: monotone in depth). At the frame of
/// highest pressure it was above 1 (1.0061 for 1 um, docs/stress.md): there the pit unloads
/// the contact's centre. Run coarse here (64^2 cells, 24 steps, 16 layers); the life ratios
/// 0.995 / 0.985 for 0.25 / 1 um were measured on a finer run (96^2, 30 steps).
#[test]
fn pit_life_ratio_is_taken_at_the_worst_position() {
    let path = format!(
        "{}/../../examples/ehl_thesis_ch3_single_pit.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let text = std::fs::read_to_string(path).unwrap();
    let text = format!(
        "{}\n[stress]\nbody = 1\ndepth = 2.0\nlayers = 16\n\n[fatigue]\n",
        text.replace("snapshots = [", "# snapshots = [")
    );
    let ratio = |depth: f64| {
        let sets: Vec<String> = [
            "grid.nx=64".to_string(),
            "grid.ny=64".to_string(),
            "motion.travel.steps=24".to_string(),
            "output.frames_every=1".to_string(),
            format!("features[0].depth={depth:e}"),
        ]
        .to_vec();
        let c = parse_str(&text, "pit.toml", &sets).unwrap();
        let s = solve(&c, &Silent).unwrap();
        assert!(s.summary.converged, "{}", s.summary.termination);
        s.summary.life_ratio.unwrap()
    };
    let (shallow, deep) = (ratio(0.25e-6), ratio(1e-6));
    assert!(
        deep < shallow && shallow < 1.0,
        "life ratio 0.25 um {shallow}, 1 um {deep}"
    );
}
