//! `rigid.inverse_kinematics` (also `rigid.pinocchio.inverse_kinematics`): the Python side of
//! `rigid::kinematics::inverse`, which does the work; this file parses the target and the options
//! and prints the result as a dict.

use crate::convert::{self, matrix, value_error, vector};
use crate::model::{Data, Model, Place};
use crate::pinocchio::refuse_mujoco;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rigid::kinematics::{self, ErrorTwist, IkError, Options, Site, Target};
use rigid::multibody as mb;
use rigid::spatial::{Mat3, Transform, Vec3};

/// A target of `inverse_kinematics`: a 3-vector (a position), a 4 x 4 homogeneous matrix, a pair
/// `(R, p)`, or an object with a `homogeneous` attribute (Pinocchio's `SE3`).
fn ik_target(x: &Bound<'_, PyAny>) -> PyResult<Target> {
    const F: &str = "inverse_kinematics";
    let x = if x.hasattr("homogeneous")? {
        x.getattr("homogeneous")?
    } else {
        x.clone()
    };
    if let Ok((r, p)) = x.extract::<(Bound<'_, PyAny>, Bound<'_, PyAny>)>() {
        let r = matrix(&r, F, "target_pose[0] (R)", "3", 3)?;
        if r.rows != 3 {
            return Err(value_error(F, "target_pose[0] (R) must be 3 x 3"));
        }
        let s = r.as_slice();
        let p = convert::vec3(&p, F, "target_pose[1] (p)")?;
        return Ok(Target::Pose(Transform::new(Mat3::from_row_slice(s), p)));
    }
    if let Ok(m) = matrix(&x, F, "target_pose", "4", 4) {
        if m.rows != 4 {
            return Err(value_error(
                F,
                "target_pose must be a 4 x 4 homogeneous matrix",
            ));
        }
        let s = m.as_slice();
        let r = Mat3::new(s[0], s[1], s[2], s[4], s[5], s[6], s[8], s[9], s[10]);
        return Ok(Target::Pose(Transform::new(
            r,
            Vec3::new(s[3], s[7], s[11]),
        )));
    }
    let p = convert::vec3(&x, F, "target_pose").map_err(|_| {
        PyValueError::new_err(
            "inverse_kinematics: target_pose must be a position (3,), a 4 x 4 homogeneous \
             matrix, a pair (R, p) or a pinocchio SE3",
        )
    })?;
    Ok(Target::Position(p))
}

/// Inverse kinematics (`rigid::kinematics::inverse`): joint positions that put the joint or
/// frame `frame` at `target_pose`, from `q0` (default neutral) then random restarts. Returns a
/// dict: `q` (the model's layout), `converged`, `angular_error`, `linear_error`,
/// `position_error`, `iterations`, `total_iterations`, `attempts`.
#[pyfunction]
#[pyo3(signature = (model, frame, target_pose, q0 = None, *, twist = "body", tolerance = 1e-9,
    max_iterations = 100, damping = 1e-3, restarts = 20, seed = 0, respect_limits = true,
    data = None))]
#[allow(clippy::too_many_arguments)]
pub fn inverse_kinematics<'py>(
    py: Python<'py>,
    model: PyRef<'py, Model>,
    frame: &str,
    target_pose: &Bound<'py, PyAny>,
    q0: Option<&Bound<'py, PyAny>>,
    twist: &str,
    tolerance: f64,
    max_iterations: usize,
    damping: f64,
    restarts: usize,
    seed: u64,
    respect_limits: bool,
    data: Option<PyRefMut<'py, Data>>,
) -> PyResult<Bound<'py, PyDict>> {
    const F: &str = "inverse_kinematics";
    let core = &*model.inner;
    refuse_mujoco(F, core)?;
    let m = &core.model;
    let site = match core.lookup(F, frame)? {
        Place::Joint(j) => Site::Joint(j),
        Place::Frame(f) => Site::Frame(f),
    };
    let target = ik_target(target_pose)?;
    let q0 = match q0 {
        Some(x) => {
            let x = vector(x, F, "q0", "nq", core.nq())?;
            let mut out = Vec::new();
            core.q_into(&x, &mut out, F, "q0")?;
            out
        }
        None => mb::neutral(m),
    };
    let twist = match twist {
        "body" => ErrorTwist::Body,
        "space" => ErrorTwist::Space,
        _ => {
            return Err(PyValueError::new_err(format!(
                "{F}: twist must be \"body\" or \"space\", got \"{twist}\""
            )))
        }
    };
    let options = Options {
        twist,
        angular_tolerance: tolerance,
        linear_tolerance: tolerance,
        max_iterations,
        damping,
        restarts,
        seed,
        respect_limits,
    };
    let result = match data {
        Some(mut d) => {
            core.check_data(F, &d)?;
            kinematics::inverse(m, &mut d.inner, site, &target, &q0, &options)
        }
        None => kinematics::inverse(m, &mut mb::Data::new(m), site, &target, &q0, &options),
    };
    let s = match result {
        Ok(s) => s,
        Err(IkError::NotConverged { best }) => *best,
        Err(IkError::BadOption {
            name,
            value,
            reason,
        }) => {
            let name = match name {
                "angular_tolerance" | "linear_tolerance" => "tolerance",
                n => n,
            };
            return Err(PyValueError::new_err(format!(
                "{F}: {name} = {value}: {reason}"
            )));
        }
        Err(IkError::Input(e)) => return Err(value_error(F, format!("q0: {e}"))),
        Err(e) => return Err(value_error(F, format!("target_pose: {e}"))),
    };
    let out = PyDict::new(py);
    out.set_item("q", core.q_out(py, &s.q))?;
    out.set_item("converged", s.converged)?;
    out.set_item("angular_error", s.angular_error)?;
    out.set_item("linear_error", s.linear_error)?;
    out.set_item("position_error", s.position_error)?;
    out.set_item("iterations", s.iterations)?;
    out.set_item("total_iterations", s.total_iterations)?;
    out.set_item("attempts", s.attempts)?;
    Ok(out)
}
