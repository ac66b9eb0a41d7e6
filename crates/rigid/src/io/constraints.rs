//! The constraint files of `rigid eval --constraints` (see `docs/conventions.md`):
//!
//! ```json
//! {"constraints": [{"type": "point" | "frame", "joint1": NAME,
//!                   "placement1": {"translation": [3], "rotation": [[3x3]]},
//!                   "joint2": NAME or "universe", "placement2": {...},
//!                   "reference_frame": "local" | "local_world_aligned",
//!                   "baumgarte": {"kp": 0, "kd": 0}}],
//!  "mu": 0, "restitution": 0}
//! ```
//!
//! Joints by name, placements relative to the joint frame (to the world for `"universe"`), the
//! semantics of [`ConstraintModel`]. Defaults: `placement` the identity (either key may be left
//! out), `joint2` `"universe"`, `reference_frame` `"local"`, no Baumgarte correction, `mu` and
//! `restitution` 0. Added keys: a constraint's `"name"`; `{"type": "joint_coordinate",
//! "joint1", "joint2", "polycoef": [5]}` (MJCF's `<equality joint>`); and the solver's
//! `"max_iter"` (default 1000; one exact solve when `mu` is 0), `"absolute_accuracy"` and
//! `"relative_accuracy"` (default 1e-12).

use crate::multibody::constraints::{
    Baumgarte, ConstraintKind, ConstraintModel, ProximalSettings, UNIVERSE,
};
use crate::multibody::Model;
use crate::spatial::{Mat3, Transform, Vec3};
use serde_json::Value;

/// A parsed constraint file.
#[derive(Clone, Debug, PartialEq)]
pub struct ConstraintFile {
    /// The constraints, in the file's order.
    pub constraints: Vec<ConstraintModel>,
    /// `mu`, the iteration limit and the accuracies.
    pub settings: ProximalSettings,
    /// The restitution coefficient of the impulses.
    pub restitution: f64,
}

/// Reads a constraint file against `model` (joint names looked up; the constraints themselves
/// are checked when the workspace is made,
/// [`ConstraintData::new`](crate::multibody::constraints::ConstraintData::new)).
///
/// ```
/// let model = rigid::multibody::builtin("double_pendulum").unwrap();
/// let text = r#"{"constraints": [{"type": "point", "joint1": "joint2",
///     "placement1": {"translation": [0, 0, -1]}, "reference_frame": "local_world_aligned",
///     "baumgarte": {"kp": 100, "kd": 20}}], "mu": 0}"#;
/// let file = rigid::io::constraints::parse_constraints(text, &model).unwrap();
/// assert_eq!((file.constraints.len(), file.constraints[0].joint2), (1, None));
/// let err = rigid::io::constraints::parse_constraints(
///     r#"{"constraints": [{"type": "point", "joint1": "elbow"}]}"#, &model).unwrap_err();
/// assert_eq!(err, "constraint 0: \"joint1\": no joint named \"elbow\" (\"universe\" is the world)");
/// ```
///
/// # Errors
/// A message naming the constraint and the field: malformed JSON, a missing or mistyped field,
/// an unknown joint, type or reference frame, a number out of range.
pub fn parse_constraints(text: &str, model: &Model) -> Result<ConstraintFile, String> {
    let root: Value = serde_json::from_str(text).map_err(|e| format!("malformed JSON: {e}"))?;
    let list = root
        .get("constraints")
        .ok_or("expected an object with a \"constraints\" array")?
        .as_array()
        .ok_or("\"constraints\" is not an array")?;
    let constraints = list
        .iter()
        .enumerate()
        .map(|(i, c)| constraint(c, model).map_err(|e| format!("constraint {i}: {e}")))
        .collect::<Result<Vec<_>, _>>()?;
    let mu = number(&root, "mu", 0.0)?;
    let settings = ProximalSettings {
        mu,
        absolute_accuracy: number(&root, "absolute_accuracy", 1e-12)?,
        relative_accuracy: number(&root, "relative_accuracy", 1e-12)?,
        max_iter: match root.get("max_iter") {
            None => 1000,
            Some(x) => x
                .as_u64()
                .filter(|n| *n >= 1)
                .ok_or("\"max_iter\" is not a positive integer")? as usize,
        },
    };
    if mu.is_nan()
        || mu < 0.0
        || settings.absolute_accuracy < 0.0
        || settings.relative_accuracy < 0.0
    {
        return Err("\"mu\" and the accuracies must be >= 0".into());
    }
    let restitution = number(&root, "restitution", 0.0)?;
    if !(0.0..=1.0).contains(&restitution) {
        return Err(format!("\"restitution\" {restitution} is not in [0, 1]"));
    }
    Ok(ConstraintFile {
        constraints,
        settings,
        restitution,
    })
}

fn constraint(c: &Value, model: &Model) -> Result<ConstraintModel, String> {
    if !c.is_object() {
        return Err("not an object".into());
    }
    let text = |key: &str, default: Option<&'static str>| -> Result<String, String> {
        match c.get(key) {
            None => default
                .map(String::from)
                .ok_or(format!("\"{key}\" is missing")),
            Some(v) => v
                .as_str()
                .map(String::from)
                .ok_or(format!("\"{key}\" is not a string")),
        }
    };
    let joint = |key: &str, default| -> Result<Option<_>, String> {
        let name = text(key, default)?;
        if name == UNIVERSE {
            return Ok(None);
        }
        model.joint_id(&name).map(Some).ok_or(format!(
            "\"{key}\": no joint named \"{name}\" (\"universe\" is the world)"
        ))
    };
    let kind = match text("type", None)?.as_str() {
        "point" => ConstraintKind::Point,
        "frame" => ConstraintKind::Frame,
        "joint_coordinate" => {
            let p = c.get("polycoef").ok_or("\"polycoef\" is missing")?;
            let arr = p
                .as_array()
                .filter(|a| a.len() <= 5)
                .ok_or("\"polycoef\" is not an array of at most 5 numbers")?;
            let mut polycoef = [0.0; 5];
            for (k, x) in arr.iter().enumerate() {
                polycoef[k] = x
                    .as_f64()
                    .ok_or(format!("\"polycoef\"[{k}] is not a number"))?;
            }
            let joint1 = joint("joint1", None)?.ok_or("\"joint1\" must be a joint")?;
            let name = text("name", Some(""))?;
            return Ok(ConstraintModel::joint_coordinate(
                joint1,
                joint("joint2", Some(UNIVERSE))?,
                polycoef,
            )
            .with_name(name));
        }
        other => {
            return Err(format!(
                "\"type\" is \"{other}\" (expected \"point\", \"frame\" or \"joint_coordinate\")"
            ))
        }
    };
    let reference = ConstraintModel::reference_named(&text("reference_frame", Some("local"))?)?;
    let (kp, kd) = match c.get("baumgarte") {
        None => (0.0, 0.0),
        Some(b) if b.is_object() => (
            number(b, "kp", 0.0).map_err(|e| format!("\"baumgarte\": {e}"))?,
            number(b, "kd", 0.0).map_err(|e| format!("\"baumgarte\": {e}"))?,
        ),
        Some(_) => return Err("\"baumgarte\" is not an object".into()),
    };
    Ok(ConstraintModel {
        name: text("name", Some(""))?,
        kind,
        joint1: joint("joint1", None)?,
        placement1: placement(c.get("placement1")).map_err(|e| format!("\"placement1\": {e}"))?,
        joint2: joint("joint2", Some(UNIVERSE))?,
        placement2: placement(c.get("placement2")).map_err(|e| format!("\"placement2\": {e}"))?,
        reference,
        baumgarte: Baumgarte { kp, kd },
    })
}

/// `{"translation": [3], "rotation": [[3x3]]}` (each key optional), or the identity if absent.
fn placement(p: Option<&Value>) -> Result<Transform, String> {
    let Some(p) = p else {
        return Ok(Transform::identity());
    };
    if !p.is_object() {
        return Err("is not an object".into());
    }
    let row = |v: &Value, what: &str| -> Result<[f64; 3], String> {
        let a = v
            .as_array()
            .filter(|a| a.len() == 3)
            .ok_or(format!("{what} is not an array of 3 numbers"))?;
        let mut out = [0.0; 3];
        for (k, x) in a.iter().enumerate() {
            out[k] = x.as_f64().ok_or(format!("{what}[{k}] is not a number"))?;
        }
        Ok(out)
    };
    let translation = match p.get("translation") {
        None => Vec3::zeros(),
        Some(t) => Vec3::from(row(t, "\"translation\"")?),
    };
    let rotation = match p.get("rotation") {
        None => Mat3::identity(),
        Some(r) => {
            let rows = r
                .as_array()
                .filter(|a| a.len() == 3)
                .ok_or("\"rotation\" is not a 3x3 array (row-major)")?;
            let mut m = Mat3::zeros();
            for (i, x) in rows.iter().enumerate() {
                let x = row(x, &format!("\"rotation\"[{i}]"))?;
                for (k, y) in x.iter().enumerate() {
                    m[(i, k)] = *y;
                }
            }
            m
        }
    };
    Ok(Transform::new(rotation, translation))
}

/// `obj[key]` as a number, or `default` if absent.
fn number(obj: &Value, key: &str, default: f64) -> Result<f64, String> {
    match obj.get(key) {
        None => Ok(default),
        Some(x) => x.as_f64().ok_or(format!("\"{key}\" is not a number")),
    }
}
