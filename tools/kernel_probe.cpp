// tidalcrust_kernel_probe_generic: forces/gravity.cpp and forces/tree_gravity.cpp built for plain
// x86-64-v2 (no AVX-512, no -march=native; CMakeLists.txt) prints, one line each, "portable <hash>"
// and "fast <hash>" of the direct sum on the fixed particle set of tests/support/kernel_probe.hpp,
// "tree_portable <hash>" and "tree_fast <hash>" of the tree code on its tree set, and this build's
// label of the fast kernel.
// GravityKernels.PortableBitsEqualAcrossBuilds compares them with the native build's.
#include <cstdio>

#include "support/kernel_probe.hpp"

int main() {
  using namespace tidalcrust;
  std::printf("portable %s\n", test_support::probe_hash(GravityKernel::portable).c_str());
  std::printf("fast %s\n", test_support::probe_hash(GravityKernel::fast).c_str());
  std::printf("tree_portable %s\n", test_support::tree_probe_hash(GravityKernel::portable).c_str());
  std::printf("tree_fast %s\n", test_support::tree_probe_hash(GravityKernel::fast).c_str());
  std::printf("fast_label %s\n", gravity_kernel_label(GravityKernel::fast));
  return 0;
}
