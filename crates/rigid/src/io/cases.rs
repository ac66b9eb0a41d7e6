//! The states of `rigid eval`: `{"cases": [{"q": [...], "v": [...], "a": [...], "tau": [...]}]}`
//! (`v`, `a` and `tau` default to zero), every field checked against a model.

use crate::multibody::Model;
use serde_json::Value;

/// One state to evaluate.
#[derive(Clone, Debug, PartialEq)]
pub struct Case {
    /// Configuration (`nq`).
    pub q: Vec<f64>,
    /// Velocity (`nv`).
    pub v: Vec<f64>,
    /// Acceleration (`nv`).
    pub a: Vec<f64>,
    /// Generalized force (`nv`).
    pub tau: Vec<f64>,
}

/// Reads `{"cases": [...]}`, checking every field's type and length against `model`.
///
/// ```
/// let model = rigid::multibody::builtin("pendulum").unwrap();
/// let cases = rigid::io::cases::parse_cases(r#"{"cases": [{"q": [0.1]}]}"#, &model).unwrap();
/// assert_eq!((cases[0].q.as_slice(), cases[0].v.as_slice()), (&[0.1][..], &[0.0][..]));
/// let err = rigid::io::cases::parse_cases(r#"{"cases": [{"q": [0.1, 2]}]}"#, &model).unwrap_err();
/// assert_eq!(err, "case 0: \"q\" has 2 entries (expected nq = 1)");
/// ```
///
/// # Errors
/// A message naming the case and the field: malformed JSON (with its line and column), a missing
/// or mistyped field, a wrong length.
pub fn parse_cases(text: &str, model: &Model) -> Result<Vec<Case>, String> {
    parse_cases_with(text, model.nq(), model.nv())
}

/// As [`parse_cases`], for vectors of `nq` and `nv` numbers (e.g. Pinocchio's `nq`, see
/// [`crate::interop`]).
///
/// ```
/// let cases = rigid::io::cases::parse_cases_with(r#"{"cases": [{"q": [1, 0]}]}"#, 2, 1).unwrap();
/// assert_eq!((cases[0].q.len(), cases[0].tau.len()), (2, 1));
/// ```
///
/// # Errors
/// As [`parse_cases`].
pub fn parse_cases_with(text: &str, nq: usize, nv: usize) -> Result<Vec<Case>, String> {
    let root: Value = serde_json::from_str(text).map_err(|e| format!("malformed JSON: {e}"))?;
    let list = root
        .get("cases")
        .ok_or("expected an object with a \"cases\" array")?
        .as_array()
        .ok_or("\"cases\" is not an array")?;
    let mut cases = Vec::with_capacity(list.len());
    for (i, c) in list.iter().enumerate() {
        if !c.is_object() {
            return Err(format!("case {i}: not an object"));
        }
        let field = |name: &str, len: usize, dim: &str, required: bool| {
            vector(c.get(name), len, required)
                .map_err(|e| format!("case {i}: \"{name}\" {e} (expected {dim} = {len})"))
        };
        cases.push(Case {
            q: field("q", nq, "nq", true)?,
            v: field("v", nv, "nv", false)?,
            a: field("a", nv, "nv", false)?,
            tau: field("tau", nv, "nv", false)?,
        });
    }
    Ok(cases)
}

/// A vector of `len` numbers, or zeros if absent and not required.
fn vector(value: Option<&Value>, len: usize, required: bool) -> Result<Vec<f64>, String> {
    let Some(value) = value else {
        return if required {
            Err("is missing".into())
        } else {
            Ok(vec![0.0; len])
        };
    };
    let arr = value.as_array().ok_or("is not an array of numbers")?;
    let out = arr
        .iter()
        .enumerate()
        .map(|(k, x)| x.as_f64().ok_or(format!("[{k}] is not a number")))
        .collect::<Result<Vec<f64>, _>>()?;
    if out.len() != len {
        return Err(format!("has {} entries", out.len()));
    }
    Ok(out)
}
