//! Surface features in steady runs (dry contact, and EHL with the features on a body that stands
//! still): identities, symmetry, complementarity and conservation checks.

use ehl::case::parse_str;
use ehl::run::{solve, Silent};
use ehl::solution::Solution;

/// Thesis Table 1.1 rollers (R1 = R2 = 10 mm, L = 4 mm, 30 kN; b = 0.66 mm) on a 48 x 48 grid.
const DRY: &str = r#"
kind = "dry"
[body1]
shape = "roller"
radius = 0.01
length = 4e-3
youngs_modulus = 200e9
poisson_ratio = 0.3
[body2]
shape = "roller"
radius = 0.01
length = 4e-3
youngs_modulus = 200e9
poisson_ratio = 0.3
[load]
force = 30000.0
[grid]
nx = 48
ny = 48
[solver]
tolerance = 1e-9
"#;

/// Thesis ch. 2 rollers, body 2 standing still (SRR = 2: u1 = 2 u_e, u2 = 0).
const EHL: &str = r#"
kind = "ehl"
[body1]
shape = "roller"
radius = 0.06
length = 9.5e-3
youngs_modulus = 200e9
poisson_ratio = 0.3
[body2]
shape = "roller"
radius = 0.06
length = 9.5e-3
youngs_modulus = 200e9
poisson_ratio = 0.3
[load]
force = 6000.0
[motion]
entrainment_speed = 2.7
slide_to_roll = 2.0
[lubricant]
viscosity = 0.04
pressure_viscosity_coefficient = 15.9e-9
density = 846.0
[grid]
nx = 96
ny = 32
"#;

fn pit(body: u8, width: f64, length: f64, depth: f64, x: f64, y: f64) -> String {
    format!(
        "\n[[features]]\nkind = \"pit\"\nbody = {body}\nwidth = {width:e}\nlength = {length:e}\ndepth = {depth:e}\nx = {x:e}\ny = {y:e}\n"
    )
}

fn run(text: &str) -> Solution {
    let case = parse_str(text, "case.toml", &[]).expect("valid case");
    solve(&case, &Silent).expect("solved")
}

#[test]
fn zero_depth_features_reproduce_the_smooth_solution() {
    let smooth = run(DRY);
    let zero = run(&(DRY.to_string() + &pit(1, 0.4e-3, 1e-3, 0.0, 0.0, 0.0)));
    assert_eq!(smooth.fields.pressure, zero.fields.pressure);
    let smooth = run(EHL);
    let zero = run(&(EHL.to_string() + &pit(2, 0.2e-3, 1e-3, 0.0, 0.0, 0.0)));
    assert!(smooth.summary.converged);
    assert_eq!(smooth.fields.pressure, zero.fields.pressure);
    assert_eq!(smooth.fields.film, zero.fields.film);
}

/// A pit much deeper than the local elastic deflection (50 um against ~7 um for a 2 GPa strip
/// 0.4 mm wide) carries no pressure (the contact condition p = 0 where the gap stays open), the
/// load moves to the rest of the contact, and the maximum pressure rises at the pit's edges.
#[test]
fn a_deep_pit_carries_no_pressure_in_dry_contact() {
    let (w, l) = (0.4e-3, 1.0e-3);
    let s = run(&(DRY.to_string() + &pit(1, w, l, 50e-6, 0.0, 0.0)));
    let smooth = run(DRY);
    assert!(s.summary.converged, "{}", s.summary.termination);
    let g = s.grid;
    let pmax = s.summary.max_pressure_pa;
    let mut inside = 0;
    for j in 0..g.ny {
        for i in 0..g.nx {
            // cells wholly inside the pit
            let (x0, x1) = (g.x(i) - 0.5 * g.dx, g.x(i) + 0.5 * g.dx);
            let (y0, y1) = (g.y(j) - 0.5 * g.dy, g.y(j) + 0.5 * g.dy);
            if x0 >= -0.5 * w && x1 <= 0.5 * w && y0 >= -0.5 * l && y1 <= 0.5 * l {
                inside += 1;
                assert!(s.fields.pressure[g.idx(i, j)] <= 1e-9 * pmax, "({i}, {j})");
            }
        }
    }
    assert!(inside >= 20, "{inside} cells inside the pit");
    // the load is still carried (solver tolerance 1e-9), by a higher peak
    assert!(s.summary.load_error < 1e-6, "{}", s.summary.load_error);
    assert!(pmax > 1.05 * smooth.summary.max_pressure_pa);
}

/// Two pits placed symmetrically about the roller's mid-length give a pressure field symmetric
/// under y -> -y (the grid, the rollers and their end images are symmetric).
#[test]
fn symmetric_pits_give_a_symmetric_pressure() {
    let text = DRY.to_string()
        + &pit(1, 0.3e-3, 0.4e-3, 2e-6, 0.1e-3, 1.0e-3)
        + &pit(2, 0.3e-3, 0.4e-3, 2e-6, 0.1e-3, -1.0e-3);
    let s = run(&text);
    let g = s.grid;
    let p = &s.fields.pressure;
    let pmax = s.summary.max_pressure_pa;
    let smooth = run(DRY);
    let mut changed = 0.0f64;
    for j in 0..g.ny {
        for i in 0..g.nx {
            let (a, b) = (p[g.idx(i, j)], p[g.idx(i, g.ny - 1 - j)]);
            assert!((a - b).abs() < 1e-6 * pmax, "({i}, {j}): {a} vs {b}");
            changed = changed.max((a - smooth.fields.pressure[g.idx(i, j)]).abs());
        }
    }
    // and the pits do change the pressure (a test on the smooth field would pass trivially)
    assert!(changed > 0.05 * pmax, "{changed}");
}

/// A bump (negative depth) is not clipped: it raises the pressure over it (by ~5 % here, a
/// 1 um bump 0.3 b wide under a 7.2 GPa Hertz pressure). A gap clamped at zero, as before the
/// features were built, would leave the pressure unchanged.
#[test]
fn a_bump_raises_the_pressure() {
    let s = run(&(DRY.to_string() + &pit(1, 0.2e-3, 0.4e-3, -1e-6, 0.0, 0.0)));
    let smooth = run(DRY);
    let g = s.grid;
    let k = g.idx(g.nx / 2, g.ny / 2);
    assert!(
        s.fields.pressure[k] > 1.02 * smooth.fields.pressure[k],
        "{} vs {}",
        s.fields.pressure[k],
        smooth.fields.pressure[k]
    );
}

/// EHL with a pit on the standing body: converges, balances the load and conserves mass
/// (inflow = outflow + side leakage: the flux form telescopes, so the imbalance is the sum of
/// the cells' residuals, each solved to 1e-6 of its own flows: 1e-4 of the inflow allows for
/// the wet cells' sum; measured 1.5e-7).
#[test]
fn a_pit_on_the_standing_body_in_ehl_conserves_load_and_mass() {
    let s = run(&(EHL.to_string() + &pit(2, 0.2e-3, 1e-3, 0.5e-6, 0.0, 0.0)));
    let smooth = run(EHL);
    assert!(s.summary.converged, "{}", s.summary.termination);
    // the load the written pressure carries, integrated here over its cells (the rectangle rule
    // the solver balances, so this checks that the written field is the balanced one): 1e-6,
    // the solve's tolerance
    let g = s.grid;
    let carried = s.fields.pressure.iter().sum::<f64>() * g.dx * g.dy;
    assert!((carried / 6000.0 - 1.0).abs() < 1e-6, "carried {carried} N");
    let (i, o, l) = (
        s.summary.mass_inflow_kg_s.unwrap(),
        s.summary.mass_outflow_kg_s.unwrap(),
        s.summary.side_leakage_kg_s.unwrap(),
    );
    assert!((i - o - l).abs() < 1e-4 * i, "in {i}, out {o}, side {l}");
    // the pit changes the film where it sits: the cell nearest its centre (x = 0)
    let ic = (0..g.nx)
        .min_by(|&a, &b| g.x(a).abs().total_cmp(&g.x(b).abs()))
        .unwrap();
    let k = g.idx(ic, g.ny / 2);
    let (h, h0) = (
        s.fields.film.as_ref().unwrap()[k],
        smooth.fields.film.as_ref().unwrap()[k],
    );
    // far more than the solve's film accuracy (1e-6): 5e-3 of the film, 3 nm (measured 1.3e-2,
    // 7.9 nm: in the Hertz zone the pressure flattens most of the 0.5 um)
    assert!((h - h0).abs() > 5e-3 * h0, "{h} vs {h0}");
}

/// A measured surface read from a `.npy` file beside the case: a 2 x 2 map of one depth spanning
/// w x l is, by its bilinear interpolation, exactly a flat-bottomed pit w x l, so both give the
/// same contact (the map's file, read relative to the case file's folder, and its spacings are
/// checked).
#[test]
fn a_height_map_file_equals_the_pit_it_describes() {
    let (w, l, d) = (0.3e-3, 0.6e-3, 3e-6);
    // dy spans the length, dx the width; off-centre, so a wrong centre would show
    let map = format!(
        "\n[[features]]\nkind = \"height-map\"\nfile = \"maps/flat.npy\"\ndx = {w:e}\ndy = {l:e}\nx = 0.1e-3\ny = 0.5e-3\n"
    );
    let from_map = solve_with_map("maps/flat.npy", d, &map);
    let from_pit = run(&(DRY.to_string() + &pit(1, w, l, d, 0.1e-3, 0.5e-3)));
    let pmax = from_pit.summary.max_pressure_pa;
    let diff = largest_pressure_difference(&from_map, &from_pit);
    assert!(diff < 1e-9 * pmax, "{diff}");
    // and the pit is not the smooth contact
    let smooth = run(DRY);
    assert!((smooth.summary.max_pressure_pa - pmax).abs() > 1e-3 * pmax);
}

/// DRY with the feature text `map`, whose `.npy` file `file` (a path relative to the case)
/// holds a 2 x 2 map of the one depth `d` (m): by its bilinear interpolation, a flat-bottomed
/// pit dx x dy.
fn solve_with_map(file: &str, d: f64, map: &str) -> Solution {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(file);
    std::fs::create_dir_all(path.parent().unwrap()).unwrap();
    ndarray_npy::write_npy(&path, &ndarray::Array2::<f64>::from_elem((2, 2), d)).unwrap();
    let case_path = dir.path().join("case.toml");
    let text = DRY.to_string() + map;
    std::fs::write(&case_path, &text).unwrap();
    let case = parse_str(&text, &case_path.display().to_string(), &[]).expect("map case");
    solve(&case, &Silent).unwrap()
}

/// The largest pressure difference between two solutions on one grid (Pa).
fn largest_pressure_difference(a: &Solution, b: &Solution) -> f64 {
    a.fields
        .pressure
        .iter()
        .zip(&b.fields.pressure)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max)
}

/// The contract lets every localized kind carry a `pattern` (interface.md: "same body, x, y,
/// pattern keys"), a height map included: the 2 x 2 map of one depth on a 1 x 2 pattern gives
/// the contact of the same pit on the same pattern (a scan found the pattern refused).
#[test]
fn a_patterned_height_map_equals_the_patterned_pit() {
    let (w, l, d) = (0.2e-3, 0.4e-3, 3e-6);
    let pattern = "pattern = { rows = 1, columns = 2, row_pitch = 1e-3, column_pitch = 0.8e-3 }\n";
    let map = format!(
        "\n[[features]]\nkind = \"height-map\"\nfile = \"flat.npy\"\ndx = {w:e}\ndy = {l:e}\nx = 0.05e-3\ny = 0.0\n{pattern}"
    );
    let from_map = solve_with_map("flat.npy", d, &map);
    let from_pit = run(&(DRY.to_string() + &pit(1, w, l, d, 0.05e-3, 0.0) + pattern));
    let pmax = from_pit.summary.max_pressure_pa;
    let diff = largest_pressure_difference(&from_map, &from_pit);
    assert!(diff < 1e-9 * pmax, "{diff}");
    // and the second copy matters: one pit alone is another contact
    let single = run(&(DRY.to_string() + &pit(1, w, l, d, 0.05e-3, 0.0)));
    assert!((single.summary.max_pressure_pa - pmax).abs() > 1e-4 * pmax);
}

/// A .npy header may declare any shape: a 128-byte file declaring 10^6 x 10^6 float64 values
/// made the reader ask for 8 TB and abort the program (exit 134, found by a scan). Its size is
/// now checked against the file first, and the case is refused by `features[0].file`.
#[test]
fn a_height_map_declaring_more_than_its_file_holds_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let mut header =
        "{'descr': '<f8', 'fortran_order': False, 'shape': (1000000, 1000000), }".to_string();
    while (10 + header.len() + 1) % 64 != 0 {
        header.push(' ');
    }
    header.push('\n');
    let mut bytes = b"\x93NUMPY\x01\x00".to_vec();
    bytes.extend_from_slice(&(header.len() as u16).to_le_bytes());
    bytes.extend_from_slice(header.as_bytes());
    std::fs::write(dir.path().join("huge.npy"), &bytes).unwrap();
    let text = DRY.to_string()
        + "\n[[features]]\nkind = \"height-map\"\nfile = \"huge.npy\"\ndx = 1e-7\ndy = 1e-7\n";
    let case_path = dir.path().join("case.toml");
    match parse_str(&text, &case_path.display().to_string(), &[]) {
        Err(ehl::Error::Case { key, message, .. }) => {
            assert_eq!(key, "features[0].file");
            assert!(message.contains("declares a shape"), "{message}");
        }
        other => panic!("{other:?}"),
    }
}

/// A solved pressure beyond the models' range is said: a bump 60 um wide and 120 um high on a
/// dry ball (slope ~4, accepted by the 1 % of R depth rule) concentrates 500 N into a few cells,
/// hundreds of GPa, p / E' above 1 (a scan found it reported without a word). The smooth ball
/// (p_h / E' = 0.009) gets no such warning.
#[test]
fn a_pressure_beyond_the_elastic_range_is_warned() {
    let ball = "kind = \"dry\"\n[body1]\nshape = \"ball\"\nradius = 0.0127\nyoungs_modulus = 210e9\npoisson_ratio = 0.3\n[body2]\nshape = \"flat\"\nyoungs_modulus = 210e9\npoisson_ratio = 0.3\n[load]\nforce = 500.0\n[grid]\nnx = 64\n";
    let warned = |s: &Solution| {
        s.summary
            .warnings
            .iter()
            .any(|w| w.contains("reduced modulus"))
    };
    let bump = run(&format!(
        "{ball}[[features]]\nkind = \"dent\"\nwidth = 60e-6\ndepth = -1.2e-4\n"
    ));
    assert!(
        bump.summary.max_pressure_pa > 0.1 * 2.3e11,
        "{}",
        bump.summary.max_pressure_pa
    );
    assert!(warned(&bump), "{:?}", bump.summary.warnings);
    let smooth = run(ball);
    assert!(!warned(&smooth), "{:?}", smooth.summary.warnings);
}

/// A feature whose travel never brings it onto the grid leaves the run smooth, and the summary
/// says so (a scan found a dent travelling from -5 to -4 mm towards a contact within +-0.5 mm
/// run and reported without a word); the example's own travel through the contact is not
/// warned.
#[test]
fn a_feature_that_never_reaches_the_grid_is_warned() {
    let path = format!(
        "{}/../../examples/ehl_transient_ball_dent.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let solve = |sets: &[&str]| {
        let mut all: Vec<String> = ["grid.nx=32", "grid.ny=32", "output.snapshots=[]"]
            .iter()
            .map(|s| s.to_string())
            .collect();
        all.extend(sets.iter().map(|s| s.to_string()));
        let case = ehl::case::load_file(std::path::Path::new(&path), &all).unwrap();
        solve(&case, &Silent).unwrap().summary
    };
    let never = |s: &ehl::solution::Summary| {
        s.warnings
            .iter()
            .any(|w| w.contains("never comes onto the grid"))
    };
    let away = solve(&[
        "features[0].x=-5e-3",
        "motion.travel={from=-5e-3,to=-4e-3,steps=10}",
    ]);
    assert!(never(&away), "{:?}", away.warnings);
    let through = solve(&["motion.travel={from=-0.4e-3,to=0.4e-3,steps=10}"]);
    assert!(!never(&through), "{:?}", through.warnings);
    // the path form starts features[0] at `from`, wherever the case put it (a review: the
    // check used the case's position): the example's dent (x = -0.4 mm) sent from -5 mm never
    // arrives, and a dent put at -5 mm but sent from -0.4 mm does
    let sent_away = solve(&["motion.travel={from=-5e-3,to=-4e-3,steps=10}"]);
    assert!(never(&sent_away), "{:?}", sent_away.warnings);
    let brought = solve(&[
        "features[0].x=-5e-3",
        "motion.travel={from=-0.4e-3,to=0.4e-3,steps=10}",
    ]);
    assert!(!never(&brought), "{:?}", brought.warnings);
}
