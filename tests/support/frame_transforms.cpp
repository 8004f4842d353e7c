#include "tests/support/frame_transforms.hpp"

#include <algorithm>
#include <numeric>
#include <utility>
#include <vector>

namespace fnet::testing {

Frame shuffled_rows(Frame frame, std::mt19937_64& rng) {
  std::shuffle(frame.contacts.begin(), frame.contacts.end(), rng);
  return frame;
}

Frame reversed_pairs(Frame frame) {
  for (Contact& c : frame.contacts) std::swap(c.i, c.j);
  return frame;
}

Frame relabelled(Frame frame, std::mt19937_64& rng) {
  std::vector<std::int64_t> new_label(frame.particle_count);
  std::iota(new_label.begin(), new_label.end(), std::int64_t{0});
  std::shuffle(new_label.begin(), new_label.end(), rng);
  for (Contact& c : frame.contacts) c.i = new_label[c.i], c.j = new_label[c.j];
  if (!frame.particles.empty()) {
    std::vector<Particle> moved(frame.particles.size());
    for (std::size_t k = 0; k < moved.size(); ++k) moved[new_label[k]] = frame.particles[k];
    frame.particles = std::move(moved);
  }
  return frame;
}

Frame scaled(Frame frame, double factor) {
  for (Contact& c : frame.contacts) c.fn *= factor, c.ft *= factor;
  return frame;
}

}  // namespace fnet::testing
