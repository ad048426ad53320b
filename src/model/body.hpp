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
/// liquid: a spring of a liquid layer (LiquidLayer): ocean.shear_fraction of its stiffness (a small
/// static shear modulus that steadies the liquid) and damping; the pressure is the layer's.
enum class SpringKind : std::uint8_t { interior = 0, shell = 1, cross = 2, liquid = 3 };

/// A liquid layer (docs/ocean.md; forces/liquid_pressure.hpp): the liquid particles
/// (Species::liquid) and the tetrahedra that fill the layer between them and the solid particles
/// around it carry an energy of volume alone: a bulk modulus and no shear modulus. The layer's
/// springs (SpringKind::liquid) add a small shear modulus (ocean.shear_fraction) and damping.
struct LiquidLayer {
  double bulk_modulus = 0;  ///< K, e_g (G M^2/R^4); 0: no liquid layer
  /// [Nt] particle indices, positively oriented as built, each with a liquid or crust corner; every
  /// corner is a pressure node (forces/liquid_pressure.hpp)
  std::vector<std::array<std::int32_t, 4>> tetrahedra;
  /// tau_M, t_grav: 0, the liquid springs stay elastic; > 0, a Maxwell liquid (docs/ocean.md,
  /// "A Maxwell liquid"): from the end of the relaxation their static forces are a fixed support
  /// (State::liquid_support) and their rest lengths creep toward their lengths at the rate 1/tau_M,
  /// so the liquid's shear relaxes and only its pressure holds a static load
  double maxwell_time = 0;
  bool present() const { return bulk_modulus > 0; }
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
