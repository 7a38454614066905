//! The memory limit through the environment override, so that the test does not depend on the
//! machine's memory.

use std::process::Command;

fn example(name: &str) -> String {
    format!("{}/../../examples/{name}", env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn a_case_over_the_memory_limit_is_refused_naming_the_grid_key() {
    let out = Command::new(env!("CARGO_BIN_EXE_ehl"))
        .args(["check", &example("dry_ball_on_flat.toml")])
        .env("EHL_MEMORY_LIMIT", "1e6")
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.contains("grid.nx") && err.contains("1.0 MB"), "{err}");
    // the same case within the limit is accepted
    let out = Command::new(env!("CARGO_BIN_EXE_ehl"))
        .args(["check", &example("dry_ball_on_flat.toml")])
        .env("EHL_MEMORY_LIMIT", "1e10")
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0));
    // a limit that is no positive number is an error, not ignored (a scan: "abc", "-5")
    for bad in ["abc", "-5", "0"] {
        let out = Command::new(env!("CARGO_BIN_EXE_ehl"))
            .args(["check", &example("dry_ball_on_flat.toml")])
            .env("EHL_MEMORY_LIMIT", bad)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{bad}: {err}");
        assert!(
            err.contains("EHL_MEMORY_LIMIT") && err.contains("positive number of bytes"),
            "{err}"
        );
    }
}
