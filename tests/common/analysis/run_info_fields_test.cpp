// The field list of RunInfo, which every codec of the run announcement walks.
#include <iomanip>
#include <set>
#include <sstream>
#include <string>
#include <typeinfo>
#include <vector>

#include <gtest/gtest.h>

#include "common/run/run_frame.hpp"
#include "tests/support/run_info_sample.hpp"

namespace fnet {
namespace {

// The compile-time check counts the fields; this one sees that they are the members, each once.
TEST(RunInfoFields, VisitEveryMemberOnce) {
  RunInfo info;
  std::set<const void*> members;
  std::size_t visits = 0;
  for_each_run_info_field(
      [&](const RunInfoField&, auto& value) {
        members.insert(&value);
        ++visits;
      },
      info);
  EXPECT_EQ(visits, member_count<RunInfo>());
  EXPECT_EQ(members.size(), member_count<RunInfo>());
}

TEST(RunInfoFields, NamesAreUniqueInEveryCodec) {
  std::set<std::string> names, attributes, keys;
  std::size_t n = 0;
  for_each_run_info_field([&](const RunInfoField& field) {
    names.insert(field.name);
    attributes.insert(field.attribute);
    keys.insert(field.key);
    ++n;
  });
  EXPECT_EQ(names.size(), n);
  EXPECT_EQ(attributes.size(), n);
  EXPECT_EQ(keys.size(), n);
}

// What makes the round trips of the codecs able to fail: no field at its default, no two fields of
// one type alike (so that a swap shows).
TEST(RunInfoFields, SampleGivesEveryFieldAValueOfItsOwn) {
  const RunInfo sample = testing::distinct_run_info(), defaults;
  std::set<std::string> values;
  std::size_t n = 0;
  for_each_run_info_field(
      [&](const RunInfoField& field, const auto& value, const auto& default_value) {
        EXPECT_NE(value, default_value) << field.name;
        std::ostringstream text;
        text << typeid(value).name() << ' ' << std::setprecision(17) << value;
        values.insert(text.str());
        ++n;
      },
      sample, defaults);
  EXPECT_EQ(values.size(), n);
}

}  // namespace
}  // namespace fnet
