#include "model/stage_records.hpp"

namespace tidalcrust {

namespace {
template <std::size_t I = 0>
bool make_record_at(const std::string& name, StageRecord& record) {
  if constexpr (I < std::variant_size_v<StageRecord>) {
    if (name == stage_names[I]) {
      record.emplace<I>();
      return true;
    }
    return make_record_at<I + 1>(name, record);
  } else {
    return false;
  }
}
}  // namespace

bool make_stage_record(const std::string& name, StageRecord& record) { return make_record_at(name, record); }

std::string stage_list(StageSet stages, const char* separator) {
  std::string out;
  for (std::size_t i = 0; i < stage_count; ++i)
    if (stages.contains(static_cast<StageId>(i))) out += (out.empty() ? "" : separator) + std::string(stage_names[i]);
  return out;
}

}  // namespace tidalcrust
