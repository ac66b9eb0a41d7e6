/* MuJoCo's inverse dynamics and mass matrix, timed the way `rigid bench` times rigid's: random
 * states drawn once (hinges and slides about qpos0 within +-1, quaternions uniform on SO(3),
 * velocities and accelerations uniform in [-1, 1]), one pass calls the path once per state, a
 * sample is the pass time over the number of states, the report is the median of the samples
 * after one warm-up pass, the paths taking turns pass by pass. Printed as one JSON object (ns per
 * call):
 *
 *   rnea      mj_kinematics, mj_comPos, mj_comVel, mj_rne(flg_acc = 1): M(q) a + c(q, v)
 *   crba      mj_kinematics, mj_comPos, mj_crb, mj_fullM: the dense M(q) (armature included)
 *   crba_sparse  the same without mj_fullM (MuJoCo's own sparse M, ready to factor)
 *
 * Each path computes from q (and v, a) what it needs, as rigid's RNEA and CRBA do from q.
 * Built against the libmujoco of the pip wheel by bench/compare_mujoco.py:
 *   cc -O2 timings.c -I$MUJOCO/include -L$MUJOCO -l:libmujoco.so.4.0.0 -Wl,-rpath,$MUJOCO -lm
 * Usage: timings MODEL.xml [states=1000] [repetitions=21] [seed=7]
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <mujoco/mujoco.h>

static uint64_t rng_state;
static double uniform(double lo, double hi) {
  /* splitmix64 */
  uint64_t z = (rng_state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return lo + (hi - lo) * ((z >> 11) * (1.0 / 9007199254740992.0));
}
static double normal(void) {
  double u = uniform(1e-12, 1), v = uniform(0, 1);
  return sqrt(-2 * log(u)) * cos(2 * M_PI * v);
}
static void unit_quat(double* q) {
  double n = 0;
  for (int i = 0; i < 4; i++) { q[i] = normal(); n += q[i] * q[i]; }
  n = sqrt(n);
  for (int i = 0; i < 4; i++) q[i] /= n;
}
static double now(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return t.tv_sec * 1e9 + t.tv_nsec;
}
static int cmp(const void* a, const void* b) {
  double x = *(const double*)a, y = *(const double*)b;
  return (x > y) - (x < y);
}

enum { RNEA, CRBA, CRBA_SPARSE, NPATH };
static const char* NAMES[NPATH] = {"rnea", "crba", "crba_sparse"};

int main(int argc, char** argv) {
  if (argc < 2) { fprintf(stderr, "usage: %s MODEL.xml [states] [reps] [seed]\n", argv[0]); return 2; }
  int nstate = argc > 2 ? atoi(argv[2]) : 1000, reps = argc > 3 ? atoi(argv[3]) : 21;
  rng_state = argc > 4 ? strtoull(argv[4], 0, 10) : 7;
  char err[1000];
  mjModel* m = mj_loadXML(argv[1], 0, err, sizeof(err));
  if (!m) { fprintf(stderr, "%s\n", err); return 1; }
  mjData* d = mj_makeData(m);
  int nq = m->nq, nv = m->nv;
  double* Q = malloc(sizeof(double) * nq * nstate);
  double* V = malloc(sizeof(double) * nv * nstate);
  double* A = malloc(sizeof(double) * nv * nstate);
  double* out = malloc(sizeof(double) * (nv > 0 ? nv : 1));
  double* M = malloc(sizeof(double) * (nv * nv > 0 ? nv * nv : 1));
  for (int s = 0; s < nstate; s++) {
    double* q = Q + s * nq;
    memcpy(q, m->qpos0, sizeof(double) * nq);
    for (int j = 0; j < m->njnt; j++) {
      int a = m->jnt_qposadr[j];
      switch (m->jnt_type[j]) {
        case mjJNT_FREE: for (int i = 0; i < 3; i++) q[a + i] = uniform(-1, 1); unit_quat(q + a + 3); break;
        case mjJNT_BALL: unit_quat(q + a); break;
        default: q[a] += uniform(-1, 1);
      }
    }
    for (int i = 0; i < nv; i++) { V[s * nv + i] = uniform(-1, 1); A[s * nv + i] = uniform(-1, 1); }
  }
  double* samples = malloc(sizeof(double) * NPATH * reps);
  double sink = 0;
  for (int r = -1; r < reps; r++) {
    for (int p = 0; p < NPATH; p++) {
      double t0 = now();
      for (int s = 0; s < nstate; s++) {
        memcpy(d->qpos, Q + s * nq, sizeof(double) * nq);
        mj_kinematics(m, d);
        mj_comPos(m, d);
        if (p == RNEA) {
          memcpy(d->qvel, V + s * nv, sizeof(double) * nv);
          memcpy(d->qacc, A + s * nv, sizeof(double) * nv);
          mj_comVel(m, d);
          mj_rne(m, d, 1, out);
          sink += out[0];
        } else {
          mj_crb(m, d);
          if (p == CRBA) { mj_fullM(m, d, M); sink += M[0]; }
          else sink += d->M[0];
        }
      }
      double t = (now() - t0) / nstate;
      if (r >= 0) samples[p * reps + r] = t;
    }
  }
  printf("{\"model\": \"%s\", \"nq\": %d, \"nv\": %d, \"mujoco\": \"%s\"", argv[1], nq, nv, mj_versionString());
  for (int p = 0; p < NPATH; p++) {
    qsort(samples + p * reps, reps, sizeof(double), cmp);
    printf(", \"%s\": %.2f", NAMES[p], samples[p * reps + reps / 2]);
  }
  printf(", \"sink\": %g}\n", sink == 12345.678 ? 1.0 : 0.0);
  mj_deleteData(d);
  mj_deleteModel(m);
  return 0;
}
