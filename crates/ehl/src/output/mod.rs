//! Writers: `summary.json`, `fields.npz`, `fields.vtk`, `centerline.csv`, `axial.csv`,
//! `pressure.png`, `film.png`, `centerline.png` (see the "Outputs in DIR" table of the interface).
//!
//! [`write_all`] is atomic: every file goes into a temporary sibling folder
//! (`.<DIR name>.tmp-<pid>-<n>`), which replaces `DIR` only when every file is written. On any
//! failure the temporary folder is removed and an old `DIR` is left untouched, so a half-written
//! output folder never exists under the final name.
//!
//! **Never deleting the user's files.** Every output folder holds the marker file
//! [`MARKER`] (`.ehl-output`, with the program version). An existing `DIR` is replaced only if it
//! holds the marker or is empty; otherwise the write is refused, naming the folder, before
//! anything is solved when the caller takes the lock first (the CLI does). A folder written by an
//! ehl without markers must be removed by hand once.
//!
//! **One writer per folder.** [`OutputLock`] locks `.<DIR name>.lock` beside `DIR`
//! ([`std::fs::File::try_lock`], released by the system when the process ends, even by a kill);
//! a second process writing the same `DIR` is refused at once ("another ehl process is writing
//! DIR"). The lock file is removed when the lock is dropped.
//!
//! **Interrupted writes.** A process killed while writing leaves `.<DIR name>.tmp-<pid>-<n>` (or
//! `.old-<pid>-<n>`) beside `DIR`; the next write of `DIR` removes those whose process no longer
//! runs (Linux: no `/proc/<pid>`). The CLI also removes its own on Ctrl-C or SIGTERM through
//! [`abort_cleanup`].
//!
//! Before anything is written the solution is checked: every field must have `nx * ny` values and
//! every value must be finite, and so must every summary figure. A NaN or infinity is refused with
//! an error naming the field (and the cell) or the summary key: the program never writes a NaN
//! silently. The one exception is `film`, which may be `+inf` in cells where there is no material
//! (beyond the end of the shorter roller, per the gap convention of the crate); those cells are
//! written as `inf` in `fields.npz`, `fields.vtk` and the csv files, drawn grey on `film.png` and
//! left out of every range and extreme.
//!
//! | file | writer |
//! | --- | --- |
//! | `summary.json` | [`summary`] |
//! | `fields.npz` | [`npz`] |
//! | `fields.vtk` | [`vtk`] |
//! | `centerline.csv`, `axial.csv` | [`csv`] |
//! | `pressure.png`, `film.png`, `centerline.png` | [`plot`] |
//! | transient runs: `timeline.csv`, `frames.npz`, `timeline.png`, `passage.gif`, `passage.pvd` with `frames/`, `snapshots/` | [`transient`] |

pub mod colormap;
pub mod csv;
pub mod npz;
pub mod plot;
pub mod stream;
pub mod stress;
pub mod summary;
pub mod synthetic;
pub mod temperature;
pub mod transient;
pub mod vtk;

use crate::case::Case;
use crate::solution::Solution;
use crate::{Error, Result};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Mutex, MutexGuard};

/// Names of the files [`write_all`] writes (film.png only when the solution has a film).
pub const SUMMARY_JSON: &str = "summary.json";
pub const FIELDS_NPZ: &str = "fields.npz";
pub const FIELDS_VTK: &str = "fields.vtk";
pub const CENTERLINE_CSV: &str = "centerline.csv";
pub const AXIAL_CSV: &str = "axial.csv";
pub const PRESSURE_PNG: &str = "pressure.png";
pub const FILM_PNG: &str = "film.png";
pub const CENTERLINE_PNG: &str = "centerline.png";

/// Writes every output of a solved case into `dir`, atomically: all files go to a temporary
/// sibling folder which replaces `dir` only when every file is written. An existing `dir` is
/// replaced only if ehl wrote it (it holds the [`MARKER`] file) or it is empty; missing parent
/// folders are created. Takes the output's [`OutputLock`] for the time of the write; a caller
/// that solves first should take the lock before solving and call [`write_locked`].
///
/// Errors ([`Error::Output`], naming the path): a field of the wrong length, a NaN or infinite
/// value (naming the field or summary key), a folder that ehl did not write, another process
/// writing the same folder, any I/O or drawing failure. After an error neither `dir` nor the
/// temporary folder has changed or remains.
pub fn write_all(dir: &Path, case: &Case, solution: &Solution) -> Result<()> {
    validate(dir, solution)?;
    let lock = OutputLock::acquire(dir)?;
    write_locked(&lock, case, solution)
}

/// [`write_all`] into the folder that `lock` holds.
pub fn write_locked(lock: &OutputLock, case: &Case, solution: &Solution) -> Result<()> {
    let dir = lock.dir();
    write_with(
        dir,
        |tmp| write_files(tmp, case, solution, None),
        || validate(dir, solution),
    )
}

/// The outputs of a run whose transient files were streamed into `staging` by `stream` as it
/// ran ([`stream::TransientStream`]; `None` for a steady run): checks the solution
/// ([`validate`]), writes the other files beside them and puts the folder in place of the
/// output folder. On an error the staging folder is removed and the output folder is as it was.
/// The caller holds the output's [`OutputLock`].
pub fn write_staged(
    staging: Staging,
    case: &Case,
    solution: &Solution,
    stream: Option<stream::TransientStream>,
) -> Result<()> {
    validate(&staging.dir, solution)?;
    write_files(staging.path(), case, solution, stream)?;
    staging.commit()
}

/// Checks that a solution can be written: field lengths, finite values, finite summary figures,
/// and for a transient run the timeline, frames and snapshots ([`transient::validate`]).
/// [`write_all`] calls it first; it is public so that callers can check before a long write.
pub fn validate(dir: &Path, solution: &Solution) -> Result<()> {
    let g = &solution.grid;
    let err = |message: String| Error::Output {
        path: dir.to_path_buf(),
        message,
    };
    if g.nx == 0 || g.ny == 0 {
        return Err(err(format!("empty grid ({} x {} cells)", g.nx, g.ny)));
    }
    for (name, v) in [
        ("dx", g.dx),
        ("dy", g.dy),
        ("x_min", g.x_min),
        ("y_min", g.y_min),
    ] {
        if !v.is_finite() || ((name == "dx" || name == "dy") && v <= 0.0) {
            return Err(err(format!(
                "grid.{name} = {v} is not a finite positive size"
            )));
        }
    }
    for (name, field) in named_fields(solution) {
        check_field(g, "", name, field).map_err(&err)?;
    }
    if solution
        .fields
        .film
        .as_ref()
        .is_some_and(|f| f.iter().all(|v| !v.is_finite()))
    {
        return Err(err("field `film` has no finite value".into()));
    }
    summary::check_finite(&solution.summary).map_err(|key| {
        err(format!(
            "summary figure `{key}` is not finite; refusing to write a non-finite value"
        ))
    })?;
    if let Some(t) = &solution.transient {
        transient::validate(g, t).map_err(err)?;
    }
    Ok(())
}

/// Checks one field of a solution (`at`: where it is, e.g. "frame of step 12", empty for the
/// solution's own fields): `grid.len()` values, none NaN or infinite, except `+inf` in `film`
/// (no material). The message names the field and the first bad cell.
pub(crate) fn check_field(
    g: &crate::grid::Grid,
    at: &str,
    name: &str,
    field: &[f64],
) -> std::result::Result<(), String> {
    let at = if at.is_empty() {
        String::new()
    } else {
        format!("{at}: ")
    };
    if field.len() != g.len() {
        return Err(format!(
            "{at}field `{name}` has {} values, the {} x {} grid needs {}",
            field.len(),
            g.nx,
            g.ny,
            g.len()
        ));
    }
    let allow_pos_inf = name == "film";
    if let Some(k) = field
        .iter()
        .position(|v| v.is_nan() || (v.is_infinite() && !(allow_pos_inf && *v > 0.0)))
    {
        let (i, j) = (k % g.nx, k / g.nx);
        return Err(format!(
            "{at}field `{name}` is {} at cell (i = {i}, j = {j}), x = {:.6e} m, y = {:.6e} m; \
             refusing to write a non-finite value",
            field[k],
            g.x(i),
            g.y(j)
        ));
    }
    Ok(())
}

/// The fields present in a solution, by their output name, in output order.
pub(crate) fn named_fields(solution: &Solution) -> Vec<(&'static str, &[f64])> {
    named(&solution.fields)
}

/// The fields present, by their output name, in output order.
pub(crate) fn named(f: &crate::solution::Fields) -> Vec<(&'static str, &[f64])> {
    let mut v: Vec<(&'static str, &[f64])> = vec![
        ("pressure", &f.pressure[..]),
        ("deformation", &f.deformation[..]),
    ];
    if let Some(h) = &f.film {
        v.push(("film", &h[..]));
    }
    if let Some(e) = &f.viscosity {
        v.push(("viscosity", &e[..]));
    }
    if let Some(r) = &f.density {
        v.push(("density", &r[..]));
    }
    v
}

fn write_files(
    tmp: &Path,
    case: &Case,
    solution: &Solution,
    stream: Option<stream::TransientStream>,
) -> Result<()> {
    summary::write(&tmp.join(SUMMARY_JSON), case, solution)?;
    npz::write(&tmp.join(FIELDS_NPZ), solution)?;
    vtk::write(&tmp.join(FIELDS_VTK), case, solution)?;
    csv::write_centerline(&tmp.join(CENTERLINE_CSV), solution)?;
    csv::write_axial(&tmp.join(AXIAL_CSV), solution)?;
    plot::write_pressure(&tmp.join(PRESSURE_PNG), case, solution)?;
    if solution.fields.film.is_some() {
        plot::write_film(&tmp.join(FILM_PNG), case, solution)?;
    }
    plot::write_centerline(&tmp.join(CENTERLINE_PNG), case, solution)?;
    match stream {
        Some(s) => s.finish(case, solution)?,
        None => transient::write(tmp, case, solution)?,
    }
    stress::write(tmp, case, solution)?;
    temperature::write(tmp, case, solution)?;
    Ok(())
}

static SEQ: AtomicUsize = AtomicUsize::new(0);

fn io_err(path: &Path, e: impl std::fmt::Display) -> Error {
    Error::Output {
        path: path.to_path_buf(),
        message: e.to_string(),
    }
}

/// An I/O failure on `at` while writing the output folder `dir`: names `dir` (what the user
/// gave), and `at` and the reason in words.
fn io_err_at(dir: &Path, at: &Path, what: &str, e: &std::io::Error) -> Error {
    let reason = match e.kind() {
        std::io::ErrorKind::PermissionDenied => "permission denied".to_string(),
        std::io::ErrorKind::ReadOnlyFilesystem => "read-only file system".to_string(),
        std::io::ErrorKind::StorageFull => "no space left on the device".to_string(),
        _ => e.to_string(),
    };
    io_err(dir, format!("{what} `{}`: {reason}", at.display()))
}

// ---------------------------------------------------------------- ownership marker

/// The file that marks a folder as written by ehl: [`write_all`] puts it in every output folder
/// (with the program version) and replaces only a folder that holds it or is empty, so that
/// `--out` pointed at a folder of the user's own files never deletes them.
pub const MARKER: &str = ".ehl-output";

fn marker_text() -> String {
    format!(
        "ehl {} output folder\nWritten by the ehl program; ehl replaces this folder as a whole \
         when it writes here again. Remove this file to keep ehl from replacing the folder.\n",
        env!("CARGO_PKG_VERSION")
    )
}

/// Writes the ownership marker into `dir` (a folder ehl has just created).
pub fn write_marker(dir: &Path) -> Result<()> {
    let path = dir.join(MARKER);
    std::fs::write(&path, marker_text()).map_err(|e| io_err(&path, e))
}

/// Ok if ehl may replace `dir`: it does not exist, is an empty folder, or holds the [`MARKER`].
/// Otherwise an error naming the folder, the reason and how to go on.
pub fn check_replaceable(dir: &Path) -> Result<()> {
    let meta = match std::fs::metadata(dir) {
        Ok(m) => m,
        // missing, or under a file (the write names the file when it creates the parents)
        Err(e)
            if matches!(
                e.kind(),
                std::io::ErrorKind::NotFound | std::io::ErrorKind::NotADirectory
            ) =>
        {
            return Ok(())
        }
        Err(e) => return Err(io_err_at(dir, dir, "cannot read", &e)),
    };
    if !meta.is_dir() {
        return Err(io_err(
            dir,
            "exists and is not a folder; not replacing it (choose another output folder)",
        ));
    }
    let mut entries = std::fs::read_dir(dir).map_err(|e| io_err_at(dir, dir, "cannot read", &e))?;
    let empty = entries.next().is_none();
    if empty || dir.join(MARKER).is_file() {
        return Ok(());
    }
    Err(io_err(
        dir,
        format!(
            "the folder holds files that ehl did not write (it has no {MARKER} marker), so ehl \
             will not replace it; choose another output folder (--out), or empty or remove `{}` \
             first",
            dir.display()
        ),
    ))
}

// ---------------------------------------------------------------- cleanup on a signal

/// Paths to remove if the process is stopped (Ctrl-C, SIGTERM): temporary folders and files
/// being written, old folders moved aside, lock files held. The folder swap holds this lock too,
/// so a cleanup never sees a half-done swap.
static LIVE: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

fn live() -> MutexGuard<'static, Vec<PathBuf>> {
    LIVE.lock().unwrap_or_else(|e| e.into_inner())
}

/// Registers a temporary path (file or folder) for [`abort_cleanup`].
pub fn register_temp(path: &Path) {
    live().push(path.to_path_buf());
}

/// Unregisters a path given to [`register_temp`].
pub fn unregister_temp(path: &Path) {
    let mut v = live();
    if let Some(k) = v.iter().rposition(|p| p == path) {
        v.remove(k);
    }
}

/// Set by [`abort_cleanup`]: the process is ending on a signal.
static ABORTING: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

/// Whether [`abort_cleanup`] has run: a writer streaming into a temporary folder stops.
pub fn aborting() -> bool {
    ABORTING.load(Ordering::SeqCst)
}

/// For a signal handler about to end the process: removes every registered temporary folder,
/// temporary file and lock file, and keeps every writer of this process from going on (the
/// registry stays locked). An output folder is never left half replaced. Call it once, then
/// exit.
pub fn abort_cleanup() {
    // writers that stream into a temporary folder while the solver runs (a transient run's
    // frames) check this before each write and stop
    ABORTING.store(true, Ordering::SeqCst);
    let guard = live();
    for p in guard.iter() {
        match std::fs::symlink_metadata(p) {
            Ok(m) if m.is_dir() => {
                // a write already under way may add a file while the folder is emptied (the
                // removal then fails on the folder itself): try again, for at most a second
                for _ in 0..100 {
                    match std::fs::remove_dir_all(p) {
                        Err(e) if e.kind() != std::io::ErrorKind::NotFound => {
                            std::thread::sleep(std::time::Duration::from_millis(10))
                        }
                        _ => break,
                    }
                }
            }
            Ok(_) => {
                let _ = std::fs::remove_file(p);
            }
            Err(_) => {}
        }
    }
    // never unlocked: the process is about to exit
    std::mem::forget(guard);
}

/// Whether a process with this id runs. Linux: `/proc/PID` exists. Where there is no `/proc`
/// this cannot be told and the answer is `true` (nothing is cleaned then).
pub fn pid_is_running(pid: u32) -> bool {
    if pid == std::process::id() || !Path::new("/proc/self").exists() {
        return true;
    }
    Path::new("/proc").join(pid.to_string()).exists()
}

/// Removes what a killed writer of `<parent>/<name>` left behind: `.<name>.tmp-<pid>-<n>` and
/// `.<name>.old-<pid>-<n>` whose process no longer runs. Errors are ignored (best effort).
pub fn clean_stale(parent: &Path, name: &str) {
    let Ok(entries) = std::fs::read_dir(parent) else {
        return;
    };
    for e in entries.flatten() {
        let file = e.file_name();
        let Some(file) = file.to_str() else { continue };
        let Some(rest) = [".tmp-", ".old-"]
            .iter()
            .find_map(|k| file.strip_prefix(&format!(".{name}{k}")))
        else {
            continue;
        };
        let Some((pid, n)) = rest.split_once('-') else {
            continue;
        };
        let (Ok(pid), true) = (
            pid.parse::<u32>(),
            !n.is_empty() && n.bytes().all(|b| b.is_ascii_digit()),
        ) else {
            continue;
        };
        if !pid_is_running(pid) {
            let _ = std::fs::remove_dir_all(e.path());
        }
    }
}

// ---------------------------------------------------------------- the output lock

/// The parent of an output folder (`.` for a bare name) and the folder's name.
fn parent_and_name(dir: &Path) -> Result<(PathBuf, String)> {
    let name = dir
        .file_name()
        .ok_or_else(|| {
            io_err(
                dir,
                "an output folder (--out) needs a name of its own, e.g. --out out/case; the root folder cannot be one",
            )
        })?
        .to_string_lossy()
        .into_owned();
    let parent = match dir.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    Ok((parent, name))
}

/// Creates `parent` and its missing ancestors; returns the folders created, deepest first.
/// An ancestor that is a file is named as such.
fn create_parent(dir: &Path, parent: &Path) -> Result<Vec<PathBuf>> {
    let mut missing = Vec::new();
    let mut p = parent;
    loop {
        match std::fs::metadata(p) {
            Ok(m) if m.is_dir() => break,
            Ok(_) => {
                return Err(io_err(
                    dir,
                    format!("`{}` is a file, not a folder", p.display()),
                ))
            }
            // "not a directory": an ancestor is a file, named when the walk reaches it
            Err(e)
                if matches!(
                    e.kind(),
                    std::io::ErrorKind::NotFound | std::io::ErrorKind::NotADirectory
                ) =>
            {
                missing.push(p.to_path_buf())
            }
            Err(e) => return Err(io_err_at(dir, p, "cannot use the folder", &e)),
        }
        match p.parent() {
            Some(q) if !q.as_os_str().is_empty() => p = q,
            _ => break,
        }
    }
    for m in missing.iter().rev() {
        match std::fs::create_dir(m) {
            Ok(()) => {}
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists && m.is_dir() => {}
            Err(e) => return Err(io_err_at(dir, m, "cannot create the folder", &e)),
        }
    }
    Ok(missing)
}

/// Makes sure the folder `dir` exists (a sweep's folder, which holds point folders and is never
/// replaced as a whole): creates it and its parents if missing, with the [`MARKER`] in a folder
/// it created. Errors name `dir` and say why (a parent is a file, permission denied).
pub fn create_folder(dir: &Path) -> Result<()> {
    match std::fs::metadata(dir) {
        Ok(m) if m.is_dir() => return Ok(()),
        Ok(_) => {
            return Err(io_err(
                dir,
                "exists and is not a folder (choose another output folder)",
            ))
        }
        Err(_) => {}
    }
    create_parent(dir, dir)?;
    write_marker(dir)
}

/// An exclusive lock on an output folder: the file `.<name>.lock` beside it, locked with
/// [`std::fs::File::try_lock`] (an advisory lock the system drops when the process ends, even
/// when it is killed). Taken before solving and held until the folder is in place, so two
/// processes never write the same folder: the second is refused at once. Dropping it removes
/// the lock file (and the parent folders it created, if they are still empty).
#[derive(Debug)]
pub struct OutputLock {
    dir: PathBuf,
    path: PathBuf,
    file: Option<std::fs::File>,
    created: Vec<PathBuf>,
}

impl OutputLock {
    /// Takes the lock of `dir`, then removes what killed writers of `dir` left behind and
    /// checks that ehl may replace `dir` ([`check_replaceable`]). Creates missing parent
    /// folders. Errors: another process holds the lock ("another ehl process is writing
    /// DIR"), the folder is not ehl's, a parent is a file or cannot be written.
    pub fn acquire(dir: &Path) -> Result<OutputLock> {
        // `.`, `..` or `a/..` name an existing folder without a last component: use its real
        // path, so that it is judged like any other folder (the marker rule refuses it unless
        // ehl wrote it)
        let resolved;
        let dir = match (dir.file_name(), std::fs::canonicalize(dir)) {
            (None, Ok(real)) if real.file_name().is_some() => {
                resolved = real;
                resolved.as_path()
            }
            _ => dir,
        };
        let (parent, name) = parent_and_name(dir)?;
        if std::fs::metadata(dir).is_ok_and(|m| !m.is_dir()) {
            return Err(io_err(
                dir,
                "exists and is not a folder; not replacing it (choose another output folder)",
            ));
        }
        let created = create_parent(dir, &parent)?;
        let path = parent.join(format!(".{name}.lock"));
        let mut lock = OutputLock {
            dir: dir.to_path_buf(),
            path: path.clone(),
            file: None,
            created,
        };
        // a lock file removed by its owner between our open and our lock is stale: open again
        for _ in 0..20 {
            let file = std::fs::OpenOptions::new()
                .read(true)
                .write(true)
                .create(true)
                .truncate(false)
                .open(&path)
                .map_err(|e| io_err_at(dir, &parent, "cannot write in", &e))?;
            match file.try_lock() {
                Ok(()) => {}
                Err(std::fs::TryLockError::WouldBlock) => {
                    return Err(io_err(
                        dir,
                        format!(
                            "another ehl process is writing `{}` (lock file `{}`); wait for it \
                             to finish or choose another output folder",
                            dir.display(),
                            path.display()
                        ),
                    ));
                }
                // a file system without locks: go on unlocked rather than refuse every write
                Err(std::fs::TryLockError::Error(e))
                    if e.kind() == std::io::ErrorKind::Unsupported => {}
                Err(std::fs::TryLockError::Error(e)) => {
                    return Err(io_err_at(dir, &path, "cannot lock", &e));
                }
            }
            if same_file(&file, &path) {
                lock.file = Some(file);
                break;
            }
        }
        let Some(file) = &mut lock.file else {
            return Err(io_err(
                dir,
                format!("cannot take the lock `{}`", path.display()),
            ));
        };
        register_temp(&path);
        // the pid, for a person looking at the lock file
        let _ = file.set_len(0);
        let _ = writeln!(file, "{}", std::process::id());
        clean_stale(&parent, &name);
        check_replaceable(dir)?;
        Ok(lock)
    }

    /// The locked output folder.
    pub fn dir(&self) -> &Path {
        &self.dir
    }
}

#[cfg(unix)]
fn same_file(file: &std::fs::File, path: &Path) -> bool {
    use std::os::unix::fs::MetadataExt;
    match (file.metadata(), std::fs::metadata(path)) {
        (Ok(a), Ok(b)) => a.dev() == b.dev() && a.ino() == b.ino(),
        _ => false,
    }
}

#[cfg(not(unix))]
fn same_file(_: &std::fs::File, path: &Path) -> bool {
    path.exists()
}

impl Drop for OutputLock {
    fn drop(&mut self) {
        if self.file.is_some() {
            unregister_temp(&self.path);
            // removed while still locked, so a waiting process sees a stale file and reopens
            let _ = std::fs::remove_file(&self.path);
            self.file = None;
        }
        if !self.dir.exists() {
            for d in &self.created {
                if std::fs::remove_dir(d).is_err() {
                    break;
                }
            }
        }
    }
}

// ---------------------------------------------------------------- the atomic write

/// The atomic folder write: `check` runs first (nothing touched if it fails), then `fill` writes
/// into a fresh temporary sibling folder (which gets the [`MARKER`] first), which then replaces
/// `dir` if ehl may replace it ([`check_replaceable`]).
fn write_with(
    dir: &Path,
    fill: impl FnOnce(&Path) -> Result<()>,
    check: impl FnOnce() -> Result<()>,
) -> Result<()> {
    check()?;
    let staging = Staging::begin(dir)?;
    fill(staging.path())?;
    staging.commit()
}

/// The temporary sibling folder of an atomic write, open: files go into [`Staging::path`], and
/// [`Staging::commit`] puts the folder in place of `dir`. Dropped without a commit (an error on
/// the way), the folder is removed; on Ctrl-C [`abort_cleanup`] removes it. A transient run of
/// the CLI opens it before solving and streams its per-step files into it
/// ([`stream::TransientStream`]).
pub struct Staging {
    dir: PathBuf,
    parent: PathBuf,
    name: String,
    tag: String,
    tmp: PathBuf,
    open: bool,
}

impl Staging {
    /// Checks that ehl may write `dir` (not a file; replaceable: see [`check_replaceable`]),
    /// creates the missing parent folders and the temporary folder with the [`MARKER`].
    pub fn begin(dir: &Path) -> Result<Staging> {
        let (parent, name) = parent_and_name(dir)?;
        if std::fs::metadata(dir).is_ok_and(|m| !m.is_dir()) {
            return Err(io_err(
                dir,
                "exists and is not a folder; not replacing it (choose another output folder)",
            ));
        }
        check_replaceable(dir)?;
        create_parent(dir, &parent)?;
        let tag = format!(
            "{}-{}",
            std::process::id(),
            SEQ.fetch_add(1, Ordering::Relaxed)
        );
        let tmp = parent.join(format!(".{name}.tmp-{tag}"));
        if tmp.exists() {
            // a leftover of a crashed process with the same pid: it is ours to clear
            std::fs::remove_dir_all(&tmp).map_err(|e| io_err(&tmp, e))?;
        }
        register_temp(&tmp);
        if let Err(e) = std::fs::create_dir(&tmp) {
            unregister_temp(&tmp);
            return Err(io_err_at(dir, &parent, "cannot write in", &e));
        }
        let staging = Staging {
            dir: dir.to_path_buf(),
            parent,
            name,
            tag,
            tmp,
            open: true,
        };
        write_marker(&staging.tmp)?;
        Ok(staging)
    }

    /// The temporary folder being filled.
    pub fn path(&self) -> &Path {
        &self.tmp
    }

    /// The output folder it will replace (for messages).
    pub fn target(&self) -> &Path {
        &self.dir
    }

    /// Replaces `dir` by the filled folder (see [`replace_dir`]); on an error the temporary
    /// folder is removed and `dir` is as it was.
    pub fn commit(mut self) -> Result<()> {
        replace_dir(&self.tmp, &self.dir, &self.parent, &self.name, &self.tag)?;
        self.open = false;
        unregister_temp(&self.tmp);
        Ok(())
    }
}

impl Drop for Staging {
    fn drop(&mut self) {
        if self.open {
            let _ = std::fs::remove_dir_all(&self.tmp);
            unregister_temp(&self.tmp);
        }
    }
}

/// Moves `tmp` to `dir`; an existing `dir` is first moved aside and removed only once the new
/// folder is in place (it is restored if the move fails). The swap holds the cleanup registry,
/// so a Ctrl-C never leaves `dir` missing.
fn replace_dir(tmp: &Path, dir: &Path, parent: &Path, name: &str, tag: &str) -> Result<()> {
    check_replaceable(dir)?;
    let mut reg = live();
    if dir.is_dir() {
        let old = parent.join(format!(".{name}.old-{tag}"));
        std::fs::rename(dir, &old).map_err(|e| io_err(dir, e))?;
        if let Err(e) = std::fs::rename(tmp, dir) {
            let _ = std::fs::rename(&old, dir);
            return Err(io_err(dir, e));
        }
        reg.push(old.clone());
        drop(reg);
        let removed = std::fs::remove_dir_all(&old).map_err(|e| io_err(&old, e));
        unregister_temp(&old);
        removed
    } else {
        std::fs::rename(tmp, dir).map_err(|e| io_err(dir, e))
    }
}

/// Index of the row nearest y = 0 (the axial centre); for a tie the lower row.
pub(crate) fn centre_row(solution: &Solution) -> usize {
    let g = &solution.grid;
    nearest(g.ny, |j| g.y(j), 0.0)
}

/// Index of the column nearest the x of the pressure maximum (`summary.max_pressure_at_m[0]`).
pub(crate) fn max_pressure_column(solution: &Solution) -> usize {
    let g = &solution.grid;
    nearest(g.nx, |i| g.x(i), solution.summary.max_pressure_at_m[0])
}

fn nearest(n: usize, coord: impl Fn(usize) -> f64, target: f64) -> usize {
    (0..n)
        .min_by(|&a, &b| {
            (coord(a) - target)
                .abs()
                .total_cmp(&(coord(b) - target).abs())
        })
        .unwrap_or(0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn failing_fill_leaves_no_dir_and_no_temp() {
        let root = tempfile::tempdir().unwrap();
        let dir = root.path().join("out");
        let r = write_with(
            &dir,
            |tmp| {
                std::fs::write(tmp.join("summary.json"), "{}").unwrap();
                Err(io_err(&tmp.join("fields.npz"), "disk full (injected)"))
            },
            || Ok(()),
        );
        let e = r.unwrap_err().to_string();
        assert!(e.contains("fields.npz") && e.contains("injected"), "{e}");
        assert!(!dir.exists());
        assert_eq!(std::fs::read_dir(root.path()).unwrap().count(), 0);
    }

    #[test]
    fn failing_fill_keeps_old_dir() {
        let root = tempfile::tempdir().unwrap();
        let dir = root.path().join("out");
        std::fs::create_dir(&dir).unwrap();
        write_marker(&dir).unwrap();
        std::fs::write(dir.join("old.txt"), "old").unwrap();
        let r = write_with(&dir, |_| Err(io_err(&dir, "injected")), || Ok(()));
        assert!(r.is_err());
        assert_eq!(std::fs::read_to_string(dir.join("old.txt")).unwrap(), "old");
        assert_eq!(std::fs::read_dir(root.path()).unwrap().count(), 1);
    }

    #[test]
    fn success_replaces_old_dir_with_the_marker() {
        let root = tempfile::tempdir().unwrap();
        let dir = root.path().join("out");
        std::fs::create_dir(&dir).unwrap();
        write_marker(&dir).unwrap();
        std::fs::write(dir.join("stale.txt"), "old").unwrap();
        write_with(
            &dir,
            |tmp| std::fs::write(tmp.join("new.txt"), "new").map_err(|e| io_err(tmp, e)),
            || Ok(()),
        )
        .unwrap();
        assert!(!dir.join("stale.txt").exists());
        assert_eq!(std::fs::read_to_string(dir.join("new.txt")).unwrap(), "new");
        assert!(dir.join(MARKER).is_file());
        assert_eq!(std::fs::read_dir(root.path()).unwrap().count(), 1);
    }

    #[test]
    fn a_folder_without_the_marker_is_never_replaced() {
        let root = tempfile::tempdir().unwrap();
        let dir = root.path().join("mine");
        std::fs::create_dir(&dir).unwrap();
        std::fs::write(dir.join("notes.txt"), "precious").unwrap();
        let r = write_with(
            &dir,
            |tmp| std::fs::write(tmp.join("new.txt"), "new").map_err(|e| io_err(tmp, e)),
            || Ok(()),
        );
        let e = r.unwrap_err().to_string();
        assert!(e.contains("mine") && e.contains("did not write"), "{e}");
        assert_eq!(
            std::fs::read_to_string(dir.join("notes.txt")).unwrap(),
            "precious"
        );
        assert_eq!(std::fs::read_dir(root.path()).unwrap().count(), 1);
        let e = OutputLock::acquire(&dir).unwrap_err().to_string();
        assert!(e.contains("--out"), "{e}");
        // the lock file went with the refused lock
        assert_eq!(std::fs::read_dir(root.path()).unwrap().count(), 1);
    }

    #[test]
    fn a_second_lock_is_refused_and_the_lock_file_goes_with_the_first() {
        let root = tempfile::tempdir().unwrap();
        let dir = root.path().join("a/b/out");
        let first = OutputLock::acquire(&dir).unwrap();
        let e = OutputLock::acquire(&dir).unwrap_err().to_string();
        assert!(e.contains("another ehl process is writing"), "{e}");
        drop(first);
        // nothing was written: the lock file and the created parents are gone
        assert_eq!(std::fs::read_dir(root.path()).unwrap().count(), 0);
        let again = OutputLock::acquire(&dir).unwrap();
        drop(again);
    }

    #[test]
    fn stale_temp_folders_of_dead_processes_are_removed() {
        if !Path::new("/proc/self").exists() {
            return;
        }
        let root = tempfile::tempdir().unwrap();
        // a pid above the kernel's limit (4194304) never runs
        let dead = root.path().join(".out.tmp-999999999-0");
        let dead_old = root.path().join(".out.old-999999999-3");
        let alive = root
            .path()
            .join(format!(".out.tmp-{}-77", std::process::id()));
        let other = root.path().join(".other.tmp-999999999-0");
        for d in [&dead, &dead_old, &alive, &other] {
            std::fs::create_dir(d).unwrap();
        }
        let lock = OutputLock::acquire(&root.path().join("out")).unwrap();
        assert!(!dead.exists() && !dead_old.exists());
        assert!(alive.exists() && other.exists());
        drop(lock);
    }

    #[test]
    fn parent_that_is_a_file_is_named() {
        let root = tempfile::tempdir().unwrap();
        std::fs::write(root.path().join("f"), "x").unwrap();
        let e = OutputLock::acquire(&root.path().join("f/sub/out"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("f` is a file, not a folder"), "{e}");
        assert!(!e.contains("os error"), "{e}");
    }

    #[test]
    fn permission_denied_names_the_output_folder() {
        let dir = Path::new("/some/out");
        let e = io_err_at(
            dir,
            Path::new("/some"),
            "cannot write in",
            &std::io::Error::from(std::io::ErrorKind::PermissionDenied),
        )
        .to_string();
        assert_eq!(
            e,
            "writing /some/out: cannot write in `/some`: permission denied"
        );
    }

    #[test]
    fn nearest_index() {
        let xs = [-1.0, -0.2, 0.3, 1.0];
        assert_eq!(nearest(4, |i| xs[i], 0.0), 1);
        assert_eq!(nearest(4, |i| xs[i], 0.9), 3);
    }
}
