//! `rigid.Model` and `rigid.Data`: a kinematic tree and its workspace, in rigid's layout or in
//! Pinocchio's (joint order by sibling name, `(cos θ, sin θ)` coordinates, linear-first
//! free-flyer velocities), with the conversions the verbs apply at the boundary.

use crate::convert::{self, array1, array2, Vector};
use numpy::{PyArray1, PyArray2, PyArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyAny;
use rigid::interop::{Layout, LayoutError, MujocoLayout, PinocchioLayout};
use rigid::io::mjcf::{self, MjcfError};
use rigid::io::urdf::{self, InertiaPolicy, SiblingOrder, UrdfError, UrdfOptions};
use rigid::multibody::{builtin, builtin_names, FrameId, JointId, MultibodyError};
use std::ffi::CString;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;

pub use crate::data::Data;

pyo3::create_exception!(
    rigid,
    SdfWarning,
    pyo3::exceptions::PyUserWarning,
    "Something in an SDF file that rigid reads past or leaves out (plugins, a gearbox, a loop a \
     point or a weld cannot close, ...): the file loads, the message names the element and the line."
);

pyo3::create_exception!(
    rigid,
    MjcfWarning,
    pyo3::exceptions::PyUserWarning,
    "Something in an MJCF file that rigid reads past or tolerates (actuators, sensors, gravity \
     compensation, ...): the file loads, the message names the element and the line."
);

pyo3::create_exception!(
    rigid,
    UrdfWarning,
    pyo3::exceptions::PyUserWarning,
    "Something in a URDF file that was tolerated (a non-physical inertia loaded as written, an \
     unknown element, ...): the file loads, the message names the element and the line."
);

/// The model and what the Python verbs need around it.
pub struct ModelCore {
    /// The kinematic tree, in rigid's layout.
    pub model: rigid::multibody::Model,
    /// `Some` for `layout="pinocchio"`.
    pub layout: Option<PinocchioLayout>,
    /// `q` differs between the layouts (a continuous or planar joint, Pinocchio layout).
    pub convert_q: bool,
    /// `v` differs (a free-flyer, Pinocchio layout).
    pub convert_v: bool,
    /// The warnings of the URDF loader.
    pub warnings: Vec<String>,
    /// Unique per loaded model (kept when gravity is changed): a `Data` works with the model it
    /// was made for.
    pub id: u64,
    /// The URDF or MJCF file it was loaded from (for the replay's meshes).
    pub source: Option<PathBuf>,
    /// `Some` for `layout="mujoco"`.
    pub mujoco: Option<MujocoLayout>,
    /// MuJoCo's `qpos0`, for a model read from MJCF.
    pub qpos0: Option<Vec<f64>>,
}

/// The next [`ModelCore::id`].
static NEXT_ID: AtomicU64 = AtomicU64::new(0);

impl ModelCore {
    pub(crate) fn new(
        model: rigid::multibody::Model,
        pinocchio: bool,
        warnings: Vec<String>,
    ) -> Self {
        let layout = pinocchio.then(|| PinocchioLayout::new(&model));
        let convert_q = layout.as_ref().is_some_and(|l| l.nq() != model.nq());
        let convert_v = layout
            .as_ref()
            .is_some_and(|l| (0..model.nv()).any(|k| l.v_index(k) != k));
        Self {
            model,
            layout,
            convert_q,
            convert_v,
            warnings,
            id: NEXT_ID.fetch_add(1, Ordering::Relaxed),
            source: None,
            mujoco: None,
            qpos0: None,
        }
    }

    /// The MuJoCo layout when it has a free joint: then velocities map through the
    /// `q`-dependent `T(q)` and only the verbs of `dynamics` that handle it accept the model.
    pub fn mujoco_free(&self) -> Option<&MujocoLayout> {
        self.mujoco.as_ref().filter(|l| l.has_free_joint())
    }

    /// The length of `q` in this model's layout.
    pub fn nq(&self) -> usize {
        self.layout
            .as_ref()
            .map_or(self.model.nq(), PinocchioLayout::nq)
    }

    /// The length of `v`.
    pub fn nv(&self) -> usize {
        self.model.nv()
    }

    /// Writes `q` (argument `name` of `func`) into `out` in rigid's layout.
    pub fn q_into(
        &self,
        x: &Vector<'_>,
        out: &mut Vec<f64>,
        func: &str,
        name: &str,
    ) -> PyResult<()> {
        let q = x.as_slice();
        if let Some(l) = &self.mujoco {
            out.resize(self.model.nq(), 0.0);
            return l.q_from_mujoco(q, out).map_err(|e| match e {
                MultibodyError::NonFinite { index, .. } => {
                    convert::value_error(func, format!("{name}[{index}] is not finite"))
                }
                e => convert::value_error(func, format!("{name}: {e}")),
            });
        }
        match &self.layout {
            Some(l) if self.convert_q => {
                out.resize(self.model.nq(), 0.0);
                l.q_from_pinocchio(q, out).map_err(|e| match e {
                    LayoutError::Input(MultibodyError::NonFinite { index, .. }) => {
                        convert::value_error(func, format!("{name}[{index}] is not finite"))
                    }
                    e => convert::value_error(func, format!("{name}: {e}")),
                })
            }
            _ => {
                out.clear();
                out.extend_from_slice(q);
                Ok(())
            }
        }
    }

    /// Writes a velocity-space vector (`v`, `a`, `τ`: argument `name` of `func`) into `out` in
    /// rigid's layout. In Pinocchio's layout with a free-flyer, non-finite entries are refused
    /// here, so that the error gives the index in the caller's vector.
    pub fn v_into(
        &self,
        x: &Vector<'_>,
        out: &mut Vec<f64>,
        func: &str,
        name: &str,
    ) -> PyResult<()> {
        let v = x.as_slice();
        if self.mujoco_free().is_some() {
            return Err(convert::value_error(
                func,
                "not available in the mujoco layout for a model with a free joint (MuJoCo's \
                 free-joint velocity depends on q): rnea, aba, nle, gravity, crba, minverse, \
                 jacobian, kinetic_energy, com and potential_energy are; use layout=\"rigid\" \
                 for the others"
                    .to_string(),
            ));
        }
        match &self.layout {
            Some(l) if self.convert_v => {
                if let Some(i) = v.iter().position(|x| !x.is_finite()) {
                    return Err(convert::value_error(
                        func,
                        format!("{name}[{i}] is not finite"),
                    ));
                }
                out.resize(self.nv(), 0.0);
                l.permute_v(v, out);
            }
            _ => {
                out.clear();
                out.extend_from_slice(v);
            }
        }
        Ok(())
    }

    /// A velocity-space result as a fresh array in this model's layout.
    pub fn v_out<'py>(&self, py: Python<'py>, v: &[f64]) -> Bound<'py, PyArray1<f64>> {
        match &self.layout {
            Some(_) if self.convert_v => PyArray1::from_vec(py, self.v_to_layout(v)),
            _ => array1(py, v),
        }
    }

    /// A configuration as a fresh array in this model's layout.
    pub fn q_out<'py>(&self, py: Python<'py>, q: &[f64]) -> Bound<'py, PyArray1<f64>> {
        if self.mujoco.is_some() {
            return PyArray1::from_vec(py, self.q_to_layout(q));
        }
        match &self.layout {
            Some(_) if self.convert_q => PyArray1::from_vec(py, self.q_to_layout(q)),
            _ => array1(py, q),
        }
    }

    /// A velocity-space vector from rigid's layout to this model's.
    pub fn v_to_layout(&self, v: &[f64]) -> Vec<f64> {
        match &self.layout {
            Some(l) if self.convert_v => {
                let mut out = vec![0.0; v.len()];
                l.permute_v(v, &mut out);
                out
            }
            _ => v.to_vec(),
        }
    }

    /// A configuration from rigid's layout to this model's.
    pub fn q_to_layout(&self, q: &[f64]) -> Vec<f64> {
        if let Some(l) = &self.mujoco {
            let mut out = vec![0.0; q.len()];
            l.q_to_mujoco(q, &mut out);
            return out;
        }
        match &self.layout {
            Some(l) if self.convert_q => {
                let mut out = vec![0.0; l.nq()];
                l.q_to_pinocchio(q, &mut out);
                out
            }
            _ => q.to_vec(),
        }
    }

    /// The velocity-space index of this layout's coordinate `k` in rigid's.
    pub fn v_index(&self, k: usize) -> usize {
        match &self.layout {
            Some(l) if self.convert_v => l.v_index(k),
            _ => k,
        }
    }

    /// An `nv × nv` matrix (`M`, `M⁻¹`, `C`) as a fresh array in this layout:
    /// `out[(r, c)] = m[(v_index(r), v_index(c))]`, written straight into the array (no
    /// intermediate matrix).
    pub fn matrix_out<'py>(
        &self,
        py: Python<'py>,
        m: &nalgebra::DMatrix<f64>,
    ) -> Bound<'py, PyArray2<f64>> {
        let (rows, cols) = m.shape();
        match &self.layout {
            Some(l) if self.convert_v => {
                array2(py, rows, cols, |r, c| m[(l.v_index(r), l.v_index(c))])
            }
            _ => array2(py, rows, cols, |r, c| m[(r, c)]),
        }
    }

    /// A `6 × nv` Jacobian as a fresh array: rows `(ω, v)` in rigid's layout, `(v, ω)` and
    /// columns permuted in Pinocchio's. Written column by column straight from the column-major
    /// source into the row-major array.
    pub fn jacobian_out<'py>(
        &self,
        py: Python<'py>,
        j: &nalgebra::DMatrix<f64>,
    ) -> Bound<'py, PyArray2<f64>> {
        let nv = j.ncols();
        // SAFETY: a new C-contiguous array, every entry written below before Python sees it.
        let a = unsafe { PyArray2::<f64>::new(py, [6, nv], false) };
        // SAFETY: the array was just made here and nothing else refers to it.
        let out = unsafe { a.as_slice_mut() }.unwrap_or(&mut []);
        let shift = if self.layout.is_some() { 3 } else { 0 };
        for c in 0..nv {
            let col = j.column(self.v_index(c));
            for r in 0..6 {
                out[r * nv + c] = col[(r + shift) % 6];
            }
        }
        a
    }

    /// `data` was made for this model (or for it before a gravity change).
    pub fn check_data(&self, func: &str, data: &Data) -> PyResult<()> {
        if data.model.id == self.id {
            Ok(())
        } else {
            Err(PyValueError::new_err(format!(
                "{func}: data was made for model '{}', not for this model '{}' (use \
                 model.create_data())",
                data.model.model.name(),
                self.model.name()
            )))
        }
    }

    /// What a name stands for: a joint (its moved frame), or else a named frame.
    pub fn lookup(&self, func: &str, name: &str) -> PyResult<Place> {
        if let Some(j) = self.model.joint_id(name) {
            return Ok(Place::Joint(j));
        }
        self.model.frame_id(name).map(Place::Frame).map_err(|e| {
            PyValueError::new_err(format!(
                "{func}: {e} (a joint or frame name of model '{}')",
                self.model.name()
            ))
        })
    }
}

/// A joint or a named frame.
#[derive(Clone, Copy)]
pub enum Place {
    /// The frame of a joint, as moved by it.
    Joint(JointId),
    /// A named frame (a link, a fixed joint, an operational frame).
    Frame(FrameId),
}

/// The URDF options of `Model.from_urdf`'s arguments (siblings by name in Pinocchio's layout).
pub(crate) fn urdf_options(
    floating: bool,
    inertia: &str,
    pinocchio: bool,
) -> PyResult<UrdfOptions> {
    Ok(UrdfOptions {
        floating,
        inertia: policy(inertia)?,
        sibling_order: if pinocchio {
            SiblingOrder::Name
        } else {
            SiblingOrder::File
        },
    })
}

/// A URDF that could not be loaded: `FileNotFoundError`/`OSError` or `ValueError`, naming the file.
pub(crate) fn urdf_error(shown: &str, e: &UrdfError) -> PyErr {
    match e {
        UrdfError::Io { source, .. } => convert::io_error(source, e.to_string()),
        _ => PyValueError::new_err(format!("{shown}: {e}")),
    }
}

pub(crate) fn policy(inertia: &str) -> PyResult<InertiaPolicy> {
    inertia
        .parse()
        .map_err(|e: String| PyValueError::new_err(format!("Model.from_urdf: inertia: {e}")))
}

pub(crate) fn parse_layout(func: &str, layout: &str) -> PyResult<Layout> {
    layout
        .parse()
        .map_err(|e: String| PyValueError::new_err(format!("{func}: {e}")))
}

/// Issues each warning as a Python warning of `category`.
pub(crate) fn warn_all(
    py: Python<'_>,
    category: &Bound<'_, pyo3::types::PyType>,
    warnings: &[String],
) -> PyResult<()> {
    for w in warnings {
        let text = CString::new(w.replace('\0', " ")).unwrap_or_default();
        PyErr::warn(py, category.as_any(), &text, 2)?;
    }
    Ok(())
}

/// A kinematic tree (Pinocchio's `Model`): joints depth-first from the root, their placements,
/// the bodies' spatial inertias, limits and gravity. Constant but for `gravity`. Subclassable
/// (`rigid.pinocchio.Model` is one); pickled through its stable serialised form
/// (`Model::to_json`), which reads back bit for bit.
#[pyclass(module = "rigid", name = "Model", subclass)]
pub struct Model {
    pub inner: Arc<ModelCore>,
}

#[pymethods]
impl Model {
    /// A model from its serialised form (`model.to_json()`; what pickling stores), in `layout`;
    /// without `json`, the empty model (no joint: Pinocchio's `pin.Model()`). `warnings`,
    /// `source` (the file it was read from) and `qpos0` (an MJCF model's) are kept as given.
    #[new]
    #[pyo3(signature = (json = None, layout = "rigid", *, warnings = Vec::new(), source = None, qpos0 = None))]
    fn py_new(
        json: Option<&str>,
        layout: &str,
        warnings: Vec<String>,
        source: Option<PathBuf>,
        qpos0: Option<Vec<f64>>,
    ) -> PyResult<Self> {
        let kind = parse_layout("Model", layout)?;
        let model = match json {
            Some(text) => rigid::multibody::Model::from_json(text)
                .map_err(|e| PyValueError::new_err(format!("Model: json: {e}")))?,
            None => rigid::multibody::ModelBuilder::new("model")
                .build()
                .map_err(|e| PyValueError::new_err(format!("Model: {e}")))?,
        };
        let mut core = ModelCore::new(model, kind == Layout::Pinocchio, warnings);
        if kind == Layout::Mujoco {
            core.mujoco = Some(MujocoLayout::new(&core.model));
        }
        core.source = source;
        core.qpos0 = qpos0;
        Ok(Self {
            inner: Arc::new(core),
        })
    }

    /// The model's stable serialised form (JSON: joints, placements, inertias, frames, limits,
    /// armature, damping, friction, gravity; rigid's layout). `rigid.Model(json)` reads it back
    /// bit for bit.
    fn to_json(&self) -> String {
        self.inner.model.to_json()
    }

    /// Write the model as MJCF (a `.xml` path) or URDF (`.urdf`, its meshes as OBJ files in
    /// `STEM_meshes/` beside it), with the collision geometry of the file it was loaded from;
    /// returns the notes on what the format cannot express (`rigid convert`).
    fn save(&self, path: PathBuf) -> PyResult<Vec<String>> {
        let core = &self.inner;
        rigid::io::write::save(&core.model, core.source.as_deref(), &path).map_err(|e| match &e {
            rigid::io::write::SaveError::Io { source, .. } => {
                convert::io_error(source, e.to_string())
            }
            _ => PyValueError::new_err(e.to_string()),
        })
    }

    /// Pickling: `(type(self), (json, layout), {warnings, source, qpos0})`; the copy computes
    /// the same numbers bit for bit and is a new model (a `Data` of the original does not work
    /// with it: pickle the two together, `pickle.dumps((model, data))`, to keep the pair).
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyAny>> {
        let py = slf.py();
        let me = slf.borrow();
        let core = &me.inner;
        let kwargs = pyo3::types::PyDict::new(py);
        kwargs.set_item("warnings", core.warnings.clone())?;
        kwargs.set_item("source", core.source.clone())?;
        kwargs.set_item("qpos0", core.qpos0.clone())?;
        let args = (core.model.to_json(), me.layout());
        let rebuild = py
            .import("functools")?
            .getattr("partial")?
            .call((slf.get_type(),), Some(&kwargs))?;
        (rebuild, args).into_pyobject(py).map(Bound::into_any)
    }

    /// A new model whose body inertias are `pi` (ten per body, `dynamic_parameters`' order),
    /// each checked to be physical (a clear `ValueError` names the first body that is not;
    /// `check=False` takes them as they are).
    #[pyo3(signature = (pi, *, check = true))]
    fn with_dynamic_parameters(&self, pi: &Bound<'_, PyAny>, check: bool) -> PyResult<Self> {
        crate::scale::with_dynamic_parameters(self, pi, check)
    }

    /// `copy.copy`: the same (constant) model, shared.
    fn __copy__<'py>(slf: &Bound<'py, Self>) -> Bound<'py, Self> {
        slf.clone()
    }
    /// Load a URDF file (Pinocchio's `buildModelFromUrdf`). With `mimic=True`, a
    /// `rigid.MimicModel` whose `<mimic>` joints follow their sources with no coordinate of
    /// their own (Pinocchio's `mimic=True`; `layout` `"rigid"` or `"pinocchio"`).
    #[staticmethod]
    #[pyo3(signature = (path, floating = false, inertia = "warn", layout = "rigid", mimic = false))]
    fn from_urdf(
        py: Python<'_>,
        path: PathBuf,
        floating: bool,
        inertia: &str,
        layout: &str,
        mimic: bool,
    ) -> PyResult<Py<PyAny>> {
        if mimic {
            let m = crate::mimic::MimicModel::from_urdf(py, path, floating, inertia, layout)?;
            return Ok(Py::new(py, m)?.into_any());
        }
        Ok(Py::new(py, Self::load_urdf(py, path, floating, inertia, layout)?)?.into_any())
    }

    /// Load an MJCF file (MuJoCo's XML) with MuJoCo's compiled inertias; `layout="mujoco"` reads
    /// and writes MuJoCo's `qpos`, `qvel`, `qfrc` (hinges from `ref`, quaternions w first,
    /// free-joint velocity world-linear then body-angular). With `mimic=True`, a
    /// `rigid.MimicModel` whose `<equality joint>` elements with a linear polynomial are
    /// couplings (the driven joint has no coordinate of its own).
    #[staticmethod]
    #[pyo3(signature = (path, layout = "rigid", mimic = false))]
    fn from_mjcf(py: Python<'_>, path: PathBuf, layout: &str, mimic: bool) -> PyResult<Py<PyAny>> {
        const F: &str = "Model.from_mjcf";
        let kind = parse_layout(F, layout)?;
        let (m, warnings) = Self::read_mjcf(py, &path)?;
        if mimic {
            let shown = path.display().to_string();
            let mimics = m
                .mimics()
                .map_err(|e| PyValueError::new_err(format!("{shown}: {e}")))?;
            let mm = crate::mimic::MimicModel::coupled(F, &shown, kind, m.model, &mimics)?;
            return Ok(Py::new(py, mm)?.into_any());
        }
        Ok(Py::new(py, Self::of_mjcf(m, warnings, kind, path))?.into_any())
    }

    /// Load an SDF file (SDFormat 1.4–1.11, one model): links no joint holds float (free-flyers),
    /// loops are `ConstraintModel.from_sdf(model)`; what rigid leaves out is an `SdfWarning`.
    /// With `mimic=True`, a `rigid.MimicModel` whose gearboxes are couplings.
    #[staticmethod]
    #[pyo3(signature = (path, layout = "rigid", mimic = false))]
    fn from_sdf(py: Python<'_>, path: PathBuf, layout: &str, mimic: bool) -> PyResult<Py<PyAny>> {
        const F: &str = "Model.from_sdf";
        let kind = parse_layout(F, layout)?;
        let (m, warnings) = Self::read_sdf(py, &path)?;
        if mimic {
            let shown = path.display().to_string();
            let mimics = m.mimics();
            let mm = crate::mimic::MimicModel::coupled(F, &shown, kind, m.model, &mimics)?;
            return Ok(Py::new(py, mm)?.into_any());
        }
        Ok(Py::new(py, Self::of_sdf(m, warnings, kind, path))?.into_any())
    }

    /// Load a model file, MJCF for a `.xml` file, SDF for `.sdf`, URDF otherwise (`floating`
    /// and `inertia` apply to URDF only).
    #[staticmethod]
    #[pyo3(signature = (path, layout = "rigid", floating = false, inertia = "warn"))]
    fn from_file(
        py: Python<'_>,
        path: PathBuf,
        layout: &str,
        floating: bool,
        inertia: &str,
    ) -> PyResult<Self> {
        let ext = |x: &str| path.extension().is_some_and(|e| e.eq_ignore_ascii_case(x));
        let (mjcf, sdf) = (ext("xml"), ext("sdf"));
        if !mjcf && !sdf {
            return Self::load_urdf(py, path, floating, inertia, layout);
        }
        if floating {
            return Err(PyValueError::new_err(
                "Model.from_file: floating applies to URDF; MJCF and SDF files declare their \
                 free bodies",
            ));
        }
        let kind = parse_layout("Model.from_file", layout)?;
        if sdf {
            let (m, warnings) = Self::read_sdf(py, &path)?;
            return Ok(Self::of_sdf(m, warnings, kind, path));
        }
        let (m, warnings) = Self::read_mjcf(py, &path)?;
        Ok(Self::of_mjcf(m, warnings, kind, path))
    }

    /// A built-in model: `puma560`, `puma560_armature`, `pendulum`, `double_pendulum`.
    #[staticmethod]
    #[pyo3(signature = (name, layout = "rigid"))]
    fn builtin(name: &str, layout: &str) -> PyResult<Self> {
        let kind = parse_layout("Model.builtin", layout)?;
        let model = builtin(name).ok_or_else(|| {
            PyValueError::new_err(format!(
                "Model.builtin: unknown model \"{name}\" (built-in models: {})",
                builtin_names().join(", ")
            ))
        })?;
        let mut core = ModelCore::new(model, kind == Layout::Pinocchio, Vec::new());
        if kind == Layout::Mujoco {
            core.mujoco = Some(MujocoLayout::new(&core.model));
        }
        Ok(Self {
            inner: Arc::new(core),
        })
    }

    /// A new workspace for this model (Pinocchio's `model.createData()`).
    fn create_data(slf: &Bound<'_, Self>) -> Data {
        Data::of(slf)
    }

    /// Alias of `create_data` (Pinocchio's name).
    #[pyo3(name = "createData")]
    fn create_data_pinocchio(slf: &Bound<'_, Self>) -> Data {
        Data::of(slf)
    }

    /// The model's name.
    #[getter]
    fn name(&self) -> &str {
        self.inner.model.name()
    }

    /// Number of configuration coordinates (in this model's layout).
    #[getter]
    fn nq(&self) -> usize {
        self.inner.nq()
    }

    /// Number of degrees of freedom.
    #[getter]
    fn nv(&self) -> usize {
        self.inner.nv()
    }

    /// Number of moving joints (Pinocchio's `njoints - 1`: no "universe").
    #[getter]
    fn njoints(&self) -> usize {
        self.inner.model.njoints()
    }

    /// `"rigid"`, `"pinocchio"` or `"mujoco"`.
    #[getter]
    fn layout(&self) -> &'static str {
        if self.inner.mujoco.is_some() {
            "mujoco"
        } else if self.inner.layout.is_some() {
            "pinocchio"
        } else {
            "rigid"
        }
    }

    /// MuJoCo's `qpos0` (its layout) for a model read from MJCF, else `None`.
    #[getter]
    fn qpos0<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        self.inner.qpos0.as_ref().map(|q| array1(py, q))
    }

    /// The moving joints' names in order (Pinocchio's `model.names[1:]`).
    #[getter]
    fn names(&self) -> Vec<String> {
        self.inner
            .model
            .joints()
            .iter()
            .map(|j| j.name.clone())
            .collect()
    }

    /// Each joint's type: `revolute`, `continuous`, `prismatic`, `spherical`, `free_flyer`,
    /// `planar`.
    #[getter]
    fn joint_types(&self) -> Vec<&'static str> {
        self.inner
            .model
            .joints()
            .iter()
            .map(|j| j.type_name())
            .collect()
    }

    /// First index of each joint's coordinates in `q` (this layout).
    #[getter]
    fn idx_qs(&self) -> Vec<usize> {
        self.joint_q().into_iter().map(|(i, _)| i).collect()
    }

    /// Number of configuration coordinates of each joint (this layout).
    #[getter]
    fn nqs(&self) -> Vec<usize> {
        self.joint_q().into_iter().map(|(_, n)| n).collect()
    }

    /// First index of each joint's coordinates in `v`.
    #[getter]
    fn idx_vs(&self) -> Vec<usize> {
        self.inner.model.joints().iter().map(|j| j.idx_v).collect()
    }

    /// Number of degrees of freedom of each joint.
    #[getter]
    fn nvs(&self) -> Vec<usize> {
        self.inner.model.joints().iter().map(|j| j.nv).collect()
    }

    /// The named frames (links, fixed joints, operational frames), in order.
    #[getter]
    fn frame_names(&self) -> Vec<String> {
        self.inner
            .model
            .frames()
            .iter()
            .map(|f| f.name.clone())
            .collect()
    }

    /// Total mass of the moving bodies (kg; Pinocchio's `computeTotalMass` less the bodies
    /// welded to the world).
    #[getter]
    fn total_mass(&self) -> f64 {
        self.inner.model.total_mass()
    }

    /// The URDF loader's warnings (each also issued as a `rigid.UrdfWarning`).
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.inner.warnings.clone()
    }

    /// Gravity in the world frame (m/s², default `[0, 0, -9.81]`; Pinocchio's
    /// `model.gravity.linear`). Settable.
    #[getter]
    fn gravity<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let g = self.inner.model.gravity();
        array1(py, &[g.x, g.y, g.z])
    }

    #[setter]
    fn set_gravity(&mut self, g: &Bound<'_, PyAny>) -> PyResult<()> {
        let g = convert::vec3(g, "Model.gravity", "gravity")?;
        let core = &self.inner;
        let model = core.model.clone().with_gravity(g);
        self.inner = Arc::new(ModelCore {
            model,
            layout: core.layout.clone(),
            convert_q: core.convert_q,
            convert_v: core.convert_v,
            warnings: core.warnings.clone(),
            id: core.id,
            source: core.source.clone(),
            mujoco: core.mujoco.clone(),
            qpos0: core.qpos0.clone(),
        });
        Ok(())
    }

    fn __repr__(&self) -> String {
        format!(
            "rigid.Model('{}', nq={}, nv={}, njoints={}, layout='{}')",
            self.inner.model.name(),
            self.inner.nq(),
            self.inner.nv(),
            self.inner.model.njoints(),
            self.layout()
        )
    }
}

impl Model {
    fn joint_q(&self) -> Vec<(usize, usize)> {
        let joints = self.inner.model.joints();
        match &self.inner.layout {
            Some(l) => (0..joints.len()).map(|i| l.joint_q(i)).collect(),
            None => joints.iter().map(|j| (j.idx_q, j.nq)).collect(),
        }
    }
}

impl Model {
    /// An MJCF file read, its warnings issued as `MjcfWarning`s (and returned, with the path).
    fn read_mjcf(py: Python<'_>, path: &Path) -> PyResult<(mjcf::MjcfModel, Vec<String>)> {
        let shown = path.display().to_string();
        let m = mjcf::load_mjcf(path).map_err(|e| match &e {
            MjcfError::Io { source, .. } => convert::io_error(source, e.to_string()),
            _ => PyValueError::new_err(format!("{shown}: {e}")),
        })?;
        let warnings: Vec<String> = m.warnings.iter().map(|w| format!("{shown}: {w}")).collect();
        warn_all(py, &py.get_type::<MjcfWarning>(), &warnings)?;
        Ok((m, warnings))
    }

    /// The model of an MJCF file read by [`Model::read_mjcf`], in the layout `kind`.
    fn of_mjcf(m: mjcf::MjcfModel, warnings: Vec<String>, kind: Layout, path: PathBuf) -> Self {
        let layout = m.layout();
        let qpos0 = m.qpos0.clone();
        let mut core = ModelCore::new(m.model, kind == Layout::Pinocchio, warnings);
        if kind == Layout::Mujoco {
            core.mujoco = Some(layout);
        }
        core.qpos0 = Some(qpos0);
        core.source = Some(path);
        Self {
            inner: Arc::new(core),
        }
    }

    /// An SDF file read, its warnings issued as `SdfWarning`s (and returned, with the path).
    fn read_sdf(py: Python<'_>, path: &Path) -> PyResult<(rigid::io::sdf::SdfModel, Vec<String>)> {
        let shown = path.display().to_string();
        let m = rigid::io::sdf::load_sdf(path).map_err(|e| match &e {
            rigid::io::sdf::SdfError::Io { source, .. } => convert::io_error(source, e.to_string()),
            _ => PyValueError::new_err(format!("{shown}: {e}")),
        })?;
        let warnings: Vec<String> = m.warnings.iter().map(|w| format!("{shown}: {w}")).collect();
        warn_all(py, &py.get_type::<SdfWarning>(), &warnings)?;
        Ok((m, warnings))
    }

    /// The model of an SDF file read by [`Model::read_sdf`], in the layout `kind`.
    fn of_sdf(
        m: rigid::io::sdf::SdfModel,
        warnings: Vec<String>,
        kind: Layout,
        path: PathBuf,
    ) -> Self {
        let mut core = ModelCore::new(m.model, kind == Layout::Pinocchio, warnings);
        core.source = Some(path);
        Self {
            inner: Arc::new(core),
        }
    }

    /// [`Model::from_urdf`] without `mimic`.
    pub(crate) fn load_urdf(
        py: Python<'_>,
        path: PathBuf,
        floating: bool,
        inertia: &str,
        layout: &str,
    ) -> PyResult<Self> {
        let kind = parse_layout("Model.from_urdf", layout)?;
        let pinocchio = kind == Layout::Pinocchio;
        let opts = urdf_options(floating, inertia, pinocchio)?;
        let shown = path.display().to_string();
        let (model, warnings) =
            urdf::load_urdf_with(&path, &opts).map_err(|e| urdf_error(&shown, &e))?;
        let warnings: Vec<String> = warnings.iter().map(|w| format!("{shown}: {w}")).collect();
        warn_all(py, &py.get_type::<UrdfWarning>(), &warnings)?;
        let mut core = ModelCore::new(model, pinocchio, warnings);
        if kind == Layout::Mujoco {
            core.mujoco = Some(MujocoLayout::new(&core.model));
        }
        core.source = Some(path);
        Ok(Self {
            inner: Arc::new(core),
        })
    }
}
