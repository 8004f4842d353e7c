#include "tests/reference/standard_reduction.hpp"

#include <algorithm>
#include <iterator>
#include <stdexcept>

namespace fnet::reference {

std::vector<std::optional<std::size_t>> reduce_lowest_rows(std::vector<Column> boundary) {
  const std::size_t n = boundary.size();
  std::vector<std::optional<std::size_t>> lowest(n);
  std::vector<std::optional<std::size_t>> column_with_lowest(n);  // row -> the reduced column ending there
  Column sum;
  for (std::size_t j = 0; j < n; ++j) {
    Column& column = boundary[j];
    if (!std::is_sorted(column.begin(), column.end()) ||
        std::adjacent_find(column.begin(), column.end()) != column.end())
      throw std::invalid_argument("boundary column is not a strictly ascending list of rows");
    while (!column.empty() && column_with_lowest[column.back()]) {
      const Column& other = boundary[*column_with_lowest[column.back()]];
      sum.clear();
      std::set_symmetric_difference(column.begin(), column.end(), other.begin(), other.end(), std::back_inserter(sum));
      column.swap(sum);
    }
    if (column.empty()) continue;
    lowest[j] = column.back();
    column_with_lowest[column.back()] = j;
  }
  return lowest;
}

}  // namespace fnet::reference
