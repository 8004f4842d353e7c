// Writes a synthetic packing (tests/support/synthetic_frame.hpp) as the two CSV files
// fnet-analyze diagram reads, numbers in the shortest form that reads back to the same double.
//   write_synthetic_frame N SEED CONTACTS.csv PARTICLES.csv
#include <charconv>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>

#include "tests/support/synthetic_frame.hpp"

namespace {

template <class T>
void put(std::string& out, T v) {
  char buf[32];
  const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, end);
}

template <class First, class... Rest>
void put_row(std::string& out, First first, Rest... rest) {
  put(out, first);
  ((out += ',', put(out, rest)), ...);
  out += '\n';
}

bool write_file(const char* path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  return static_cast<bool>(out.flush());
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 5) {
    std::cerr << "usage: write_synthetic_frame N SEED CONTACTS.csv PARTICLES.csv\n";
    return 2;
  }
  const fnet::Frame frame = fnet::testing::synthetic_frame(
      {.particles = std::strtoull(argv[1], nullptr, 10), .seed = std::strtoull(argv[2], nullptr, 10)});
  std::string text = "i,j,fn,ft\n";
  for (const fnet::Contact& c : frame.contacts) put_row(text, c.i, c.j, c.fn, c.ft);
  if (!write_file(argv[3], text)) {
    std::cerr << argv[3] << ": cannot write\n";
    return 1;
  }
  text = "id,x,y,r\n";
  for (std::size_t i = 0; i < frame.particles.size(); ++i) {
    const fnet::Particle& p = frame.particles[i];
    put_row(text, static_cast<std::int64_t>(i), p.x, p.y, p.r);
  }
  if (!write_file(argv[4], text)) {
    std::cerr << argv[4] << ": cannot write\n";
    return 1;
  }
  return 0;
}
