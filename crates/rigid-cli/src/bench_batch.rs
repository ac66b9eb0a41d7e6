//! `rigid bench MODEL --batch`: throughput of [`rigid::multibody::batch`] in states per second,
//! for a loop of single calls and for the batch entry points on 1, 2, … threads (each in its
//! own rayon pool), median over the passes; the configurations take turns pass by pass.

use nalgebra::DVector;
use rigid::error::DimensionError;
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

/// A batch entry point on row-major states, with workspaces made once per thread pool.
type Kernel = fn(&mut batch::Batch, &Model, &Rows, &mut [f64]) -> Result<(), MultibodyError>;
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

/// Single `crba` calls, `write(M column-major, nv, out_k)` with `per` numbers per state: the
/// loop counterpart of `Batch::crba_into`.
fn loop_crba_into(
    m: &Model,
    r: &Rows,
    out: &mut [f64],
    d: &mut Data,
    per: usize,
    write: impl Fn(&[f64], usize, &mut [f64]) -> Result<(), DimensionError>,
) -> Result<(), MultibodyError> {
    let nq = m.nq();
    for k in 0..r.n {
        let t = crba(m, d, &r.qs[k * nq..][..nq])?;
        write(t.as_slice(), m.nv(), &mut out[k * per..][..per])?;
    }
    Ok(())
}

/// The loop counterpart of `crba_lower`: single calls, each matrix's lower triangle packed.
fn loop_crba_lower(
    m: &Model,
    r: &Rows,
    out: &mut [f64],
    d: &mut Data,
) -> Result<(), MultibodyError> {
    let nv = m.nv();
    loop_crba_into(m, r, out, d, nv * (nv + 1) / 2, batch::pack_lower)
}

fn loop_crba(m: &Model, r: &Rows, out: &mut [f64], d: &mut Data) -> Result<(), MultibodyError> {
    loop_crba_into(m, r, out, d, m.nv() * m.nv(), |t, _, out| {
        out.copy_from_slice(t);
        Ok(())
    })
}

/// Wall time (s) of one run of `f`.
fn secs(f: impl FnOnce() -> Result<(), MultibodyError>) -> Result<f64, String> {
    let s = Instant::now();
    f().map_err(|e| e.to_string())?;
    Ok(s.elapsed().as_secs_f64())
}

fn median(mut x: Vec<f64>) -> f64 {
    x.sort_by(f64::total_cmp);
    x[x.len() / 2]
}

/// `{"rnea": {"loop": states/s, "threads_1": …, "threads_2": …, "threads_2_vs_loop": speed-up,
/// "threads_2_vs_1": speed-up, …}, "aba": …, "crba": …, "crba_lower": …}` (`crba_lower`: the packed
/// lower triangles of `Batch::crba_lower`); a speed-up is the median over passes of
/// the ratio of the two configurations' times within the pass.
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
    let kernels: [(&str, usize, Kernel, Single); 4] = [
        (
            "rnea",
            nv,
            |b, m, r, o| b.rnea(m, &r.qs, &r.vs, &r.as_, o),
            loop_rnea,
        ),
        (
            "aba",
            nv,
            |b, m, r, o| b.aba(m, &r.qs, &r.vs, &r.as_, o),
            loop_aba,
        ),
        ("crba", nv * nv, |b, m, r, o| b.crba(m, &r.qs, o), loop_crba),
        (
            "crba_lower",
            nv * (nv + 1) / 2,
            |b, m, r, o| b.crba_lower(m, &r.qs, o),
            loop_crba_lower,
        ),
    ];
    let pools = threads
        .iter()
        .map(|&k| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(k)
                .build()
                .map_err(|e| e.to_string())
        })
        .collect::<Result<Vec<_>, _>>()?;
    let mut out = serde_json::Map::new();
    for (name, per, par, single) in kernels {
        let mut buf = vec![0.0; rows.n * per];
        let mut data = Data::new(model);
        let mut batches: Vec<batch::Batch> = pools
            .iter()
            .map(|p| p.install(|| batch::Batch::new(model)))
            .collect();
        // the loop and every thread count take turns pass by pass, so that a slow spell of a
        // shared machine hits them alike; each turn is an untimed pass then a timed one, so that
        // what is timed is a pool already awake (the steady state of a long batch), not the wake-up
        // of threads that slept through the other configurations' turns
        let mut t = vec![Vec::with_capacity(reps.max(1)); 1 + pools.len()];
        for _ in 0..reps.max(1) {
            single(model, rows, &mut buf, &mut data).map_err(|e| e.to_string())?;
            t[0].push(secs(|| single(model, rows, &mut buf, &mut data))?);
            for ((pool, b), t) in pools.iter().zip(&mut batches).zip(&mut t[1..]) {
                pool.install(|| par(b, model, rows, &mut buf))
                    .map_err(|e| e.to_string())?;
                t.push(pool.install(|| secs(|| par(b, model, rows, &mut buf)))?);
            }
        }
        // speed-ups as the median over passes of the ratio within each pass (the configurations
        // ran back to back), which cancels the slow spells that a ratio of medians keeps
        let ratio = |a: &[f64], b: &[f64]| median(a.iter().zip(b).map(|(a, b)| a / b).collect());
        let mut row = serde_json::Map::new();
        row.insert(
            "loop".into(),
            serde_json::json!(rows.n as f64 / median(t[0].clone())),
        );
        for (c, &k) in threads.iter().enumerate() {
            let tk = &t[c + 1];
            row.insert(
                format!("threads_{k}"),
                serde_json::json!(rows.n as f64 / median(tk.clone())),
            );
            row.insert(
                format!("threads_{k}_vs_loop"),
                serde_json::json!(ratio(&t[0], tk)),
            );
            row.insert(
                format!("threads_{k}_vs_{}", threads[0]),
                serde_json::json!(ratio(&t[1], tk)),
            );
        }
        out.insert(name.into(), serde_json::Value::Object(row));
    }
    Ok(serde_json::Value::Object(out))
}
