// Frames over real DDS on loopback: a publisher in a child process, the subscriber here.
#include "common/transport/frame_transport.hpp"

#include <unistd.h>

#include <chrono>
#include <csignal>
#include <map>
#include <random>
#include <set>
#include <sys/wait.h>
#include <thread>

#include <gtest/gtest.h>

#include "common/run/frame_bounds.hpp"
#include "fnet.h"
#include "tests/support/run_frame_compare.hpp"
#include "tests/support/run_info_sample.hpp"

namespace fnet {
namespace {

RunFrame make_frame(const std::string& run, std::uint32_t index, std::size_t n, std::size_t m) {
  std::mt19937_64 rng(1000 * index + n);
  std::uniform_real_distribution<double> u(-1e3, 1e3);
  std::uniform_int_distribution<std::uint32_t> pick(0, static_cast<std::uint32_t>(n - 1));
  RunFrame f;
  f.header = {run, index, 1000ull * index, 0.5 * index, 0.6 + 1e-3 * index, 3.25};
  f.frame.label = frame_label(run, index);
  f.frame.particle_count = n;
  for (std::size_t k = 0; k < n; ++k) f.frame.particles.push_back({u(rng), u(rng), std::fabs(u(rng))});
  if (index % 3 == 1) {  // every third frame is 3D
    f.frame.dimension = 3;
    for (Particle& p : f.frame.particles) p.z = u(rng);
  }
  for (std::size_t k = 0; k < m; ++k) f.frame.contacts.push_back({pick(rng), pick(rng), u(rng), std::fabs(u(rng))});
  for (std::size_t k = 0; k < 7; ++k) f.wall_contacts.push_back({pick(rng), u(rng), std::fabs(u(rng))});
  return f;
}

RunInfo make_info(const std::string& run) {
  return {run, 2000, 0.4, 0.5, 4000, 0.5, 0.8, 2.5e-5, 7.19377e-4, 0.9, 5, 42, R"({"particles":2000})", "mu05"};
}

using testing::expect_bit_exact;

// Runs `publish` in a child process (forked before this process creates any DDS entity); the parent's pipe end reads
// one byte when it has finished writing. The child then waits for `release` (a byte from the parent) so that late
// joiners can still be served from its durability history.
struct Publisher {
  pid_t pid = -1;
  int done_fd = -1, release_fd = -1;

  template <class Fn>
  explicit Publisher(Fn publish) {
    int done[2], release[2];
    if (pipe(done) != 0 || pipe(release) != 0) throw std::runtime_error("pipe");
    pid = fork();
    if (pid == 0) {
      close(done[0]);
      close(release[1]);
      int rc = 0;
      try {
        dds::FramePublisher pub(domain());
        publish(pub);
        if (!pub.wait_for_acks(DDS_SECS(30))) rc = 3;
        char c = 1;
        if (write(done[1], &c, 1) != 1) rc = 4;
        if (read(release[0], &c, 1) < 0) rc = 5;
      } catch (const std::exception& e) {
        std::fprintf(stderr, "publisher: %s\n", e.what());
        rc = 2;
      }
      _exit(rc);
    }
    close(done[1]);
    close(release[0]);
    done_fd = done[0];
    release_fd = release[1];
  }
  void wait_done() const {
    char c;
    ASSERT_EQ(read(done_fd, &c, 1), 1) << "publisher died before finishing";
  }
  int finish() {
    char c = 1;
    if (write(release_fd, &c, 1) != 1) ADD_FAILURE() << "release write failed";
    int status = 0;
    waitpid(pid, &status, 0);
    close(done_fd);
    close(release_fd);
    pid = -1;
    return WIFEXITED(status) ? WEXITSTATUS(status) : 100;
  }
  ~Publisher() {
    if (pid > 0) {
      kill(pid, SIGKILL);
      waitpid(pid, nullptr, 0);
    }
  }
  static dds_domainid_t domain() { return static_cast<dds_domainid_t>(std::stoi(std::getenv("FNET_TEST_DOMAIN"))); }
};

// Gives each test its own domain (set before any participant exists).
void use_domain(int id) { setenv("FNET_TEST_DOMAIN", std::to_string(id).c_str(), 1); }

dds::Received collect(dds::FrameSubscriber& sub, std::size_t frames, std::chrono::seconds limit) {
  dds::Received all;
  const auto deadline = std::chrono::steady_clock::now() + limit;
  while (all.frames.size() < frames && std::chrono::steady_clock::now() < deadline) {
    dds::Received got = sub.take(DDS_MSECS(200));
    for (auto& i : got.infos) all.infos.push_back(std::move(i));
    for (auto& f : got.frames) all.frames.push_back(std::move(f));
    for (auto& m : got.malformed) all.malformed.push_back(std::move(m));
  }
  return all;
}

TEST(FrameTransport, SubscriberReceivesEveryFrameBitExactInOrder) {
  use_domain(11);
  constexpr std::uint32_t kFrames = 40;
  Publisher pub([&](dds::FramePublisher& p) {
    // Wait for the subscriber to match, so this test checks live delivery (late joining is below).
    for (int k = 0; k < 100 && p.matched_readers() == 0; ++k)
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    p.publish(make_info("live"));
    for (std::uint32_t k = 0; k < kFrames; ++k) p.publish(make_frame("live", k, 2000, 4000));
  });
  dds::FrameSubscriber sub(Publisher::domain());  // after fork: a DDS runtime does not survive fork()
  const dds::Received got = collect(sub, kFrames, std::chrono::seconds(60));
  EXPECT_EQ(pub.finish(), 0);
  ASSERT_EQ(got.frames.size(), kFrames);
  ASSERT_EQ(got.infos.size(), 1u);
  EXPECT_EQ(got.infos[0], make_info("live"));
  for (std::uint32_t k = 0; k < kFrames; ++k) expect_bit_exact(make_frame("live", k, 2000, 4000), got.frames[k]);
  EXPECT_TRUE(got.malformed.empty());
}

TEST(FrameTransport, LateSubscriberGetsEveryFrameOfEveryRun) {
  use_domain(12);
  constexpr std::uint32_t kFrames = 30;
  Publisher pub([&](dds::FramePublisher& p) {
    for (const char* run : {"a", "b"}) {
      p.publish(make_info(run));
      for (std::uint32_t k = 0; k < kFrames; ++k) p.publish(make_frame(run, k, 500, 900));
    }
  });
  pub.wait_done();  // every frame written before the subscriber exists
  dds::FrameSubscriber sub(Publisher::domain());
  const dds::Received got = collect(sub, 2 * kFrames, std::chrono::seconds(60));
  EXPECT_EQ(pub.finish(), 0);
  ASSERT_EQ(got.frames.size(), 2 * kFrames);
  EXPECT_EQ(got.infos.size(), 2u);
  std::map<std::string, std::uint32_t> next;
  for (const RunFrame& f : got.frames) {
    const std::uint32_t expected = next[f.header.run_id]++;  // in order within a run
    ASSERT_EQ(f.header.index, expected) << f.header.run_id;
    expect_bit_exact(make_frame(f.header.run_id, expected, 500, 900), f);
  }
}

TEST(FrameTransport, RunInfoCarriesEveryField) {
  use_domain(14);
  const RunInfo sample = testing::distinct_run_info();
  Publisher pub([&](dds::FramePublisher& p) { p.publish(sample); });
  pub.wait_done();
  dds::FrameSubscriber sub(Publisher::domain());
  std::vector<RunInfo> infos;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (infos.empty() && std::chrono::steady_clock::now() < deadline)
    for (RunInfo& i : sub.take(DDS_MSECS(200)).infos) infos.push_back(std::move(i));
  EXPECT_EQ(pub.finish(), 0);
  ASSERT_EQ(infos.size(), 1u);
  testing::expect_same_fields(sample, infos[0]);
}

// The members of the wire type, read from the marshalling ops Cyclone generated from the IDL: a member
// added to the IDL but not to the field list would travel as zero, and fails here instead.
TEST(FrameTransport, RunInfoFieldListCoversEveryMemberOfTheIdl) {
  std::set<std::uint32_t> wire;  // member offsets
  const std::uint32_t* ops = fnet_RunInfo_desc.m_ops;
  for (std::size_t k = 0; DDS_OP(ops[k]) != DDS_OP_RTS;) {
    ASSERT_EQ(DDS_OP(ops[k]), DDS_OP_ADR) << "op word " << k;
    const int type = DDS_OP_TYPE(ops[k]);
    ASSERT_TRUE(type == DDS_OP_VAL_4BY || type == DDS_OP_VAL_8BY || type == DDS_OP_VAL_BST)
        << "member of type code " << type << " at op word " << k << ": teach this test how long its op is";
    wire.insert(ops[k + 1]);
    k += type == DDS_OP_VAL_BST ? 3 : 2;  // op, offset[, bound]
  }
  fnet_RunInfo sample{};
  std::set<std::uint32_t> listed;
  for_each_run_info_field(
      [&](const RunInfoField&, const auto& member) {
        listed.insert(static_cast<std::uint32_t>(reinterpret_cast<const char*>(&member) -
                                                 reinterpret_cast<const char*>(&sample)));
      },
      sample);
  EXPECT_EQ(listed, wire);
}

TEST(FrameTransport, OverlongRunInfoStringIsRefusedByName) {
  use_domain(15);
  Publisher pub([](dds::FramePublisher& p) {
    RunInfo info = testing::distinct_run_info();
    info.config_json.assign(4097, 'x');
    try {
      p.publish(info);
    } catch (const std::invalid_argument& e) {
      if (std::string(e.what()) == "config_json longer than 4096 bytes") return;
      throw std::runtime_error(std::string("wrong message: ") + e.what());
    }
    throw std::runtime_error("published a config_json of 4097 bytes");
  });
  EXPECT_EQ(pub.finish(), 0);
}

TEST(FrameTransport, MalformedSampleIsReportedAndLaterFramesStillArrive) {
  use_domain(13);
  Publisher pub([&](dds::FramePublisher& p) {
    for (int k = 0; k < 100 && p.matched_readers() == 0; ++k)
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    // A raw sample whose arrays disagree, written by a second writer on the same topic.
    dds::Entity participant(dds::check(dds_create_participant(Publisher::domain(), nullptr, nullptr), "participant"));
    const dds_entity_t topic = dds::check(
        dds_create_topic(participant.get(), &fnet_ForceFrame_desc, dds::kFrameTopic, nullptr, nullptr), "topic");
    dds::Qos qos;
    dds_qset_reliability(qos.get(), DDS_RELIABILITY_RELIABLE, DDS_SECS(1));
    dds_qset_history(qos.get(), DDS_HISTORY_KEEP_ALL, 0);
    dds_qset_durability(qos.get(), DDS_DURABILITY_TRANSIENT_LOCAL);
    const dds_entity_t writer = dds::check(dds_create_writer(participant.get(), topic, qos.get(), nullptr), "writer");
    for (int k = 0; k < 100; ++k) {
      dds_publication_matched_status_t st{};
      dds_get_publication_matched_status(writer, &st);
      if (st.current_count > 0) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    fnet_ForceFrame bad{};
    std::strcpy(bad.run_id, "broken");
    std::uint32_t pairs[3] = {0, 1, 2};
    double forces[2] = {1.0, 0.5};
    bad.particle_count = 3;
    bad.dimension = 2;
    bad.contact_pairs = {3, 3, pairs, false};
    bad.contact_forces = {2, 2, forces, false};
    if (dds_write(writer, &bad) != DDS_RETCODE_OK) throw std::runtime_error("raw write failed");
    // A 3D frame whose z does not cover its particles, then a frame of dimension 5.
    double xyr[9] = {0, 0, 0.5, 1, 0, 0.5, 0, 1, 0.5}, z[2] = {0.25, 0.75};
    bad.frame = 1;
    bad.dimension = 3;
    bad.contact_pairs = {2, 2, pairs, false};
    bad.particles = {9, 9, xyr, false};
    bad.particle_z = {2, 2, z, false};
    if (dds_write(writer, &bad) != DDS_RETCODE_OK) throw std::runtime_error("raw write failed");
    bad.frame = 2;
    bad.dimension = 5;
    bad.particle_z = {0, 0, nullptr, false};
    if (dds_write(writer, &bad) != DDS_RETCODE_OK) throw std::runtime_error("raw write failed");
    dds_wait_for_acks(writer, DDS_SECS(10));
    p.publish(make_frame("fine", 0, 10, 12));
  });
  dds::FrameSubscriber sub(Publisher::domain());
  dds::Received got = collect(sub, 1, std::chrono::seconds(30));
  for (int k = 0; k < 10 && got.malformed.size() < 3; ++k) {
    dds::Received more = collect(sub, 1, std::chrono::seconds(1));
    for (auto& m : more.malformed) got.malformed.push_back(std::move(m));
  }
  EXPECT_EQ(pub.finish(), 0);
  ASSERT_EQ(got.frames.size(), 1u);
  expect_bit_exact(make_frame("fine", 0, 10, 12), got.frames[0]);
  ASSERT_EQ(got.malformed.size(), 3u);
  EXPECT_NE(got.malformed[0].find("run broken frame 0"), std::string::npos) << got.malformed[0];
  EXPECT_NE(got.malformed[0].find("contact arrays disagree"), std::string::npos) << got.malformed[0];
  EXPECT_NE(got.malformed[1].find("run broken frame 1: 2 z values for 3 particles"), std::string::npos)
      << got.malformed[1];
  EXPECT_NE(got.malformed[2].find("run broken frame 2: dimension 5 is neither 2 nor 3"), std::string::npos)
      << got.malformed[2];
}

}  // namespace
}  // namespace fnet

namespace fnet {
namespace {

// A frame above the subscriber's bound is refused unread, with a reason naming it and the bound;
// a take holding a byte budget stops at the frame that reaches it.
TEST(FrameTransport, AFrameAboveTheSizeBoundIsRefusedAndATakeStopsAtItsByteBudget) {
  use_domain(212);
  constexpr std::uint32_t kSmall = 10;
  Publisher pub([&](dds::FramePublisher& p) {
    p.publish(make_frame("sized", 0, 3000, 6000));
    for (std::uint32_t k = 1; k <= kSmall; ++k) p.publish(make_frame("sized", k, 500, 900));
  });
  pub.wait_done();
  const std::size_t big = frame_bytes(3000, 6000, 7), small = frame_bytes(500, 900, 7);
  ASSERT_EQ(big, 3000 * 32 + 6000 * 32 + 7 * 24);
  const std::size_t budget = 2 * small + 1;  // the third frame reaches it
  dds::FrameSubscriber sub(Publisher::domain(), DDS_LENGTH_UNLIMITED, {big - 1, "the planted bound"});
  std::vector<RunFrame> frames;
  std::vector<dds::RefusedFrame> refused;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (frames.size() < kSmall && std::chrono::steady_clock::now() < deadline) {
    dds::Received got = sub.take(DDS_MSECS(200), SIZE_MAX, budget);
    EXPECT_LE(got.frames.size(), 3u);
    for (auto& f : got.frames) frames.push_back(std::move(f));
    for (auto& r : got.refused) refused.push_back(std::move(r));
  }
  EXPECT_EQ(pub.finish(), 0);
  ASSERT_EQ(frames.size(), kSmall);
  for (std::uint32_t k = 0; k < kSmall; ++k) expect_bit_exact(make_frame("sized", k + 1, 500, 900), frames[k]);
  ASSERT_EQ(refused.size(), 1u);
  EXPECT_EQ(refused[0].header, make_frame("sized", 0, 3000, 6000).header);
  EXPECT_EQ(refused[0].reason, "run sized frame 0: refused unread: its 3000 grains and 6000 contacts hold " +
                                   mebibytes(big) + ", above the planted bound, " + mebibytes(big - 1));
}

}  // namespace
}  // namespace fnet
