#include "common/transport/run_status_topic.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstring>
#include <map>
#include <set>
#include <thread>

#include "common/transport/dds_entity.hpp"
#include "fnet.h"

namespace fnet::dds {
namespace {

// A bounded IDL string from a std::string: cut to its capacity (a status is a report, never refused).
template <std::size_t N>
void put(char (&wire)[N], const std::string& value) {
  const std::size_t n = std::min(value.size(), N - 1);
  std::memcpy(wire, value.data(), n);
  wire[n] = '\0';
}

void set_status_qos(Qos& qos) {
  dds_qset_reliability(qos.get(), DDS_RELIABILITY_RELIABLE, DDS_SECS(1));
  dds_qset_history(qos.get(), DDS_HISTORY_KEEP_LAST, 1);
  dds_qset_durability(qos.get(), DDS_DURABILITY_TRANSIENT_LOCAL);
}

dds_entity_t status_topic(dds_entity_t participant) {
  return check(dds_create_topic(participant, &fnet_RunStatus_desc, kRunStatusTopic, nullptr, nullptr),
               "dds_create_topic(RunStatus)");
}

using Guid = std::array<unsigned char, 16>;
Guid guid_of(const dds_builtintopic_endpoint_t& e) {
  Guid g{};
  std::memcpy(g.data(), e.participant_key.v, g.size());
  return g;
}

// The participants of the endpoints matched with `entity` (a writer's readers, or a reader's
// writers), by instance handle.
template <class Matched, class Data>
std::map<dds_instance_handle_t, Guid> matched_participants(dds_entity_t entity, Matched matched, Data data) {
  std::map<dds_instance_handle_t, Guid> out;
  const dds_return_t n = matched(entity, nullptr, 0);
  if (n <= 0) return out;
  std::vector<dds_instance_handle_t> handles(static_cast<std::size_t>(n));
  const dds_return_t got = matched(entity, handles.data(), handles.size());
  for (dds_return_t k = 0; k < std::min(got, n); ++k)
    if (dds_builtintopic_endpoint_t* e = data(entity, handles[static_cast<std::size_t>(k)])) {
      out[handles[static_cast<std::size_t>(k)]] = guid_of(*e);
      dds_builtintopic_free_endpoint(e);
    }
  return out;
}

}  // namespace

RunStatusWriter::RunStatusWriter(dds_entity_t participant) {
  Qos qos;
  set_status_qos(qos);
  writer_ = check(dds_create_writer(participant, status_topic(participant), qos.get(), nullptr),
                  "dds_create_writer(RunStatus)");
}

void RunStatusWriter::write(const RunStatus& s) {
  fnet_RunStatus w{};
  put(w.run_id, s.run_id);
  put(w.server, s.server);
  w.settled_through = s.settled_through;
  w.stored = s.stored;
  put(w.store_fault, s.store_fault);
  const dds_return_t rc = dds_write(writer_, &w);
  if (rc != DDS_RETCODE_OK) throw Error("dds_write(RunStatus)", rc);
}

RunStatusReader::RunStatusReader(dds_entity_t participant) {
  Qos qos;
  set_status_qos(qos);
  reader_ = check(dds_create_reader(participant, status_topic(participant), qos.get(), nullptr),
                  "dds_create_reader(RunStatus)");
}

std::vector<ServerStore> RunStatusReader::servers(dds_entity_t frame_writer, const std::string& run_id) {
  const auto frame_readers =
      matched_participants(frame_writer, dds_get_matched_subscriptions, dds_get_matched_subscription_data);
  const auto status_writers =
      matched_participants(reader_, dds_get_matched_publications, dds_get_matched_publication_data);
  std::set<Guid> readers, servers;
  for (const auto& [handle, guid] : frame_readers) readers.insert(guid);
  for (const auto& [handle, guid] : status_writers)
    if (readers.count(guid)) servers.insert(guid);
  std::map<Guid, ServerStore> out;
  for (const Guid& g : servers) out[g];
  // Samples are taken as they come, the latest of the run kept per writer: the history holds the
  // statuses of every run of every server, read once.
  constexpr std::size_t kBatch = 64;
  while (true) {
    void* samples[kBatch] = {};
    dds_sample_info_t infos[kBatch];
    const dds_return_t n = dds_take(reader_, samples, infos, kBatch, kBatch);
    if (n <= 0) break;
    for (dds_return_t k = 0; k < n; ++k) {
      const auto& s = *static_cast<const fnet_RunStatus*>(samples[k]);
      if (infos[k].valid_data && run_id == s.run_id)
        latest_[infos[k].publication_handle] = {s.run_id, s.server, s.settled_through, s.stored, s.store_fault};
    }
    dds_return_loan(reader_, samples, n);
  }
  for (const auto& [handle, status] : latest_)
    if (const auto writer = status_writers.find(handle);
        writer != status_writers.end() && servers.count(writer->second))
      out[writer->second].status = status;
  std::vector<ServerStore> list;
  for (auto& [guid, store] : out) list.push_back(std::move(store));
  return list;
}

StoreOutcome wait_for_stores(const std::function<std::vector<ServerStore>()>& servers, const std::string& run_id,
                             std::uint32_t through, double timeout_seconds) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_seconds);
  while (true) {
    StoreOutcome out;
    for (const ServerStore& s : servers()) {
      if (!s.status) {
        out.unconfirmed.push_back("a fnet-server reading its frames said nothing of run " + run_id);
      } else if (!s.status->store_fault.empty()) {
        out.faults.push_back("fnet-server " + s.status->server + ": " + s.status->store_fault + " (its store holds " +
                             std::to_string(s.status->stored) + " frames of run " + run_id + ")");
      } else if (s.status->settled_through < through) {
        out.unconfirmed.push_back("fnet-server " + s.status->server + " had stored run " + run_id +
                                  " only below frame " + std::to_string(s.status->settled_through) + " of " +
                                  std::to_string(through));
      }
    }
    if (!out.faults.empty() || out.unconfirmed.empty() || std::chrono::steady_clock::now() >= deadline) return out;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
}

}  // namespace fnet::dds
