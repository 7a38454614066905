//! Reliability of the program's input and output: no picture hangs a run, closed or full output
//! streams end the program without a panic, `--out` never deletes files ehl did not write and is
//! written by one process at a time, a sweep's size is bounded, messages name what the user gave,
//! and a case file that is not a regular file is refused instead of blocking.
//!
//! Every test that could block on the old behaviour runs the program with a time limit (the
//! process is killed and the test fails), so the suite never hangs.

mod common;
use common::*;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

fn examples() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples")
}

fn ehl_cmd(w: &Work, args: &[&str]) -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_ehl"));
    c.args(args).current_dir(w.path());
    c
}

/// Runs `cmd` with stdout and stderr into files, killing it after `limit`; panics then.
fn run_limited(w: &Work, mut cmd: Command, limit: Duration) -> Out {
    let (o, e) = (w.file(".stdout"), w.file(".stderr"));
    cmd.stdout(std::fs::File::create(&o).unwrap())
        .stderr(std::fs::File::create(&e).unwrap())
        .stdin(Stdio::null());
    let mut child = cmd.spawn().expect("run ehl");
    let start = Instant::now();
    let status = loop {
        if let Some(s) = child.try_wait().unwrap() {
            break s;
        }
        if start.elapsed() > limit {
            let _ = child.kill();
            let _ = child.wait();
            panic!("ehl did not finish within {limit:?}: {cmd:?}");
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    let out = Out {
        code: status.code().unwrap_or(-1),
        stdout: std::fs::read_to_string(&o).unwrap_or_default(),
        stderr: std::fs::read_to_string(&e).unwrap_or_default(),
    };
    let _ = std::fs::remove_file(o);
    let _ = std::fs::remove_file(e);
    out
}

fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

// ------------------------------------------------------------------ 1. pictures never hang

/// The second roller shifted along its axis by 2.5 mm (both are 4 mm long), so that the
/// centre row (the one nearest y = 0) lies on the first alone: the film there is +inf (no
/// material) all along the line, which used to loop forever inside plotters while drawing
/// centerline.png. (At 2 mm the second roller started at y = 0 and the centre row was a tie
/// between the rows at -+dy/2.)
#[test]
fn no_material_on_the_centre_row_does_not_hang_the_pictures() {
    let w = Work::new(DRY);
    let case = examples().join("dry_roller_mirror1_psi.toml");
    let case = case.to_str().unwrap();
    let args = [
        "run",
        case,
        "--set",
        "body2.axial_offset=2.5e-3",
        "--set",
        "grid.nx=32",
        "--set",
        "grid.ny=48",
        "--out",
        "results",
    ];
    let o = run_limited(&w, ehl_cmd(&w, &args), Duration::from_secs(240));
    assert!(o.code == 0 || o.code == 3, "{}", o.stderr);
    let png = w.file("results").join("centerline.png");
    assert!(std::fs::metadata(png).unwrap().len() > 0);
    // the case is the one meant: no material anywhere on the centre row
    let csv = std::fs::read_to_string(w.file("results").join("centerline.csv")).unwrap();
    let films: Vec<&str> = csv
        .lines()
        .skip(1)
        .map(|l| l.rsplit(',').next().unwrap())
        .collect();
    assert!(
        !films.is_empty() && films.iter().all(|f| *f == "inf"),
        "centre row films {films:?}"
    );
}

/// A killed run leaves `.results.tmp-PID-N`; the next write removes it when PID no longer runs,
/// and keeps those of running processes.
#[test]
fn stale_temp_folders_of_dead_runs_are_removed() {
    let w = Work::new(DRY);
    let dead = w.file(".results.tmp-999999999-0");
    let dead_old = w.file(".results.old-999999999-1");
    let alive = w.file(format!(".results.tmp-{}-0", std::process::id()).as_str());
    for d in [&dead, &dead_old, &alive] {
        std::fs::create_dir(d).unwrap();
        std::fs::write(d.join("summary.json"), "{}").unwrap();
    }
    let o = w.ehl(&["run", "case.toml", "--out", "results"]);
    assert!(o.code == 0 || o.code == 3, "{}", o.stderr);
    assert!(!dead.exists() && !dead_old.exists());
    assert!(alive.exists());
}

/// Starts `ehl run case.toml --out results` in `w`, its output into `.stdout` and `.stderr`.
#[cfg(unix)]
fn spawn_run(w: &Work) -> (std::process::Child, PathBuf, PathBuf) {
    let (o, e) = (w.file(".stdout"), w.file(".stderr"));
    let child = ehl_cmd(w, &["run", "case.toml", "--out", "results"])
        .stdout(std::fs::File::create(&o).unwrap())
        .stderr(std::fs::File::create(&e).unwrap())
        .spawn()
        .unwrap();
    (child, o, e)
}

/// Sends SIGTERM to `child` and waits for it to end (killed, and the test failed, 120 s after
/// `start`).
#[cfg(unix)]
fn terminate(child: &mut std::process::Child, start: Instant) -> std::process::ExitStatus {
    let killed = Command::new("kill")
        .args(["-TERM", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(killed.success());
    loop {
        if let Some(s) = child.try_wait().unwrap() {
            return s;
        }
        if start.elapsed() > Duration::from_secs(120) {
            let _ = child.kill();
            panic!("ehl did not stop on SIGTERM");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
}

/// SIGTERM while solving: exit 130, and nothing of the run is left (no lock file, no temporary
/// folder, no output folder).
#[cfg(unix)]
#[test]
fn sigterm_removes_what_the_run_had_started() {
    let w = Work::new(&edit(
        &edit(EHL, "nx = 64", "nx = 256"),
        "ny = 32",
        "ny = 128",
    ));
    let (mut child, o, e) = spawn_run(&w);
    let lock = w.file(".results.lock");
    let start = Instant::now();
    while !lock.exists() {
        if start.elapsed() > Duration::from_secs(60) || child.try_wait().unwrap().is_some() {
            let _ = child.kill();
            panic!("the run took no lock on its output before solving");
        }
        std::thread::sleep(Duration::from_millis(5));
    }
    let status = terminate(&mut child, start);
    if status.code() == Some(0) {
        // finished before the signal arrived: nothing to check
        return;
    }
    assert_eq!(status.code(), Some(130), "{status:?}");
    std::fs::remove_file(o).unwrap();
    std::fs::remove_file(e).unwrap();
    assert_eq!(names(w.path()), ["case.toml"]);
}

/// SIGTERM while a transient run streams its frames into the output's temporary folder:
/// exit 130, and neither that folder (its spill files, its `.vtr` frames) nor a lock nor an
/// output folder is left.
#[cfg(unix)]
#[test]
fn sigterm_during_a_streamed_transient_run_leaves_nothing() {
    let text = std::fs::read_to_string(examples().join("ehl_transient_line_groove.toml")).unwrap();
    let w = Work::new(&edit(
        &text,
        "travel =",
        "travel = { from = -1.2e-3, to = 1.0e-3, steps = 100000 }",
    ));
    let (mut child, o, e) = spawn_run(&w);
    // wait until many frames have been streamed (`.vtr` files in the temporary folder): the
    // solver keeps writing new ones while the signal handler empties the folder, which must
    // still go (a single removal pass left it behind)
    let start = Instant::now();
    let streaming = || {
        std::fs::read_dir(w.path()).unwrap().any(|d| {
            let d = d.unwrap();
            d.file_name().to_string_lossy().starts_with(".results.tmp-")
                && std::fs::read_dir(d.path().join("frames")).is_ok_and(|f| f.count() >= 500)
        })
    };
    while !streaming() {
        if start.elapsed() > Duration::from_secs(60) || child.try_wait().unwrap().is_some() {
            let _ = child.kill();
            panic!("no frame was streamed into the temporary folder");
        }
        std::thread::sleep(Duration::from_millis(5));
    }
    let status = terminate(&mut child, start);
    assert_eq!(status.code(), Some(130), "{status:?}");
    std::fs::remove_file(o).unwrap();
    std::fs::remove_file(e).unwrap();
    assert_eq!(names(w.path()), ["case.toml"]);
}

// ------------------------------------------------------------------ 2. closed and full streams

fn check_args() -> Vec<String> {
    vec![
        "check".into(),
        examples()
            .join("dry_ball_on_flat.toml")
            .to_string_lossy()
            .into_owned(),
    ]
}

/// `ehl check ... | head -0`: the reader is gone before ehl writes.
#[test]
fn closed_stdout_ends_quietly() {
    let w = Work::new(DRY);
    for args in [check_args(), vec!["--help".to_string()]] {
        // a pipe whose reader is gone before ehl starts
        let (reader, writer) = std::io::pipe().unwrap();
        drop(reader);
        let o = ehl_cmd(&w, &[])
            .args(&args)
            .stdout(writer)
            .stderr(Stdio::piped())
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(141), "{args:?}: {stderr}");
        assert!(stderr.is_empty(), "{args:?}: {stderr}");
    }
}

/// `ehl check missing.toml 2>&1 | true`: the error message cannot be written; no panic.
#[test]
fn closed_stderr_does_not_panic() {
    let w = Work::new(DRY);
    let (reader, writer) = std::io::pipe().unwrap();
    drop(reader);
    let status = ehl_cmd(&w, &["check", "missing.toml"])
        .stdout(Stdio::null())
        .stderr(writer)
        .status()
        .unwrap();
    assert_eq!(status.code(), Some(1));
}

/// `ehl check ... > /dev/full`: an error message and exit 1.
#[cfg(target_os = "linux")]
#[test]
fn full_stdout_is_an_error() {
    let w = Work::new(DRY);
    for args in [check_args(), vec!["--version".to_string()]] {
        let o = ehl_cmd(&w, &[])
            .args(&args)
            .stdout(
                std::fs::OpenOptions::new()
                    .write(true)
                    .open("/dev/full")
                    .unwrap(),
            )
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {stderr}");
        assert!(
            stderr.contains("standard output") && !stderr.contains("panicked"),
            "{stderr}"
        );
    }
}

// ------------------------------------------------------------------ 3. never delete user files

#[test]
fn out_never_replaces_a_folder_ehl_did_not_write() {
    let w = Work::new(DRY);
    std::fs::create_dir(w.file("mine")).unwrap();
    std::fs::write(w.file("mine/notes.txt"), "precious").unwrap();
    // the folder holding the case file itself
    std::fs::copy(w.file("case.toml"), w.file("mine/case.toml")).unwrap();
    let o = w.ehl(&["run", "mine/case.toml", "--out", "mine"]);
    assert_eq!(o.code, 1, "{}", o.stderr);
    assert!(
        o.stderr.contains("mine")
            && o.stderr.contains("did not write")
            && o.stderr.contains("--out"),
        "{}",
        o.stderr
    );
    assert_eq!(names(&w.file("mine")), ["case.toml", "notes.txt"]);
    assert_eq!(names(w.path()), ["case.toml", "mine"]);
    // the current folder and a parent given as `.` or `dir/..` are folders like any other
    for out in [".", "mine/.."] {
        let o = w.ehl(&["run", "case.toml", "--out", out]);
        assert_eq!(o.code, 1, "--out {out}: {}", o.stderr);
        assert!(
            o.stderr.contains("did not write"),
            "--out {out}: {}",
            o.stderr
        );
        assert_eq!(names(w.path()), ["case.toml", "mine"], "--out {out}");
    }

    // an empty folder is used, and then holds the marker: a second run replaces it
    std::fs::create_dir(w.file("empty")).unwrap();
    for _ in 0..2 {
        let o = w.ehl(&["run", "case.toml", "--out", "empty"]);
        assert!(o.code == 0 || o.code == 3, "{}", o.stderr);
    }
    let marker = std::fs::read_to_string(w.file("empty/.ehl-output")).unwrap();
    assert!(marker.starts_with("ehl "), "{marker}");
    // a user file added to an ehl folder does not make it the user's: the marker decides, and
    // the next run replaces the folder whole
    std::fs::write(w.file("empty/extra.txt"), "added").unwrap();
    let o = w.ehl(&["run", "case.toml", "--out", "empty"]);
    assert!(o.code == 0 || o.code == 3, "{}", o.stderr);
    assert!(w.file("empty/summary.json").is_file());
    assert!(w.file("empty/.ehl-output").is_file());
    assert!(!w.file("empty/extra.txt").exists());
}

/// A transient run (which streams its files into the output's temporary folder while it
/// solves) writes into `--out .` when `.` is an ehl output folder, as a steady run does: the
/// temporary folder sits beside the folder `.` names.
#[test]
fn a_streamed_transient_run_writes_into_out_dot() {
    let text = std::fs::read_to_string(examples().join("ehl_transient_line_groove.toml")).unwrap();
    let w = Work::new(&edit(
        &edit(
            &text,
            "travel =",
            "travel = { from = -1.2e-3, to = 1.0e-3, steps = 20 }",
        ),
        "nx =",
        "nx = 128",
    ));
    let o = w.ehl(&["run", "case.toml", "--out", "res", "-q"]);
    assert_eq!(o.code, 0, "{}", o.stderr);
    let o = Command::new(env!("CARGO_BIN_EXE_ehl"))
        .args(["run", "../case.toml", "--out", ".", "-q"])
        .current_dir(w.file("res"))
        .output()
        .unwrap();
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(w.file("res/timeline.csv").is_file() && w.file("res/frames.npz").is_file());
    assert_eq!(names(w.path()), ["case.toml", "res"]);
}

/// A sweep refuses, before solving, a point folder holding the user's files; the sweep folder
/// itself may hold other files (it is never replaced).
#[test]
fn sweep_point_folders_are_checked_before_solving() {
    let w = Work::new(DRY);
    std::fs::create_dir_all(w.file("study/p001_force=2000")).unwrap();
    std::fs::write(w.file("study/p001_force=2000/mine.txt"), "x").unwrap();
    std::fs::write(w.file("study/readme.txt"), "x").unwrap();
    let o = w.ehl(&[
        "sweep",
        "case.toml",
        "--vary",
        "load.force=1000,2000",
        "--out",
        "study",
    ]);
    assert_eq!(o.code, 1, "{}", o.stderr);
    assert!(o.stderr.contains("p001_force=2000"), "{}", o.stderr);
    // nothing solved
    assert_eq!(names(&w.file("study")), ["p001_force=2000", "readme.txt"]);
    assert_eq!(names(&w.file("study/p001_force=2000")), ["mine.txt"]);
}

/// A second process writing the same --out is refused at once.
#[test]
fn a_locked_output_is_refused() {
    let w = Work::new(DRY);
    let lock = std::fs::OpenOptions::new()
        .create(true)
        .truncate(false)
        .write(true)
        .open(w.file(".results.lock"))
        .unwrap();
    lock.try_lock().unwrap();
    let o = w.ehl(&["run", "case.toml", "--out", "results"]);
    assert_eq!(o.code, 1, "{}", o.stderr);
    assert!(
        o.stderr.contains("another ehl process is writing") && o.stderr.contains("results"),
        "{}",
        o.stderr
    );
    assert!(!w.file("results").exists());
    drop(lock);
    let o = w.ehl(&["run", "case.toml", "--out", "results"]);
    assert!(o.code == 0 || o.code == 3, "{}", o.stderr);
    // the lock file goes with the run
    assert_eq!(names(w.path()), ["case.toml", "results"]);
}

/// Two shards into one sweep folder at the same time: both succeed, sweep.csv holds every point.
#[test]
fn concurrent_shards_combine() {
    let w = Work::new(DRY);
    let shard = |k: &str| {
        ehl_cmd(
            &w,
            &[
                "sweep",
                "case.toml",
                "--vary",
                "load.force=1000:4000:4",
                "--out",
                "study",
                "--jobs",
                "1",
                "--shard",
                k,
            ],
        )
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap()
    };
    let (a, b) = (shard("0/2"), shard("1/2"));
    for c in [a, b] {
        let o = c.wait_with_output().unwrap();
        assert_eq!(
            o.status.code(),
            Some(0),
            "{}",
            String::from_utf8_lossy(&o.stderr)
        );
    }
    let csv = std::fs::read_to_string(w.file("study/sweep.csv")).unwrap();
    assert_eq!(csv.lines().count(), 5, "{csv}");
    assert!(!names(&w.file("study")).iter().any(|n| n.contains(".tmp")));
}

// ------------------------------------------------------------------ 4. bounded sweeps

#[test]
fn sweep_size_is_bounded_before_anything_is_made() {
    let w = Work::new(DRY);
    let o = w.ehl(&[
        "sweep",
        "case.toml",
        "--vary",
        "load.force=1:2:100000000000",
    ]);
    assert_eq!(o.code, 2, "{}", o.stderr);
    assert!(
        o.stderr.contains("--vary")
            && o.stderr.contains("load.force")
            && o.stderr.contains("100000"),
        "{}",
        o.stderr
    );
    let o = w.ehl(&[
        "sweep",
        "case.toml",
        "--vary",
        "load.force=1000:2000:1000",
        "--vary",
        "body1.radius=0.01:0.02:1000",
    ]);
    assert_eq!(o.code, 2, "{}", o.stderr);
    assert!(
        o.stderr.contains("--vary") && o.stderr.contains("100000"),
        "{}",
        o.stderr
    );
    assert!(w.no_outputs());
}

// ------------------------------------------------------------------ 5. messages

#[test]
fn non_finite_range_ends_are_refused_by_name() {
    let w = Work::new(DRY);
    for spec in [
        "load.force=nan:inf:3",
        "load.force=1000:inf:3",
        "load.force=-inf:1:2",
    ] {
        let o = w.ehl(&["sweep", "case.toml", "--vary", spec]);
        assert_eq!(o.code, 2, "{spec}: {}", o.stderr);
        assert!(
            o.stderr.contains("not a finite number") && o.stderr.contains("load.force"),
            "{spec}: {}",
            o.stderr
        );
        assert!(!o.stderr.contains("NaN"), "{}", o.stderr);
    }
}

#[test]
fn out_under_a_file_says_so() {
    let w = Work::new(DRY);
    std::fs::write(w.file("plain"), "x").unwrap();
    for cmd in [
        vec!["run", "case.toml", "--out", "plain/results"],
        vec![
            "sweep",
            "case.toml",
            "--vary",
            "load.force=1000,2000",
            "--out",
            "plain/study",
        ],
    ] {
        let o = w.ehl(&cmd);
        assert_eq!(o.code, 1, "{}", o.stderr);
        assert!(
            o.stderr.contains("`plain` is a file, not a folder") && !o.stderr.contains("os error"),
            "{}",
            o.stderr
        );
    }
}

/// Under a read-only folder the message names the --out given and says why. (Skipped when the
/// tests run as root, who may write anywhere.)
#[cfg(unix)]
#[test]
fn out_under_a_read_only_folder_names_it() {
    use std::os::unix::fs::PermissionsExt;
    let w = Work::new(DRY);
    let ro = w.file("ro");
    std::fs::create_dir(&ro).unwrap();
    std::fs::set_permissions(&ro, std::fs::Permissions::from_mode(0o555)).unwrap();
    if std::fs::write(ro.join("probe"), "x").is_ok() {
        return; // root
    }
    let o = w.ehl(&["run", "case.toml", "--out", "ro/results"]);
    std::fs::set_permissions(&ro, std::fs::Permissions::from_mode(0o755)).unwrap();
    assert_eq!(o.code, 1, "{}", o.stderr);
    assert!(
        o.stderr.starts_with("error: writing ro/results: ")
            && o.stderr.contains("permission denied")
            && !o.stderr.contains(".tmp-"),
        "{}",
        o.stderr
    );
}

// ------------------------------------------------------------------ 6. case files

#[cfg(unix)]
#[test]
fn a_fifo_or_device_as_case_file_is_refused_without_blocking() {
    let w = Work::new(DRY);
    let made = Command::new("mkfifo").arg(w.file("pipe.toml")).status();
    if made.is_ok_and(|s| s.success()) {
        for cmd in [
            vec!["check", "pipe.toml"],
            vec!["sweep", "pipe.toml", "--vary", "load.force=1000,2000"],
        ] {
            let o = run_limited(&w, ehl_cmd(&w, &cmd), Duration::from_secs(30));
            assert_eq!(o.code, 1, "{}", o.stderr);
            assert!(
                o.stderr
                    .starts_with("error: pipe.toml: cannot read the case file")
                    && o.stderr.contains("FIFO"),
                "{}",
                o.stderr
            );
        }
    }
    let o = run_limited(
        &w,
        ehl_cmd(&w, &["run", "/dev/zero"]),
        Duration::from_secs(30),
    );
    assert_eq!(o.code, 1, "{}", o.stderr);
    assert!(o.stderr.contains("device"), "{}", o.stderr);
    assert!(w.no_outputs());
}

#[test]
fn a_huge_case_file_is_refused() {
    let w = Work::new(DRY);
    let f = std::fs::File::create(w.file("huge.toml")).unwrap();
    f.set_len(17 * 1024 * 1024).unwrap();
    for cmd in [
        vec!["check", "huge.toml"],
        vec!["sweep", "huge.toml", "--vary", "load.force=1000,2000"],
    ] {
        let o = w.ehl(&cmd);
        assert_eq!(o.code, 1, "{}", o.stderr);
        assert!(o.stderr.contains("16 MiB"), "{}", o.stderr);
    }
}
