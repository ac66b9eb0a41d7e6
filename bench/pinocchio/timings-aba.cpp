// Articulated-body forward dynamics and M^-1 timings (see timings.cpp).
#include "timings.hpp"

#include <pinocchio/algorithm/aba.hpp>

namespace bench
{
  double run_aba(size_t k, const Model & model, Data & data, const States & s, int nstates)
  {
    using pinocchio::Convention;
    auto pass = [&](auto && call) { return timed_pass(call, nstates); };
    switch (k)
    {
    case 8:
      return pass([&](int i) {
        pinocchio::aba(
          model, data, CRef(s.q[i]), CRef(s.v[i]), CRef(s.tau[i]), Convention::LOCAL);
        return data.ddq[0];
      });
    case 9:
      return pass([&](int i) {
        pinocchio::aba(
          model, data, CRef(s.q[i]), CRef(s.v[i]), CRef(s.tau[i]), Convention::WORLD);
        return data.ddq[0];
      });
    case 10:
#ifdef PINOCCHIO_ENABLE_TEMPLATE_INSTANTIATION
      // computeMinverse is not in libpinocchio_default.so: this build would compile the very
      // same code as the header build (minutes of compile time), so it leaves it to that one.
      return -1.0;
#else
      return pass([&](int i) {
        pinocchio::computeMinverse(model, data, CRef(s.q[i]));
        return data.Minv(0, model.nv - 1);
      });
#endif
    }
    return -1.0;
  }
} // namespace bench
