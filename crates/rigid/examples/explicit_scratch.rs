use rigid::explicit::{ExplicitModel, TableOptions};
use rigid::mass::{RotationalInertia, SpatialInertia};
use rigid::multibody::*;
use rigid::spatial::{so3, Transform, Vec3};
use std::time::Instant;
fn main() {
    let n: usize = std::env::args().nth(1).unwrap().parse().unwrap();
    let mut rng = Rng::new(5);
    let mut b = ModelBuilder::new("generic");
    let mut parent = None;
    let unit = |rng: &mut Rng| Vec3::new(rng.normal(), rng.normal(), rng.normal()).normalize();
    for k in 0..n {
        let axis = unit(&mut rng);
        let placement = Transform::new(
            so3::exp(&(unit(&mut rng) * rng.uniform(-2.0, 2.0))),
            Vec3::new(
                rng.uniform(-0.4, 0.4),
                rng.uniform(-0.4, 0.4),
                rng.uniform(-0.4, 0.4),
            ),
        );
        let r = so3::exp(&(unit(&mut rng) * rng.uniform(-3.0, 3.0)));
        let g = SpatialInertia::from_com(
            1.0,
            Vec3::new(0.1, 0.05, -0.1),
            RotationalInertia::diagonal(0.05, 0.06, 0.07).in_rotated_frame(&r),
        );
        parent = Some(
            b.add_joint(
                parent,
                &format!("j{k}"),
                JointType::Revolute { axis },
                placement,
                g,
            )
            .unwrap(),
        );
    }
    let model = b.build().unwrap();
    let t = Instant::now();
    match ExplicitModel::derive(&model) {
        Ok(ex) => {
            println!("derive {:?}", t.elapsed());
            let t = Instant::now();
            let tabs = ex.tables(&TableOptions::default());
            let terms: usize = tabs.entries.iter().map(|e| e.terms.len()).sum();
            println!("tables {:?}, {terms} terms", t.elapsed());
        }
        Err(e) => println!("error after {:?}: {e}", t.elapsed()),
    }
}
