// fnet-server's API (make_api) over a registry holding one real stored run, as the targets that
// speak to the server use it: built once per process, its heavy work run at once (ApiContext's
// default offload), so that an input's calls have all ended when the handler returns.
#pragma once

#include <filesystem>
#include <memory>

#include <boost/asio/thread_pool.hpp>

#include "server/api/api_methods.hpp"
#include "tests/fuzz/fuzz_input.hpp"

namespace fnet::fuzz {

struct ApiOverStore {
  boost::asio::thread_pool pool{1};
  std::unique_ptr<server::Registry> registry;
  std::unique_ptr<server::ApiContext> context;
  rpc::Handler handler;
  ApiOverStore() {
    const std::filesystem::path data = scratch_dir() / "data";
    std::filesystem::create_directories(data);
    const std::filesystem::path store = std::filesystem::path(FNET_SOURCE_DIR) / "tests/data/store-v2/legacy-v2.h5";
    std::filesystem::copy_file(store, data / "legacy-v2.h5", std::filesystem::copy_options::overwrite_existing);
    registry = std::make_unique<server::Registry>(data, pool);
    registry->load();
    context = std::make_unique<server::ApiContext>(server::ApiContext{*registry});
    handler = server::make_api(*context);
  }
};

}  // namespace fnet::fuzz
