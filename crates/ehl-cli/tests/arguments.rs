//! `--set` overrides, `ehl check`, and the command-line argument errors of `run`, `check` and
//! `sweep` (exit status 2 for usage errors, 1 for case errors; no output folder either way).

mod common;
use common::*;

#[test]
fn check_validates_and_prints() {
    let w = Work::new(DRY);
    let o = w.ehl(&["check", "case.toml"]);
    assert_eq!(o.code, 0, "{}", o.stderr);
    assert!(!o.stdout.trim().is_empty());
    assert!(w.no_outputs(), "check writes nothing");
}

#[test]
fn set_fixes_and_breaks_a_case() {
    // the file's bad value is replaced before validation
    let w = bad(DRY, "force", "force = -1.0");
    assert_eq!(w.ehl(&["check", "case.toml"]).code, 1);
    let o = w.ehl(&["check", "case.toml", "--set", "load.force=30000"]);
    assert_eq!(o.code, 0, "{}", o.stderr);
    // a good case broken by a bad value: the key and the value are named
    let w = Work::new(DRY);
    w.expect_error(
        &["--set", "body1.poisson_ratio=0.5"],
        "body1.poisson_ratio",
        &["found 0.5"],
    );
    // a bare word is a string: kind=ehl then needs [motion]
    w.expect_error(&["--set", "kind=ehl"], "motion", &["missing"]);
    // inline tables and inf
    let o = w.ehl(&[
        "check",
        "case.toml",
        "--set",
        "body1.profile={ kind = \"crowned\", crown_radius = 0.5 }",
        "--set",
        "body2.length=inf",
    ]);
    assert_eq!(o.code, 0, "{}", o.stderr);
    // a parameter inside an inline table
    w.expect_error(
        &["--set", "body1.profile={ kind = \"crowned\" }"],
        "body1.profile.crown_radius",
        &["missing"],
    );
    // later --set wins
    let o = w.ehl(&[
        "check",
        "case.toml",
        "--set",
        "grid.nx=4",
        "--set",
        "grid.nx=64",
    ]);
    assert_eq!(o.code, 0, "{}", o.stderr);
}

#[test]
fn set_unknown_key_suggests() {
    let w = Work::new(DRY);
    w.expect_error(
        &["--set", "load.forse=5000"],
        "load.forse",
        &["did you mean `load.force`?", "--set load.forse=5000"],
    );
    w.expect_error(
        &["--set", "motion.slide_to_rol=0.1"],
        "motion.slide_to_rol",
        &["did you mean `motion.slide_to_roll`?"],
    );
    w.expect_error(
        &["--set", "features[0].depth=1e-8"],
        "features[0].depth",
        &["no [[features]]"],
    );
    // setting inside a value that is not a table
    w.expect_error(
        &["--set", "load.force.x=1"],
        "load.force.x",
        &["not a table"],
    );
}

#[test]
fn set_without_equals_is_a_usage_error() {
    let w = Work::new(DRY);
    let o = w.ehl(&["run", "case.toml", "--set", "load.force"]);
    assert_eq!(o.code, 2, "{}", o.stderr);
    assert!(o.stderr.contains("KEY=VALUE"), "{}", o.stderr);
    assert!(w.no_outputs());
}

#[test]
fn run_and_check_argument_errors() {
    let w = Work::new(DRY);
    for args in [
        vec!["run"],
        vec!["check"],
        vec!["run", "case.toml", "--bogus"],
        vec!["frobnicate", "case.toml"],
        vec![],
    ] {
        let o = w.ehl(&args);
        assert_eq!(o.code, 2, "{args:?}: {}", o.stderr);
        assert!(w.no_outputs());
    }
    let o = w.ehl(&["--help"]);
    assert_eq!(o.code, 0);
    assert!(o.stdout.contains("Exit status"), "{}", o.stdout);
    assert!(
        o.stdout.contains("did not converge"),
        "exit 3 documented: {}",
        o.stdout
    );
}

#[test]
fn sweep_argument_errors() {
    let w = Work::new(DRY);
    let usage: &[(&[&str], &str)] = &[
        (&[], "--vary"),
        (&["--vary", "load.force"], "KEY=START:STOP:N"),
        (&["--vary", "load.forse=1,2"], "did you mean `load.force`?"),
        (&["--vary", "load.force=1000:2000"], "START:STOP:N"),
        (&["--vary", "load.force=1000:2000:0"], "at least 1"),
        (&["--vary", "load.force=a:2000:3"], "is not a number"),
        (&["--vary", "load.force=1000:2000:2.5"], "whole number"),
        (&["--vary", "load.force=1000,,2000"], "empty value"),
        (
            &["--vary", "load.force=1,2", "--shard", "2/2"],
            "0 <= K < N",
        ),
        (&["--vary", "load.force=1,2", "--shard", "1"], "K/N"),
        (&["--vary", "load.force=1,2", "--jobs", "0"], "--jobs"),
        (
            &["--vary", "load.force=1,2", "--vary", "load.force=3"],
            "given twice",
        ),
    ];
    for (extra, fragment) in usage {
        let mut args = vec!["sweep", "case.toml"];
        args.extend_from_slice(extra);
        let o = w.ehl(&args);
        assert_eq!(o.code, 2, "{args:?}: {}", o.stderr);
        assert!(
            o.stderr.contains(fragment),
            "{args:?}: expected `{fragment}` in {}",
            o.stderr
        );
        assert!(w.no_outputs());
    }
}

#[test]
fn sweep_validates_every_point_before_solving() {
    let w = Work::new(DRY);
    // the third point (poisson_ratio = 0.5) is invalid: nothing is solved or created
    let o = w.ehl(&[
        "sweep",
        "case.toml",
        "--vary",
        "body1.poisson_ratio=0.2,0.3,0.5",
        "--out",
        "results",
    ]);
    assert_eq!(o.code, 1, "{}", o.stderr);
    assert!(
        o.stderr.starts_with(
            "error: sweep point p002_poisson_ratio=0.5: case.toml: body1.poisson_ratio:"
        ),
        "{}",
        o.stderr
    );
    assert!(o.stderr.contains("found 0.5"), "{}", o.stderr);
    assert!(w.no_outputs());
    // a range reaching a bad value
    let o = w.ehl(&["sweep", "case.toml", "--vary", "load.force=-1000:1000:3"]);
    assert_eq!(o.code, 1);
    assert!(o.stderr.contains("load.force"), "{}", o.stderr);
    assert!(o.stderr.contains("found -1000"), "{}", o.stderr);
    assert!(w.no_outputs());
    // --set errors are case errors too
    let o = w.ehl(&[
        "sweep",
        "case.toml",
        "--vary",
        "load.force=1000,2000",
        "--set",
        "grid.nxx=3",
    ]);
    assert_eq!(o.code, 1);
    assert!(o.stderr.contains("did you mean `grid.nx`?"), "{}", o.stderr);
    assert!(w.no_outputs());
}
