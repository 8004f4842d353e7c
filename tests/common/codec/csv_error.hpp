// The message of the CsvError a read throws, "<accepted>" when it throws none.
#pragma once

#include <string>

#include "common/codec/frame_csv.hpp"

namespace fnet::testing {

template <class Read>
std::string csv_error(Read read) {
  try {
    read();
  } catch (const CsvError& e) {
    return e.what();
  }
  return "<accepted>";
}

}  // namespace fnet::testing
