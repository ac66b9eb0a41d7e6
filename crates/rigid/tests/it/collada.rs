//! COLLADA meshes: the scene graph's transforms and units applied, polygons triangulated, and a
//! real robot's `.dae` equal to its STL twin.

use rigid::io::collada::parse_dae;
use rigid::io::mesh_file::read_mesh;
use rigid::spatial::Vec3;

use crate::common;

/// A unit cube (12 triangles) as two `<polylist>` quads and `<triangles>`, instanced twice.
const CUBE: &str = r##"<?xml version="1.0"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
 <asset><unit name="centimetre" meter="0.01"/><up_axis>Y_UP</up_axis></asset>
 <library_geometries><geometry id="cube"><mesh>
  <source id="pos"><float_array id="pos-a" count="24">
    0 0 0  100 0 0  100 100 0  0 100 0  0 0 100  100 0 100  100 100 100  0 100 100</float_array>
   <technique_common><accessor source="#pos-a" count="8" stride="3"/></technique_common></source>
  <source id="nrm"><float_array id="nrm-a" count="3">0 0 1</float_array>
   <technique_common><accessor source="#nrm-a" count="1" stride="3"/></technique_common></source>
  <vertices id="v"><input semantic="POSITION" source="#pos"/></vertices>
  <polylist count="2"><input semantic="VERTEX" source="#v" offset="0"/>
   <input semantic="NORMAL" source="#nrm" offset="1"/>
   <vcount>4 4</vcount><p>0 0 3 0 2 0 1 0  4 0 5 0 6 0 7 0</p></polylist>
  <triangles count="8"><input semantic="VERTEX" source="#v" offset="0"/>
   <p>0 1 5 0 5 4  1 2 6 1 6 5  2 3 7 2 7 6  3 0 4 3 4 7</p></triangles>
 </mesh></geometry></library_geometries>
 <library_visual_scenes><visual_scene id="s">
  <node id="a"><instance_geometry url="#cube"/></node>
  <node id="b"><translate>300 0 0</translate><rotate>0 0 1 90</rotate>
   <node id="c"><scale>2 1 1</scale><instance_geometry url="#cube"/></node></node>
 </visual_scene></library_visual_scenes>
 <scene><instance_visual_scene url="#s"/></scene>
</COLLADA>"##;

#[test]
fn the_scene_graph_places_and_scales_each_instance() {
    let mesh = parse_dae(CUBE).unwrap();
    assert_eq!(mesh.triangles.len(), 24);
    let half = |k: usize| {
        rigid::mass::TriMesh::new(
            mesh.vertices.clone(),
            mesh.triangles[12 * k..12 * k + 12].to_vec(),
        )
    };
    let bounds = |m: &rigid::mass::TriMesh| {
        m.triangles.iter().flatten().fold(
            (Vec3::repeat(f64::INFINITY), Vec3::repeat(f64::NEG_INFINITY)),
            |(lo, hi), &i| (lo.inf(&mesh.vertices[i]), hi.sup(&mesh.vertices[i])),
        )
    };
    let (mut unit, mut moved) = (0, 0);
    for k in 0..2 {
        let m = half(k);
        let props = m.mass_properties().unwrap(); // closed and outward
        let (lo, hi) = bounds(&m);
        if (props.volume - 1.0).abs() < 1e-12 {
            // the first cube: 1 m (100 cm) on a side at the origin
            assert!((props.com - Vec3::repeat(0.5)).norm() < 1e-12);
            unit += 1;
        } else {
            // the second: scaled 2x along x, turned 90° about z, moved 3 m along x
            assert!((props.volume - 2.0).abs() < 1e-12);
            assert!((lo - Vec3::new(2.0, 0.0, 0.0)).norm() < 1e-12, "{lo}");
            assert!((hi - Vec3::new(3.0, 2.0, 1.0)).norm() < 1e-12, "{hi}");
            moved += 1;
        }
    }
    assert_eq!((unit, moved), (1, 1));
}

#[test]
fn bad_collada_is_an_error_not_a_panic() {
    for bad in [
        "<notcollada/>",
        "<COLLADA><library_geometries><geometry id=\"g\"><mesh/></geometry></library_geometries></COLLADA>",
        &CUBE.replace("4 0 5 0 6 0 7 0", "4 0 5 0 6 0 99 0"),
        &CUBE.replace("100 100 100", "100 x 100"),
        &CUBE.replace("<vcount>4 4</vcount>", "<vcount>4 40</vcount>"),
    ] {
        assert!(parse_dae(bad).is_err(), "accepted: {bad}");
    }
}

#[test]
fn a_robot_dae_matches_its_stl_twin() {
    // TIAGo's arm: a Y-up COLLADA collision mesh and the STL visual mesh of the same part
    // (example-robot-data's files, checked in under tests/fixtures/robots/)
    let erd = common::example_robot_data();
    let dir = erd.join("tiago_description/meshes/arm");
    let dae = read_mesh(&dir.join("arm_2_collision.dae")).unwrap();
    let stl = read_mesh(&dir.join("arm_2.stl")).unwrap();
    let bounds = |m: &rigid::mass::TriMesh| {
        m.vertices.iter().fold(
            (Vec3::repeat(f64::INFINITY), Vec3::repeat(f64::NEG_INFINITY)),
            |(lo, hi), v| (lo.inf(v), hi.sup(v)),
        )
    };
    let (a, b) = (bounds(&dae), bounds(&stl));
    // the collision mesh is a simplified hull of the visual one: same box within 2 mm
    assert!(
        (a.0 - b.0).amax() < 2e-3 && (a.1 - b.1).amax() < 2e-3,
        "{a:?} {b:?}"
    );
}
