// Mass matrix (CRBA) and Cholesky forward dynamics timings (see timings.cpp).
#include "timings.hpp"

#include <pinocchio/algorithm/rnea.hpp>
#include <pinocchio/algorithm/crba.hpp>
#include <pinocchio/algorithm/cholesky.hpp>

namespace bench
{
  double run_crba(size_t k, const Model & model, Data & data, const States & s, int nstates)
  {
    using pinocchio::Convention;
    auto pass = [&](auto && call) { return timed_pass(call, nstates); };
    switch (k)
    {
    case 6:
      return pass([&](int i) {
        pinocchio::crba(model, data, CRef(s.q[i]), Convention::LOCAL);
        return data.M(0, model.nv - 1);
      });
    case 7:
      return pass([&](int i) {
        pinocchio::crba(model, data, CRef(s.q[i]), Convention::WORLD);
        return data.M(0, model.nv - 1);
      });
    case 11:
      // forward dynamics the textbook way: nle, M (CRBA), sparse Cholesky
      // factorisation of M, then ddq = M^-1 (tau - nle)
      return pass([&](int i) {
        pinocchio::nonLinearEffects(model, data, CRef(s.q[i]), CRef(s.v[i]));
        pinocchio::crba(model, data, CRef(s.q[i]), Convention::WORLD);
        pinocchio::cholesky::decompose(model, data);
        data.ddq = s.tau[i] - data.nle;
        pinocchio::cholesky::solve(model, data, data.ddq);
        return data.ddq[0];
      });
    }
    return -1.0;
  }
} // namespace bench
