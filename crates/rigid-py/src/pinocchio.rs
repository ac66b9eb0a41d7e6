//! The verbs the Pinocchio layer (`rigid.pinocchio`, Python sources in `python/rigid/pinocchio/`)
//! needs beyond the others: the spatial Jacobian of all joints, frame placements, the
//! centre-of-mass Jacobian, the centroidal momentum and its matrix, kinematics derivatives,
//! `interpolate`, `normalize`; and, private (`_` names), the Jacobians already in a `Data` (its
//! fields are `Data`'s getters, data.rs). Inverse kinematics is in inverse_kinematics.rs,
//! SE(3)/SO(3) `exp`, `log` and their Jacobians in lie.rs. Every number is computed by the
//! `rigid` crate; this file converts.

use crate::convert::{array1, array2, matrix, value_error, vector};
use crate::dynamics::reference_frame;
use crate::model::{Data, Model, ModelCore, Place};
use numpy::{PyArray1, PyArray2, PyArrayMethods};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyString;
use rigid::multibody::{self as mb, PinocchioCoords, ReferenceFrame};
use rigid::spatial::{Transform, Twist, Vec3, Wrench};

type Array1<'py> = Bound<'py, PyArray1<f64>>;
type Array2<'py> = Bound<'py, PyArray2<f64>>;

/// `true` for Pinocchio's layout (spatial vectors linear first).
fn linear_first(core: &ModelCore) -> bool {
    core.layout.is_some()
}

/// The six numbers of a twist in the model's layout: `(v, ω)` in Pinocchio's, `(ω, v)` else.
pub(crate) fn twist6(core: &ModelCore, t: &Twist) -> [f64; 6] {
    let (a, b) = if linear_first(core) {
        (t.v, t.w)
    } else {
        (t.w, t.v)
    };
    [a.x, a.y, a.z, b.x, b.y, b.z]
}

/// The six numbers of a wrench in the model's layout: `(f, m)` in Pinocchio's, `(m, f)` else.
pub(crate) fn wrench6(core: &ModelCore, w: &Wrench) -> [f64; 6] {
    twist6(core, &Twist::new(w.m, w.f))
}

/// A 6 x nv matrix of rigid's (rows angular first) as a fresh array in the model's layout
/// ([`ModelCore::jacobian_out`]).
pub(crate) fn six_by_nv<'py>(
    py: Python<'py>,
    core: &ModelCore,
    m: &nalgebra::DMatrix<f64>,
) -> Array2<'py> {
    core.jacobian_out(py, m)
}

/// A 3 x nv matrix of rigid's as a fresh array, columns in the model's layout.
pub(crate) fn three_by_nv<'py>(
    py: Python<'py>,
    core: &ModelCore,
    m: &nalgebra::DMatrix<f64>,
) -> Array2<'py> {
    array2(py, 3, m.ncols(), |r, c| m[(r, core.v_index(c))])
}

pub(crate) fn refuse_mujoco(func: &str, core: &ModelCore) -> PyResult<()> {
    if core.mujoco.is_some() {
        return Err(PyValueError::new_err(format!(
            "{func}: not available in the mujoco layout; load the model with layout=\"rigid\" or \
             \"pinocchio\""
        )));
    }
    Ok(())
}

/// The external wrenches `fext` of `rnea` / `aba`: an `(njoints, 6)` array-like, or a sequence
/// of objects with a `vector` attribute (Pinocchio's `Force`), one per moving joint in its joint
/// frame, `(m, f)` in rigid's layout and `(f, m)` in Pinocchio's; in Pinocchio's layout also
/// `njoints + 1` of them, the first (the universe's) ignored, as Pinocchio does.
pub(crate) fn external_wrenches(
    core: &ModelCore,
    x: &Bound<'_, PyAny>,
    func: &str,
) -> PyResult<Vec<Wrench>> {
    refuse_mujoco(&format!("{func}: fext"), core)?;
    let n = core.model.njoints();
    let rows: Vec<[f64; 6]> = match x
        .get_item(0)
        .ok()
        .filter(|e| e.hasattr("vector").unwrap_or(false))
    {
        Some(_) => x
            .try_iter()?
            .map(|e| {
                let v = e?.getattr("vector")?;
                let v = vector(&v, func, "fext[i].vector", "6", 6)?;
                let s = v.as_slice();
                Ok([s[0], s[1], s[2], s[3], s[4], s[5]])
            })
            .collect::<PyResult<_>>()?,
        None => {
            let m = matrix(x, func, "fext", "6", 6)?;
            m.as_slice()
                .chunks_exact(6)
                .map(|s| [s[0], s[1], s[2], s[3], s[4], s[5]])
                .collect()
        }
    };
    let skip = usize::from(linear_first(core) && rows.len() == n + 1);
    if rows.len() - skip != n {
        return Err(PyValueError::new_err(format!(
            "{func}: fext has {} wrenches, expected one per moving joint ({n}{})",
            rows.len(),
            if linear_first(core) {
                format!(", or {} with the universe's first", n + 1)
            } else {
                String::new()
            }
        )));
    }
    Ok(rows[skip..]
        .iter()
        .map(|r| {
            let (a, b) = (Vec3::new(r[0], r[1], r[2]), Vec3::new(r[3], r[4], r[5]));
            if linear_first(core) {
                Wrench::new(b, a)
            } else {
                Wrench::new(a, b)
            }
        })
        .collect())
}

/// Position bounds of the model's layout in rigid's: a continuous joint's `(cos θ, sin θ)`
/// bounds and a planar joint's angle give no bound (the angle is drawn in `[-π, π]`), and
/// `|x| ≥ 1e300` (Pinocchio's `±max double` for no limit) is infinite. `side` is -1 for lower
/// bounds, +1 for upper ones (the sign of "no bound").
pub(crate) fn bounds_to_rigid(
    core: &ModelCore,
    x: &Bound<'_, PyAny>,
    func: &str,
    name: &str,
    side: f64,
) -> PyResult<Vec<f64>> {
    refuse_mujoco(&format!("{func}: {name}"), core)?;
    let b = vector(x, func, name, "nq", core.nq())?;
    let b = b.as_slice();
    if let Some(i) = b.iter().position(|x| x.is_nan()) {
        return Err(value_error(func, format!("{name}[{i}] is NaN")));
    }
    let none = side * f64::INFINITY;
    let infinite = |x: f64| {
        if x.abs() >= 1e300 {
            x.signum() * f64::INFINITY
        } else {
            x
        }
    };
    let model = &core.model;
    let mut out = vec![0.0; model.nq()];
    for (i, j) in model.joints().iter().enumerate() {
        let (pin_q, _) = core
            .layout
            .as_ref()
            .map_or((j.idx_q, j.nq), |l| l.joint_q(i));
        let dst = &mut out[j.coordinates()];
        let coords = if core.layout.is_some() {
            j.kind.pinocchio_coords(j.continuous)
        } else {
            PinocchioCoords::Same
        };
        match coords {
            PinocchioCoords::CosSin => dst[0] = none,
            PinocchioCoords::Planar => {
                dst[0] = b[pin_q];
                dst[1] = b[pin_q + 1];
                dst[2] = none;
            }
            _ => dst.copy_from_slice(&b[pin_q..pin_q + j.nq]),
        }
    }
    Ok(out.into_iter().map(infinite).collect())
}

/// The spatial (world-frame) Jacobian of every joint, column k `[Ad_{oMi}] S_k` (6 x nv), at `q`
/// (default: the `q` of the last call with this `data`). Rows `(ω, v)` in rigid's layout,
/// `(v, ω)` in Pinocchio's (Pinocchio's `computeJointJacobians`, `data.J`).
#[pyfunction]
#[pyo3(signature = (model, data, q = None))]
pub fn compute_joint_jacobians<'py>(
    py: Python<'py>,
    model: PyRef<'py, Model>,
    mut data: PyRefMut<'py, Data>,
    q: Option<&Bound<'py, PyAny>>,
) -> PyResult<Array2<'py>> {
    const F: &str = "compute_joint_jacobians";
    let core = &*model.inner;
    refuse_mujoco(F, core)?;
    match q {
        Some(q) => crate::dynamics::load(F, &model, &mut data, q, &[])?,
        None => core.check_data(F, &data)?,
    }
    let d = &mut *data;
    if d.q.len() != core.model.nq() {
        return Err(value_error(
            F,
            "no q given and none used before with this data",
        ));
    }
    let j = mb::compute_joint_jacobians(&core.model, &mut d.inner, &d.q)
        .map_err(|e| value_error(F, e))?;
    Ok(six_by_nv(py, core, j))
}

/// World poses of the named frames, `oMf = oMi iMf`, from the joint placements of the last
/// forward kinematics (Pinocchio's `updateFramePlacements`); then `data.placement(frame)`.
#[pyfunction]
pub fn update_frame_placements(
    model: PyRef<'_, Model>,
    mut data: PyRefMut<'_, Data>,
) -> PyResult<()> {
    model.inner.check_data("update_frame_placements", &data)?;
    mb::update_frame_placements(&model.inner.model, &mut data.inner);
    Ok(())
}

/// Forward kinematics at `q`, then the frames' placements (Pinocchio's
/// `framesForwardKinematics`).
#[pyfunction]
pub fn frames_forward_kinematics(
    model: PyRef<'_, Model>,
    mut data: PyRefMut<'_, Data>,
    q: &Bound<'_, PyAny>,
) -> PyResult<()> {
    const F: &str = "frames_forward_kinematics";
    crate::dynamics::load(F, &model, &mut data, q, &[])?;
    let d = &mut *data;
    let m = &model.inner.model;
    mb::forward_kinematics_q(m, &mut d.inner, &d.q).map_err(|e| value_error(F, e))?;
    mb::update_frame_placements(m, &mut d.inner);
    Ok(())
}

/// The Jacobian of the centre of mass of the moving bodies, `ċ = J_c v` (3 x nv, world frame;
/// Pinocchio's `jacobianCenterOfMass`); also the subtrees' centres of mass.
#[pyfunction]
pub fn com_jacobian<'py>(
    py: Python<'py>,
    model: PyRef<'py, Model>,
    mut data: PyRefMut<'py, Data>,
    q: &Bound<'py, PyAny>,
) -> PyResult<Array2<'py>> {
    const F: &str = "com_jacobian";
    refuse_mujoco(F, &model.inner)?;
    crate::dynamics::load(F, &model, &mut data, q, &[])?;
    let d = &mut *data;
    let j = mb::jacobian_center_of_mass(&model.inner.model, &mut d.inner, &d.q)
        .map_err(|e| value_error(F, e))?;
    Ok(three_by_nv(py, &model.inner, j))
}

/// The centroidal momentum matrix `A_G` (6 x nv) with `h_G = A_G v`, about the centre of mass in
/// world axes: rows `(L_G, p)` (angular, linear momentum) in rigid's layout, `(p, L_G)` in
/// Pinocchio's (Pinocchio's `ccrba`, which also fills `hg` and `Ig`).
#[pyfunction]
pub fn centroidal_momentum_matrix<'py>(
    py: Python<'py>,
    model: PyRef<'py, Model>,
    mut data: PyRefMut<'py, Data>,
    q: &Bound<'py, PyAny>,
    v: &Bound<'py, PyAny>,
) -> PyResult<Array2<'py>> {
    const F: &str = "centroidal_momentum_matrix";
    refuse_mujoco(F, &model.inner)?;
    crate::dynamics::load(F, &model, &mut data, q, &[("v", v)])?;
    let d = &mut *data;
    let ag = mb::centroidal_momentum_matrix(&model.inner.model, &mut d.inner, &d.q, &d.v)
        .map_err(|e| value_error(F, e))?;
    Ok(six_by_nv(py, &model.inner, ag))
}

/// The centroidal momentum `h_G` (6,): `(L_G, p)` in rigid's layout, `(p, L_G)` in Pinocchio's
/// (Pinocchio's `computeCentroidalMomentum`, `data.hg`).
#[pyfunction]
pub fn centroidal_momentum<'py>(
    py: Python<'py>,
    model: PyRef<'py, Model>,
    mut data: PyRefMut<'py, Data>,
    q: &Bound<'py, PyAny>,
    v: &Bound<'py, PyAny>,
) -> PyResult<Array1<'py>> {
    const F: &str = "centroidal_momentum";
    refuse_mujoco(F, &model.inner)?;
    crate::dynamics::load(F, &model, &mut data, q, &[("v", v)])?;
    let d = &mut *data;
    let h = mb::centroidal_momentum(&model.inner.model, &mut d.inner, &d.q, &d.v)
        .map_err(|e| value_error(F, e))?;
    Ok(array1(py, &wrench6(&model.inner, &h)))
}

/// The centres of mass of the model and of every subtree at `q` (with `v`: their velocities;
/// with `a` too: their accelerations), world frame; returns the model's (Pinocchio's
/// `centerOfMass(model, data, q[, v[, a]])`; the subtrees' are in `data`).
#[pyfunction]
#[pyo3(signature = (model, data, q, v = None, a = None))]
pub fn _subtree_centers_of_mass<'py>(
    py: Python<'py>,
    model: PyRef<'py, Model>,
    mut data: PyRefMut<'py, Data>,
    q: &Bound<'py, PyAny>,
    v: Option<&Bound<'py, PyAny>>,
    a: Option<&Bound<'py, PyAny>>,
) -> PyResult<Array1<'py>> {
    const F: &str = "centerOfMass";
    refuse_mujoco(F, &model.inner)?;
    let m = &model.inner.model;
    let c = match (v, a) {
        (None, None) => {
            crate::dynamics::load(F, &model, &mut data, q, &[])?;
            let d = &mut *data;
            mb::subtree_centers_of_mass(m, &mut d.inner, &d.q, mb::KinematicLevel::Position)
        }
        (Some(v), None) => {
            crate::dynamics::load(F, &model, &mut data, q, &[("v", v)])?;
            let d = &mut *data;
            mb::subtree_centers_of_mass(
                m,
                &mut d.inner,
                &d.q,
                mb::KinematicLevel::Velocity { v: &d.v },
            )
        }
        (Some(v), Some(a)) => {
            crate::dynamics::load(F, &model, &mut data, q, &[("v", v), ("a", a)])?;
            let d = &mut *data;
            mb::subtree_centers_of_mass(
                m,
                &mut d.inner,
                &d.q,
                mb::KinematicLevel::Acceleration { v: &d.v, a: &d.a },
            )
        }
        (None, Some(_)) => return Err(value_error(F, "a given without v")),
    }
    .map_err(|e| value_error(F, e))?;
    Ok(array1(py, &[c.x, c.y, c.z]))
}

/// The derivatives of the twist `V` and acceleration `A` of a joint's frame or a named frame
/// with respect to `q` (along `q ⊕ δ`), `v` and `a`: `(∂V/∂q, ∂V/∂v, ∂A/∂q, ∂A/∂v, ∂A/∂a)`, each
/// 6 x nv, in `frame` `"body"`, `"spatial"` or `"world_aligned"` (as `jacobian`); rows
/// `(v, ω)` and free-flyer columns linear first in Pinocchio's layout (Pinocchio's
/// `computeForwardKinematicsDerivatives` then `getJointAccelerationDerivatives` /
/// `getFrameAccelerationDerivatives`).
#[pyfunction]
#[pyo3(signature = (model, data, q, v, a, name, frame = None))]
#[allow(clippy::too_many_arguments)]
pub fn kinematics_derivatives<'py>(
    py: Python<'py>,
    model: PyRef<'py, Model>,
    mut data: PyRefMut<'py, Data>,
    q: &Bound<'py, PyAny>,
    v: &Bound<'py, PyAny>,
    a: &Bound<'py, PyAny>,
    name: &Bound<'py, PyAny>,
    frame: Option<&Bound<'py, PyAny>>,
) -> PyResult<(
    Array2<'py>,
    Array2<'py>,
    Array2<'py>,
    Array2<'py>,
    Array2<'py>,
)> {
    const F: &str = "kinematics_derivatives";
    let core = &*model.inner;
    refuse_mujoco(F, core)?;
    let rf = frame.map_or(Ok(ReferenceFrame::Body), reference_frame)?;
    let place = place(core, F, name)?;
    crate::dynamics::load(F, &model, &mut data, q, &[("v", v), ("a", a)])?;
    let d = &mut *data;
    let m = &core.model;
    let r = match place {
        Place::Joint(j) => {
            mb::joint_kinematics_derivatives(m, &mut d.inner, &d.q, &d.v, &d.a, j, rf)
        }
        Place::Frame(f) => {
            mb::frame_kinematics_derivatives(m, &mut d.inner, &d.q, &d.v, &d.a, f, rf)
        }
    }
    .map_err(|e| value_error(F, e))?;
    Ok((
        six_by_nv(py, core, r.velocity_dq),
        six_by_nv(py, core, r.velocity_dv),
        six_by_nv(py, core, r.acceleration_dq),
        six_by_nv(py, core, r.acceleration_dv),
        six_by_nv(py, core, r.acceleration_da),
    ))
}

/// A joint or frame: a name (a joint's first, then the frames'), or `("joint", i)` /
/// `("frame", i)` with rigid's 0-based index.
fn place(core: &ModelCore, func: &str, name: &Bound<'_, PyAny>) -> PyResult<Place> {
    if let Ok(s) = name.cast::<PyString>() {
        return core.lookup(func, &s.to_cow()?);
    }
    let (kind, i): (String, usize) = name.extract().map_err(|_| {
        PyTypeError::new_err(format!(
            "{func}: name must be a joint or frame name (a string), got {}",
            name.get_type()
        ))
    })?;
    let (n, place) = match kind.as_str() {
        "joint" => (core.model.njoints(), Place::Joint(mb::JointId(i))),
        "frame" => (core.model.frames().len(), Place::Frame(mb::FrameId(i))),
        _ => {
            return Err(PyValueError::new_err(format!(
                "{func}: unknown place kind {kind}"
            )))
        }
    };
    if i >= n {
        return Err(PyValueError::new_err(format!(
            "{func}: {kind} index {i} out of range ({n})"
        )));
    }
    Ok(place)
}

/// The Jacobian of a joint or frame from the spatial Jacobian and placements already in `data`
/// (Pinocchio's `getJointJacobian`, `getFrameJacobian`).
#[pyfunction]
pub fn _stored_jacobian<'py>(
    py: Python<'py>,
    model: PyRef<'py, Model>,
    mut data: PyRefMut<'py, Data>,
    name: &Bound<'py, PyAny>,
    frame: &Bound<'py, PyAny>,
) -> PyResult<Array2<'py>> {
    const F: &str = "getJointJacobian";
    let core = &*model.inner;
    core.check_data(F, &data)?;
    let rf = reference_frame(frame)?;
    let m = &core.model;
    let j = match place(core, F, name)? {
        Place::Joint(j) => mb::stored_joint_jacobian(m, &mut data.inner, j, rf),
        Place::Frame(f) => mb::stored_frame_jacobian(m, &mut data.inner, f, rf),
    }
    .map_err(|e| value_error(F, e))?;
    Ok(six_by_nv(py, core, j))
}

/// `q0 ⊕ u (q1 ⊖ q0)`: the configuration a fraction `u` of the way from `q0` to `q1` along the
/// joints' geodesics (Pinocchio's `interpolate`).
#[pyfunction]
pub fn interpolate<'py>(
    py: Python<'py>,
    model: PyRef<'py, Model>,
    q0: &Bound<'py, PyAny>,
    q1: &Bound<'py, PyAny>,
    u: f64,
) -> PyResult<Array1<'py>> {
    const F: &str = "interpolate";
    let core = &*model.inner;
    refuse_mujoco(F, core)?;
    if !u.is_finite() {
        return Err(value_error(F, "u is not finite"));
    }
    let (x0, x1) = (
        vector(q0, F, "q0", "nq", core.nq())?,
        vector(q1, F, "q1", "nq", core.nq())?,
    );
    let (mut r0, mut r1) = (Vec::new(), Vec::new());
    core.q_into(&x0, &mut r0, F, "q0")?;
    core.q_into(&x1, &mut r1, F, "q1")?;
    if let Some(l) = &core.layout {
        l.nearest_angles(&r0, &mut r1);
    }
    let m = &core.model;
    let mut v = vec![0.0; m.nv()];
    mb::difference(m, &r0, &r1, &mut v).map_err(|e| value_error(F, e))?;
    let mut out = vec![0.0; m.nq()];
    mb::integrate(m, &r0, &v, u, &mut out).map_err(|e| value_error(F, e))?;
    if let Some(l) = &core.layout {
        l.integrate_signs(&r0, &v, u, &mut out);
    }
    Ok(core.q_out(py, &out))
}

/// `q` with each quaternion (and, in Pinocchio's layout, each `(cos θ, sin θ)` pair) scaled to
/// unit norm (Pinocchio's `normalize`); other coordinates unchanged.
#[pyfunction]
pub fn normalize<'py>(
    py: Python<'py>,
    model: PyRef<'py, Model>,
    q: &Bound<'py, PyAny>,
) -> PyResult<Array1<'py>> {
    const F: &str = "normalize";
    let core = &*model.inner;
    refuse_mujoco(F, core)?;
    let x = vector(q, F, "q", "nq", core.nq())?;
    let mut out = x.as_slice().to_vec();
    if let Some(i) = out.iter().position(|v| !v.is_finite()) {
        return Err(value_error(F, format!("q[{i}] is not finite")));
    }
    let unit = |s: &mut [f64]| {
        let n = s.iter().map(|x| x * x).sum::<f64>().sqrt();
        if n > 0.0 {
            s.iter_mut().for_each(|x| *x /= n);
        }
    };
    for (i, j) in core.model.joints().iter().enumerate() {
        let (o, coords) = match &core.layout {
            Some(l) => (l.joint_q(i).0, j.kind.pinocchio_coords(j.continuous)),
            None => (j.idx_q, PinocchioCoords::Same),
        };
        match (coords, &j.kind) {
            (PinocchioCoords::CosSin, _) => unit(&mut out[o..o + 2]),
            (PinocchioCoords::Planar, _) => unit(&mut out[o + 2..o + 4]),
            (_, mb::JointType::FreeFlyer) => unit(&mut out[o + 3..o + 7]),
            (_, mb::JointType::Spherical) => unit(&mut out[o..o + 4]),
            _ => {}
        }
    }
    Ok(array1(py, &out))
}

pub(crate) fn transforms<'py>(py: Python<'py>, ts: &[Transform]) -> PyResult<Bound<'py, PyAny>> {
    let mut out = Vec::with_capacity(ts.len() * 16);
    for t in ts {
        let (r, p) = (&t.rotation, &t.translation);
        for i in 0..3 {
            out.extend_from_slice(&[r[(i, 0)], r[(i, 1)], r[(i, 2)], p[i]]);
        }
        out.extend_from_slice(&[0.0, 0.0, 0.0, 1.0]);
    }
    Ok(PyArray1::from_vec(py, out)
        .reshape([ts.len(), 4, 4])?
        .into_any())
}

pub(crate) fn rows6<'py>(py: Python<'py>, rows: Vec<[f64; 6]>) -> PyResult<Bound<'py, PyAny>> {
    let n = rows.len();
    Ok(PyArray1::from_vec(py, rows.concat())
        .reshape([n, 6])?
        .into_any())
}

pub(crate) fn vec3s<'py>(py: Python<'py>, xs: &[Vec3]) -> PyResult<Bound<'py, PyAny>> {
    let flat: Vec<f64> = xs.iter().flat_map(|x| [x.x, x.y, x.z]).collect();
    Ok(PyArray1::from_vec(py, flat)
        .reshape([xs.len(), 3])?
        .into_any())
}

/// Registers this file's functions, and Pinocchio's names of the public ones.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(compute_joint_jacobians, m)?)?;
    m.add_function(wrap_pyfunction!(update_frame_placements, m)?)?;
    m.add_function(wrap_pyfunction!(frames_forward_kinematics, m)?)?;
    m.add_function(wrap_pyfunction!(com_jacobian, m)?)?;
    m.add_function(wrap_pyfunction!(centroidal_momentum_matrix, m)?)?;
    m.add_function(wrap_pyfunction!(centroidal_momentum, m)?)?;
    m.add_function(wrap_pyfunction!(kinematics_derivatives, m)?)?;
    m.add_function(wrap_pyfunction!(interpolate, m)?)?;
    m.add_function(wrap_pyfunction!(normalize, m)?)?;
    m.add_function(wrap_pyfunction!(
        crate::inverse_kinematics::inverse_kinematics,
        m
    )?)?;
    m.add_function(wrap_pyfunction!(_subtree_centers_of_mass, m)?)?;
    m.add_function(wrap_pyfunction!(_stored_jacobian, m)?)?;
    crate::lie::register(m)?;
    m.add_function(wrap_pyfunction!(_model_assign, m)?)?;
    m.add_function(wrap_pyfunction!(_bounds_to_rigid, m)?)?;
    for (alias, name) in [
        ("computeJointJacobians", "compute_joint_jacobians"),
        ("updateFramePlacements", "update_frame_placements"),
        ("framesForwardKinematics", "frames_forward_kinematics"),
        ("ccrba", "centroidal_momentum_matrix"),
    ] {
        m.add(alias, m.getattr(name)?)?;
    }
    Ok(())
}

/// Makes `dst` the model `src` (the Pinocchio layer's model edits: a new serialised form read
/// back, then swapped in). With `keep_id`, `dst` keeps its identity, so that a `Data` made for it
/// still works with it (its sizes are checked by every algorithm).
#[pyfunction]
pub fn _model_assign(mut dst: PyRefMut<'_, Model>, src: PyRef<'_, Model>, keep_id: bool) {
    let s = &*src.inner;
    let mut core = ModelCore::new(s.model.clone(), s.layout.is_some(), s.warnings.clone());
    core.source = s.source.clone();
    core.mujoco = s.mujoco.clone();
    core.qpos0 = s.qpos0.clone();
    if keep_id {
        core.id = dst.inner.id;
    }
    dst.inner = std::sync::Arc::new(core);
}

/// Pinocchio-layout position bounds `(lower, upper)` in rigid's layout (as
/// `random_configuration` reads them): the layer's `lowerPositionLimit` setter.
#[pyfunction]
pub fn _bounds_to_rigid<'py>(
    py: Python<'py>,
    model: PyRef<'py, Model>,
    lower: &Bound<'py, PyAny>,
    upper: &Bound<'py, PyAny>,
) -> PyResult<(Array1<'py>, Array1<'py>)> {
    let core = &*model.inner;
    let lo = bounds_to_rigid(core, lower, "lowerPositionLimit", "lower", -1.0)?;
    let up = bounds_to_rigid(core, upper, "upperPositionLimit", "upper", 1.0)?;
    Ok((array1(py, &lo), array1(py, &up)))
}
