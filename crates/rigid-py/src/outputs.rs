//! The batch verbs' fresh output arrays, from a cache of the arrays they returned before.
//!
//! A large array that numpy frees goes back to the kernel; on a virtual machine whose balloon
//! device reports free pages (virtio-balloon `VIRTIO_BALLOON_F_REPORTING`), the guest gives it
//! to the host a few seconds later, and the first touch of the next fresh array then faults on
//! the host too: about 0.5 µs per TALOS state of `rnea_batch`, more than the batch itself
//! (BENCHMARKS.md, `bench/first_touch.py`). So the verbs keep the arrays they made, up to a
//! limit in bytes (the most recent first), and make a fresh output from one of the same length
//! that no Python object refers to any more: a loop of calls that drops each result before the
//! next call touches no new memory, as with `out=`. `rigid.set_output_cache(max_bytes)` sets
//! the limit (0: no cache, and the kept arrays are let go).
//!
//! An output is a reshaped view of a flat array the cache holds; every view of a result (a row,
//! a slice, a memoryview) holds that flat array, so its reference count is 1 exactly when only
//! the cache refers to it. Every batch kernel writes every entry of its output (the Rust tests
//! fill the outputs with NaN first), so a reused array shows nothing of its last result.

use numpy::ndarray::Dimension;
use numpy::{PyArray, PyArray1, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use std::collections::VecDeque;
use std::sync::Mutex;

/// The limit the cache starts with: 512 MiB (10⁵ TALOS states of `rnea_batch` are 30 MB, 10⁴
/// of `rnea_derivatives_batch` 2 x 116 MB).
const DEFAULT_LIMIT: usize = 512 << 20;

/// The arrays the verbs made, oldest first, and the limit on their bytes together.
struct Cache {
    limit: usize,
    arrays: VecDeque<Py<PyArray1<f64>>>,
}

static CACHE: Mutex<Cache> = Mutex::new(Cache {
    limit: DEFAULT_LIMIT,
    arrays: VecDeque::new(),
});

/// The cache (a panic while it was held leaves it consistent: every change is one call).
fn cache() -> std::sync::MutexGuard<'static, Cache> {
    CACHE.lock().unwrap_or_else(|e| e.into_inner())
}

impl Cache {
    /// The bytes of the arrays kept.
    fn bytes(&self, py: Python<'_>) -> usize {
        self.arrays
            .iter()
            .map(|a| a.bind(py).len() * size_of::<f64>())
            .sum()
    }

    /// Lets the oldest arrays go until at most `limit - room` bytes are kept.
    fn make_room(&mut self, py: Python<'_>, room: usize) {
        while !self.arrays.is_empty() && self.bytes(py) + room > self.limit {
            self.arrays.pop_front();
        }
    }
}

/// Whether only the cache refers to `a`.
fn idle(a: &Py<PyArray1<f64>>) -> bool {
    // SAFETY: `a` is a live object (the cache holds a reference), read with the GIL held.
    unsafe { pyo3::ffi::Py_REFCNT(a.as_ptr()) == 1 }
}

/// A C-contiguous float64 array of `shape` whose entries the caller must all write: a kept
/// array of that length that nothing else refers to, or a new one (numpy's: huge pages for a
/// large one) that the cache keeps when it fits the limit.
pub(crate) fn fresh<'py, D: Dimension>(
    py: Python<'py>,
    shape: impl numpy::ndarray::IntoDimension<Dim = D>,
) -> PyResult<Bound<'py, PyArray<f64, D>>> {
    let shape = shape.into_dimension();
    let len = shape.size();
    let bytes = len * size_of::<f64>();
    let mut c = cache();
    let flat = match c
        .arrays
        .iter()
        .position(|a| idle(a) && a.bind(py).len() == len)
    {
        Some(i) => {
            let a = c.arrays.remove(i).expect("an index of the cache");
            c.arrays.push_back(a.clone_ref(py));
            a.into_bound(py)
        }
        None if len > 0 && bytes <= c.limit => {
            c.make_room(py, bytes);
            let a = PyArray1::<f64>::zeros(py, len, false);
            c.arrays.push_back(a.clone().unbind());
            a
        }
        None => return Ok(PyArray::zeros(py, shape, false)),
    };
    drop(c);
    flat.reshape(shape)
}

/// The most bytes of output arrays the batch verbs keep for their next fresh outputs
/// (default 512 MiB; 0: none, and the kept arrays are let go). Returns the previous limit.
///
/// A fresh output is made from a kept array of the same size that no Python object refers to
/// any more, so a loop that drops each result before the next call touches no new memory (on a
/// virtual machine that gives freed memory back to its host, a first touch can cost more than
/// the batch). Arrays still in use count against the limit until they are let go.
#[pyfunction]
pub fn set_output_cache(py: Python<'_>, max_bytes: i64) -> PyResult<i64> {
    let limit = usize::try_from(max_bytes).map_err(|_| {
        PyValueError::new_err(format!(
            "set_output_cache: max_bytes must be 0 or more, got {max_bytes}"
        ))
    })?;
    let mut c = cache();
    let previous = std::mem::replace(&mut c.limit, limit);
    c.make_room(py, 0);
    drop(c);
    Ok(i64::try_from(previous).unwrap_or(i64::MAX))
}
