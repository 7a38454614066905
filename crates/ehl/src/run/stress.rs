//! The stress below the surface of a solved case (`[stress]`) and its fatigue indicator
//! (`[fatigue]`): which loads, which step, which bodies; the physics is in [`crate::stress`].

use crate::case::{Case, Kind};
use crate::grid::Grid;
use crate::solution::{Solution, StressFigures, Summary};
use crate::stress::BodyStress;
use crate::Result;

/// The stress of a solved case.
#[derive(Debug, Clone)]
pub struct StressAnalysis {
    pub grid: Grid,
    /// the chosen bodies, in order
    pub bodies: Vec<BodyStress>,
    /// transient runs: (step, x_p in m) of the fields used: the kept frame with the highest
    /// pressure (the worst position of the features)
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
            return (f.pressure.clone(), Some(f.film.clone()), Some((f.step, f.x_p_m)));
        }
    }
    (solution.fields.pressure.clone(), solution.fields.film.clone(), None)
}

/// Computes the stress of `solution` when the case asks for it (`[stress]`); a warning goes
/// into `warnings` when the shear traction could not be formed (the stress is then frictionless).
pub fn analyse(case: &Case, solution: &Solution, warnings: &mut Vec<String>) -> Result<Option<StressAnalysis>> {
    let Some(spec) = &case.stress else {
        return Ok(None);
    };
    let grid = solution.grid;
    let line = case.is_infinite_line();
    let (pressure, film, step) = loads(solution);
    let pressure: Vec<f64> = pressure.iter().map(|p| p.max(0.0)).collect();
    let tractions: Option<[Vec<f64>; 2]> = match case.kind {
        Kind::Dry => (spec.friction != 0.0).then(|| {
            let q: Vec<f64> = pressure.iter().map(|p| spec.friction * p).collect();
            [q.clone(), q.iter().map(|v| -v).collect()]
        }),
        Kind::Ehl => {
            let (motion, lub) = (case.motion.as_ref(), case.lubricant.as_ref());
            match (motion, lub, film) {
                (Some(m), Some(lub), Some(film)) => {
                    let viscosity: Vec<f64> = pressure
                        .iter()
                        .map(|&p| crate::lubricant::viscosity::viscosity(lub, p))
                        .collect();
                    let input = crate::friction::FrictionInput {
                        grid: &grid,
                        pressure: &pressure,
                        film: &film,
                        viscosity: &viscosity,
                        u1: m.u1(),
                        u2: m.u2(),
                        rheology: &lub.rheology,
                        load: 1.0,
                    };
                    match crate::friction::surface_tractions(&input) {
                        Ok(t) => Some(t),
                        Err(e) => {
                            warnings.push(format!(
                                "stress computed without the surface shear: the lubricant's shear stress could not be formed ({e})"
                            ));
                            None
                        }
                    }
                }
                _ => None,
            }
        }
    };
    let dy = if line { f64::INFINITY } else { grid.dy };
    let z = spec.depths(grid.dx, dy);
    let bodies = spec
        .bodies
        .iter()
        .map(|&k| {
            let nu = if k == 1 { case.body1.poisson_ratio } else { case.body2.poisson_ratio };
            let q = tractions.as_ref().map(|t| t[k as usize - 1].as_slice());
            BodyStress::new(k, &grid, &pressure, q, nu, &z, line)
        })
        .collect();
    Ok(Some(StressAnalysis {
        grid,
        bodies,
        step,
        with_traction: tractions.is_some(),
    }))
}

/// Fills the stress and fatigue keys of `summary` from `analysis`: the maxima over the bodies,
/// each body's figures, the fatigue integral (the sum over the bodies: the contact survives when
/// both do) and a warning for each maximum on the first layer.
pub fn summarise(case: &Case, analysis: &StressAnalysis, summary: &mut Summary) {
    let area = if case.is_infinite_line() { analysis.grid.dx } else { analysis.grid.cell_area() };
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
            if peak.layer == 0 && peak.value > 0.0 {
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
    summary.fatigue_integral = case.fatigue.map(|_| total);
    summary.stress_at_xp_m = analysis.step.map(|s| s.1);
    summary.stress = Some(per_body);
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
