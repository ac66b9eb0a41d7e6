//! The closed-form volume, centroid and inertia of every primitive agree with an independent
//! numerical integration written here.
//!
//! The integration is a midpoint rule over an `n × n` grid of columns covering the shape's
//! bounding box in (x, y); along each column the solid is an interval `[z0, z1]` (every shape
//! here is convex in z), integrated exactly: `∫dz = z1 - z0`, `∫z dz = (z1² - z0²)/2`,
//! `∫z² dz = (z1³ - z0³)/3`. Only the inside test (the interval) is shape-specific; it is written
//! from the shape's geometric definition, not from the code under test. The error comes from the
//! cells cut by the curved rim; with `n = 1500` the measured relative errors (largest entry) are
//! at most `1.7e-5` (cylinder volume) and `7.3e-6` (cylinder inertia), so the tolerance is `1e-4`;
//! a missing term in a formula (the capsule's `3r/8`, the cone's `3/80 h²`) is off by more than
//! `1e-2`. The centroid comes out at the origin to `1e-6` of the size.

use rigid::mass::{Shape, ShapeError};
use rigid::spatial::{Mat3, Vec3};

/// Volume, centroid and unit-density second moment `C = ∫ r rᵀ dV` by column integration.
fn integrate(
    half: (f64, f64),
    n: usize,
    column: impl Fn(f64, f64) -> Option<(f64, f64)>,
) -> (f64, Vec3, Mat3) {
    let (hx, hy) = (2.0 * half.0 / n as f64, 2.0 * half.1 / n as f64);
    let da = hx * hy;
    let (mut v, mut s, mut c) = (0.0, Vec3::zeros(), Mat3::zeros());
    for i in 0..n {
        let x = -half.0 + (i as f64 + 0.5) * hx;
        for j in 0..n {
            let y = -half.1 + (j as f64 + 0.5) * hy;
            let Some((z0, z1)) = column(x, y) else {
                continue;
            };
            let l = z1 - z0;
            let zm = (z1 * z1 - z0 * z0) / 2.0;
            let zz = (z1.powi(3) - z0.powi(3)) / 3.0;
            v += l * da;
            s += Vec3::new(x * l, y * l, zm) * da;
            c += Mat3::new(
                x * x * l,
                x * y * l,
                x * zm,
                x * y * l,
                y * y * l,
                y * zm,
                x * zm,
                y * zm,
                zz,
            ) * da;
        }
    }
    (v, s / v, c)
}

/// Compares the shape's closed forms with the integration; returns (volume error, inertia error),
/// both relative.
fn check(
    shape: Shape,
    half: (f64, f64),
    column: impl Fn(f64, f64) -> Option<(f64, f64)>,
) -> (f64, f64) {
    let m = 2.5;
    let (v, com, c) = integrate(half, 1500, column);
    let scale = half.0.max(half.1);
    assert!(
        com.norm() < 1e-6 * scale,
        "{shape:?}: centroid {com:?} is not at the origin"
    );
    // Inertia about the origin (= centroid) of density m / V: (m / V)(tr(C) 1 - C).
    let i_num = (Mat3::identity() * c.trace() - c) * (m / v);
    let i = *shape.inertia_com(m).matrix();
    let e_v = (v - shape.volume()).abs() / shape.volume();
    let e_i = (i_num - i).amax() / i.amax();
    println!(
        "{}: volume error {e_v:.2e}, inertia error {e_i:.2e}",
        shape.name()
    );
    assert!(e_v < 1e-4, "{shape:?}: volume {v} vs {}", shape.volume());
    assert!(
        e_i < 1e-4,
        "{shape:?}: inertia\n{i_num}\nvs closed form\n{i}"
    );
    (e_v, e_i)
}

#[test]
fn box_closed_form_matches_numerical_integration() {
    let (lx, ly, lz) = (0.3, 0.2, 0.7);
    check(
        Shape::Box {
            size: Vec3::new(lx, ly, lz),
        },
        (lx / 2.0, ly / 2.0),
        |_, _| Some((-lz / 2.0, lz / 2.0)),
    );
}

#[test]
fn cylinder_closed_form_matches_numerical_integration() {
    let (r, l) = (0.15, 0.5);
    check(
        Shape::Cylinder {
            radius: r,
            length: l,
        },
        (r, r),
        |x, y| (x * x + y * y <= r * r).then_some((-l / 2.0, l / 2.0)),
    );
}

#[test]
fn sphere_closed_form_matches_numerical_integration() {
    let r = 0.4;
    check(Shape::Sphere { radius: r }, (r, r), |x, y| {
        let q = r * r - x * x - y * y;
        (q >= 0.0).then(|| (-q.sqrt(), q.sqrt()))
    });
}

#[test]
fn ellipsoid_closed_form_matches_numerical_integration() {
    let (a, b, c) = (0.5, 0.3, 0.2);
    check(
        Shape::Ellipsoid {
            semi_axes: Vec3::new(a, b, c),
        },
        (a, b),
        |x, y| {
            let q = 1.0 - (x / a).powi(2) - (y / b).powi(2);
            (q >= 0.0).then(|| (-c * q.sqrt(), c * q.sqrt()))
        },
    );
}

#[test]
fn capsule_closed_form_matches_numerical_integration() {
    // A cylinder of length l with hemispherical caps: at radius ρ the solid spans
    // |z| ≤ l/2 + sqrt(r² - ρ²).
    let (r, l) = (0.2, 0.3);
    check(
        Shape::Capsule {
            radius: r,
            length: l,
        },
        (r, r),
        |x, y| {
            let q = r * r - x * x - y * y;
            (q >= 0.0).then(|| (-l / 2.0 - q.sqrt(), l / 2.0 + q.sqrt()))
        },
    );
}

#[test]
fn cone_closed_form_matches_numerical_integration_with_origin_at_the_centroid() {
    // Base of radius r in the plane z = -h/4, apex at z = 3h/4: at radius ρ the solid spans
    // -h/4 ≤ z ≤ 3h/4 - h ρ / r. The integration also finds the centroid at the origin.
    let (r, h) = (0.25, 0.6);
    check(
        Shape::Cone {
            radius: r,
            height: h,
        },
        (r, r),
        |x, y| {
            let rho = (x * x + y * y).sqrt();
            (rho <= r).then(|| (-h / 4.0, 0.75 * h - h * rho / r))
        },
    );
}

#[test]
fn thin_rod_closed_form_matches_numerical_integration() {
    let (m, l, n) = (1.5, 0.8, 100_000);
    let dz = l / n as f64;
    let izz_rod: f64 = (0..n)
        .map(|k| (-l / 2.0 + (k as f64 + 0.5) * dz).powi(2) * m / l * dz)
        .sum();
    let i = Shape::ThinRod { length: l }.inertia_com(m);
    let expected = Mat3::from_diagonal(&Vec3::new(izz_rod, izz_rod, 0.0));
    assert!((i.matrix() - expected).amax() < 1e-9 * izz_rod);
    assert_eq!(Shape::ThinRod { length: l }.volume(), 0.0);
}

#[test]
fn point_has_no_volume_and_no_inertia_about_itself() {
    assert_eq!(Shape::Point.volume(), 0.0);
    assert_eq!(*Shape::Point.inertia_com(3.0).matrix(), Mat3::zeros());
    assert!(!Shape::Point.has_volume());
}

#[test]
fn numerical_integration_error_shrinks_with_the_grid() {
    // The check above is meaningful only if the integration converges: halve the cell size and
    // the sphere's inertia error drops.
    let r = 0.4;
    let err = |n| {
        let (v, _, c) = integrate((r, r), n, |x, y| {
            let q = r * r - x * x - y * y;
            (q >= 0.0).then(|| (-q.sqrt(), q.sqrt()))
        });
        let izz = (c[(0, 0)] + c[(1, 1)]) / v;
        (izz - 0.4 * r * r).abs() / (0.4 * r * r)
    };
    let (e1, e2, e3) = (err(100), err(400), err(1600));
    println!("sphere I_zz error: n=100 {e1:.2e}, n=400 {e2:.2e}, n=1600 {e3:.2e}");
    assert!(e2 < e1 && e3 < e2 && e3 < 1e-4);
}

#[test]
fn limiting_cases_agree_sphere_ellipsoid_capsule() {
    let r = 0.3;
    let sphere = Shape::Sphere { radius: r }.inertia_com(2.0);
    let ellipsoid = Shape::Ellipsoid {
        semi_axes: Vec3::repeat(r),
    }
    .inertia_com(2.0);
    let capsule = Shape::Capsule {
        radius: r,
        length: 1e-9,
    }
    .inertia_com(2.0);
    assert!((sphere.matrix() - ellipsoid.matrix()).amax() < 1e-15);
    assert!((sphere.matrix() - capsule.matrix()).amax() < 1e-9);
}

#[test]
fn every_closed_form_inertia_is_physical() {
    let shapes = [
        Shape::Box {
            size: Vec3::new(1.0, 0.01, 0.3),
        },
        Shape::Cylinder {
            radius: 0.01,
            length: 2.0,
        },
        Shape::Sphere { radius: 1.0 },
        Shape::Ellipsoid {
            semi_axes: Vec3::new(1.0, 0.1, 0.01),
        },
        Shape::Capsule {
            radius: 0.1,
            length: 3.0,
        },
        Shape::Cone {
            radius: 1.0,
            height: 0.01,
        },
        Shape::ThinRod { length: 1.0 },
    ];
    for s in shapes {
        s.validate().unwrap();
        s.inertia_com(1.0)
            .validate(1e-12)
            .unwrap_or_else(|e| panic!("{s:?}: {e}"));
    }
}

#[test]
fn invalid_dimensions_are_rejected_naming_the_field() {
    let cases = [
        (
            Shape::Box {
                size: Vec3::new(1.0, -1.0, 1.0),
            },
            "size[1]",
        ),
        (
            Shape::Cylinder {
                radius: 0.0,
                length: 1.0,
            },
            "radius",
        ),
        (
            Shape::Capsule {
                radius: 1.0,
                length: f64::NAN,
            },
            "length",
        ),
        (
            Shape::Cone {
                radius: 1.0,
                height: f64::INFINITY,
            },
            "height",
        ),
        (
            Shape::Ellipsoid {
                semi_axes: Vec3::new(1.0, 1.0, -2.0),
            },
            "semi_axes[2]",
        ),
        (Shape::ThinRod { length: -1.0 }, "length"),
    ];
    for (shape, field) in cases {
        let e: ShapeError = shape.validate().unwrap_err();
        assert_eq!(e.field, field);
        assert!(e.to_string().contains(field));
    }
}
