#include "common/analysis/metric_vocabulary.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace fnet {
namespace {

using ::testing::HasSubstr;

std::string error_of(std::string_view name, std::optional<double> q) {
  try {
    parse_metric(name, q);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no error";
}

TEST(MetricVocabulary, NamesMapToTheirStoredSeriesAndExponents) {
  const MetricChoice b = parse_metric("bottleneck");
  EXPECT_TRUE(b.is_bottleneck());
  EXPECT_EQ(b.stored, Metric::bottleneck);
  EXPECT_EQ(parse_metric("wasserstein1").q, 1.0);
  EXPECT_EQ(parse_metric("wasserstein1").stored, Metric::wasserstein1);
  EXPECT_EQ(parse_metric("wasserstein2", 2.0).stored, Metric::wasserstein2);
  EXPECT_EQ(parse_metric("wasserstein", 1.0).stored, Metric::wasserstein1);
  EXPECT_EQ(parse_metric("wasserstein", 2.0).stored, Metric::wasserstein2);
  const MetricChoice w = parse_metric("wasserstein", 3.5);
  EXPECT_FALSE(w.stored.has_value());
  EXPECT_FALSE(w.is_bottleneck());
  EXPECT_EQ(w.label(), "wasserstein q=3.5");
  EXPECT_EQ(parse_metric("wasserstein2").label(), "wasserstein2");
}

TEST(MetricVocabulary, MisusedExponentsAreErrorsThatSayWhy) {
  EXPECT_THAT(error_of("bottleneck", 2.0), HasSubstr("does not apply to metric 'bottleneck'"));
  EXPECT_THAT(error_of("wasserstein1", 2.0), HasSubstr("contradicts metric 'wasserstein1'"));
  EXPECT_THAT(error_of("wasserstein", std::nullopt), HasSubstr("needs q"));
  EXPECT_THAT(error_of("wasserstein", 0.5), HasSubstr("got 0.5"));
  EXPECT_THAT(error_of("wasserstein", std::numeric_limits<double>::infinity()), HasSubstr("'bottleneck'"));
  EXPECT_THAT(error_of("wasserstein", std::nan("")), HasSubstr(">= 1"));
  EXPECT_THAT(error_of("Wasserstein2", std::nullopt), HasSubstr("unknown metric 'Wasserstein2'"));
}

TEST(MetricVocabulary, SeriesKeysAndDimensions) {
  EXPECT_EQ(series_key(Metric::wasserstein2, 1, ForceKind::tangential), "wasserstein2/pd1/tangential");
  EXPECT_EQ(series_key(Metric::bottleneck, 0, ForceKind::normal), "bottleneck/pd0/normal");
  EXPECT_EQ(check_dim(0), 0);
  EXPECT_EQ(check_dim(1), 1);
  EXPECT_THROW(check_dim(2), std::invalid_argument);
  EXPECT_THROW(check_dim(-1), std::invalid_argument);
}

}  // namespace
}  // namespace fnet
