// Analytical derivatives of inverse and forward dynamics (see timings.cpp):
// computeRNEADerivatives (dtau/dq, dtau/dv and M, upper triangle) and
// computeABADerivatives (ddq/dq, ddq/dv and Minv, symmetrised), Carpentier & Mansard 2018.
#include "timings.hpp"

#include <pinocchio/algorithm/rnea-derivatives.hpp>
#include <pinocchio/algorithm/aba-derivatives.hpp>

namespace bench
{
  double run_derivatives(size_t k, const Model & model, Data & data, const States & s, int nstates)
  {
    auto pass = [&](auto && call) { return timed_pass(call, nstates); };
    switch (k)
    {
    case 12:
      return pass([&](int i) {
        pinocchio::computeRNEADerivatives(model, data, CRef(s.q[i]), CRef(s.v[i]), CRef(s.a[i]));
        return data.dtau_dq(0, 0);
      });
    case 13:
      return pass([&](int i) {
        pinocchio::computeABADerivatives(model, data, CRef(s.q[i]), CRef(s.v[i]), CRef(s.tau[i]));
        return data.ddq_dq(0, 0);
      });
    }
    return -1.0;
  }
} // namespace bench
