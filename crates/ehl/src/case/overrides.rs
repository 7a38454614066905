//! `--set KEY=VALUE` overrides, applied to the TOML tree before validation.
//!
//! KEY is a dotted path as in error messages (`load.force`, `body1.profile.crown_radius`,
//! `features[0].depth`; `features.0.depth` also works). VALUE is read as a TOML value (number,
//! boolean, quoted string, inline table, array, `inf`, `nan`); anything that is not valid TOML is
//! taken as a bare string, so `--set kind=ehl` works without quotes.

use super::schema;
use crate::{Error, Result};
use toml::{Table, Value};

/// Reads VALUE as TOML, falling back to a bare string.
pub fn parse_value(text: &str) -> Value {
    let text = text.trim();
    if let Ok(t) = format!("v = {text}").parse::<Table>() {
        if t.len() == 1 {
            if let Some(v) = t.get("v") {
                return v.clone();
            }
        }
    }
    Value::String(text.to_string())
}

/// A message when `text` is written as a number that a 64-bit float cannot hold: a finite
/// literal that overflows to infinity (`1e999`) or a non-zero one that underflows to zero
/// (`1e-999`). TOML rejects such literals, so without this check they would be taken as
/// bare strings and reported as "a string".
pub fn out_of_range(text: &str) -> Option<String> {
    let t = text.trim();
    let digits = t.trim_start_matches(['+', '-']).replace('_', "");
    if !digits.starts_with(|c: char| c.is_ascii_digit() || c == '.') {
        return None; // inf, nan, words
    }
    let v: f64 = digits.parse().ok()?;
    let mantissa_nonzero = digits
        .split(['e', 'E'])
        .next()
        .is_some_and(|m| m.chars().any(|c| ('1'..='9').contains(&c)));
    if v.is_infinite() {
        Some(format!(
            "the number `{t}` is out of range: the largest finite number is about 1.8e308"
        ))
    } else if v == 0.0 && mantissa_nonzero {
        Some(format!(
            "the number `{t}` is out of range: it is not zero but smaller than the smallest number (about 4.9e-324)"
        ))
    } else {
        None
    }
}

/// One segment of a key path.
#[derive(Debug, Clone, PartialEq)]
enum Seg {
    Key(String),
    Index(usize),
}

/// Splits `features[0].depth` / `features.0.depth` into segments; returns the display form too.
fn split_path(key: &str) -> Option<(Vec<Seg>, String)> {
    let mut segs = Vec::new();
    for part in key.split('.') {
        let part = part.trim();
        if part.is_empty() {
            return None;
        }
        let (name, rest) = match part.find('[') {
            Some(i) => (&part[..i], &part[i..]),
            None => (part, ""),
        };
        if !name.is_empty() {
            match name.parse::<usize>() {
                Ok(i) if !segs.is_empty() => segs.push(Seg::Index(i)),
                _ => segs.push(Seg::Key(name.to_string())),
            }
        } else if rest.is_empty() {
            return None;
        }
        let mut rest = rest;
        while !rest.is_empty() {
            let close = rest.find(']')?;
            if !rest.starts_with('[') {
                return None;
            }
            let idx: usize = rest[1..close].trim().parse().ok()?;
            segs.push(Seg::Index(idx));
            rest = &rest[close + 1..];
        }
    }
    if segs.is_empty() || !matches!(segs[0], Seg::Key(_)) {
        return None;
    }
    let mut display = String::new();
    for s in &segs {
        match s {
            Seg::Key(k) => {
                if !display.is_empty() {
                    display.push('.');
                }
                display.push_str(k);
            }
            Seg::Index(i) => display.push_str(&format!("[{i}]")),
        }
    }
    Some((segs, display))
}

/// Splits `KEY=VALUE` at the first `=`.
pub fn split_assignment(text: &str) -> Option<(&str, &str)> {
    let i = text.find('=')?;
    let (k, v) = (text[..i].trim(), text[i + 1..].trim());
    (!k.is_empty()).then_some((k, v))
}

/// Checks that `key` is a valid dotted key of a case file (for `--set` and `--vary`), returning
/// its display form, or a message naming the closest valid key.
pub fn check_key(key: &str) -> std::result::Result<String, String> {
    let Some((_, display)) = split_path(key) else {
        return Err(format!(
            "`{key}` is not a dotted key path (write it like `load.force` or `features[0].depth`)"
        ));
    };
    if schema::is_known(&display) {
        Ok(display)
    } else {
        Err(schema::unknown_key_message(&display))
    }
}

/// Applies one `KEY=VALUE` override to the tree.
pub fn apply(root: &mut Table, assignment: &str, file: &str) -> Result<()> {
    let err = |key: &str, message: String| Error::Case {
        file: file.to_string(),
        key: key.to_string(),
        message,
    };
    let Some((key, value)) = split_assignment(assignment) else {
        return Err(err(
            "--set",
            format!("`{assignment}` is not of the form KEY=VALUE (e.g. `load.force=5000`)"),
        ));
    };
    let display = check_key(key).map_err(|m| err(key, format!("{m} (in --set {assignment})")))?;
    let (segs, _) = split_path(key).expect("checked by check_key");
    if let Some(m) = out_of_range(value) {
        return Err(err(&display, format!("{m} (in --set {assignment})")));
    }
    let value = parse_value(value);

    // walk down, creating missing tables
    let mut here: &mut Table = root;
    let mut shown = String::new();
    let n = segs.len();
    let mut i = 0;
    while i < n {
        let Seg::Key(name) = &segs[i] else {
            unreachable!("split_path puts a key before every index")
        };
        if !shown.is_empty() {
            shown.push('.');
        }
        shown.push_str(name);
        let last = i + 1 == n;
        if last {
            here.insert(name.clone(), value);
            return Ok(());
        }
        if let Seg::Index(idx) = segs[i + 1] {
            // an array of tables element: it must exist already
            let entry = here.get_mut(name.as_str());
            let Some(Value::Array(items)) = entry else {
                return Err(err(
                    &display,
                    format!(
                        "the case has no [[{name}]] entries, so `{name}[{idx}]` does not exist (in --set {assignment})"
                    ),
                ));
            };
            let count = items.len();
            shown.push_str(&format!("[{idx}]"));
            let Some(item) = items.get_mut(idx) else {
                return Err(err(
                    &display,
                    format!(
                        "the case has {count} [[{name}]] entries (numbered from 0), so `{shown}` does not exist (in --set {assignment})"
                    ),
                ));
            };
            if i + 2 == n {
                *item = value;
                return Ok(());
            }
            let Value::Table(t) = item else {
                return Err(err(
                    &shown,
                    format!("is not a table (in --set {assignment})"),
                ));
            };
            here = t;
            i += 2;
            continue;
        }
        let entry = here
            .entry(name.clone())
            .or_insert_with(|| Value::Table(Table::new()));
        match entry {
            Value::Table(t) => here = t,
            other => {
                return Err(err(
                    &shown,
                    format!(
                        "is {}, not a table, so `{display}` cannot be set (in --set {assignment}); set `{shown}` as a whole, e.g. `{shown}={{ ... }}`",
                        super::read::describe(other)
                    ),
                ))
            }
        }
        i += 1;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_parse_as_toml_or_bare_strings() {
        assert_eq!(parse_value("5000"), Value::Integer(5000));
        assert_eq!(parse_value("0.05"), Value::Float(0.05));
        assert_eq!(parse_value("inf"), Value::Float(f64::INFINITY));
        assert_eq!(parse_value("true"), Value::Boolean(true));
        assert_eq!(parse_value("ehl"), Value::String("ehl".into()));
        assert_eq!(parse_value("\"ehl\""), Value::String("ehl".into()));
        let t = parse_value("{ kind = \"crowned\", crown_radius = 0.5 }");
        assert_eq!(t.get("crown_radius"), Some(&Value::Float(0.5)));
    }

    #[test]
    fn numbers_out_of_range_are_named_so() {
        assert!(out_of_range("1e999").unwrap().contains("out of range"));
        assert!(out_of_range("-1.5E+400").unwrap().contains("out of range"));
        assert!(out_of_range("1e-999").unwrap().contains("out of range"));
        for ok in [
            "1e300",
            "0",
            "0.0e-999",
            "inf",
            "-inf",
            "nan",
            "ehl",
            "\"1e999\"",
        ] {
            assert_eq!(out_of_range(ok), None, "{ok}");
        }
        let mut t: Table = "kind = \"dry\"".parse().unwrap();
        let e = apply(&mut t, "load.force=1e999", "c.toml")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("load.force") && e.contains("out of range"),
            "{e}"
        );
        assert!(!e.contains("without quotes"), "{e}");
    }

    #[test]
    fn paths() {
        let (s, d) = split_path("features.0.depth").unwrap();
        assert_eq!(d, "features[0].depth");
        assert_eq!(s.len(), 3);
        assert_eq!(split_path("features[1].x").unwrap().1, "features[1].x");
        assert!(split_path("load..force").is_none());
        assert!(split_path("[0]").is_none());
    }

    #[test]
    fn apply_creates_tables_and_checks_keys() {
        let mut t: Table = "kind = \"dry\"".parse().unwrap();
        apply(&mut t, "motion.slide_to_roll=0.1", "c.toml").unwrap();
        assert_eq!(
            t["motion"]["slide_to_roll"],
            Value::Float(0.1),
            "missing table is created"
        );
        let e = apply(&mut t, "load.forse=1", "c.toml")
            .unwrap_err()
            .to_string();
        assert!(e.contains("load.force"), "{e}");
        let e = apply(&mut t, "features[0].x=1", "c.toml")
            .unwrap_err()
            .to_string();
        assert!(e.contains("no [[features]]"), "{e}");
    }
}
