use rigid::explicit::ExplicitModel;
use rigid::multibody::*;
use std::time::Instant;
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let mut model = match builtin(&args[1]) {
        Some(m) => m,
        None => rigid::io::urdf::load_urdf(&args[1], false).unwrap(),
    };
    if args.len() > 2 {
        let l: Vec<(String, f64)> = args[2].split(',').map(|s| (s.to_string(), 0.0)).collect();
        model = rigid::explicit::lock_joints(&model, &l).unwrap();
    }
    let t = Instant::now();
    let ex = ExplicitModel::derive(&model).unwrap();
    println!("derive {:?}, {} params", t.elapsed(), ex.parameters().len());
    let n = ex.n();
    let vals = ex.parameters().values();
    let mut tot = 0;
    let mut totg = 0;
    let mut totb = 0;
    for i in 0..n {
        for j in i..n {
            tot += ex.mass(i, j).len();
        }
        totg += ex.gravity(i).len();
        for j in 0..n {
            totb += ex.centrifugal(i, j).len();
            for k in j + 1..n {
                totb += ex.coriolis(i, j, k).len();
            }
        }
    }
    let h = |e: &rigid::explicit::Expr| {
        let mut v: Vec<_> = e.terms().iter().map(|t| (t.freq, t.sin)).collect();
        v.dedup();
        v.len()
    };
    let mut hm = 0;
    let mut hb = 0;
    let mut hg = 0;
    for i in 0..n {
        for j in i..n {
            hm += h(ex.mass(i, j));
        }
        hg += h(ex.gravity(i));
        for j in 0..n {
            hb += h(ex.centrifugal(i, j));
            for k in j + 1..n {
                hb += h(ex.coriolis(i, j, k));
            }
        }
    }
    println!("harmonics: M {hm} g {hg} b+c {hb}");
    println!(
        "terms: M upper {tot}, g {totg}, b+c {totb}; M11 {} M22 {}",
        ex.mass(0, 0).len(),
        ex.mass(1, 1).len()
    );
    let mut d = Data::new(&model);
    let mut rng = Rng::new(3);
    let mut worst = 0.0f64;
    for _ in 0..50 {
        let q = random_configuration(&model, &mut rng);
        let v: Vec<f64> = (0..n).map(|_| rng.uniform(-1.0, 1.0)).collect();
        let m = crba(&model, &mut d, &q).unwrap().clone();
        let g = gravity_torques(&model, &mut d, &q).unwrap().clone();
        let nle = nonlinear_effects(&model, &mut d, &q, &v).unwrap().clone();
        for i in 0..n {
            for j in 0..n {
                worst = worst.max((ex.mass(i, j).eval(&q, &vals) - m[(i, j)]).abs());
            }
            worst = worst.max((ex.gravity(i).eval(&q, &vals) - g[i]).abs());
            let mut c = ex.gravity(i).eval(&q, &vals);
            for j in 0..n {
                c += ex.centrifugal(i, j).eval(&q, &vals) * v[j] * v[j];
                for k in j + 1..n {
                    c += ex.coriolis(i, j, k).eval(&q, &vals) * v[j] * v[k];
                }
            }
            worst = worst.max((c - nle[i]).abs());
        }
    }
    println!("worst abs err {worst:e}");
    let tol: f64 = std::env::var("TOL")
        .ok()
        .map(|s| s.parse().unwrap())
        .unwrap_or(0.0);
    let offsets: Vec<f64> = std::env::var("OFF")
        .ok()
        .map(|s| {
            s.split(',')
                .map(|x| x.parse::<f64>().unwrap() * std::f64::consts::PI)
                .collect()
        })
        .unwrap_or_default();
    let t = Instant::now();
    let tabs = ex.tables(&rigid::explicit::TableOptions {
        tolerance: tol,
        offsets,
    });
    println!(
        "tables {:?}: {} constants, {} vars",
        t.elapsed(),
        tabs.constants.len(),
        tabs.vars.len()
    );
    let mut cm = 0;
    let mut cg = 0;
    let mut cb = 0;
    for e in &tabs.entries {
        match e.kind {
            rigid::explicit::EntryKind::Mass(..) => cm += e.terms.len(),
            rigid::explicit::EntryKind::Gravity(..) => cg += e.terms.len(),
            _ => cb += e.terms.len(),
        }
    }
    println!("table terms: M {cm} g {cg} b+c {cb}");
    let mut worst2 = 0.0f64;
    let mut viol = 0;
    for _ in 0..200 {
        let q = random_configuration(&model, &mut rng);
        for e in &tabs.entries {
            let exact = match e.kind {
                rigid::explicit::EntryKind::Mass(i, j) => ex.mass(i, j),
                rigid::explicit::EntryKind::Coriolis(i, j, k) => ex.coriolis(i, j, k),
                rigid::explicit::EntryKind::Centrifugal(i, j) => ex.centrifugal(i, j),
                rigid::explicit::EntryKind::Gravity(i) => ex.gravity(i),
            }
            .eval(&q, &vals);
            let err = (tabs.eval(e, &q) - exact).abs();
            worst2 = worst2.max(err - e.error_bound);
            if err > e.error_bound + 1e-12 {
                viol += 1;
            }
        }
    }
    println!("table eval: worst (err - bound) {worst2:e}, violations {viol}");
    let names = |k: rigid::explicit::EntryKind| {
        let e = tabs.entry(k).unwrap();
        let mut s = format!("{} =", k.label());
        for t in &e.terms {
            s += &format!(
                " {:+.4}*{}[",
                t.factor * tabs.constants[t.constant].value,
                tabs.constants[t.constant].name
            );
            for (v, (c, sn)) in &t.monomial {
                s += &format!(
                    "{}{}:{}",
                    if *c == 1 { "C" } else { "" },
                    "S".repeat(*sn as usize),
                    tabs.vars[*v].label()
                );
            }
            s += "]";
        }
        s + &format!("  bound {:.3e} dropped {}", e.error_bound, e.dropped)
    };
    use rigid::explicit::EntryKind::*;
    if n >= 3 {
        for k in [Gravity(1), Gravity(2), Mass(1, 1), Mass(1, 2), Mass(0, 0)] {
            println!("{}", names(k));
        }
    }
}
fn _unused() {}
