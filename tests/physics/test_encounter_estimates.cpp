#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "physics/encounter_estimates.hpp"
#include "base/errors.hpp"

using namespace tidalcrust;

// Section 1.1: "the strain caused by the tidal encounter could be of order 10% for a parabolic
// equal mass encounter" (q = 2R, V_q = sqrt(2) v_c) with e_g/E between 0.1 and 1.
TEST(EncounterEstimates, GrazingParabolicEqualMassGivesStrainOfOrderTenPercent) {
  const Encounter grazing = grazing_parabolic_encounter();  // M2 = 1, q = 2, V_q = sqrt(2)
  // V_q is the escape speed at q: V_q^2 = 2 G (M + M2) / q.
  EXPECT_DOUBLE_EQ(grazing.pericenter_speed * grazing.pericenter_speed,
                   2.0 * (1.0 + grazing.perturber_mass) / grazing.pericenter);
  for (double e_g_over_E : {0.1, 0.2, 0.5, 1.0}) {
    const auto est = estimate_encounter(grazing, 1.0 / e_g_over_E);
    EXPECT_NEAR(est.strain, std::sqrt(e_g_over_E) / (4.0 * std::sqrt(2.0)), 1e-15);
    EXPECT_GT(est.strain, 0.05);
    EXPECT_LT(est.strain, 0.2);
  }
  // Press's eta = Delta v / v_c = 2 m R / (q^2 V_q) of this encounter.
  EXPECT_NEAR(estimate_encounter(grazing, 1.0).delta_v, 1.0 / (2.0 * std::sqrt(2.0)), 1e-15);
}

TEST(EncounterEstimates, EquationsAreMutuallyConsistent) {
  const Encounter g = encounter_of("T5", 0.5, 1.84, 1.60);
  const double E = 3.0;  // e_g
  const auto est = estimate_encounter(g, E);
  const double tidal = 0.5 / (1.84 * 1.84) / 1.60;  // (R/q)^2 (m/M) (v_c/V_q)
  EXPECT_NEAR(est.strain, tidal / std::sqrt(E), 1e-15);
  EXPECT_NEAR(est.delta_v, 2 * tidal, 1e-15);
  EXPECT_NEAR(est.encounter_time, 2 * 1.84 / 1.60, 1e-15);
  EXPECT_NEAR(est.elastic_time, 1 / std::sqrt(E), 1e-15);
  EXPECT_NEAR(est.strain_rate, est.strain / est.elastic_time, 1e-15);  // eq. 10
  EXPECT_NEAR(est.time_ratio, 1.84 / 1.60 * std::sqrt(E), 1e-14);      // eq. 11 as printed
  // The paper's eq. 11 is half of t_enc/t_elas with t_enc = 2q/V_q (eq. 2).
  EXPECT_NEAR(est.time_ratio, 0.5 * est.encounter_time / est.elastic_time, 1e-14);
  // eq. 4, Delta v^2 ~ eps^2 E / rho with rho = 3/(4 pi), gives eq. 5 up to 2/sqrt(4 pi/3) = 0.977.
  const double balance_strain = est.delta_v / std::sqrt(E / (3.0 / (4.0 * std::numbers::pi)));
  EXPECT_NEAR(balance_strain / est.strain, 2.0 / std::sqrt(4.0 * std::numbers::pi / 3.0), 1e-14);
}

// "The ratio E_ice/e_g is large enough that the time scale for the encounter could be a few
// times longer than the elastic time scale": E = 3 e_g (the T-series interior, section 2.9).
TEST(EncounterEstimates, EncounterIsAFewElasticTimesLong) {
  const auto est = estimate_encounter(grazing_parabolic_encounter(), 3.0);
  EXPECT_GT(est.time_ratio, 1.0);
  EXPECT_LT(est.time_ratio, 5.0);
}

TEST(EncounterEstimates, PhysicalUnitsForDione) {
  const auto scales = body_scales(find_table1_body("Dione"));
  const double E = youngs_in_e_g(ice_youngs_modulus_GPa, scales);
  EXPECT_NEAR(E, 0.9 / scales.e_g_GPa, 1e-15);
  const auto est = estimate_encounter(grazing_parabolic_encounter(), E);
  // Strain rate in 1/s is E-independent: (R/q)^2 (m/M) (v_c/V_q) / t_grav ~ 1e-4 /s for rho ~ 1.
  const double rate_per_s = est.strain_rate / scales.t_grav_s;
  EXPECT_NEAR(rate_per_s, 1.0 / (4.0 * std::sqrt(2.0)) / scales.t_grav_s, 1e-18);
  EXPECT_GT(rate_per_s, 1e-5);
  EXPECT_LT(rate_per_s, 1e-3);
}

TEST(EncounterEstimates, RejectsBadInput) {
  EXPECT_THROW(estimate_encounter(encounter_of("bad", 1.0, 0.0, 1.4), 1.0), InputError);
  EXPECT_THROW(estimate_encounter(encounter_of("bad", 1.0, -2.0, 1.4), 1.0), InputError);
  EXPECT_THROW(estimate_encounter(encounter_of("bad", -1.0, 2.0, 1.4), 1.0), InputError);
  EXPECT_THROW(estimate_encounter(encounter_of("bad", 1.0, 2.0, 0.0), 1.0), InputError);
  EXPECT_THROW(estimate_encounter(encounter_of("bad", std::nan(""), 2.0, 1.4), 1.0), InputError);
  EXPECT_THROW(estimate_encounter(encounter_of("bad", 1.0, 2.0, 1.4), 0.0), InputError);
  EXPECT_THROW(youngs_in_e_g(-0.9, body_scales(find_table1_body("Rhea"))), InputError);
  EXPECT_NO_THROW(estimate_encounter(encounter_of("bad", 0.0, 2.0, 1.4), 1.0));  // no perturber: zero strain
}
