// Kinematics and inverse dynamics timings (see timings.cpp).
#include "timings.hpp"

#include <pinocchio/algorithm/kinematics.hpp>
#include <pinocchio/algorithm/jacobian.hpp>
#include <pinocchio/algorithm/rnea.hpp>

namespace bench
{
  double run_kinematics(size_t k, const Model & model, Data & data, const States & s, int nstates)
  {
    using pinocchio::Convention;
    auto pass = [&](auto && call) { return timed_pass(call, nstates); };
    switch (k)
    {
    case 0:
      return pass([&](int i) {
        pinocchio::forwardKinematics(model, data, CRef(s.q[i]));
        return data.oMi.back().translation()[0];
      });
    case 1:
      return pass([&](int i) {
        pinocchio::forwardKinematics(model, data, CRef(s.q[i]), CRef(s.v[i]), CRef(s.a[i]));
        return data.a.back().linear()[0];
      });
    case 2:
      return pass([&](int i) {
        pinocchio::computeJointJacobians(model, data, CRef(s.q[i]));
        return data.J(0, model.nv - 1);
      });
    case 3:
      return pass([&](int i) {
        pinocchio::rnea(model, data, CRef(s.q[i]), CRef(s.v[i]), CRef(s.a[i]));
        return data.tau[0];
      });
    case 4:
      return pass([&](int i) {
        pinocchio::computeGeneralizedGravity(model, data, CRef(s.q[i]));
        return data.g[0];
      });
    case 5:
      return pass([&](int i) {
        pinocchio::nonLinearEffects(model, data, CRef(s.q[i]), CRef(s.v[i]));
        return data.nle[0];
      });
    }
    return -1.0;
  }

  Vec rnea_once(const Model & model, const Vec & q, const Vec & v, const Vec & a)
  {
    Data data(model);
    return pinocchio::rnea(model, data, CRef(q), CRef(v), CRef(a));
  }
} // namespace bench
