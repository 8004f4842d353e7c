// The protocol: frames at fixed intervals from the relaxed packing to rho_final, determinism for
// a seed, checkpoint/resume bit for bit, CSV export readable by the analysis.
#include "server/dem/protocol.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "common/codec/frame_csv.hpp"
#include "common/topology/frame.hpp"
#include "server/dem/checkpoint.hpp"
#include "server/dem/csv_export.hpp"
#include "server/dem/diagnostics.hpp"
#include "server/dem/initial_packing.hpp"
#include "server/dem/workers.hpp"
#include "tests/support/run_frame_compare.hpp"

namespace fnet::sim {
namespace {

Params small(std::uint64_t seed = 5) {
  Params p;
  p.particles = 150;
  p.box = std::sqrt(150 * 0.25 * 3.141592653589793 * (1 + 0.4 * 0.4 / 12) / 0.635);
  p.compression_speed = 2e-2;
  p.relax_energy = 1e-5;
  p.frames = 7;
  p.seed = seed;
  return p;
}

using fnet::testing::same_bits;

void expect_identical(const std::vector<FrameSnapshot>& a, const std::vector<FrameSnapshot>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].index, b[k].index);
    EXPECT_EQ(a[k].step, b[k].step);
    EXPECT_TRUE(same_bits(a[k].rho, b[k].rho) && same_bits(a[k].z, b[k].z)) << "frame " << k;
    ASSERT_EQ(a[k].frame.particles.size(), b[k].frame.particles.size());
    for (std::size_t i = 0; i < a[k].frame.particles.size(); ++i) {
      const auto &p = a[k].frame.particles[i], &q = b[k].frame.particles[i];
      ASSERT_TRUE(same_bits(p.x, q.x) && same_bits(p.y, q.y) && same_bits(p.r, q.r)) << "frame " << k << " grain " << i;
    }
    ASSERT_EQ(a[k].frame.contacts.size(), b[k].frame.contacts.size()) << "frame " << k;
    for (std::size_t c = 0; c < a[k].frame.contacts.size(); ++c) {
      const auto &p = a[k].frame.contacts[c], &q = b[k].frame.contacts[c];
      ASSERT_TRUE(p.i == q.i && p.j == q.j && same_bits(p.fn, q.fn) && same_bits(p.ft, q.ft)) << "frame " << k;
    }
    ASSERT_EQ(a[k].wall_contacts.size(), b[k].wall_contacts.size());
    for (std::size_t w = 0; w < a[k].wall_contacts.size(); ++w) {
      const auto &p = a[k].wall_contacts[w], &q = b[k].wall_contacts[w];
      ASSERT_TRUE(p.grain == q.grain && p.wall_particle == q.wall_particle && p.side == q.side &&
                  same_bits(p.fn, q.fn) && same_bits(p.ft, q.ft))
          << "frame " << k << " wall contact " << w;
    }
  }
}

std::vector<FrameSnapshot> full_run(const Params& p, Workers* workers = nullptr) {
  std::vector<FrameSnapshot> frames;
  Simulation s = make_lattice(p);
  RunOptions o;
  o.sink = [&](const FrameSnapshot& f) { frames.push_back(f); };
  o.workers = workers;
  EXPECT_TRUE(run(s, o));
  return frames;
}

TEST(Protocol, FramesAtFixedIntervalsFromRelaxedToFinalDensity) {
  const Params p = small();
  const std::vector<FrameSnapshot> frames = full_run(p);
  ASSERT_EQ(frames.size(), p.frames);
  EXPECT_EQ(frames[0].step, 0);
  EXPECT_NEAR(frames[0].rho, 0.635, 0.03);  // the box fits the expected grain area; 150 grains scatter
  EXPECT_GE(frames.back().rho, p.rho_final);
  EXPECT_LT(frames.back().rho, p.rho_final + 5e-4);  // within one (large) step at v_c = 0.02
  const std::int64_t interval = frames[1].step;
  for (std::size_t k = 1; k < frames.size(); ++k) {
    EXPECT_NEAR(static_cast<double>(frames[k].step - frames[k - 1].step), static_cast<double>(interval), 1.0);
    EXPECT_NEAR(frames[k].time, static_cast<double>(frames[k].step) / p.dt_divisor, 1e-9);
    EXPECT_GT(frames[k].rho, frames[k - 1].rho);
  }
  for (const FrameSnapshot& f : frames) {
    EXPECT_NO_THROW(fnet::validate(f.frame));
    std::size_t positive = 0;
    for (const auto& c : f.frame.contacts) positive += c.fn > 0;
    EXPECT_DOUBLE_EQ(f.z, 2.0 * static_cast<double>(positive) / static_cast<double>(p.particles));
  }
  EXPECT_GT(frames.back().z, 3.0);  // jammed at rho = 0.9
}

TEST(Protocol, DeterministicForASeed) {
  expect_identical(full_run(small(5)), full_run(small(5)));
  EXPECT_NE(full_run(small(6)).back().frame.particles[0].x, full_run(small(5)).back().frame.particles[0].x);
}

// The relaxation ends when the grains are at rest (translational energy below the target, not
// by the cap), and its damping stops there: two copies of the relaxed state with different
// relax_damping compress to the same bits.
TEST(Protocol, RelaxationEndsAtRestAndTheCompressionIsUndamped) {
  Params p = small(4);
  p.relax_energy = 1e-12;
  Simulation s = make_lattice(p);
  std::vector<Relaxation> ends;
  RunOptions o;
  o.relaxed = [&](const Relaxation& r) { ends.push_back(r); };
  o.max_steps = kRelaxCheck;
  while (s.phase == Phase::relax) ASSERT_FALSE(run(s, o));
  ASSERT_EQ(ends.size(), 1u);
  EXPECT_FALSE(ends[0].capped);
  EXPECT_EQ(ends[0].steps, s.step);
  EXPECT_EQ(ends[0].target, 1e-12);
  const double tau2 = s.c.tau_c * s.c.tau_c;
  EXPECT_LT(translational_energy(s) / static_cast<double>(s.n) * tau2, 1e-12);
  EXPECT_DOUBLE_EQ(ends[0].energy, translational_energy(s) / static_cast<double>(s.n) * tau2);

  Simulation other = s;
  other.params.relax_damping = 5;
  std::vector<FrameSnapshot> a, b;
  RunOptions to_end;
  to_end.sink = [&](const FrameSnapshot& f) { a.push_back(f); };
  ASSERT_TRUE(run(s, to_end));
  to_end.sink = [&](const FrameSnapshot& f) { b.push_back(f); };
  ASSERT_TRUE(run(other, to_end));
  ASSERT_EQ(a.size(), p.frames - 1);  // frame 0 came out with the relaxation's last step
  expect_identical(a, b);
}

// A relaxation that cannot reach its target is ended by relax_max_time, and says so.
TEST(Protocol, RelaxationCappedByMaxTimeSaysSo) {
  Params p = small(4);
  p.relax_energy = 0;  // never reached
  p.relax_max_time = 20;
  Simulation s = make_lattice(p);
  std::vector<Relaxation> ends;
  RunOptions o;
  o.relaxed = [&](const Relaxation& r) { ends.push_back(r); };
  ASSERT_TRUE(run(s, o));
  ASSERT_EQ(ends.size(), 1u);
  EXPECT_TRUE(ends[0].capped);
  EXPECT_EQ(ends[0].steps, 20 * 50);
}

// The threaded step evaluates the pairs in parallel and lets every body sum its pairs in the
// serial loop's order: any team size gives the serial run's frames bit for bit, also when a run
// is resumed with another team size. 400 grains so that each thread has hundreds of pairs; the
// team works once the packing is dense (step() uses it from 2 pairs per grain on).
TEST(Protocol, ThreadsGiveTheSameBits) {
  Params p = small(9);
  p.particles = 400;
  p.box = std::sqrt(400 * 0.25 * 3.141592653589793 * (1 + 0.4 * 0.4 / 12) / 0.635);
  p.compression_speed = 5e-2;
  p.relax_energy = 1e-4;
  const std::vector<FrameSnapshot> serial = full_run(p);
  for (const unsigned threads : {2u, 3u}) {
    Workers team(threads);
    ASSERT_EQ(team.size(), threads);
    expect_identical(full_run(p, &team), serial);
    EXPECT_GT(team.runs(), 1000u) << "the team never worked";
  }
  // Three quarters of the run on one thread, saved to a checkpoint, the rest (the dense end) resumed
  // from the file on two.
  Simulation whole = make_lattice(p);
  ASSERT_TRUE(run(whole, RunOptions{}));
  std::vector<FrameSnapshot> frames;
  RunOptions o;
  o.sink = [&](const FrameSnapshot& f) { frames.push_back(f); };
  const std::filesystem::path file = std::filesystem::path(::testing::TempDir()) / "fnet_sim_threads.ckpt";
  {
    Simulation s = make_lattice(p);
    o.max_steps = whole.step * 3 / 4;
    ASSERT_FALSE(run(s, o));
    save_checkpoint(s, "threads-test", file);
  }
  Restored r = load_checkpoint(file);
  std::filesystem::remove(file);
  Workers team(2);
  o.workers = &team;
  o.max_steps = -1;
  ASSERT_TRUE(run(r.simulation, o));
  EXPECT_GT(team.runs(), 100u);
  expect_identical(frames, serial);
}

// A run stopped at arbitrary steps (in the relaxation and mid-compression), saved and resumed
// from the file, gives the frames of the uninterrupted run bit for bit.
TEST(Protocol, ResumeFromCheckpointIsBitwiseIdentical) {
  const Params p = small();
  const std::vector<FrameSnapshot> reference = full_run(p);
  const std::filesystem::path file = std::filesystem::path(::testing::TempDir()) / "fnet_sim_resume.ckpt";
  for (std::int64_t stop_at : {777, 5003}) {
    std::vector<FrameSnapshot> frames;
    RunOptions o;
    o.sink = [&](const FrameSnapshot& f) { frames.push_back(f); };
    o.max_steps = stop_at;
    {
      Simulation s = make_lattice(p);
      ASSERT_FALSE(run(s, o));
      save_checkpoint(s, "resume-test", file);
    }
    Restored r = load_checkpoint(file);
    EXPECT_EQ(r.run_id, "resume-test");
    EXPECT_EQ(r.simulation.step, stop_at);
    o.max_steps = 3000;  // stop and resume once more
    if (!run(r.simulation, o)) {
      save_checkpoint(r.simulation, r.run_id, file);
      r = load_checkpoint(file);
      o.max_steps = -1;
      ASSERT_TRUE(run(r.simulation, o));
    }
    expect_identical(frames, reference);
  }
  std::filesystem::remove(file);
}

// The ensemble is the checkpoint's last entry: a checkpoint written before it existed (the same
// bytes without it) loads as one with no ensemble, and resumes to the same state.
TEST(Protocol, CheckpointKeepsTheEnsembleAndOlderCheckpointsStillLoad) {
  const Params p = small();
  RunOptions o;
  o.max_steps = 500;
  Simulation s = make_lattice(p);
  ASSERT_FALSE(run(s, o));
  const std::filesystem::path file = std::filesystem::path(::testing::TempDir()) / "fnet_sim_ensemble.ckpt";
  save_checkpoint(s, "mu05-s3", file, "mu05");
  Restored with = load_checkpoint(file);
  EXPECT_EQ(with.run_id, "mu05-s3");
  EXPECT_EQ(with.ensemble, "mu05");
  save_checkpoint(s, "old", file, "");
  std::filesystem::resize_file(file, std::filesystem::file_size(file) - sizeof(std::uint64_t));  // no ensemble
  Restored old = load_checkpoint(file);
  std::filesystem::remove(file);
  EXPECT_EQ(old.run_id, "old");
  EXPECT_EQ(old.ensemble, "");
  EXPECT_EQ(old.simulation.step, with.simulation.step);
  EXPECT_EQ(old.simulation.x[0], with.simulation.x[0]);
}

TEST(Protocol, CsvExportIsWhatTheAnalysisReads) {
  const Params p = small();
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "fnet_sim_csv";
  std::filesystem::remove_all(dir);
  prepare_csv_dir(dir, 0);
  std::vector<FrameSnapshot> frames;
  Simulation s = make_lattice(p);
  RunOptions o;
  o.sink = [&](const FrameSnapshot& f) {
    frames.push_back(f);
    write_frame_csv(dir, f);
  };
  ASSERT_TRUE(run(s, o));
  std::ifstream index(dir / "index.csv");
  std::string line;
  std::getline(index, line);
  EXPECT_EQ(line, "frame,step,time,rho,z");
  std::size_t rows = 0;
  while (std::getline(index, line)) ++rows;
  EXPECT_EQ(rows, p.frames);
  for (const FrameSnapshot& f : frames) {
    char name[64];
    std::snprintf(name, sizeof name, "frame_%04zu_", f.index);
    const fnet::Frame read =
        fnet::read_frame_csv(dir / (std::string(name) + "contacts.csv"), dir / (std::string(name) + "particles.csv"));
    EXPECT_NO_THROW(fnet::validate(read));
    ASSERT_EQ(read.particle_count, p.particles);
    ASSERT_EQ(read.contacts.size(), f.frame.contacts.size());
    for (std::size_t c = 0; c < read.contacts.size(); ++c) {  // shortest round-trip formatting: every bit
      const auto &r = read.contacts[c], &w = f.frame.contacts[c];
      EXPECT_TRUE(r.i == w.i && r.j == w.j && same_bits(r.fn, w.fn) && same_bits(r.ft, w.ft)) << "contact " << c;
    }
    ASSERT_EQ(read.particles.size(), f.frame.particles.size());
    for (std::size_t i = 0; i < read.particles.size(); ++i) {
      const auto &r = read.particles[i], &w = f.frame.particles[i];
      EXPECT_TRUE(same_bits(r.x, w.x) && same_bits(r.y, w.y) && same_bits(r.r, w.r)) << "particle " << i;
    }
    EXPECT_TRUE(std::filesystem::exists(dir / (std::string(name) + "wall_contacts.csv")));
  }
  // A resumed export keeps the index rows of the frames already written.
  prepare_csv_dir(dir, 3);
  std::ifstream again(dir / "index.csv");
  rows = 0;
  std::getline(again, line);
  while (std::getline(again, line)) ++rows;
  EXPECT_EQ(rows, 3u);
  std::filesystem::remove_all(dir);
}

TEST(Params, ConstantsOfThePaper) {
  const Constants c = derive(Params{});
  EXPECT_NEAR(c.tau_c, 0.0359688, 1e-7);
  EXPECT_NEAR(c.gamma_n, 38.5415, 1e-4);
  EXPECT_NEAR(c.dt, 7.19377e-4, 1e-9);
  Params p;
  EXPECT_THROW(apply_json(p, nlohmann::json{{"no_such_key", 1}}), std::invalid_argument);
  apply_json(p, nlohmann::json{{"mu", 0.0}, {"particles", 500}, {"integrator", "verlet"}});
  EXPECT_EQ(p.mu, 0.0);
  EXPECT_EQ(p.particles, 500u);
  EXPECT_EQ(p.integrator, Integrator::verlet);
  p.en = 0;
  EXPECT_THROW(validate(p), std::invalid_argument);
}

}  // namespace
}  // namespace fnet::sim
