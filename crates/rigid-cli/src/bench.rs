//! `rigid bench MODEL [--floating] [--json]`: how fast is this robot? The median nanoseconds
//! per call of each multibody algorithm over pre-drawn random states, or with `--batch` the
//! states per second of the batch entry points; the timing itself is
//! [`rigid::timing`]'s (method, and the keys shared with Pinocchio's timing program that
//! `bench/compare.py` divides by, in its documentation). This module parses and prints.

use clap::Args;
use rigid::multibody::{Data, Model};
use rigid::timing::{batch_throughput, time_algorithms, States, ALGORITHMS};

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
    /// Report the throughput (states/s) of the batch entry points (RNEA, ABA, CRBA, the RNEA
    /// derivatives) instead: a loop of single calls, then `rigid::multibody::batch` (states side
    /// by side in SIMD lanes, packs spread over threads) on each `--threads` count.
    #[arg(long)]
    batch: bool,
    /// Time only these algorithms (comma separated keys, e.g. `rnea,crba`; with `--batch`, of
    /// `rnea`, `aba`, `crba`, `crba_lower`, `rnea_derivatives`).
    #[arg(long, value_delimiter = ',')]
    only: Vec<String>,
    /// Thread counts for `--batch`, comma separated.
    #[arg(long, value_delimiter = ',', default_value = "1,2")]
    threads: Vec<usize>,
    /// States side by side in the batch's SIMD lanes (2, 4 or 8; default: `RIGID_LANES` when
    /// set, else as many as the CPU's vector unit holds, 8 with AVX-512, 4 with AVX2, else 2). A
    /// width wider than the CPU's runs the same kernels on narrower instructions.
    #[arg(long, requires = "batch")]
    lanes: Option<usize>,
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
    let t = time_algorithms(&model, &mut data, &states, &names, args.repetitions)
        .map_err(|e| e.to_string())?;
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
    let only: Vec<&str> = args.only.iter().map(String::as_str).collect();
    let width = args.lanes;
    if let Some(w) = width.filter(|w| ![2, 4, 8].contains(w)) {
        return Err(format!("--lanes must be 2, 4 or 8, not {w}"));
    }
    let rates = batch_throughput(model, s, &only, &args.threads, width, args.repetitions)
        .map_err(|e| e.to_string())?;
    // `{"rnea": {"loop": states/s, "threads_1": …, "threads_2": …, "threads_2_vs_loop": speed-up,
    // "threads_2_vs_1": speed-up, …}, "aba": …, "crba": …, "crba_lower": …}`
    let first = args.threads.first().copied().unwrap_or(1);
    let mut t = serde_json::Map::new();
    for r in &rates {
        let mut row = serde_json::Map::new();
        row.insert("loop".into(), serde_json::json!(r.single));
        for k in &r.threads {
            let n = k.threads;
            row.insert(format!("threads_{n}"), serde_json::json!(k.rate));
            row.insert(format!("threads_{n}_vs_loop"), serde_json::json!(k.vs_loop));
            row.insert(
                format!("threads_{n}_vs_{first}"),
                serde_json::json!(k.vs_first),
            );
        }
        t.insert(r.name.into(), serde_json::Value::Object(row));
    }
    let t = serde_json::Value::Object(t);
    // states side by side in the vector registers (8 with AVX-512, 4 with AVX2, else 2)
    let lanes = width.unwrap_or_else(|| rigid::multibody::batch::Batch::new(model).lanes());
    if args.json {
        let out = serde_json::json!({
            "model": model.name(),
            "nq": model.nq(),
            "nv": model.nv(),
            "states": s.len(),
            "lanes": lanes,
            "states_per_second": t,
        });
        println!("{out}");
        return Ok(());
    }
    println!(
        "{} (nq {}, nv {}): states per second over {} states, median of {} passes; the batch \
         computes {lanes} states side by side in SIMD lanes",
        model.name(),
        model.nq(),
        model.nv(),
        s.len(),
        args.repetitions.max(1)
    );
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
