#include <gtest/gtest.h>

#include <filesystem>
#include <vector>

#include "io/checkpoint_names.hpp"

using namespace tidalcrust;
namespace fs = std::filesystem;

TEST(SnapshotFiles, NamesAndPanelChoice) {
  EXPECT_EQ(snapshot_path("runs/T5/enc.h5", 1250), fs::path("runs/T5/enc.snap-1250.h5"));
  const std::vector<double> times = {0, 0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 3.5, 4.0};
  EXPECT_EQ(choose_snapshot_panels(times, 1.6, 20), (std::vector<std::size_t>{0, 1, 2, 3, 4, 5, 6, 7, 8}));
  const auto chosen = choose_snapshot_panels(times, 1.6, 4);  // even picks 0, 3, 5, 8; 3 is nearest 1.6
  EXPECT_EQ(chosen, (std::vector<std::size_t>{0, 3, 5, 8}));
  const auto with_pericenter = choose_snapshot_panels(times, 1.1, 4);  // nearest is 2
  EXPECT_EQ(with_pericenter, (std::vector<std::size_t>{0, 2, 5, 8}));
}
