// Pinocchio timing program for rigid's side-by-side comparison (bench/compare.py).
//
// Loads models written by export_models.py (plain joint trees), draws 1000
// random states per model (q from randomConfiguration within finite bounds,
// v, a, tau uniform in [-1, 1]), and times each algorithm as one pass over all
// states, cycling through them so that branch prediction and caches are not
// flattered by a repeated input. A run is REPS passes per algorithm; the
// algorithms are interleaved inside each repetition so that machine noise
// spreads over all of them. Reported: median over the passes, in ns per call.
//
// Output: one JSON object per model and line:
//   {"model", "nq", "nv", "ns_per_call": {...}, "build": "..."}
//
// Usage: timings [--reps N] [--states N] [--build LABEL] NAME=FILE.model ...
//
// All calls pass Eigen::Ref<const Eigen::VectorXd> arguments: those are the
// argument types Pinocchio instantiates in libpinocchio_default.so, so a build
// with -DPINOCCHIO_ENABLE_TEMPLATE_INSTANTIATION really calls the wheel's
// precompiled algorithms, and a build without it compiles them here.

#include "timings.hpp"

#include <pinocchio/algorithm/joint-configuration.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

using bench::CRef;
using bench::Data;
using bench::Model;
using bench::States;
using bench::Vec;

volatile double bench::g_sink = 0.0;

namespace
{
  States draw_states(const Model & model, int n)
  {
    States s;
    s.q.reserve(n);
    s.v.reserve(n);
    s.a.reserve(n);
    s.tau.reserve(n);
    for (int i = 0; i < n; ++i)
    {
      s.q.push_back(pinocchio::randomConfiguration(model));
      s.v.push_back(Vec::Random(model.nv));
      s.a.push_back(Vec::Random(model.nv));
      s.tau.push_back(Vec::Random(model.nv));
    }
    return s;
  }

  Vec read_vec(std::istream & in, long n)
  {
    Vec x(n);
    for (long i = 0; i < n; ++i)
      in >> x[i];
    return x;
  }

  // Rebuilds the Model written by export_models.py (write_plain) with
  // Model::addJoint / appendBodyToJoint, then checks RNEA against the torque
  // Pinocchio's Python module computed on the same state (returns the max error).
  double load_plain(const std::string & path, Model & model)
  {
    std::ifstream in(path);
    if (!in)
      throw std::runtime_error("cannot open " + path);
    int nq, nv, njoints;
    in >> nq >> nv >> njoints;
    for (int j = 1; j < njoints; ++j)
    {
      std::string kind;
      size_t parent;
      Eigen::Vector3d axis, p;
      Eigen::Matrix3d R;
      double mass, I[6];
      Eigen::Vector3d lever;
      in >> kind >> parent >> axis[0] >> axis[1] >> axis[2];
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
          in >> R(r, c);
      in >> p[0] >> p[1] >> p[2] >> mass >> lever[0] >> lever[1] >> lever[2];
      for (double & x : I)
        in >> x;
      pinocchio::JointModel jm;
      if (kind == "RX")
        jm = pinocchio::JointModelRX();
      else if (kind == "RY")
        jm = pinocchio::JointModelRY();
      else if (kind == "RZ")
        jm = pinocchio::JointModelRZ();
      else if (kind == "PX")
        jm = pinocchio::JointModelPX();
      else if (kind == "PY")
        jm = pinocchio::JointModelPY();
      else if (kind == "PZ")
        jm = pinocchio::JointModelPZ();
      else if (kind == "RU")
        jm = pinocchio::JointModelRevoluteUnaligned(axis);
      else if (kind == "PU")
        jm = pinocchio::JointModelPrismaticUnaligned(axis);
      else if (kind == "FF")
        jm = pinocchio::JointModelFreeFlyer();
      else
        throw std::runtime_error("unknown joint type " + kind + " in " + path);
      const Vec lo = read_vec(in, jm.nq()), hi = read_vec(in, jm.nq());
      const Vec big = Vec::Constant(jm.nv(), 1e6);
      const auto id = model.addJoint(
        parent, jm, pinocchio::SE3(R, p), "joint" + std::to_string(j), big, big, lo, hi);
      model.appendBodyToJoint(
        id, pinocchio::Inertia(mass, lever, pinocchio::Symmetric3(I[0], I[1], I[2], I[3], I[4], I[5])));
    }
    std::string tag;
    in >> tag;
    if (!in || tag != "check" || model.nq != nq || model.nv != nv)
      throw std::runtime_error("malformed model file " + path);
    const Vec q = read_vec(in, nq), v = read_vec(in, nv), a = read_vec(in, nv),
              tau = read_vec(in, nv);
    const Vec mine = bench::rnea_once(model, q, v, a);
    return (mine - tau).cwiseAbs().maxCoeff();
  }

  double median(std::vector<double> x)
  {
    std::sort(x.begin(), x.end());
    const size_t n = x.size();
    return n % 2 ? x[n / 2] : 0.5 * (x[n / 2 - 1] + x[n / 2]);
  }

} // namespace

int main(int argc, char ** argv)
{
  int reps = 21;
  int nstates = 1000;
  std::string build = "unspecified";
  std::vector<std::pair<std::string, std::string>> models;
  for (int i = 1; i < argc; ++i)
  {
    if (!std::strcmp(argv[i], "--reps") && i + 1 < argc)
      reps = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--states") && i + 1 < argc)
      nstates = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--build") && i + 1 < argc)
      build = argv[++i];
    else
    {
      std::string arg = argv[i];
      const size_t eq = arg.find('=');
      if (eq == std::string::npos)
      {
        std::fprintf(
          stderr, "usage: %s [--reps N] [--states N] [--build LABEL] NAME=FILE.model ...\n", argv[0]);
        return 2;
      }
      models.emplace_back(arg.substr(0, eq), arg.substr(eq + 1));
    }
  }

  for (const auto & nm : models)
  {
    Model model;
    const double check_err = load_plain(nm.second, model);
    if (!(check_err < 1e-8))
    {
      std::fprintf(
        stderr, "%s: RNEA differs from Pinocchio-Python's by %g after loading\n", nm.first.c_str(),
        check_err);
      return 1;
    }
    Data data(model);
    std::srand(42); // randomConfiguration and Vec::Random draw from std::rand
    const States s = draw_states(model, nstates);

    const auto & keys = bench::ALGO_KEYS;
    const size_t nalgos = bench::N_ALGOS;
    auto run = [&](size_t k) -> double {
      if (k < 6)
        return bench::run_kinematics(k, model, data, s, nstates);
      if (k == 6 || k == 7 || k == 11)
        return bench::run_crba(k, model, data, s, nstates);
      if (k >= 12)
        return bench::run_derivatives(k, model, data, s, nstates);
      return bench::run_aba(k, model, data, s, nstates);
    };
    std::vector<std::vector<double>> samples(nalgos);
    for (size_t k = 0; k < nalgos; ++k) // one untimed warm-up pass each
      run(k);
    for (int r = 0; r < reps; ++r)
      for (size_t k = 0; k < nalgos; ++k)
        samples[k].push_back(run(k));

    std::printf(
      "{\"model\": \"%s\", \"nq\": %d, \"nv\": %d, \"build\": \"%s\", \"states\": %d, \"reps\": %d, "
      "\"ns_per_call\": {",
      nm.first.c_str(), model.nq, model.nv, build.c_str(), nstates, reps);
    double med[64];
    for (size_t k = 0; k < nalgos; ++k)
      med[k] = median(samples[k]);
    auto find = [&](const char * key) {
      for (size_t k = 0; k < nalgos; ++k)
        if (!std::strcmp(keys[k], key))
          return med[k];
      return -1.0;
    };
    // "crba" and "aba": the faster of Pinocchio's two conventions (the most
    // favourable number for Pinocchio); both are reported as well.
    std::printf(
      "\"crba\": %.1f, \"aba\": %.1f", std::min(find("crba_local"), find("crba_world")),
      std::min(find("aba_local"), find("aba_world")));
    for (size_t k = 0; k < nalgos; ++k)
      if (med[k] >= 0.0) // negative: not timed by this build
        std::printf(", \"%s\": %.1f", keys[k], med[k]);
    std::printf("}}\n");
    std::fflush(stdout);
  }
  return bench::g_sink == 12345.678 ? 1 : 0;
}
