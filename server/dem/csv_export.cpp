#include "server/dem/csv_export.hpp"

#include <charconv>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace fnet::sim {
namespace {

void put(std::string& out, double v) {
  char buf[32];
  const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, ec == std::errc() ? end : buf);
}

void put(std::string& out, std::int64_t v) {
  char buf[24];
  const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, ec == std::errc() ? end : buf);
}

// One CSV row: the values separated by commas, then a newline.
template <class First, class... Rest>
void put_row(std::string& out, First first, Rest... rest) {
  put(out, first);
  ((out += ',', put(out, rest)), ...);
  out += '\n';
}

void write_file(const std::filesystem::path& path, const std::string& text, bool append = false) {
  std::ofstream out(path, append ? std::ios::app : std::ios::trunc);
  out << text;
  out.flush();
  if (!out) throw std::runtime_error(path.string() + ": cannot write");
}

std::string frame_name(std::size_t index, const char* what) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "frame_%04zu_%s.csv", index, what);
  return buf;
}

constexpr const char* kIndexHeader = "frame,step,time,rho,z\n";

}  // namespace

void prepare_csv_dir(const std::filesystem::path& dir, std::size_t keep_frames) {
  std::filesystem::create_directories(dir);
  const std::filesystem::path index = dir / "index.csv";
  std::string text = kIndexHeader;
  if (keep_frames > 0) {
    std::ifstream in(index);
    std::string line;
    std::getline(in, line);  // header
    while (std::getline(in, line)) {
      std::size_t frame = 0;
      if (std::sscanf(line.c_str(), "%zu,", &frame) == 1 && frame < keep_frames) text += line + "\n";
    }
  }
  write_file(index, text);
}

void write_frame_csv(const std::filesystem::path& dir, const FrameSnapshot& f) {
  std::string text = "id,x,y,r\n";
  text.reserve(64 * f.frame.particles.size());
  for (std::size_t i = 0; i < f.frame.particles.size(); ++i) {
    const fnet::Particle& p = f.frame.particles[i];
    put_row(text, static_cast<std::int64_t>(i), p.x, p.y, p.r);
  }
  write_file(dir / frame_name(f.index, "particles"), text);

  text = "i,j,fn,ft\n";
  for (const fnet::Contact& c : f.frame.contacts) put_row(text, c.i, c.j, c.fn, c.ft);
  write_file(dir / frame_name(f.index, "contacts"), text);

  text = "grain,wall,side,fn,ft\n";
  for (const WallContact& c : f.wall_contacts)
    put_row(text, c.grain, c.wall_particle, static_cast<std::int64_t>(c.side), c.fn, c.ft);
  write_file(dir / frame_name(f.index, "wall_contacts"), text);

  text.clear();
  put_row(text, static_cast<std::int64_t>(f.index), f.step, f.time, f.rho, f.z);
  write_file(dir / "index.csv", text, /*append=*/true);
}

}  // namespace fnet::sim
