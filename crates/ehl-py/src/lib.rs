//! `ehl._ehl`: the Python bindings of the `ehl` library (pyo3, stable ABI). Thin: cases go
//! through the library's case reader (`ehl::case::parse_str`, with `--set` overrides), solves
//! through `ehl::run::cancel::solve`, outputs through `ehl::output::write_all`; here are only
//! the conversions to and from Python objects. The public Python API is `ehl/__init__.py`.
//!
//! Memory: a `Solution` owns the library's solution; its arrays are read-only NumPy views of
//! the solution's vectors (no copy), which keep the `Solution` alive.
//!
//! Threads: a solve runs on a thread of its own with the GIL released; the calling thread
//! waits in steps of `poll` seconds, and between them (holding the GIL) checks for signals
//! (Ctrl-C: the solve is cancelled and KeyboardInterrupt raised) and passes the latest progress
//! report to the Python callback. Python delivers Ctrl-C to the main thread only: solves in
//! other threads stop through `cancel_all` (every running solve's token is in a registry).

use ehl::run::cancel::{self, CancelToken};
use numpy::ndarray::ArrayView2;
use numpy::{PyArray1, PyArray2, PyArrayMethods};
use pyo3::exceptions::{PyKeyboardInterrupt, PyRuntimeError, PyTypeError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};
use std::path::PathBuf;
use std::sync::{mpsc, Mutex};
use std::time::Duration;

// ------------------------------------------------------------------ errors

/// An exception class of `ehl.errors` (pure Python, so that it can have attributes and two
/// bases, e.g. `CaseError(EhlError, ValueError)`).
fn error_class<'py>(py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyAny>> {
    py.import("ehl.errors")?.getattr(name)
}

/// The arguments of an `ehl.errors` class: (message, file or path, key, reason).
type ErrorArgs = (String, Option<String>, Option<String>, Option<String>);

/// A library error as the Python exception: `CaseError` (with `.file`, `.key`, `.reason`),
/// `OutputError` (`.path`, `.reason`), `SolverError`, or `KeyboardInterrupt` for a cancelled
/// solve.
fn py_err(py: Python<'_>, e: ehl::Error) -> PyErr {
    let text = e.to_string();
    let made = (|| -> PyResult<PyErr> {
        let (class, args): (&str, ErrorArgs) = match e {
            ehl::Error::Case { file, key, message }
            | ehl::Error::Unsupported { file, key, message } => {
                ("CaseError", (text, Some(file), Some(key), Some(message)))
            }
            ehl::Error::CaseFile { file, message } => {
                ("CaseError", (text, Some(file), None, Some(message)))
            }
            ehl::Error::Output { path, message } => (
                "OutputError",
                (text, Some(path.display().to_string()), None, Some(message)),
            ),
            ehl::Error::Solver(m) => ("SolverError", (text, None, None, Some(m))),
            ehl::Error::Cancelled => {
                return Ok(PyKeyboardInterrupt::new_err("ehl: solve cancelled"))
            }
        };
        let value = error_class(py, class)?.call1(args)?;
        Ok(PyErr::from_value(value))
    })();
    made.unwrap_or_else(|e| e)
}

/// A `CaseError` made here (a Python value that is no case value).
fn case_err(py: Python<'_>, file: &str, key: &str, reason: String) -> PyErr {
    py_err(
        py,
        ehl::Error::Case {
            file: file.to_string(),
            key: key.to_string(),
            message: reason,
        },
    )
}

/// A case that another thread is changing (a borrow error) as a `RuntimeError` that says so,
/// not a panic. With the GIL held while a case is changed (see `Case.set`) it does not happen
/// with Python's threads; the check stays for safety.
fn busy<T>(r: Result<T, impl std::fmt::Display>) -> PyResult<T> {
    r.map_err(|e| {
        PyRuntimeError::new_err(format!(
            "ehl.Case is being changed by another thread ({e}); use one case per thread \
             (case.copy()) or a lock"
        ))
    })
}

// ------------------------------------------------------------------ Python <-> TOML

/// A Python value as a TOML value: bool, int, float (numpy scalars too), str, os.PathLike,
/// dict, list, tuple, numpy arrays. `key` names the place in messages; an error carries the
/// dotted path of the value that has no case-file form (`features[1].depth`) and the reason.
fn to_toml(v: &Bound<'_, PyAny>, key: &str) -> Result<toml::Value, (String, String)> {
    to_toml_at(v, key, 0)
}

/// Most levels of dicts and lists a value may nest: a case file nests three or four; a dict
/// that contains itself, or a list nested 20000 deep, recursed without end and crashed the
/// interpreter (a scan).
const MAX_NESTING: usize = 64;

/// [`to_toml`] at nesting level `depth`.
fn to_toml_at(
    v: &Bound<'_, PyAny>,
    key: &str,
    depth: usize,
) -> Result<toml::Value, (String, String)> {
    use toml::Value;
    let fail = |m: String| (key.to_string(), m);
    if depth > MAX_NESTING {
        return Err(fail(format!(
            "`{key}` nests more than {MAX_NESTING} levels of dicts and lists (a value that contains itself?); a case nests a few"
        )));
    }
    if v.is_instance_of::<PyBool>() {
        return Ok(Value::Boolean(
            v.extract::<bool>().map_err(|e| fail(e.to_string()))?,
        ));
    }
    if v.is_instance_of::<PyInt>() {
        return match v.extract::<i64>() {
            Ok(i) => Ok(Value::Integer(i)),
            Err(_) => Ok(Value::Float(
                v.extract::<f64>().map_err(|e| fail(e.to_string()))?,
            )),
        };
    }
    if v.is_instance_of::<PyFloat>() {
        return Ok(Value::Float(
            v.extract::<f64>().map_err(|e| fail(e.to_string()))?,
        ));
    }
    if let Ok(s) = v.cast::<PyString>() {
        return Ok(Value::String(s.to_string()));
    }
    if let Ok(d) = v.cast::<PyDict>() {
        let mut t = toml::Table::new();
        for (k, item) in d.iter() {
            let Ok(name) = k.extract::<String>() else {
                let place = if key.is_empty() {
                    "the case dict".to_string()
                } else {
                    format!("`{key}`")
                };
                return Err(fail(format!("{place} has a key {k} that is not a string")));
            };
            let sub = if key.is_empty() {
                name.clone()
            } else {
                format!("{key}.{name}")
            };
            if item.is_none() {
                continue; // None: the key is left out (its default applies)
            }
            t.insert(name, to_toml_at(&item, &sub, depth + 1)?);
        }
        return Ok(Value::Table(t));
    }
    if v.is_instance_of::<PyList>() || v.is_instance_of::<PyTuple>() {
        let mut items = Vec::new();
        for (i, item) in v.try_iter().map_err(|e| fail(e.to_string()))?.enumerate() {
            let item = item.map_err(|e| fail(e.to_string()))?;
            items.push(to_toml_at(&item, &format!("{key}[{i}]"), depth + 1)?);
        }
        return Ok(Value::Array(items));
    }
    if v.is_none() {
        return Err(fail(format!(
            "`{key}` is None; give a value, or leave the key out for its default"
        )));
    }
    let type_name = v
        .get_type()
        .name()
        .map(|n| n.to_string())
        .unwrap_or_default();
    // numpy scalars and arrays, os.PathLike
    if type_name == "bool_" || type_name == "bool" {
        if let Ok(b) = v.extract::<bool>() {
            return Ok(Value::Boolean(b));
        }
    }
    if v.hasattr("tolist").unwrap_or(false) {
        if let Ok(l) = v.call_method0("tolist") {
            if !l.is(v) {
                return to_toml_at(&l, key, depth + 1);
            }
        }
    }
    if v.hasattr("__fspath__").unwrap_or(false) {
        if let Ok(p) = v.call_method0("__fspath__") {
            return to_toml_at(&p, key, depth + 1);
        }
    }
    if v.hasattr("__index__").unwrap_or(false) {
        if let Ok(i) = v.extract::<i64>() {
            return Ok(Value::Integer(i));
        }
    }
    if let Ok(f) = v.extract::<f64>() {
        return Ok(Value::Float(f));
    }
    Err(fail(format!(
        "`{key}` is a Python {type_name}, which has no case-file form (give a number, bool, str, dict or list)"
    )))
}

/// A TOML value as a Python object (tables as dicts, arrays as lists).
fn from_toml(py: Python<'_>, v: &toml::Value) -> PyResult<Py<PyAny>> {
    use toml::Value;
    Ok(match v {
        Value::String(s) => s.into_pyobject(py)?.into_any().unbind(),
        Value::Integer(i) => i.into_pyobject(py)?.into_any().unbind(),
        Value::Float(f) => f.into_pyobject(py)?.into_any().unbind(),
        Value::Boolean(b) => PyBool::new(py, *b).to_owned().into_any().unbind(),
        Value::Datetime(d) => d.to_string().into_pyobject(py)?.into_any().unbind(),
        Value::Array(a) => {
            let l = PyList::empty(py);
            for x in a {
                l.append(from_toml(py, x)?)?;
            }
            l.into_any().unbind()
        }
        Value::Table(t) => table_to_dict(py, t)?.into_any().unbind(),
    })
}

fn table_to_dict<'py>(py: Python<'py>, t: &toml::Table) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    for (k, x) in t {
        d.set_item(k, from_toml(py, x)?)?;
    }
    Ok(d)
}

/// JSON as Python objects (for the summary, which is `summary.json`'s document).
fn from_json(py: Python<'_>, v: &serde_json::Value) -> PyResult<Py<PyAny>> {
    use serde_json::Value;
    Ok(match v {
        Value::Null => py.None(),
        Value::Bool(b) => PyBool::new(py, *b).to_owned().into_any().unbind(),
        Value::Number(n) => {
            if let Some(i) = n.as_i64() {
                i.into_pyobject(py)?.into_any().unbind()
            } else if let Some(u) = n.as_u64() {
                u.into_pyobject(py)?.into_any().unbind()
            } else {
                n.as_f64()
                    .unwrap_or(f64::NAN)
                    .into_pyobject(py)?
                    .into_any()
                    .unbind()
            }
        }
        Value::String(s) => s.into_pyobject(py)?.into_any().unbind(),
        Value::Array(a) => {
            let l = PyList::empty(py);
            for x in a {
                l.append(from_json(py, x)?)?;
            }
            l.into_any().unbind()
        }
        Value::Object(o) => {
            let d = PyDict::new(py);
            for (k, x) in o {
                d.set_item(k, from_json(py, x)?)?;
            }
            d.into_any().unbind()
        }
    })
}

// ------------------------------------------------------------------ Case

/// A validated case: the case file's text, the overrides applied to it (the CLI's `--set`),
/// and the validated `ehl::case::Case`.
#[pyclass(module = "ehl", name = "Case", from_py_object)]
#[derive(Clone)]
struct PyCase {
    text: String,
    file: String,
    overrides: Vec<String>,
    case: ehl::case::Case,
}

impl PyCase {
    fn parse(py: Python<'_>, text: String, file: String, overrides: Vec<String>) -> PyResult<Self> {
        let case = py
            .detach(|| ehl::case::parse_str(&text, &file, &overrides))
            .map_err(|e| py_err(py, e))?;
        Ok(PyCase {
            text,
            file,
            overrides,
            case,
        })
    }

    /// The case file's TOML tree with the overrides applied.
    fn tree(&self, py: Python<'_>) -> PyResult<toml::Table> {
        let mut root: toml::Table = self.text.parse().map_err(|e: toml::de::Error| {
            py_err(
                py,
                ehl::Error::CaseFile {
                    file: self.file.clone(),
                    message: e.to_string(),
                },
            )
        })?;
        for o in &self.overrides {
            ehl::case::overrides::apply(&mut root, o, &self.file).map_err(|e| py_err(py, e))?;
        }
        Ok(root)
    }
}

/// `x` in SI with a unit, or "inf".
fn si(x: f64, scale: f64, unit: &str, digits: usize) -> String {
    if x.is_finite() {
        format!("{:.*} {unit}", digits, x * scale)
    } else {
        "inf".into()
    }
}

#[pymethods]
impl PyCase {
    /// Reads a case file (TOML), as `ehl run CASE.toml` does.
    #[staticmethod]
    fn from_file(py: Python<'_>, path: PathBuf) -> PyResult<Self> {
        let text = ehl::case::read_case_text(&path).map_err(|e| py_err(py, e))?;
        // kept absolute: a height map's relative path is read from the case file's folder at
        // every validation (set, copy, unpickling), and after an os.chdir a relative name
        // pointed elsewhere (a scan)
        let path = std::path::absolute(&path).unwrap_or(path);
        Self::parse(py, text, path.display().to_string(), Vec::new())
    }

    /// A case from TOML text; `file` names it in error messages and is the folder that a
    /// height map's relative path is read from.
    #[staticmethod]
    #[pyo3(signature = (text, file = "<string>".to_string()))]
    fn from_toml(py: Python<'_>, text: String, file: String) -> PyResult<Self> {
        Self::parse(py, text, file, Vec::new())
    }

    /// A case from a dict with the case file's structure (nested dicts for tables, a list of
    /// dicts for `features`).
    #[staticmethod]
    #[pyo3(signature = (d, file = "<dict>".to_string()))]
    fn from_dict(py: Python<'_>, d: &Bound<'_, PyDict>, file: String) -> PyResult<Self> {
        let v = to_toml(d.as_any(), "").map_err(|(key, message)| {
            if key.is_empty() {
                // the dict as a whole (a key that is not a string): no key to name
                py_err(
                    py,
                    ehl::Error::CaseFile {
                        file: file.clone(),
                        message,
                    },
                )
            } else {
                case_err(py, &file, &key, message)
            }
        })?;
        let toml::Value::Table(t) = v else {
            unreachable!("a dict converts to a table")
        };
        Self::parse(py, t.to_string(), file, Vec::new())
    }

    /// Overrides one key by its dotted path, as the CLI's `--set KEY=VALUE`:
    /// `case.set("load.force", 5000)`, `case.set("features[0].depth", 1e-7)`,
    /// `case.set("body1.profile", {"kind": "crowned", "crown_radius": 0.5})`. The case is
    /// validated again; on an error (`CaseError` naming the key) it is left unchanged.
    ///
    /// Threads: the value is converted first (that may run Python code: `tolist`,
    /// `__fspath__`, `__repr__`) with no borrow of the case held; the case is then borrowed
    /// only while it is parsed again, with the GIL held (parsing takes milliseconds), so no
    /// other Python thread can meet the case borrowed (e.g. `solve(case)` in another thread:
    /// before, `set` released the GIL while parsing and such a `solve` panicked).
    fn set(slf: &Bound<'_, Self>, key: &str, value: &Bound<'_, PyAny>) -> PyResult<()> {
        let py = slf.py();
        let file = busy(slf.try_borrow())?.file.clone();
        let v = to_toml(value, key).map_err(|(k, m)| case_err(py, &file, &k, m))?;
        let text = match &v {
            toml::Value::Table(t) => {
                // inline-table form of a table value
                let items: Vec<String> = t
                    .iter()
                    .map(|(k, x)| format!("{} = {}", toml_key(k), x))
                    .collect();
                format!("{{ {} }}", items.join(", "))
            }
            other => other.to_string(),
        };
        let assignment = format!("{key}={text}");
        // the library's messages say where an override came from in the CLI's words
        let cli = format!(" (in --set {assignment})");
        let ours = format!(" (in Case.set({key:?}, {}))", value.repr()?);
        // from here on no Python code runs and the GIL stays held
        let mut this = busy(slf.try_borrow_mut())?;
        let mut overrides = this.overrides.clone();
        overrides.push(assignment);
        match ehl::case::parse_str(&this.text, &this.file, &overrides) {
            Ok(next) => {
                this.overrides = overrides;
                this.case = next;
                Ok(())
            }
            Err(e) => {
                drop(this); // (making the exception runs Python code)
                Err(match e {
                    ehl::Error::Case { file, key, message } => {
                        let message = message.replace(&cli, &ours);
                        py_err(py, ehl::Error::Case { file, key, message })
                    }
                    e => py_err(py, e),
                })
            }
        }
    }

    /// The value of a dotted key as set in the case file or by `set` (not the defaults: see
    /// `to_dict()`'s note). Raises `CaseError` for a key that is not set.
    fn get(&self, py: Python<'_>, key: &str) -> PyResult<Py<PyAny>> {
        let root = self.tree(py)?;
        let display = ehl::case::check_key(key).map_err(|m| case_err(py, &self.file, key, m))?;
        let not_set = || {
            case_err(
                py,
                &self.file,
                &display,
                "is not set in this case (its default applies: see `ehl check` or the summary's \"case\")".into(),
            )
        };
        let mut here = toml::Value::Table(root);
        // `check_key` gives the display form: dotted names, each followed by any number of
        // indices (`features[0].depth`, `a[0][1]`)
        for part in display.split('.') {
            let (name, mut rest) = match part.find('[') {
                Some(i) => (&part[..i], &part[i..]),
                None => (part, ""),
            };
            here = here.get(name).cloned().ok_or_else(not_set)?;
            while let Some(close) = rest.find(']') {
                let i: usize = rest[1..close].parse().map_err(|_| {
                    case_err(
                        py,
                        &self.file,
                        &display,
                        format!("`{part}` has an index that is not a whole number"),
                    )
                })?;
                here = match &here {
                    toml::Value::Array(a) => a.get(i).cloned().ok_or_else(|| {
                        // an index past the end is no key with a default: the entry is missing
                        case_err(
                            py,
                            &self.file,
                            &display,
                            format!(
                                "index {i} does not exist: `{name}` has {} entr{}",
                                a.len(),
                                if a.len() == 1 { "y" } else { "ies" }
                            ),
                        )
                    })?,
                    _ => return Err(not_set()),
                };
                rest = &rest[close + 1..];
            }
        }
        from_toml(py, &here)
    }

    /// The case as a dict: the case file's keys with the overrides applied (defaults are not
    /// filled in; a solution's `summary["case"]` holds the resolved case with every default).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        table_to_dict(py, &self.tree(py)?)
    }

    /// The case as TOML text (the case file with the overrides applied): `ehl run` reads it.
    fn to_toml(&self, py: Python<'_>) -> PyResult<String> {
        Ok(self.tree(py)?.to_string())
    }

    /// The derived quantities that `ehl check` prints, as a dict (SI units; the key names end
    /// in the unit). Quantities that do not apply to the contact are None.
    fn check<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let r = ehl::reference::check_report(&self.case);
        let d = PyDict::new(py);
        let num = |x: f64| if x.is_nan() { None } else { Some(x) };
        let h = &r.hertz;
        d.set_item("title", &r.title)?;
        d.set_item(
            "kind",
            match r.kind {
                ehl::case::Kind::Dry => "dry",
                ehl::case::Kind::Ehl => "ehl",
            },
        )?;
        d.set_item(
            "contact",
            if h.point {
                "point"
            } else if h.contact_length.is_infinite() {
                "infinite line"
            } else {
                "finite line"
            },
        )?;
        d.set_item("reduced_modulus_pa", h.e_red)?;
        d.set_item("reduced_radius_m", h.r)?;
        d.set_item("reduced_radius_y_m", h.r_y)?;
        d.set_item("contact_length_m", num(h.contact_length))?;
        d.set_item("load_n", h.force)?;
        d.set_item("load_per_length_n_m", num(h.force_per_length))?;
        d.set_item("hertz_half_width_m", h.b)?;
        d.set_item("hertz_semi_axis_y_m", num(h.a_y).filter(|_| h.point))?;
        d.set_item("ellipticity", num(h.ellipticity))?;
        d.set_item("hertz_approach_m", num(h.approach))?;
        d.set_item("hertz_pressure_pa", h.ph)?;
        d.set_item("W", r.w)?;
        d.set_item("U", r.u)?;
        d.set_item("G", r.g)?;
        d.set_item("moes_M", r.moes.map(|m| m.0))?;
        d.set_item("moes_L", r.moes.map(|m| m.1))?;
        d.set_item("spike_pressure_pa", r.spike.map(|s| s.0))?;
        d.set_item("spike_position_m", r.spike.map(|s| s.1))?;
        let films = PyList::empty(py);
        for f in &r.films {
            let e = PyDict::new(py);
            e.set_item("formula", f.name)?;
            e.set_item("central_film_m", f.central)?;
            e.set_item("min_film_m", f.minimum)?;
            e.set_item("fitted_with", f.laws)?;
            e.set_item("case_uses_same_laws", f.laws_match)?;
            films.append(e)?;
        }
        d.set_item("film_estimates", films)?;
        d.set_item("nx", r.nx)?;
        d.set_item("ny", r.ny)?;
        d.set_item("dx_m", r.dx)?;
        d.set_item("dy_m", r.dy)?;
        d.set_item("cells_across_2b", r.cells_across_2b)?;
        d.set_item("cells_across_y", r.cells_across_y)?;
        d.set_item("memory_estimate_bytes", r.memory.0)?;
        d.set_item("memory_limit_bytes", r.memory.1)?;
        if let Some(st) = &r.stress {
            let e = PyDict::new(py);
            e.set_item("bodies", st.bodies.clone())?;
            e.set_item("layers", st.layers)?;
            e.set_item("first_depth_m", st.first_m)?;
            e.set_item("depth_m", st.depth_m)?;
            e.set_item("depth_over_b", st.depth_b)?;
            e.set_item("window_m", st.window.map(|w| w.0))?;
            e.set_item("window_layers", st.window.map(|w| w.1))?;
            e.set_item("passage_bytes", st.window.map(|w| w.2))?;
            if let Some((name, c, h, slope)) = &st.fatigue {
                let f = PyDict::new(py);
                f.set_item("criterion", name)?;
                f.set_item("stress_exponent", c)?;
                f.set_item("depth_exponent", h)?;
                f.set_item("weibull_slope", slope)?;
                f.set_item("dang_van_alpha", st.dang_van.map(|d| d.0))?;
                f.set_item("dang_van_beta_pa", st.dang_van.map(|d| d.1))?;
                e.set_item("fatigue", f)?;
            } else {
                e.set_item("fatigue", py.None())?;
            }
            d.set_item("stress", e)?;
        } else {
            d.set_item("stress", py.None())?;
        }
        if let Some(t) = &r.transient {
            let e = PyDict::new(py);
            e.set_item("steps", t.steps)?;
            e.set_item("dt_s", t.dt)?;
            e.set_item("duration_s", t.dt * t.steps as f64)?;
            e.set_item("x_p_from_m", t.xp.0)?;
            e.set_item("x_p_to_m", t.xp.1)?;
            e.set_item("u1_m_s", t.u.0)?;
            e.set_item("u2_m_s", t.u.1)?;
            e.set_item("feature_cells_per_step", t.cells_per_step.0)?;
            e.set_item("film_cells_per_step", t.cells_per_step.1)?;
            // the steps that give one cell a step where the case's are coarse, else None
            e.set_item("steps_for_one_cell", t.steps_for_one_cell)?;
            e.set_item("frames_every", t.frames_every)?;
            e.set_item("frames_bytes", t.frames_bytes)?;
            d.set_item("transient", e)?;
        } else {
            d.set_item("transient", py.None())?;
        }
        if let Some(t) = &r.thermal {
            let e = PyDict::new(py);
            e.set_item("inlet_temperature_k", t.inlet_temperature)?;
            e.set_item("viscosity_beta_1_k", t.beta)?;
            e.set_item("thermal_loading_L", t.loading)?;
            e.set_item("murch_wilson_film_ratio", t.murch_wilson)?;
            e.set_item("gupta_film_ratio", t.gupta)?;
            e.set_item("peclet_1", t.peclet[0])?;
            e.set_item("peclet_2", t.peclet[1])?;
            e.set_item("points_across_film", t.points_across_film)?;
            e.set_item(
                "above_converged_loading",
                t.loading > ehl::ehl::thermal::CONVERGED_THERMAL_LOADING,
            )?;
            d.set_item("thermal", e)?;
        } else {
            d.set_item("thermal", py.None())?;
        }
        Ok(d)
    }

    /// A copy (`set` on the copy leaves this case as it is).
    fn copy(&self) -> Self {
        self.clone()
    }

    fn __copy__(&self) -> Self {
        self.clone()
    }

    fn __deepcopy__(&self, _memo: &Bound<'_, PyAny>) -> Self {
        self.clone()
    }

    /// Pickling (e.g. for a process pool): the case file's text, its name and the overrides;
    /// unpickling parses and validates them again (a height map is read again from its path).
    fn __reduce__<'py>(
        slf: &Bound<'py, Self>,
    ) -> PyResult<(Bound<'py, PyAny>, (String, String, Vec<String>))> {
        let f = slf.py().import("ehl._ehl")?.getattr("_case_from_state")?;
        let c = slf.borrow();
        Ok((f, (c.text.clone(), c.file.clone(), c.overrides.clone())))
    }

    /// The case file (made absolute by `from_file`), or the name given to `from_toml` /
    /// `from_dict` (`<string>`, `<dict>` by default).
    #[getter]
    fn file(&self) -> &str {
        &self.file
    }

    #[getter]
    fn title(&self) -> &str {
        &self.case.title
    }

    /// "dry" or "ehl".
    #[getter]
    fn kind(&self) -> &'static str {
        match self.case.kind {
            ehl::case::Kind::Dry => "dry",
            ehl::case::Kind::Ehl => "ehl",
        }
    }

    /// True for a transient run (`motion.travel` given).
    #[getter]
    fn transient(&self) -> bool {
        ehl::run::transient::kinematics(&self.case).is_some()
    }

    /// The overrides applied so far, as `--set` arguments (`"load.force=5000"`).
    #[getter]
    fn overrides(&self) -> Vec<String> {
        self.overrides.clone()
    }

    fn __repr__(&self) -> String {
        let c = &self.case;
        let mut parts = vec![format!("{:?}", c.title), format!("kind={}", self.kind())];
        let transient = ehl::run::transient::kinematics(c);
        if let Some(k) = transient {
            parts.push(format!("transient ({} steps)", k.steps));
        }
        if c.is_infinite_line() {
            parts.push(format!(
                "load {}",
                si(c.load.force_per_length, 1e-3, "kN/m", 1)
            ));
        } else {
            parts.push(format!("load {}", si(c.load.force, 1.0, "N", 1)));
        }
        if let Some(m) = &c.motion {
            parts.push(format!(
                "u_e {} SRR {}",
                si(m.entrainment_speed, 1.0, "m/s", 3),
                m.slide_to_roll
            ));
        }
        if !c.features.is_empty() {
            parts.push(format!("{} feature(s)", c.features.len()));
        }
        parts.push(format!("grid {} x {}", c.grid.nx, c.grid.ny));
        parts.push(format!("file={:?}", self.file));
        if !self.overrides.is_empty() {
            parts.push(format!("set={:?}", self.overrides));
        }
        format!("ehl.Case({})", parts.join(", "))
    }
}

/// A TOML key, quoted when it is not a bare key.
fn toml_key(k: &str) -> String {
    if !k.is_empty()
        && k.chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
    {
        k.to_string()
    } else {
        toml::Value::String(k.to_string()).to_string()
    }
}

// ------------------------------------------------------------------ Solution

/// A solved case: the library's solution and the case it came from. Immutable.
#[pyclass(module = "ehl", name = "Solution", frozen, weakref)]
struct PySolution {
    case: PyCase,
    sol: ehl::solution::Solution,
}

/// A read-only NumPy view (ny, nx) of `data`, owned by `owner` (no copy).
fn view<'py>(owner: &Bound<'py, PySolution>, data: &[f64]) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let g = owner.get().sol.grid;
    let v = ArrayView2::from_shape((g.ny, g.nx), data)
        .map_err(|e| PyTypeError::new_err(format!("field of the wrong size: {e}")))?;
    // SAFETY: `data` lives in the frozen (never mutated) Solution that the array keeps alive
    // through its base object; the array is made read-only below.
    let a = unsafe { PyArray2::borrow_from_array(&v, owner.clone().into_any()) };
    let kw = PyDict::new(owner.py());
    kw.set_item("write", false)?;
    a.call_method("setflags", (), Some(&kw))?;
    Ok(a)
}

fn optional_view<'py>(
    owner: &Bound<'py, PySolution>,
    data: Option<&Vec<f64>>,
) -> PyResult<Option<Bound<'py, PyArray2<f64>>>> {
    data.map(|d| view(owner, d)).transpose()
}

/// Columns of a list of serialisable records as NumPy arrays: bool columns as bool, whole
/// numbers as int64, others as float64 (null as NaN).
fn columns<'py, T: serde::Serialize>(py: Python<'py>, rows: &[T]) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let values: Vec<serde_json::Value> = rows
        .iter()
        .map(|r| serde_json::to_value(r).unwrap_or(serde_json::Value::Null))
        .collect();
    let Some(serde_json::Value::Object(first)) = values.first() else {
        return Ok(d);
    };
    for key in first.keys() {
        let col: Vec<&serde_json::Value> = values
            .iter()
            .map(|v| v.get(key).unwrap_or(&serde_json::Value::Null))
            .collect();
        if col.iter().all(|v| v.is_boolean()) {
            let b: Vec<bool> = col.iter().map(|v| v.as_bool().unwrap_or(false)).collect();
            d.set_item(key, PyArray1::from_vec(py, b))?;
        } else if col.iter().all(|v| v.is_u64() || v.is_i64()) {
            let i: Vec<i64> = col.iter().map(|v| v.as_i64().unwrap_or(0)).collect();
            d.set_item(key, PyArray1::from_vec(py, i))?;
        } else {
            let f: Vec<f64> = col.iter().map(|v| v.as_f64().unwrap_or(f64::NAN)).collect();
            d.set_item(key, PyArray1::from_vec(py, f))?;
        }
    }
    Ok(d)
}

#[pymethods]
impl PySolution {
    /// The figures of `summary.json` as a dict (SI): `converged`, `max_pressure_pa`,
    /// `central_film_m`, `min_film_m`, `friction_coefficient`, ..., `grid_m` and `case` (the
    /// resolved case with every default).
    #[getter]
    fn summary<'py>(&self, py: Python<'py>) -> PyResult<Py<PyAny>> {
        let text =
            ehl::output::summary::to_json(&self.case.case, &self.sol).map_err(|e| py_err(py, e))?;
        let v: serde_json::Value = serde_json::from_str(&text)
            .map_err(|e| PyTypeError::new_err(format!("summary: {e}")))?;
        from_json(py, &v)
    }

    /// Whether the solver converged (a transient run: every step).
    #[getter]
    fn converged(&self) -> bool {
        self.sol.summary.converged
    }

    /// The case that was solved (a copy).
    #[getter]
    fn case(&self) -> PyCase {
        self.case.clone()
    }

    /// Cell centres along x (m), shape (nx,).
    #[getter]
    fn x<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let g = self.sol.grid;
        PyArray1::from_vec(py, (0..g.nx).map(|i| g.x(i)).collect())
    }

    /// Cell centres along y (m), shape (ny,) (an infinite line contact: one cell, y = 0).
    #[getter]
    fn y<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let g = self.sol.grid;
        PyArray1::from_vec(py, (0..g.ny).map(|j| g.y(j)).collect())
    }

    /// Pressure (Pa), shape (ny, nx), read-only view (a transient run: the last step).
    #[getter]
    fn pressure<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        view(slf, &slf.get().sol.fields.pressure)
    }

    /// Film thickness (m), shape (ny, nx); dry contact: the loaded gap; inf where a body has
    /// no material.
    #[getter]
    fn film<'py>(slf: &Bound<'py, Self>) -> PyResult<Option<Bound<'py, PyArray2<f64>>>> {
        optional_view(slf, slf.get().sol.fields.film.as_ref())
    }

    /// Combined elastic deflection of both surfaces (m), shape (ny, nx).
    #[getter]
    fn deformation<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        view(slf, &slf.get().sol.fields.deformation)
    }

    /// Viscosity (Pa s), shape (ny, nx); None for a dry contact.
    #[getter]
    fn viscosity<'py>(slf: &Bound<'py, Self>) -> PyResult<Option<Bound<'py, PyArray2<f64>>>> {
        optional_view(slf, slf.get().sol.fields.viscosity.as_ref())
    }

    /// Density (kg/m^3), shape (ny, nx); None for a dry contact.
    #[getter]
    fn density<'py>(slf: &Bound<'py, Self>) -> PyResult<Option<Bound<'py, PyArray2<f64>>>> {
        optional_view(slf, slf.get().sol.fields.density.as_ref())
    }

    /// Thermal runs (`[thermal]`): the temperatures (K) as a dict: `mid_film`, `max_film`,
    /// `surface_1`, `surface_2` as read-only (ny, nx) views (NaN where the film was not
    /// solved: beyond the cavitation boundary and in the far inlet), `film_section` (nz, nx, K)
    /// and `section_z` (nz, nx, m), the film across z along the centre grid line at
    /// `section_y` (m), and `inlet` (K). None for an isothermal run.
    #[getter]
    fn temperature<'py>(slf: &Bound<'py, Self>) -> PyResult<Option<Bound<'py, PyDict>>> {
        let py = slf.py();
        let sol = &slf.get().sol;
        let Some(t) = sol.temperature.as_ref() else {
            return Ok(None);
        };
        let d = PyDict::new(py);
        d.set_item("mid_film", view(slf, &t.mid_film)?)?;
        d.set_item("max_film", view(slf, &t.max_film)?)?;
        d.set_item("surface_1", view(slf, &t.surface_1)?)?;
        d.set_item("surface_2", view(slf, &t.surface_2)?)?;
        let nx = sol.grid.nx;
        for (name, v) in [
            ("film_section", &t.film_section),
            ("section_z", &t.section_z),
        ] {
            let a = PyArray1::from_slice(py, v).reshape([t.nz, nx])?;
            d.set_item(name, a)?;
        }
        d.set_item("section_y", sol.grid.y(t.section_row))?;
        d.set_item("inlet", t.inlet)?;
        Ok(Some(d))
    }

    /// `[stress]` runs: the content of `stress.npz` as a dict: `x` (nx), `y` (ny), `z` (nz, m),
    /// and for each computed body k `sxx_k`, `syy_k`, `szz_k`, `syz_k`, `sxz_k`, `sxy_k`,
    /// `von_mises_k`, `tresca_k` (Pa, float32 arrays shaped (nz, ny, nx); copies), plus
    /// `x_p_m` (the kept frame a transient run's stress is of, else None) and `with_traction`.
    /// None without `[stress]`.
    #[getter]
    fn stress<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyDict>>> {
        let Some(a) = self.sol.stress.as_ref() else {
            return Ok(None);
        };
        let g = &a.grid;
        let d = PyDict::new(py);
        let x: Vec<f64> = (0..g.nx).map(|i| g.x(i)).collect();
        let y: Vec<f64> = (0..g.ny).map(|j| g.y(j)).collect();
        d.set_item("x", PyArray1::from_vec(py, x))?;
        d.set_item("y", PyArray1::from_vec(py, y))?;
        let z = a
            .bodies
            .first()
            .map(|b| b.field.z.clone())
            .unwrap_or_default();
        let nz = z.len();
        d.set_item("z", PyArray1::from_vec(py, z))?;
        for b in &a.bodies {
            let named = ehl::stress::kernel::COMPONENTS
                .iter()
                .zip(b.field.components.iter())
                .map(|(n, v)| (*n, v))
                .chain([("von_mises", &b.von_mises), ("tresca", &b.max_shear)]);
            for (name, v) in named {
                let arr = PyArray1::from_slice(py, v).reshape([nz, g.ny, g.nx])?;
                d.set_item(format!("{name}_{}", b.body), arr)?;
            }
        }
        d.set_item("x_p_m", a.step.map(|s| s.1))?;
        d.set_item("with_traction", a.with_traction)?;
        Ok(Some(d))
    }

    /// Transient runs: `timeline.csv` as a dict of columns (NumPy arrays, one entry per step,
    /// step 0 the steady start): `step`, `time_s`, `x_p_m`, `max_pressure_pa`, `min_film_m`,
    /// `central_film_m`, `friction_coefficient` (NaN where not computed), `converged`, ...;
    /// thermal runs add the temperature columns (`max_film_temperature_k`, ...). None for a
    /// steady run.
    #[getter]
    fn timeline<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyDict>>> {
        self.sol
            .transient
            .as_ref()
            .map(|t| columns(py, &t.timeline))
            .transpose()
    }

    /// Transient runs: the kept frames (every `output.frames_every`-th step), a list of dicts
    /// with `step`, `time_s`, `x_p_m` and read-only (ny, nx) views `pressure` (Pa) and `film`
    /// (m). None for a steady run.
    #[getter]
    fn frames<'py>(slf: &Bound<'py, Self>) -> PyResult<Option<Bound<'py, PyList>>> {
        let py = slf.py();
        let Some(t) = slf.get().sol.transient.as_ref() else {
            return Ok(None);
        };
        let l = PyList::empty(py);
        for f in &t.frames {
            let d = PyDict::new(py);
            d.set_item("step", f.step)?;
            d.set_item("time_s", f.time_s)?;
            d.set_item("x_p_m", f.x_p_m)?;
            d.set_item("pressure", view(slf, &f.pressure)?)?;
            d.set_item("film", view(slf, &f.film)?)?;
            l.append(d)?;
        }
        Ok(Some(l))
    }

    /// Transient runs: the full fields at `output.snapshots`, a list of dicts with
    /// `x_p_m` (requested), `step` (the nearest step) and the (ny, nx) views `pressure`, `film`,
    /// `deformation`, `viscosity`, `density`. None for a steady run.
    #[getter]
    fn snapshots<'py>(slf: &Bound<'py, Self>) -> PyResult<Option<Bound<'py, PyList>>> {
        let py = slf.py();
        let Some(t) = slf.get().sol.transient.as_ref() else {
            return Ok(None);
        };
        let l = PyList::empty(py);
        for (x, step, f) in &t.snapshots {
            let d = PyDict::new(py);
            d.set_item("x_p_m", *x)?;
            d.set_item("step", *step)?;
            d.set_item("pressure", view(slf, &f.pressure)?)?;
            d.set_item("film", optional_view(slf, f.film.as_ref())?)?;
            d.set_item("deformation", view(slf, &f.deformation)?)?;
            d.set_item("viscosity", optional_view(slf, f.viscosity.as_ref())?)?;
            d.set_item("density", optional_view(slf, f.density.as_ref())?)?;
            l.append(d)?;
        }
        Ok(Some(l))
    }

    /// Writes the outputs of `ehl run` into `dir` (summary.json, fields.npz, fields.vtk, the
    /// csv profiles, the pictures; transient runs add the timeline, frames, animation and
    /// snapshots). Atomic: the files go into a temporary folder that replaces `dir` only when
    /// all are written; `dir` is replaced only if ehl wrote it (or it is empty). Returns `dir`
    /// (a `pathlib.Path`). Not interruptible: the GIL is released and no signal is checked
    /// until the write has ended, so Ctrl-C raises KeyboardInterrupt only after it, with `dir`
    /// complete (or, on an error, as it was).
    fn write(&self, py: Python<'_>, dir: PathBuf) -> PyResult<PathBuf> {
        py.detach(|| ehl::output::write_all(&dir, &self.case.case, &self.sol))
            .map_err(|e| py_err(py, e))?;
        Ok(dir)
    }

    fn __repr__(&self) -> String {
        let s = &self.sol.summary;
        let mut parts = vec![format!(
            "max pressure {:.4} GPa (Hertz {:.4} GPa)",
            s.max_pressure_pa * 1e-9,
            s.hertz_pressure_pa * 1e-9
        )];
        if let Some(h) = s.central_film_m {
            parts.push(format!("central film {:.4} um", h * 1e6));
        }
        if let Some(h) = s.min_film_m {
            parts.push(format!("minimum film {:.4} um", h * 1e6));
        }
        if let Some(a) = s.approach_m {
            parts.push(format!("approach {:.4} um", a * 1e6));
        }
        if let Some(f) = s.friction_coefficient {
            parts.push(format!("friction {f:.5}"));
        }
        if let Some(h) = s.min_film_over_travel_m {
            parts.push(format!("minimum film over the travel {:.4} um", h * 1e6));
        }
        let state = match s.steps {
            Some(n) => {
                let failed = s.failed_steps.as_ref().map_or(0, |f| f.len());
                if failed == 0 {
                    format!("{n} time steps, all converged")
                } else {
                    format!("{n} time steps, {failed} NOT converged")
                }
            }
            None if s.converged => format!("converged in {} iterations", s.iterations),
            None => format!("NOT converged ({})", s.termination),
        };
        let g = self.sol.grid;
        format!(
            "<ehl.Solution {:?}: {state}, {:.2} s, {} x {} cells: {}>",
            self.case.case.title,
            s.wall_time_s,
            g.nx,
            g.ny,
            parts.join(", ")
        )
    }
}

// ------------------------------------------------------------------ solve

/// The latest progress report of a solve, for the waiting thread to pass on.
#[derive(Default)]
struct Reporter(Mutex<Option<(f64, String)>>);

impl ehl::run::Progress for Reporter {
    fn report(&self, fraction: f64, message: &str) {
        if let Ok(mut s) = self.0.lock() {
            *s = Some((fraction, message.to_string()));
        }
    }
}

impl Reporter {
    fn take(&self) -> Option<(f64, String)> {
        self.0.lock().ok().and_then(|mut s| s.take())
    }
}

/// The tokens of the solves running now in this process (any thread), by a number of their
/// own: `cancel_all` cancels them. A solve registers its token when it starts and removes it
/// when it ends (`Registered`'s drop, also on an error or a panic).
static LIVE: Mutex<Vec<(u64, CancelToken)>> = Mutex::new(Vec::new());
static NEXT_ID: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);

/// A token in `LIVE` for as long as this value lives.
struct Registered(u64);

impl Registered {
    fn new(token: &CancelToken) -> Self {
        let id = NEXT_ID.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        live().push((id, token.clone()));
        Registered(id)
    }
}

impl Drop for Registered {
    fn drop(&mut self) {
        live().retain(|(id, _)| *id != self.0);
    }
}

/// `LIVE`, locked (a panic while it was held cannot leave it inconsistent: push and retain).
fn live() -> std::sync::MutexGuard<'static, Vec<(u64, CancelToken)>> {
    LIVE.lock().unwrap_or_else(|e| e.into_inner())
}

/// Cancels every solve running now in this process, in any thread; returns how many. Each
/// stops within a solver iteration and raises KeyboardInterrupt in its own thread. Solves
/// started later are not affected. For Ctrl-C with solves in worker threads (Python delivers
/// the signal to the main thread only): `except KeyboardInterrupt: ehl.cancel_all(); raise`.
#[pyfunction]
fn cancel_all() -> usize {
    let live = live();
    for (_, t) in live.iter() {
        t.cancel();
    }
    live.len()
}

/// Solves `case` with the GIL released (see the module documentation). `callback(fraction,
/// message)` receives progress reports, at most one per `poll` seconds. Ctrl-C (a signal seen
/// by the main thread) or an exception raised by the callback cancels the solve: the error is
/// raised once the solver has stopped (within a solver iteration).
#[pyfunction]
#[pyo3(signature = (case, callback = None, poll = 0.05))]
fn _solve(
    py: Python<'_>,
    case: &Bound<'_, PyCase>,
    callback: Option<Bound<'_, PyAny>>,
    poll: f64,
) -> PyResult<PySolution> {
    let case = busy(case.try_borrow())?.clone();
    let token = CancelToken::new();
    let _registered = Registered::new(&token);
    let reporter = Reporter::default();
    // (NaN, which `clamp` passes through and `Duration` panics on, as the default)
    let poll = Duration::from_secs_f64(if poll.is_nan() {
        0.05
    } else {
        poll.clamp(0.001, 1.0)
    });
    let (tx, rx) = mpsc::channel();
    // (a Mutex: the GIL-free closures below must be Send, and a Receiver is not Sync)
    let rx = Mutex::new(rx);
    let recv = |timeout: Option<Duration>| {
        let rx = rx.lock().unwrap_or_else(|e| e.into_inner());
        match timeout {
            Some(t) => rx.recv_timeout(t),
            None => rx.recv().map_err(|_| mpsc::RecvTimeoutError::Disconnected),
        }
    };
    let result = std::thread::scope(|s| -> PyResult<_> {
        let (c, rep, tok) = (&case.case, &reporter, &token);
        std::thread::Builder::new()
            .name("ehl-solve".into())
            .spawn_scoped(s, move || {
                let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                    cancel::solve(c, rep, tok)
                }));
                let _ = tx.send(r);
            })
            .map_err(|e| {
                py_err(
                    py,
                    ehl::Error::Solver(format!("cannot start a thread: {e}")),
                )
            })?;
        let stop = |e: PyErr| -> PyResult<_> {
            token.cancel();
            let _ = py.detach(|| recv(None));
            Err(e)
        };
        loop {
            match py.detach(|| recv(Some(poll))) {
                Ok(r) => return Ok(r),
                Err(mpsc::RecvTimeoutError::Disconnected) => {
                    return Err(py_err(
                        py,
                        ehl::Error::Solver("the solver's thread ended without a result".into()),
                    ))
                }
                Err(mpsc::RecvTimeoutError::Timeout) => {}
            }
            if let Err(e) = py.check_signals() {
                return stop(e);
            }
            if let (Some(cb), Some((f, m))) = (&callback, reporter.take()) {
                if let Err(e) = cb.call1((f, m)) {
                    return stop(e);
                }
            }
        }
    })?;
    let sol = match result {
        Ok(Ok(sol)) => sol,
        Ok(Err(e)) => return Err(py_err(py, e)),
        Err(panic) => {
            let what = panic
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| panic.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown".into());
            return Err(py_err(
                py,
                ehl::Error::Solver(format!(
                    "internal error (a bug in ehl, please report it): {what}"
                )),
            ));
        }
    };
    if let (Some(cb), Some((f, m))) = (&callback, reporter.take()) {
        cb.call1((f, m))?;
    }
    Ok(PySolution { case, sol })
}

/// The inverse of `Case.__reduce__`: the case of a file's text, its name and the overrides.
/// The Python exception that a library error of `kind` ("case", "case-file", "output",
/// "solver", "cancelled") with `reason` becomes, returned, not raised: for the tests of the
/// error mapping, since a case that makes the solver fail is refused before it reaches it.
#[pyfunction]
fn _exception_for(py: Python<'_>, kind: &str, reason: String) -> PyResult<Py<PyAny>> {
    let e = match kind {
        "case" => ehl::Error::Case {
            file: "case.toml".into(),
            key: "load.force".into(),
            message: reason,
        },
        "case-file" => ehl::Error::CaseFile {
            file: "case.toml".into(),
            message: reason,
        },
        "output" => ehl::Error::Output {
            path: "out".into(),
            message: reason,
        },
        "solver" => ehl::Error::Solver(reason),
        "cancelled" => ehl::Error::Cancelled,
        other => {
            return Err(pyo3::exceptions::PyValueError::new_err(format!(
                "unknown error kind {other:?}"
            )))
        }
    };
    Ok(py_err(py, e).into_value(py).into_any())
}

#[pyfunction]
fn _case_from_state(
    py: Python<'_>,
    text: String,
    file: String,
    overrides: Vec<String>,
) -> PyResult<PyCase> {
    PyCase::parse(py, text, file, overrides)
}

#[pymodule]
fn _ehl(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(_case_from_state, m)?)?;
    m.add_function(wrap_pyfunction!(_exception_for, m)?)?;
    m.add_class::<PyCase>()?;
    m.add_class::<PySolution>()?;
    m.add_function(wrap_pyfunction!(_solve, m)?)?;
    m.add_function(wrap_pyfunction!(cancel_all, m)?)?;
    m.add("__version__", ehl::VERSION)?;
    Ok(())
}
