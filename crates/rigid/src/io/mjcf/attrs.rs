//! Attribute readers shared by every pass: numbers checked for count and finiteness, integers,
//! keywords, booleans, and an element's orientation.

use super::defaults::{Attrs, ALTERNATIVES};
use super::orientation::{self, Alternative, Quat};
use super::parse::Compiler;
use super::xml::Element;
use super::{MjcfError, Reader};

/// The numbers of attribute `name` (value `value`), at most `len` of them, exactly `len` when
/// `exact`; `None` when absent.
pub(super) fn numbers(
    r: &Reader,
    e: &Element,
    value: Option<&str>,
    name: &str,
    len: usize,
    exact: bool,
) -> Result<Option<Vec<f64>>, MjcfError> {
    let Some(text) = value else { return Ok(None) };
    let mut out = Vec::with_capacity(len.min(16));
    for word in text.split_whitespace() {
        let x: f64 = word.parse().map_err(|_| {
            r.invalid(
                e,
                format!("attribute \"{name}\": \"{}\" is not a number", shown(word)),
            )
        })?;
        if !x.is_finite() {
            return Err(r.invalid(e, format!("attribute \"{name}\" is not finite ({word})")));
        }
        out.push(x);
    }
    if out.len() > len {
        return Err(r.invalid(
            e,
            format!(
                "attribute \"{name}\" has {} numbers, at most {len}",
                out.len()
            ),
        ));
    }
    if exact && out.len() < len {
        return Err(r.invalid(
            e,
            format!(
                "attribute \"{name}\" has {} numbers, needs {len}",
                out.len()
            ),
        ));
    }
    Ok(Some(out))
}

/// A value as quoted in a message: at most 40 characters.
pub(super) fn shown(text: &str) -> String {
    match text.char_indices().nth(40) {
        None => text.to_string(),
        Some((cut, _)) => format!("{}… ({} bytes)", &text[..cut], text.len()),
    }
}

/// Exactly `N` numbers of `name` in `attrs`, or `default`.
pub(super) fn array<const N: usize>(
    r: &Reader,
    e: &Element,
    attrs: &Attrs,
    name: &str,
    default: [f64; N],
) -> Result<[f64; N], MjcfError> {
    Ok(
        numbers(r, e, attrs.get(name), name, N, true)?.map_or(default, |v| {
            let mut a = [0.0; N];
            a.copy_from_slice(&v);
            a
        }),
    )
}

/// Up to `N` numbers of `name` in `attrs`, over `default` (MuJoCo's non-exact attributes).
pub(super) fn partial<const N: usize>(
    r: &Reader,
    e: &Element,
    attrs: &Attrs,
    name: &str,
    default: [f64; N],
) -> Result<[f64; N], MjcfError> {
    let mut a = default;
    if let Some(v) = numbers(r, e, attrs.get(name), name, N, false)? {
        a[..v.len()].copy_from_slice(&v);
    }
    Ok(a)
}

/// One number (the first of several for `stiffness` and `damping`, MuJoCo's polynomial
/// coefficients whose first is the linear one).
pub(super) fn scalar(
    r: &Reader,
    e: &Element,
    attrs: &Attrs,
    name: &str,
    default: f64,
) -> Result<f64, MjcfError> {
    let many = matches!(name, "stiffness" | "damping");
    Ok(
        numbers(r, e, attrs.get(name), name, if many { 4 } else { 1 }, !many)?
            .and_then(|v| v.first().copied())
            .unwrap_or(default),
    )
}

/// An integer attribute.
pub(super) fn int(
    r: &Reader,
    e: &Element,
    attrs: &Attrs,
    name: &str,
    default: i32,
) -> Result<i32, MjcfError> {
    match attrs.get(name) {
        None => Ok(default),
        Some(t) => t.trim().parse().map_err(|_| {
            r.invalid(
                e,
                format!("attribute \"{name}\": \"{}\" is not an integer", shown(t)),
            )
        }),
    }
}

/// A keyword attribute: the index of its value among `words`, or `default`.
pub(super) fn keyword(
    r: &Reader,
    e: &Element,
    attrs: &Attrs,
    name: &str,
    words: &[&str],
    default: usize,
) -> Result<usize, MjcfError> {
    match attrs.get(name) {
        None => Ok(default),
        Some(t) => words.iter().position(|w| *w == t.trim()).ok_or_else(|| {
            r.invalid(
                e,
                format!(
                    "attribute \"{name}\" is \"{}\", expected one of: {}",
                    shown(t),
                    words.join(", ")
                ),
            )
        }),
    }
}

/// A `true`/`false` attribute.
pub(super) fn boolean(
    r: &Reader,
    e: &Element,
    attrs: &Attrs,
    name: &str,
    default: bool,
) -> Result<bool, MjcfError> {
    Ok(match attrs.get(name) {
        None => default,
        Some(_) => keyword(r, e, attrs, name, &["false", "true"], 0)? == 1,
    })
}

/// The orientation of an element: its (or its class's) alternative if any, else `quat`
/// normalised (MuJoCo refuses a zero quaternion), else the identity.
pub(super) fn orientation(
    r: &Reader,
    e: &Element,
    attrs: &Attrs,
    c: &Compiler,
) -> Result<Quat, MjcfError> {
    for name in ALTERNATIVES {
        let Some(text) = attrs.get(name) else {
            continue;
        };
        let n = match name {
            "axisangle" => 4,
            "xyaxes" => 6,
            _ => 3,
        };
        let v = numbers(r, e, Some(text), name, n, true)?.unwrap_or_default();
        let alt = match name {
            "axisangle" => Alternative::AxisAngle([v[0], v[1], v[2], v[3]]),
            "xyaxes" => Alternative::XyAxes([v[0], v[1], v[2], v[3], v[4], v[5]]),
            "zaxis" => Alternative::ZAxis([v[0], v[1], v[2]]),
            _ => Alternative::Euler([v[0], v[1], v[2]]),
        };
        return orientation::resolve(&alt, c.degree, &c.eulerseq).map_err(|m| r.invalid(e, m));
    }
    let mut q = array(r, e, attrs, "quat", orientation::IDENTITY)?;
    if orientation::normalize(&mut q) == 0.0 {
        return Err(r.invalid(e, "zero quaternion (or too long to normalise)".into()));
    }
    Ok(q)
}

/// The element's own attributes (no class).
pub(super) fn own(e: &Element) -> Attrs {
    Attrs::from(e.attrs.clone())
}
