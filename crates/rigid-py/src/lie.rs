//! SE(3) and SO(3) `exp`, `log` and their Jacobians for the Pinocchio layer (`rigid.pinocchio`'s
//! `exp6`, `log6`, `Jexp6`, `Jlog6`, `exp3`, `log3`, `Jexp3`, `Jlog3`), computed by
//! `rigid::spatial` and `rigid::multibody`; twists linear first, as Pinocchio's `Motion`.

use crate::convert::{self, array1, array2, matrix, value_error, vector};
use numpy::PyArray2;
use pyo3::prelude::*;
use rigid::multibody as mb;
use rigid::spatial::{so3, Mat3, Mat6, Transform, Twist, Vec3};

type Array2<'py> = Bound<'py, PyArray2<f64>>;

fn twist_in(x: &Bound<'_, PyAny>, func: &str) -> PyResult<Twist> {
    let v = vector(x, func, "v", "6", 6)?;
    let s = v.as_slice();
    // linear first, as Pinocchio's Motion
    Ok(Twist::new(
        Vec3::new(s[3], s[4], s[5]),
        Vec3::new(s[0], s[1], s[2]),
    ))
}

fn rotation_in(x: &Bound<'_, PyAny>, func: &str) -> PyResult<Mat3> {
    let r = matrix(x, func, "R", "3", 3)?;
    if r.rows != 3 {
        return Err(value_error(func, "R must be 3 x 3"));
    }
    Ok(Mat3::from_row_slice(r.as_slice()))
}

/// A 6 x 6 matrix of rigid's (angular first) in Pinocchio's order (linear first).
fn mat6_linear_first<'py>(py: Python<'py>, m: &Mat6) -> Array2<'py> {
    array2(py, 6, 6, |r, c| m[((r + 3) % 6, (c + 3) % 6)])
}

fn se3_in(r: &Bound<'_, PyAny>, p: &Bound<'_, PyAny>, func: &str) -> PyResult<Transform> {
    Ok(Transform::new(
        rotation_in(r, func)?,
        convert::vec3(p, func, "p")?,
    ))
}

fn m3<'py>(py: Python<'py>, m: &Mat3) -> Array2<'py> {
    array2(py, 3, 3, |r, c| m[(r, c)])
}

/// `exp6(v)`: the 4 x 4 pose `exp(v̂)` of a twist (6,) (linear first).
#[pyfunction]
pub fn _exp6<'py>(py: Python<'py>, v: &Bound<'py, PyAny>) -> PyResult<Array2<'py>> {
    let h = Transform::exp(&twist_in(v, "exp6")?).to_homogeneous();
    Ok(array2(py, 4, 4, |r, c| h[(r, c)]))
}

/// `log6(R, p)`: the twist (6,) (linear first) whose exponential is the pose.
#[pyfunction]
pub fn _log6<'py>(
    py: Python<'py>,
    r: &Bound<'py, PyAny>,
    p: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, numpy::PyArray1<f64>>> {
    let t = se3_in(r, p, "log6")?.log();
    Ok(array1(py, &[t.v.x, t.v.y, t.v.z, t.w.x, t.w.y, t.w.z]))
}

/// `Jexp6(v)`: the right Jacobian of SE(3)'s exponential (6 x 6, linear first).
#[pyfunction]
pub fn _jexp6<'py>(py: Python<'py>, v: &Bound<'py, PyAny>) -> PyResult<Array2<'py>> {
    Ok(mat6_linear_first(
        py,
        &mb::se3_right_jacobian(&twist_in(v, "Jexp6")?),
    ))
}

/// `Jlog6(R, p)`: the inverse right Jacobian at the pose's log (6 x 6, linear first).
#[pyfunction]
pub fn _jlog6<'py>(
    py: Python<'py>,
    r: &Bound<'py, PyAny>,
    p: &Bound<'py, PyAny>,
) -> PyResult<Array2<'py>> {
    let t = se3_in(r, p, "Jlog6")?.log();
    Ok(mat6_linear_first(py, &mb::se3_right_jacobian_inverse(&t)))
}

/// `exp3(w)`: the rotation `exp(ŵ)` (3 x 3).
#[pyfunction]
pub fn _exp3<'py>(py: Python<'py>, w: &Bound<'py, PyAny>) -> PyResult<Array2<'py>> {
    Ok(m3(py, &so3::exp(&convert::vec3(w, "exp3", "w")?)))
}

/// `log3(R)`: the rotation vector (3,).
#[pyfunction]
pub fn _log3<'py>(
    py: Python<'py>,
    r: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, numpy::PyArray1<f64>>> {
    let w = so3::log(&rotation_in(r, "log3")?);
    Ok(array1(py, &[w.x, w.y, w.z]))
}

/// `Jexp3(w)`: the right Jacobian of SO(3)'s exponential (3 x 3).
#[pyfunction]
pub fn _jexp3<'py>(py: Python<'py>, w: &Bound<'py, PyAny>) -> PyResult<Array2<'py>> {
    let w = convert::vec3(w, "Jexp3", "w")?;
    Ok(m3(py, &mb::so3_right_jacobian(&w)))
}

/// `Jlog3(R)`: the inverse right Jacobian at the rotation's log (3 x 3).
#[pyfunction]
pub fn _jlog3<'py>(py: Python<'py>, r: &Bound<'py, PyAny>) -> PyResult<Array2<'py>> {
    let w = so3::log(&rotation_in(r, "Jlog3")?);
    Ok(m3(py, &mb::so3_right_jacobian_inverse(&w)))
}

/// Registers the maps.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(_exp6, m)?)?;
    m.add_function(wrap_pyfunction!(_log6, m)?)?;
    m.add_function(wrap_pyfunction!(_jexp6, m)?)?;
    m.add_function(wrap_pyfunction!(_jlog6, m)?)?;
    m.add_function(wrap_pyfunction!(_exp3, m)?)?;
    m.add_function(wrap_pyfunction!(_log3, m)?)?;
    m.add_function(wrap_pyfunction!(_jexp3, m)?)?;
    m.add_function(wrap_pyfunction!(_jlog3, m)?)?;
    Ok(())
}
