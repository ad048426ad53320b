#pragma once
// One checkpoint = the full content needed to continue a run bit for bit: body, state, stage
// bookkeeping, resolved configuration and the observables gathered so far. The file format is
// io/checkpoint_file.hpp.
#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "model/body.hpp"
#include "model/state.hpp"

namespace tidalcrust {

/// One shell spring failure (paper section 2.6).
struct FailureEvent {
  double time = 0;                      ///< t_grav
  std::int64_t step = 0;
  std::int32_t spring = 0;              ///< index into Body::springs
  double strain = 0;                    ///< (L - L0)/L0 when it failed
  std::array<double, 3> position{};     ///< spring midpoint, R, same frame as State
};

/// A sample of the conserved quantities (body + perturber, about the origin) and of where the
/// perturber is.
struct TimeseriesSample {
  double time = 0;
  std::int64_t failed = 0;              ///< failed springs so far
  double kinetic_energy = 0;
  std::array<double, 3> momentum{};
  std::array<double, 3> angular_momentum{};
  /// Perturber position minus the body's centre of mass (orbital_frame.hpp), R; the simulated
  /// track including the body's recoil. Zero when there is no perturber.
  std::array<double, 3> perturber_offset{};
};

struct Observables {
  std::vector<FailureEvent> failures;
  std::vector<TimeseriesSample> timeseries;
};

/// Which stage wrote the checkpoint and everything its next step depends on.
struct StageInfo {
  std::string stage;               ///< "build", "stretch", "relax", "encounter"
  bool complete = true;            ///< false for a mid-stage (periodic or SIGINT) checkpoint
  std::int64_t start_step = 0;     ///< global step at which the stage started
  std::int64_t end_step = 0;       ///< global step at which the stage ends
  std::string parent_hash;         ///< state_hash of the checkpoint the stage started from
  std::map<std::string, double> scalars;      ///< results and schedule phases, by name
  std::map<std::string, std::string> labels;  ///< e.g. "encounter" -> "T5"
};

struct Checkpoint {
  StageInfo stage;
  std::string config_toml;  ///< resolved configuration (to_toml)
  Body body;
  State state;
  Observables observables;
};

}  // namespace tidalcrust
