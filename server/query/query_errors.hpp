// What a query cannot answer, as its client must be told: each error names what it could not find.
// A transport maps each to its own error (server/api: the JSON-RPC codes of proto/api.md).
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

namespace fnet::query {

class UnknownRun : public std::runtime_error {
 public:
  explicit UnknownRun(std::string run);
  std::string run;
};

class UnknownFrame : public std::runtime_error {
 public:
  UnknownFrame(std::string run, std::uint32_t frame);
  std::string run;
  std::uint32_t frame;
};

// A committed frame whose force network cannot be had (or cannot be used); what() is `reason`.
class NoNetwork : public std::runtime_error {
 public:
  NoNetwork(std::string run, std::uint32_t frame, const std::string& reason);
  std::string run;
  std::uint32_t frame;
  std::string reason;
};

}  // namespace fnet::query
