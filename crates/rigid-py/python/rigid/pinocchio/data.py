"""Pinocchio's ``Data``: the workspace of one model, its fields (``oMi``, ``oMf``, ``M``, ``nle``,
``J``, ...) read from rigid's buffers in Pinocchio's layout when asked for."""

import numpy as np

from .. import rigid as _r
from .spatial import SE3, Force, Inertia, Motion

__all__ = ["Data"]

# ---------------------------------------------------------------- data

# Pinocchio's Data fields that the layer does not fill (reading one says so)
_DATA_UNSUPPORTED = {
    "oYcrb", "Ycrb", "Yaba", "oYaba", "dJ", "ov", "oa", "oa_gf", "of", "oh", "h", "dAdq",
    "dAdv", "dFda", "dFdq", "dFdv", "dHdq", "dAg", "dhg", "Fcrb", "B", "D", "U", "Ivx", "vxI",
    "oK", "oL", "iMf", "lambda_c", "lambda_c_prox", "impulse_c", "dq_after", "contact_chol",
    "constraint_chol", "jointTorqueRegressor", "kineticEnergyRegressor",
    "potentialEnergyRegressor", "staticRegressor", "dac_da", "dac_dq", "dac_dv", "dvc_dq",
    "osim", "primal_dual_contact_solution",
    "primal_rhs_contact", "lastChild", "nvSubtree", "parents_fromRow", "supports_fromRow",
    "start_idx_v_fromRow", "end_idx_v_fromRow", "nvSubtree_fromRow", "q_in", "v_in", "a_in",
    "tau_in", "of_augmented", "oYaba_augmented", "mimic_subtree_joint",
}


class _Items:
    """A read-only sequence built on access (``data.oMi``, ``data.v``, ...)."""

    __slots__ = ("_n", "_get")

    def __init__(self, n, get):
        self._n, self._get = n, get

    def __len__(self):
        return self._n

    def __getitem__(self, i):
        if isinstance(i, slice):
            return [self._get(k) for k in range(*i.indices(self._n))]
        if i < 0:
            i += self._n
        if not 0 <= i < self._n:
            raise IndexError(f"index {i} out of range ({self._n})")
        return self._get(i)

    def __iter__(self):
        return (self._get(k) for k in range(self._n))

    def tolist(self):
        return list(self)

    def __repr__(self):
        return repr(list(self))


def _se3_items(H):
    return _Items(len(H), lambda i: SE3(H[i]))


class Data(_r.Data):
    """The workspace of one model with Pinocchio's fields, read from rigid's buffers in
    Pinocchio's layout when asked for (each field is what the last algorithm that fills it
    wrote, as in Pinocchio)."""

    def __init__(self, model):
        self._model = model
        self.kinetic_energy = 0.0
        self.potential_energy = 0.0
        self._com_local = False

    def _a(self, name):
        """The field ``name`` as ``rigid.Data`` reads it (an array in the model's layout)."""
        return getattr(_r.Data, name).__get__(self)

    @property
    def mechanical_energy(self):
        return self.kinetic_energy + self.potential_energy

    def _with_universe(self, name, zero):
        rows = self._a(name)
        return np.concatenate([zero[None], rows]) if len(rows) else zero[None]

    @property
    def oMi(self):
        return _se3_items(self._with_universe("oMi", np.eye(4)))

    @property
    def liMi(self):
        return _se3_items(self._with_universe("liMi", np.eye(4)))

    @property
    def oMf(self):
        oMi, oMf = self._a("oMi"), self._a("oMf")
        srcs = [s for _, s in self._model._frames]

        def get(i):
            s = srcs[i]
            if s[0] == "joint":
                return SE3(oMi[s[1]])
            if s[0] == "frame":
                return SE3(oMf[s[1]])
            return SE3()

        return _Items(len(srcs), get)

    def _motions(self, name, cls):
        rows = self._with_universe(name, np.zeros(6))
        return _Items(len(rows), lambda i: cls(rows[i]))

    v = property(lambda s: s._motions("v", Motion))
    a = property(lambda s: s._motions("a", Motion))
    f = property(lambda s: s._motions("f", Force))

    @property
    def a_gf(self):
        """The accelerations with gravity as the world's (``a_gf[0] = -g``)."""
        zero = np.concatenate([-_r.Model.gravity.__get__(self._model), np.zeros(3)])
        rows = self._with_universe("a_gf", zero)
        return _Items(len(rows), lambda i: Motion(rows[i]))

    # the constrained or impulse dynamics' derivatives when they were the last computed
    ddq_dq = property(lambda s: s._derivative("ddq_dq", "ddq_dq"))
    ddq_dv = property(lambda s: s._derivative("ddq_dv", "ddq_dv"))
    ddq_dtau = property(lambda s: s._derivative("ddq_dtau", "Minv"))

    def _derivative(self, name, unconstrained):
        c = self.__dict__.get("_constrained")
        return c[name] if c is not None and name in c else self._a(unconstrained)

    @property
    def hg(self):
        return Force(self._a("hg"))

    @property
    def Ig(self):
        m, c, I = self._a("Ig")
        return Inertia(m, c, I)

    def _subtree(self, whole, sub, point):
        """``[whole] + subtrees``: world frame after ``jacobianCenterOfMass``, each joint's frame
        after ``centerOfMass`` (Pinocchio's conventions)."""
        rows = self._a(sub)
        if self._com_local and len(rows):
            oMi = self._a("oMi")
            R, p = oMi[:, :3, :3], oMi[:, :3, 3]
            x = rows - p if point else rows
            rows = np.einsum("nji,nj->ni", R, x)
        return [self._a(whole)] + [r.copy() for r in rows]

    com = property(lambda s: s._subtree("com", "subtree_com", True))
    vcom = property(lambda s: s._subtree("vcom", "subtree_vcom", False))
    acom = property(lambda s: s._subtree("acom", "subtree_acom", False))

    @property
    def mass(self):
        return [float(self._a("mass"))] + self._a("subtree_mass").tolist()

    def __getattr__(self, name):
        if name in _DATA_UNSUPPORTED:
            raise NotImplementedError(
                f"data.{name} is not filled by rigid.pinocchio; the fields it provides are oMi, "
                "oMf, liMi, v, a, a_gf, f, tau, nle, g, ddq, M, Minv, C, J, Jcom, Ag, hg, Ig, "
                "com, vcom, acom, mass, dtau_dq, dtau_dv, ddq_dq, ddq_dv, kinetic_energy, "
                "potential_energy")
        raise AttributeError(f"'Data' object has no attribute '{name}'")

    def __reduce__(self):
        return (Data, (self._model,))

    def __copy__(self):
        return Data(self._model)

    def __deepcopy__(self, memo):
        return Data(memo.get(id(self._model), self._model))

    def copy(self):
        return Data(self._model)

    def __repr__(self):
        return f"rigid.pinocchio.Data(model='{self._model.name}')"
