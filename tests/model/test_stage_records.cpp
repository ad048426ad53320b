// Typed stage records (model/stage_records.hpp): typed access by stage, the stage a record names,
// and that every field is visited once.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "base/errors.hpp"
#include "model/checkpoint.hpp"
#include "support/synthetic_encounter.hpp"
#include "base/invariant.hpp"

using namespace tidalcrust;
using namespace tidalcrust::test_support;

TEST(StageRecord, TypedAccessRefusesOtherStagesNamingTheFile) {
  Checkpoint c = synthetic_encounter(1);
  const EncounterRecord& e = stage_record<EncounterRecord>(c, "ENC.h5");
  EXPECT_EQ(e.encounter.name, "T5");
  EXPECT_EQ(e.encounter.perturber_mass, 0.5);
  EXPECT_EQ(e.pericenter_time, 1.2);
  c.stage.record = RelaxRecord{};
  try {
    stage_record<EncounterRecord>(c, "ENC.h5");
    FAIL();
  } catch (const InputError& err) {
    EXPECT_STREQ(err.what(), "ENC.h5: stage is 'relax', expected an 'encounter' checkpoint");
  }
  EXPECT_THROW(c.stage.as<EncounterRecord>(), InternalError);
}

TEST(StageRecord, NamesFollowThePipelineAndMakeTheirRecord) {
  const char* expected[] = {"build", "stretch", "relax", "encounter"};
  for (const char* name : expected) {
    StageRecord record;
    ASSERT_TRUE(make_stage_record(name, record)) << name;
    EXPECT_STREQ(stage_name(record), name);
  }
  StageRecord record;
  EXPECT_FALSE(make_stage_record("analyze", record));
  EXPECT_STREQ(stage_name_of<RelaxRecord>(), "relax");
}

TEST(StageRecord, EveryFieldIsVisitedOnceWithAUnit) {
  auto check = [](const auto& record, std::size_t expected_fields) {
    std::set<std::string> names;
    std::size_t fields = 0;
    visit_fields(record, [&](const char* name, const auto&, const char* unit, const char* meaning) {
      ++fields;
      EXPECT_TRUE(names.insert(name).second) << name << " listed twice";
      EXPECT_NE(unit, nullptr) << name;
      EXPECT_GT(std::string(meaning).size(), 0u) << name;
    });
    EXPECT_EQ(fields, expected_fields);
  };
  check(BuildRecord{}, 3);
  check(StretchRecord{}, 9);
  check(RelaxRecord{}, 13);
  check(EncounterRecord{}, 31);  // 18 + the energy budget's three accumulators + the local rule's three + shadow_distance + flaw_length, growth_strain_factor + after and the orbit's three angles
}
