// Pinocchio side of crates/rigid/examples/multibody_timing.rs (the "ur5" model: UR5 DH table,
// RZ joints, the same masses, CoMs and inertias), timed the same way (fastest of 21 batches of
// 1000 pre-drawn random states). Build against the PyPI wheels `pin` and `cmeel-eigen`:
//
//   P=$(python -c "import cmeel, os; print(os.path.join(os.path.dirname(cmeel.__file__), '..', 'cmeel.prefix'))")
//   g++ -O3 -DNDEBUG -std=c++17 -DBOOST_MPL_CFG_NO_PREPROCESSED_HEADERS -DBOOST_MPL_LIMIT_LIST_SIZE=30 \
//       -DBOOST_MPL_LIMIT_VECTOR_SIZE=30 -DBOOST_FUSION_INVOKE_MAX_ARITY=12 -I$P/include -I$P/include/eigen3 \
//       ur5_dh.cpp -o ur5_dh -L$P/lib -lpinocchio_default -Wl,-rpath,$P/lib
//
// (the defines are Pinocchio's INTERFACE_COMPILE_DEFINITIONS from its CMake config). Pinocchio's
// crba fills the upper triangle only; rigid's fills the full symmetric matrix.
#include <pinocchio/multibody.hpp>

#include <pinocchio/algorithm/kinematics.hpp>
#include <pinocchio/algorithm/jacobian.hpp>
#include <pinocchio/algorithm/rnea.hpp>
#include <pinocchio/algorithm/crba.hpp>
#include <pinocchio/algorithm/aba.hpp>
#include <chrono>
#include <cstdio>
#include <random>
#include <vector>
#include <algorithm>
using namespace pinocchio;
static SE3 Tz(double d){ return SE3(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0,0,d)); }
static SE3 Tx(double a){ return SE3(Eigen::Matrix3d::Identity(), Eigen::Vector3d(a,0,0)); }
static SE3 Rx(double t){ return SE3(Eigen::AngleAxisd(t, Eigen::Vector3d::UnitX()).toRotationMatrix(), Eigen::Vector3d::Zero()); }
int main(){
  double d[6]={0.089159,0,0,0.10915,0.09465,0.0823}, a[6]={0,-0.425,-0.39225,0,0,0};
  double al[6]={M_PI/2,0,0,M_PI/2,-M_PI/2,0}, m[6]={3.7,8.393,2.275,1.219,1.219,0.1879};
  Model model; JointIndex parent=0; SE3 prev=SE3::Identity();
  for(int i=0;i<6;i++){
    JointIndex j = model.addJoint(parent, JointModelRZ(), prev, "j"+std::to_string(i));
    SE3 link = Tz(d[i])*Tx(a[i])*Rx(al[i]);
    Eigen::Matrix3d I = Eigen::Vector3d(0.01*m[i],0.012*m[i],0.008*m[i]).asDiagonal();
    model.appendBodyToJoint(j, Inertia(m[i], Eigen::Vector3d(-a[i]/2,0,0.01), I), link);
    parent=j; prev=link;
  }
  Data data(model);
  std::mt19937 gen(7); std::uniform_real_distribution<double> U(-1,1);
  const int n=1000; std::vector<Eigen::VectorXd> Q,V,A;
  for(int k=0;k<n;k++){ Eigen::VectorXd q(6),v(6),ac(6); for(int i=0;i<6;i++){q[i]=M_PI*U(gen);v[i]=U(gen);ac[i]=U(gen);} Q.push_back(q);V.push_back(v);A.push_back(ac);}
  auto time=[&](const char* name, auto f){ double best=1e30; for(int r=0;r<21;r++){ auto t0=std::chrono::steady_clock::now(); for(int k=0;k<n;k++) f(k); auto t1=std::chrono::steady_clock::now(); best=std::min(best, std::chrono::duration<double,std::nano>(t1-t0).count()/n);} printf(" %s %.0f", name, best); };
  printf("pinocchio ur5 (nv 6), ns/call:");
  time("fk",[&](int k){ forwardKinematics(model,data,Q[k],V[k],A[k]); });
  time("jac",[&](int k){ computeJointJacobians(model,data,Q[k]); });
  time("rnea",[&](int k){ rnea(model,data,Q[k],V[k],A[k]); });
  time("crba",[&](int k){ crba(model,data,Q[k]); });
  time("aba",[&](int k){ aba(model,data,Q[k],V[k],A[k]); });
  printf("\n");
}
