//! Batch evaluation of many states at once: inverse dynamics, forward dynamics, mass matrices
//! and the derivatives of inverse and forward dynamics for `N` states, each written to a
//! caller-owned, row-major output.
//!
//! RNEA, ABA, CRBA and the RNEA derivatives run `W` states side by side in the lanes of the
//! CPU's vector registers (`W` = 8 with AVX-512, 4 with AVX2, 2 otherwise, chosen at run time;
//! [`Batch::lanes`]): the model's tree is walked once per pack of `W` states, and every scalar
//! of the single-state algorithm becomes a `W`-wide vector (`lanes.rs`, one file per kernel:
//! `rnea.rs`, `crba.rs`, `aba.rs`, `derivatives.rs`). The packs are spread across the cores
//! (rayon). The kernels compute what the single calls do in their order of operations (the
//! single call of ABA is its kernel at one lane), so the results equal [`rnea`](super::rnea),
//! [`aba`](super::aba), [`crba`](super::crba) and [`rnea_derivatives`](super::rnea_derivatives)
//! bit for bit (every joint type; checked on every robot of example-robot-data). The ABA
//! derivatives are single calls, spread across the cores.
//!
//! Inputs are row-major: state `k`'s configuration is `qs[k nq..(k + 1) nq]`, its velocity
//! `vs[k nv..(k + 1) nv]`, and so on. The states are cut into a few contiguous blocks per
//! thread, and each state's result goes to its own slice of the output, in the input order,
//! for any number of threads. Every state is checked as the single calls check it (lengths
//! first, for all; then finite entries and unit quaternions, 64 states at a time, just before
//! they are computed, while their rows are in the cache): on an error, nothing is computed from
//! the bad state, and the rows of other states may have been written or not. Run inside a
//! `rayon::ThreadPool::install` to choose the number of threads. The free functions make their
//! workspaces per call; a [`Batch`] keeps them across calls (nothing allocated per call).
//!
//! ```
//! use rigid::multibody::{batch, puma560, Puma560Options};
//! let model = puma560(Puma560Options::default());
//! let (nq, nv, n) = (model.nq(), model.nv(), 4);
//! let qs = vec![0.1; n * nq];
//! let zeros = vec![0.0; n * nv];
//! let mut tau = vec![0.0; n * nv];
//! batch::rnea_batch(&model, &qs, &zeros, &zeros, &mut tau)?;
//! assert!(tau.chunks(nv).all(|t| t == &tau[..nv]));
//! # Ok::<(), rigid::multibody::MultibodyError>(())
//! ```

// The lane kernels and what moves states in and out of them are always compiled: ABA's single
// call runs its kernel at one lane. The threads (`threads.rs`, `calls.rs`) need `parallel`.
mod aba;
#[cfg(feature = "parallel")]
mod calls;
#[cfg_attr(not(feature = "parallel"), allow(dead_code))]
mod crba;
#[cfg_attr(not(feature = "parallel"), allow(dead_code))]
mod derivatives;
#[cfg_attr(not(feature = "parallel"), allow(dead_code))]
mod lanes;
#[cfg_attr(not(feature = "parallel"), allow(dead_code))]
mod pack;
mod pose;
#[cfg_attr(not(feature = "parallel"), allow(dead_code))]
mod rnea;
#[cfg_attr(not(feature = "parallel"), allow(dead_code, unused_imports))]
mod rows;
#[cfg_attr(not(feature = "parallel"), allow(dead_code, unused_imports))]
mod simd;
#[cfg(feature = "parallel")]
mod threads;

pub(crate) use aba::aba_one;
#[cfg(feature = "parallel")]
pub use calls::{
    aba_batch, aba_derivatives_batch, crba_batch, crba_lower_batch, rnea_batch,
    rnea_derivatives_batch,
};
pub(crate) use pack::Pack;
#[cfg(feature = "parallel")]
pub use threads::{pack_lower, Batch};

/// States a task checks and then computes at a time (rounded to whole packs): few enough that
/// their rows are still in the core's cache when the kernel reads them (64 TALOS states hold
/// 77 KiB of `q`, `v`, `a`). Checking a whole task's states first read them twice from memory
/// at 10⁵ states (BENCHMARKS.md, "States beyond the caches").
pub(super) const CHUNK: usize = 64;
