#pragma once
// Eight hinges at once (AVX-512): HingeEvaluator::force_and_energy's forces, collapse flags and
// E_h / C, lane by lane the same IEEE operations in the same order (products, sums, divisions
// and square roots are correctly rounded in a vector as in a scalar; no FMA), so the same bits.
// Only where __AVX512F__ is defined; ForceField falls back to the evaluator elsewhere and for
// the last hinges of a range. tests/forces/test_hinge_force_x8.cpp compares the bits.
#if defined(__AVX512F__)
#include <immintrin.h>

#include <cstddef>
#include <cstdint>

#include "forces/hinge_force.hpp"

namespace tidalcrust {

/// Hinges [first, first + 8): corners[4 * h + v] the particle of vertex v (wing_1, wing_2,
/// edge_a, edge_b) of hinge h, positions [N*3] (R), rest[h] its HalfRestAngle, stiffness[h] its
/// k_e (G M^2/R^2). Writes force[12 h + 3 v + k] (G M^2/R^2) and energy_per_prefactor[h]
/// (G M^2/R^2), as HingeForces::on and ::energy_per_prefactor; returns the lanes (bit l: hinge
/// first + l) whose face collapsed (HingeForces::collapsed).
inline unsigned hinge_forces_x8(std::size_t first, const std::int32_t* corners, const double* position,
                                const HalfRestAngle* rest, const double* stiffness, double* force,
                                double* energy_per_prefactor) {
  struct V3 {
    __m512d x, y, z;
  };
  // The all-lanes masked forms: GCC 12 warns about the plain ones' undefined pass-through operand.
  const auto gather = [](__m256i index, const double* base) {
    return _mm512_mask_i32gather_pd(_mm512_setzero_pd(), 0xFF, index, base, 8);
  };
  const auto sqrt = [](__m512d a) { return _mm512_maskz_sqrt_pd(0xFF, a); };
  const auto sub = [](const V3& a, const V3& b) {
    return V3{_mm512_sub_pd(a.x, b.x), _mm512_sub_pd(a.y, b.y), _mm512_sub_pd(a.z, b.z)};
  };
  // Eigen's Vector3d: a.cross(b) componentwise, a.dot(b) = (a0 b0 + a1 b1) + a2 b2.
  const auto cross = [](const V3& a, const V3& b) {
    return V3{_mm512_sub_pd(_mm512_mul_pd(a.y, b.z), _mm512_mul_pd(a.z, b.y)),
              _mm512_sub_pd(_mm512_mul_pd(a.z, b.x), _mm512_mul_pd(a.x, b.z)),
              _mm512_sub_pd(_mm512_mul_pd(a.x, b.y), _mm512_mul_pd(a.y, b.x))};
  };
  const auto dot = [](const V3& a, const V3& b) {
    return _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(a.x, b.x), _mm512_mul_pd(a.y, b.y)), _mm512_mul_pd(a.z, b.z));
  };
  const auto scale = [](__m512d s, const V3& a) {
    return V3{_mm512_mul_pd(s, a.x), _mm512_mul_pd(s, a.y), _mm512_mul_pd(s, a.z)};
  };
  // Vertex v of the 8 hinges: corners are 4 per hinge, positions 3 per particle.
  const __m256i lane4 = _mm256_setr_epi32(0, 4, 8, 12, 16, 20, 24, 28);
  const auto vertex = [&](int v) {
    const __m256i particle = _mm256_i32gather_epi32(corners + 4 * first + v, lane4, 4);
    const __m256i index = _mm256_mullo_epi32(particle, _mm256_set1_epi32(3));
    return V3{gather(index, position), gather(index, position + 1),
              gather(index, position + 2)};
  };
  const V3 x1 = vertex(0), x2 = vertex(1), x3 = vertex(2), x4 = vertex(3);
  const __m256i lane2 = _mm256_setr_epi32(0, 2, 4, 6, 8, 10, 12, 14);
  const double* rest_pairs = reinterpret_cast<const double*>(rest + first);  // {sin, cos} per hinge
  const __m512d rest_sin = gather(lane2, rest_pairs);
  const __m512d rest_cos = gather(lane2, rest_pairs + 1);
  const __m512d k_e = _mm512_loadu_pd(stiffness + first);
  const __m512d one = _mm512_set1_pd(1.0), half = _mm512_set1_pd(0.5), two = _mm512_set1_pd(2.0),
                zero = _mm512_setzero_pd();

  const V3 e = sub(x4, x3);
  const V3 n1 = cross(sub(x1, x3), sub(x1, x4));
  const V3 n2 = cross(sub(x2, x4), sub(x2, x3));
  const __m512d n1_sq = dot(n1, n1), n2_sq = dot(n2, n2);
  const __m512d n1_norm = sqrt(n1_sq), n2_norm = sqrt(n2_sq);
  const __m512d length = sqrt(dot(e, e));
  const __m512d inv_length = _mm512_div_pd(one, length);
  const __m512d inv_normal_product = _mm512_div_pd(one, _mm512_mul_pd(n1_norm, n2_norm));
  const __m512d cos_theta = _mm512_mul_pd(dot(n1, n2), inv_normal_product);
  const __m512d sin_theta = _mm512_mul_pd(dot(cross(n1, n2), e), _mm512_mul_pd(inv_normal_product, inv_length));
  // Both half-angle branches, then the one the evaluator takes (cos_theta >= 0) per lane.
  const __mmask8 upper = _mm512_cmp_pd_mask(cos_theta, zero, _CMP_GE_OQ);
  const __m512d cos_half_upper = sqrt(_mm512_mul_pd(half, _mm512_add_pd(one, cos_theta)));
  const __m512d sin_half_upper = _mm512_div_pd(sin_theta, _mm512_mul_pd(two, cos_half_upper));
  const __m512d sign_bit = _mm512_set1_pd(-0.0);
  const __m512d sin_half_lower =  // copysign(sqrt(0.5 (1 - cos)), sin)
      _mm512_or_pd(_mm512_andnot_pd(sign_bit, sqrt(_mm512_mul_pd(half, _mm512_sub_pd(one, cos_theta)))),
                   _mm512_and_pd(sign_bit, sin_theta));
  const __m512d cos_half_lower = _mm512_div_pd(sin_theta, _mm512_mul_pd(two, sin_half_lower));
  const __m512d sin_half = _mm512_mask_blend_pd(upper, sin_half_lower, sin_half_upper);
  const __m512d cos_half = _mm512_mask_blend_pd(upper, cos_half_lower, cos_half_upper);
  const __m512d sin_half_difference =
      _mm512_sub_pd(_mm512_mul_pd(sin_half, rest_cos), _mm512_mul_pd(cos_half, rest_sin));
  const __m512d k_e_c = _mm512_div_pd(_mm512_mul_pd(_mm512_mul_pd(k_e, length), length), _mm512_add_pd(n1_norm, n2_norm));
  const __m512d magnitude = _mm512_mul_pd(k_e_c, sin_half_difference);
  const V3 w1 = scale(_mm512_div_pd(one, n1_sq), n1), w2 = scale(_mm512_div_pd(one, n2_sq), n2);
  // !(std::min(n1, n2) >= f L^2): std::min(a, b) is b < a ? b : a, as _mm512_min_pd(b, a).
  const __mmask8 not_collapsed = _mm512_cmp_pd_mask(
      _mm512_maskz_min_pd(0xFF, n2_norm, n1_norm),
      _mm512_mul_pd(_mm512_mul_pd(_mm512_set1_pd(collapsed_face_fraction), length), length), _CMP_GE_OQ);

  const __m512d wing = _mm512_mul_pd(magnitude, length);
  const V3 on0 = scale(wing, w1), on1 = scale(wing, w2);
  const auto along = [&](__m512d m, const V3& d) { return _mm512_mul_pd(_mm512_mul_pd(m, dot(d, e)), inv_length); };
  const __m512d minus_magnitude = _mm512_xor_pd(magnitude, sign_bit);
  const V3 a2 = scale(along(magnitude, sub(x1, x4)), w1), b2 = scale(along(magnitude, sub(x2, x4)), w2);
  const V3 a3 = scale(along(minus_magnitude, sub(x1, x3)), w1), b3 = scale(along(magnitude, sub(x2, x3)), w2);
  const V3 on2{_mm512_add_pd(a2.x, b2.x), _mm512_add_pd(a2.y, b2.y), _mm512_add_pd(a2.z, b2.z)};
  const V3 on3{_mm512_sub_pd(a3.x, b3.x), _mm512_sub_pd(a3.y, b3.y), _mm512_sub_pd(a3.z, b3.z)};

  const __m512d cos_half_difference =
      _mm512_add_pd(_mm512_mul_pd(cos_half, rest_cos), _mm512_mul_pd(sin_half, rest_sin));
  const __mmask8 small = _mm512_cmp_pd_mask(cos_half_difference, zero, _CMP_GE_OQ);
  const __m512d one_minus_cos = _mm512_mask_blend_pd(
      small, _mm512_sub_pd(one, cos_half_difference),
      _mm512_div_pd(_mm512_mul_pd(sin_half_difference, sin_half_difference), _mm512_add_pd(one, cos_half_difference)));
  _mm512_storeu_pd(energy_per_prefactor + first, _mm512_mul_pd(_mm512_mul_pd(two, k_e), one_minus_cos));

  // force[12 h + 3 v + k]: 12 doubles per hinge, written component by component.
  const __m256i lane12 = _mm256_setr_epi32(0, 12, 24, 36, 48, 60, 72, 84);
  double* out = force + 12 * first;
  const V3* on[4] = {&on0, &on1, &on2, &on3};
  for (int v = 0; v < 4; ++v) {
    _mm512_i32scatter_pd(out + 3 * v, lane12, on[v]->x, 8);
    _mm512_i32scatter_pd(out + 3 * v + 1, lane12, on[v]->y, 8);
    _mm512_i32scatter_pd(out + 3 * v + 2, lane12, on[v]->z, 8);
  }
  return static_cast<unsigned>(static_cast<__mmask8>(~not_collapsed));
}

}  // namespace tidalcrust
#endif
