// Shared declarations of the timing program (see timings.cpp). The algorithms are
// split over three translation units (timings-kin.cpp, timings-crba.cpp,
// timings-aba.cpp) so that Pinocchio's heavy template instantiation compiles on
// several cores.
#pragma once

#include <pinocchio/multibody.hpp>

#include <chrono>
#include <vector>

namespace bench
{
  using pinocchio::Data;
  using pinocchio::Model;
  using Vec = Eigen::VectorXd;
  using CRef = Eigen::Ref<const Eigen::VectorXd>;

  struct States
  {
    std::vector<Vec> q, v, a, tau;
  };

  // Defeats dead-code elimination: one element of each result is folded in per call.
  extern volatile double g_sink;

  // One timed pass: the algorithm on every state in turn, the lambda inlined into
  // the loop (no indirect call per state). Returns ns per call.
  template<typename F>
  inline double timed_pass(F && call, int nstates)
  {
    double acc = 0.0;
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < nstates; ++i)
      acc += call(i);
    const auto t1 = std::chrono::steady_clock::now();
    g_sink = g_sink + acc;
    return std::chrono::duration<double, std::nano>(t1 - t0).count() / double(nstates);
  }

  // algorithm k of ALGO_KEYS, one timed pass over the states
  double run_kinematics(size_t k, const Model & model, Data & data, const States & s, int nstates);
  double run_crba(size_t k, const Model & model, Data & data, const States & s, int nstates);
  double run_aba(size_t k, const Model & model, Data & data, const States & s, int nstates);
  double run_derivatives(size_t k, const Model & model, Data & data, const States & s, int nstates);
  // RNEA once (for the load check)
  Vec rnea_once(const Model & model, const Vec & q, const Vec & v, const Vec & a);

  constexpr const char * ALGO_KEYS[] = {
    "forward_kinematics", "forward_kinematics_qva", "jacobians", "rnea",
    "gravity", "nonlinear_effects", "crba_local", "crba_world",
    "aba_local", "aba_world", "minverse", "cholesky_fd",
    "rnea_derivatives", "aba_derivatives"};
  // keys 0-5 live in timings-kin.cpp, 6, 7, 11 in timings-crba.cpp, 8-10 in timings-aba.cpp,
  // 12-13 in timings-deriv.cpp
  constexpr size_t N_ALGOS = sizeof(ALGO_KEYS) / sizeof(ALGO_KEYS[0]);
} // namespace bench
