//! One rigid body: `mass_properties` (a `rigid mass` spec as a TOML file or the same structure in
//! Python), the shape helpers that make its parts, `spatial_inertia`, `simulate_body`; and the
//! inertia doctor of a URDF, MJCF or SDF file, `doctor`.

use crate::convert::{array1, array2, io_error, rows_array, value_error, vec3};
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};
use rigid::body::{Integrator, Setup, Simulator, State};
use rigid::io::spec::{parse_spec, read_spec, SpecError};
use rigid::mass::{
    Compound, MassProperties, RotationalInertia, SpatialInertia, DEFAULT_INERTIA_TOLERANCE,
};
use rigid::simulation::step_count;
use rigid::spatial::{so3, Mat3, Vec3};
use std::path::{Path, PathBuf};

/// A Python value of a spec as TOML (`at` names it in messages).
fn to_toml(x: &Bound<'_, PyAny>, at: &str) -> PyResult<toml::Value> {
    use toml::Value;
    if x.is_instance_of::<PyBool>() {
        return Ok(Value::Boolean(x.extract()?));
    }
    if x.is_instance_of::<PyInt>() {
        return Ok(Value::Integer(x.extract()?));
    }
    if x.is_instance_of::<PyFloat>() {
        return Ok(Value::Float(x.extract()?));
    }
    if x.is_instance_of::<PyString>() {
        return Ok(Value::String(x.extract()?));
    }
    if let Ok(d) = x.cast::<PyDict>() {
        let mut t = toml::Table::new();
        for (k, v) in d.iter() {
            let k: String = k
                .extract()
                .map_err(|_| PyTypeError::new_err(format!("{at}: keys must be strings")))?;
            let value = to_toml(&v, &format!("{at}[\"{k}\"]"))?;
            t.insert(k, value);
        }
        return Ok(Value::Table(t));
    }
    if x.is_instance_of::<PyList>() || x.is_instance_of::<PyTuple>() {
        let items = x
            .try_iter()?
            .enumerate()
            .map(|(i, v)| to_toml(&v?, &format!("{at}[{i}]")))
            .collect::<PyResult<Vec<_>>>()?;
        return Ok(Value::Array(items));
    }
    if x.hasattr("tolist")? {
        // a numpy array or scalar
        return to_toml(&x.call_method0("tolist")?, at);
    }
    Err(PyTypeError::new_err(format!(
        "{at}: expected a number, string, list or dict, got {}",
        x.get_type().name()?
    )))
}

fn spec_error(func: &str, e: SpecError) -> PyErr {
    match &e {
        SpecError::Io { path, source } => {
            io_error(source, format!("{func}: {}: {e}", path.display()))
        }
        _ => value_error(func, e),
    }
}

/// The body described by `spec`: a path to a TOML spec, a dict `{"part": [...]}`, a list of
/// part dicts, or one part dict.
fn compound(func: &str, spec: &Bound<'_, PyAny>) -> PyResult<Compound> {
    if let Ok(path) = spec.extract::<PathBuf>() {
        if !spec.is_instance_of::<PyDict>() {
            return read_spec(&path).map_err(|e| spec_error(func, e));
        }
    }
    let value = to_toml(spec, "spec")?;
    let table = match value {
        toml::Value::Table(t) if t.contains_key("part") => t,
        part @ toml::Value::Table(_) => {
            toml::Table::from_iter([("part".to_string(), toml::Value::Array(vec![part]))])
        }
        parts @ toml::Value::Array(_) => toml::Table::from_iter([("part".to_string(), parts)]),
        _ => {
            return Err(PyTypeError::new_err(format!(
                "{func}: spec must be a path, a dict {{\"part\": [...]}}, a list of parts or a part"
            )))
        }
    };
    let text = toml::to_string(&table).map_err(|e| value_error(func, e))?;
    parse_spec(&text, Path::new(".")).map_err(|e| spec_error(func, e))
}

fn properties(func: &str, body: &Compound) -> PyResult<MassProperties> {
    body.mass_properties()
        .map_err(|e| value_error(func, body.error_message(&e)))
}

fn mat3<'py>(py: Python<'py>, m: &Mat3) -> Bound<'py, PyAny> {
    array2(py, 3, 3, |r, c| m[(r, c)]).into_any()
}

fn vec3_array<'py>(py: Python<'py>, v: &Vec3) -> Bound<'py, PyAny> {
    array1(py, &[v.x, v.y, v.z]).into_any()
}

/// Mass properties of a body made of parts, with the keys of `rigid mass --json`.
#[pyfunction]
pub fn mass_properties<'py>(
    py: Python<'py>,
    spec: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyDict>> {
    const F: &str = "mass_properties";
    let p = properties(F, &compound(F, spec)?)?;
    let g = p.spatial_inertia_origin.matrix();
    let validity = p.validity(DEFAULT_INERTIA_TOLERANCE);
    let d = PyDict::new(py);
    d.set_item("mass", p.mass)?;
    d.set_item("com", vec3_array(py, &p.com))?;
    d.set_item("inertia_com", mat3(py, p.inertia_com.matrix()))?;
    d.set_item("inertia_origin", mat3(py, p.inertia_origin.matrix()))?;
    d.set_item("principal_moments", vec3_array(py, &p.principal_moments))?;
    d.set_item("principal_axes", mat3(py, &p.principal_axes))?;
    d.set_item("spatial_inertia_origin", array2(py, 6, 6, |r, c| g[(r, c)]))?;
    d.set_item("valid", validity.is_ok())?;
    d.set_item("validity_error", validity.err().map(|e| e.to_string()))?;
    Ok(d)
}

/// One part of a spec as a dict, checked: `shape`, its dimensions, and the optional keys.
fn part<'py>(
    py: Python<'py>,
    shape: &str,
    dims: &[(&str, &Bound<'py, PyAny>)],
    options: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("shape", shape)?;
    for (k, v) in dims {
        d.set_item(*k, v)?;
    }
    if let Some(o) = options {
        for (k, v) in o.iter() {
            if !v.is_none() {
                d.set_item(k, v)?;
            }
        }
    }
    let func = format!("rigid.{shape}");
    // checked now, so that a wrong dimension is reported where the part is made
    compound(&func, d.as_any())?;
    Ok(d)
}

macro_rules! shape_fn {
    ($(#[$doc:meta])* $fn:ident, $shape:literal, ($($dim:ident),*)) => {
        $(#[$doc])*
        #[pyfunction]
        #[pyo3(signature = ($($dim,)* **options))]
        pub fn $fn<'py>(
            py: Python<'py>,
            $($dim: &Bound<'py, PyAny>,)*
            options: Option<&Bound<'py, PyDict>>,
        ) -> PyResult<Bound<'py, PyDict>> {
            part(py, $shape, &[$((stringify!($dim), $dim)),*], options)
        }
    };
}

shape_fn!(
    /// A box of edge lengths `size = [lx, ly, lz]` (m), centred on its frame.
    r#box, "box", (size)
);
shape_fn!(
    /// A solid cylinder, axis along z, centred.
    cylinder, "cylinder", (radius, length)
);
shape_fn!(
    /// A solid ball.
    sphere, "sphere", (radius)
);
shape_fn!(
    /// A solid ellipsoid of semi-axes `[a, b, c]`.
    ellipsoid, "ellipsoid", (semi_axes)
);
shape_fn!(
    /// A capsule: a cylinder of `radius` and `length` along z with hemispherical caps.
    capsule, "capsule", (radius, length)
);
shape_fn!(
    /// A solid cone, axis along z, origin at its centroid (base at `z = -h/4`).
    cone, "cone", (radius, height)
);
shape_fn!(
    /// A thin rod along z (give a mass).
    rod, "rod", (length)
);
shape_fn!(
    /// A point mass (give a mass).
    point, "point", ()
);
shape_fn!(
    /// A closed triangle mesh (STL or OBJ) of uniform density, in its own coordinates.
    mesh, "mesh", (file)
);

/// The 6 × 6 spatial inertia `G` about the frame's origin, angular first:
/// `[[I_c + m[c]ᵀ[c], m[c]], [m[c]ᵀ, m 1]]`.
#[pyfunction]
#[pyo3(signature = (mass, com = None, inertia = None))]
pub fn spatial_inertia<'py>(
    py: Python<'py>,
    mass: f64,
    com: Option<&Bound<'py, PyAny>>,
    inertia: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyAny>> {
    const F: &str = "spatial_inertia";
    if !(mass.is_finite() && mass >= 0.0) {
        return Err(value_error(
            F,
            format!("mass must be finite and >= 0, got {mass}"),
        ));
    }
    let c = com.map_or(Ok(Vec3::zeros()), |c| vec3(c, F, "com"))?;
    let i = match inertia {
        None => RotationalInertia::zero(),
        Some(x) => {
            let rows: [[f64; 3]; 3] = x
                .call_method0("tolist")
                .unwrap_or_else(|_| x.clone())
                .extract()
                .map_err(|_| {
                    PyTypeError::new_err(format!("{F}: inertia must be a 3 x 3 matrix"))
                })?;
            let m = Mat3::from_fn(|r, c| rows[r][c]);
            RotationalInertia::from_matrix(&m)
                .map_err(|e| value_error(F, format!("inertia: {e}")))?
        }
    };
    let g = SpatialInertia::from_com(mass, c, i).matrix();
    Ok(array2(py, 6, 6, |r, c| g[(r, c)]).into_any())
}

/// Simulates one rigid body, free or on a pivot, and returns its trajectory; with `ground`, the
/// body of a spec file on the ground (see [`crate::simulation::BodyOnGround`]).
#[pyfunction]
#[pyo3(signature = (spec, omega = None, velocity = None, gravity = None, pivot = None,
                    duration = 10.0, dt = 1e-3, integrator = "rk4", ground = None,
                    friction = None, restitution = None, q0 = None))]
#[allow(clippy::too_many_arguments)]
pub fn simulate_body<'py>(
    py: Python<'py>,
    spec: &Bound<'py, PyAny>,
    omega: Option<&Bound<'py, PyAny>>,
    velocity: Option<&Bound<'py, PyAny>>,
    gravity: Option<&Bound<'py, PyAny>>,
    pivot: Option<&Bound<'py, PyAny>>,
    duration: f64,
    dt: f64,
    integrator: &str,
    ground: Option<f64>,
    friction: Option<f64>,
    restitution: Option<f64>,
    q0: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    const F: &str = "simulate_body";
    let opt =
        |x: Option<&Bound<'py, PyAny>>, name| x.map_or(Ok(Vec3::zeros()), |x| vec3(x, F, name));
    let (w0, v0, g) = (
        opt(omega, "omega")?,
        opt(velocity, "velocity")?,
        opt(gravity, "gravity")?,
    );
    if ground.is_none() && (friction.is_some() || restitution.is_some() || q0.is_some()) {
        return Err(value_error(
            F,
            "friction, restitution and q0 apply with ground",
        ));
    }
    if let Some(height) = ground {
        if pivot.is_some() {
            return Err(value_error(
                F,
                "pivot does not apply to a body on the ground",
            ));
        }
        if !matches!(integrator, "rk4" | "semi-implicit") {
            return Err(value_error(
                F,
                format!("on the ground the integrator is \"semi-implicit\", not \"{integrator}\""),
            ));
        }
        let path: PathBuf = match spec.extract::<PathBuf>() {
            Ok(p) if !spec.is_instance_of::<PyDict>() => p,
            _ => {
                return Err(PyTypeError::new_err(format!(
                    "{F}: on the ground the spec is a path to a TOML spec file"
                )))
            }
        };
        let q0 = q0
            .map(|x| crate::convert::vector(x, F, "q0", "7", 7).map(|v| v.as_slice().to_vec()))
            .transpose()?;
        let run = crate::simulation::BodyOnGround {
            path: &path,
            height,
            friction,
            restitution,
            q0,
            twist: [w0.x, w0.y, w0.z, v0.x, v0.y, v0.z],
            gravity: gravity.map(|_| g),
            duration,
            dt,
            every: 1,
        };
        return run.run(py, F);
    }
    let pivot = pivot.map(|p| vec3(p, F, "pivot")).transpose()?;
    let integrator: Integrator = integrator.parse().map_err(|e| value_error(F, e))?;
    let steps = step_count(duration, dt).map_err(|e| value_error(F, e))?;
    let p = properties(F, &compound(F, spec)?)?;
    let err = |e: rigid::body::BodyError| value_error(F, e);
    // integrated in a frame {b} with the spec frame's axes, at the CoM (free) or at the pivot
    let setup = Setup::new(&p, pivot, w0, v0, g).map_err(err)?;
    let mut sim = Simulator::new(setup.body.clone(), setup.x0, integrator, dt).map_err(err)?;
    let n = usize::try_from(steps).map_err(|e| value_error(F, e))? + 1;
    // reserved up front up to a million rows; a longer run grows the arrays as it goes
    let r = n.min(1 << 20);
    let (mut t, mut energy) = (Vec::with_capacity(r), Vec::with_capacity(r));
    let (mut pos, mut quat) = (Vec::with_capacity(3 * r), Vec::with_capacity(4 * r));
    let (mut w, mut v) = (Vec::with_capacity(3 * r), Vec::with_capacity(3 * r));
    let mut record = |time: f64, x: &State, e: f64| {
        // the frame at the CoM with the spec frame's axes, and its body twist
        let (pose, twist) = setup.com_frame(x);
        t.push(time);
        energy.push(e);
        pos.extend_from_slice(pose.translation.as_slice());
        quat.extend_from_slice(&so3::to_quaternion(&pose.rotation));
        w.extend_from_slice(twist.w.as_slice());
        v.extend_from_slice(twist.v.as_slice());
    };
    record(0.0, sim.state(), sim.body().energy(sim.state()));
    let failure = py.detach(|| {
        for _ in 1..n {
            if let Err(e) = sim.step() {
                return Some(format!("t = {:.6} s: {e}", sim.time()));
            }
            record(sim.time(), sim.state(), sim.body().energy(sim.state()));
        }
        None
    });
    if let Some(e) = failure {
        return Err(value_error(F, e));
    }
    let rows = t.len();
    let d = PyDict::new(py);
    d.set_item("t", array1(py, &t))?;
    d.set_item("position", rows_array(py, pos, rows, 3)?)?;
    d.set_item("quaternion", rows_array(py, quat, rows, 4)?)?;
    d.set_item("omega", rows_array(py, w, rows, 3)?)?;
    d.set_item("velocity", rows_array(py, v, rows, 3)?)?;
    d.set_item("energy", array1(py, &energy))?;
    Ok(d)
}

/// The inertia doctor of a URDF, MJCF (`.xml`) or SDF (`.sdf`) file: the structure of
/// `rigid doctor --json` as dicts; `fix` writes the file with the repaired `<inertial>`
/// elements, in its own format.
#[pyfunction]
#[pyo3(signature = (path, fix = None))]
pub fn doctor<'py>(
    py: Python<'py>,
    path: PathBuf,
    fix: Option<PathBuf>,
) -> PyResult<Bound<'py, PyAny>> {
    use rigid::doctor::{examine_file, DoctorFileError};
    let shown = path.display().to_string();
    let examined = examine_file(&path).map_err(|e| {
        let io = match &e {
            DoctorFileError::Urdf(rigid::io::urdf::UrdfError::Io { source, .. })
            | DoctorFileError::Mjcf(rigid::io::mjcf::MjcfError::Io { source, .. })
            | DoctorFileError::Sdf(rigid::io::sdf::SdfError::Io { source, .. }) => Some(source),
            _ => None,
        };
        match io {
            Some(source) => io_error(source, format!("doctor: {e}")),
            None => value_error("doctor", format!("{shown}: {e}")),
        }
    })?;
    if let Some(out) = fix {
        let text = std::fs::read_to_string(&path)
            .map_err(|e| io_error(&e, format!("doctor: {shown}: {e}")))?;
        let (fixed, notes) = examined
            .fixed(&text)
            .map_err(|e| value_error("doctor", format!("{shown}: {e}")))?;
        // what was not repaired (a body in an included file, MJCF's inertiafromgeom)
        let warnings = py.import("warnings")?;
        for n in notes {
            warnings.call_method1("warn", (format!("doctor: {shown}: {n}"),))?;
        }
        std::fs::write(&out, fixed)
            .map_err(|e| io_error(&e, format!("doctor: cannot write {}: {e}", out.display())))?;
    }
    let json = serde_json::to_string(&examined.report).map_err(|e| value_error("doctor", e))?;
    py.import("json")?.call_method1("loads", (json,))
}
