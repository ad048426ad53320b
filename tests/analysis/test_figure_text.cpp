// The one formatter of every number and title on the figures (analysis/figure_text): no negative
// zero, units on the encounter's parameters, and the time step (with its factor) in every title.
#include <gtest/gtest.h>

#include <string>

#include "analysis/figure_text.hpp"

using namespace tidalcrust;

namespace {
bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }
}  // namespace

TEST(FigureText, NumbersNeverReadNegativeZero) {
  for (const double tiny : {-1e-17, -0.0, -0.004, -4.9e-3}) {
    EXPECT_EQ(fixed_text(tiny, 2), "0.00") << tiny;
    EXPECT_EQ(signed_fixed_text(tiny, 2), "0.00") << tiny;
  }
  EXPECT_EQ(general_text(-0.0), "0");
  EXPECT_EQ(fixed_text(-0.4, 0), "0");
  // Values that do not round to zero keep their sign.
  EXPECT_EQ(fixed_text(-0.006, 2), "-0.01");
  EXPECT_EQ(signed_fixed_text(-1.5, 2), "-1.50");
  EXPECT_EQ(signed_fixed_text(1.84, 2), "+1.84");
  EXPECT_EQ(general_text(-1e-17), "-1e-17");
  EXPECT_EQ(general_text(0.5), "0.5");
}

TEST(FigureText, PanelAtPericenterReadsZero) {
  EXPECT_EQ(time_from_pericenter_text(-1e-17), "t \u2212 t_peri = 0.00 t_grav");
  EXPECT_EQ(time_from_pericenter_text(1.84), "t \u2212 t_peri = +1.84 t_grav");
  EXPECT_EQ(time_from_pericenter_text(-1.0), "t \u2212 t_peri = -1.00 t_grav");
}

TEST(FigureText, EncounterTitlesNameUnitsAndTheTimeStep) {
  const Encounter strong = encounter_of("strong", 0.5, 1.84, 1.6);
  // Branched from a relaxed body at step 750, t = 3 (dt 0.004): full and half time step.
  const StepClock full{3.0, 750, 0.004}, half{3.0, 750, 0.002};
  const std::string full_title = encounter_figure_title("strong: perturber orbit", strong, full);
  const std::string half_title = encounter_figure_title("strong: perturber orbit", strong, half);
  for (const std::string& title : {full_title, half_title}) {
    EXPECT_EQ(title.rfind("strong: perturber orbit\n", 0), 0u) << title;
    EXPECT_TRUE(contains(title, "M\u2082 = 0.5 M")) << title;
    EXPECT_TRUE(contains(title, "q = 1.84 R")) << title;
    EXPECT_TRUE(contains(title, "V_q = 1.6 \u221a(GM/R)")) << title;
  }
  EXPECT_TRUE(contains(full_title, "dt = 0.004 t_grav")) << full_title;
  EXPECT_FALSE(contains(full_title, "\u00d7")) << full_title;
  EXPECT_TRUE(contains(half_title, "dt = 0.002 t_grav = 0.5 \u00d7 the body's dt")) << half_title;
  EXPECT_NE(full_title, half_title);
  EXPECT_EQ(dt_factor_of(half), 0.5);
  EXPECT_EQ(dt_factor_of(full), 1.0);
  EXPECT_EQ(dt_factor_of({0.0, 0, 0.002}), 1.0);  // a stage from step 0 has no earlier dt
}

// Of a moon (docs/moon.md, "Output in SI") the texts give SI beside the model units: hours first
// in the time, the encounter's parameters and dt in SI on a third title line, the time axis in hours.
TEST(FigureText, AMoonsTextsGiveSiBesideTheModelUnits) {
  const MoonScale tethys{"Tethys", model_units(0.62e21, 531e3)};
  const double t_grav_h = tethys.units.time_s / 3600;  // 0.528 h
  EXPECT_EQ(time_from_pericenter_text(1.84, &tethys),
            "t \u2212 t_peri = " + signed_fixed_text(1.84 * t_grav_h, 2) + " h (+1.84 t_grav)");
  EXPECT_EQ(time_from_pericenter_text(-1e-17, &tethys), "t \u2212 t_peri = 0.00 h (0.00 t_grav)");
  const Encounter t5 = encounter_of("T5", 0.5, 1.84, 1.6);
  const StepClock clock{3.0, 750, 0.002};
  EXPECT_EQ(encounter_si_text(t5, clock, tethys),
            "Tethys: M\u2082 = 3.1e+20 kg, q = 977 km, V_q = 0.4466 km/s; dt = " +
                general_text(0.002 * tethys.units.time_s, 4) + " s");
  const std::string title = encounter_figure_title("T5: orbit", t5, clock, &tethys);
  EXPECT_EQ(title, encounter_figure_title("T5: orbit", t5, clock) + "\n" + encounter_si_text(t5, clock, tethys));
  EXPECT_EQ(si_text(1.84, Dimension::length, tethys), "977 km");
  EXPECT_EQ(time_axis_label(&tethys), "t \u2212 t_peri [h]");
  EXPECT_EQ(time_axis_label(nullptr), "t \u2212 t_peri [t_grav]");
}
