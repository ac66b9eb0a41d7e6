//! Reading files: triangle meshes (STL, OBJ, COLLADA), the body specs of `rigid mass` (TOML),
//! URDF robots, SRDF files ([`srdf`]), MuJoCo's MJCF models, SDFormat models ([`sdf`]), constraint files, and finding the robot files of
//! example-robot-data ([`robots`]); writing MJCF and URDF ([`write`]).

#[cfg(feature = "serde")]
pub mod cases;
#[cfg(feature = "mesh")]
pub mod collada;
#[cfg(all(feature = "collision", feature = "mesh"))]
pub mod collision;
#[cfg(feature = "serde")]
pub mod constraints;
#[cfg(feature = "mesh")]
pub mod mesh_file;
#[cfg(feature = "mjcf")]
pub mod mjcf;
pub mod robots;
#[cfg(all(feature = "urdf", feature = "collision"))]
pub mod sdf;
#[cfg(feature = "spec")]
pub mod spec;
#[cfg(feature = "urdf")]
pub mod srdf;
#[cfg(feature = "urdf")]
pub mod urdf;
#[cfg(all(feature = "collision", feature = "mesh"))]
pub mod write;

/// A number in the shortest form that reads back to the same `f64` (`0` for zero, no `.0`): how
/// the writers and the doctor's repairs print numbers into files.
#[cfg(any(feature = "urdf", all(feature = "collision", feature = "mesh")))]
pub(crate) fn shortest(x: f64) -> String {
    if x == 0.0 {
        return "0".into();
    }
    let s = format!("{x:?}");
    s.strip_suffix(".0").map_or(s.clone(), str::to_string)
}
