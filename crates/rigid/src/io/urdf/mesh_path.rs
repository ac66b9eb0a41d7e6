//! Where a URDF's `<mesh filename>` is on disk: `package://PKG/rest`, `file://path` or a path
//! relative to the URDF file.

use std::path::{Path, PathBuf};

/// The file a `<mesh filename>` of the URDF at `urdf` refers to, if it exists.
///
/// - `package://PKG/rest`: `PKG` is looked for as an ancestor folder of the URDF file named
///   `PKG`, or a folder `PKG` inside an ancestor (the layout of description packages and of
///   example-robot-data, whose files say `package://example-robot-data/robots/...`), then in
///   every folder of `ROS_PACKAGE_PATH` and in `share/` of every prefix of `AMENT_PREFIX_PATH`
///   and `CMAKE_PREFIX_PATH`.
/// - `file://path`: the path.
/// - anything else: relative to the URDF file's folder (or absolute).
///
/// ```
/// use rigid::io::urdf::resolve_mesh_path;
/// let dir = std::env::temp_dir().join("rigid_doc_mesh_path/my_robot/urdf");
/// std::fs::create_dir_all(dir.join("../meshes")).unwrap();
/// std::fs::write(dir.join("../meshes/a.stl"), b"").unwrap();
/// let urdf = dir.join("robot.urdf");
/// let found = resolve_mesh_path("package://my_robot/meshes/a.stl", Some(&urdf)).unwrap();
/// assert!(found.ends_with("my_robot/meshes/a.stl"));
/// assert_eq!(resolve_mesh_path("../meshes/a.stl", Some(&urdf)), Some(dir.join("../meshes/a.stl")));
/// ```
#[must_use]
pub fn resolve_mesh_path(filename: &str, urdf: Option<&Path>) -> Option<PathBuf> {
    let dir = urdf.and_then(Path::parent);
    if let Some(rest) = filename.strip_prefix("package://") {
        let (pkg, sub) = rest.split_once('/').unwrap_or((rest, ""));
        let mut candidates = Vec::new();
        if let Some(dir) = dir {
            for a in dir.ancestors() {
                if a.file_name().is_some_and(|n| n == pkg) {
                    candidates.push(a.join(sub));
                }
                candidates.push(a.join(pkg).join(sub));
            }
        }
        for var in ["ROS_PACKAGE_PATH"] {
            if let Some(paths) = std::env::var_os(var) {
                for p in std::env::split_paths(&paths) {
                    candidates.push(p.join(pkg).join(sub));
                }
            }
        }
        for var in ["AMENT_PREFIX_PATH", "CMAKE_PREFIX_PATH"] {
            if let Some(paths) = std::env::var_os(var) {
                for p in std::env::split_paths(&paths) {
                    candidates.push(p.join("share").join(pkg).join(sub));
                }
            }
        }
        return candidates.into_iter().find(|c| c.is_file());
    }
    let path = match filename.strip_prefix("file://") {
        Some(p) => PathBuf::from(p),
        None => match dir {
            Some(d) => d.join(filename),
            None => PathBuf::from(filename),
        },
    };
    path.is_file().then_some(path)
}
