#include "common/topology/diagram.hpp"

#include <algorithm>

namespace fnet {

void sort_canonical(Diagram& diagram) {
  std::sort(diagram.begin(), diagram.end(), [](const PersistencePoint& a, const PersistencePoint& b) {
    return a.birth != b.birth ? a.birth > b.birth : a.death > b.death;
  });
}

}  // namespace fnet
