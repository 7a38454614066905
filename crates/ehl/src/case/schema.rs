//! The set of valid case-file keys (dotted paths), the check for unknown keys, and the
//! "did you mean" suggestion for a misspelt one.
//!
//! Paths are written as in error messages: `body1.radius`, `lubricant.rheology.model`,
//! `features[0].depth`. In the schema an array element is written `features[]`.

use toml::{Table, Value};

/// Keys shared by `[body1]` and `[body2]` (body2 also has `axial_offset`).
const BODY_KEYS: &[&str] = &[
    "shape",
    "radius",
    "radius_y",
    "length",
    "youngs_modulus",
    "poisson_ratio",
    "profile",
    "profile.kind",
    "profile.crown_radius",
    "profile.load",
    "profile.edge_length",
    "profile.edge_radius",
    "profile.angle",
    "conductivity",
    "heat_capacity",
    "density",
];

/// Every other valid key (tables included).
const OTHER_KEYS: &[&str] = &[
    "title",
    "kind",
    "body1",
    "body2",
    "body2.axial_offset",
    "alignment",
    "alignment.tilt",
    "alignment.skew",
    "load",
    "load.force",
    "load.max_hertz_pressure",
    "load.force_per_length",
    "load.dimensionless_load",
    "motion",
    "motion.entrainment_speed",
    "motion.slide_to_roll",
    "motion.dimensionless_speed",
    "motion.travel",
    "motion.travel.from",
    "motion.travel.to",
    "motion.travel.steps",
    "motion.travel.duration",
    "lubricant",
    "lubricant.viscosity",
    "lubricant.pressure_viscosity_coefficient",
    "lubricant.dimensionless_material",
    "lubricant.density",
    "lubricant.viscosity_model",
    "lubricant.density_model",
    "lubricant.rheology",
    "lubricant.rheology.model",
    "lubricant.rheology.shear_modulus",
    "lubricant.rheology.power_law_index",
    "lubricant.rheology.limiting_shear_coefficient",
    "lubricant.rheology.eyring_stress",
    "features",
    "features[]",
    "features[].kind",
    "features[].body",
    "features[].width",
    "features[].length",
    "features[].depth",
    "features[].x",
    "features[].y",
    "features[].pattern",
    "features[].pattern.rows",
    "features[].pattern.columns",
    "features[].pattern.row_pitch",
    "features[].pattern.column_pitch",
    "features[].file",
    "features[].dx",
    "features[].dy",
    "features[].amplitude",
    "features[].wavelength",
    "grid",
    "grid.nx",
    "grid.ny",
    "grid.x_min",
    "grid.x_max",
    "grid.y_min",
    "grid.y_max",
    "solver",
    "solver.tolerance",
    "solver.max_iterations",
    "solver.mirror_levels",
    "solver.free_end_correction",
    "solver.wedge_upwind_order",
    "output",
    "output.frames_every",
    "output.snapshots",
    "output.animation",
    "stress",
    "stress.body",
    "stress.depth",
    "stress.depth_m",
    "stress.layers",
    "stress.spacing",
    "stress.friction",
    "stress.window",
    "fatigue",
    "fatigue.criterion",
    "fatigue.fatigue_limit",
    "fatigue.weibull_slope",
    "fatigue.stress_exponent",
    "fatigue.depth_exponent",
    "fatigue.dang_van",
    "fatigue.dang_van.alpha",
    "fatigue.dang_van.beta",
    "thermal",
    "thermal.inlet_temperature",
    "thermal.viscosity_temperature",
    "thermal.viscosity_beta",
    "thermal.thermal_expansion",
    "thermal.conductivity",
    "thermal.conductivity_pressure",
    "thermal.heat_capacity",
    "thermal.points_across_film",
    "thermal.tolerance",
    "thermal.film_tolerance",
    "thermal.max_iterations",
    "thermal.side_flow",
    "thermal.coupled_newton",
];

/// Every valid key of a case file, in schema form (`features[]` for array elements).
pub fn all_keys() -> Vec<String> {
    let mut keys: Vec<String> = OTHER_KEYS.iter().map(|s| s.to_string()).collect();
    for body in ["body1", "body2"] {
        for k in BODY_KEYS {
            keys.push(format!("{body}.{k}"));
        }
    }
    keys
}

/// `features[3].depth` -> `features[].depth` (the schema form of a path).
pub fn schema_form(path: &str) -> String {
    let mut out = String::with_capacity(path.len());
    let mut in_index = false;
    for c in path.chars() {
        match c {
            '[' => {
                in_index = true;
                out.push('[');
            }
            ']' => {
                in_index = false;
                out.push(']');
            }
            _ if in_index => {}
            _ => out.push(c),
        }
    }
    out
}

/// True if `path` (display form, e.g. `features[0].x`) is a valid key or table of a case file.
pub fn is_known(path: &str) -> bool {
    let s = schema_form(path);
    all_keys().contains(&s)
}

fn split_parent(path: &str) -> (&str, &str) {
    match path.rfind('.') {
        Some(i) => (&path[..i], &path[i + 1..]),
        None => ("", path),
    }
}

/// Similarity of two key names in [0, 1]: normalised Damerau-Levenshtein, raised when one name
/// contains the other (`speed` -> `entrainment_speed`).
fn similarity(a: &str, b: &str) -> f64 {
    let mut s = strsim::normalized_damerau_levenshtein(a, b);
    if a.len() >= 3 && b.len() >= 3 && (a.contains(b) || b.contains(a)) {
        s = s.max(0.7);
    }
    s
}

/// The closest valid key to an unknown `path` (display form), in display form, if any is close
/// enough to be a likely intended key. Keys in the same table are preferred on near ties.
pub fn suggest(path: &str) -> Option<String> {
    let schema_path = schema_form(path);
    let (parent, leaf) = split_parent(&schema_path);
    let (display_parent, _) = split_parent(path);
    let mut best: Option<(f64, String)> = None;
    for cand in all_keys() {
        if cand.ends_with("[]") {
            continue;
        }
        let (cparent, cleaf) = split_parent(&cand);
        let sim = similarity(&leaf.to_lowercase(), cleaf);
        let same = cparent == parent;
        // a key in the same table is accepted at a lower similarity than one elsewhere
        // ... and a very short name only in the same table (`x` is not `features[0].x`)
        let threshold = if same {
            0.45
        } else if leaf.len() < 4 {
            f64::INFINITY
        } else {
            0.6
        };
        if sim < threshold {
            continue;
        }
        let score = sim + if same { 0.1 } else { 0.0 };
        if !matches!(&best, Some((s, _)) if score <= *s) {
            // show array indices as the user wrote them
            let shown = if same {
                if display_parent.is_empty() {
                    cleaf.to_string()
                } else {
                    format!("{display_parent}.{cleaf}")
                }
            } else {
                cand.replace("[]", "[0]")
            };
            best = Some((score, shown));
        }
    }
    best.map(|(_, s)| s)
}

/// The valid keys directly inside table `parent` (schema form; "" for the top level).
pub fn keys_in(parent: &str) -> Vec<String> {
    let parent = schema_form(parent);
    all_keys()
        .into_iter()
        .filter_map(|k| {
            let (p, leaf) = split_parent(&k);
            (p == parent && !leaf.ends_with("[]")).then(|| leaf.to_string())
        })
        .collect()
}

/// The message for an unknown key at `path`: a suggestion if one is close, else the valid keys
/// of its table.
pub fn unknown_key_message(path: &str) -> String {
    // a key below a plain value (`load.force.x`)
    let mut ancestor = path;
    while let Some(i) = ancestor.rfind('.') {
        ancestor = &ancestor[..i];
        if is_known(ancestor) && keys_in(ancestor).is_empty() {
            return format!("`{ancestor}` holds a value, not a table, so it has no keys");
        }
    }
    if path.split('.').any(|seg| seg.trim().is_empty()) {
        return format!(
            "`{path}` has an empty or blank key name, which no case-file key has; write keys like `load.force`"
        );
    }
    if let Some(s) = suggest(path) {
        return format!("unknown key; did you mean `{s}`?");
    }
    let (mut parent, _) = split_parent(path);
    // a path below an unknown table (`a.b.c.d`): name the deepest prefix that is a known table
    if !parent.is_empty() && !is_known(parent) {
        let mut known = "";
        let mut p = parent;
        while let Some(i) = p.rfind('.') {
            p = &p[..i];
            if is_known(p) {
                known = p;
                break;
            }
        }
        let first_unknown = if known.is_empty() {
            parent.split('.').next().unwrap_or(parent)
        } else {
            let rest = &parent[known.len() + 1..];
            rest.split('.').next().unwrap_or(rest)
        };
        parent = known;
        let keys = keys_in(parent);
        return if parent.is_empty() {
            format!(
                "unknown key: a case file has no table `{first_unknown}`; the top level holds: {}",
                keys.join(", ")
            )
        } else {
            format!(
                "unknown key: [{parent}] has no sub-table `{first_unknown}`; valid keys in [{parent}]: {}",
                keys.join(", ")
            )
        };
    }
    let keys = keys_in(parent);
    if parent.is_empty() {
        format!(
            "unknown key; the top level of a case file holds: {}",
            keys.join(", ")
        )
    } else {
        format!("unknown key; valid keys in [{parent}]: {}", keys.join(", "))
    }
}

/// Finds the first unknown key in the tree, returning its display path.
pub fn first_unknown(root: &Table) -> Option<String> {
    walk_table(root, "")
}

fn join(prefix: &str, key: &str) -> String {
    if prefix.is_empty() {
        key.to_string()
    } else {
        format!("{prefix}.{key}")
    }
}

fn walk_table(t: &Table, prefix: &str) -> Option<String> {
    for (k, v) in t {
        let path = join(prefix, k);
        if !is_known(&path) {
            return Some(path);
        }
        if let Some(p) = walk_value(v, &path) {
            return Some(p);
        }
    }
    None
}

fn walk_value(v: &Value, path: &str) -> Option<String> {
    match v {
        Value::Table(t) => walk_table(t, path),
        Value::Array(items) if is_known(&format!("{path}[]")) => {
            for (i, item) in items.iter().enumerate() {
                if let Value::Table(t) = item {
                    if let Some(p) = walk_table(t, &format!("{path}[{i}]")) {
                        return Some(p);
                    }
                }
            }
            None
        }
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn suggestions() {
        assert_eq!(suggest("load.forse").as_deref(), Some("load.force"));
        assert_eq!(
            suggest("load.entrainment_speed").as_deref(),
            Some("motion.entrainment_speed")
        );
        assert_eq!(suggest("lubricnt").as_deref(), Some("lubricant"));
        assert_eq!(
            suggest("body1.young_modulus").as_deref(),
            Some("body1.youngs_modulus")
        );
        assert_eq!(
            suggest("body2.poisson").as_deref(),
            Some("body2.poisson_ratio")
        );
        assert_eq!(
            suggest("body1.axial_offset").as_deref(),
            Some("body2.axial_offset")
        );
        assert_eq!(
            suggest("features[2].dept").as_deref(),
            Some("features[2].depth")
        );
        assert_eq!(suggest("grid.qqqqqqqq"), None);
        assert_eq!(suggest("load.x"), None);
        assert!(unknown_key_message("load.force.x").contains("not a table"));
    }

    #[test]
    fn unknown_nested_keys_name_the_deepest_known_table() {
        let m = unknown_key_message("a.b.c.d.e.f");
        assert!(m.contains("no table `a`") && m.contains("title"), "{m}");
        let m = unknown_key_message("grid.qq.zz.ww");
        assert!(
            m.contains("[grid] has no sub-table `qq`") && m.contains("nx"),
            "{m}"
        );
        assert!(!m.ends_with(": "), "{m}");
        let m = unknown_key_message("load.");
        assert!(m.contains("`load.`") && m.contains("empty or blank"), "{m}");
        let m = unknown_key_message(" ");
        assert!(m.contains("` `"), "{m}");
    }

    #[test]
    fn known_keys() {
        assert!(is_known("features[12].pattern.rows"));
        assert!(is_known("body2.profile.crown_radius"));
        assert!(!is_known("body1.axial_offset"));
        assert!(!is_known("load.forse"));
    }
}
