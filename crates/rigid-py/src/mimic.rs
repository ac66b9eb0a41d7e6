//! `rigid.MimicModel`: a robot whose mimic joints follow their sources
//! (`rigid::multibody::MimicModel`), evaluated in the reduced coordinates, as Pinocchio's
//! `buildModelFromUrdf(path, mimic=True)`; made by `Model.from_urdf(path, mimic=True)`.

use crate::convert::{array1, array2, value_error, vector};
use crate::model::{parse_layout, urdf_error, urdf_options, warn_all, UrdfWarning};
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use rigid::interop::{Layout, PinocchioLayout};
use rigid::io::urdf;
use rigid::multibody::{self as mb, JointId, MimicData};
use std::path::PathBuf;
use std::sync::Mutex;

/// A robot whose mimic joints follow their sources, `q_m = multiplier · q_s + offset`, with no
/// coordinate of their own: `nq`, `nv` and every vector and matrix leave them out (Pinocchio's
/// `mimic=True`). `rnea`, `crba`, `nle` are the full model's projected on the
/// reduced coordinates (`τ = Gᵀ τ_full`, `M = Gᵀ M_full G`); `aba` solves `M q̈ = τ − nle`.
/// `expand_q` and `expand_v` return the full model's vectors in rigid's layout.
/// In `layout="pinocchio"`, vectors are in Pinocchio's order and coordinates.
#[pyclass(module = "rigid", frozen)]
pub struct MimicModel {
    inner: mb::MimicModel,
    layout: Option<PinocchioLayout>,
    data: Mutex<MimicData>,
}

impl MimicModel {
    /// `Model.from_urdf(path, ..., mimic=True)`.
    pub(crate) fn from_urdf(
        py: Python<'_>,
        path: PathBuf,
        floating: bool,
        inertia: &str,
        layout: &str,
    ) -> PyResult<Self> {
        const F: &str = "Model.from_urdf";
        let kind = parse_layout(F, layout)?;
        if kind == Layout::Mujoco {
            return Err(value_error(
                F,
                "mimic=True with layout=\"mujoco\": not available (MuJoCo keeps a coordinate for \
                 every joint); use layout=\"rigid\" or \"pinocchio\"",
            ));
        }
        let pinocchio = kind == Layout::Pinocchio;
        let opts = urdf_options(floating, inertia, pinocchio)?;
        let shown = path.display().to_string();
        let (mm, warnings) =
            urdf::load_urdf_mimic(&path, &opts).map_err(|e| urdf_error(&shown, &e))?;
        let warnings: Vec<String> = warnings.iter().map(|w| format!("{shown}: {w}")).collect();
        warn_all(py, &py.get_type::<UrdfWarning>(), &warnings)?;
        Ok(Self::new(mm, pinocchio))
    }

    /// `Model.from_mjcf`/`from_sdf(path, ..., mimic=True)`: `model` with `mimics` as couplings,
    /// in the layout `kind` (MuJoCo's refused: it keeps a coordinate for every joint).
    pub(crate) fn coupled(
        func: &str,
        shown: &str,
        kind: Layout,
        model: rigid::multibody::Model,
        mimics: &[mb::Mimic],
    ) -> PyResult<Self> {
        if kind == Layout::Mujoco {
            return Err(value_error(
                func,
                "mimic=True with layout=\"mujoco\": not available (MuJoCo keeps a coordinate for \
                 every joint); use layout=\"rigid\" or \"pinocchio\"",
            ));
        }
        let mm = mb::MimicModel::new(model, mimics)
            .map_err(|e| value_error(func, format!("{shown}: {e}")))?;
        Ok(Self::new(mm, kind == Layout::Pinocchio))
    }

    pub(crate) fn new(inner: mb::MimicModel, pinocchio: bool) -> Self {
        let layout = pinocchio.then(|| PinocchioLayout::of_mimic(&inner));
        let data = Mutex::new(MimicData::new(&inner));
        Self {
            inner,
            layout,
            data,
        }
    }

    fn q(&self, x: &Bound<'_, PyAny>, func: &str) -> PyResult<Vec<f64>> {
        let n = self
            .layout
            .as_ref()
            .map_or(self.inner.nq(), PinocchioLayout::nq);
        let x = vector(x, func, "q", "nq", n)?;
        let mut q = x.as_slice().to_vec();
        if let Some(l) = &self.layout {
            q = vec![0.0; self.inner.nq()];
            l.q_from_pinocchio(x.as_slice(), &mut q)
                .map_err(|e| value_error(func, e))?;
        }
        Ok(q)
    }

    fn v(&self, x: &Bound<'_, PyAny>, func: &str, name: &str) -> PyResult<Vec<f64>> {
        let x = vector(x, func, name, "nv", self.inner.nv())?;
        let mut v = x.as_slice().to_vec();
        if let Some(l) = &self.layout {
            l.permute_v(x.as_slice(), &mut v);
        }
        Ok(v)
    }

    fn v_out<'py>(&self, py: Python<'py>, x: &[f64]) -> Bound<'py, PyArray1<f64>> {
        match &self.layout {
            Some(l) => {
                let mut y = vec![0.0; x.len()];
                l.permute_v(x, &mut y);
                array1(py, &y)
            }
            None => array1(py, x),
        }
    }

    fn m_out<'py>(&self, py: Python<'py>, m: &nalgebra::DMatrix<f64>) -> Bound<'py, PyArray2<f64>> {
        let p = |k: usize| self.layout.as_ref().map_or(k, |l| l.v_index(k));
        array2(py, m.nrows(), m.ncols(), |r, c| m[(p(r), p(c))])
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, MimicData> {
        self.data
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
    }
}

#[pymethods]
impl MimicModel {
    /// Number of configuration coordinates (mimic joints have none).
    #[getter]
    fn nq(&self) -> usize {
        self.layout
            .as_ref()
            .map_or(self.inner.nq(), PinocchioLayout::nq)
    }
    /// Number of degrees of freedom (mimic joints have none).
    #[getter]
    fn nv(&self) -> usize {
        self.inner.nv()
    }
    /// The couplings, `(joint, source, multiplier, offset)` by name, each to a joint that is no
    /// mimic (a chain composed).
    #[getter]
    fn mimics(&self) -> Vec<(String, String, f64, f64)> {
        let m = self.inner.model();
        self.inner
            .mimics()
            .iter()
            .map(|c| {
                let name = |j: JointId| m.joint(j).name.clone();
                (name(c.joint), name(c.source), c.multiplier, c.offset)
            })
            .collect()
    }
    /// The joint names (all of them, the mimics included), in the model's order.
    #[getter]
    fn names(&self) -> Vec<String> {
        self.inner
            .model()
            .joints()
            .iter()
            .map(|j| j.name.clone())
            .collect()
    }
    /// The neutral configuration.
    fn neutral<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.q_out(py, &self.inner.neutral())
    }
    /// The full configuration `E(q)` (rigid's layout of the full model): each mimic coordinate
    /// `multiplier · q_source + offset`.
    fn expand_q<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let q = self.q(q, "MimicModel.expand_q")?;
        let mut full = vec![0.0; self.inner.model().nq()];
        self.inner.expand_q(&q, &mut full);
        Ok(array1(py, &full))
    }
    /// The full velocity `G v` (rigid's layout of the full model).
    fn expand_v<'py>(
        &self,
        py: Python<'py>,
        v: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let v = self.v(v, "MimicModel.expand_v", "v")?;
        let mut full = vec![0.0; self.inner.model().nv()];
        self.inner.expand_v(&v, &mut full);
        Ok(array1(py, &full))
    }
    /// Inverse dynamics `τ = Gᵀ ID(E(q), G v, G a)`.
    fn rnea<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        v: &Bound<'py, PyAny>,
        a: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        const F: &str = "MimicModel.rnea";
        let (q, v, a) = (self.q(q, F)?, self.v(v, F, "v")?, self.v(a, F, "a")?);
        let mut md = self.lock();
        let tau = self
            .inner
            .rnea(&mut md, &q, &v, &a)
            .map_err(|e| value_error(F, e))?;
        Ok(self.v_out(py, tau.as_slice()))
    }
    /// The mass matrix `M = Gᵀ M_full G`.
    fn crba<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        const F: &str = "MimicModel.crba";
        let q = self.q(q, F)?;
        let mut md = self.lock();
        let m = self
            .inner
            .crba(&mut md, &q)
            .map_err(|e| value_error(F, e))?;
        Ok(self.m_out(py, m))
    }
    /// `c + g`, Coriolis, centrifugal and gravity forces.
    fn nle<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        v: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        const F: &str = "MimicModel.nle";
        let (q, v) = (self.q(q, F)?, self.v(v, F, "v")?);
        let mut md = self.lock();
        let b = self
            .inner
            .nonlinear_effects(&mut md, &q, &v)
            .map_err(|e| value_error(F, e))?;
        Ok(self.v_out(py, b.as_slice()))
    }
    /// Forward dynamics `q̈ = M⁻¹ (τ − c − g)`.
    fn aba<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        v: &Bound<'py, PyAny>,
        tau: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        const F: &str = "MimicModel.aba";
        let (q, v, t) = (self.q(q, F)?, self.v(v, F, "v")?, self.v(tau, F, "tau")?);
        let mut md = self.lock();
        let a = self
            .inner
            .aba(&mut md, &q, &v, &t)
            .map_err(|e| value_error(F, e))?;
        Ok(self.v_out(py, a.as_slice()))
    }
    /// `(∂τ/∂q, ∂τ/∂v, M)` at `(q, v, a)` (`q` along `q ⊕ δ`).
    #[allow(clippy::type_complexity)]
    fn rnea_derivatives<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        v: &Bound<'py, PyAny>,
        a: &Bound<'py, PyAny>,
    ) -> PyResult<(
        Bound<'py, PyArray2<f64>>,
        Bound<'py, PyArray2<f64>>,
        Bound<'py, PyArray2<f64>>,
    )> {
        const F: &str = "MimicModel.rnea_derivatives";
        let (q, v, a) = (self.q(q, F)?, self.v(v, F, "v")?, self.v(a, F, "a")?);
        let mut md = self.lock();
        let d = self
            .inner
            .rnea_derivatives(&mut md, &q, &v, &a)
            .map_err(|e| value_error(F, e))?;
        Ok((
            self.m_out(py, d.dtau_dq),
            self.m_out(py, d.dtau_dv),
            self.m_out(py, d.dtau_da),
        ))
    }
    /// `(∂q̈/∂q, ∂q̈/∂v, M⁻¹)` at `(q, v, tau)`.
    #[allow(clippy::type_complexity)]
    fn aba_derivatives<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        v: &Bound<'py, PyAny>,
        tau: &Bound<'py, PyAny>,
    ) -> PyResult<(
        Bound<'py, PyArray2<f64>>,
        Bound<'py, PyArray2<f64>>,
        Bound<'py, PyArray2<f64>>,
    )> {
        const F: &str = "MimicModel.aba_derivatives";
        let (q, v, t) = (self.q(q, F)?, self.v(v, F, "v")?, self.v(tau, F, "tau")?);
        let mut md = self.lock();
        let d = self
            .inner
            .aba_derivatives(&mut md, &q, &v, &t)
            .map_err(|e| value_error(F, e))?;
        Ok((
            self.m_out(py, d.dqdd_dq),
            self.m_out(py, d.dqdd_dv),
            self.m_out(py, d.dqdd_dtau),
        ))
    }
    /// The Jacobian (6 x nv) of the frame (or joint) called `frame` in `reference` (as `rigid.jacobian`'s
    /// `frame`; default world-aligned): rows `(ω, v)`, or `(v, ω)` in Pinocchio's layout.
    #[pyo3(signature = (q, frame, reference = None))]
    fn frame_jacobian<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        frame: &str,
        reference: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        const F: &str = "MimicModel.frame_jacobian";
        let q = self.q(q, F)?;
        let rf = reference.map_or(
            Ok(mb::ReferenceFrame::WorldAligned),
            crate::dynamics::reference_frame,
        )?;
        // a named frame, else a joint's moved frame (as rigid.jacobian)
        let model = self.inner.model();
        let mut md = self.lock();
        let j = match (model.frame_id(frame), model.joint_id(frame)) {
            (Ok(id), _) => self.inner.frame_jacobian(&mut md, &q, id, rf),
            (Err(_), Some(id)) => self.inner.joint_jacobian(&mut md, &q, id, rf),
            (Err(e), None) => return Err(value_error(F, e)),
        }
        .map_err(|e| value_error(F, e))?;
        // rows (ω, v) in rigid's layout; (v, ω) and columns permuted in Pinocchio's
        let p = |k: usize| self.layout.as_ref().map_or(k, |l| l.v_index(k));
        let shift = if self.layout.is_some() { 3 } else { 0 };
        Ok(array2(py, 6, j.ncols(), |r, c| j[((r + shift) % 6, p(c))]))
    }

    fn __repr__(&self) -> String {
        let m = self.inner.model();
        format!(
            "MimicModel('{}': nq={}, nv={}, {} mimic joints of {})",
            m.name(),
            self.nq(),
            self.inner.nv(),
            self.inner.mimics().len(),
            m.njoints()
        )
    }
}

impl MimicModel {
    fn q_out<'py>(&self, py: Python<'py>, q: &[f64]) -> Bound<'py, PyArray1<f64>> {
        match &self.layout {
            Some(l) => {
                let mut out = vec![0.0; l.nq()];
                l.q_to_pinocchio(q, &mut out);
                array1(py, &out)
            }
            None => array1(py, q),
        }
    }
}
