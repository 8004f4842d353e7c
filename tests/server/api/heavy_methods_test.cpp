// Which requests are heavy: those that compute distances (distance.get, blocks.get, the curves,
// a series that is not stored) or read a network back from the store (network.get) hand their
// work to ApiContext::offload, fnet-server's analysis pool, and end their call from there; the
// others answer at once on the transport's thread.
#include <chrono>
#include <exception>
#include <functional>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <boost/asio/thread_pool.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "server/api/api_methods.hpp"
#include "tests/support/synthetic_frame.hpp"
#include "tests/support/temp_dir.hpp"

namespace fnet::server {
namespace {

using json = nlohmann::json;

struct Api {
  testing::TempDir dir;
  boost::asio::thread_pool pool{1};
  Registry registry{dir.path(), pool};
  ApiContext context{registry};
  std::vector<std::function<void()>> offloaded;
  Api() {
    context.offload = [this](std::function<void()> work) { offloaded.push_back(std::move(work)); };
  }
};

struct Ended {
  bool called = false;
  json result;
  std::exception_ptr error;
};

// Calls `method` through make_api; returns how the call ended so far.
Ended call(Api& api, const rpc::Handler& handler, const std::string& method, const json& params) {
  Ended ended;
  try {
    handler(method, params, nullptr, [&](json r, std::exception_ptr e) {
      ended.called = true;
      ended.result = std::move(r);
      ended.error = e;
    });
  } catch (...) {
    ended.called = true;
    ended.error = std::current_exception();
  }
  // Run what was offloaded, as the pool would, and see it end the call.
  while (!api.offloaded.empty()) {
    EXPECT_FALSE(ended.called) << method << " ended before its offloaded work ran";
    auto work = std::move(api.offloaded.front());
    api.offloaded.erase(api.offloaded.begin());
    work();
  }
  return ended;
}

int error_code(const Ended& e) {
  try {
    std::rethrow_exception(e.error);
  } catch (const rpc::Error& err) {
    return err.code();
  } catch (...) {
    return 0;
  }
}

TEST(HeavyMethods, DistancesBlocksCurvesAndComputedSeriesRunOffloadedTheRestAtOnce) {
  Api api;
  const rpc::Handler handler = make_api(api.context);
  struct Case {
    std::string method;
    json params;
    bool heavy;
  };
  const std::vector<Case> cases{
      {"distance.get", {{"run", "r"}, {"frame", 1}, {"other_frame", 0}, {"metric", "bottleneck"}}, true},
      {"blocks.get", {{"run", "r"}, {"frame", 1}, {"other_frame", 0}, {"metric", "bottleneck"}}, true},
      {"network.get", {{"run", "r"}, {"frame", 1}}, true},
      {"ensemble.series", {{"run", "r"}, {"metric", "bottleneck"}}, true},
      {"series.get", {{"run", "r"}, {"metric", "wasserstein"}, {"q", 3}}, true},
      {"series.get", {{"run", "r"}, {"metric", "bottleneck"}, {"essential", "separate"}}, true},
      {"series.get", {{"run", "r"}, {"metric", "bottleneck"}}, false},
      {"series.get", {{"run", "r"}, {"ratio", "wasserstein1"}}, false},
      {"diagram.get", {{"run", "r"}, {"frame", 0}}, false},
      {"run.get", {{"run", "r"}}, false},
  };
  for (const Case& c : cases) {
    std::size_t offloaded = 0;
    api.context.offload = [&](std::function<void()> work) {
      ++offloaded;
      api.offloaded.push_back(std::move(work));
    };
    const Ended e = call(api, handler, c.method, c.params);
    EXPECT_EQ(offloaded, c.heavy ? 1u : 0u) << c.method << " " << c.params.dump();
    ASSERT_TRUE(e.called) << c.method;
    // No run 'r': every call ends with the unknown-run error, wherever it ran.
    EXPECT_EQ(error_code(e), rpc::kUnknownRun) << c.method << " " << c.params.dump();
  }
  // Parameters are checked before any work is handed over: an unknown one ends the call at once.
  std::size_t offloaded = 0;
  api.context.offload = [&](std::function<void()> work) {
    ++offloaded;
    work();
  };
  const Ended bad = call(api, handler, "distance.get", {{"frame", 1}, {"other_frame", 0}, {"dimension", 1}});
  EXPECT_EQ(offloaded, 0u);
  EXPECT_EQ(error_code(bad), rpc::kInvalidParams);
}

// Two consecutive frames of 3 000 disks, analyzed by the registry: their distances take thousands
// of the solvers' steps.
void add_two_frames(Registry& registry) {
  Frame frame = testing::synthetic_frame(testing::disordered_packing(2, 3000, 7));
  for (std::uint32_t k = 0; k < 2; ++k) {
    RunFrame f;
    f.header = {"big", k, 100ull * k, 1.0 * k, 0.84, 4.0};
    f.frame = frame;
    f.frame.label = frame_label("big", k);
    registry.on_frame(std::move(f));
    frame = testing::next_frame(frame, {.seed = k + 1});
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (std::chrono::steady_clock::now() < deadline) {
    const auto s = registry.run("big");
    if (s && s->frames == 2 && s->pending == 0) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  FAIL() << "frames not analyzed";
}

TEST(HeavyMethods, AHeavyCallPastItsBudgetIsStoppedWithTheLimitNamedAndTheNextCallIsServed) {
  Api api;
  add_two_frames(api.registry);
  const json w2 = {{"run", "big"}, {"frame", 1}, {"other_frame", 0}, {"metric", "wasserstein"}, {"q", 2}};
  api.context.max_call_seconds = std::chrono::duration<double>(1e-6);
  const rpc::Handler bounded = make_api(api.context);
  const Ended stopped = call(api, bounded, "distance.get", w2);
  ASSERT_TRUE(stopped.called);
  try {
    std::rethrow_exception(stopped.error);
  } catch (const rpc::Error& e) {
    EXPECT_EQ(e.code(), rpc::kLimitExceeded);
    EXPECT_EQ(e.data().value("limit", ""), "max_call_seconds") << e.data().dump();
    EXPECT_EQ(e.data().value("value", -1.0), 1e-6) << e.data().dump();
  } catch (...) {
    ADD_FAILURE() << "distance.get past its budget did not end with error -32008";
  }
  api.context.max_call_seconds = std::chrono::duration<double>(600);
  const Ended served = call(api, make_api(api.context), "distance.get", w2);
  ASSERT_TRUE(served.called);
  ASSERT_FALSE(served.error);
  EXPECT_GT(served.result.value("value", 0.0), 0.0) << served.result.dump();
}

}  // namespace
}  // namespace fnet::server
