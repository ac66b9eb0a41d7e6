//! `rigid.Data`: the workspace of one model's algorithms, and its fields read in the model's
//! layout (Pinocchio's names: `oMi`, `M`, `nle`, `J`, `com`, ...), each a fresh array of what the
//! last algorithm that fills it wrote.

use crate::convert::{array1, array2};
use crate::model::{Model, ModelCore, Place};
use crate::pinocchio::{rows6, six_by_nv, three_by_nv, transforms, twist6, vec3s, wrench6};
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use rigid::spatial::Transform;
use std::sync::Arc;

/// A world pose `(R, p)` as numpy arrays.
type Pose<'py> = (Bound<'py, PyArray2<f64>>, Bound<'py, PyArray1<f64>>);

/// The workspace of the algorithms for one model (Pinocchio's `Data`): every buffer allocated
/// once. After `forward_kinematics`, `placement(name)` gives a joint's or frame's world pose.
/// Subclassable; pickled (and copied) as a fresh workspace of its model.
#[pyclass(module = "rigid", name = "Data", subclass)]
pub struct Data {
    pub inner: rigid::multibody::Data,
    /// The model it was made for (names, layout).
    pub model: Arc<ModelCore>,
    /// The Python model it was made for (pickled with it).
    pub owner: Py<Model>,
    /// Scratch buffers for the layout conversions.
    pub q: Vec<f64>,
    pub v: Vec<f64>,
    pub a: Vec<f64>,
}

impl Data {
    pub(crate) fn of(model: &Bound<'_, Model>) -> Self {
        let core = &model.borrow().inner;
        Self {
            inner: rigid::multibody::Data::new(&core.model),
            model: Arc::clone(core),
            owner: model.clone().unbind(),
            q: Vec::new(),
            v: Vec::new(),
            a: Vec::new(),
        }
    }
}

#[pymethods]
impl Data {
    /// A workspace for `model` (Pinocchio's `pin.Data(model)`).
    #[new]
    fn new(model: &Bound<'_, Model>) -> Self {
        Self::of(model)
    }

    /// Pickling and copying: `(type(self), (model,))`, a fresh workspace of the same model (the
    /// model is pickled with it, once however many data refer to it).
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyAny>> {
        let py = slf.py();
        let owner = slf.borrow().owner.clone_ref(py);
        (slf.get_type(), (owner,))
            .into_pyobject(py)
            .map(Bound::into_any)
    }

    /// `copy.copy`: a fresh workspace of the same model.
    fn __copy__<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyAny>> {
        let owner = slf.borrow().owner.clone_ref(slf.py());
        slf.get_type().call1((owner,))
    }

    /// `copy.deepcopy`: a fresh workspace of the same model, or of its copy when the model is
    /// copied in the same call (`copy.deepcopy((model, data))`).
    fn __deepcopy__<'py>(
        slf: &Bound<'py, Self>,
        memo: &Bound<'py, pyo3::types::PyDict>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let py = slf.py();
        let owner = slf.borrow().owner.clone_ref(py).into_bound(py);
        let key = owner.as_ptr() as usize;
        let model = memo.get_item(key)?.unwrap_or_else(|| owner.into_any());
        slf.get_type().call1((model,))
    }

    /// The world pose `(R, p)` of a joint's frame (as moved by the joint; Pinocchio's
    /// `data.oMi[model.getJointId(name)]`) or of a named frame (a link, a fixed joint;
    /// Pinocchio's `data.oMf[model.getFrameId(name)]`), from the last `forward_kinematics`:
    /// `R` (3, 3) a rotation matrix, `p` (3,) in metres, `x_world = R x_frame + p`.
    fn placement<'py>(&self, py: Python<'py>, name: &str) -> PyResult<Pose<'py>> {
        let core = &self.model;
        let t: Transform = match core.lookup("Data.placement", name)? {
            Place::Joint(j) => self.inner.placements[j.0],
            Place::Frame(f) => {
                let frame = &core.model.frames()[f.0];
                match frame.parent {
                    Some(p) => self.inner.placements[p.0] * frame.placement,
                    None => frame.placement,
                }
            }
        };
        let r = &t.rotation;
        let p = &t.translation;
        Ok((
            array2(py, 3, 3, |i, j| r[(i, j)]),
            array1(py, &[p.x, p.y, p.z]),
        ))
    }

    fn __repr__(&self) -> String {
        format!("rigid.Data(model='{}')", self.model.model.name())
    }

    // ---- the fields, in the model's layout (Pinocchio's names)

    /// Joints' world poses `oMi` (njoints, 4, 4).
    #[getter(oMi)]
    fn o_mi<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        transforms(py, &self.inner.placements)
    }

    /// Joints' poses in their parents' frames `liMi` (njoints, 4, 4).
    #[getter(liMi)]
    fn li_mi<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        transforms(py, &self.inner.parent_placements)
    }

    /// Frames' world poses (nframes, 4, 4; rigid's frames).
    #[getter(oMf)]
    fn o_mf<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        transforms(py, &self.inner.frame_placements)
    }

    /// Bodies' spatial velocities (njoints, 6; in the model's layout: linear first in Pinocchio's).
    #[getter(v)]
    fn v<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let core = &*self.model;
        rows6(
            py,
            self.inner
                .velocities
                .iter()
                .map(|t| twist6(core, t))
                .collect(),
        )
    }

    /// Bodies' spatial accelerations (njoints, 6).
    #[getter(a)]
    fn a<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let core = &*self.model;
        rows6(
            py,
            self.inner
                .accelerations
                .iter()
                .map(|t| twist6(core, t))
                .collect(),
        )
    }

    /// Bodies' spatial accelerations with gravity (njoints, 6).
    #[getter(a_gf)]
    fn a_gf<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let core = &*self.model;
        rows6(
            py,
            self.inner
                .accelerations_gravity
                .iter()
                .map(|t| twist6(core, t))
                .collect(),
        )
    }

    /// The wrenches the joints transmit (njoints, 6).
    #[getter(f)]
    fn f<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let core = &*self.model;
        rows6(
            py,
            self.inner.forces.iter().map(|w| wrench6(core, w)).collect(),
        )
    }

    /// The last `rnea`'s torques (nv,).
    #[getter(tau)]
    fn tau<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let core = &*self.model;
        Ok(core.v_out(py, self.inner.tau.as_slice()).into_any())
    }

    /// The last nonlinear effects `c + g` (nv,).
    #[getter(nle)]
    fn nle<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let core = &*self.model;
        Ok(core.v_out(py, self.inner.nle.as_slice()).into_any())
    }

    /// The last generalized gravity (nv,).
    #[getter(g)]
    fn g<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let core = &*self.model;
        Ok(core.v_out(py, self.inner.g.as_slice()).into_any())
    }

    /// The last `aba`'s accelerations (nv,).
    #[getter(ddq)]
    fn ddq<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let core = &*self.model;
        Ok(core.v_out(py, self.inner.ddq.as_slice()).into_any())
    }

    /// The last `crba`'s mass matrix (nv, nv).
    #[getter(M)]
    fn mass_matrix<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let core = &*self.model;
        Ok(core.matrix_out(py, &self.inner.mass_matrix).into_any())
    }

    /// The last inverse mass matrix (nv, nv).
    #[getter(Minv)]
    fn minv<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let core = &*self.model;
        Ok(core.matrix_out(py, &self.inner.minv).into_any())
    }

    /// The last Coriolis matrix (nv, nv).
    #[getter(C)]
    fn coriolis<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let core = &*self.model;
        Ok(core.matrix_out(py, &self.inner.coriolis).into_any())
    }

    /// The last RNEA derivative with respect to q (nv, nv).
    #[getter(dtau_dq)]
    fn dtau_dq<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let core = &*self.model;
        Ok(core
            .matrix_out(py, &self.inner.derivatives.dtau_dq)
            .into_any())
    }

    /// The last RNEA derivative with respect to v (nv, nv).
    #[getter(dtau_dv)]
    fn dtau_dv<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let core = &*self.model;
        Ok(core
            .matrix_out(py, &self.inner.derivatives.dtau_dv)
            .into_any())
    }

    /// The last ABA derivative with respect to q (nv, nv).
    #[getter(ddq_dq)]
    fn ddq_dq<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let core = &*self.model;
        Ok(core
            .matrix_out(py, &self.inner.derivatives.dqdd_dq)
            .into_any())
    }

    /// The last ABA derivative with respect to v (nv, nv).
    #[getter(ddq_dv)]
    fn ddq_dv<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let core = &*self.model;
        Ok(core
            .matrix_out(py, &self.inner.derivatives.dqdd_dv)
            .into_any())
    }

    /// The joints' stacked world Jacobian (6, nv).
    #[getter(J)]
    fn jacobian<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let core = &*self.model;
        Ok(six_by_nv(py, core, &self.inner.jacobian).into_any())
    }

    /// The centre of mass Jacobian (3, nv).
    #[getter(Jcom)]
    fn jcom<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let core = &*self.model;
        Ok(three_by_nv(py, core, &self.inner.com_jacobian).into_any())
    }

    /// The centroidal momentum matrix (6, nv).
    #[getter(Ag)]
    fn ag<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let core = &*self.model;
        Ok(six_by_nv(py, core, &self.inner.centroidal_map).into_any())
    }

    /// The centroidal momentum (6,).
    #[getter(hg)]
    fn hg<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let core = &*self.model;
        Ok(array1(py, &wrench6(core, &self.inner.centroidal_momentum)).into_any())
    }

    /// The centre of mass (3,).
    #[getter(com)]
    fn com<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        Ok(array1(py, self.inner.com.as_slice()).into_any())
    }

    /// The centre of mass velocity (3,).
    #[getter(vcom)]
    fn vcom<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        Ok(array1(py, self.inner.com_velocity.as_slice()).into_any())
    }

    /// The centre of mass acceleration (3,).
    #[getter(acom)]
    fn acom<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        Ok(array1(py, self.inner.com_acceleration.as_slice()).into_any())
    }

    /// The total mass (kg).
    #[getter(mass)]
    fn mass<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        Ok(self.inner.mass.into_pyobject(py)?.into_any())
    }

    /// Each subtree's centre of mass (njoints, 3).
    #[getter(subtree_com)]
    fn subtree_com<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        vec3s(py, &self.inner.subtree_coms)
    }

    /// Each subtree's centre of mass velocity (njoints, 3).
    #[getter(subtree_vcom)]
    fn subtree_vcom<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        vec3s(py, &self.inner.subtree_com_velocities)
    }

    /// Each subtree's centre of mass acceleration (njoints, 3).
    #[getter(subtree_acom)]
    fn subtree_acom<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        vec3s(py, &self.inner.subtree_com_accelerations)
    }

    /// Each subtree's mass (njoints,).
    #[getter(subtree_mass)]
    fn subtree_mass<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        Ok(array1(py, &self.inner.subtree_masses).into_any())
    }

    /// The last configuration an algorithm was given (the model's layout).
    #[getter(q_in)]
    fn q_in<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let core = &*self.model;
        Ok(core.q_out(py, &self.q).into_any())
    }

    /// The last velocity an algorithm was given (the model's layout).
    #[getter(v_in)]
    fn v_in<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let core = &*self.model;
        Ok(core.v_out(py, &self.v).into_any())
    }

    /// The centroidal inertia `(mass, centre of mass (3,), inertia about it (3, 3))`.
    #[getter(Ig)]
    fn ig<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let g = &self.inner.centroidal_inertia;
        let i = g.inertia_com();
        let i = i.matrix();
        let c = g.com();
        Ok((
            g.mass(),
            array1(py, c.as_slice()),
            array2(py, 3, 3, |r, k| i[(r, k)]),
        )
            .into_pyobject(py)?
            .into_any())
    }
}
