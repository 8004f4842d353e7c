// fnet-analyze publish: replays a recorded run onto DDS, as fnet-simd would stream it.
#include <algorithm>
#include <chrono>
#include <iostream>
#include <thread>

#include <boost/program_options.hpp>

#include "common/transport/frame_transport.hpp"
#include "server/fnet-analyze/commands.hpp"
#include "server/sources/run_source.hpp"
#include "server/sources/source_kinds.hpp"

namespace po = boost::program_options;

namespace fnet::analyze {
namespace {
constexpr int kNotDelivered = 3;
constexpr int kStoreFault = 4;
}  // namespace

int publish_command(const std::vector<std::string>& args) {
  const std::vector<sources::SourceKind> kinds = sources::run_kinds();
  po::options_description options(
      "usage: fnet-analyze publish " + sources::run_usage(kinds) +
      " [--ensemble E] [--rate FPS]\n"
      "       [--domain D] [--ack-timeout S]\n\n"
      "Publishes the run's announcement and every frame on the DDS topics fnet_RunInfo and\n"
      "fnet_ForceFrame (set CYCLONEDDS_URI), then waits until every matched reader acknowledged\n"
      "them. Frames are sent as recorded: invalid ones too (fnet-server rejects and reports them).\n"
      "Exit code 3: no reader matched at all (the frames reached no one), or a matched reader had not\n"
      "acknowledged every frame after --ack-timeout seconds, or went away during the run, or a\n"
      "fnet-server among them had not stored them by then: it may lack frames. Exit code 4: a fnet-server reading the "
      "run reports that it cannot store it (a\n"
      "store fault: a full disk, no file descriptor left), naming the run, the server and why.\n\n"
      "options");
  double rate = 0;
  int domain = 0;
  double linger = 0, wait_for_reader = 10, ack_timeout = 600;
  options.add_options()("help,h", "show this help");
  sources::add_run_options(kinds, options);
  options.add_options()("rate", po::value(&rate)->default_value(0), "frames per second (0: as fast as possible)")(
      "domain", po::value(&domain)->default_value(0), "DDS domain id")(
      "wait-for-reader", po::value(&wait_for_reader)->default_value(10),
      "seconds to wait for a subscriber (e.g. fnet-server) to be discovered before publishing; 0: don't")(
      "ack-timeout", po::value(&ack_timeout)->default_value(ack_timeout),
      "seconds to wait at the end until every matched reader acknowledged every frame (a busy fnet-server "
      "takes frames only as fast as it analyzes them)")(
      "linger", po::value(&linger)->default_value(0),
      "seconds to keep serving late subscribers from the durability history after the last frame");
  const auto vm = parse_options(options, args);
  if (!vm) return 0;
  if (!(ack_timeout >= 0) || ack_timeout > 1e6) throw po::error("--ack-timeout must be between 0 and 1e6 seconds");
  const std::unique_ptr<sources::FrameSource> source = sources::open_run(kinds, *vm);
  const RunInfo& info = source->announcement();
  dds::FramePublisher publisher(static_cast<dds_domainid_t>(domain));
  // Discovery takes a moment; frames written before it are still served to late readers only
  // while this process lives (see --linger).
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::duration<double>(wait_for_reader);
  while (publisher.matched_readers() == 0 && std::chrono::steady_clock::now() < give_up)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  publisher.publish(info);
  const auto start = std::chrono::steady_clock::now();
  std::size_t published = 0;
  std::uint32_t through = 0;  // one past the last frame index published
  while (const std::optional<RunFrame> frame = source->next()) {
    if (rate > 0)
      std::this_thread::sleep_until(start + std::chrono::duration<double>(static_cast<double>(published) / rate));
    publisher.publish(*frame);
    through = std::max(through, frame->header.index + 1);
    ++published;
  }
  const auto acks_from = std::chrono::steady_clock::now();
  const bool acknowledged = publisher.wait_for_acks(static_cast<dds_duration_t>(ack_timeout * 1e9));
  const double left = ack_timeout - std::chrono::duration<double>(std::chrono::steady_clock::now() - acks_from).count();
  const dds::StoreOutcome stores = dds::wait_for_stores([&] { return publisher.servers_storing(info.run_id); },
                                                        info.run_id, through, std::max(0.0, left));
  std::cerr << "fnet-analyze publish: run " << info.run_id << ": " << published << " frames published, "
            << publisher.matched_readers() << " reader(s) matched\n";
  const std::uint32_t lost = publisher.lost_frame_readers();
  if (lost > 0)
    std::cerr << "fnet-analyze publish: error: run " << info.run_id << ": " << lost
              << " reader(s) went away during the run (stopped, or silent longer than the DDS lease): they may "
                 "lack frames\n";
  if (!acknowledged)
    std::cerr << "fnet-analyze publish: error: run " << info.run_id
              << ": not every frame was acknowledged by every matched reader within --ack-timeout " << ack_timeout
              << " s; the frames it has not acknowledged may not have reached it\n";
  for (const std::string& fault : stores.faults)
    std::cerr << "fnet-analyze publish: error: run " << info.run_id << " is not stored: " << fault << "\n";
  for (const std::string& late : stores.unconfirmed)
    std::cerr << "fnet-analyze publish: error: run " << info.run_id << ": " << late << " after --ack-timeout "
              << ack_timeout << " s\n";
  if (!stores.faults.empty()) return kStoreFault;
  if (lost > 0 || !acknowledged || !stores.unconfirmed.empty()) return kNotDelivered;
  if (linger > 0) std::this_thread::sleep_for(std::chrono::duration<double>(linger));
  // No reader matched, neither before the frames nor while they were served: they reached no one.
  if (publisher.matched_readers() == 0) {
    std::cerr << "fnet-analyze publish: error: run " << info.run_id << ": no reader on DDS domain " << domain
              << " matched (is fnet-server reading that domain? see --domain and --wait-for-reader): the frames "
                 "reached no one\n";
    return kNotDelivered;
  }
  return 0;
}

}  // namespace fnet::analyze
