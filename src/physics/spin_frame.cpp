#include "physics/spin_frame.hpp"

#include <cmath>
#include <limits>

#include <Eigen/Dense>

#include "base/portable_math.hpp"
#include "model/center_of_mass.hpp"

namespace tidalcrust {

Matrix3 spin_rotation(double angular_velocity, double time, bool portable) {
  const double angle = angular_velocity * time;
  if (angle == 0) return Matrix3::Identity();
  const double c = portable_math::cos(angle, portable), s = portable_math::sin(angle, portable);
  Matrix3 r;
  r << c, -s, 0, s, c, 0, 0, 0, 1;
  return r;
}

void add_rotating_frame_acceleration(const Body& body, double angular_velocity, const double* x, const double* v,
                                     std::vector<double>& a) {
  if (angular_velocity == 0) return;
  const Vec3 c = mass_weighted_mean(body, x);
  const double w2 = angular_velocity * angular_velocity, two_w = 2 * angular_velocity;
  const std::size_t n = body.particle_count();
  for (std::size_t i = 0; i < n; ++i) {
    a[3 * i] += w2 * (x[3 * i] - c.x());
    a[3 * i + 1] += w2 * (x[3 * i + 1] - c.y());
    if (v) {
      a[3 * i] += two_w * v[3 * i + 1];
      a[3 * i + 1] -= two_w * v[3 * i];
    }
  }
}

void rotating_to_inertial(const Body& body, State& state, double angular_velocity, bool portable) {
  if (angular_velocity == 0) return;
  const Matrix3 turn = spin_rotation(angular_velocity, state.time, portable);
  const Vec3 c = body_center_of_mass(body, state);
  const Vec3 spin(0, 0, angular_velocity);
  for (std::size_t i = 0; i < body.particle_count(); ++i) {
    const Vec3 r = vec3_at(state.position, i) - c;
    const Vec3 v = vec3_at(state.velocity, i) + spin.cross(r);
    set_vec3(state.position, i, Vec3(c + turn * r));
    set_vec3(state.velocity, i, Vec3(turn * v));
  }
}

ShellFlattening shell_flattening(const Body& body, const State& state, const Matrix3& to_body) {
  const Vec3 c = body_center_of_mass(body, state);
  // Normal equations of r = a0 + a2 P2, summed in node order.
  double n = 0, sp = 0, spp = 0, sr = 0, srp = 0;
  std::vector<double> radius, p2;
  for (std::size_t i = 0; i < body.particle_count(); ++i) {
    if (body.species[i] != static_cast<std::uint8_t>(Species::shell)) continue;
    const Vec3 r = to_body * (vec3_at(state.position, i) - c);
    const double d = r.norm(), mu = r.z() / d, p = 1.5 * mu * mu - 0.5;
    radius.push_back(d), p2.push_back(p);
    n += 1, sp += p, spp += p * p, sr += d, srp += d * p;
  }
  ShellFlattening f;
  const double det = n * spp - sp * sp;
  if (radius.empty() || det == 0) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    return {nan, nan, nan, nan, nan, nan};
  }
  f.p2_amplitude = (n * srp - sp * sr) / det;
  f.mean_radius = (sr - f.p2_amplitude * sp) / n;
  f.equatorial_radius = f.mean_radius - 0.5 * f.p2_amplitude;
  f.polar_radius = f.mean_radius + f.p2_amplitude;
  f.flattening = (f.equatorial_radius - f.polar_radius) / f.equatorial_radius;
  double squares = 0;
  for (std::size_t k = 0; k < radius.size(); ++k) {
    const double e = radius[k] - f.mean_radius - f.p2_amplitude * p2[k];
    squares += e * e;
  }
  f.rms_residual = std::sqrt(squares / n);
  return f;
}

namespace {

/// I^-1 L about the centre of mass c (see body_angular_velocity).
Vec3 angular_velocity_about(const Body& body, const State& state, const Vec3& c) {
  if (body.particle_count() < 3) return Vec3::Zero();
  const Vec3 vc = body_center_of_mass_velocity(body, state);
  Matrix3 inertia = Matrix3::Zero();
  Vec3 momentum = Vec3::Zero();
  for (std::size_t i = 0; i < body.particle_count(); ++i) {
    const Vec3 r = vec3_at(state.position, i) - c;
    inertia += body.mass[i] * (r.squaredNorm() * Matrix3::Identity() - r * r.transpose());
    momentum += body.mass[i] * r.cross(Vec3(vec3_at(state.velocity, i) - vc));
  }
  return inertia.ldlt().solve(momentum);
}

}  // namespace

Vec3 body_angular_velocity(const Body& body, const State& state) {
  return angular_velocity_about(body, state, body_center_of_mass(body, state));
}

void remove_rigid_rotation(const Body& body, State& state) {
  const Vec3 c = body_center_of_mass(body, state);  // once: this runs after every relax step
  const Vec3 w = angular_velocity_about(body, state, c);
  for (std::size_t i = 0; i < body.particle_count(); ++i)
    set_vec3(state.velocity, i, Vec3(vec3_at(state.velocity, i) - w.cross(Vec3(vec3_at(state.position, i) - c))));
}

double centrifugal_flattening(double h2, double angular_velocity) {
  return 0.5 * h2 * angular_velocity * angular_velocity;
}

}  // namespace tidalcrust
