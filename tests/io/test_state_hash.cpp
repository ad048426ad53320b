#include <gtest/gtest.h>

#include <xxhash.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "io/state_hash.hpp"
#include "support/synthetic_checkpoint.hpp"

using namespace tidalcrust;

namespace {
double next_up(double v) { return std::nextafter(v, INFINITY); }
}  // namespace

TEST(StateHash, Is32LowercaseHexDigitsAndDeterministic) {
  const State s = test_support::synthetic_checkpoint().state;
  const std::string h = state_hash(s);
  ASSERT_EQ(h.size(), 32u);
  for (char ch : h) EXPECT_TRUE((ch >= '0' && ch <= '9') || (ch >= 'a' && ch <= 'f')) << h;
  EXPECT_EQ(h, state_hash(s));
  State copy = s;
  EXPECT_EQ(h, state_hash(copy));
}

TEST(StateHash, EqualsOneShotXxh3OfTheDocumentedByteLayout) {
  // Independent reconstruction of the canonical byte stream (state_hash.cpp), hashed in one go.
  State s;
  s.time = 1.5;
  s.step = 42;
  s.position = {1, 2, 3};
  s.velocity = {-1, -2, -3};
  s.springs.rest_length = {0.25};
  s.springs.stiffness = {0.06};
  s.springs.failed = {1};
  s.hinges.rest_angle = {};
  s.perturber = {true, 0.5, {3, 0, 0}, {0, 1, 0}};
  std::vector<unsigned char> bytes;
  auto put = [&](const auto& v) {
    const auto* p = reinterpret_cast<const unsigned char*>(&v);
    bytes.insert(bytes.end(), p, p + sizeof v);
  };
  auto put_array = [&](const auto& values) {
    put(static_cast<std::int64_t>(values.size()));
    for (auto v : values) put(v);
  };
  put(s.time);
  put(s.step);
  put_array(s.position);
  put_array(s.velocity);
  put_array(s.springs.rest_length);
  put_array(s.springs.stiffness);
  put_array(s.springs.failed);
  put_array(s.hinges.rest_angle);
  put(std::uint8_t{1});
  put(s.perturber.mass);
  for (double v : s.perturber.position) put(v);
  for (double v : s.perturber.velocity) put(v);
  XXH128_hash_t h = XXH3_128bits(bytes.data(), bytes.size());
  char expected[33];
  std::snprintf(expected, sizeof expected, "%016llx%016llx", static_cast<unsigned long long>(h.high64),
                static_cast<unsigned long long>(h.low64));
  EXPECT_EQ(state_hash(s), std::string(expected));
}

TEST(StateHash, ChangesWhenAnyHashedFieldChangesByOneUlp) {
  const State base = test_support::synthetic_checkpoint().state;
  const std::string h0 = state_hash(base);
  std::vector<std::pair<const char*, std::function<void(State&)>>> edits = {
      {"time", [](State& s) { s.time = next_up(s.time); }},
      {"step", [](State& s) { s.step += 1; }},
      {"position first", [](State& s) { s.position.front() = next_up(s.position.front()); }},
      {"position last", [](State& s) { s.position.back() = next_up(s.position.back()); }},
      {"velocity", [](State& s) { s.velocity[7] = next_up(s.velocity[7]); }},
      {"rest_length", [](State& s) { s.springs.rest_length[3] = next_up(s.springs.rest_length[3]); }},
      {"stiffness", [](State& s) { s.springs.stiffness[9] = next_up(s.springs.stiffness[9]); }},
      {"failed", [](State& s) { s.springs.failed[0] = 1; }},
      {"rest_angle", [](State& s) { s.hinges.rest_angle[2] = next_up(s.hinges.rest_angle[2]); }},
      {"perturber mass", [](State& s) { s.perturber.mass = next_up(s.perturber.mass); }},
      {"perturber position", [](State& s) { s.perturber.position[2] = next_up(s.perturber.position[2]); }},
      {"perturber velocity", [](State& s) { s.perturber.velocity[1] = next_up(s.perturber.velocity[1]); }},
      {"perturber absent", [](State& s) { s.perturber.present = false; }},
      {"negative zero", [](State& s) { s.position[0] = -0.0; }},
      {"one particle less", [](State& s) { s.position.resize(s.position.size() - 3); }},
  };
  for (auto& [name, edit] : edits) {
    State s = base;
    edit(s);
    EXPECT_NE(state_hash(s), h0) << name;
  }
}

TEST(StateHash, IgnoresFieldsOutsideTheDefinition) {
  // dt, damping and hinge stiffness are not part of the hashed state (io/state_hash.hpp).
  const State base = test_support::synthetic_checkpoint().state;
  State s = base;
  s.dt *= 2;
  s.springs.damping[0] = 50;
  s.hinges.stiffness[0] = 1;
  EXPECT_EQ(state_hash(s), state_hash(base));
  // An absent perturber's leftover numbers do not matter.
  State a = base, b = base;
  a.perturber.present = b.perturber.present = false;
  b.perturber.mass = 9;
  EXPECT_EQ(state_hash(a), state_hash(b));
}
