//! Typed, checked reads from one table of the TOML tree. Every failure is an
//! [`Error::Case`] naming the file, the full dotted key and what is wrong.

use crate::Error;
use toml::{Table, Value};

pub(crate) type R<T> = std::result::Result<T, Error>;

/// A number for messages, to 6 significant digits: plain for ordinary magnitudes, exponent form
/// otherwise (values a person typed come back as typed).
pub fn fmt_num(v: f64) -> String {
    if v.is_nan() {
        return "nan".into();
    }
    if v.is_infinite() {
        return if v > 0.0 { "inf".into() } else { "-inf".into() };
    }
    let r: f64 = format!("{v:.5e}").parse().unwrap_or(v);
    if r == 0.0 || (1e-3..1e6).contains(&r.abs()) {
        format!("{r}")
    } else {
        format!("{r:e}")
    }
}

/// "a string (\"30mm\")", "the integer 3", ... for messages about wrong types.
pub fn describe(v: &Value) -> String {
    match v {
        Value::String(s) => format!("the string \"{s}\""),
        Value::Integer(i) => format!("the integer {i}"),
        Value::Float(f) => format!("the number {}", fmt_num(*f)),
        Value::Boolean(b) => format!("the boolean {b}"),
        Value::Datetime(d) => format!("the date {d}"),
        Value::Array(_) => "an array".into(),
        Value::Table(_) => "a table".into(),
    }
}

/// One table of the case, with its dotted path for messages.
#[derive(Clone, Copy)]
pub(crate) struct Sec<'a> {
    pub file: &'a str,
    pub path: &'a str,
    pub table: &'a Table,
}

pub(crate) fn case_err(file: &str, key: &str, message: impl Into<String>) -> Error {
    Error::Case {
        file: file.to_string(),
        key: key.to_string(),
        message: message.into(),
    }
}

impl<'a> Sec<'a> {
    /// The full dotted key of `k` in this table.
    pub fn key(&self, k: &str) -> String {
        if self.path.is_empty() {
            k.to_string()
        } else {
            format!("{}.{}", self.path, k)
        }
    }

    pub fn err(&self, k: &str, message: impl Into<String>) -> Error {
        case_err(self.file, &self.key(k), message)
    }

    pub fn has(&self, k: &str) -> bool {
        self.table.contains_key(k)
    }

    pub fn get(&self, k: &str) -> Option<&'a Value> {
        self.table.get(k)
    }

    /// Error for a key that is required but absent.
    pub fn missing(&self, k: &str, what: &str) -> Error {
        self.err(k, format!("missing: give {what}"))
    }

    /// A number (integers accepted), any value including inf and nan; `unit` for messages.
    pub fn num(&self, k: &str, unit: &str) -> R<Option<f64>> {
        match self.get(k) {
            None => Ok(None),
            Some(Value::Float(f)) => Ok(Some(*f)),
            Some(Value::Integer(i)) => Ok(Some(*i as f64)),
            Some(Value::String(s)) if s.trim().parse::<f64>().is_ok() => Err(self.err(
                k,
                format!(
                    "expected a number ({unit}), found the string \"{s}\"; write it without quotes"
                ),
            )),
            Some(v) => Err(self.err(
                k,
                format!("expected a number ({unit}), found {}", describe(v)),
            )),
        }
    }

    /// A finite number.
    pub fn finite(&self, k: &str, unit: &str) -> R<Option<f64>> {
        match self.num(k, unit)? {
            Some(v) if !v.is_finite() => Err(self.err(
                k,
                format!("must be a finite number ({unit}), found {}", fmt_num(v)),
            )),
            v => Ok(v),
        }
    }

    /// [`Sec::num`], required: a missing key is an error asking for `what`.
    pub fn required_num(&self, k: &str, unit: &str, what: &str) -> R<f64> {
        self.num(k, unit)?.ok_or_else(|| self.missing(k, what))
    }

    /// [`Sec::finite`], required: a missing key is an error asking for `what`.
    pub fn required_finite(&self, k: &str, unit: &str, what: &str) -> R<f64> {
        self.finite(k, unit)?.ok_or_else(|| self.missing(k, what))
    }

    /// [`Sec::positive`], required: a missing key is an error asking for `what`.
    pub fn required_positive(&self, k: &str, unit: &str, what: &str) -> R<f64> {
        self.positive(k, unit)?.ok_or_else(|| self.missing(k, what))
    }

    /// A positive, finite number.
    pub fn positive(&self, k: &str, unit: &str) -> R<Option<f64>> {
        match self.num(k, unit)? {
            Some(v) if !(v > 0.0 && v.is_finite()) => Err(self.err(
                k,
                format!(
                    "must be a positive, finite number ({unit}), found {}",
                    fmt_num(v)
                ),
            )),
            v => Ok(v),
        }
    }

    /// A finite number >= 0.
    pub fn non_negative(&self, k: &str, unit: &str) -> R<Option<f64>> {
        match self.num(k, unit)? {
            Some(v) if !(v >= 0.0 && v.is_finite()) => Err(self.err(
                k,
                format!(
                    "must be a finite number >= 0 ({unit}), found {}",
                    fmt_num(v)
                ),
            )),
            v => Ok(v),
        }
    }

    /// A whole number (an integral float such as `128.0` is accepted, e.g. from a sweep).
    pub fn int(&self, k: &str, what: &str) -> R<Option<i64>> {
        match self.get(k) {
            None => Ok(None),
            Some(Value::Integer(i)) => Ok(Some(*i)),
            Some(Value::Float(f)) if f.is_finite() && f.fract() == 0.0 && f.abs() < 9e15 => {
                Ok(Some(*f as i64))
            }
            Some(v) => Err(self.err(
                k,
                format!("expected a whole number ({what}), found {}", describe(v)),
            )),
        }
    }

    /// A whole number >= `min`.
    pub fn count(&self, k: &str, what: &str, min: i64) -> R<Option<usize>> {
        match self.int(k, what)? {
            Some(v) if v < min => {
                Err(self.err(k, format!("must be at least {min} ({what}), found {v}")))
            }
            Some(v) => Ok(Some(v as usize)),
            None => Ok(None),
        }
    }

    pub fn boolean(&self, k: &str) -> R<Option<bool>> {
        match self.get(k) {
            None => Ok(None),
            Some(Value::Boolean(b)) => Ok(Some(*b)),
            Some(v) => Err(self.err(k, format!("expected true or false, found {}", describe(v)))),
        }
    }

    pub fn string(&self, k: &str, what: &str) -> R<Option<&'a str>> {
        match self.get(k) {
            None => Ok(None),
            Some(Value::String(s)) => Ok(Some(s.as_str())),
            Some(v) => Err(self.err(
                k,
                format!("expected a string ({what}), found {}", describe(v)),
            )),
        }
    }

    /// One of a fixed set of words.
    pub fn choice(&self, k: &str, options: &[&'static str]) -> R<Option<&'static str>> {
        let list = options
            .iter()
            .map(|o| format!("\"{o}\""))
            .collect::<Vec<_>>()
            .join(", ");
        let Some(s) = self.string(k, &format!("one of {list}"))? else {
            return Ok(None);
        };
        choose(s, options).map(Some).map_err(|m| self.err(k, m))
    }

    /// A sub-table.
    pub fn table(&self, k: &str, what: &str) -> R<Option<&'a Table>> {
        match self.get(k) {
            None => Ok(None),
            Some(Value::Table(t)) => Ok(Some(t)),
            Some(v) => Err(self.err(
                k,
                format!("expected a table ({what}), found {}", describe(v)),
            )),
        }
    }
}

/// Matches `s` against `options` (case-insensitive, `_` = `-`), else a message with the closest.
pub fn choose(s: &str, options: &[&'static str]) -> std::result::Result<&'static str, String> {
    let norm = s.trim().to_lowercase().replace('_', "-");
    if let Some(o) = options.iter().find(|o| **o == norm) {
        return Ok(o);
    }
    let list = options
        .iter()
        .map(|o| format!("\"{o}\""))
        .collect::<Vec<_>>()
        .join(", ");
    let best = options
        .iter()
        .map(|o| (strsim::normalized_damerau_levenshtein(&norm, o), *o))
        .max_by(|a, b| a.0.total_cmp(&b.0));
    match best {
        Some((sim, o)) if sim >= 0.5 => Err(format!(
            "unknown value \"{s}\"; did you mean \"{o}\"? (expected one of {list})"
        )),
        _ => Err(format!("unknown value \"{s}\"; expected one of {list}")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_for_messages() {
        assert_eq!(fmt_num(0.03), "0.03");
        assert_eq!(fmt_num(200e9), "2e11");
        assert_eq!(fmt_num(1.5e-9), "1.5e-9");
        assert_eq!(fmt_num(0.0), "0");
        assert_eq!(fmt_num(-5.0), "-5");
        assert_eq!(fmt_num(f64::INFINITY), "inf");
        assert_eq!(fmt_num(1.3183216521636505), "1.31832");
        assert_eq!(fmt_num(30000.0), "30000");
    }

    #[test]
    fn choices() {
        assert_eq!(choose("Roller", &["roller", "ball"]), Ok("roller"));
        assert_eq!(
            choose("rounded_edge", &["straight", "rounded-edge"]),
            Ok("rounded-edge")
        );
        let e = choose("rolller", &["roller", "ball", "flat"]).unwrap_err();
        assert!(e.contains("did you mean \"roller\""), "{e}");
    }
}
