//! Round trips and guarantees of the writers: summary.json keys per the interface, fields.npz
//! read back with NpzReader, the csv profiles parsed back, fields.vtk header and byte counts,
//! atomic replacement, refusal of non-finite values.
//!
//! Every comparison of numbers is exact: npz and vtk store the f64 bits, the csv and json
//! writers use shortest round-trip formatting, so anything but equality is a bug.

use ehl::output::{synthetic, write_all};
use ndarray::{Array1, Array2};
use ndarray_npy::NpzReader;
use serde_json::Value;
use std::path::Path;

fn entries(p: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(p)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

#[test]
fn writes_every_file_and_replaces_an_old_folder() {
    let root = tempfile::tempdir().unwrap();
    let dir = root.path().join("a/b/out");
    std::fs::create_dir_all(&dir).unwrap();
    // an earlier ehl output (it holds the marker), with a file the new outputs do not have
    ehl::output::write_marker(&dir).unwrap();
    std::fs::write(dir.join("stale.txt"), "from an earlier run").unwrap();
    let (case, sol) = synthetic::ehl_ball(false);
    write_all(&dir, &case, &sol).unwrap();
    assert_eq!(
        entries(&dir),
        [
            ".ehl-output",
            "axial.csv",
            "centerline.csv",
            "centerline.png",
            "fields.npz",
            "fields.vtk",
            "film.png",
            "pressure.png",
            "summary.json"
        ]
    );
    // nothing else left beside it (no temporary or old folder)
    assert_eq!(entries(dir.parent().unwrap()), ["out"]);
    // a dry solution without film: no film.png, no film column
    let (case, mut sol) = synthetic::dry_ball();
    sol.fields.film = None;
    write_all(&dir, &case, &sol).unwrap();
    assert!(!dir.join("film.png").exists());
    let head = std::fs::read_to_string(dir.join("centerline.csv")).unwrap();
    assert_eq!(
        head.lines().next().unwrap(),
        "x_m,pressure_pa,deformation_m"
    );
}

#[test]
fn summary_json_has_the_interface_keys() {
    let root = tempfile::tempdir().unwrap();
    let keys_common = [
        "converged",
        "iterations",
        "wall_time_s",
        "load_n",
        "load_error",
        "max_pressure_pa",
        "max_pressure_at_m",
        "hertz_pressure_pa",
        "hertz_half_width_m",
    ];
    // lubricated
    let (case, sol) = synthetic::ehl_ball(false);
    let dir = root.path().join("ehl");
    write_all(&dir, &case, &sol).unwrap();
    let v: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap();
    for k in keys_common.iter().chain(&[
        "central_film_m",
        "min_film_m",
        "min_film_at_m",
        "friction_coefficient",
        "friction_force_n",
    ]) {
        assert!(v.get(*k).is_some(), "summary.json lacks `{k}`");
    }
    assert_eq!(v["version"], ehl::VERSION);
    assert_eq!(v["title"], case.title.as_str());
    assert_eq!(v["converged"], true);
    assert_eq!(
        v["max_pressure_pa"].as_f64().unwrap(),
        sol.summary.max_pressure_pa
    );
    assert_eq!(
        v["min_film_m"].as_f64().unwrap(),
        sol.summary.min_film_m.unwrap()
    );
    let at = v["max_pressure_at_m"].as_array().unwrap();
    assert_eq!(at.len(), 2);
    assert_eq!(at[1].as_f64().unwrap(), sol.summary.max_pressure_at_m[1]);
    assert!(v.get("approach_m").is_none() && v.get("contact_area_m2").is_none());
    // the resolved case, with its infinite lengths spelt "inf"
    let c = &v["case"];
    assert_eq!(c["kind"], "ehl");
    assert_eq!(c["body1"]["shape"], "ball");
    assert_eq!(c["body1"]["length"], "inf");
    assert_eq!(c["body2"]["radius"], "inf");
    assert_eq!(c["lubricant"]["viscosity_model"], "roelands");
    assert_eq!(c["lubricant"]["rheology"]["model"], "newtonian");
    assert_eq!(c["motion"]["entrainment_speed"].as_f64().unwrap(), 0.09);
    assert_eq!(c["grid"]["nx"], 96);
    assert_eq!(v["grid_m"]["nx"], 96);
    assert_eq!(v["grid_m"]["dx"].as_f64().unwrap(), sol.grid.dx);

    // dry infinite line
    let (case, sol) = synthetic::dry_infinite_line();
    let dir = root.path().join("dry");
    write_all(&dir, &case, &sol).unwrap();
    let v: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap();
    for k in keys_common.iter().chain(&["approach_m", "contact_area_m2"]) {
        assert!(v.get(*k).is_some(), "summary.json lacks `{k}`");
    }
    for k in ["central_film_m", "friction_coefficient", "friction_force_n"] {
        assert!(v.get(k).is_none(), "dry summary has `{k}`");
    }
    assert_eq!(v["case"]["body1"]["length"], "inf");
    assert_eq!(v["case"]["body1"]["profile"]["kind"], "straight");
    assert!(v["case"].get("motion").is_none() && v["case"].get("lubricant").is_none());
    assert_eq!(
        v["approach_m"].as_f64().unwrap(),
        sol.summary.approach_m.unwrap()
    );
}

#[test]
fn npz_reads_back_exactly() {
    let root = tempfile::tempdir().unwrap();
    for (case, sol) in [
        synthetic::ehl_ball(false),
        synthetic::dry_roller(),
        synthetic::dry_infinite_line(),
    ] {
        let dir = root.path().join("o");
        write_all(&dir, &case, &sol).unwrap();
        let mut npz = NpzReader::new(std::fs::File::open(dir.join("fields.npz")).unwrap()).unwrap();
        let mut names = npz.names().unwrap();
        names.sort();
        let mut expect = vec!["x", "y", "pressure", "deformation"];
        if sol.fields.film.is_some() {
            expect.push("film");
        }
        if sol.fields.viscosity.is_some() {
            expect.extend(["viscosity", "density"]);
        }
        let mut expect: Vec<String> = expect.iter().map(|s| format!("{s}.npy")).collect();
        expect.sort();
        // ndarray-npy stores each array as `<name>.npy`; names() reports the stored names
        let names: Vec<String> = names
            .iter()
            .map(|n| {
                if n.ends_with(".npy") {
                    n.clone()
                } else {
                    format!("{n}.npy")
                }
            })
            .collect();
        assert_eq!(names, expect);
        let (nx, ny) = (sol.grid.nx, sol.grid.ny);
        let x: Array1<f64> = npz.by_name("x").unwrap();
        let y: Array1<f64> = npz.by_name("y").unwrap();
        assert_eq!(x.to_vec(), sol.grid.xs());
        assert_eq!(y.to_vec(), sol.grid.ys());
        let check = |npz: &mut NpzReader<std::fs::File>, name: &str, field: &[f64]| {
            let a: Array2<f64> = npz.by_name(name).unwrap();
            assert_eq!(a.dim(), (ny, nx), "{name} shape");
            // row j, column i is the value at (x[i], y[j])
            for j in [0, ny / 2, ny - 1] {
                for i in [0, nx / 3, nx - 1] {
                    assert_eq!(a[[j, i]], field[j * nx + i], "{name}[{j},{i}]");
                }
            }
            assert_eq!(a.iter().copied().collect::<Vec<_>>(), field, "{name}");
        };
        check(&mut npz, "pressure", &sol.fields.pressure);
        check(&mut npz, "deformation", &sol.fields.deformation);
        if let Some(h) = &sol.fields.film {
            check(&mut npz, "film", h);
        }
        if let Some(e) = &sol.fields.viscosity {
            check(&mut npz, "viscosity", e);
            check(&mut npz, "density", sol.fields.density.as_ref().unwrap());
        }
    }
}

fn parse_csv(text: &str) -> (Vec<String>, Vec<Vec<f64>>) {
    let mut lines = text.lines();
    let head: Vec<String> = lines.next().unwrap().split(',').map(String::from).collect();
    let rows: Vec<Vec<f64>> = lines
        .map(|l| {
            let r: Vec<f64> = l.split(',').map(|s| s.parse::<f64>().unwrap()).collect();
            assert_eq!(r.len(), head.len(), "ragged row {l}");
            r
        })
        .collect();
    (head, rows)
}

#[test]
fn csv_profiles_parse_back() {
    let root = tempfile::tempdir().unwrap();
    let (case, sol) = synthetic::ehl_ball(false);
    let dir = root.path().join("o");
    write_all(&dir, &case, &sol).unwrap();
    let g = sol.grid;
    let (head, rows) = parse_csv(&std::fs::read_to_string(dir.join("centerline.csv")).unwrap());
    assert_eq!(
        head,
        [
            "x_m",
            "pressure_pa",
            "deformation_m",
            "film_m",
            "viscosity_pa_s",
            "density_kg_m3"
        ]
    );
    assert_eq!(rows.len(), g.nx);
    // 96 rows: y = 0 is a cell edge; the nearest centres are rows 47 and 48, the writer takes 47
    let j = 47;
    assert!((g.y(j)).abs() <= 0.5 * g.dy + 1e-18);
    for (i, r) in rows.iter().enumerate() {
        assert_eq!(r[0], g.x(i));
        assert_eq!(r[1], sol.fields.pressure[g.idx(i, j)]);
        assert_eq!(r[3], sol.fields.film.as_ref().unwrap()[g.idx(i, j)]);
        assert_eq!(r[5], sol.fields.density.as_ref().unwrap()[g.idx(i, j)]);
    }
    let (head, rows) = parse_csv(&std::fs::read_to_string(dir.join("axial.csv")).unwrap());
    assert_eq!(head, ["y_m", "pressure_pa", "deformation_m", "film_m"]);
    assert_eq!(rows.len(), g.ny);
    // the column through the pressure maximum: the maximum itself is in it
    let pmax = rows.iter().map(|r| r[1]).fold(f64::MIN, f64::max);
    assert_eq!(pmax, sol.summary.max_pressure_pa);
    for (j, r) in rows.iter().enumerate() {
        assert_eq!(r[0], g.y(j));
    }
    // infinite line: axial.csv has the single row, centerline all of x
    let (case, sol) = synthetic::dry_infinite_line();
    write_all(&dir, &case, &sol).unwrap();
    let (_, rows) = parse_csv(&std::fs::read_to_string(dir.join("axial.csv")).unwrap());
    assert_eq!(rows.len(), 1);
    assert_eq!(rows[0][1], sol.summary.max_pressure_pa);
    let (_, rows) = parse_csv(&std::fs::read_to_string(dir.join("centerline.csv")).unwrap());
    assert_eq!(
        rows.iter().map(|r| r[1]).collect::<Vec<_>>(),
        sol.fields.pressure
    );
}

/// Reads one ASCII line from `b` at `*pos`.
fn line(b: &[u8], pos: &mut usize) -> String {
    let end = b[*pos..].iter().position(|&c| c == b'\n').unwrap() + *pos;
    let s = String::from_utf8(b[*pos..end].to_vec()).unwrap();
    *pos = end + 1;
    s
}

fn doubles(b: &[u8], pos: &mut usize, n: usize) -> Vec<f64> {
    let v = (0..n)
        .map(|k| f64::from_be_bytes(b[*pos + 8 * k..*pos + 8 * k + 8].try_into().unwrap()))
        .collect();
    *pos += 8 * n;
    assert_eq!(b[*pos], b'\n', "binary block not followed by a newline");
    *pos += 1;
    v
}

#[test]
fn vtk_header_and_counts_are_consistent() {
    let root = tempfile::tempdir().unwrap();
    for (case, sol) in [synthetic::ehl_ball(false), synthetic::dry_infinite_line()] {
        let dir = root.path().join("o");
        write_all(&dir, &case, &sol).unwrap();
        let b = std::fs::read(dir.join("fields.vtk")).unwrap();
        let g = sol.grid;
        let mut pos = 0;
        assert_eq!(line(&b, &mut pos), "# vtk DataFile Version 3.0");
        let title = line(&b, &mut pos);
        assert!(
            title.len() < 256 && title.contains("pressure Pa"),
            "{title}"
        );
        assert_eq!(line(&b, &mut pos), "BINARY");
        assert_eq!(line(&b, &mut pos), "DATASET RECTILINEAR_GRID");
        assert_eq!(
            line(&b, &mut pos),
            format!("DIMENSIONS {} {} 1", g.nx, g.ny)
        );
        assert_eq!(line(&b, &mut pos), format!("X_COORDINATES {} double", g.nx));
        assert_eq!(doubles(&b, &mut pos, g.nx), g.xs());
        assert_eq!(line(&b, &mut pos), format!("Y_COORDINATES {} double", g.ny));
        assert_eq!(doubles(&b, &mut pos, g.ny), g.ys());
        assert_eq!(line(&b, &mut pos), "Z_COORDINATES 1 double");
        assert_eq!(doubles(&b, &mut pos, 1), [0.0]);
        assert_eq!(line(&b, &mut pos), format!("POINT_DATA {}", g.len()));
        let mut seen = Vec::new();
        while pos < b.len() {
            let head = line(&b, &mut pos);
            let name = head
                .strip_prefix("SCALARS ")
                .unwrap()
                .strip_suffix(" double 1")
                .unwrap()
                .to_string();
            assert_eq!(line(&b, &mut pos), "LOOKUP_TABLE default");
            let v = doubles(&b, &mut pos, g.len());
            let want: &[f64] = match name.as_str() {
                "pressure" => &sol.fields.pressure,
                "deformation" => &sol.fields.deformation,
                "film" => sol.fields.film.as_deref().unwrap(),
                "viscosity" => sol.fields.viscosity.as_deref().unwrap(),
                "density" => sol.fields.density.as_deref().unwrap(),
                other => panic!("unexpected field {other}"),
            };
            assert_eq!(v, want, "{name}");
            seen.push(name);
        }
        assert_eq!(pos, b.len());
        let n_expected = 3 + 2 * sol.fields.viscosity.is_some() as usize;
        assert_eq!(seen.len(), n_expected, "{seen:?}");
    }
}

#[test]
fn non_finite_values_are_refused_by_name_and_nothing_is_written() {
    let root = tempfile::tempdir().unwrap();
    let dir = root.path().join("out");
    let (case, good) = synthetic::ehl_ball(false);

    let mut sol = good.clone();
    sol.fields.pressure[1234] = f64::NAN;
    let e = write_all(&dir, &case, &sol).unwrap_err().to_string();
    assert!(
        e.contains("`pressure`") && e.contains("NaN") && e.contains("out"),
        "{e}"
    );

    let mut sol = good.clone();
    sol.fields.viscosity.as_mut().unwrap()[7] = f64::INFINITY;
    let e = write_all(&dir, &case, &sol).unwrap_err().to_string();
    assert!(e.contains("`viscosity`") && e.contains("inf"), "{e}");

    let mut sol = good.clone();
    sol.fields.film.as_mut().unwrap()[7] = f64::NEG_INFINITY;
    let e = write_all(&dir, &case, &sol).unwrap_err().to_string();
    assert!(e.contains("`film`"), "{e}");

    let mut sol = good.clone();
    sol.summary.load_error = f64::NAN;
    let e = write_all(&dir, &case, &sol).unwrap_err().to_string();
    assert!(e.contains("`load_error`"), "{e}");

    let mut sol = good.clone();
    sol.summary.min_film_at_m = Some([0.0, f64::INFINITY]);
    let e = write_all(&dir, &case, &sol).unwrap_err().to_string();
    assert!(e.contains("`min_film_at_m.1`"), "{e}");

    let mut sol = good.clone();
    sol.fields.deformation.pop();
    let e = write_all(&dir, &case, &sol).unwrap_err().to_string();
    assert!(e.contains("`deformation`") && e.contains("9215"), "{e}");

    // nothing was created: no folder, no temporary folder
    assert!(
        entries(root.path()).is_empty(),
        "{:?}",
        entries(root.path())
    );

    // an existing folder survives a refused write untouched
    write_all(&dir, &case, &good).unwrap();
    let before = std::fs::read(dir.join("summary.json")).unwrap();
    let mut sol = good.clone();
    sol.fields.density.as_mut().unwrap()[0] = f64::NAN;
    assert!(write_all(&dir, &case, &sol).is_err());
    assert_eq!(std::fs::read(dir.join("summary.json")).unwrap(), before);
    assert_eq!(entries(root.path()), ["out"]);
}

#[test]
fn film_may_be_infinite_where_there_is_no_material() {
    // beyond the end of the shorter roller the gap is +inf (crate convention): written, not refused
    let root = tempfile::tempdir().unwrap();
    let dir = root.path().join("out");
    let (case, mut sol) = synthetic::dry_roller();
    let nx = sol.grid.nx;
    for v in &mut sol.fields.film.as_mut().unwrap()[..3 * nx] {
        *v = f64::INFINITY;
    }
    write_all(&dir, &case, &sol).unwrap();
    let mut npz = NpzReader::new(std::fs::File::open(dir.join("fields.npz")).unwrap()).unwrap();
    let h: Array2<f64> = npz.by_name("film").unwrap();
    assert_eq!(h[[0, 0]], f64::INFINITY);
    let axial = std::fs::read_to_string(dir.join("axial.csv")).unwrap();
    assert!(axial.lines().nth(1).unwrap().ends_with(",inf"), "{axial}");
}

#[test]
fn an_unusable_target_is_an_error_naming_it() {
    let root = tempfile::tempdir().unwrap();
    let file = root.path().join("plain-file");
    std::fs::write(&file, "x").unwrap();
    let (case, sol) = synthetic::dry_ball();
    // the target exists as a file
    let e = write_all(&file, &case, &sol).unwrap_err().to_string();
    assert!(
        e.contains("plain-file") && e.contains("not a folder"),
        "{e}"
    );
    // the parent is a file
    let e = write_all(&file.join("out"), &case, &sol)
        .unwrap_err()
        .to_string();
    assert!(e.contains("plain-file"), "{e}");
    assert_eq!(entries(root.path()), ["plain-file"]);
}

/// Every file under `dir`, relative, sorted, with its bytes.
fn tree(dir: &Path) -> Vec<(String, Vec<u8>)> {
    fn walk(root: &Path, at: &Path, out: &mut Vec<(String, Vec<u8>)>) {
        for e in std::fs::read_dir(at).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                walk(root, &p, out);
            } else {
                let rel = p.strip_prefix(root).unwrap().to_string_lossy().into_owned();
                out.push((rel, std::fs::read(&p).unwrap()));
            }
        }
    }
    let mut out = Vec::new();
    walk(dir, dir, &mut out);
    out.sort_by(|a, b| a.0.cmp(&b.0));
    out
}

/// Solves an example through the streaming writer (which also keeps every frame in the
/// solution), writes the same solution with the in-memory writer, and asserts that the two
/// folders hold the same files, byte for byte, and that no spill file is left.
fn streamed_equals_in_memory(example: &str, sets: &[&str]) {
    let path = format!("{}/../../examples/{example}", env!("CARGO_MANIFEST_DIR"));
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    let case = ehl::case::load_file(Path::new(&path), &sets).unwrap();
    let root = tempfile::tempdir().unwrap();
    let (a, b) = (root.path().join("streamed"), root.path().join("in-memory"));
    let staging = ehl::output::Staging::begin(&a).unwrap();
    let mut stream = ehl::output::stream::TransientStream::new(&staging, &case).keeping_frames();
    let sol = ehl::run::solve_with(&case, &ehl::run::Silent, &mut stream).unwrap();
    let kept = sol.transient.as_ref().unwrap().frames.len();
    ehl::output::write_staged(staging, &case, &sol, Some(stream)).unwrap();
    write_all(&b, &case, &sol).unwrap();
    let (ta, tb) = (tree(&a), tree(&b));
    let names = |t: &[(String, Vec<u8>)]| t.iter().map(|f| f.0.clone()).collect::<Vec<_>>();
    assert_eq!(names(&ta), names(&tb), "{example}: the same files");
    for ((name, x), (_, y)) in ta.iter().zip(&tb) {
        assert!(
            x == y,
            "{example}: {name} differs ({} against {} bytes)",
            x.len(),
            y.len()
        );
    }
    assert!(
        names(&ta).iter().any(|n| n == "passage.gif") && kept > 2,
        "{example}: {kept} frames"
    );
    // nothing was left beside the output: the staging folder became it
    let left: Vec<String> = std::fs::read_dir(root.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(left.len(), 2, "{left:?}");
}

/// The streaming writer of transient runs writes what the in-memory writer writes: a line
/// contact with more frames than `passage.gif` shows (201 kept, 120 shown), a thermal line
/// (the extra timeline columns), and the thesis pit on a roller (the zoomed pictures, the
/// snapshots).
#[test]
fn streamed_transient_outputs_equal_the_in_memory_ones() {
    streamed_equals_in_memory("ehl_transient_line_groove.toml", &["grid.nx=128"]);
    streamed_equals_in_memory(
        "ehl_thermal_transient_groove.toml",
        &["grid.nx=128", "motion.travel.steps=12"],
    );
    streamed_equals_in_memory(
        "ehl_thesis_ch3_single_pit.toml",
        &[
            "grid.nx=48",
            "grid.ny=48",
            "motion.travel.steps=10",
            "output.snapshots=[-0.5e-3, 0.0]",
        ],
    );
}

/// A streamed run that fails leaves nothing: the staging folder is removed when dropped.
#[test]
fn a_dropped_staging_folder_leaves_nothing() {
    let root = tempfile::tempdir().unwrap();
    let dir = root.path().join("out");
    {
        let staging = ehl::output::Staging::begin(&dir).unwrap();
        std::fs::write(staging.path().join("timeline.csv"), "step\n").unwrap();
        assert!(staging.path().exists());
    }
    assert_eq!(std::fs::read_dir(root.path()).unwrap().count(), 0);
}
