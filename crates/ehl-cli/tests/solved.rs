//! `ehl run` and `ehl sweep` end to end: a solved run, a non-converged run (exit 3, outputs and
//! `converged = false` still written), sweeps with shards, and the sweep bookkeeping (rerun skips
//! finished points, sweep.csv is rebuilt from every finished folder so shards combine).

mod common;
use common::*;

fn write_summary(w: &Work, folder: &str, json: &str) {
    let dir = w.file("results").join(folder);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("summary.json"), json).unwrap();
}

fn read_csv(w: &Work) -> Vec<Vec<String>> {
    std::fs::read_to_string(w.file("results").join("sweep.csv"))
        .unwrap()
        .lines()
        .map(|l| l.split(',').map(|c| c.to_string()).collect())
        .collect()
}

#[test]
fn sweep_skips_finished_points_and_rebuilds_the_csv() {
    let w = Work::new(DRY);
    // two of three points finished earlier (e.g. by other shards)
    write_summary(
        &w,
        "p000_force=1000",
        r#"{"converged": true, "iterations": 12, "load_n": 1000.0, "max_pressure_pa": 1.2e9, "approach_m": 3.5e-6, "max_von_mises_pa": 7.1e8, "life_ratio": 0.97}"#,
    );
    write_summary(
        &w,
        "p002_force=3000",
        r#"{"converged": false, "iterations": 500, "load_n": 2999.0, "max_pressure_pa": 2.0e9, "approach_m": 8.1e-6}"#,
    );
    // shard 0/2 holds points 0 and 2: both finished, so nothing is solved
    let o = w.ehl(&[
        "sweep",
        "case.toml",
        "--vary",
        "load.force=1000:3000:3",
        "--out",
        "results",
        "--shard",
        "0/2",
    ]);
    assert_eq!(o.code, 0, "{}", o.stderr);
    assert!(o.stdout.contains("2 already done"), "{}", o.stdout);
    assert!(
        o.stdout.contains("sweep.csv holds 2 of 3 points"),
        "{}",
        o.stdout
    );
    let rows = read_csv(&w);
    let header = &rows[0];
    assert_eq!(header[0], "load.force");
    assert_eq!(header[1], "converged");
    assert_eq!(header.last().unwrap(), "folder");
    let col = |name: &str| header.iter().position(|h| h == name).unwrap();
    assert_eq!(rows.len(), 3, "header + 2 finished points");
    assert_eq!(rows[1][0], "1000");
    assert_eq!(rows[1][col("converged")], "true");
    assert_eq!(rows[1][col("iterations")], "12");
    assert_eq!(rows[1][col("approach_m")], "3.5e-6");
    // the stress and fatigue figures are columns too (a scan found them missing)
    assert_eq!(
        rows[1][col("max_von_mises_pa")].parse::<f64>().unwrap(),
        7.1e8
    );
    assert_eq!(rows[1][col("life_ratio")], "0.97");
    assert_eq!(
        rows[1][col("central_film_m")],
        "",
        "absent figures are empty cells"
    );
    assert_eq!(rows[2][0], "3000");
    assert_eq!(rows[2][col("converged")], "false");
    assert_eq!(rows[2][col("folder")], "p002_force=3000");
    // figures nested under "summary" are found too
    write_summary(
        &w,
        "p001_force=2000",
        r#"{"summary": {"converged": true, "iterations": 9, "load_n": 2000.0}, "version": "0.1.0"}"#,
    );
    let o = w.ehl(&[
        "sweep",
        "case.toml",
        "--vary",
        "load.force=1000:3000:3",
        "--out",
        "results",
        "--shard",
        "1/2",
    ]);
    assert_eq!(o.code, 0, "{}", o.stderr);
    let rows = read_csv(&w);
    assert_eq!(rows.len(), 4);
    assert_eq!(rows[2][0], "2000");
    assert_eq!(rows[2][col("iterations")], "9");
}

#[test]
fn run_writes_outputs_and_exits_0() {
    let w = Work::new(DRY);
    let o = w.ehl(&["run", "case.toml", "--quiet"]);
    assert_eq!(o.code, 0, "{}", o.stderr);
    assert!(o.stdout.contains("converged"), "{}", o.stdout);
    let dir = w.file("out").join("case");
    for f in [
        "summary.json",
        "fields.npz",
        "centerline.csv",
        "pressure.png",
    ] {
        assert!(dir.join(f).is_file(), "{f} missing");
    }
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap();
    assert_eq!(s["converged"], true);
    // --out and --set
    let o = w.ehl(&[
        "run",
        "case.toml",
        "--out",
        "results",
        "--set",
        "load.force=20000",
    ]);
    assert_eq!(o.code, 0, "{}", o.stderr);
    assert!(w.file("results").join("summary.json").is_file());
}

#[test]
fn run_not_converged_exits_3_with_outputs() {
    let w = Work::new(DRY);
    let o = w.ehl(&[
        "run",
        "case.toml",
        "--out",
        "results",
        "--set",
        "solver.max_iterations=1",
        "--set",
        "solver.tolerance=1e-14",
    ]);
    assert_eq!(o.code, 3, "{}", o.stderr);
    let s: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(w.file("results").join("summary.json")).unwrap(),
    )
    .unwrap();
    assert_eq!(s["converged"], false);
}

#[test]
fn sweep_solves_every_point_and_shards_combine() {
    let w = Work::new(DRY);
    let sweep = |shard: &str| {
        w.ehl(&[
            "sweep",
            "case.toml",
            "--vary",
            "load.force=10000:30000:3",
            "--vary",
            "body2.radius=0.01,0.02",
            "--out",
            "results",
            "--jobs",
            "2",
            "--shard",
            shard,
        ])
    };
    let o = sweep("0/2");
    assert_eq!(o.code, 0, "{}", o.stderr);
    assert_eq!(read_csv(&w).len(), 1 + 3, "shard 0/2 holds points 0, 2, 4");
    let o = sweep("1/2");
    assert_eq!(o.code, 0, "{}", o.stderr);
    let rows = read_csv(&w);
    assert_eq!(rows.len(), 1 + 6);
    assert_eq!(rows[0][0], "load.force");
    assert_eq!(rows[0][1], "body2.radius");
    // the integrated load follows the varied force (load balance to the solver tolerance)
    let col = rows[0].iter().position(|h| h == "load_n").unwrap();
    for r in &rows[1..] {
        let f: f64 = r[0].parse().unwrap();
        let load: f64 = r[col].parse().unwrap();
        assert!((load / f - 1.0).abs() < 1e-4, "{r:?}");
    }
    // a rerun solves nothing
    let o = sweep("0/1");
    assert_eq!(o.code, 0);
    assert!(o.stdout.contains("6 already done"), "{}", o.stdout);
    assert_eq!(read_csv(&w).len(), 7);
    assert!(w
        .file("results")
        .join("p005_force=30000_radius=0.02")
        .join("summary.json")
        .is_file());
}
