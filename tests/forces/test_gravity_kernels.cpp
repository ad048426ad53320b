// The portable gravity kernels (direct sum and tree) give the same bits in a build without AVX-512
// as in this (native) build; the fast kernels differ from them exactly when they use AVX-512.
#include <gtest/gtest.h>

#include <cstdio>
#include <map>
#include <sstream>
#include <string>

#include "model/config.hpp"
#include "base/errors.hpp"
#include "forces/force_field.hpp"
#include "support/kernel_probe.hpp"

using namespace tidalcrust;
using test_support::probe_hash;

namespace {

/// The lines "name value" that tidalcrust_kernel_probe_generic prints.
std::map<std::string, std::string> generic_probe() {
  std::map<std::string, std::string> values;
  FILE* pipe = popen(TIDALCRUST_KERNEL_PROBE, "r");
  if (!pipe) return values;
  std::string text;
  char buffer[256];
  while (std::fgets(buffer, sizeof buffer, pipe)) text += buffer;
  EXPECT_EQ(pclose(pipe), 0);
  std::istringstream lines(text);
  std::string name, value;
  while (lines >> name >> value) values[name] = value;
  return values;
}

}  // namespace

TEST(GravityKernels, PortableBitsEqualAcrossBuilds) {
  const auto generic = generic_probe();
  ASSERT_EQ(generic.count("portable"), 1u) << "no output from " << TIDALCRUST_KERNEL_PROBE;
  EXPECT_EQ(generic.at("fast_label"), "fast/generic");
  EXPECT_EQ(generic.at("portable"), probe_hash(GravityKernel::portable));
  // Without AVX-512 the fast kernel is the portable code, which same_gravity_bits relies on.
  EXPECT_EQ(generic.at("fast"), generic.at("portable"));
}

TEST(GravityKernels, PortableTreeBitsEqualAcrossBuilds) {
  // The tree code's portable kernel (plain lane loops, correctly rounded operations, the opening
  // angle from SLEEF's pow): the same accelerations, potential energy and angle in the
  // x86-64-v2 build as in this one; without AVX-512 its fast kernel is that same code.
  const auto generic = generic_probe();
  ASSERT_EQ(generic.count("tree_portable"), 1u) << "no tree output from " << TIDALCRUST_KERNEL_PROBE;
  EXPECT_EQ(generic.at("tree_portable"), test_support::tree_probe_hash(GravityKernel::portable));
  EXPECT_EQ(generic.at("tree_fast"), generic.at("tree_portable"));
#if defined(__AVX512F__)
  EXPECT_NE(test_support::tree_probe_hash(GravityKernel::fast), test_support::tree_probe_hash(GravityKernel::portable));
#else
  EXPECT_EQ(test_support::tree_probe_hash(GravityKernel::fast), test_support::tree_probe_hash(GravityKernel::portable));
#endif
}

TEST(GravityKernels, FastDiffersFromPortableExactlyWithAvx512) {
#if defined(__AVX512F__)
  EXPECT_STREQ(gravity_kernel_label(GravityKernel::fast), "fast/avx512");
  EXPECT_NE(probe_hash(GravityKernel::fast), probe_hash(GravityKernel::portable));
#else
  EXPECT_STREQ(gravity_kernel_label(GravityKernel::fast), "fast/generic");
  EXPECT_EQ(probe_hash(GravityKernel::fast), probe_hash(GravityKernel::portable));
#endif
}

TEST(GravityKernels, LabelsAndWhichGiveTheSameBits) {
  EXPECT_STREQ(gravity_kernel_label(GravityKernel::portable), "portable");
  EXPECT_TRUE(same_gravity_bits("portable", "portable"));
  EXPECT_TRUE(same_gravity_bits("fast/generic", "portable"));
  EXPECT_TRUE(same_gravity_bits("portable", "fast/generic"));
  EXPECT_FALSE(same_gravity_bits("fast/avx512", "portable"));
  EXPECT_FALSE(same_gravity_bits("fast/avx512", "fast/generic"));
}

TEST(GravityKernels, ConfigurationChoosesTheKernel) {
  Config config;
  EXPECT_EQ(force_options(config, 0.0).gravity_kernel, GravityKernel::fast);  // today's default
  apply_override(config, "gravity.kernel=portable");
  validate(config, "test");
  EXPECT_EQ(force_options(config, 0.0).gravity_kernel, GravityKernel::portable);
  EXPECT_THROW(apply_override(config, "gravity.kernel=exact"), InputError);
}
