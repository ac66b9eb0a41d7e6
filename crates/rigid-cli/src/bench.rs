//! `rigid bench MODEL [--floating] [--json]`: how fast is this robot? Times each multibody
//! algorithm over pre-drawn random states (so that branch prediction is not flattered), repeated,
//! and reports the median nanoseconds per call.
//!
//! Method: `--states` random states `(q, v, a, τ)` are drawn once (`q` uniform within the joint
//! limits, unit quaternions uniform on SO(3); `v`, `a`, `τ` uniform in `[-1, 1]`); one pass calls
//! the algorithm once per state; the time of a pass divided by the number of states is one
//! sample; the report is the median of `--repetitions` samples, after one warm-up pass; the
//! algorithms take turns pass by pass, as in Pinocchio's timing program. The keys
//! are those of Pinocchio's timing program in `bench/pinocchio/` so that `bench/compare.py` can
//! divide one by the other:
//!
//! | key | rigid call | Pinocchio call |
//! | --- | --- | --- |
//! | `forward_kinematics` | `forward_kinematics_q` (placements) | `forwardKinematics(q)` |
//! | `forward_kinematics_qva` | `forward_kinematics` (placements, V, A) | `forwardKinematics(q, v, a)` |
//! | `jacobians` | `compute_joint_jacobians` | `computeJointJacobians(q)` |
//! | `rnea`, `gravity`, `nonlinear_effects` | `rnea`, `gravity_torques`, `nonlinear_effects` | same |
//! | `crba` | `crba` (full symmetric `M`) | `crba` (upper triangle only) |
//! | `aba` | `aba` | `aba` |
//! | `minverse` | `compute_minverse` (full symmetric `M⁻¹`) | `computeMinverse` (upper triangle only; `bench/pinocchio/timings-aba.cpp` does not symmetrise) |
//! | `cholesky_fd` | `forward_dynamics_cholesky` (nle + CRBA + Cholesky solve) | nle + crba + `cholesky::solve` |
//! | `rnea_derivatives` | `rnea_derivatives` (`∂τ/∂q`, `∂τ/∂v`, full symmetric `M`) | `computeRNEADerivatives` (`M` upper triangle) |
//! | `aba_derivatives` | `aba_derivatives` (`∂q̈/∂q`, `∂q̈/∂v`, full symmetric `M⁻¹`) | `computeABADerivatives` |

use clap::Args;
use rigid::multibody::{
    aba, aba_derivatives, compute_joint_jacobians, compute_minverse, crba,
    forward_dynamics_cholesky, forward_kinematics, forward_kinematics_q, gravity_torques,
    nonlinear_effects, random_configuration, rnea, rnea_derivatives, Data, Model, MultibodyError,
    Rng,
};
use std::hint::black_box;
use std::time::Instant;

/// Arguments of `rigid bench`.
#[derive(Args)]
pub struct BenchArgs {
    /// A URDF file or a built-in model name (`puma560`, …).
    model: String,
    #[command(flatten)]
    load: crate::load::LoadArgs,
    /// Print one JSON object instead of a table.
    #[arg(long)]
    json: bool,
    /// Number of timed passes; the median is reported.
    #[arg(long, default_value_t = 21)]
    repetitions: usize,
    /// Number of pre-drawn random states per pass.
    #[arg(long, default_value_t = 1000)]
    states: usize,
    /// Seed of the random states.
    #[arg(long, default_value_t = 7)]
    seed: u64,
    /// Report the throughput (states/s) of the batch entry points (RNEA, ABA, CRBA) instead: a
    /// loop of single calls, then `rigid::multibody::batch` on each `--threads` count.
    #[arg(long)]
    batch: bool,
    /// Time only these algorithms (comma separated keys, e.g. `rnea,crba`).
    #[arg(long, value_delimiter = ',')]
    only: Vec<String>,
    /// Thread counts for `--batch`, comma separated.
    #[arg(long, value_delimiter = ',', default_value = "1,2")]
    threads: Vec<usize>,
}

/// The algorithms timed, in output order (the JSON keys).
pub const ALGORITHMS: [&str; 12] = [
    "forward_kinematics",
    "forward_kinematics_qva",
    "jacobians",
    "rnea",
    "gravity",
    "nonlinear_effects",
    "crba",
    "aba",
    "minverse",
    "cholesky_fd",
    "rnea_derivatives",
    "aba_derivatives",
];

/// Pre-drawn random states, one `Vec` per state.
pub struct States {
    q: Vec<Vec<f64>>,
    v: Vec<Vec<f64>>,
    a: Vec<Vec<f64>>,
    tau: Vec<Vec<f64>>,
}

impl States {
    /// `n` random states of `model`.
    pub fn new(model: &Model, n: usize, seed: u64) -> Self {
        let mut rng = Rng::new(seed);
        let vec = |rng: &mut Rng| -> Vec<f64> {
            (0..model.nv()).map(|_| rng.uniform(-1.0, 1.0)).collect()
        };
        let (mut q, mut v, mut a, mut tau) = (vec![], vec![], vec![], vec![]);
        for _ in 0..n {
            q.push(random_configuration(model, &mut rng));
            v.push(vec(&mut rng));
            a.push(vec(&mut rng));
            tau.push(vec(&mut rng));
        }
        Self { q, v, a, tau }
    }
}

/// One call of an algorithm on state `i`, returning one entry of its result (kept alive with
/// `black_box` so that nothing is optimised away).
type Call = fn(&Model, &mut Data, &States, usize) -> Result<f64, MultibodyError>;

/// The call timed under each key of [`ALGORITHMS`].
fn call_of(name: &str) -> Option<Call> {
    let f: Call = match name {
        "forward_kinematics" => |m, d, s, i| forward_kinematics_q(m, d, &s.q[i]).map(|()| 0.0),
        "forward_kinematics_qva" => {
            |m, d, s, i| forward_kinematics(m, d, &s.q[i], &s.v[i], &s.a[i]).map(|()| 0.0)
        }
        "jacobians" => |m, d, s, i| compute_joint_jacobians(m, d, &s.q[i]).map(|j| j[0]),
        "rnea" => |m, d, s, i| rnea(m, d, &s.q[i], &s.v[i], &s.a[i]).map(|t| t[0]),
        "gravity" => |m, d, s, i| gravity_torques(m, d, &s.q[i]).map(|t| t[0]),
        "nonlinear_effects" => |m, d, s, i| nonlinear_effects(m, d, &s.q[i], &s.v[i]).map(|t| t[0]),
        "crba" => |m, d, s, i| crba(m, d, &s.q[i]).map(|x| x[0]),
        "aba" => |m, d, s, i| aba(m, d, &s.q[i], &s.v[i], &s.tau[i]).map(|t| t[0]),
        "minverse" => |m, d, s, i| compute_minverse(m, d, &s.q[i]).map(|x| x[0]),
        "cholesky_fd" => {
            |m, d, s, i| forward_dynamics_cholesky(m, d, &s.q[i], &s.v[i], &s.tau[i]).map(|t| t[0])
        }
        "rnea_derivatives" => {
            |m, d, s, i| rnea_derivatives(m, d, &s.q[i], &s.v[i], &s.a[i]).map(|x| x.dtau_dq[0])
        }
        "aba_derivatives" => {
            |m, d, s, i| aba_derivatives(m, d, &s.q[i], &s.v[i], &s.tau[i]).map(|x| x.dqdd_dq[0])
        }
        _ => return None,
    };
    Some(f)
}

/// Mean ns per call of one pass of `f` through every state.
fn pass(model: &Model, data: &mut Data, s: &States, name: &str, f: Call) -> Result<f64, String> {
    let n = s.q.len();
    let t = Instant::now();
    for i in 0..n {
        black_box(f(model, data, s, i).map_err(|e| format!("{name}: {e}"))?);
    }
    Ok(t.elapsed().as_nanos() as f64 / n.max(1) as f64)
}

/// Median ns per call of each algorithm in `names` over `reps` passes through `states`: one
/// warm-up pass each, then the algorithms take turns pass by pass (as Pinocchio's timing program
/// does), so that a slow spell of a shared machine hits all of them alike.
///
/// # Errors
/// An unknown key, or an algorithm error (e.g. a singular mass matrix).
pub fn time_algorithms(
    model: &Model,
    data: &mut Data,
    s: &States,
    names: &[&str],
    reps: usize,
) -> Result<Vec<f64>, String> {
    let calls = names
        .iter()
        .map(|n| call_of(n).ok_or_else(|| format!("unknown algorithm {n}")))
        .collect::<Result<Vec<_>, _>>()?;
    for (name, f) in names.iter().zip(&calls) {
        pass(model, data, s, name, *f)?;
    }
    let mut samples = vec![Vec::with_capacity(reps.max(1)); names.len()];
    for _ in 0..reps.max(1) {
        for ((name, f), x) in names.iter().zip(&calls).zip(&mut samples) {
            x.push(pass(model, data, s, name, *f)?);
        }
    }
    Ok(samples
        .into_iter()
        .map(|mut x| {
            x.sort_by(f64::total_cmp);
            x[x.len() / 2]
        })
        .collect())
}

/// Run `rigid bench`.
///
/// # Errors
/// An unknown model, or an algorithm error.
pub fn run(args: &BenchArgs) -> Result<(), String> {
    let model = crate::load::load_model(&args.model, &args.load)?;
    let states = States::new(&model, args.states.max(1), args.seed);
    if args.batch {
        return run_batch(args, &model, &states);
    }
    let mut data = Data::new(&model);
    let names: Vec<&str> = ALGORITHMS
        .into_iter()
        .filter(|name| args.only.is_empty() || args.only.iter().any(|o| o == name))
        .collect();
    let t = time_algorithms(&model, &mut data, &states, &names, args.repetitions)?;
    let mut times = serde_json::Map::new();
    for (name, t) in names.iter().zip(t) {
        times.insert((*name).to_string(), serde_json::json!(t));
    }
    if args.json {
        let out = serde_json::json!({
            "model": model.name(),
            "nq": model.nq(),
            "nv": model.nv(),
            "ns_per_call": times,
        });
        println!("{out}");
        return Ok(());
    }
    println!(
        "{} (nq {}, nv {}): median ns per call over {} passes of {} random states",
        model.name(),
        model.nq(),
        model.nv(),
        args.repetitions.max(1),
        args.states.max(1)
    );
    for (name, t) in &times {
        println!("  {name:<24} {:>10.0}", t.as_f64().unwrap_or(f64::NAN));
    }
    Ok(())
}

/// `rigid bench --batch`: states per second of a loop of single calls and of the batch entry
/// points per thread count, and the speed-up over the loop.
fn run_batch(args: &BenchArgs, model: &Model, s: &States) -> Result<(), String> {
    let rows = crate::bench_batch::Rows::new(&s.q, &s.v, &s.a);
    let t = crate::bench_batch::throughput(model, &rows, &args.threads, args.repetitions)?;
    if args.json {
        let out = serde_json::json!({
            "model": model.name(),
            "nq": model.nq(),
            "nv": model.nv(),
            "states": s.q.len(),
            "states_per_second": t,
        });
        println!("{out}");
        return Ok(());
    }
    println!(
        "{} (nq {}, nv {}): states per second over {} states, median of {} passes",
        model.name(),
        model.nq(),
        model.nv(),
        s.q.len(),
        args.repetitions.max(1)
    );
    let first = args.threads.first().copied().unwrap_or(1);
    let f = |row: &serde_json::Value, key: String| row[key].as_f64().unwrap_or(f64::NAN);
    for (name, row) in t.as_object().into_iter().flatten() {
        print!("  {name:<6} loop {:>9.0}", f(row, "loop".into()));
        for k in &args.threads {
            print!(
                "   {k} thread(s) {:>9.0} ({:.2}x loop, {:.2}x {first} thread(s))",
                f(row, format!("threads_{k}")),
                f(row, format!("threads_{k}_vs_loop")),
                f(row, format!("threads_{k}_vs_{first}")),
            );
        }
        println!();
    }
    println!("(speed-ups: median over passes of the ratio of times within a pass)");
    Ok(())
}
