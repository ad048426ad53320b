#pragma once
// The body description: particles, springs, hinges and faces with their fixed properties. It
// never changes once built; everything that evolves (positions, rest lengths, stiffnesses,
// failures) lives in State.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace tidalcrust {

/// interior: a node of the interior network; shell: a crust node; liquid: a particle of a liquid
/// layer (an ocean), which has no springs and feels pressure only (LiquidLayer).
enum class Species : std::uint8_t { interior = 0, shell = 1, liquid = 2 };

/// "interior", "shell" or "liquid" for a Species value (messages, the checkpoint's species labels).
inline const char* species_name(std::uint8_t species) {
  return species == static_cast<std::uint8_t>(Species::shell)    ? "shell"
         : species == static_cast<std::uint8_t>(Species::liquid) ? "liquid"
                                                                  : "interior";
}
enum class SpringKind : std::uint8_t { interior = 0, shell = 1, cross = 2 };

/// A liquid layer (docs/ocean.md; forces/liquid_pressure.hpp): the liquid particles
/// (Species::liquid) interact with each other through their number density alone, which gives the
/// layer a bulk modulus and no shear modulus, and with the solid particles at its boundary by
/// contact.
struct LiquidLayer {
  double support_radius = 0;  ///< H, the support of the Wendland C2 kernel, R; 0: no liquid layer
  double bulk_modulus = 0;    ///< K, e_g (G M^2/R^4)
  /// [N] weight of each particle in a liquid particle's density sum: 1 for a liquid particle, 0
  /// for a solid one (the liquid meets the solid through contact, below).
  std::vector<double> density_weight;
  /// [N] delta_b, R: a liquid particle closer than this to solid particle b is pushed off it with
  /// energy (k/2)(delta_b - r)^2 (LiquidContact); 0 for a liquid particle and for a solid one the
  /// liquid does not touch. The builder sets it to the closest liquid particle's distance.
  std::vector<double> contact_radius;
  double contact_stiffness = 0;  ///< k, G M^2/R^3
  bool present() const { return support_radius > 0; }
};

struct Body {
  std::vector<double> mass;                          ///< [N] in units of the body mass M
  std::vector<std::uint8_t> species;                 ///< [N] Species values
  std::vector<std::array<std::int32_t, 2>> springs;  ///< [Ns] particle indices
  std::vector<std::uint8_t> spring_kind;             ///< [Ns] SpringKind values
  /// [Nh] one hinge per shell edge: {wing_1, wing_2, edge_a, edge_b} (Bridson 2003 x1..x4):
  /// edge_a-edge_b is the shared edge, wing_1 and wing_2 the opposite vertices of its faces.
  /// Ordered so that (wing_1, edge_a, edge_b) and (wing_2, edge_b, edge_a) are both
  /// counter-clockwise seen from outside; then hinge_angle() (hinge_geometry.hpp) has the
  /// same sign on every hinge of a convex shell.
  std::vector<std::array<std::int32_t, 4>> hinges;
  std::vector<double> hinge_stiffness;               ///< [Nh] k_e in G M^2 / R^2 (a force; eq. 22)
  std::vector<std::array<std::int32_t, 3>> faces;    ///< [Nf] shell triangles, outward CCW
  /// [Ns] a shell spring fails beyond eps_S * strength_factor: the crust's strength sampled at the
  /// spring's midpoint as built ([crust], docs/crust.md); 1 for every other spring and for a
  /// uniform crust. Empty stands for all 1 (a body put together by hand); failure_strain_factor.
  std::vector<double> strength_factor;
  double softening = 0.0;  ///< Plummer softening length in R (1/100 of min initial spacing)
  LiquidLayer liquid;      ///< an ocean between the crust and the solid interior; absent by default

  std::size_t particle_count() const { return mass.size(); }
  std::size_t spring_count() const { return springs.size(); }
  std::size_t hinge_count() const { return hinges.size(); }
  /// The factor on eps_S of spring n (strength_factor, 1 when it is empty).
  double failure_strain_factor(std::size_t n) const { return strength_factor.empty() ? 1.0 : strength_factor[n]; }
  std::size_t count_species(Species s) const {
    std::size_t n = 0;
    for (auto v : species) n += (v == static_cast<std::uint8_t>(s));
    return n;
  }
  std::size_t count_springs(SpringKind k) const {
    std::size_t n = 0;
    for (auto v : spring_kind) n += (v == static_cast<std::uint8_t>(k));
    return n;
  }
};

}  // namespace tidalcrust
