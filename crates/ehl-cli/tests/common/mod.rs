//! Helpers for the CLI tests: run the built `ehl` binary in a temporary folder.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::Command;

/// The thesis chapter 1 dry case (Table 1.1) on a coarse grid: R1 = R2 = 10 mm, L = 4 mm,
/// F = 30 kN, E = 200 GPa, nu = 0.3.
pub const DRY: &str = r#"title = "thesis chapter 1"
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
nx = 32
ny = 32
"#;

/// The thesis chapter 2 EHL case on a coarse grid.
pub const EHL: &str = r#"title = "thesis chapter 2"
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
slide_to_roll = 0.0

[lubricant]
viscosity = 0.04
pressure_viscosity_coefficient = 15.9e-9
density = 846.0

[grid]
nx = 64
ny = 32
"#;

pub struct Out {
    pub code: i32,
    pub stdout: String,
    pub stderr: String,
}

/// A temporary working folder holding `case.toml`.
pub struct Work {
    pub dir: tempfile::TempDir,
}

impl Work {
    pub fn new(case: &str) -> Work {
        let dir = tempfile::tempdir().expect("temp dir");
        std::fs::write(dir.path().join("case.toml"), case).expect("write case");
        Work { dir }
    }

    pub fn path(&self) -> &Path {
        self.dir.path()
    }

    pub fn file(&self, name: &str) -> PathBuf {
        self.dir.path().join(name)
    }

    /// Runs `ehl args...` with the work folder as the current directory.
    pub fn ehl(&self, args: &[&str]) -> Out {
        let o = Command::new(env!("CARGO_BIN_EXE_ehl"))
            .args(args)
            .current_dir(self.path())
            .output()
            .expect("run ehl");
        Out {
            code: o.status.code().unwrap_or(-1),
            stdout: String::from_utf8_lossy(&o.stdout).into_owned(),
            stderr: String::from_utf8_lossy(&o.stderr).into_owned(),
        }
    }

    /// True if nothing but the case file (and other inputs written by the test) is in the folder:
    /// no `out/` and no folder given by `--out`.
    pub fn no_outputs(&self) -> bool {
        !self.file("out").exists() && !self.file("results").exists()
    }

    /// `ehl run case.toml [extra...]` must fail with exit status 1, print
    /// `error: case.toml: <key>: ...` containing every fragment, and leave no output folder.
    #[track_caller]
    pub fn expect_error(&self, extra: &[&str], key: &str, fragments: &[&str]) -> String {
        let mut args = vec!["run", "case.toml"];
        args.extend_from_slice(extra);
        let o = self.ehl(&args);
        assert_eq!(o.code, 1, "exit status for {args:?}; stderr: {}", o.stderr);
        let head = format!("error: case.toml: {key}: ");
        assert!(
            o.stderr.starts_with(&head),
            "expected the message to start with `{head}`, got: {}",
            o.stderr
        );
        for f in fragments {
            assert!(o.stderr.contains(f), "expected `{f}` in: {}", o.stderr);
        }
        assert!(self.no_outputs(), "an output folder was created");
        // the same case through --out
        let mut args2 = args.clone();
        args2.extend_from_slice(&["--out", "results"]);
        let o2 = self.ehl(&args2);
        assert_eq!(o2.code, 1);
        assert!(self.no_outputs(), "an output folder was created with --out");
        o.stderr
    }
}

/// `base` with the first line starting with `old` after the line `header` (e.g. `[body2]`; ""
/// for the whole file) replaced by `new` (`new` empty: the line is removed). Panics if no line
/// matched, so that a test cannot silently check the unedited case.
pub fn edit_in(base: &str, header: &str, old: &str, new: &str) -> String {
    let mut seen_header = header.is_empty();
    let mut done = false;
    let text = base
        .lines()
        .filter_map(|l| {
            if l.trim() == header {
                seen_header = true;
            }
            if seen_header && !done && l.starts_with(old) {
                done = true;
                (!new.is_empty()).then(|| new.to_string())
            } else {
                Some(l.to_string())
            }
        })
        .collect::<Vec<_>>()
        .join("\n")
        + "\n";
    assert!(done, "no line starting with `{old}` after `{header}`");
    text
}

/// `base` with the first line starting with `old` replaced by `new`.
pub fn edit(base: &str, old: &str, new: &str) -> String {
    edit_in(base, "", old, new)
}

/// A work folder whose case is `base` edited by [`edit`].
pub fn bad(base: &str, old: &str, new: &str) -> Work {
    Work::new(&edit(base, old, new))
}
