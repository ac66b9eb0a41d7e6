//! The stable serialised form of a [`Model`]: every field a user gave (joints, placements, body
//! inertias, frames, limits, armature, damping, friction, gravity), nothing derived (the
//! [plan](super::plan) is rebuilt on reading), in any serde format; [`Model::to_json`] and
//! [`Model::from_json`] for JSON. Numbers round-trip exactly (serde_json writes the shortest
//! decimal that reads back to the same `f64`), so a model read back computes the same results
//! bit for bit: what shipping a model to another process or machine needs (Python's pickle, Dask,
//! Ray).
//!
//! The form: `{"format": "rigid-model", "version": 1, "name", "gravity": [3], "joints": [{"name",
//! "kind": {"type": "revolute", "axis": [3]}, "parent": index or null, "placement":
//! {"rotation": [[3x3]], "translation": [3]}, "idx_q", "nq", "idx_v", "nv", "subtree_end",
//! "continuous"}], "inertias": [{"mass", "first_moment": [3], "inertia_origin": [[3x3]]}],
//! "frames": [{"name", "parent", "placement", "kind"}], "lower", "upper", "velocity_limit",
//! "effort_limit": [numbers or null for no limit], "armature", "damping", "friction": [numbers]}`.
//! Reading checks everything the builder checks (names, depth-first parents and indices,
//! rigid placements, finite inertias with non-negative mass, limits, lengths), so a hostile file
//! is an error, never an inconsistent model.
//!
//! ```
//! let model = rigid::multibody::builtin("puma560").unwrap();
//! let json = model.to_json();
//! let back = rigid::multibody::Model::from_json(&json)?;
//! assert_eq!(back.to_json(), json);
//! # Ok::<(), rigid::multibody::ModelError>(())
//! ```

use super::builder::{check_inertia, check_placement};
use super::model::{Frame, Joint};
use super::{InertiaCheck, Model, ModelError};
use crate::mass::SpatialInertia;
use serde::{Deserialize, Serialize};

const FORMAT: &str = "rigid-model";
const VERSION: u32 = 1;

/// The file form of a model (module documentation).
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct ModelFile {
    format: String,
    version: u32,
    name: String,
    gravity: [f64; 3],
    joints: Vec<Joint>,
    inertias: Vec<SpatialInertia>,
    frames: Vec<Frame>,
    /// `null` for `-∞`.
    lower: Vec<Option<f64>>,
    /// `null` for `+∞` (also the velocity and effort limits).
    upper: Vec<Option<f64>>,
    velocity_limit: Vec<Option<f64>>,
    effort_limit: Vec<Option<f64>>,
    armature: Vec<f64>,
    damping: Vec<f64>,
    friction: Vec<f64>,
}

/// `Some(x)` for a finite `x`, `None` for an infinity (JSON has no infinity).
fn finite(x: &[f64]) -> Vec<Option<f64>> {
    x.iter().map(|v| v.is_finite().then_some(*v)).collect()
}

impl From<&Model> for ModelFile {
    fn from(m: &Model) -> Self {
        Self {
            format: FORMAT.into(),
            version: VERSION,
            name: m.name.clone(),
            gravity: [m.gravity.x, m.gravity.y, m.gravity.z],
            joints: m.joints().to_vec(),
            inertias: m.inertias().to_vec(),
            frames: m.frames.clone(),
            lower: finite(&m.lower),
            upper: finite(&m.upper),
            velocity_limit: finite(&m.velocity_limit),
            effort_limit: finite(&m.effort_limit),
            armature: m.armature.clone(),
            damping: m.damping.clone(),
            friction: m.friction.clone(),
        }
    }
}

impl TryFrom<ModelFile> for Model {
    type Error = ModelError;

    /// Checks the file as the builder checks its calls, then builds the model and its plan.
    fn try_from(f: ModelFile) -> Result<Self, ModelError> {
        let invalid = |what: String| ModelError::InvalidFile { what };
        if f.format != FORMAT || f.version != VERSION {
            return Err(invalid(format!(
                "format \"{}\" version {} (expected \"{FORMAT}\" version {VERSION})",
                f.format, f.version
            )));
        }
        if f.gravity.iter().any(|g| !g.is_finite()) {
            return Err(ModelError::BadGravity);
        }
        let (mut nq, mut nv) = (0, 0);
        let mut names = std::collections::HashSet::new();
        for (i, j) in f.joints.iter().enumerate() {
            if !names.insert(j.name.as_str()) {
                return Err(ModelError::DuplicateName {
                    name: j.name.clone(),
                });
            }
            if j.parent.is_some_and(|p| p.0 >= i) {
                return Err(ModelError::NotDepthFirst {
                    name: j.name.clone(),
                    parent: format!("index {}", j.parent.map_or(0, |p| p.0)),
                });
            }
            if j.kind.normalized_axis() != Some(j.kind) {
                return Err(ModelError::BadAxis {
                    name: j.name.clone(),
                });
            }
            let indices = (j.idx_q, j.nq, j.idx_v, j.nv);
            if indices != (nq, j.kind.nq(), nv, j.kind.nv()) || j.subtree_end <= i {
                return Err(invalid(format!("joint '{}': wrong indices", j.name)));
            }
            check_placement(&j.name, &j.placement)?;
            (nq, nv) = (nq + j.nq, nv + j.nv);
        }
        // each subtree is the contiguous range of its depth-first descendants
        let n = f.joints.len();
        for (i, j) in f.joints.iter().enumerate() {
            let end = (i + 1..n)
                .find(|&k| !ancestors(&f.joints, k).any(|a| a == i))
                .unwrap_or(n);
            if j.subtree_end != end {
                return Err(invalid(format!("joint '{}': wrong subtree_end", j.name)));
            }
        }
        if f.inertias.len() != n {
            return Err(invalid(format!(
                "{} inertias for {n} joints",
                f.inertias.len()
            )));
        }
        for (j, g) in f.joints.iter().zip(&f.inertias) {
            check_inertia(&j.name, g, InertiaCheck::AsWritten)?;
        }
        for fr in &f.frames {
            if fr.parent.is_some_and(|p| p.0 >= n) {
                return Err(ModelError::UnknownParent {
                    name: fr.name.clone(),
                    parent: fr.parent.map_or(0, |p| p.0),
                });
            }
            check_placement(&fr.name, &fr.placement)?;
        }
        let lengths = [
            ("lower", f.lower.len(), nq),
            ("upper", f.upper.len(), nq),
            ("velocity_limit", f.velocity_limit.len(), nv),
            ("effort_limit", f.effort_limit.len(), nv),
            ("armature", f.armature.len(), nv),
            ("damping", f.damping.len(), nv),
            ("friction", f.friction.len(), nv),
        ];
        for (what, got, expected) in lengths {
            if got != expected {
                return Err(invalid(format!(
                    "{what} has {got} entries, expected {expected}"
                )));
            }
        }
        let or = |x: &[Option<f64>], inf: f64| -> Vec<f64> {
            x.iter().map(|v| v.unwrap_or(inf)).collect()
        };
        let (lower, upper) = (or(&f.lower, f64::NEG_INFINITY), or(&f.upper, f64::INFINITY));
        let velocity = or(&f.velocity_limit, f64::INFINITY);
        let effort = or(&f.effort_limit, f64::INFINITY);
        let bad_limits = lower
            .iter()
            .zip(&upper)
            .any(|(l, u)| l.is_nan() || u.is_nan() || l > u)
            || velocity
                .iter()
                .chain(&effort)
                .any(|x| x.is_nan() || *x < 0.0);
        let bad_extra = |x: &[f64]| x.iter().any(|a| !a.is_finite() || *a < 0.0);
        if bad_limits || bad_extra(&f.armature) || bad_extra(&f.damping) || bad_extra(&f.friction) {
            return Err(invalid(
                "limits, armature, damping or friction out of range".into(),
            ));
        }
        Ok(Model::from_parts(
            f.name,
            f.gravity.into(),
            f.joints,
            f.inertias,
            f.frames,
            [lower, upper, velocity, effort],
            f.armature,
            f.damping,
            f.friction,
        ))
    }
}

/// The strict ancestors of joint `k`, nearest first.
fn ancestors(joints: &[Joint], k: usize) -> impl Iterator<Item = usize> + '_ {
    std::iter::successors(joints[k].parent.map(|p| p.0), |&a| {
        joints[a].parent.map(|p| p.0)
    })
}

impl Serialize for Model {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        ModelFile::from(self).serialize(s)
    }
}

impl<'de> Deserialize<'de> for Model {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let file = ModelFile::deserialize(d)?;
        Model::try_from(file).map_err(serde::de::Error::custom)
    }
}

impl Model {
    /// The model in its stable JSON form: every field a user gave, nothing derived, numbers that
    /// read back to the same `f64` ([`Model`]'s `Serialize` implementation).
    #[must_use]
    pub fn to_json(&self) -> String {
        serde_json::to_string(&ModelFile::from(self)).expect("a model always serialises")
    }

    /// A model from its JSON form, checked as the builder checks its input.
    ///
    /// # Errors
    /// Malformed JSON or a form that does not describe a valid model
    /// ([`ModelError::InvalidFile`] and the builder's errors, naming the joint or frame).
    pub fn from_json(text: &str) -> Result<Model, ModelError> {
        let file: ModelFile = serde_json::from_str(text).map_err(|e| ModelError::InvalidFile {
            what: format!("malformed model JSON: {e}"),
        })?;
        Model::try_from(file)
    }
}
