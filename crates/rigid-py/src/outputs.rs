//! The batch verbs' fresh output arrays, from a cache of the arrays they returned before.
//!
//! A large array that numpy frees goes back to the kernel; on a virtual machine whose balloon
//! device reports free pages (virtio-balloon `VIRTIO_BALLOON_F_REPORTING`), the guest gives it
//! to the host a few seconds later, and the first touch of the next fresh array then faults on
//! the host too: for `rnea_batch` on 10⁵ TALOS states, 629 ns/state with a new array after a
//! pause against 304 with `out=` (BENCHMARKS.md, `bench/first_touch.py`). So the verbs keep the
//! arrays they made, up to a limit in bytes, and make a fresh output from the most recent one
//! of the same length that no Python object refers to any more: a loop of calls that drops each
//! result before the next call touches no new memory, as with `out=`.
//! `rigid.set_output_cache(max_bytes)` sets the limit; it starts at 0 (no cache: every fresh
//! output is a new array), since the reuse has a risk the caller must accept (below).
//!
//! **The risk.** "Nothing refers to it" is read from the reference count. A raw pointer to the
//! data taken through `__array_interface__`, the buffer protocol released early, ctypes or a C
//! extension that keeps the address without a reference is invisible to it: the array is made
//! again by the next call and what the pointer reads changes under it. Opt in only where
//! results are read through numpy objects.
//!
//! An output is a reshaped view of a flat array the cache holds; numpy makes every view of a
//! result (a row, a slice, a memoryview) refer to that flat array, so its reference count is 1
//! exactly when only the cache refers to it. Every batch kernel writes every entry of its
//! output (the Rust tests fill the outputs with NaN first, and so does `test_batch.py` with a
//! result before it is made again), so a reused array shows nothing of its last result.
//!
//! The lock is held only for Rust work on the list: numpy's allocation (which releases the GIL)
//! and letting arrays go (whose deallocation may run Python code) happen after it is released.

use numpy::ndarray::{Dimension, IntoDimension};
use numpy::npyffi::{_PyArray_GET_ITEM_DATA, NPY_ARRAY_WRITEABLE};
use numpy::{PyArray, PyArray1, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::sync::MutexExt;
use std::collections::VecDeque;
use std::sync::{Mutex, MutexGuard};

/// The limit the cache starts with: 0, no cache (the reuse is opt-in; a limit that serves a
/// loop is the output's size, e.g. 512 MiB: 10⁵ states of TALOS with its 50 velocities are 40
/// MB of `rnea_batch`, 10⁴ of `rnea_derivatives_batch` 2 x 200 MB).
const DEFAULT_LIMIT: usize = 0;

/// The arrays the verbs made, oldest first, and the limit on their bytes together.
struct Cache {
    limit: usize,
    arrays: VecDeque<Py<PyArray1<f64>>>,
}

static CACHE: Mutex<Cache> = Mutex::new(Cache {
    limit: DEFAULT_LIMIT,
    arrays: VecDeque::new(),
});

/// The cache, locked without deadlocking with the interpreter (a panic while it was held
/// leaves it consistent: each change to it is one call).
fn cache(py: Python<'_>) -> MutexGuard<'static, Cache> {
    CACHE
        .lock_py_attached(py)
        .unwrap_or_else(|e| e.into_inner())
}

impl Cache {
    /// Takes the oldest arrays out until the rest and `room` more bytes fit the limit, and
    /// returns them, to be let go after the lock is released.
    fn make_room(&mut self, py: Python<'_>, room: usize) -> Vec<Py<PyArray1<f64>>> {
        let bytes = |a: &Py<PyArray1<f64>>| a.bind(py).len() * size_of::<f64>();
        let mut kept: usize = self.arrays.iter().map(bytes).sum();
        let mut out = vec![];
        while kept + room > self.limit {
            let Some(a) = self.arrays.pop_front() else {
                break;
            };
            kept -= bytes(&a);
            out.push(a);
        }
        out
    }
}

/// Whether `a` can be made again: only the cache refers to it, and it is still writeable (a
/// caller could have reached it through a result's `base`).
fn idle(py: Python<'_>, a: &Py<PyArray1<f64>>) -> bool {
    let array = a.bind(py).as_array_ptr();
    // SAFETY: `a` is a live numpy array (the cache holds a reference), read while attached.
    let (count, flags) = unsafe {
        let fields = _PyArray_GET_ITEM_DATA(array);
        (pyo3::ffi::Py_REFCNT(a.as_ptr()), (*fields).flags)
    };
    count == 1 && flags & NPY_ARRAY_WRITEABLE != 0
}

/// A C-contiguous float64 array of `shape` whose entries the caller must all write: the most
/// recent kept array of that length that nothing else refers to, or a new one (numpy's: huge
/// pages for a large one) that the cache keeps when it fits the limit.
pub(crate) fn fresh<'py, D: Dimension>(
    py: Python<'py>,
    shape: impl IntoDimension<Dim = D>,
) -> PyResult<Bound<'py, PyArray<f64, D>>> {
    let shape = shape.into_dimension();
    let len = shape.size();
    let bytes = len * size_of::<f64>();
    let (kept, cached) = {
        let mut c = cache(py);
        let i = c
            .arrays
            .iter()
            .rposition(|a| idle(py, a) && a.bind(py).len() == len);
        let kept = i.and_then(|i| c.arrays.remove(i));
        if let Some(a) = &kept {
            c.arrays.push_back(a.clone_ref(py));
        }
        (kept, len > 0 && bytes <= c.limit)
    };
    let flat = match kept {
        Some(a) => a.into_bound(py),
        None if cached => {
            let a = PyArray1::<f64>::zeros(py, len, false);
            let gone = {
                let mut c = cache(py);
                let gone = c.make_room(py, bytes);
                c.arrays.push_back(a.clone().unbind());
                gone
            };
            drop(gone);
            a
        }
        None => return Ok(PyArray::zeros(py, shape, false)),
    };
    flat.reshape(shape)
}

/// The most bytes of output arrays the batch verbs keep for their next fresh outputs
/// (default 0: none; setting 0 lets the kept arrays go). Returns the previous limit.
///
/// A fresh output is made from a kept array of the same size that no Python object refers to
/// any more, so a loop that drops each result before the next call touches no new memory (on a
/// virtual machine that gives freed memory back to its host, a first touch can cost more than
/// the batch). Arrays still in use count against the limit until they are let go.
///
/// Opt in only where results are read through numpy objects: a raw pointer to a result's data
/// (`__array_interface__`, ctypes, a C extension) holds no reference, so the next call may
/// overwrite what it points to.
#[pyfunction]
pub fn set_output_cache(py: Python<'_>, max_bytes: i128) -> PyResult<i128> {
    if max_bytes < 0 {
        return Err(PyValueError::new_err(format!(
            "set_output_cache: max_bytes must be 0 or more, got {max_bytes}"
        )));
    }
    let limit = usize::try_from(max_bytes).unwrap_or(usize::MAX);
    let (previous, gone) = {
        let mut c = cache(py);
        let previous = std::mem::replace(&mut c.limit, limit);
        (previous, c.make_room(py, 0))
    };
    drop(gone);
    Ok(previous as i128)
}
