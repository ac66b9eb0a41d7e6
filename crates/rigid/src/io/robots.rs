//! The robot files of example-robot-data: where its `robots/` folder is on this machine
//! ([`example_robot_data`]), and the robots known by a short name ([`ROBOTS`], [`robot`]).
//!
//! `rigid simulate ur5`, the benchmarks and the tests all find the files here. The folder is
//! looked for, in order:
//!
//! 1. `$EXAMPLE_ROBOT_DATA` (the `robots/` folder itself);
//! 2. `share/example-robot-data/robots` under each prefix of `$AMENT_PREFIX_PATH`, then of
//!    `$CMAKE_PREFIX_PATH` (a ROS or conda install);
//! 3. `cmeel.prefix/share/example-robot-data/robots` under the site-packages folders of Python
//!    (`$RIGID_PYTHON`, else `python3`): where `pip install example-robot-data` puts it.
//!
//! ```no_run
//! use rigid::io::robots::robot;
//! let ur5 = robot("ur5").unwrap();
//! assert!(!ur5.floating);
//! if let Some(path) = ur5.urdf() {
//!     let model = rigid::io::urdf::load_urdf(&path, ur5.floating)?;
//!     assert_eq!(model.nv(), 6);
//! }
//! # Ok::<(), rigid::io::urdf::UrdfError>(())
//! ```

use std::path::{Path, PathBuf};
use std::process::Command;

/// A robot of example-robot-data known by a short name.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Robot {
    /// The short name (`ur5`, `panda`, `talos`, …).
    pub name: &'static str,
    /// Its URDF file, relative to the `robots/` folder.
    pub file: &'static str,
    /// A floating base (a legged robot or a humanoid): it moves with a free-flyer root joint.
    pub floating: bool,
}

impl Robot {
    /// The robot's URDF file on this machine, if example-robot-data is found and has it.
    #[must_use]
    pub fn urdf(&self) -> Option<PathBuf> {
        let p = example_robot_data()?.join(self.file);
        p.is_file().then_some(p)
    }
}

/// The robots of example-robot-data known by name.
pub const ROBOTS: &[Robot] = &[
    Robot {
        name: "ur5",
        file: "ur_description/urdf/ur5_robot.urdf",
        floating: false,
    },
    Robot {
        name: "ur10",
        file: "ur_description/urdf/ur10_robot.urdf",
        floating: false,
    },
    Robot {
        name: "panda",
        file: "panda_description/urdf/panda.urdf",
        floating: false,
    },
    Robot {
        name: "talos",
        file: "talos_data/robots/talos_reduced.urdf",
        floating: true,
    },
    Robot {
        name: "talos_full",
        file: "talos_data/robots/talos_full_v2.urdf",
        floating: true,
    },
    Robot {
        name: "solo12",
        file: "solo_description/robots/solo12.urdf",
        floating: true,
    },
    Robot {
        name: "anymal",
        file: "anymal_b_simple_description/robots/anymal.urdf",
        floating: true,
    },
    Robot {
        name: "tiago",
        file: "tiago_description/robots/tiago.urdf",
        floating: false,
    },
];

/// The robot of [`ROBOTS`] with this name.
#[must_use]
pub fn robot(name: &str) -> Option<&'static Robot> {
    ROBOTS.iter().find(|r| r.name == name)
}

/// The `robots/` folder under which example-robot-data keeps its robot files (see the
/// [module](self) documentation for where it is looked for), or `None` if it is not installed.
/// Only `$EXAMPLE_ROBOT_DATA` is returned without checking that the folder exists.
#[must_use]
pub fn example_robot_data() -> Option<PathBuf> {
    if let Some(p) = std::env::var_os("EXAMPLE_ROBOT_DATA") {
        return Some(p.into());
    }
    let share = |prefix: &Path| prefix.join("share/example-robot-data/robots");
    for var in ["AMENT_PREFIX_PATH", "CMAKE_PREFIX_PATH"] {
        if let Some(paths) = std::env::var_os(var) {
            if let Some(p) = std::env::split_paths(&paths)
                .map(|p| share(&p))
                .find(|p| p.is_dir())
            {
                return Some(p);
            }
        }
    }
    let python = std::env::var_os("RIGID_PYTHON").unwrap_or_else(|| "python3".into());
    let out = Command::new(python)
        .args([
            "-c",
            "import site, sysconfig; \
             print('\\n'.join(site.getsitepackages() + [sysconfig.get_paths()['purelib']]))",
        ])
        .output()
        .ok()?;
    String::from_utf8_lossy(&out.stdout)
        .lines()
        .map(|site| share(&Path::new(site.trim()).join("cmeel.prefix")))
        .find(|p| p.is_dir())
}
