#include <gtest/gtest.h>

#include <string>

#include "base/errors.hpp"
#include "model/recorded_encounter.hpp"
#include "support/synthetic_encounter.hpp"

using namespace tidalcrust;
using tidalcrust::test_support::synthetic_encounter;

TEST(RecordedEncounter, RefusesOtherStagesAndMissingScalars) {
  Checkpoint c = synthetic_encounter(1);
  const RecordedEncounter e = recorded_encounter(c, "ENC.h5");
  EXPECT_EQ(e.name, "T5");
  EXPECT_EQ(e.perturber_mass, 0.5);
  EXPECT_EQ(e.pericenter_time, 1.2);
  c.stage.scalars.erase(encounter_keys::pericenter_time);
  try {
    recorded_encounter(c, "ENC.h5");
    FAIL();
  } catch (const InputError& err) {
    EXPECT_NE(std::string(err.what()).find("pericenter_time"), std::string::npos);
  }
  c.stage.stage = "relax";
  EXPECT_THROW(recorded_encounter(c, "ENC.h5"), InputError);
}
