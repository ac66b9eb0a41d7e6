//! Compound bodies: parts posed in the body frame add up as the notes say (Steiner, rotated
//! frames, `G_a = [Ad_{T_ba}]ᵀ G_b [Ad_{T_ba}]`), whichever way their mass is given.

use rigid::io::spec::{parse_spec, SpecError};
use rigid::mass::{
    Compound, CompoundError, Geometry, MassOrDensity, Part, PartError, RotationalInertia, Shape,
    TriMesh,
};
use rigid::spatial::{skew, so3, Mat3, Mat6, Transform, Vec3};
use std::path::Path;

fn part(shape: Shape, mass: MassOrDensity, pose: Transform) -> Part {
    Part {
        name: None,
        geometry: Geometry::Shape(shape),
        mass,
        pose,
    }
}

#[test]
fn rotated_and_translated_part_follows_steiner_and_the_rotated_frame_formula() {
    let s = Shape::Box {
        size: Vec3::new(0.4, 0.2, 0.1),
    };
    let r = so3::from_rpy(0.4, 0.2, -0.7);
    let p = Vec3::new(0.3, -0.1, 0.2);
    let body = Compound::new(vec![part(
        s,
        MassOrDensity::Mass(2.0),
        Transform::new(r, p),
    )]);
    let props = body.mass_properties().unwrap();
    // I_b = R I_p Rᵀ (the part's inertia expressed in body axes), then Steiner to the origin.
    let i_p = Mat3::from_diagonal(&Vec3::new(
        2.0 * (0.04 + 0.01) / 12.0,
        2.0 * (0.16 + 0.01) / 12.0,
        2.0 * (0.16 + 0.04) / 12.0,
    ));
    let i_c = r * i_p * r.transpose();
    let i_o = i_c + (Mat3::identity() * p.norm_squared() - p * p.transpose()) * 2.0;
    assert!((props.com - p).norm() < 1e-15);
    assert!((props.inertia_com.matrix() - i_c).amax() < 1e-15);
    assert!((props.inertia_origin.matrix() - i_o).amax() < 1e-15);
    // Principal moments are the box's, ascending; the axes diagonalise I_c.
    let (l, axes) = (props.principal_moments, props.principal_axes);
    assert!((l - Vec3::new(i_p[(0, 0)], i_p[(1, 1)], i_p[(2, 2)])).norm() < 1e-15);
    assert!((axes.transpose() * i_c * axes - Mat3::from_diagonal(&l)).amax() < 1e-15);
    assert!((axes.determinant() - 1.0).abs() < 1e-12);
}

#[test]
fn spatial_inertia_of_a_compound_is_the_sum_of_adjoint_transformed_part_inertias() {
    let parts = vec![
        part(
            Shape::Cylinder {
                radius: 0.1,
                length: 0.5,
            },
            MassOrDensity::Density(7800.0),
            Transform::new(so3::from_rpy(1.0, 0.0, 0.5), Vec3::new(0.0, 0.2, 0.0)),
        ),
        part(
            Shape::Cone {
                radius: 0.2,
                height: 0.3,
            },
            MassOrDensity::Mass(1.5),
            Transform::new(so3::from_rpy(0.0, -0.3, 2.0), Vec3::new(-0.4, 0.0, 0.1)),
        ),
        part(
            Shape::Point,
            MassOrDensity::Mass(0.25),
            Transform::from_translation(Vec3::new(0.0, 0.0, 1.0)),
        ),
    ];
    let body = Compound::new(parts.clone());
    let g = body
        .mass_properties()
        .unwrap()
        .spatial_inertia_origin
        .matrix();
    // Each part's G_p = diag(I_p, m 1) at its own CoM frame {p}, moved to {b} with T_pb = T_bp⁻¹.
    let mut want = Mat6::zeros();
    for p in &parts {
        let Geometry::Shape(s) = p.geometry else {
            unreachable!()
        };
        let m = match p.mass {
            MassOrDensity::Mass(m) => m,
            MassOrDensity::Density(rho) => rho * s.volume(),
        };
        let mut g_p = Mat6::zeros();
        g_p.fixed_view_mut::<3, 3>(0, 0)
            .copy_from(s.inertia_com(m).matrix());
        g_p.fixed_view_mut::<3, 3>(3, 3)
            .copy_from(&(Mat3::identity() * m));
        let ad = p.pose.inverse().adjoint();
        want += ad.transpose() * g_p * ad;
    }
    assert!((g - want).amax() < 1e-12 * want.amax(), "{g}\n{want}");
    // And the closed form [[I_c + m[c]ᵀ[c], m[c]], [m[c]ᵀ, m 1]].
    let props = body.mass_properties().unwrap();
    let (m, k) = (props.mass, skew(&props.com));
    assert!((g.fixed_view::<3, 3>(0, 3) - k * m).amax() < 1e-12);
    assert!((g.fixed_view::<3, 3>(0, 0) - (props.inertia_com.matrix() - k * k * m)).amax() < 1e-12);
}

#[test]
fn density_gives_mass_density_times_volume() {
    let s = Shape::Sphere { radius: 0.1 };
    let p = part(s, MassOrDensity::Density(1000.0), Transform::identity());
    let m = p.mass().unwrap();
    assert!((m - 1000.0 * 4.0 / 3.0 * std::f64::consts::PI * 1e-3).abs() < 1e-12);
}

#[test]
fn density_on_a_point_or_rod_and_nonpositive_mass_are_part_errors() {
    let point = part(
        Shape::Point,
        MassOrDensity::Density(1.0),
        Transform::identity(),
    );
    let e = Compound::new(vec![point]).mass_properties().unwrap_err();
    assert!(matches!(
        e,
        CompoundError::Part {
            index: 0,
            source: PartError::DensityWithoutVolume { what: "point" }
        }
    ));
    let rod = part(
        Shape::ThinRod { length: 1.0 },
        MassOrDensity::Mass(-1.0),
        Transform::identity(),
    );
    assert!(matches!(
        rod.mass(),
        Err(PartError::BadMass { field: "mass", .. })
    ));
    assert!(matches!(
        Compound::default().mass_properties(),
        Err(CompoundError::NoMass)
    ));
}

#[test]
fn mesh_part_keeps_its_own_off_centre_coordinates() {
    // A unit cube mesh spanning [1, 2] × [0, 1] × [0, 1] in its own frame, posed 1 m up: its
    // CoM in the body frame is (1.5, 0.5, 1.5).
    let v: Vec<Vec3> = (0..8)
        .map(|i| Vec3::new(1.0 + (i & 1) as f64, ((i >> 1) & 1) as f64, (i >> 2) as f64))
        .collect();
    let quads = [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ];
    let tris = quads
        .iter()
        .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
        .collect();
    let mesh = TriMesh::new(v, tris).mass_properties().unwrap();
    let body = Compound::new(vec![Part {
        name: Some("cube".into()),
        geometry: Geometry::Mesh(mesh),
        mass: MassOrDensity::Density(2.0),
        pose: Transform::from_translation(Vec3::new(0.0, 0.0, 1.0)),
    }]);
    let props = body.mass_properties().unwrap();
    assert!((props.mass - 2.0).abs() < 1e-14);
    assert!((props.com - Vec3::new(1.5, 0.5, 1.5)).norm() < 1e-14);
    assert!((props.inertia_com.matrix() - Mat3::identity() * (2.0 * 2.0 / 12.0)).amax() < 1e-14);
}

#[test]
fn hand_given_nonphysical_inertia_is_reported_invalid() {
    // Principal moments 1, 1, 3 violate λ1 + λ2 ≥ λ3: no mass distribution has them.
    let body = Compound::new(vec![Part {
        name: None,
        geometry: Geometry::Inertia(RotationalInertia::diagonal(1.0, 1.0, 3.0)),
        mass: MassOrDensity::Mass(1.0),
        pose: Transform::identity(),
    }]);
    let e = body.mass_properties().unwrap().validity(1e-9).unwrap_err();
    assert!(e.to_string().contains("triangle inequality"), "{e}");
}

#[test]
fn spec_quaternion_is_normalised_within_tolerance_and_equals_the_rpy_rotation() {
    let half = (0.25f64).sin();
    let spec = |rot: &str| {
        format!("[[part]]\nshape = \"box\"\nsize = [0.4, 0.2, 0.1]\nmass = 1\nposition = [1, 2, 3]\n{rot}\n")
    };
    let dir = Path::new(".");
    let a = parse_spec(&spec("rpy = [0, 0, 0.5]"), dir).unwrap();
    let q = format!(
        "quaternion = [0, 0, {}, {}]",
        half * (1.0 + 5e-7),
        (0.25f64).cos() * (1.0 + 5e-7)
    );
    let b = parse_spec(&spec(&q), dir).unwrap();
    let (pa, pb) = (a.mass_properties().unwrap(), b.mass_properties().unwrap());
    assert!((pa.inertia_com.matrix() - pb.inertia_com.matrix()).amax() < 1e-12);
    assert!(so3::check(&b.parts[0].pose.rotation, 1e-14).is_ok());
}

#[test]
fn spec_errors_name_part_field_and_line() {
    let text = "# comment\n[[part]]\nname = \"a\"\nshape = \"sphere\"\nradius = 1\nmass = 1\n\n[[part]]\nname = \"b\"\nshape = \"box\"\nsize = [1, 0, 1]\nmass = 1\n";
    let e = parse_spec(text, Path::new(".")).unwrap_err();
    let SpecError::Part {
        number,
        name,
        line,
        field,
        ..
    } = &e
    else {
        panic!("{e}")
    };
    assert_eq!(
        (*number, name.as_deref(), field.as_str()),
        (2, Some("b"), "size[1]")
    );
    assert_eq!(*line, 11, "{e}"); // the line of `size = ...`
    let msg = e.to_string();
    assert!(
        msg.contains("part 2") && msg.contains("\"b\"") && msg.contains("size[1]"),
        "{msg}"
    );

    // A missing key is reported at its part's [[part]] header.
    let e = parse_spec("\n[[part]]\nshape = \"point\"\n", Path::new(".")).unwrap_err();
    assert!(
        matches!(&e, SpecError::Part { line: 2, field, .. } if field == "mass"),
        "{e}"
    );

    let e = parse_spec("[[part]]\nshape = \"box\"\nsize = [1, 1\n", Path::new(".")).unwrap_err();
    assert!(
        matches!(
            e,
            SpecError::Syntax { line: 3, .. } | SpecError::Syntax { line: 4, .. }
        ),
        "{e}"
    );
}

#[test]
fn a_box_cut_in_two_has_the_inertia_of_the_whole_box() {
    // Two halves 0.2 x 0.3 x 0.1 side by side along x (centres at ±0.1) are one 0.4 x 0.3 x 0.1
    // box: the compound must equal the closed form of the whole.
    let half = Shape::Box {
        size: Vec3::new(0.2, 0.3, 0.1),
    };
    let at = |x: f64| {
        part(
            half,
            MassOrDensity::Density(500.0),
            Transform::from_translation(Vec3::new(x, 0.0, 0.0)),
        )
    };
    let props = Compound::new(vec![at(-0.1), at(0.1)])
        .mass_properties()
        .unwrap();
    let whole = Shape::Box {
        size: Vec3::new(0.4, 0.3, 0.1),
    };
    let m = 500.0 * whole.volume();
    assert!((props.mass - m).abs() < 1e-12 * m);
    assert!(props.com.norm() < 1e-15);
    assert!((props.inertia_com.matrix() - whole.inertia_com(m).matrix()).amax() < 1e-15);
}

#[test]
fn a_cylinder_cut_into_slices_has_the_inertia_of_the_whole_cylinder() {
    // Ten slices of length L/10 stacked along z, each turned about z by a different angle (a
    // cylinder is symmetric about its axis), make the whole cylinder.
    let (r, l, n) = (0.05, 0.6, 10);
    let parts = (0..n)
        .map(|k| {
            let z = -l / 2.0 + l * (k as f64 + 0.5) / n as f64;
            part(
                Shape::Cylinder {
                    radius: r,
                    length: l / n as f64,
                },
                MassOrDensity::Mass(0.3),
                Transform::new(so3::from_rpy(0.0, 0.0, k as f64), Vec3::new(0.0, 0.0, z)),
            )
        })
        .collect();
    let props = Compound::new(parts).mass_properties().unwrap();
    let whole = Shape::Cylinder {
        radius: r,
        length: l,
    }
    .inertia_com(3.0);
    assert!((props.inertia_com.matrix() - whole.matrix()).amax() < 1e-15);
}

mod random {
    use super::*;
    use proptest::prelude::*;

    fn shape() -> impl Strategy<Value = Shape> {
        let d = 0.01..1.0f64;
        prop_oneof![
            (d.clone(), d.clone(), d.clone()).prop_map(|(a, b, c)| Shape::Box {
                size: Vec3::new(a, b, c)
            }),
            (d.clone(), d.clone()).prop_map(|(radius, length)| Shape::Cylinder { radius, length }),
            (d.clone(), d.clone()).prop_map(|(radius, length)| Shape::Capsule { radius, length }),
            (d.clone(), d.clone()).prop_map(|(radius, height)| Shape::Cone { radius, height }),
            (d.clone(), d.clone(), d.clone()).prop_map(|(a, b, c)| Shape::Ellipsoid {
                semi_axes: Vec3::new(a, b, c)
            }),
            d.clone().prop_map(|length| Shape::ThinRod { length }),
            Just(Shape::Point),
        ]
    }

    fn posed_part() -> impl Strategy<Value = Part> {
        (
            shape(),
            0.1..10.0f64,
            prop::array::uniform3(-1.0..1.0f64),
            prop::array::uniform3(-3.2..3.2f64),
        )
            .prop_map(|(s, m, p, rpy)| {
                part(
                    s,
                    MassOrDensity::Mass(m),
                    Transform::new(so3::from_rpy(rpy[0], rpy[1], rpy[2]), Vec3::from(p)),
                )
            })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        #[test]
        fn any_compound_of_real_parts_is_physical_and_its_principal_axes_diagonalise_it(
            parts in prop::collection::vec(posed_part(), 1..6)
        ) {
            let props = Compound::new(parts.clone()).mass_properties().unwrap();
            prop_assert!(props.validity(1e-9).is_ok());
            let (l, r) = (props.principal_moments, props.principal_axes);
            let d = r.transpose() * props.inertia_com.matrix() * r - Mat3::from_diagonal(&l);
            prop_assert!(d.amax() < 1e-12 * l[2].max(1e-12));
            prop_assert!(l[0] <= l[1] && l[1] <= l[2]);
            prop_assert!((r.determinant() - 1.0).abs() < 1e-12);
            // The CoM is the mass-weighted mean of the parts' centres.
            let m: f64 = parts.iter().map(|p| p.mass().unwrap()).sum();
            let c = parts
                .iter()
                .fold(Vec3::zeros(), |acc, p| acc + p.pose.translation * p.mass().unwrap())
                / m;
            prop_assert!((props.com - c).norm() < 1e-12);
            // Steiner: I_origin = I_com + m [c]ᵀ[c].
            let k = skew(&c);
            prop_assert!((props.inertia_origin.matrix() - (props.inertia_com.matrix() - k * k * m)).amax() < 1e-10);
        }
    }
}

#[test]
fn angular_momentum_about_any_point_matches_the_sum_over_point_masses() {
    // L_q = Σ m_i (r_i - q) × ṙ_i with ṙ_i = v + ω × r_i (v: velocity of the frame origin),
    // summed directly; and about the CoM it is I_c ω.
    let pts = [
        (1.0, Vec3::new(0.3, -0.2, 0.5)),
        (2.5, Vec3::new(-0.4, 0.1, 0.0)),
        (0.7, Vec3::new(0.0, 0.9, -0.3)),
    ];
    let body = Compound::new(
        pts.iter()
            .map(|&(m, r)| {
                part(
                    Shape::Point,
                    MassOrDensity::Mass(m),
                    Transform::from_translation(r),
                )
            })
            .collect(),
    );
    let g = body.spatial_inertia().unwrap();
    let tw = rigid::spatial::Twist::new(Vec3::new(0.2, -1.0, 0.4), Vec3::new(1.5, 0.3, -0.8));
    for q in [Vec3::zeros(), Vec3::new(1.0, 2.0, -0.5), g.com()] {
        let want = pts.iter().fold(Vec3::zeros(), |acc, &(m, r)| {
            acc + (r - q).cross(&(tw.v + tw.w.cross(&r))) * m
        });
        let got = g.angular_momentum_about(&tw, &q);
        assert!((got - want).norm() < 1e-12, "q = {q}: {got} vs {want}");
    }
    let l_c = g.angular_momentum_com(&tw);
    assert!((l_c - g.angular_momentum_about(&tw, &g.com())).norm() < 1e-12);
}
