//! SE(3) and SO(3) `exp`, `log` and their Jacobians for the Pinocchio layer (`rigid.pinocchio`'s
//! `exp6`, `log6`, `Jexp6`, `Jlog6`, `exp3`, `log3`, `Jexp3`, `Jlog3`), computed by
//! `rigid::spatial` and `rigid::multibody`; twists linear first, as Pinocchio's `Motion`.

use crate::convert::{self, array1, array2, matrix, value_error, vector};
use numpy::PyArray2;
use pyo3::exceptions::PyValueError;
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

/// SE(3) and SO(3) maps for the Pinocchio layer (twists linear first, as Pinocchio's `Motion`):
/// `("exp6", v)` → 4 x 4, `("log6", R, p)` → (6,), `("Jexp6", v)`, `("Jlog6", R, p)` → 6 x 6,
/// `("exp3", w)` → 3 x 3, `("log3", R)` → (3,), `("Jexp3", w)`, `("Jlog3", R)` → 3 x 3.
#[pyfunction]
#[pyo3(signature = (op, x, p = None))]
pub fn _lie<'py>(
    py: Python<'py>,
    op: &str,
    x: &Bound<'py, PyAny>,
    p: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyAny>> {
    let se3 = |x: &Bound<'py, PyAny>, p: Option<&Bound<'py, PyAny>>| -> PyResult<Transform> {
        let r = rotation_in(x, op)?;
        let p = p.ok_or_else(|| PyValueError::new_err(format!("{op}: needs R and p")))?;
        Ok(Transform::new(r, convert::vec3(p, op, "p")?))
    };
    let m3 = |m: &Mat3| array2(py, 3, 3, |r, c| m[(r, c)]).into_any();
    Ok(match op {
        "exp6" => {
            let t = Transform::exp(&twist_in(x, op)?);
            let h = t.to_homogeneous();
            array2(py, 4, 4, |r, c| h[(r, c)]).into_any()
        }
        "log6" => {
            let t = se3(x, p)?.log();
            array1(py, &[t.v.x, t.v.y, t.v.z, t.w.x, t.w.y, t.w.z]).into_any()
        }
        "Jexp6" => mat6_linear_first(py, &mb::se3_right_jacobian(&twist_in(x, op)?)).into_any(),
        "Jlog6" => {
            mat6_linear_first(py, &mb::se3_right_jacobian_inverse(&se3(x, p)?.log())).into_any()
        }
        "exp3" => m3(&so3::exp(&convert::vec3(x, op, "w")?)),
        "log3" => {
            let w = so3::log(&rotation_in(x, op)?);
            array1(py, &[w.x, w.y, w.z]).into_any()
        }
        "Jexp3" => m3(&mb::so3_right_jacobian(&convert::vec3(x, op, "w")?)),
        "Jlog3" => m3(&mb::so3_right_jacobian_inverse(&so3::log(&rotation_in(
            x, op,
        )?))),
        _ => {
            return Err(PyValueError::new_err(format!(
                "_lie: unknown operation {op}"
            )))
        }
    })
}
