//! The pruned explicit model of the PUMA 560 against the 1986 tables (Armstrong, Khatib &
//! Burdick; notes 000) and against rigid's own numbers.
//!
//! The model is rigid's `puma560` with the paper's rotor inertias as armature (as in
//! `multibody_puma560.rs`), written in the paper's angles `θ2 = q2 + π`, `θ3 = q3 + π` and pruned
//! at tolerance 0.01:
//! - every entry's error (against CRBA and `gravity_torques` for `a_ij` and `g_i`, against the
//!   exact expressions for `b_ijk` and `c_ij`) stays below its printed bound at 10 000 random
//!   states within the joint limits;
//! - the surviving terms of `g2`, `g3`, `a22`, `a23` are those of the 1986 tables
//!   (`g2 = c1 C2 + c2 S23 + c3 S2`, `g3 = c1 S23 + c2 C23`, `a22 = c0 + c1 S3`,
//!   `a23 = c0 + c1 S3 + c2 C3`) and their coefficients are within 1 % of least-squares fits of
//!   rigid's numeric `g` and `M` on those functions (20 000 samples of `q` uniform on the torus,
//!   the fits of `multibody_puma560.rs` with more samples).

use nalgebra::{DMatrix, DVector};
use rigid::explicit::{EntryKind, ExplicitModel, TableOptions, Tables};
use rigid::multibody::*;
use std::f64::consts::PI;

fn puma_paper() -> Model {
    let mut m = puma560(Puma560Options::default());
    m.set_armature(&[1.14, 4.71, 0.83, 0.20, 0.18, 0.19])
        .unwrap();
    m
}

fn pruned(model: &Model) -> (ExplicitModel, Tables) {
    let ex = ExplicitModel::derive(model).unwrap();
    let tables = ex.tables(&TableOptions {
        tolerance: 0.01,
        offsets: vec![0.0, PI, PI, 0.0, 0.0, 0.0],
    });
    (ex, tables)
}

#[test]
fn pruned_entries_stay_within_their_printed_bounds() {
    let model = puma_paper();
    let (ex, tables) = pruned(&model);
    let values = ex.parameters().values();
    let mut data = Data::new(&model);
    let mut rng = Rng::new(1986);
    let entries = &tables.entries;
    let mut worst_ratio = vec![0.0f64; entries.len()];
    for _ in 0..10_000 {
        let q = random_configuration(&model, &mut rng);
        let m = crba(&model, &mut data, &q).unwrap().clone();
        let g = gravity_torques(&model, &mut data, &q).unwrap().clone();
        for (e, ratio) in entries.iter().zip(&mut worst_ratio) {
            let exact = match e.kind {
                EntryKind::Mass(i, j) => m[(i, j)],
                EntryKind::Gravity(i) => g[i],
                EntryKind::Coriolis(i, j, k) => ex.coriolis(i, j, k).eval(&q, &values),
                EntryKind::Centrifugal(i, j) => ex.centrifugal(i, j).eval(&q, &values),
            };
            let err = (tables.eval(e, &q) - exact).abs();
            let slack = 1e-12 * (1.0 + exact.abs());
            assert!(
                err <= e.error_bound + slack,
                "{}: error {err:e} above its bound {:e} at q = {q:?}",
                e.kind.label(),
                e.error_bound
            );
            if e.error_bound > 0.0 {
                *ratio = ratio.max(err / e.error_bound);
            }
        }
    }
    let pruned: Vec<_> = entries.iter().filter(|e| e.dropped > 0).collect();
    let tightest = worst_ratio.iter().copied().fold(0.0, f64::max);
    eprintln!(
        "{} of {} entries pruned ({} terms kept of {}); largest actual error / bound over 10 000 states: {tightest:.2}",
        pruned.len(),
        entries.len(),
        entries.iter().map(|e| e.terms.len()).sum::<usize>(),
        entries.iter().map(|e| e.terms.len() + e.dropped).sum::<usize>(),
    );
    assert!(!pruned.is_empty());
}

/// Least squares `y ≈ Σ_k c_k f_k`.
fn fit(rows: &[Vec<f64>], y: &[f64]) -> Vec<f64> {
    let a = DMatrix::from_fn(rows.len(), rows[0].len(), |i, j| rows[i][j]);
    let b = DVector::from_column_slice(y);
    let x = (a.transpose() * &a)
        .cholesky()
        .unwrap()
        .solve(&(a.transpose() * b));
    x.iter().copied().collect()
}

/// The surviving terms of an entry as `(monomial, coefficient)`.
fn survivors(tables: &Tables, kind: EntryKind) -> Vec<(String, f64)> {
    let e = tables.entry(kind).unwrap();
    e.terms
        .iter()
        .map(|t| {
            let mono = tables.monomial_label(&t.monomial);
            (mono, t.factor * tables.constants[t.constant].value)
        })
        .collect()
}

#[test]
fn pruned_gravity_and_inertia_terms_have_the_structure_and_values_of_the_1986_tables() {
    let model = puma_paper();
    let (_, tables) = pruned(&model);
    let mut data = Data::new(&model);
    let mut rng = Rng::new(7);
    // basis functions in the paper's angles, by monomial label
    let basis: [(EntryKind, &[&str]); 4] = [
        (EntryKind::Gravity(1), &["C2", "S23", "S2"]),
        (EntryKind::Gravity(2), &["S23", "C23"]),
        (EntryKind::Mass(1, 1), &["", "S3"]),
        (EntryKind::Mass(1, 2), &["", "S3", "C3"]),
    ];
    let f = |label: &str, t2: f64, t3: f64| -> f64 {
        match label {
            "" => 1.0,
            "C2" => t2.cos(),
            "S2" => t2.sin(),
            "S3" => t3.sin(),
            "C3" => t3.cos(),
            "S23" => (t2 + t3).sin(),
            "C23" => (t2 + t3).cos(),
            _ => unreachable!(),
        }
    };
    let mut rows: Vec<Vec<Vec<f64>>> = vec![Vec::new(); 4];
    let mut ys: Vec<Vec<f64>> = vec![Vec::new(); 4];
    for _ in 0..20_000 {
        let q: Vec<f64> = (0..6).map(|_| rng.uniform(-PI, PI)).collect();
        let (t2, t3) = (q[1] + PI, q[2] + PI);
        let g = gravity_torques(&model, &mut data, &q).unwrap().clone();
        let m = crba(&model, &mut data, &q).unwrap().clone();
        for (k, (kind, labels)) in basis.iter().enumerate() {
            rows[k].push(labels.iter().map(|l| f(l, t2, t3)).collect());
            ys[k].push(match *kind {
                EntryKind::Gravity(i) => g[i],
                EntryKind::Mass(i, j) => m[(i, j)],
                _ => unreachable!(),
            });
        }
    }
    for (k, (kind, labels)) in basis.iter().enumerate() {
        let got = survivors(&tables, *kind);
        let mut names: Vec<&str> = got.iter().map(|(m, _)| m.as_str()).collect();
        let mut want: Vec<&str> = labels.to_vec();
        names.sort_unstable();
        want.sort_unstable();
        assert_eq!(names, want, "{}: surviving terms {got:?}", kind.label());
        let coefs = fit(&rows[k], &ys[k]);
        for (label, c) in labels.iter().zip(&coefs) {
            let ours = got.iter().find(|(m, _)| m == label).unwrap().1;
            eprintln!(
                "{} {label:>4}: pruned model {ours:+.5}, least squares {c:+.5}",
                kind.label()
            );
            assert!(
                (ours - c).abs() <= 0.01 * c.abs(),
                "{} {label}: {ours} vs fit {c}",
                kind.label()
            );
        }
    }
    // the paper's abbreviated expressions, for the record (Table A7, A4): g2 ≈ -37.2 C2 - 8.4 S23
    // + 1.02 S2; the toolbox's parameters give -37.2, -8.74, 1.02
    let g2 = survivors(&tables, EntryKind::Gravity(1));
    let c2 = g2.iter().find(|(m, _)| m == "C2").unwrap().1;
    assert!((c2 - -37.2).abs() < 0.1, "{c2}");
}

#[test]
fn the_text_tables_print_each_entry_its_approximation_and_bound() {
    let (_, tables) = pruned(&puma_paper());
    let text = tables.to_text();
    assert!(text.contains("θ2 = q2 + π, θ3 = q3 + π"), "{text}");
    let g2 = text
        .lines()
        .skip_while(|l| !l.starts_with("g2 = "))
        .take(2)
        .collect::<Vec<_>>();
    assert!(
        g2[0].contains("·C2") && g2[0].contains("·S23") && g2[0].contains("·S2;"),
        "{g2:?}"
    );
    assert!(
        g2[1].contains("≈ -37.2·C2 - 8.74·S23 + 1.02·S2") && g2[1].contains("|error| ≤"),
        "{g2:?}"
    );
    assert!(text.contains("Table 5. The abbreviated constants"));
    let latex = tables.to_latex();
    assert!(latex.starts_with("\\documentclass") && latex.contains("g_{2} &="));
}
