//! Numbers across the boundary: array-likes in (a zero-copy fast path for contiguous float64
//! numpy arrays, a checked conversion for everything else), fresh float64 numpy arrays out, and
//! rigid's errors as Python exceptions.

use numpy::{
    PyArray1, PyArray2, PyArrayDescrMethods, PyArrayMethods, PyReadonlyArray2, PyUntypedArray,
    PyUntypedArrayMethods,
};
use pyo3::exceptions::{PyFileNotFoundError, PyOSError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyString};

/// An input vector: the caller's float64 array itself (no copy), or a converted copy.
pub enum Vector<'py> {
    /// A C-contiguous, aligned, 1-D float64 numpy array.
    Borrowed(Bound<'py, PyArray1<f64>>),
    /// Anything else, converted.
    Owned(Vec<f64>),
}

impl Vector<'_> {
    /// The numbers.
    pub fn as_slice(&self) -> &[f64] {
        match self {
            // SAFETY: the array is aligned and contiguous (checked in `vector`), and it is only
            // read while this thread holds the GIL and runs no Python code, so nothing writes
            // to it meanwhile; every output is a fresh array, so no input aliases an output.
            Self::Borrowed(a) => unsafe { a.as_slice().unwrap_or(&[]) },
            Self::Owned(v) => v,
        }
    }
}

/// An input matrix of `rows × cols`, row-major: a C-contiguous, aligned float64 array (the
/// caller's, or a converted copy), borrowed read-only through rust-numpy's borrow checking, so
/// that its numbers can be read with the GIL released (the batch verbs do) while no Rust code
/// can write them. As with numpy's own functions that release the GIL, Python code in another
/// thread that writes to an input during such a call leaves its result unspecified.
pub struct Matrix<'py> {
    array: PyReadonlyArray2<'py, f64>,
    /// Number of rows.
    pub rows: usize,
}

impl Matrix<'_> {
    /// The numbers, row-major.
    pub fn as_slice(&self) -> &[f64] {
        // contiguous: checked in `matrix`
        self.array.as_slice().unwrap_or(&[])
    }
}

/// `func: name has N entries, expected what = n`.
fn length_error(func: &str, name: &str, what: &str, expected: usize, got: usize) -> PyErr {
    PyValueError::new_err(format!(
        "{func}: {name} has {got} entries, expected {what} = {expected}"
    ))
}

/// `func: name must hold real numbers ...` for a numpy array of another kind.
fn check_real(func: &str, name: &str, a: &Bound<'_, PyUntypedArray>) -> PyResult<()> {
    let dtype = a.dtype();
    if matches!(dtype.kind(), b'f' | b'i' | b'u' | b'b') {
        Ok(())
    } else {
        Err(PyTypeError::new_err(format!(
            "{func}: {name} must hold real numbers (float64), got an array of dtype {}",
            dtype.str()?
        )))
    }
}

/// `numpy.require(x, float64, "CA")`: a C-contiguous, aligned float64 array (copied when `x` is
/// not one; an array unpickled by dask's or Ray's workers may be unaligned).
fn as_float64<'py>(x: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
    let np = x.py().import("numpy")?;
    let f64_ = np.getattr("float64")?;
    np.call_method1("require", (x, f64_, "CA"))
}

fn shape_text(shape: &[usize]) -> String {
    match shape {
        [n] => format!("({n},)"),
        _ => format!(
            "({})",
            shape
                .iter()
                .map(ToString::to_string)
                .collect::<Vec<_>>()
                .join(", ")
        ),
    }
}

/// The argument `name` of `func` as `n` float64 numbers (`what` names `n`, e.g. `nq`). A
/// C-contiguous 1-D float64 array is used in place; any other array of real numbers (also a
/// column or row vector) or sequence of numbers is converted.
///
/// # Errors
/// `TypeError` for something that is not numbers (a string, complex numbers, nested lists);
/// `ValueError` for the wrong length or shape, naming the argument, the expected and the given
/// length.
pub fn vector<'py>(
    x: &Bound<'py, PyAny>,
    func: &str,
    name: &str,
    what: &str,
    n: usize,
) -> PyResult<Vector<'py>> {
    if let Ok(a) = x.cast::<PyArray1<f64>>() {
        if a.is_contiguous() && a.is_aligned() {
            let len = a.len();
            if len != n {
                return Err(length_error(func, name, what, n, len));
            }
            return Ok(Vector::Borrowed(a.clone()));
        }
    }
    let v = vector_slow(x, func, name, what, n)?;
    if v.len() != n {
        return Err(length_error(func, name, what, n, v.len()));
    }
    Ok(Vector::Owned(v))
}

fn vector_slow(
    x: &Bound<'_, PyAny>,
    func: &str,
    name: &str,
    what: &str,
    n: usize,
) -> PyResult<Vec<f64>> {
    if let Ok(a) = x.cast::<PyUntypedArray>() {
        check_real(func, name, a)?;
        let shape = a.shape().to_vec();
        let is_vector = match shape.as_slice() {
            [_] => true,
            [r, c] => *r == 1 || *c == 1,
            _ => false,
        };
        if !is_vector {
            return Err(PyValueError::new_err(format!(
                "{func}: {name} must be a vector of {what} = {n} numbers, got an array of shape {}",
                shape_text(&shape)
            )));
        }
        let flat = x.call_method1("reshape", (-1,))?;
        let a = as_float64(&flat)?;
        let a = a.cast::<PyArray1<f64>>()?;
        return Ok(a.to_vec()?);
    }
    if x.is_instance_of::<PyString>() || x.is_instance_of::<PyBytes>() {
        return Err(PyTypeError::new_err(format!(
            "{func}: {name} must be a sequence of {what} = {n} numbers, got a string"
        )));
    }
    x.extract::<Vec<f64>>().map_err(|e| {
        PyTypeError::new_err(format!(
            "{func}: {name} must be a sequence of {what} = {n} numbers, got {}: {e}",
            x.get_type()
                .name()
                .map_or_else(|_| "?".into(), |s| s.to_string())
        ))
    })
}

/// The argument `name` of `func` as an `N × cols` matrix of float64 numbers (`what` names
/// `cols`), any `N`. A C-contiguous 2-D float64 array is used in place; any other 2-D array-like
/// of real numbers is converted.
///
/// # Errors
/// As [`vector`], for a shape other than `(N, cols)`.
pub fn matrix<'py>(
    x: &Bound<'py, PyAny>,
    func: &str,
    name: &str,
    what: &str,
    cols: usize,
) -> PyResult<Matrix<'py>> {
    let shape_error = |shape: &[usize]| {
        PyValueError::new_err(format!(
            "{func}: {name} must be an array of shape (N, {what} = {cols}), got shape {}",
            shape_text(shape)
        ))
    };
    let fast = match x.cast::<PyArray2<f64>>() {
        Ok(a) if a.is_c_contiguous() && a.is_aligned() => Some(a.clone()),
        _ => None,
    };
    let a = match fast {
        Some(a) => a,
        None => {
            let arr = if let Ok(a) = x.cast::<PyUntypedArray>() {
                check_real(func, name, a)?;
                as_float64(x)?
            } else {
                let np = x.py().import("numpy")?;
                let a = np.call_method1("asarray", (x,)).map_err(|e| {
                    PyTypeError::new_err(format!("{func}: {name} is not an array of numbers: {e}"))
                })?;
                check_real(func, name, a.cast::<PyUntypedArray>()?)?;
                as_float64(&a)?
            };
            let u = arr.cast::<PyUntypedArray>()?;
            if u.ndim() != 2 {
                return Err(shape_error(u.shape()));
            }
            arr.cast_into::<PyArray2<f64>>()?
        }
    };
    let shape = a.shape();
    if shape[1] != cols {
        return Err(shape_error(shape));
    }
    let rows = shape[0];
    let array = a
        .try_readonly()
        .map_err(|e| value_error(func, format!("{name} cannot be read: {e}")))?;
    Ok(Matrix { array, rows })
}

/// A fresh 1-D float64 array.
pub fn array1<'py>(py: Python<'py>, x: &[f64]) -> Bound<'py, PyArray1<f64>> {
    PyArray1::from_slice(py, x)
}

/// A fresh `rows × cols` float64 array with entry `(r, c)` = `f(r, c)`.
pub fn array2<'py>(
    py: Python<'py>,
    rows: usize,
    cols: usize,
    f: impl Fn(usize, usize) -> f64,
) -> Bound<'py, PyArray2<f64>> {
    // SAFETY: a new array, C-contiguous, every entry written below before Python sees it.
    let a = unsafe { PyArray2::<f64>::new(py, [rows, cols], false) };
    // SAFETY: the array was just made here and nothing else refers to it.
    let out = unsafe { a.as_slice_mut() }.unwrap_or(&mut []);
    for r in 0..rows {
        for c in 0..cols {
            out[r * cols + c] = f(r, c);
        }
    }
    a
}

/// A fresh float64 array of `rows` rows of `cols` numbers from a row-major vector.
pub fn rows_array(
    py: Python<'_>,
    data: Vec<f64>,
    rows: usize,
    cols: usize,
) -> PyResult<Bound<'_, PyArray2<f64>>> {
    PyArray1::from_vec(py, data).reshape([rows, cols])
}

/// rigid's `MultibodyError` (and other input errors) as `ValueError: func: message`.
pub fn value_error(func: &str, e: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(format!("{func}: {e}"))
}

/// An I/O error as `FileNotFoundError` (missing file) or `OSError`, with the message.
pub fn io_error(e: &std::io::Error, message: String) -> PyErr {
    match e.kind() {
        std::io::ErrorKind::NotFound => PyFileNotFoundError::new_err(message),
        _ => PyOSError::new_err(message),
    }
}

/// A 3-vector argument.
pub fn vec3(x: &Bound<'_, PyAny>, func: &str, name: &str) -> PyResult<rigid::spatial::Vec3> {
    let v = vector(x, func, name, "3", 3)?;
    let s = v.as_slice();
    if let Some(i) = s.iter().position(|x| !x.is_finite()) {
        return Err(PyValueError::new_err(format!(
            "{func}: {name}[{i}] is not finite"
        )));
    }
    Ok(rigid::spatial::Vec3::new(s[0], s[1], s[2]))
}

/// A 4 × 4 homogeneous matrix (any array-like) as a `Transform`: finite, its last row
/// `(0, 0, 0, 1)`, its rotation checked (to 1e-6).
pub fn pose(x: &Bound<'_, PyAny>, func: &str, name: &str) -> PyResult<rigid::spatial::Transform> {
    let m = matrix(x, func, name, "4", 4).map_err(|e| {
        value_error(
            func,
            format!("{name} must be a 4 x 4 homogeneous matrix ({e})"),
        )
    })?;
    let s = m.as_slice();
    if m.rows != 4 || s[12..15].iter().any(|&v| v != 0.0) || s[15] != 1.0 {
        return Err(value_error(
            func,
            format!("{name} must be a 4 x 4 homogeneous matrix (last row 0, 0, 0, 1)"),
        ));
    }
    if s.iter().any(|v| !v.is_finite()) {
        return Err(value_error(func, format!("{name} has a non-finite entry")));
    }
    let r = rigid::spatial::Mat3::new(s[0], s[1], s[2], s[4], s[5], s[6], s[8], s[9], s[10]);
    rigid::spatial::so3::check(&r, 1e-6).map_err(|e| value_error(func, format!("{name}: {e}")))?;
    Ok(rigid::spatial::Transform::new(
        r,
        rigid::spatial::Vec3::new(s[3], s[7], s[11]),
    ))
}

/// The argument `name` of `func` as `n` finite numbers ([`vector`], NaN and infinities refused).
///
/// # Errors
/// As [`vector`]; `ValueError` naming the argument for a non-finite entry.
pub fn finite_vector(
    x: &Bound<'_, PyAny>,
    func: &str,
    name: &str,
    what: &str,
    n: usize,
) -> PyResult<Vec<f64>> {
    let v = vector(x, func, name, what, n)?.as_slice().to_vec();
    if v.iter().any(|x| !x.is_finite()) {
        return Err(value_error(func, format!("{name} has a non-finite entry")));
    }
    Ok(v)
}
