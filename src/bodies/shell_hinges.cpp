#include "bodies/shell_hinges.hpp"
#include "base/invariant.hpp"

#include <map>
#include <stdexcept>
#include <string>
#include <utility>

namespace tidalcrust {

std::vector<std::array<std::int32_t, 4>> make_hinges(const std::vector<std::array<std::int32_t, 2>>& edges,
                                                      const std::vector<std::array<std::int32_t, 3>>& faces) {
  // Directed edge u->v of a CCW face -> the face's third vertex.
  std::map<std::pair<std::int32_t, std::int32_t>, std::int32_t> opposite;
  for (const auto& f : faces)
    for (int k = 0; k < 3; ++k) {
      const bool first = opposite.emplace(std::pair{f[k], f[(k + 1) % 3]}, f[(k + 2) % 3]).second;
      TIDALCRUST_ASSERT(first, "make_hinges: directed edge " + std::to_string(f[k]) + "->" +
                                   std::to_string(f[(k + 1) % 3]) + " belongs to two faces");
    }
  std::vector<std::array<std::int32_t, 4>> hinges;
  hinges.reserve(edges.size());
  for (const auto& [a, b] : edges) {
    const auto w1 = opposite.find({a, b});
    const auto w2 = opposite.find({b, a});
    TIDALCRUST_ASSERT(w1 != opposite.end() && w2 != opposite.end(),
                      "make_hinges: edge " + std::to_string(a) + "-" + std::to_string(b) +
                          " does not have a face on each side");
    hinges.push_back({w1->second, w2->second, a, b});
  }
  return hinges;
}

}  // namespace tidalcrust
