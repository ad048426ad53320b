#include "bodies/shell_topology.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <unordered_map>

#include "base/errors.hpp"

namespace tidalcrust {

namespace {
std::uint64_t edge_key(std::int32_t a, std::int32_t b) {
  const auto lo = static_cast<std::uint32_t>(std::min(a, b));
  const auto hi = static_cast<std::uint32_t>(std::max(a, b));
  return (std::uint64_t{hi} << 32) | lo;
}
}  // namespace

ShellTopology shell_topology(const Body& body) {
  std::unordered_map<std::uint64_t, std::int32_t> shell_spring_of_edge;
  for (std::size_t s = 0; s < body.spring_count(); ++s) {
    if (body.spring_kind[s] != static_cast<std::uint8_t>(SpringKind::shell)) continue;
    shell_spring_of_edge.emplace(edge_key(body.springs[s][0], body.springs[s][1]),
                                 static_cast<std::int32_t>(s));
  }
  ShellTopology topology;
  topology.face_edge_spring.resize(body.faces.size());
  topology.spring_faces.assign(body.spring_count(), {-1, -1});
  for (std::size_t f = 0; f < body.faces.size(); ++f) {
    const auto& face = body.faces[f];
    for (int k = 0; k < 3; ++k) {
      const std::int32_t a = face[k], b = face[(k + 1) % 3];
      const auto it = shell_spring_of_edge.find(edge_key(a, b));
      if (it == shell_spring_of_edge.end())
        throw InputError(fmt::format("body: edge ({}, {}) of shell face {} has no shell spring", a, b, f));
      topology.face_edge_spring[f][k] = it->second;
      auto& faces = topology.spring_faces[static_cast<std::size_t>(it->second)];
      if (faces[0] < 0) faces[0] = static_cast<std::int32_t>(f);
      else if (faces[1] < 0) faces[1] = static_cast<std::int32_t>(f);
      else
        throw InputError(fmt::format("body: shell spring {} is an edge of more than two faces", it->second));
    }
  }
  return topology;
}

}  // namespace tidalcrust
