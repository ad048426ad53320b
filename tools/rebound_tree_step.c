// A cross-check, not part of the build: the time per step of REBOUND's tree code (Rein & Liu 2012;
// https://github.com/hannorein/rebound, built with OPENMP=1) on the particles of a tidalcrust
// checkpoint, for comparison with `tidalcrust bench` on the same machine at the same time
// (README, "Large N: the tree code"). Gravity by REBOUND's Barnes-Hut tree, opening angle 0.5
// (opening_angle2 = 0.25, its default), leapfrog, Plummer softening as the body's; 2 warm-up
// steps, then the median ms per step of 5 repeats of 5 steps.
//
//   python3 -c "import h5py, numpy as n; f = h5py.File('relax.h5', 'r');
//     n.asarray(f['particles/body/position/value'][0], '<f8').tofile('pos.bin');
//     n.asarray(f['particles/body/mass'][()], '<f8').tofile('mass.bin')"
//   cc -O3 -fopenmp -I REBOUND/src tools/rebound_tree_step.c -L REBOUND/src -lrebound -lm -o rebound_tree_step
//   OMP_NUM_THREADS=2 LD_LIBRARY_PATH=REBOUND/src ./rebound_tree_step pos.bin mass.bin SOFTENING DT [N]
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "rebound.h"

static double seconds(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

int main(int argc, char** argv) {
  if (argc < 5) {
    fprintf(stderr, "usage: %s POSITIONS.bin MASSES.bin SOFTENING DT [N]\n", argv[0]);
    return 2;
  }
  FILE* positions = fopen(argv[1], "rb");
  FILE* masses = fopen(argv[2], "rb");
  if (!positions || !masses) {
    fprintf(stderr, "%s: cannot open %s\n", argv[0], positions ? argv[2] : argv[1]);
    return 2;
  }
  struct reb_simulation* r = reb_simulation_create();
  r->gravity = REB_GRAVITY_TREE;
  r->boundary = REB_BOUNDARY_OPEN;
  r->opening_angle2 = 0.25;
  reb_simulation_set_integrator(r, "leapfrog");
  r->softening = atof(argv[3]);
  r->dt = atof(argv[4]);
  r->root_size = 4.0;  // a cube of side 4 R about the origin holds the body
  const long limit = argc > 5 ? atol(argv[5]) : -1;
  double x[3], m;
  for (long i = 0; (limit < 0 || i < limit) && fread(x, sizeof(double), 3, positions) == 3 &&
                   fread(&m, sizeof(double), 1, masses) == 1;
       ++i) {
    struct reb_particle p = {0};
    p.x = x[0], p.y = x[1], p.z = x[2], p.m = m;
    reb_simulation_add(r, p);
  }
  reb_simulation_steps(r, 2);
  enum { repeats = 5, steps = 5 };
  double ms[repeats];
  for (int k = 0; k < repeats; ++k) {
    const double start = seconds();
    reb_simulation_steps(r, steps);
    ms[k] = (seconds() - start) / steps * 1e3;
  }
  for (int a = 0; a < repeats; ++a)
    for (int b = a + 1; b < repeats; ++b)
      if (ms[b] < ms[a]) {
        const double t = ms[a];
        ms[a] = ms[b], ms[b] = t;
      }
  printf("rebound tree: %zu particles, %.1f ms per step (median of %d x %d steps; min %.1f, max %.1f)\n",
         (size_t)r->N, ms[repeats / 2], repeats, steps, ms[0], ms[repeats - 1]);
  reb_simulation_free(r);
  return 0;
}
