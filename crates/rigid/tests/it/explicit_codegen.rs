//! The exact explicit model's generated code — Rust (compiled with `rustc`), C (with the system
//! `cc`) and Python (run with `RIGID_PYTHON`, else `python3`) — equals rigid's CRBA,
//! `nonlinear_effects` and `gravity_torques` to 1e-12 (relative, infinity norm per quantity and
//! state) at 1000 random states, for the two pendulums, the PUMA 560, the UR5 and the 7-joint
//! Panda (fingers locked).
//!
//! The UR5 and the Panda come from example-robot-data (the copies under `tests/fixtures/robots/`);
//! the Panda's generated Coriolis terms (26 000 terms) and mass matrix exceed the straight-line
//! limit, so its Rust and C use the table form, which this test therefore covers too.
//!
//! Compiling and running the generated code needs `rustc`, a C compiler and `python3` at test
//! time: that is a live check, run when `RIGID_CROSSCHECK=1` (else each test derives the model
//! and writes the code in the three languages only). Every run checks the Rust code committed for
//! the benchmark (`benches/explicit/`), which cargo compiles into this test binary, against the
//! same reference, and that it is what `rigid explicit` writes today (up to formatting; exactly,
//! after `rustfmt`, in the live run).

use rigid::explicit::{ExplicitModel, Lang, TableOptions};
use rigid::multibody::{crba, gravity_torques, nonlinear_effects, Data, Model};
use std::fmt::Write;
use std::process::Command;

use crate::common::reference::{live, python};
use crate::explicit_support;
use explicit_support::{models, rel, run, scratch, states};

/// The generated Rust of the benchmark, compiled by cargo into this binary.
#[path = "../../benches/explicit/puma560.rs"]
mod puma560_code;
#[path = "../../benches/explicit/ur5.rs"]
mod ur5_code;

const STATES: usize = 1000;
const TOLERANCE: f64 = 1e-12;

const RUST_DRIVER: &str = r#"#[path = "model.rs"]
mod model;
use std::io::{BufRead, Write};
fn main() {
    let mut out = String::new();
    for line in std::io::stdin().lock().lines() {
        let x: Vec<f64> = line.unwrap().split_whitespace().map(|s| s.parse().unwrap()).collect();
        let (mut q, mut v) = ([0.0; model::N], [0.0; model::N]);
        q.copy_from_slice(&x[..model::N]);
        v.copy_from_slice(&x[model::N..]);
        let m = model::mass_matrix(&q);
        let mut all: Vec<f64> = m.iter().flatten().copied().collect();
        all.extend(model::coriolis_centrifugal(&q, &v));
        all.extend(model::gravity(&q));
        let s: Vec<String> = all.iter().map(|x| format!("{x:e}")).collect();
        out.push_str(&s.join(" "));
        out.push('\n');
    }
    std::io::stdout().write_all(out.as_bytes()).unwrap();
}
"#;

const C_DRIVER: &str = r#"#include <stdio.h>
#include "model.c"
int main(void) {
    double q[N], v[N], M[N][N], c[N], g[N];
    for (;;) {
        for (int i = 0; i < N; ++i) if (scanf("%lf", &q[i]) != 1) return 0;
        for (int i = 0; i < N; ++i) if (scanf("%lf", &v[i]) != 1) return 1;
        mass_matrix(q, M);
        coriolis_centrifugal(q, v, c);
        gravity(q, g);
        for (int i = 0; i < N; ++i) for (int j = 0; j < N; ++j) printf("%.17g ", M[i][j]);
        for (int i = 0; i < N; ++i) printf("%.17g ", c[i]);
        for (int i = 0; i < N; ++i) printf("%.17g ", g[i]);
        printf("\n");
    }
}
"#;

const PYTHON_DRIVER: &str = r#"import importlib.util, sys
spec = importlib.util.spec_from_file_location("model", sys.argv[1])
m = importlib.util.module_from_spec(spec)
spec.loader.exec_module(m)
out = []
for line in sys.stdin:
    x = [float(t) for t in line.split()]
    q, v = x[:m.N], x[m.N:]
    vals = [e for row in m.mass_matrix(q) for e in row] + m.coriolis_centrifugal(q, v) + m.gravity(q)
    out.append(" ".join(repr(e) for e in vals))
print("\n".join(out))
"#;

/// Runs the generated code of `lang` on the states; one row of `M, c, g` per state.
fn outputs(name: &str, lang: Lang, code: &str, n: usize, input: &str) -> Vec<Vec<f64>> {
    let dir = scratch(&format!("explicit_{name}_{lang:?}"));
    let text = match lang {
        Lang::Rust => {
            std::fs::write(dir.join("model.rs"), code).unwrap();
            std::fs::write(dir.join("main.rs"), RUST_DRIVER).unwrap();
            let rustc = std::env::var("RUSTC").unwrap_or_else(|_| "rustc".into());
            run(
                Command::new(rustc).current_dir(&dir).args([
                    "--edition",
                    "2021",
                    "-C",
                    "opt-level=1",
                    "-D",
                    "warnings",
                    "main.rs",
                    "-o",
                    "prog",
                ]),
                None,
            );
            run(&mut Command::new(dir.join("prog")), Some(input))
        }
        Lang::C => {
            std::fs::write(dir.join("model.c"), code).unwrap();
            std::fs::write(dir.join("main.c"), format!("#define N {n}\n{C_DRIVER}")).unwrap();
            let cc = std::env::var("CC").unwrap_or_else(|_| "cc".into());
            run(
                Command::new(cc).current_dir(&dir).args([
                    "-std=c99", "-O1", "-Wall", "-Werror", "main.c", "-o", "prog", "-lm",
                ]),
                None,
            );
            run(&mut Command::new(dir.join("prog")), Some(input))
        }
        Lang::Python => {
            std::fs::write(dir.join("model.py"), code).unwrap();
            std::fs::write(dir.join("main.py"), PYTHON_DRIVER).unwrap();
            run(
                Command::new(python())
                    .current_dir(&dir)
                    .args(["main.py", "model.py"]),
                Some(input),
            )
        }
    };
    text.lines()
        .map(|l| l.split_whitespace().map(|x| x.parse().unwrap()).collect())
        .collect()
}

fn check(name: &str, model: &Model) {
    let n = model.nv();
    let explicit = ExplicitModel::derive(model).unwrap();
    let tables = explicit.tables(&TableOptions::default());
    let st = states(model, STATES, 15);
    let mut input = String::new();
    for (q, v) in &st {
        let row: Vec<String> = q.iter().chain(v).map(|x| format!("{x:e}")).collect();
        let _ = writeln!(input, "{}", row.join(" "));
    }
    let mut data = Data::new(model);
    let expected: Vec<(Vec<f64>, Vec<f64>, Vec<f64>)> = st
        .iter()
        .map(|(q, v)| {
            let m = crba(model, &mut data, q).unwrap();
            let m: Vec<f64> = (0..n * n).map(|k| m[(k / n, k % n)]).collect();
            let nle = nonlinear_effects(model, &mut data, q, v)
                .unwrap()
                .as_slice()
                .to_vec();
            let g = gravity_torques(model, &mut data, q)
                .unwrap()
                .as_slice()
                .to_vec();
            (m, nle, g)
        })
        .collect();
    let compile = live(&format!(
        "{name}: compiling and running the generated code (rustc, cc, python3)"
    ));
    for lang in [Lang::Rust, Lang::C, Lang::Python] {
        let code = tables.to_code(lang, &format!("rigid explicit {name}"));
        assert!(code.contains("gravity"), "{name} {lang:?}: {code}");
        if !compile {
            continue;
        }
        let rows = outputs(name, lang, &code, n, &input);
        assert_eq!(rows.len(), STATES, "{name} {lang:?}: one row per state");
        let mut worst = [0.0f64; 3];
        for (row, (m, nle, g)) in rows.iter().zip(&expected) {
            let (mm, rest) = row.split_at(n * n);
            let (c, gg) = rest.split_at(n);
            let c_plus_g: Vec<f64> = c.iter().zip(gg).map(|(a, b)| a + b).collect();
            worst[0] = worst[0].max(rel(mm, m));
            worst[1] = worst[1].max(rel(&c_plus_g, nle));
            worst[2] = worst[2].max(rel(gg, g));
        }
        eprintln!(
            "{name} {lang:?}: worst relative error over {STATES} states: M {:.1e}, nle {:.1e}, g {:.1e}",
            worst[0], worst[1], worst[2]
        );
        assert!(
            worst.iter().all(|&w| w <= TOLERANCE),
            "{name} {lang:?}: {worst:?} > {TOLERANCE}"
        );
    }
}

fn model(name: &str) -> Model {
    models()
        .into_iter()
        .find(|(n, _)| *n == name)
        .expect("known model")
        .1
}

#[test]
fn pendulum_generated_code_equals_crba_nle_gravity() {
    check("pendulum", &model("pendulum"));
}

#[test]
fn double_pendulum_generated_code_equals_crba_nle_gravity() {
    check("double_pendulum", &model("double_pendulum"));
}

#[test]
fn puma560_generated_code_equals_crba_nle_gravity() {
    check("puma560", &model("puma560"));
}

#[test]
fn ur5_generated_code_equals_crba_nle_gravity() {
    check("ur5", &model("ur5"));
}

/// A random tree of five joints on random axes, one of them prismatic (its displacement `q_j`
/// appears in the code), with armature.
#[test]
fn random_tree_with_prismatic_joints_generated_code_equals_crba_nle_gravity() {
    check("random_tree", &explicit_support::random_model(41, 5, true));
}

#[test]
fn panda_generated_code_equals_crba_nle_gravity() {
    let m = model("panda");
    let tables = ExplicitModel::derive(&m)
        .unwrap()
        .tables(&TableOptions::default());
    // the Panda's Coriolis terms are written as tables and loops
    assert!(tables.to_code(Lang::C, "x").contains("COEF["));
    check("panda", &m);
}

/// The generated files of the benchmark (`benches/explicit/`) are what `rigid explicit` writes
/// today, formatted by `rustfmt` (as `cargo fmt --all` leaves them). Without `rustfmt` (the
/// default run) they are compared up to formatting: all whitespace removed, and the commas that
/// `rustfmt` adds before a closing bracket of a list it breaks over lines.
#[test]
fn explicit_bench_files_are_up_to_date() {
    let dir = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("benches/explicit");
    let exact = live("the benchmark's generated files formatted by rustfmt");
    for (name, file, command) in [
        (
            "puma560",
            "puma560.rs",
            "rigid explicit puma560 --lang rust",
        ),
        ("ur5", "ur5.rs", "rigid explicit ur5 --lang rust"),
    ] {
        let code = ExplicitModel::derive(&model(name))
            .unwrap()
            .tables(&TableOptions::default())
            .to_code(Lang::Rust, command);
        let committed = std::fs::read_to_string(dir.join(file)).unwrap_or_default();
        let same = if exact {
            let code = run(
                Command::new("rustfmt").args(["--edition", "2021", "--emit", "stdout"]),
                Some(&code),
            );
            code == committed
        } else {
            unformatted(&code) == unformatted(&committed)
        };
        assert!(
            same,
            "benches/explicit/{file} is out of date: regenerate it with `cargo run --release -p \
             rigid-cli -- {} --out crates/rigid/benches/explicit/{file}`, then `cargo fmt --all`",
            command.trim_start_matches("rigid ")
        );
    }
}

/// `code` without its formatting: no whitespace, no comma before a closing bracket.
fn unformatted(code: &str) -> String {
    let s: String = code.chars().filter(|c| !c.is_whitespace()).collect();
    s.replace(",]", "]").replace(",)", ")").replace(",}", "}")
}

/// The generated Rust committed for the benchmark (`benches/explicit/`, compiled into this test
/// binary by cargo: no `rustc` call at test time) equals rigid's CRBA, `nonlinear_effects` and
/// `gravity_torques` to 1e-12 at 1000 random states, as [`check`] requires of fresh code.
#[test]
fn the_benchmarks_generated_rust_equals_crba_nle_gravity() {
    macro_rules! compare {
        ($name:literal, $code:ident) => {{
            let model = model($name);
            const N: usize = $code::N;
            assert_eq!(model.nv(), N);
            let mut data = Data::new(&model);
            let mut worst = [0.0f64; 3];
            for (q, v) in states(&model, STATES, 15) {
                let (mut qa, mut va) = ([0.0; N], [0.0; N]);
                qa.copy_from_slice(&q);
                va.copy_from_slice(&v);
                let mm: Vec<f64> = $code::mass_matrix(&qa).iter().flatten().copied().collect();
                let c = $code::coriolis_centrifugal(&qa, &va);
                let g = $code::gravity(&qa);
                let m = crba(&model, &mut data, &q).unwrap();
                let m: Vec<f64> = (0..N * N).map(|k| m[(k / N, k % N)]).collect();
                let nle = nonlinear_effects(&model, &mut data, &q, &v)
                    .unwrap()
                    .as_slice()
                    .to_vec();
                let gr = gravity_torques(&model, &mut data, &q)
                    .unwrap()
                    .as_slice()
                    .to_vec();
                let c_plus_g: Vec<f64> = c.iter().zip(&g).map(|(a, b)| a + b).collect();
                worst[0] = worst[0].max(rel(&mm, &m));
                worst[1] = worst[1].max(rel(&c_plus_g, &nle));
                worst[2] = worst[2].max(rel(&g, &gr));
            }
            eprintln!(
                "benches/explicit/{}.rs: worst relative error over {STATES} states: M {:.1e}, \
                 nle {:.1e}, g {:.1e}",
                $name, worst[0], worst[1], worst[2]
            );
            assert!(
                worst.iter().all(|&w| w <= TOLERANCE),
                "{}: {worst:?} > {TOLERANCE}",
                $name
            );
        }};
    }
    compare!("puma560", puma560_code);
    compare!("ur5", ur5_code);
}
