//! Many simulations at once: one per initial state, spread over the cores (rayon).

use super::control::Control;
use super::simulator::check_rows;
use super::{SimulationError, SimulationOptions, Simulator};
use crate::multibody::Model;
use rayon::prelude::*;

/// Simulate `steps` steps from each initial state `(q0s[k], v0s[k])` (row-major, `N × nq` and
/// `N × nv`) and write the final states into `qs` and `vs` (same layout). Each state runs in
/// its own [`Simulator`] with the control law `control(k)`, on the threads of the current rayon
/// pool (use `ThreadPool::install` to choose how many); the results are those of single runs,
/// bit for bit, whatever the number of threads.
///
/// ```
/// use rigid::multibody::builtin;
/// use rigid::simulation::{simulate_batch, Controller, SimulationOptions};
/// let model = builtin("pendulum").unwrap();
/// let q0s = [0.1, 0.2, 0.3];
/// let (mut qs, mut vs) = ([0.0; 3], [0.0; 3]);
/// simulate_batch(&model, &q0s, &[0.0; 3], SimulationOptions::default(), 100,
///                |_| Controller::none(&model), &mut qs, &mut vs)?;
/// assert!(qs.iter().zip(&q0s).all(|(q, q0)| q.abs() < *q0)); // all swing down
/// # Ok::<(), rigid::simulation::SimulationError>(())
/// ```
///
/// # Errors
/// Lengths that are not `N nq` / `N nv`, or the first failing state's error.
#[allow(clippy::too_many_arguments)]
pub fn simulate_batch<C, F>(
    model: &Model,
    q0s: &[f64],
    v0s: &[f64],
    options: SimulationOptions,
    steps: u64,
    control: F,
    qs: &mut [f64],
    vs: &mut [f64],
) -> Result<(), SimulationError>
where
    C: Control,
    F: Fn(usize) -> C + Sync,
{
    let (nq, nv) = (model.nq, model.nv);
    let n = q0s.len().checked_div(nq).unwrap_or(0);
    check_rows("q0s", nq, n, q0s.len())?;
    check_rows("v0s", nv, n, v0s.len())?;
    check_rows("qs", nq, n, qs.len())?;
    check_rows("vs", nv, n, vs.len())?;
    qs.par_chunks_mut(nq.max(1))
        .zip(vs.par_chunks_mut(nv.max(1)))
        .enumerate()
        .try_for_each(|(k, (q, v))| {
            let mut sim = Simulator::new(
                model,
                &q0s[k * nq..(k + 1) * nq],
                &v0s[k * nv..(k + 1) * nv],
                options,
                control(k),
            )?;
            sim.run(steps, |_| {})?;
            q.copy_from_slice(sim.q());
            v.copy_from_slice(sim.v());
            Ok(())
        })
}
