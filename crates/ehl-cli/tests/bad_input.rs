//! One test per class of bad input: each checks the message (file, dotted key, reason and, for
//! unknown keys, the suggestion), the exit status 1, and that no output folder was created.

mod common;
use common::*;

#[test]
fn unreadable_file() {
    let w = Work::new(DRY);
    let o = w.ehl(&["run", "missing.toml"]);
    assert_eq!(o.code, 1);
    assert!(
        o.stderr
            .starts_with("error: missing.toml: cannot read the case file"),
        "{}",
        o.stderr
    );
    assert!(w.no_outputs());
    // a folder is not a case file either
    std::fs::create_dir(w.file("dir.toml")).unwrap();
    let o = w.ehl(&["check", "dir.toml"]);
    assert_eq!(o.code, 1);
    assert!(o.stderr.contains("dir.toml: cannot read"), "{}", o.stderr);
}

#[test]
fn malformed_toml_reports_line_and_column() {
    let w = bad(DRY, "radius = 0.01", "radius = 0.01 0.02");
    let o = w.ehl(&["run", "case.toml"]);
    assert_eq!(o.code, 1);
    assert!(
        o.stderr.starts_with("error: case.toml: not valid TOML"),
        "{}",
        o.stderr
    );
    assert!(
        o.stderr.contains("line 6"),
        "line of the error: {}",
        o.stderr
    );
    assert!(o.stderr.contains("column"), "{}", o.stderr);
    assert!(w.no_outputs());
}

#[test]
fn misspelt_key_names_the_closest() {
    bad(DRY, "force = ", "forse = 30000.0").expect_error(
        &[],
        "load.forse",
        &["unknown key", "did you mean `load.force`?"],
    );
    bad(DRY, "youngs_modulus", "young_modulus = 200e9").expect_error(
        &[],
        "body1.young_modulus",
        &["did you mean `body1.youngs_modulus`?"],
    );
    // a key in the wrong table: the same name elsewhere is suggested
    Work::new(&edit(
        EHL,
        "force = ",
        "force = 6000.0\nentrainment_speed = 2.7",
    ))
    .expect_error(
        &[],
        "load.entrainment_speed",
        &["did you mean `motion.entrainment_speed`?"],
    );
    // axial_offset belongs to body2
    bad(
        DRY,
        "poisson_ratio",
        "poisson_ratio = 0.3\naxial_offset = 1e-3",
    )
    .expect_error(
        &[],
        "body1.axial_offset",
        &["did you mean `body2.axial_offset`?"],
    );
    // nothing close: the valid keys of the table are listed
    bad(DRY, "nx = 32", "nx = 32\nzzzzzz = 1").expect_error(
        &[],
        "grid.zzzzzz",
        &["valid keys in [grid]: nx, ny, x_min, x_max, y_min, y_max"],
    );
}

#[test]
fn misspelt_table_names_the_closest() {
    bad(EHL, "[lubricant]", "[lubricnt]").expect_error(
        &[],
        "lubricnt",
        &["did you mean `lubricant`?"],
    );
}

#[test]
fn missing_required_keys() {
    bad(DRY, "youngs_modulus", "").expect_error(
        &[],
        "body1.youngs_modulus",
        &["missing", "Young's modulus in Pa"],
    );
    bad(DRY, "kind", "").expect_error(&[], "kind", &["missing", "\"dry\"", "\"ehl\""]);
    bad(DRY, "force", "").expect_error(
        &[],
        "load",
        &["one of force (N), max_hertz_pressure (Pa), force_per_length (N/m) or dimensionless_load"],
    );
    bad(DRY, "shape", "").expect_error(&[], "body1.shape", &["missing"]);
    let no_body2 = DRY.split("[body2]").next().unwrap().to_string() + "[load]\nforce = 30000.0\n";
    Work::new(&no_body2).expect_error(&[], "body2", &["missing", "a [body2] table"]);
}

#[test]
fn wrong_types() {
    bad(DRY, "radius", "radius = \"10mm\"").expect_error(
        &[],
        "body1.radius",
        &["expected a number (m), found the string \"10mm\""],
    );
    bad(DRY, "radius", "radius = \"0.01\"").expect_error(
        &[],
        "body1.radius",
        &["write it without quotes"],
    );
    bad(DRY, "nx = 32", "nx = 32.5").expect_error(
        &[],
        "grid.nx",
        &["expected a whole number", "32.5"],
    );
    bad(DRY, "shape", "shape = 3").expect_error(&[], "body1.shape", &["expected a string"]);
    bad(
        DRY,
        "ny = 32",
        "ny = 32\n[solver]\nfree_end_correction = \"yes\"",
    )
    .expect_error(
        &[],
        "solver.free_end_correction",
        &["expected true or false, found the string \"yes\""],
    );
    let text = DRY.replace("[load]\nforce = 30000.0\n", "");
    Work::new(&edit(&text, "kind", "kind = \"dry\"\nload = 5")).expect_error(
        &[],
        "load",
        &["expected a table", "found the integer 5"],
    );
}

#[test]
fn unknown_choice_values() {
    bad(DRY, "shape", "shape = \"rolller\"").expect_error(
        &[],
        "body1.shape",
        &["unknown value \"rolller\"", "did you mean \"roller\"?"],
    );
    bad(DRY, "kind", "kind = \"wet\"").expect_error(
        &[],
        "kind",
        &["expected one of \"dry\", \"ehl\""],
    );
}

#[test]
fn values_that_make_no_sense() {
    let cases: &[(&str, &str, &str, &str)] = &[
        (
            "radius",
            "radius = 0.0",
            "body1.radius",
            "must be a positive, finite number (m), found 0",
        ),
        ("radius", "radius = -0.01", "body1.radius", "found -0.01"),
        (
            "radius",
            "radius = inf",
            "body1.radius",
            "for a plane use shape = \"flat\"",
        ),
        (
            "youngs_modulus",
            "youngs_modulus = -200e9",
            "body1.youngs_modulus",
            "found -2e11",
        ),
        (
            "youngs_modulus",
            "youngs_modulus = nan",
            "body1.youngs_modulus",
            "found nan",
        ),
        (
            "force",
            "force = 0",
            "load.force",
            "must be a positive, finite number (N)",
        ),
        ("force", "force = inf", "load.force", "found inf"),
        ("length", "length = 0.0", "body1.length", "must be positive"),
        (
            "length",
            "length = -inf",
            "body1.length",
            "must be positive",
        ),
        ("nx = 32", "nx = 0", "grid.nx", "must be at least 1"),
        ("ny = 32", "ny = -4", "grid.ny", "must be at least 2"),
        (
            "ny = 32",
            "ny = 32\n[solver]\ntolerance = 0.0",
            "solver.tolerance",
            "positive",
        ),
        (
            "ny = 32",
            "ny = 32\n[solver]\nmax_iterations = 0",
            "solver.max_iterations",
            "at least 1",
        ),
        (
            "ny = 32",
            "ny = 32\n[alignment]\ntilt = nan",
            "alignment.tilt",
            "finite",
        ),
    ];
    for (old, new, key, fragment) in cases {
        bad(DRY, old, new).expect_error(&[], key, &[fragment]);
    }
    // lubricant and motion values (ehl)
    let cases: &[(&str, &str, &str, &str)] = &[
        (
            "viscosity",
            "viscosity = inf",
            "lubricant.viscosity",
            "positive, finite number (Pa s), found inf",
        ),
        (
            "viscosity",
            "viscosity = 0",
            "lubricant.viscosity",
            "found 0",
        ),
        ("density", "density = -846.0", "lubricant.density", "kg/m^3"),
        (
            "entrainment_speed",
            "entrainment_speed = 0",
            "motion.entrainment_speed",
            "m/s",
        ),
        (
            "slide_to_roll",
            "slide_to_roll = 3.0",
            "motion.slide_to_roll",
            "between -2 and 2",
        ),
        (
            "pressure_viscosity_coefficient",
            "pressure_viscosity_coefficient = 15.9",
            "lubricant.pressure_viscosity_coefficient",
            "written 15.9e-9",
        ),
    ];
    for (old, new, key, fragment) in cases {
        bad(EHL, old, new).expect_error(&[], key, &[fragment]);
    }
}

#[test]
fn poisson_ratio_outside_its_range() {
    for v in ["0.5", "-1.0", "0.7", "-3"] {
        bad(DRY, "poisson_ratio", &format!("poisson_ratio = {v}")).expect_error(
            &[],
            "body1.poisson_ratio",
            &["strictly between -1 and 0.5"],
        );
    }
    // the edges' neighbours are fine
    let w = bad(DRY, "poisson_ratio", "poisson_ratio = 0.4999");
    assert_eq!(w.ehl(&["check", "case.toml"]).code, 0);
}

#[test]
fn grid_too_coarse_for_the_hertz_width() {
    // 10 cells over -1.5 .. 1.5 b: 2b spans 10 * 2 / 3 = 6.7 cells < 8; 12 cells are needed
    let msg = bad(DRY, "nx = 32", "nx = 10").expect_error(
        &[],
        "grid.nx",
        &[
            "too coarse",
            "6.7 cells across the Hertz contact width 2b",
            "Raise grid.nx to 12",
        ],
    );
    assert!(msg.contains("b = ") || msg.contains("2b = "), "{msg}");
    // 12 is enough
    let w = bad(DRY, "nx = 32", "nx = 12");
    assert_eq!(w.ehl(&["check", "case.toml"]).code, 0);
    // along the roller too
    bad(DRY, "ny = 32", "ny = 4").expect_error(&[], "grid.ny", &["too coarse along the roller"]);
}

#[test]
fn grid_extents() {
    bad(DRY, "nx = 32", "nx = 32\nx_min = 2.0\nx_max = 1.5").expect_error(
        &[],
        "grid.x_max",
        &[
            "must be greater than grid.x_min",
            "x_min = 2",
            "x_max = 1.5",
        ],
    );
    bad(DRY, "nx = 32", "nx = 32\nx_min = -0.5").expect_error(
        &[],
        "grid.x_min",
        &["whole Hertz contact", "-1 or less"],
    );
    bad(DRY, "nx = 32", "nx = 32\ny_min = 1.0\ny_max = -1.0").expect_error(
        &[],
        "grid.y_max",
        &["must be greater than grid.y_min"],
    );
    bad(DRY, "nx = 32", "nx = 32\ny_min = 0.0").expect_error(
        &[],
        "grid.y_min",
        &["cover the whole contact length"],
    );
}

#[test]
fn exactly_one_load_form() {
    bad(DRY, "force", "force = 30000.0\nmax_hertz_pressure = 2e9").expect_error(
        &[],
        "load.max_hertz_pressure",
        &[
            "exactly one form of the load",
            "`load.force`",
            "`load.max_hertz_pressure`",
        ],
    );
    bad(
        DRY,
        "force",
        "dimensionless_load = 1e-4\nforce_per_length = 1e6",
    )
    .expect_error(&[], "load.dimensionless_load", &["exactly one"]);
}

#[test]
fn infinite_line_needs_a_load_per_length() {
    let inf = edit_in(
        &edit(DRY, "length", "length = inf"),
        "[body2]",
        "length",
        "length = inf",
    );
    let inf = edit(&inf, "ny = 32", "");
    Work::new(&inf).expect_error(
        &[],
        "load.force",
        &["infinite line contact", "force_per_length (N/m)"],
    );
    let ok = Work::new(&edit(&inf, "force", "force_per_length = 7.5e6"));
    let o = ok.ehl(&["check", "case.toml"]);
    assert_eq!(o.code, 0, "{}", o.stderr);
    let o = ok.ehl(&["check", "case.toml", "--set", "grid.ny=32"]);
    assert_eq!(o.code, 1);
    assert!(
        o.stderr.contains("grid.ny: an infinite line contact"),
        "{}",
        o.stderr
    );
}

#[test]
fn ehl_needs_motion_and_lubricant() {
    let no_motion = EHL.replace(
        "[motion]\nentrainment_speed = 2.7\nslide_to_roll = 0.0\n",
        "",
    );
    Work::new(&no_motion).expect_error(&[], "motion", &["missing", "kind = \"ehl\""]);
    let no_lub = EHL.split("[lubricant]").next().unwrap().to_string() + "[grid]\nnx = 64\n";
    Work::new(&no_lub).expect_error(&[], "lubricant", &["missing", "viscosity"]);
    // a dry case ignores both
    let w = Work::new(&edit(EHL, "kind", "kind = \"dry\""));
    assert_eq!(
        w.ehl(&["check", "case.toml", "--set", "grid.x_min=-1.5"])
            .code,
        0
    );
}

#[test]
fn shape_specific_keys() {
    bad(DRY, "radius", "radius = 0.01\nradius_y = 0.02").expect_error(
        &[],
        "body1.radius_y",
        &["balls only"],
    );
    bad(DRY, "length", "").expect_error(&[], "body1.length", &["missing", "axial length"]);
    let ball = edit(&edit(DRY, "shape", "shape = \"ball\""), "length", "");
    let ball = edit_in(&ball, "[body2]", "shape", "shape = \"flat\"");
    let ball = edit_in(&ball, "[body2]", "radius", "");
    let ball = edit_in(&ball, "[body2]", "length", "");
    let ball = edit(&ball, "force", "force = 15.0");
    assert_eq!(Work::new(&ball).ehl(&["check", "case.toml"]).code, 0);
    Work::new(&edit(
        &ball,
        "radius",
        "radius = 0.01\nprofile = { kind = \"straight\" }",
    ))
    .expect_error(&[], "body1.profile", &["rollers only"]);
    Work::new(&edit(&ball, "radius", "radius = 0.01\nlength = 0.004")).expect_error(
        &[],
        "body1.length",
        &["a ball has no axial length"],
    );
    Work::new(&edit_in(
        &ball,
        "[body2]",
        "shape",
        "shape = \"flat\"\nradius = 0.02",
    ))
    .expect_error(&[], "body2.radius", &["a flat is a plane"]);
    bad(
        DRY,
        "poisson_ratio",
        "poisson_ratio = 0.3\nprofile = { kind = \"crowned\" }",
    )
    .expect_error(
        &[],
        "body1.profile.crown_radius",
        &["missing", "crown_radius"],
    );
    bad(
        DRY,
        "poisson_ratio",
        "poisson_ratio = 0.3\nprofile = { kind = \"crowned\", crown_radius = 0.5, angle = 0.1 }",
    )
    .expect_error(
        &[],
        "body1.profile.angle",
        &["not a parameter of profile kind \"crowned\""],
    );
}

#[test]
fn features_outside_the_domain() {
    let pit = "[[features]]\nkind = \"pit\"\nbody = 1\nwidth = 0.1e-3\nlength = 0.5e-3\ndepth = 2.5e-8\nx = 0.0\ny = 0.0\n";
    // inside the domain, a dry contact with a pit solves
    let w = Work::new(&(DRY.to_string() + pit));
    let o = w.ehl(&["run", "case.toml"]);
    assert!(o.code == 0 || o.code == 3, "{}", o.stderr);
    assert!(w.file("out/case/summary.json").is_file());
    // 5 mm is far outside the grid (x within +-1.5 b, b = 0.66 mm)
    Work::new(&(DRY.to_string() + &pit.replace("x = 0.0", "x = 5e-3"))).expect_error(
        &[],
        "features[0].x",
        &["wholly inside the grid", "x = 4.95 .. 5.05 mm"],
    );
    Work::new(&(DRY.to_string() + pit + &pit.replace("y = 0.0", "y = 1.9e-3"))).expect_error(
        &[],
        "features[1].y",
        &["wholly inside the grid"],
    );
    // a misspelt feature key
    Work::new(&(DRY.to_string() + &pit.replace("depth", "dept"))).expect_error(
        &[],
        "features[0].dept",
        &["did you mean `features[0].depth`?"],
    );
}

/// `motion.travel` with the path form moves features[0]'s centre: it needs a feature, on a body
/// that moves, travelling downstream.
#[test]
fn travel_path_form_without_features() {
    let w = Work::new(&edit(
        EHL,
        "slide_to_roll",
        "slide_to_roll = 0.0\ntravel = { from = -1e-3, to = 1e-3, steps = 200 }",
    ));
    w.expect_error(
        &[],
        "motion.travel.from",
        &[
            "no [[features]]",
            "motion.travel = { duration = 2e-4, steps = 200 }",
        ],
    );
    assert!(w.no_outputs());
}

const PIT: &str =
    "[[features]]\nkind = \"pit\"\nbody = 2\nwidth = 0.1e-3\nlength = 0.5e-3\ndepth = 2.5e-8\n";

#[test]
fn travel_path_form_with_features_on_a_body_standing_still() {
    // SRR = 2 stops body 2, which carries features[0]
    Work::new(
        &(edit(
            EHL,
            "slide_to_roll",
            "slide_to_roll = 2.0\ntravel = { from = -1e-3, to = 1e-3, steps = 200 }",
        ) + PIT),
    )
    .expect_error(
        &[],
        "motion.travel",
        &[
            "features[0] is on body 2, which stands still",
            "{ duration = 2e-4, steps = 200 }",
        ],
    );
}

#[test]
fn travel_must_go_downstream() {
    let text = edit(
        EHL,
        "slide_to_roll",
        "slide_to_roll = 0.0\ntravel = { from = 1e-3, to = -1e-3, steps = 200 }",
    ) + PIT;
    Work::new(&text).expect_error(
        &[],
        "motion.travel.to",
        &[
            "downstream",
            "to > from",
            "found from = 0.001 m, to = -0.001 m",
        ],
    );
    // --set reaches into the inline table: the same case with to = from
    Work::new(&text).expect_error(
        &["--set", "motion.travel.to=1e-3"],
        "motion.travel.to",
        &["to > from"],
    );
}

#[test]
fn travel_forms_are_not_mixed_and_steps_are_bounded() {
    Work::new(&edit(
        EHL,
        "slide_to_roll",
        "slide_to_roll = 0.0\ntravel = { from = -1e-3, to = 1e-3 }",
    ))
    .expect_error(&[], "motion.travel.steps", &["missing"]);
    Work::new(&edit(
        EHL,
        "slide_to_roll",
        "slide_to_roll = 0.0\ntravel = { duration = 2e-4, from = -1e-3, steps = 20 }",
    ))
    .expect_error(&[], "motion.travel.duration", &["not both"]);
    Work::new(&edit(
        EHL,
        "slide_to_roll",
        "slide_to_roll = 0.0\ntravel = { duration = 2e-4, steps = 200001 }",
    ))
    .expect_error(&[], "motion.travel.steps", &["more than the 100000"]);
    Work::new(&edit(
        EHL,
        "slide_to_roll",
        "slide_to_roll = 0.0\ntravel = { duration = -2e-4, steps = 20 }",
    ))
    .expect_error(&[], "motion.travel.duration", &["positive", "-2e-4"]);
}

#[test]
fn feature_on_a_moving_body_without_travel_suggests_one() {
    Work::new(&(EHL.to_string() + PIT)).expect_error(
        &[],
        "features[0].body",
        &["makes the film transient", "add motion.travel"],
    );
}

#[test]
fn output_table_is_checked() {
    Work::new(&(EHL.to_string() + "[output]\nframe_every = 2\n")).expect_error(
        &[],
        "output.frame_every",
        &["did you mean `output.frames_every`?"],
    );
    let text = edit(
        EHL,
        "slide_to_roll",
        "slide_to_roll = 0.0\ntravel = { from = -1e-3, to = 1e-3, steps = 200 }",
    ) + PIT
        + "[output]\nsnapshots = [0.0, 2e-3]\n";
    Work::new(&text).expect_error(
        &[],
        "output.snapshots",
        &["x_p = 0.002 m (snapshots[1]) lies outside the travel"],
    );
}
