#pragma once
// Which shell spring lies on which edge of which shell triangle. Crack rendering and crack
// clustering (paper section 2.6, Figure 4) both work face by face on the failed edges.
#include <array>
#include <cstdint>
#include <vector>

#include "model/body.hpp"

namespace tidalcrust {

struct ShellTopology {
  /// [Nf][3] spring index of face edge k = (v_k, v_(k+1)%3).
  std::vector<std::array<std::int32_t, 3>> face_edge_spring;
  /// [Ns] the (up to) two faces that share spring s; -1 where there is none (non-shell springs).
  std::vector<std::array<std::int32_t, 2>> spring_faces;
};

/// Throws InputError if a face edge has no shell spring or an edge has more than two faces.
ShellTopology shell_topology(const Body& body);

}  // namespace tidalcrust
