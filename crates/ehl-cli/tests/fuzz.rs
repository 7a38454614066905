//! Seeded mutation fuzzing of case files and command lines (issue 8).
//!
//! Every shipped example (`examples/*.toml`) is mutated by proptest strategies with a fixed
//! seed: keys set to extreme, wrong-typed or nonsensical values (0, -1, 1e-300, 1e300, inf, nan,
//! the largest integers, strings, arrays, tables), values scaled by powers of ten, keys and whole
//! tables removed, unknown keys added, and the text itself cut, doubled or garbled. Each mutant
//! then goes through the program, and the oracle holds it to the reliability standard:
//!
//! * `check` mutants (in-process through the library, and a sample through the `ehl check`
//!   binary): no panic; an accepted case prints no NaN; a refusal names the file and, for a
//!   case error, a key;
//! * `run` mutants (small grids, through the `ehl run` binary, each under a timeout): no panic,
//!   no hang, exit status 0, 1, 3 or 4; a refusal names the file; a written output folder has no
//!   NaN anywhere (`fields.npz`, the csv files, `summary.json`), no negative film, and the only
//!   infinity is the documented `+inf` film where there is no material; a refused run leaves
//!   no output folder and no temporary folder; the user's own files beside the case (and in an
//!   `--out` folder the user pointed at) are never lost.
//!
//! The bounded run is part of the default suite. The long run behind the documented command
//!
//! ```sh
//! EHL_FUZZ_CHECKS=10000 EHL_FUZZ_RUNS=1000 cargo test --release -p ehl-cli --test fuzz -- --ignored --nocapture
//! ```
//!
//! prints the counts recorded in `docs/reliability.md` (`EHL_FUZZ_SEED` picks another seed).

mod common;

use proptest::strategy::{Strategy, ValueTree};
use proptest::test_runner::{Config, RngSeed, TestRunner};
use std::panic::AssertUnwindSafe;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::Mutex;
use std::time::{Duration, Instant};
use toml::{Table, Value};

/// The shipped examples: (file name, text).
fn corpus() -> Vec<(String, String)> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples");
    let mut v: Vec<(String, String)> = std::fs::read_dir(&dir)
        .expect("examples folder")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .map(|p| {
            (
                p.file_name().unwrap().to_string_lossy().into_owned(),
                std::fs::read_to_string(&p).expect("read example"),
            )
        })
        .collect();
    v.sort();
    assert!(
        v.len() >= 10,
        "expected the shipped examples, found {}",
        v.len()
    );
    v
}

/// A value that a mutation writes into a key.
#[derive(Debug, Clone)]
enum Val {
    /// an extreme or boundary number (index into [`NUMBERS`])
    Number(usize),
    /// the key's own value times 10^k (or a plain number if it has none)
    Scaled(i32),
    /// the key's own value, negated
    Negated,
    /// a wrong-typed or odd value (index into [`OTHERS`])
    Other(usize),
}

const NUMBERS: &[f64] = &[
    0.0,
    -0.0,
    -1.0,
    1.0,
    0.5,
    2.0,
    1e-300,
    1e-30,
    1e-9,
    1e9,
    1e30,
    1e300,
    f64::INFINITY,
    f64::NEG_INFINITY,
    f64::NAN,
    f64::MAX,
    f64::MIN_POSITIVE,
    4.9e-324,
];

/// TOML value texts of other kinds.
const OTHERS: &[&str] = &[
    "0",
    "-1",
    "1",
    "3",
    "9223372036854775807",
    "-9223372036854775808",
    "1000000000",
    "\"\"",
    "\" \"",
    "\"abc\"",
    "\"1e999\"",
    "\"30mm\"",
    "\"roller\"",
    "\"ball\"",
    "\"flat\"",
    "\"dry\"",
    "\"ehl\"",
    "\"crowned\"",
    "\"straight\"",
    "\"carreau\"",
    "\"eyring\"",
    "\"barus\"",
    "\"constant\"",
    "\"pit\"",
    "true",
    "false",
    "[]",
    "[1, 2]",
    "{}",
    "1979-05-27T07:32:00Z",
    "{ kind = \"crowned\" }",
    "{ kind = \"crowned\", crown_radius = 0.5 }",
    "{ kind = \"logarithmic\", load = 8000.0 }",
    "{ kind = \"rounded-edge\", edge_length = 1e-3, edge_radius = 0.01 }",
    "{ kind = \"chamfer\", edge_length = 0.5e-3, angle = 0.01 }",
    "{ model = \"carreau\", shear_modulus = 4.5e6, power_law_index = 0.57, limiting_shear_coefficient = 0.06 }",
    "{ model = \"eyring\", eyring_stress = 5e6, limiting_shear_coefficient = 0.06 }",
    "{ from = -1e-3, to = 1e-3, steps = 10 }",
    "[{ kind = \"pit\", width = 1e-4, length = 1e-4, depth = 1e-7 }]",
];

/// One change to a case.
#[derive(Debug, Clone)]
enum Mutation {
    /// set the key (index into the candidate keys, modulo their number) to a value
    Set(usize, Val),
    /// remove the key
    Remove(usize),
    /// add a key no schema knows, next to an existing one
    Unknown(usize),
    /// garble the serialised text: (operation, position as a fraction of the length)
    Text(u8, f64),
    /// multiply one of the case's own numbers (index modulo their number) by a plausible
    /// factor: a variant a user might really run
    Factor(usize, f64),
}

#[derive(Debug, Clone)]
struct Mutant {
    example: usize,
    mutations: Vec<Mutation>,
}

fn val_strategy() -> impl Strategy<Value = Val> {
    proptest::prop_oneof![
        3 => (0..NUMBERS.len()).prop_map(Val::Number),
        3 => (-12i32..=12).prop_map(Val::Scaled),
        1 => proptest::strategy::Just(Val::Negated),
        3 => (0..OTHERS.len()).prop_map(Val::Other),
    ]
}

fn mutation_strategy(text: bool) -> impl Strategy<Value = Mutation> {
    let any_key = 0usize..10_000;
    let text_weight = if text { 1 } else { 0 };
    proptest::prop_oneof![
        8 => (any_key.clone(), val_strategy()).prop_map(|(k, v)| Mutation::Set(k, v)),
        2 => any_key.clone().prop_map(Mutation::Remove),
        1 => any_key.prop_map(Mutation::Unknown),
        text_weight => (0u8..4, 0.0..1.0f64).prop_map(|(o, p)| Mutation::Text(o, p)),
    ]
}

fn mutant_strategy(examples: usize, text: bool) -> impl Strategy<Value = Mutant> {
    (
        0..examples,
        proptest::collection::vec(mutation_strategy(text), 1..=3),
    )
        .prop_map(|(example, mutations)| Mutant { example, mutations })
}

/// Run mutants: mostly plausible variants of the example (its own numbers scaled by 0.1..10),
/// with one in four drawn from the check pool (extreme, wrong-typed, removed keys).
fn run_mutant_strategy(examples: usize) -> impl Strategy<Value = Mutant> {
    const FACTORS: &[f64] = &[0.1, 0.3, 0.5, 0.8, 1.25, 2.0, 3.0, 10.0];
    let plausible =
        (0usize..10_000, 0..FACTORS.len()).prop_map(|(k, f)| Mutation::Factor(k, FACTORS[f]));
    let one = proptest::prop_oneof![
        3 => plausible,
        1 => mutation_strategy(false),
    ];
    (0..examples, proptest::collection::vec(one, 1..=2))
        .prop_map(|(example, mutations)| Mutant { example, mutations })
}

/// The dotted paths of every leaf and table of `t` (`features[0].x` for arrays of tables).
fn paths(t: &Table, prefix: &str, out: &mut Vec<String>) {
    for (k, v) in t {
        let p = if prefix.is_empty() {
            k.clone()
        } else {
            format!("{prefix}.{k}")
        };
        out.push(p.clone());
        match v {
            Value::Table(s) => paths(s, &p, out),
            Value::Array(a) => {
                for (i, e) in a.iter().enumerate() {
                    if let Value::Table(s) = e {
                        paths(s, &format!("{p}[{i}]"), out);
                    }
                }
            }
            _ => {}
        }
    }
}

/// Keys a mutation may touch in `t`: its own, then every key of the schema.
fn candidate_keys(t: &Table) -> Vec<String> {
    let mut keys = Vec::new();
    paths(t, "", &mut keys);
    for k in ehl::case::schema::all_keys() {
        let k = k.replace("[]", "[0]");
        if !keys.contains(&k) {
            keys.push(k);
        }
    }
    keys
}

/// Splits `features[0].x` into segments `features`, `[0]`, `x`.
fn segments(path: &str) -> Vec<String> {
    let mut out = Vec::new();
    for part in path.split('.') {
        match part.split_once('[') {
            Some((name, idx)) => {
                out.push(name.to_string());
                out.push(format!("[{}", idx));
            }
            None => out.push(part.to_string()),
        }
    }
    out
}

/// The table that holds the last segment of `path`, created on the way if `create`.
fn parent_mut<'a>(t: &'a mut Table, segs: &[String], create: bool) -> Option<&'a mut Table> {
    let mut cur = t;
    let mut i = 0;
    while i + 1 < segs.len() {
        let name = &segs[i];
        let next_is_index = segs[i + 1].starts_with('[');
        if next_is_index {
            let idx: usize = segs[i + 1]
                .trim_matches(|c| c == '[' || c == ']')
                .parse()
                .ok()?;
            if create && !cur.contains_key(name) {
                cur.insert(name.clone(), Value::Array(vec![Value::Table(Table::new())]));
            }
            let arr = cur.get_mut(name)?.as_array_mut()?;
            if create && arr.len() <= idx {
                arr.resize(idx + 1, Value::Table(Table::new()));
            }
            cur = arr.get_mut(idx)?.as_table_mut()?;
            i += 2;
            if i >= segs.len() {
                return None;
            }
            continue;
        }
        if create && !cur.get(name).is_some_and(|v| v.is_table()) {
            cur.insert(name.clone(), Value::Table(Table::new()));
        }
        cur = cur.get_mut(name)?.as_table_mut()?;
        i += 1;
    }
    Some(cur)
}

fn value_for(v: &Val, old: Option<&Value>) -> Value {
    let old_num = match old {
        Some(Value::Float(f)) => Some(*f),
        Some(Value::Integer(i)) => Some(*i as f64),
        _ => None,
    };
    match v {
        Val::Number(i) => Value::Float(NUMBERS[*i]),
        Val::Scaled(k) => match old {
            Some(Value::Integer(i)) if *k >= 0 && *k <= 6 => {
                Value::Integer(i.saturating_mul(10i64.pow(*k as u32)))
            }
            _ => Value::Float(old_num.unwrap_or(1.0) * 10f64.powi(*k)),
        },
        Val::Negated => match old {
            Some(Value::Integer(i)) => Value::Integer(i.saturating_neg()),
            _ => Value::Float(-old_num.unwrap_or(1.0)),
        },
        Val::Other(i) => {
            let doc: Table = format!("v = {}", OTHERS[*i]).parse().expect("pool value");
            doc["v"].clone()
        }
    }
}

/// The mutant's text, and whether it was garbled at the text level.
fn apply(base: &str, m: &Mutant) -> String {
    let mut t: Table = base.parse().expect("example parses");
    let keys = candidate_keys(&t);
    let mut garble = Vec::new();
    for mutation in &m.mutations {
        match mutation {
            Mutation::Set(k, v) => {
                let segs = segments(&keys[k % keys.len()]);
                let last = segs.last().unwrap().clone();
                if last.starts_with('[') {
                    continue;
                }
                if let Some(p) = parent_mut(&mut t, &segs, true) {
                    let new = value_for(v, p.get(&last));
                    p.insert(last, new);
                }
            }
            Mutation::Remove(k) => {
                let segs = segments(&keys[k % keys.len()]);
                let last = segs.last().unwrap().clone();
                if let Some(p) = parent_mut(&mut t, &segs, false) {
                    p.remove(&last);
                }
            }
            Mutation::Unknown(k) => {
                let segs = segments(&keys[k % keys.len()]);
                if let Some(p) = parent_mut(&mut t, &segs, false) {
                    p.insert("colour_of_the_roller".into(), Value::Float(1.0));
                }
            }
            Mutation::Text(op, pos) => garble.push((*op, *pos)),
            Mutation::Factor(k, f) => {
                let numeric: Vec<&String> = keys
                    .iter()
                    .filter(|key| {
                        let segs = segments(key);
                        let last = segs.last().unwrap();
                        parent_mut(&mut t.clone(), &segs, false)
                            .and_then(|p| p.get(last).cloned())
                            .is_some_and(|v| v.is_float() || v.is_integer())
                    })
                    .collect();
                if numeric.is_empty() {
                    continue;
                }
                let segs = segments(numeric[k % numeric.len()]);
                let last = segs.last().unwrap().clone();
                if let Some(p) = parent_mut(&mut t, &segs, false) {
                    let new = match p.get(&last) {
                        Some(Value::Integer(i)) => Value::Integer(((*i as f64) * f).round() as i64),
                        Some(Value::Float(x)) => Value::Float(x * f),
                        _ => continue,
                    };
                    p.insert(last, new);
                }
            }
        }
    }
    let mut text = toml::to_string(&t).expect("a toml table serialises");
    for (op, pos) in garble {
        let mut at = ((text.len() as f64) * pos) as usize;
        while at > 0 && !text.is_char_boundary(at) {
            at -= 1;
        }
        match op {
            0 => text.truncate(at),
            1 => {
                // double the line at `at`
                let start = text[..at].rfind('\n').map_or(0, |i| i + 1);
                let end = text[at..].find('\n').map_or(text.len(), |i| at + i);
                let line = text[start..end].to_string();
                text.insert_str(end, &format!("\n{line}"));
            }
            2 => text.insert_str(at, "=[{\"\u{0}\u{fffd}"),
            _ => {
                let start = text[..at].rfind('\n').map_or(0, |i| i + 1);
                let end = text[at..].find('\n').map_or(text.len(), |i| at + i);
                text.replace_range(start..end, "");
            }
        }
    }
    text
}

fn runner(seed: u64) -> TestRunner {
    TestRunner::new(Config {
        rng_seed: RngSeed::Fixed(seed),
        failure_persistence: None,
        ..Config::default()
    })
}

fn seed() -> u64 {
    std::env::var("EHL_FUZZ_SEED")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(20261125)
}

fn count_from_env(var: &str, default: usize) -> usize {
    std::env::var(var)
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(default)
}

/// What the oracle found for one mutant.
#[derive(Debug, Default)]
struct Tally {
    mutants: usize,
    accepted: usize,
    refused: usize,
    /// exit 3 (solved, not converged)
    not_converged: usize,
    /// refusals by the key (or argument) they name
    refused_keys: std::collections::BTreeMap<String, usize>,
    failures: Vec<String>,
}

impl Tally {
    fn fail(&mut self, what: String) {
        self.failures.push(what);
    }

    fn report(&self, what: &str) -> String {
        format!(
            "{what}: {} mutants, {} accepted/solved, {} not converged, {} refused, {} failures",
            self.mutants,
            self.accepted,
            self.not_converged,
            self.refused,
            self.failures.len()
        )
    }

    /// Counts a refusal under the key its message names (`error: case.toml: KEY: ...`).
    fn refusal(&mut self, message: &str) {
        self.refused += 1;
        let rest = message.trim_start_matches("error: ");
        let key = rest
            .split(": ")
            .nth(1)
            .filter(|k| !k.contains(' ') || k.starts_with('`'))
            .unwrap_or("(no key: file-level)");
        *self.refused_keys.entry(key.to_string()).or_default() += 1;
    }

    /// The most frequent refused keys, for the report.
    fn top_keys(&self, n: usize) -> String {
        let mut v: Vec<(&String, &usize)> = self.refused_keys.iter().collect();
        v.sort_by(|a, b| b.1.cmp(a.1));
        v.iter()
            .take(n)
            .map(|(k, c)| format!("{k} {c}"))
            .collect::<Vec<_>>()
            .join(", ")
    }

    #[track_caller]
    fn assert_clean(&self, what: &str) {
        if !self.failures.is_empty() {
            let shown: Vec<&String> = self.failures.iter().take(12).collect();
            panic!(
                "{}\nfirst failures:\n{}",
                self.report(what),
                shown
                    .iter()
                    .map(|s| s.as_str())
                    .collect::<Vec<_>>()
                    .join("\n---\n")
            );
        }
    }
}

/// The `check` oracle in-process: parse + validate + the check report, under catch_unwind.
fn check_in_process(text: &str, tally: &mut Tally) {
    tally.mutants += 1;
    let file = "mutant.toml";
    let parsed = std::panic::catch_unwind(AssertUnwindSafe(|| {
        ehl::case::parse_str(text, file, &[]).map(|case| {
            let report = std::panic::catch_unwind(AssertUnwindSafe(|| ehl::run::check_text(&case)));
            (case, report)
        })
    }));
    match parsed {
        Err(_) => tally.fail(format!("panic while validating:\n{text}")),
        Ok(Ok((_case, Err(_)))) => tally.fail(format!("panic in the check report:\n{text}")),
        Ok(Ok((_case, Ok(report)))) => {
            tally.accepted += 1;
            if report.contains("NaN") || report.contains("nan ") {
                tally.fail(format!("the check report prints NaN:\n{report}\n{text}"));
            }
        }
        Ok(Err(e)) => {
            let msg = e.to_string();
            tally.refusal(&msg);
            if !msg.starts_with(&format!("{file}: ")) {
                tally.fail(format!("refusal does not name the file: {msg}\n{text}"));
            }
            if let ehl::Error::Case { key, .. } | ehl::Error::Unsupported { key, .. } = &e {
                if key.trim().is_empty() {
                    tally.fail(format!("refusal names no key: {msg}\n{text}"));
                }
            }
            if msg.contains("NaN") {
                tally.fail(format!("refusal prints NaN: {msg}\n{text}"));
            }
        }
    }
}

/// Runs the built `ehl` with a timeout; `None` if it had to be killed. One solver thread per
/// child: the campaigns already run one child per core, and children that each took every core
/// oversubscribed the machine, so a slow minute could read as a hang.
fn ehl_timed(dir: &Path, args: &[&str], limit: Duration) -> Option<(i32, String, String)> {
    let mut child = Command::new(env!("CARGO_BIN_EXE_ehl"))
        .env("RAYON_NUM_THREADS", "1")
        .args(args)
        .current_dir(dir)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("start ehl");
    // drain the pipes on threads so a chatty child cannot block on a full pipe
    let mut so = child.stdout.take().unwrap();
    let mut se = child.stderr.take().unwrap();
    let to = std::thread::spawn(move || {
        let mut s = String::new();
        let _ = std::io::Read::read_to_string(&mut so, &mut s);
        s
    });
    let te = std::thread::spawn(move || {
        let mut s = String::new();
        let _ = std::io::Read::read_to_string(&mut se, &mut s);
        s
    });
    let start = Instant::now();
    loop {
        match child.try_wait().expect("wait ehl") {
            Some(status) => {
                let code = status.code().unwrap_or(-1);
                return Some((code, to.join().unwrap(), te.join().unwrap()));
            }
            None if start.elapsed() > limit => {
                let _ = child.kill();
                let _ = child.wait();
                return None;
            }
            None => std::thread::sleep(Duration::from_millis(5)),
        }
    }
}

/// The `check` oracle through the binary (exit status, panics, messages).
fn check_cli(text: &str, tally: &mut Tally) {
    tally.mutants += 1;
    let work = common::Work::new(text);
    match ehl_timed(
        work.path(),
        &["check", "case.toml"],
        Duration::from_secs(30),
    ) {
        None => tally.fail(format!("`ehl check` hung (killed after 30 s):\n{text}")),
        Some((code, stdout, stderr)) => match code {
            0 => {
                tally.accepted += 1;
                if stdout.contains("NaN") {
                    tally.fail(format!("`ehl check` printed NaN:\n{stdout}\n{text}"));
                }
            }
            1 => {
                tally.refusal(&stderr);
                if !stderr.starts_with("error: case.toml: ") {
                    tally.fail(format!("refusal does not name the file: {stderr}\n{text}"));
                }
            }
            _ => tally.fail(format!(
                "`ehl check` exit status {code} (panic?): {stderr}\n{text}"
            )),
        },
    }
}

/// Every file below `dir` (relative paths), hidden ones included.
fn listing(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        let Ok(rd) = std::fs::read_dir(&d) else {
            continue;
        };
        for e in rd.flatten() {
            let p = e.path();
            if p.is_dir() {
                stack.push(p.clone());
            }
            out.push(p.strip_prefix(dir).unwrap().to_path_buf());
        }
    }
    out.sort();
    out
}

/// Non-finite or negative-film values in a written output folder (empty: clean).
fn scan_outputs(out: &Path) -> Vec<String> {
    let mut bad = Vec::new();
    let summary = out.join("summary.json");
    match std::fs::read_to_string(&summary) {
        Err(e) => bad.push(format!("no summary.json: {e}")),
        Ok(s) => {
            if s.contains("null") || s.contains("NaN") || s.contains("Infinity") {
                bad.push(format!("summary.json holds a null/NaN/Infinity: {s}"));
            }
            if let Ok(v) = serde_json::from_str::<serde_json::Value>(&s) {
                for k in ["central_film_m", "min_film_m", "centerline_min_film_m"] {
                    if let Some(h) = v.get(k).and_then(|h| h.as_f64()) {
                        if h < 0.0 {
                            bad.push(format!("summary.json {k} = {h} is negative"));
                        }
                    }
                }
            } else {
                bad.push("summary.json is not JSON".into());
            }
        }
    }
    for csv in ["centerline.csv", "axial.csv"] {
        if let Ok(s) = std::fs::read_to_string(out.join(csv)) {
            if s.to_lowercase().contains("nan") {
                bad.push(format!("{csv} holds a NaN"));
            }
        }
    }
    match std::fs::File::open(out.join("fields.npz")) {
        Err(e) => bad.push(format!("no fields.npz: {e}")),
        Ok(f) => match ndarray_npy::NpzReader::new(f) {
            Err(e) => bad.push(format!("fields.npz unreadable: {e}")),
            Ok(mut npz) => {
                let names = npz.names().unwrap_or_default();
                for name in names {
                    let Ok(a) = npz.by_name::<ndarray::OwnedRepr<f64>, ndarray::IxDyn>(&name)
                    else {
                        continue;
                    };
                    let film = name.starts_with("film");
                    if let Some(v) = a
                        .iter()
                        .find(|v| v.is_nan() || (v.is_infinite() && !(film && **v > 0.0)))
                    {
                        bad.push(format!("fields.npz `{name}` holds {v}"));
                    }
                    if film && a.iter().any(|v| *v < 0.0) {
                        bad.push(format!("fields.npz `{name}` holds a negative film"));
                    }
                }
            }
        },
    }
    bad
}

/// A small, runnable version of an example: coarse grid, few iterations allowed to run long.
fn small(text: &str) -> String {
    let mut t: Table = text.parse().expect("example parses");
    let infinite = ["body1", "body2"].iter().any(|b| {
        t.get(*b)
            .and_then(|v| v.get("length"))
            .and_then(|v| v.as_float())
            .is_some_and(|l| l.is_infinite())
    });
    let grid = t
        .entry("grid")
        .or_insert_with(|| Value::Table(Table::new()))
        .as_table_mut()
        .expect("grid table");
    grid.insert("nx".into(), Value::Integer(48));
    if !infinite {
        grid.insert("ny".into(), Value::Integer(32));
    }
    toml::to_string(&t).unwrap()
}

/// The `run` oracle: one mutant through `ehl run` in a fresh folder holding the case and a
/// user's file; `out_mode` 0: default out/, 1: `--out .` (the user's folder), 2: `--out mine`
/// (a folder holding a user's file).
fn run_cli(text: &str, out_mode: u8, limit: Duration, tally: &Mutex<Tally>) {
    let work = common::Work::new(text);
    std::fs::write(work.file("notes.txt"), "the user's own notes").unwrap();
    std::fs::create_dir(work.file("mine")).unwrap();
    std::fs::write(work.file("mine/data.csv"), "1,2,3").unwrap();
    let (out_dir, extra): (PathBuf, Vec<&str>) = match out_mode {
        1 => (work.path().to_path_buf(), vec!["--out", "."]),
        2 => (work.file("mine"), vec!["--out", "mine"]),
        _ => (work.file("out/case"), vec![]),
    };
    let mut args = vec!["run", "case.toml", "--quiet"];
    args.extend(extra);
    let result = ehl_timed(work.path(), &args, limit);
    let mut failures = Vec::new();
    let mut outcome = (0, 0, 0);
    let mut refusal = None;
    match result {
        None => failures.push(format!(
            "`ehl {}` hung (killed after {limit:?})",
            args.join(" ")
        )),
        Some((code, _stdout, stderr)) => {
            if stderr.contains("panicked") || !matches!(code, 0 | 1 | 3 | 4) {
                failures.push(format!("exit status {code}: {stderr}"));
            }
            match code {
                0 | 3 | 4 => {
                    if code != 3 {
                        outcome.0 = 1;
                    } else {
                        outcome.1 = 1;
                    }
                    for b in scan_outputs(&out_dir) {
                        failures.push(b);
                    }
                }
                1 => {
                    outcome.2 = 1;
                    refusal = Some(stderr.clone());
                    if !stderr.starts_with("error: case.toml: ")
                        && !stderr.contains("--out")
                        && !stderr.contains("case.toml")
                    {
                        failures.push(format!(
                            "refusal names neither the file nor the argument: {stderr}"
                        ));
                    }
                    if out_mode == 0 && work.file("out/case").exists() {
                        failures.push(format!("a refused run left out/case: {stderr}"));
                    }
                }
                _ => {}
            }
        }
    }
    // the user's files survive, whatever happened
    if std::fs::read_to_string(work.file("notes.txt"))
        .ok()
        .as_deref()
        != Some("the user's own notes")
    {
        failures.push("the user's notes.txt was lost".into());
    }
    if std::fs::read_to_string(work.file("mine/data.csv"))
        .ok()
        .as_deref()
        != Some("1,2,3")
    {
        failures.push("the user's mine/data.csv was lost".into());
    }
    if !work.file("case.toml").is_file() {
        failures.push("the case file was lost".into());
    }
    // no temporary folder left anywhere
    for p in listing(work.path()) {
        let name = p.to_string_lossy();
        if name.contains(".tmp-") || name.contains(".old-") {
            failures.push(format!("left a temporary entry: {name}"));
        }
    }
    let mut t = tally.lock().unwrap();
    t.mutants += 1;
    t.accepted += outcome.0;
    t.not_converged += outcome.1;
    if let Some(r) = refusal {
        t.refusal(&r);
    }
    for f in failures {
        t.fail(format!("{f}\n`ehl {}` on:\n{text}", args.join(" ")));
    }
}

fn check_campaign(n_lib: usize, n_cli: usize, seed: u64) -> (Tally, Tally) {
    let examples = corpus();
    let mut r = runner(seed);
    let strategy = mutant_strategy(examples.len(), true);
    let mut lib = Tally::default();
    for _ in 0..n_lib {
        let m = strategy.new_tree(&mut r).expect("mutant").current();
        let text = apply(&examples[m.example].1, &m);
        check_in_process(&text, &mut lib);
    }
    let mut cli = Tally::default();
    for _ in 0..n_cli {
        let m = strategy.new_tree(&mut r).expect("mutant").current();
        let text = apply(&examples[m.example].1, &m);
        check_cli(&text, &mut cli);
    }
    (lib, cli)
}

fn run_campaign(n: usize, seed: u64, limit: Duration) -> Tally {
    use rayon::prelude::*;
    let examples = corpus();
    let mut r = runner(seed ^ 0x5eed);
    let strategy = (run_mutant_strategy(examples.len()), 0u8..20);
    let mutants: Vec<(String, u8)> = (0..n)
        .map(|_| {
            let (m, out) = strategy.new_tree(&mut r).expect("mutant").current();
            let text = apply(&small(&examples[m.example].1), &m);
            // 1 in 10 runs points --out at a folder holding the user's files
            let mode = match out {
                0 => 1,
                1 => 2,
                _ => 0,
            };
            (text, mode)
        })
        .collect();
    let tally = Mutex::new(Tally::default());
    mutants
        .par_iter()
        .for_each(|(text, mode)| run_cli(text, *mode, limit, &tally));
    tally.into_inner().unwrap()
}

/// The mutation machinery itself: every mutation kind changes the text, so that the oracle
/// below is not fed the unmutated examples.
#[test]
fn mutations_change_the_case() {
    let examples = corpus();
    let base = &examples[0].1;
    let canon = toml::to_string(&base.parse::<Table>().unwrap()).unwrap();
    let cases = [
        Mutation::Set(0, Val::Number(12)),
        Mutation::Set(3, Val::Other(9)),
        Mutation::Remove(1),
        Mutation::Unknown(0),
        Mutation::Text(0, 0.5),
        Mutation::Text(2, 0.3),
    ];
    for m in cases {
        let text = apply(
            base,
            &Mutant {
                example: 0,
                mutations: vec![m.clone()],
            },
        );
        assert_ne!(text, canon, "{m:?} left the case unchanged");
    }
    // a schema key that the example lacks is created with its parents
    let t: Table = base.parse().unwrap();
    let keys = candidate_keys(&t);
    let k = keys
        .iter()
        .position(|k| k == "features[0].pattern.rows")
        .unwrap();
    let text = apply(
        base,
        &Mutant {
            example: 0,
            mutations: vec![Mutation::Set(k, Val::Other(3))],
        },
    );
    assert!(
        text.contains("[features.pattern]") || text.contains("pattern"),
        "{text}"
    );
}

/// The oracle catches what it is meant to catch: a NaN in a written field, a negative film, a
/// null in summary.json.
#[test]
fn output_scan_finds_nan_and_negative_film() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(
        d.join("summary.json"),
        r#"{"central_film_m": -1e-9, "residual": null}"#,
    )
    .unwrap();
    let mut npz = ndarray_npy::NpzWriter::new(std::fs::File::create(d.join("fields.npz")).unwrap());
    npz.add_array("pressure", &ndarray::arr1(&[1.0, f64::NAN]))
        .unwrap();
    npz.add_array("film", &ndarray::arr1(&[f64::INFINITY, -1.0]))
        .unwrap();
    npz.finish().unwrap();
    let bad = scan_outputs(d).join("\n");
    assert!(bad.contains("null"), "{bad}");
    assert!(bad.contains("central_film_m"), "{bad}");
    assert!(bad.contains("`pressure` holds NaN"), "{bad}");
    assert!(bad.contains("negative film"), "{bad}");
    assert!(
        !bad.contains("`film` holds inf"),
        "+inf film is the no-material convention: {bad}"
    );
}

/// The bounded run of the default suite: 3000 mutants through the library's check, 150
/// through `ehl check`, 24 small runs.
#[test]
fn fuzz_bounded() {
    let (lib, cli) = check_campaign(3000, 150, seed());
    eprintln!("{}", lib.report("check (library)"));
    eprintln!("{}", cli.report("check (binary)"));
    lib.assert_clean("check (library)");
    cli.assert_clean("check (binary)");
    // some mutants must pass and some must be refused, or the campaign tests nothing
    assert!(
        lib.accepted > 100 && lib.refused > 100,
        "{}",
        lib.report("check")
    );
    let runs = run_campaign(24, seed(), Duration::from_secs(120));
    eprintln!("{}", runs.report("run"));
    runs.assert_clean("run");
    assert!(
        runs.accepted + runs.not_converged > 0,
        "{}",
        runs.report("run")
    );
}

/// The long run (see the module doc for the command).
#[test]
#[ignore = "long: EHL_FUZZ_CHECKS=10000 EHL_FUZZ_RUNS=1000 cargo test --release -p ehl-cli --test fuzz -- --ignored --nocapture"]
fn fuzz_long() {
    let checks = count_from_env("EHL_FUZZ_CHECKS", 10_000);
    let runs = count_from_env("EHL_FUZZ_RUNS", 1_000);
    let started = Instant::now();
    let (lib, cli) = check_campaign(checks, checks, seed());
    let check_time = started.elapsed();
    let started = Instant::now();
    let run = run_campaign(runs, seed(), Duration::from_secs(300));
    let run_time = started.elapsed();
    println!("seed {}", seed());
    println!(
        "{} ({check_time:.0?} for both check campaigns)",
        lib.report("check (library)")
    );
    println!(
        "{}",
        cli.report("check (binary, each under a 30 s timeout)")
    );
    println!(
        "{} ({run_time:.0?})",
        run.report("run (binary, each under a 300 s timeout)")
    );
    println!("most refused keys (check): {}", lib.top_keys(15));
    println!("most refused keys (run): {}", run.top_keys(15));
    for (what, t) in [
        ("check (library)", &lib),
        ("check (binary)", &cli),
        ("run", &run),
    ] {
        for f in t.failures.iter().take(5) {
            println!("--- {what} failure:\n{f}");
        }
    }
    let all: Vec<&String> = [&lib, &cli, &run]
        .iter()
        .flat_map(|t| t.failures.iter())
        .collect();
    if !all.is_empty() {
        let path = std::env::temp_dir().join("ehl-fuzz-failures.txt");
        let text: Vec<&str> = all.iter().map(|s| s.as_str()).collect();
        let _ = std::fs::write(&path, text.join("\n=====\n"));
        println!("all {} failures: {}", all.len(), path.display());
    }
    lib.assert_clean("check (library)");
    cli.assert_clean("check (binary)");
    run.assert_clean("run");
}
