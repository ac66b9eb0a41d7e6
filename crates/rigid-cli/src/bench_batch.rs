//! `rigid bench MODEL --batch`: throughput of [`rigid::multibody::batch`] in states per second,
//! for a loop of single calls and for the batch entry points on 1, 2, … threads (each in its
//! own rayon pool), median over the passes.

use nalgebra::DVector;
use rigid::multibody::{aba, batch, crba, rnea, Data, Model, MultibodyError};
use std::time::Instant;

/// Row-major states for the batch entry points.
pub struct Rows {
    n: usize,
    qs: Vec<f64>,
    vs: Vec<f64>,
    as_: Vec<f64>,
}

impl Rows {
    /// Flatten `(q, v, a)` state lists.
    pub fn new(q: &[Vec<f64>], v: &[Vec<f64>], a: &[Vec<f64>]) -> Self {
        Self {
            n: q.len(),
            qs: q.concat(),
            vs: v.concat(),
            as_: a.concat(),
        }
    }
}

/// A batch entry point on row-major states.
type Kernel = fn(&Model, &Rows, &mut [f64]) -> Result<(), MultibodyError>;
/// A loop of single calls with one workspace.
type Single = fn(&Model, &Rows, &mut [f64], &mut Data) -> Result<(), MultibodyError>;

/// `rnea` and `aba` share one shape: `(q, v, x) ↦ nv-vector`.
type QvxFn = for<'a> fn(
    &Model,
    &'a mut Data,
    &[f64],
    &[f64],
    &[f64],
) -> Result<&'a DVector<f64>, MultibodyError>;

/// A loop of single calls of `f` over the states, the third input taken from `r.as_`.
fn loop_qvx(
    f: QvxFn,
    m: &Model,
    r: &Rows,
    out: &mut [f64],
    d: &mut Data,
) -> Result<(), MultibodyError> {
    let (nq, nv) = (m.nq(), m.nv());
    for k in 0..r.n {
        let t = f(
            m,
            d,
            &r.qs[k * nq..][..nq],
            &r.vs[k * nv..][..nv],
            &r.as_[k * nv..][..nv],
        )?;
        out[k * nv..][..nv].copy_from_slice(t.as_slice());
    }
    Ok(())
}

fn loop_rnea(m: &Model, r: &Rows, out: &mut [f64], d: &mut Data) -> Result<(), MultibodyError> {
    loop_qvx(rnea, m, r, out, d)
}

fn loop_aba(m: &Model, r: &Rows, out: &mut [f64], d: &mut Data) -> Result<(), MultibodyError> {
    loop_qvx(aba, m, r, out, d)
}

fn loop_crba(m: &Model, r: &Rows, out: &mut [f64], d: &mut Data) -> Result<(), MultibodyError> {
    let (nq, nn) = (m.nq(), m.nv() * m.nv());
    for k in 0..r.n {
        let t = crba(m, d, &r.qs[k * nq..][..nq])?;
        out[k * nn..][..nn].copy_from_slice(t.as_slice());
    }
    Ok(())
}

/// Median wall time (s) of `reps` runs of `f` (after one warm-up run).
fn median_secs(
    reps: usize,
    mut f: impl FnMut() -> Result<(), MultibodyError>,
) -> Result<f64, String> {
    f().map_err(|e| e.to_string())?;
    let mut t = Vec::with_capacity(reps.max(1));
    for _ in 0..reps.max(1) {
        let s = Instant::now();
        f().map_err(|e| e.to_string())?;
        t.push(s.elapsed().as_secs_f64());
    }
    t.sort_by(f64::total_cmp);
    Ok(t[t.len() / 2])
}

/// `{"rnea": {"loop": states/s, "threads_1": …, "threads_2": …}, "aba": …, "crba": …}`.
///
/// # Errors
/// An algorithm error, or a thread pool that cannot be built.
pub fn throughput(
    model: &Model,
    rows: &Rows,
    threads: &[usize],
    reps: usize,
) -> Result<serde_json::Value, String> {
    let nv = model.nv();
    let kernels: [(&str, usize, Kernel, Single); 3] = [
        (
            "rnea",
            nv,
            |m, r, o| batch::rnea_batch(m, &r.qs, &r.vs, &r.as_, o),
            loop_rnea,
        ),
        (
            "aba",
            nv,
            |m, r, o| batch::aba_batch(m, &r.qs, &r.vs, &r.as_, o),
            loop_aba,
        ),
        (
            "crba",
            nv * nv,
            |m, r, o| batch::crba_batch(m, &r.qs, o),
            loop_crba,
        ),
    ];
    let mut out = serde_json::Map::new();
    for (name, per, par, single) in kernels {
        let mut buf = vec![0.0; rows.n * per];
        let mut data = Data::new(model);
        let mut row = serde_json::Map::new();
        let t = median_secs(reps, || single(model, rows, &mut buf, &mut data))?;
        row.insert("loop".into(), serde_json::json!(rows.n as f64 / t));
        for &k in threads {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(k)
                .build()
                .map_err(|e| e.to_string())?;
            let t = pool.install(|| median_secs(reps, || par(model, rows, &mut buf)))?;
            row.insert(format!("threads_{k}"), serde_json::json!(rows.n as f64 / t));
        }
        out.insert(name.into(), serde_json::Value::Object(row));
    }
    Ok(serde_json::Value::Object(out))
}
