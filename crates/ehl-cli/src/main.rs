//! The `ehl` command line: `run`, `check`, `sweep`. Thin: parsing, progress, exit codes; all the
//! work is in the `ehl` library.

mod io;
mod progress;
mod sweep;

use anyhow::Result;
use clap::{Args, Parser, Subcommand};
use ehl::solution::Summary;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// Exit status when the solver stopped without converging (outputs are still written).
pub const EXIT_NOT_CONVERGED: u8 = 3;
/// Exit status when pressure and film are solved and written but the friction the case asks
/// for (slide-to-roll != 0 or a non-Newtonian rheology) could not be computed.
pub const EXIT_FRICTION_FAILED: u8 = 4;

const EXIT_CODES: &str = "\
Exit status:
  0  success
  1  error: bad case file or --set value, solver failure, or outputs not written
     (the message names the file, the key and the reason)
  2  command-line usage error (unknown option, malformed --vary or --shard, ...)
  3  solved, but the solver did not converge: outputs are written and summary.json
     has converged = false (sweep: at least one point did not converge)
  4  solved and written, but the friction the case asks for (slide_to_roll != 0 or a
     non-Newtonian rheology) could not be computed: summary.json has friction_failed
     = true and a warning, and no friction keys
  130  stopped by Ctrl-C or SIGTERM (temporary folders are removed; an existing
     output folder is left as it was)
  141  standard output was closed by its reader (e.g. `ehl check case.toml | head -1`)";

/// How output folders are written (after the exit codes in `run --help` and `sweep --help`).
const OUTPUT_NOTES: &str = "\
Output folders:
  Written atomically: into .DIR.tmp-PID-N beside DIR, renamed to DIR when complete.
  ehl replaces only a folder it wrote (it holds the marker file .ehl-output with the
  version) or an empty one; any other DIR is refused before solving. One process per
  DIR: the lock file .DIR.lock beside it; a second run is refused at once. Ctrl-C or
  SIGTERM removes the temporary folder and the lock (exit 130); what a killed process
  (SIGKILL) left is removed by the next write of DIR once that process is gone.
  Case files: regular files of at most 16 MiB. Sweeps: at most 100000 points.";

/// Dry contact and elastohydrodynamic lubrication (EHL) of finite rollers and balls.
#[derive(Parser)]
#[command(name = "ehl", version, about, after_help = EXIT_CODES)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Solve a case and write its outputs (summary.json, fields, profiles, pictures).
    #[command(after_help = format!("{EXIT_CODES}\n\n{OUTPUT_NOTES}"))]
    Run(RunArgs),
    /// Validate a case without solving; print the derived quantities (E', R, Hertz, W U G,
    /// Moes M L, film estimates, grid resolution).
    #[command(after_help = EXIT_CODES)]
    Check(CheckArgs),
    /// Solve a case over a grid of parameter values, in parallel; one sub-folder per point and
    /// sweep.csv with one row per finished point.
    #[command(after_help = format!("{EXIT_CODES}\n\n{OUTPUT_NOTES}"))]
    Sweep(SweepArgs),
}

#[derive(Args)]
struct CaseArgs {
    /// The case file (TOML).
    case: PathBuf,
    /// Override a case key by its dotted path, e.g. `--set load.force=5000`,
    /// `--set body1.profile='{ kind = "crowned", crown_radius = 0.5 }'`. VALUE is read as TOML
    /// (number, true/false, "string", { inline table }, inf), else as a bare string. Repeatable.
    #[arg(long = "set", value_name = "KEY=VALUE", value_parser = parse_set)]
    set: Vec<String>,
}

#[derive(Args)]
struct RunArgs {
    #[command(flatten)]
    case: CaseArgs,
    /// Output folder [default: out/<case file stem>]. Replaced as a whole when every output is
    /// written; nothing is left behind on an error. ehl replaces only a folder it wrote (it
    /// holds the marker file .ehl-output) or an empty one, and refuses any other before
    /// solving. One process at a time per folder (lock file .<DIR name>.lock beside it).
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
    /// No progress bar (it is shown only when stderr is a terminal anyway).
    #[arg(long, short)]
    quiet: bool,
}

#[derive(Args)]
struct CheckArgs {
    #[command(flatten)]
    case: CaseArgs,
}

#[derive(Args)]
struct SweepArgs {
    #[command(flatten)]
    case: CaseArgs,
    /// A varied key: `KEY=START:STOP:N` (N evenly spaced values, both ends included; START and
    /// STOP finite) or `KEY=v1,v2,v3`. Repeatable: the points are all combinations, the first
    /// --vary outermost; at most 100000 points in all.
    #[arg(long, value_name = "KEY=SPEC", required = true, value_parser = sweep::Vary::parse)]
    vary: Vec<sweep::Vary>,
    /// Output folder [default: out/<case file stem>-sweep]. Never replaced as a whole; its point
    /// folders are (only those ehl wrote, see `ehl run --help`). It keeps a lock file,
    /// .sweep.lock, that shards writing sweep.csv take in turn.
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
    /// Points solved at the same time [default: the number of CPUs].
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..))]
    jobs: Option<u32>,
    /// Run only the points whose index i has i % N == K (K in 0..N), e.g. one Slurm array task
    /// each. Every shard rebuilds sweep.csv from all finished points; a rerun skips points
    /// whose folder already holds a summary.json.
    #[arg(long, value_name = "K/N", value_parser = sweep::Shard::parse)]
    shard: Option<sweep::Shard>,
    /// No progress bar.
    #[arg(long, short)]
    quiet: bool,
}

/// A command-line usage error found after parsing (exit status 2).
#[derive(Debug)]
pub struct Usage(pub String);

impl std::fmt::Display for Usage {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for Usage {}

/// `--set` syntax only; the key and value are checked against the case by the library.
fn parse_set(s: &str) -> std::result::Result<String, String> {
    match ehl::case::split_assignment(s) {
        Some(_) => Ok(s.to_string()),
        None => Err("expected KEY=VALUE, e.g. load.force=5000".into()),
    }
}

/// `out/<stem><suffix>` for a case file.
fn default_out(case: &Path, suffix: &str) -> PathBuf {
    let stem = case
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "case".into());
    PathBuf::from("out").join(format!("{stem}{suffix}"))
}

/// A short human-readable line of the main figures.
pub fn result_line(s: &Summary) -> String {
    let mut parts = vec![format!(
        "max pressure {:.4} GPa (Hertz {:.4} GPa)",
        s.max_pressure_pa * 1e-9,
        s.hertz_pressure_pa * 1e-9
    )];
    if let Some(a) = s.approach_m {
        parts.push(format!("approach {:.4} um", a * 1e6));
    }
    if let Some(a) = s.contact_area_m2 {
        parts.push(format!("contact area {:.4} mm^2", a * 1e6));
    }
    if let Some(h) = s.central_film_m {
        parts.push(format!("central film {:.4} um", h * 1e6));
    }
    if let Some(h) = s.min_film_m {
        parts.push(format!("minimum film {:.4} um", h * 1e6));
    }
    if let Some(f) = s.friction_coefficient {
        parts.push(format!("friction coefficient {f:.4}"));
    }
    if s.steps.is_some() {
        parts[0] = format!("last step: {}", parts[0]);
    }
    if let (Some(p), Some(h)) = (s.max_pressure_over_travel_pa, s.min_film_over_travel_m) {
        parts.push(format!(
            "over the travel: max pressure {:.4} GPa, minimum film {:.4} um",
            p * 1e-9,
            h * 1e6
        ));
    }
    let state = if let Some(n) = s.steps {
        let failed = s.failed_steps.as_ref().map_or(0, |f| f.len());
        if failed == 0 {
            format!(
                "{n} time steps, all converged ({} Newton iterations)",
                s.iterations
            )
        } else {
            format!("{n} time steps, {failed} NOT converged")
        }
    } else if s.converged {
        format!("converged in {} iterations", s.iterations)
    } else {
        format!("NOT converged after {} iterations", s.iterations)
    };
    format!("{state} ({:.2} s): {}", s.wall_time_s, parts.join(", "))
}

fn run(args: RunArgs) -> Result<ExitCode> {
    let case = ehl::case::load_file(&args.case.case, &args.case.set)?;
    let dir = args.out.unwrap_or_else(|| default_out(&args.case.case, ""));
    // before solving: refuse a folder ehl did not write, or one another process is writing
    let lock = ehl::output::OutputLock::acquire(&dir)?;
    let bar = progress::Bar::new(args.quiet, 1000);
    let solution = solve_and_write(&lock, &case, &bar, &|| bar.finish());
    bar.finish();
    let solution = solution?;
    drop(lock);
    report(&solution, &dir)
}

/// Solves `case` and writes its outputs into the folder `lock` holds (`ehl run` and each point
/// of `ehl sweep`); `solved` is called between the solve and the write. A transient run
/// streams its per-step files (timeline rows, frames) into the output's temporary folder as it
/// goes, so that it holds no frame in memory; the folder replaces the output only once every
/// file is written, and an error removes it.
pub(crate) fn solve_and_write(
    lock: &ehl::output::OutputLock,
    case: &ehl::case::Case,
    progress: &dyn ehl::run::Progress,
    solved: &dyn Fn(),
) -> Result<ehl::solution::Solution> {
    let transient =
        case.kind == ehl::case::Kind::Ehl && ehl::run::transient::kinematics(case).is_some();
    if !transient {
        let solution = ehl::run::solve(case, progress);
        solved();
        let solution = solution?;
        ehl::output::write_locked(lock, case, &solution)?;
        return Ok(solution);
    }
    // the folder the lock resolved (`--out .` names the current folder by its name)
    let staging = ehl::output::Staging::begin(lock.dir())?;
    let mut stream = ehl::output::stream::TransientStream::new(&staging, case);
    let solution = ehl::run::solve_with(case, progress, &mut stream);
    solved();
    let solution = solution?;
    ehl::output::write_staged(staging, case, &solution, Some(stream))?;
    Ok(solution)
}

/// The result line, the warnings and the exit status of a written run.
fn report(solution: &ehl::solution::Solution, dir: &std::path::Path) -> Result<ExitCode> {
    io::out(&format!(
        "{} -> {}",
        result_line(&solution.summary),
        dir.display()
    ))?;
    for w in &solution.summary.warnings {
        io::err(&format!("warning: {w}"));
    }
    if !solution.summary.converged {
        io::err(&format!(
            "warning: the solver did not converge ({}); outputs written to {} with converged = false",
            solution.summary.termination,
            dir.display()
        ));
        Ok(ExitCode::from(EXIT_NOT_CONVERGED))
    } else if solution.summary.requested_friction_failed() {
        io::err(&format!(
            "error: the friction this case asks for (slide-to-roll or a non-Newtonian rheology) could not be computed; pressure and film are written to {} without the friction keys",
            dir.display()
        ));
        Ok(ExitCode::from(EXIT_FRICTION_FAILED))
    } else {
        Ok(ExitCode::SUCCESS)
    }
}

fn check(args: CheckArgs) -> Result<ExitCode> {
    let case = ehl::case::load_file(&args.case.case, &args.case.set)?;
    io::out(&ehl::run::check_text(&case))?;
    Ok(ExitCode::SUCCESS)
}

/// Ctrl-C, SIGTERM, SIGHUP: remove the temporary folders and lock files being written, then
/// exit 130. An output folder being swapped in is finished first (see
/// `ehl::output::abort_cleanup`), so an old result is never lost.
fn on_signal() {
    let _ = ctrlc::set_handler(|| {
        ehl::output::abort_cleanup();
        io::err("ehl: interrupted; temporary files removed");
        std::process::exit(130);
    });
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => {
            // help and version go to stdout, usage errors to stderr; either may be closed
            let to_stdout = !e.use_stderr();
            return match e.print() {
                Err(io) if to_stdout && io.kind() == std::io::ErrorKind::BrokenPipe => {
                    ExitCode::from(io::EXIT_BROKEN_PIPE)
                }
                Err(io) if to_stdout => {
                    io::err(&format!("error: writing to standard output: {io}"));
                    ExitCode::FAILURE
                }
                _ => ExitCode::from(e.exit_code().clamp(0, 255) as u8),
            };
        }
    };
    on_signal();
    // a memory limit that cannot be read was ignored without a word (a scan: "abc", "-5")
    if let Ok(v) = std::env::var(ehl::run::MEMORY_LIMIT_ENV) {
        // (set but empty counts as unset, as in the library)
        if !v.trim().is_empty()
            && !v
                .trim()
                .parse::<f64>()
                .is_ok_and(|b| b > 0.0 && b.is_finite())
        {
            io::err(&format!(
                "error: {} = {v:?}: must be a positive number of bytes, e.g. 8e9",
                ehl::run::MEMORY_LIMIT_ENV
            ));
            return ExitCode::from(2);
        }
    }
    let result = match cli.command {
        Command::Run(a) => run(a),
        Command::Check(a) => check(a),
        Command::Sweep(a) => sweep::sweep(a),
    };
    match result {
        Ok(code) => code,
        Err(e) if e.downcast_ref::<io::Closed>().is_some() => ExitCode::from(io::EXIT_BROKEN_PIPE),
        Err(e) => {
            io::err(&format!("error: {e:#}"));
            if e.downcast_ref::<Usage>().is_some() {
                ExitCode::from(2)
            } else {
                ExitCode::FAILURE
            }
        }
    }
}
