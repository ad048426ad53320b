#include "integrate/textbook_step.hpp"

#include "forces/gravity.hpp"
#include "forces/hinge_force.hpp"
#include "forces/spring_force.hpp"

namespace tidalcrust {

TextbookStep::TextbookStep(const Body& body, const State& state, ForceOptions options)
    : body_(body), options_(options), particles_(body.particle_count()), perturber_(state.perturber) {
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    TextbookParticle& p = particles_[i];
    for (std::size_t k = 0; k < 3; ++k) {
      p.x[k] = state.position[3 * i + k];
      p.v[k] = state.velocity[3 * i + k];
      p.a[k] = 0;
    }
    p.m = body.mass[i];
  }
}

void TextbookStep::compute_accelerations(const SpringState& springs, const HingeState& hinges) {
  const std::size_t n = particles_.size();
  std::vector<TextbookParticle>& p = particles_;
  for (auto& q : p) q.a[0] = q.a[1] = q.a[2] = 0;
  const double eps2 = body_.softening * body_.softening;

  if (options_.self_gravity)
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j) {
        const double dx = p[j].x[0] - p[i].x[0], dy = p[j].x[1] - p[i].x[1], dz = p[j].x[2] - p[i].x[2];
        const double f =
            PlummerPairEvaluator{p[i].m, p[j].m, eps2}.force_and_energy(dx * dx + dy * dy + dz * dz).inverse_cube;
        p[i].a[0] += p[j].m * f * dx;
        p[i].a[1] += p[j].m * f * dy;
        p[i].a[2] += p[j].m * f * dz;
        p[j].a[0] -= p[i].m * f * dx;
        p[j].a[1] -= p[i].m * f * dy;
        p[j].a[2] -= p[i].m * f * dz;
      }

  const CrossSoftening cross{options_.cross_strain_scale, options_.cross_min_force_factor};
  for (std::size_t s = 0; s < body_.spring_count(); ++s) {
    TextbookParticle& a = p[static_cast<std::size_t>(body_.springs[s][0])];
    TextbookParticle& b = p[static_cast<std::size_t>(body_.springs[s][1])];
    const Vec3 d(a.x[0] - b.x[0], a.x[1] - b.x[1], a.x[2] - b.x[2]);
    const Vec3 dv(a.v[0] - b.v[0], a.v[1] - b.v[1], a.v[2] - b.v[2]);
    const bool softened =
        options_.cross_nonlinear && body_.spring_kind[s] == static_cast<std::uint8_t>(SpringKind::cross);
    const SpringEvaluator spring(springs.rest_length[s], springs.stiffness[s],
                                 options_.damping * reduced_mass(a.m, b.m), softened ? &cross : nullptr);
    const Vec3 f = spring.force(d, dv);
    for (int k = 0; k < 3; ++k) {
      a.a[k] += f[k] / a.m;
      b.a[k] -= f[k] / b.m;
    }
  }

  for (std::size_t h = 0; h < body_.hinge_count(); ++h) {
    TextbookParticle* q[4];
    Vec3 x[4];
    for (std::size_t v = 0; v < 4; ++v) {
      q[v] = &p[static_cast<std::size_t>(body_.hinges[h][v])];
      x[v] = Vec3(q[v]->x[0], q[v]->x[1], q[v]->x[2]);
    }
    const HingeForces f =
        HingeEvaluator(hinges.rest_angle[h], body_.hinge_stiffness[h]).force_and_energy(x[0], x[1], x[2], x[3]);
    for (std::size_t v = 0; v < 4; ++v)
      for (int k = 0; k < 3; ++k) q[v]->a[k] += f.on[v][k] / q[v]->m;
  }

  perturber_acceleration_ = {0, 0, 0};
  if (perturber_.present)
    for (auto& q : p) {
      double d[3];
      for (std::size_t k = 0; k < 3; ++k) d[k] = perturber_.position[k] - q.x[k];
      const double f = PlummerPairEvaluator{q.m, perturber_.mass, eps2}
                           .force_and_energy(d[0] * d[0] + d[1] * d[1] + d[2] * d[2])
                           .inverse_cube;
      for (std::size_t k = 0; k < 3; ++k) {
        q.a[k] += perturber_.mass * f * d[k];
        perturber_acceleration_[k] -= q.m * f * d[k];
      }
    }
}

void TextbookStep::step(const SpringState& springs, const HingeState& hinges, double dt) {
  for (auto& q : particles_)
    for (int k = 0; k < 3; ++k) q.x[k] += 0.5 * dt * q.v[k];
  for (std::size_t k = 0; k < 3; ++k) perturber_.position[k] += 0.5 * dt * perturber_.velocity[k];
  compute_accelerations(springs, hinges);
  for (auto& q : particles_)
    for (int k = 0; k < 3; ++k) {
      q.v[k] += dt * q.a[k];
      q.x[k] += 0.5 * dt * q.v[k];
    }
  for (std::size_t k = 0; k < 3; ++k) {
    perturber_.velocity[k] += dt * perturber_acceleration_[k];
    perturber_.position[k] += 0.5 * dt * perturber_.velocity[k];
  }
}

}  // namespace tidalcrust
