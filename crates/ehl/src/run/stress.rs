//! The stress below the surface of a solved case (`[stress]`) and its fatigue indicator
//! (`[fatigue]`): which loads, which step, which bodies; the physics is in [`crate::stress`].

use crate::case::{Case, Kind};
use crate::grid::Grid;
use crate::solution::{PassageFigures, Solution, StressFigures, Summary};
use crate::stress::field::{StressKernels, DEFAULT_CACHE_BYTES};
use crate::stress::passage::Passage;
use crate::stress::BodyStress;
use crate::Result;
use std::time::Instant;

/// The stress of a solved case.
#[derive(Debug, Clone)]
pub struct StressAnalysis {
    pub grid: Grid,
    /// the chosen bodies, in order
    pub bodies: Vec<BodyStress>,
    /// transient runs: (step, x_p in m) of the fields used: with `[fatigue]` the kept frame of
    /// the largest fatigue integral (the worst position of the features for life), else the
    /// kept frame with the highest pressure
    pub step: Option<(usize, f64)>,
    /// whether a shear traction was applied
    pub with_traction: bool,
}

/// Pressure, film and viscosity (viscosity None in a dry run) of the fields to analyse, and the
/// transient step they belong to.
fn loads(solution: &Solution) -> (Vec<f64>, Option<Vec<f64>>, Option<(usize, f64)>) {
    if let Some(t) = &solution.transient {
        if let Some(f) = t.frames.iter().max_by(|a, b| {
            let pa = a.pressure.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
            let pb = b.pressure.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
            pa.total_cmp(&pb)
        }) {
            return (
                f.pressure.clone(),
                Some(f.film.clone()),
                Some((f.step, f.x_p_m)),
            );
        }
    }
    (
        solution.fields.pressure.clone(),
        solution.fields.film.clone(),
        None,
    )
}

/// Computes the stress of `solution` when the case asks for it (`[stress]`); a warning goes
/// into `warnings` when the shear traction could not be formed (the stress is then frictionless).
pub fn analyse(
    case: &Case,
    solution: &Solution,
    warnings: &mut Vec<String>,
) -> Result<Option<StressAnalysis>> {
    let Some(spec) = &case.stress else {
        return Ok(None);
    };
    let grid = solution.grid;
    let line = case.is_infinite_line();
    let (pressure, film, step) = loads(solution);
    let pressure: Vec<f64> = pressure.iter().map(|p| p.max(0.0)).collect();
    let tractions = match tractions(case, &grid, &pressure, film.as_deref(), None) {
        Ok(t) => t,
        Err(e) => {
            warnings.push(format!(
                "stress computed without the surface shear: the lubricant's shear stress could not be formed ({e})"
            ));
            None
        }
    };
    let dy = if line { f64::INFINITY } else { grid.dy };
    let z = spec.depths(grid.dx, dy);
    // a transient run with [fatigue]: the frame whose fatigue integral is the largest (the
    // worst position of the features for life), not the one of highest pressure: a pit inside
    // the contact unloads its centre and lowers the integral while its rims raise the pressure
    // (thesis pit, 1 um: 1.0061 at the highest-pressure frame, 0.9868 at the worst; docs/stress.md)
    if let (Some(params), Some(t)) = (case.fatigue, &solution.transient) {
        if t.frames.len() > 1 {
            return worst_frame(case, solution, &z, &params, warnings).map(Some);
        }
    }
    // both bodies of one Poisson ratio share the kernel spectra (what fits the cache budget)
    let shared = shared_kernels(case).then(|| {
        StressKernels::new(
            &grid,
            case.body1.poisson_ratio,
            &z,
            line,
            DEFAULT_CACHE_BYTES,
        )
    });
    let bodies = spec
        .bodies
        .iter()
        .map(|&k| {
            let nu = if k == 1 {
                case.body1.poisson_ratio
            } else {
                case.body2.poisson_ratio
            };
            let q = tractions.as_ref().map(|t| t[k as usize - 1].as_slice());
            match &shared {
                Some(kernels) => BodyStress::from_field(k, &grid, nu, kernels.field(&pressure, q)),
                None => BodyStress::new(k, &grid, &pressure, q, nu, &z, line),
            }
        })
        .collect();
    Ok(Some(StressAnalysis {
        grid,
        bodies,
        step,
        with_traction: tractions.is_some(),
    }))
}

/// The stress of the kept frame with the largest fatigue integral (summed over the chosen
/// bodies). Each body's kernel spectra are built once and reused for every frame.
fn worst_frame(
    case: &Case,
    solution: &Solution,
    z: &[f64],
    params: &crate::case::FatigueSpec,
    warnings: &mut Vec<String>,
) -> Result<StressAnalysis> {
    let spec = case.stress.as_ref().expect("called with [stress]");
    let t = solution
        .transient
        .as_ref()
        .expect("called for a transient run");
    let grid = solution.grid;
    let line = case.is_infinite_line();
    let area = if line { grid.dx } else { grid.cell_area() };
    let nu = |k: u8| {
        if k == 1 {
            case.body1.poisson_ratio
        } else {
            case.body2.poisson_ratio
        }
    };
    let budget = DEFAULT_CACHE_BYTES / spec.bodies.len().max(1);
    let mut kernels: Vec<(f64, StressKernels)> = Vec::new();
    for &k in &spec.bodies {
        if !kernels.iter().any(|(n, _)| *n == nu(k)) {
            kernels.push((nu(k), StressKernels::new(&grid, nu(k), z, line, budget)));
        }
    }
    let mut best: Option<(f64, StressAnalysis)> = None;
    let mut frictionless = false;
    for f in &t.frames {
        if crate::run::cancel::requested() {
            return Err(crate::Error::Cancelled);
        }
        let pressure: Vec<f64> = f.pressure.iter().map(|p| p.max(0.0)).collect();
        let q = match tractions(case, &grid, &pressure, Some(&f.film), None) {
            Ok(q) => q,
            Err(_) => {
                frictionless = true;
                None
            }
        };
        let bodies: Vec<BodyStress> = spec
            .bodies
            .iter()
            .map(|&k| {
                let kern = &kernels
                    .iter()
                    .find(|(n, _)| *n == nu(k))
                    .expect("built above")
                    .1;
                let qk = q.as_ref().map(|t| t[k as usize - 1].as_slice());
                BodyStress::from_field(k, &grid, nu(k), kern.field(&pressure, qk))
            })
            .collect();
        let total: f64 = bodies
            .iter()
            .map(|b| b.fatigue_integral(area, params))
            .sum();
        if best.as_ref().is_none_or(|(v, _)| total > *v) {
            best = Some((
                total,
                StressAnalysis {
                    grid,
                    bodies,
                    step: Some((f.step, f.x_p_m)),
                    with_traction: q.is_some(),
                },
            ));
        }
    }
    if frictionless {
        warnings.push(
            "stress computed without the surface shear at some frames: the lubricant's shear stress could not be formed there".into(),
        );
    }
    Ok(best.expect("at least two frames").1)
}

/// Whether a steady `[stress]` analysis computes both bodies with one Poisson ratio: their
/// kernel spectra are then built once ([`StressKernels`]) and used for both.
pub fn shared_kernels(case: &Case) -> bool {
    case.stress.as_ref().is_some_and(|s| s.bodies.len() == 2)
        && case.body1.poisson_ratio == case.body2.poisson_ratio
}

/// The cells of `case`'s grid and their size (m; dy infinite on an infinite line), as the
/// memory estimates need them before a grid exists.
fn case_cells(case: &Case) -> (usize, usize, f64, f64) {
    let g = case.grid;
    let (nx, ny) = (g.nx.max(1), g.ny.max(1));
    let dx = (g.x_max - g.x_min) / nx as f64;
    let dy = if case.is_infinite_line() {
        f64::INFINITY
    } else {
        (g.y_max - g.y_min) / ny as f64
    };
    (nx, ny, dx, dy)
}

/// How many distinct Poisson ratios the bodies of `[stress]` have (each has its own kernel
/// spectra); 0 without `[stress]`.
fn distinct_poisson_ratios(case: &Case) -> usize {
    let Some(spec) = case.stress.as_ref() else {
        return 0;
    };
    let mut nus: Vec<f64> = spec
        .bodies
        .iter()
        .map(|&k| {
            if k == 2 {
                case.body2.poisson_ratio
            } else {
                case.body1.poisson_ratio
            }
        })
        .collect();
    nus.dedup();
    nus.len()
}

/// Whether the `[stress]` analysis of `case` is the worst-frame search of a transient run with
/// `[fatigue]` (see `analyse`).
fn worst_frame_search(case: &Case) -> bool {
    case.stress.is_some() && case.fatigue.is_some() && super::transient::kinematics(case).is_some()
}

/// Bytes of the worst-frame search of a transient run with `[fatigue]` (0 otherwise): each
/// distinct Poisson ratio's kernel spectra, kept for all frames (what fits
/// [`DEFAULT_CACHE_BYTES`]), and a second analysis (the frame in hand beside the worst so far:
/// per body the field of `field_bytes`).
pub fn worst_frame_bytes(case: &Case) -> f64 {
    let Some(spec) = case.stress.as_ref().filter(|_| worst_frame_search(case)) else {
        return 0.0;
    };
    let (nx, ny, dx, dy) = case_cells(case);
    let layers = spec.depths(dx, dy).len();
    let spectra = kernel_cache_bytes(nx, ny, layers, distinct_poisson_ratios(case)) as f64;
    let second = crate::stress::field::field_bytes(nx * ny, layers, 3) * spec.bodies.len() as f64;
    spectra + second
}

/// Bytes of the kernel spectra shared by the two bodies of a steady analysis
/// ([`shared_kernels`]; 0 otherwise, and for the worst-frame search, which keeps its own:
/// [`worst_frame_bytes`]), within [`DEFAULT_CACHE_BYTES`].
pub fn shared_kernel_bytes(case: &Case) -> f64 {
    let Some(spec) = case
        .stress
        .as_ref()
        .filter(|_| shared_kernels(case) && !worst_frame_search(case))
    else {
        return 0.0;
    };
    let (nx, ny, dx, dy) = case_cells(case);
    kernel_cache_bytes(nx, ny, spec.depths(dx, dy).len(), 1) as f64
}

/// The shear traction along +x on each body ([body 1, body 2], Pa) for the (non-negative)
/// `pressure` on `grid`: a dry run's Coulomb traction (`stress.friction`, None when 0), an EHL
/// run's lubricant drag ([`crate::friction::surface_tractions`]) from the `film` and the
/// `viscosity` (None: formed from the pressure with the case's viscosity model). Err: the
/// lubricant's shear stress could not be formed.
pub fn tractions(
    case: &Case,
    grid: &Grid,
    pressure: &[f64],
    film: Option<&[f64]>,
    viscosity: Option<&[f64]>,
) -> Result<Option<[Vec<f64>; 2]>> {
    let Some(spec) = &case.stress else {
        return Ok(None);
    };
    match case.kind {
        Kind::Dry => Ok((spec.friction != 0.0).then(|| {
            let q: Vec<f64> = pressure.iter().map(|p| spec.friction * p).collect();
            [q.clone(), q.iter().map(|v| -v).collect()]
        })),
        Kind::Ehl => {
            let (motion, lub) = (case.motion.as_ref(), case.lubricant.as_ref());
            let (Some(m), Some(lub), Some(film)) = (motion, lub, film) else {
                return Ok(None);
            };
            let formed;
            let viscosity = match viscosity {
                Some(v) => v,
                None => {
                    formed = pressure
                        .iter()
                        .map(|&p| crate::lubricant::viscosity::viscosity(lub, p))
                        .collect::<Vec<f64>>();
                    &formed
                }
            };
            let input = crate::friction::FrictionInput {
                grid,
                pressure,
                film,
                viscosity,
                u1: m.u1(),
                u2: m.u2(),
                rheology: &lub.rheology,
                load: 1.0,
            };
            crate::friction::surface_tractions(&input).map(Some)
        }
    }
}

/// One evaluation's surface loads kept for the Dang Van second pass: time (s), pressure (Pa),
/// the tractions on [body 1, body 2] (Pa), f32.
type KeptLoads = (f64, Vec<f32>, Option<[Vec<f32>; 2]>);

/// The stress history of a transient run with `[stress]` in the material frame of each chosen
/// body ([`crate::stress::passage`]): the accumulators and how they were fed.
#[derive(Debug, Clone)]
pub struct PassageRun {
    /// one per chosen body (`stress.body`), in order
    pub passages: Vec<Passage>,
    /// every k-th step is evaluated (and the last): [`passage_every`]
    pub every: usize,
    /// evaluations left out because their step did not converge
    pub skipped_steps: Vec<usize>,
    /// wall time of the stress fields and of the accumulation (s)
    pub field_seconds: f64,
    pub accumulate_seconds: f64,
    /// the first failure to form the lubricant's shear traction (the step's stress is then
    /// frictionless)
    pub traction_failure: Option<(usize, String)>,
    /// `fatigue.dang_van`: the surface loads of each evaluation (time s, pressure Pa, the
    /// tractions of [body 1, body 2] Pa, f32) for the second pass ([`Self::finish`]); emptied
    /// by it
    loads: Vec<KeptLoads>,
    /// wall time of the Dang Van second pass (s)
    pub dang_van_seconds: f64,
    poisson: [f64; 2],
    line: bool,
    /// the kernel spectra of the window, one per distinct Poisson ratio among the chosen
    /// bodies, built at the first evaluation and reused by every later one and by the Dang Van
    /// pass ([`crate::stress::field::StressKernels`]; together within
    /// [`crate::stress::field::DEFAULT_CACHE_BYTES`])
    kernels: Vec<StressKernels>,
}

/// The kernels of `nu` among `kernels`, built (keeping at most `budget` bytes of spectra) when
/// missing.
fn kernels_for<'a>(
    kernels: &'a mut Vec<StressKernels>,
    grid: &Grid,
    nu: f64,
    z: &[f64],
    line: bool,
    budget: usize,
) -> &'a StressKernels {
    match kernels.iter().position(|k| k.matches(grid, nu, z, line)) {
        Some(i) => &kernels[i],
        None => {
            kernels.push(StressKernels::new(grid, nu, z, line, budget));
            kernels.last().expect("just pushed")
        }
    }
}

/// The evaluation stride of the passage maps: the largest k for which neither body's material
/// points nor the features (both move with a surface) travel more than one cell dx between two
/// evaluations, k = max(1, floor(dx / (max(|u1|, |u2|) dt))). Sampling every step would add
/// points closer than the grid resolves.
pub fn passage_every(dx: f64, dt: f64, speeds: [f64; 2]) -> usize {
    let v = speeds[0].abs().max(speeds[1].abs()) * dt;
    if !(v > 0.0) {
        return 1;
    }
    ((dx / v) * (1.0 + 1e-9)).floor().max(1.0) as usize
}

/// Bytes of the passage maps of a transient case with `[stress]` (0 otherwise): per chosen body
/// the accumulators on nx_body x ny x window layers ([`crate::stress::passage::bytes`]), the
/// window's stress field of a step (6 f32 components) and the finished maps (3 f32); with
/// `fatigue.dang_van` the surface loads kept for the second pass, 3 f32 per cell per
/// evaluation (pressure and both tractions).
pub fn passage_memory(case: &Case) -> f64 {
    let (Some(spec), Some(kin), Some(m)) = (
        &case.stress,
        super::transient::kinematics(case),
        case.motion.as_ref(),
    ) else {
        return 0.0;
    };
    let (nx, ny, dx, dy) = case_cells(case);
    let layers = spec.window_depths(dx, dy).len();
    let dv = case.fatigue.is_some_and(|f| f.dang_van.is_some());
    let duration = kin.steps as f64 * kin.dt;
    spec.bodies
        .iter()
        .map(|&k| {
            let u = if k == 2 { m.u2() } else { m.u1() };
            let cols = crate::stress::passage::body_columns(nx, dx, u, duration);
            let points = cols * ny * layers;
            crate::stress::passage::bytes(points, dv) + 3.0 * 4.0 * points as f64
        })
        .sum::<f64>()
        + crate::stress::field::field_bytes(nx * ny, layers, 0)
        + kernel_cache_bytes(nx, ny, layers, distinct_poisson_ratios(case)) as f64
        + if dv {
            let dx_t = kin.dt;
            let every = passage_every(dx, dx_t, [m.u1(), m.u2()]);
            (kin.steps / every + 2) as f64 * 3.0 * 4.0 * (nx * ny) as f64
        } else {
            0.0
        }
}

/// Bytes of the cached kernel spectra of a passage on `nx` x `ny` cells and `layers` window
/// layers for `bodies` distinct Poisson ratios (at most [`DEFAULT_CACHE_BYTES`]).
pub fn kernel_cache_bytes(nx: usize, ny: usize, layers: usize, bodies: usize) -> usize {
    let per = crate::stress::field::layer_spectra_bytes(nx, ny);
    let budget = DEFAULT_CACHE_BYTES / bodies.max(1);
    bodies * (layers.min(budget / per.max(1)) * per)
}

impl PassageRun {
    /// The accumulators of a transient `case` with `[stress]` on `grid`, for a run of
    /// `steps` steps of `dt` (s); None for a case without `[stress]`.
    pub fn new(case: &Case, grid: &Grid, steps: usize, dt: f64) -> Option<Self> {
        let spec = case.stress.as_ref()?;
        let m = case.motion.as_ref()?;
        let line = case.is_infinite_line();
        let dy = if line { f64::INFINITY } else { grid.dy };
        let z = spec.window_depths(grid.dx, dy);
        let dv = case.fatigue.and_then(|f| f.dang_van);
        let duration = steps as f64 * dt;
        let speeds = [m.u1(), m.u2()];
        let passages = spec
            .bodies
            .iter()
            .map(|&k| Passage::new(k, grid, speeds[k as usize - 1], duration, &z, dv))
            .collect();
        Some(PassageRun {
            passages,
            every: passage_every(grid.dx, dt, speeds),
            skipped_steps: Vec::new(),
            field_seconds: 0.0,
            accumulate_seconds: 0.0,
            traction_failure: None,
            loads: Vec::new(),
            dang_van_seconds: 0.0,
            poisson: [case.body1.poisson_ratio, case.body2.poisson_ratio],
            line,
            kernels: Vec::new(),
        })
    }

    /// Feeds step `step` of `last` (time `t`, s) when it is one to evaluate: its stress on the
    /// window layers of each chosen body, from the pressure and the lubricant's traction.
    #[allow(clippy::too_many_arguments)]
    pub fn step(
        &mut self,
        case: &Case,
        grid: &Grid,
        step: usize,
        last: usize,
        t: f64,
        converged: bool,
        pressure: &[f64],
        film: &[f64],
        viscosity: &[f64],
    ) {
        if !(step.is_multiple_of(self.every) || step == last) {
            return;
        }
        if !converged {
            self.skipped_steps.push(step);
            return;
        }
        let start = Instant::now();
        let pressure: Vec<f64> = pressure.iter().map(|p| p.max(0.0)).collect();
        let q = match tractions(case, grid, &pressure, Some(film), Some(viscosity)) {
            Ok(q) => q,
            Err(e) => {
                self.traction_failure.get_or_insert((step, e.to_string()));
                None
            }
        };
        let mut acc_s = 0.0;
        let budget = self.cache_budget();
        for p in self.passages.iter_mut() {
            let k = p.body as usize - 1;
            let traction = q.as_ref().map(|q| q[k].as_slice());
            let kernels = kernels_for(
                &mut self.kernels,
                grid,
                self.poisson[k],
                &p.z,
                self.line,
                budget,
            );
            let field = kernels.field(&pressure, traction);
            let t1 = Instant::now();
            p.accumulate(&field, t);
            acc_s += t1.elapsed().as_secs_f64();
        }
        // the tractions and the fields; the accumulation apart
        self.field_seconds += start.elapsed().as_secs_f64() - acc_s;
        self.accumulate_seconds += acc_s;
        if self.passages.iter().any(|p| p.dang_van.is_some()) {
            let f32s = |v: &[f64]| v.iter().map(|&x| x as f32).collect::<Vec<f32>>();
            self.loads.push((
                t,
                f32s(&pressure),
                q.as_ref().map(|q| [f32s(&q[0]), f32s(&q[1])]),
            ));
        }
    }

    /// The share of [`DEFAULT_CACHE_BYTES`] of each body's kernel spectra: the whole for one
    /// Poisson ratio among the chosen bodies, half each for two.
    fn cache_budget(&self) -> usize {
        let mut nus: Vec<f64> = self
            .passages
            .iter()
            .map(|p| self.poisson[p.body as usize - 1])
            .collect();
        nus.dedup();
        DEFAULT_CACHE_BYTES / nus.len().max(1)
    }

    /// Bytes of the kept kernel spectra.
    pub fn kernel_bytes(&self) -> usize {
        self.kernels.iter().map(|k| k.bytes()).sum()
    }

    /// The Dang Van second pass over the kept loads (nothing without `fatigue.dang_van`): each
    /// evaluation's field again, now that every point's mid-value is known; frees the loads.
    pub fn finish(&mut self, grid: &Grid) {
        let start = Instant::now();
        let loads = std::mem::take(&mut self.loads);
        let budget = self.cache_budget();
        for (t, p, q) in &loads {
            let p: Vec<f64> = p.iter().map(|&v| v as f64).collect();
            for ps in self.passages.iter_mut() {
                let k = ps.body as usize - 1;
                let traction: Option<Vec<f64>> =
                    q.as_ref().map(|q| q[k].iter().map(|&v| v as f64).collect());
                let kernels = kernels_for(
                    &mut self.kernels,
                    grid,
                    self.poisson[k],
                    &ps.z,
                    self.line,
                    budget,
                );
                let field = kernels.field(&p, traction.as_deref());
                ps.dang_van_pass(&field, *t);
            }
        }
        self.dang_van_seconds += start.elapsed().as_secs_f64();
    }
}

/// The passage figures of each body: the maxima of its maps and where they are (body frame).
///
/// The maxima are taken over the material columns that crossed the whole Hertz contact, from
/// x <= -b to x >= b (`half_width` b, m): a column that entered or left the grid during the
/// run saw part of the passage, and for Dang Van a part can give more than the whole (its
/// mid-value is of half a loop; a scan found the reported maximum, 2.129, at a column that had
/// only reached the contact centre, against about 2.10 for the columns that went through). The
/// maps keep every column. Where no column crossed the whole contact (a travel shorter than
/// the contact), the maxima are over all columns.
pub fn passage_figures(run: &PassageRun, half_width: f64) -> Vec<PassageFigures> {
    run.passages
        .iter()
        .map(|p| {
            let maps = p.maps();
            let (nxb, ny) = (p.nx_body, p.grid.ny);
            let at = |idx: usize| {
                let m = idx % nxb;
                let j = (idx / nxb) % ny;
                let k = idx / (nxb * ny);
                [p.x_body(m), p.grid.y(j), p.z[k]]
            };
            let through: Vec<bool> = p
                .contact_span
                .iter()
                .map(|s| s[0].min(s[1]) <= -half_width && s[0].max(s[1]) >= half_width)
                .collect();
            let any_through = through.iter().any(|&t| t);
            let peak = |v: &[f32]| {
                let mut best: Option<(usize, f32)> = None;
                for (i, &x) in v.iter().enumerate() {
                    let counts = !any_through || through[i % nxb];
                    if counts && x.is_finite() && best.is_none_or(|b| x > b.1) {
                        best = Some((i, x));
                    }
                }
                best.map(|(i, x)| (x as f64, at(i)))
            };
            let vm = peak(&maps.max_von_mises);
            let tr = peak(&maps.tau_xz_range);
            let dv = maps.dang_van.as_deref().and_then(peak);
            PassageFigures {
                body: p.body,
                max_von_mises_pa: vm.map(|v| v.0),
                max_von_mises_at_m: vm.map(|v| v.1),
                max_tau_xz_range_pa: tr.map(|v| v.0),
                max_tau_xz_range_at_m: tr.map(|v| v.1),
                max_dang_van: dv.map(|v| v.0),
                max_dang_van_at_m: dv.map(|v| v.1),
                evaluations: p.evaluations,
                every_steps: run.every,
                window_m: p.z.last().copied().unwrap_or(0.0),
                layers: p.z.len(),
                memory_bytes: p.memory_bytes(),
            }
        })
        .collect()
}

/// Fills the stress and fatigue keys of `summary` from `analysis`: the maxima over the bodies,
/// each body's figures, the fatigue integral (the sum over the bodies: the contact survives when
/// both do) and a warning for each maximum on the first layer.
pub fn summarise(case: &Case, analysis: &StressAnalysis, summary: &mut Summary) {
    let area = if case.is_infinite_line() {
        analysis.grid.dx
    } else {
        analysis.grid.cell_area()
    };
    let mut per_body = Vec::new();
    let mut total = 0.0;
    for b in &analysis.bodies {
        let fatigue = case.fatigue.map(|p| b.fatigue_integral(area, &p));
        total += fatigue.unwrap_or(0.0);
        per_body.push(StressFigures {
            body: b.body,
            max_von_mises_pa: b.peak_von_mises.value,
            max_von_mises_at_m: b.peak_von_mises.at,
            max_shear_pa: b.peak_max_shear.value,
            max_shear_at_m: b.peak_max_shear.at,
            max_orthogonal_shear_pa: b.peak_orthogonal_shear.value,
            max_orthogonal_shear_at_m: b.peak_orthogonal_shear.at,
            fatigue_integral: fatigue,
        });
        for (name, peak) in [
            ("von Mises", &b.peak_von_mises),
            ("maximum shear", &b.peak_max_shear),
            ("orthogonal shear |tau_xz|", &b.peak_orthogonal_shear),
        ] {
            // (one layer is no depth profile: its maximum says nothing about the surface)
            if peak.layer == 0 && peak.value > 0.0 && b.field.z.len() > 1 {
                summary.warnings.push(format!(
                    "the {name} maximum of body {} lies on the first layer below the surface (z = {:.3e} m): it may sit at the surface itself (sliding friction above about 0.3, or a sharp feature edge); refine with more stress.layers or a finer grid to locate it",
                    b.body, peak.at[2]
                ));
            }
        }
    }
    let best = |f: &dyn Fn(&StressFigures) -> (f64, [f64; 3])| {
        per_body
            .iter()
            .map(f)
            .max_by(|a, b| a.0.total_cmp(&b.0))
            .unwrap_or((f64::NAN, [f64::NAN; 3]))
    };
    let (v, at) = best(&|s| (s.max_von_mises_pa, s.max_von_mises_at_m));
    summary.max_von_mises_pa = Some(v);
    summary.max_von_mises_at_m = Some(at);
    let (v, at) = best(&|s| (s.max_shear_pa, s.max_shear_at_m));
    summary.max_shear_pa = Some(v);
    summary.max_shear_at_m = Some(at);
    let (v, at) = best(&|s| (s.max_orthogonal_shear_pa, s.max_orthogonal_shear_at_m));
    summary.max_orthogonal_shear_pa = Some(v);
    summary.max_orthogonal_shear_at_m = Some(at);
    summary.fatigue_integral = case.fatigue.filter(|_| total.is_finite()).map(|_| total);
    if case.fatigue.is_some() && !total.is_finite() {
        summary.warnings.push(
            "fatigue_integral and life_ratio left out: the integral overflows floating point with these fatigue.stress_exponent and fatigue.depth_exponent (the literature's are c = 9-12, h = 0-7/3)".into(),
        );
        for figures in per_body.iter_mut() {
            figures.fatigue_integral = None;
        }
    }
    summary.stress_at_xp_m = analysis.step.map(|s| s.1);
    summary.stress = Some(per_body);
}

/// The passage keys of `summary` and their warnings (a maximum on the window's deepest or first
/// layer, skipped steps, frictionless steps, a Dang Van indicator above 1).
pub fn summarise_passage(run: &PassageRun, summary: &mut Summary) {
    let figures = passage_figures(run, summary.hertz_half_width_m);
    // a maximum on the window's last layer may lie deeper; on its first, nearer the surface
    for (f, p) in figures.iter().zip(&run.passages) {
        let (Some(&first), Some(&last)) = (p.z.first(), p.z.last()) else {
            continue;
        };
        for (name, at) in [
            ("max-over-passage von Mises", f.max_von_mises_at_m),
            ("tau_xz range", f.max_tau_xz_range_at_m),
            ("Dang Van indicator", f.max_dang_van_at_m),
        ] {
            let Some(at) = at else { continue };
            if p.z.len() > 1 && at[2] == last {
                summary.warnings.push(format!(
                    "the {name} maximum of body {} lies on the deepest layer of the passage window (z = {last:.3e} m): it may lie deeper; deepen stress.window to locate it",
                    f.body
                ));
            } else if at[2] == first {
                summary.warnings.push(format!(
                    "the {name} maximum of body {} lies on the first layer of the passage window (z = {first:.3e} m): it may sit at the surface itself; refine with more stress.layers or a finer grid to locate it",
                    f.body
                ));
            }
        }
    }
    for f in &figures {
        if let (Some(dv), Some(at)) = (f.max_dang_van, f.max_dang_van_at_m) {
            if dv > 1.0 {
                summary.warnings.push(format!(
                    "the Dang Van indicator of body {} reaches {dv:.3} > 1 at x_body = {:.4e} m, z = {:.3e} m: the fatigue limit of fatigue.dang_van is crossed there",
                    f.body, at[0], at[2]
                ));
            }
        }
    }
    if !run.skipped_steps.is_empty() {
        summary.warnings.push(format!(
            "the passage maps leave out {} evaluation step(s) that did not converge (first: step {})",
            run.skipped_steps.len(),
            run.skipped_steps[0]
        ));
    }
    if let Some((step, e)) = &run.traction_failure {
        summary.warnings.push(format!(
            "the passage maps use a frictionless stress at the step(s) where the lubricant's shear stress could not be formed (first: step {step}: {e})"
        ));
    }
    summary.passage = Some(figures);
}

/// The same case with smooth surfaces, solved steadily: the reference of the life ratio.
pub fn smooth_reference(case: &Case) -> Case {
    let mut smooth = case.clone();
    smooth.features.clear();
    if let Some(m) = smooth.motion.as_mut() {
        m.travel = None;
    }
    smooth
}
