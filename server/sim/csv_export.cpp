#include "server/sim/csv_export.hpp"

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

constexpr const char* kIndexHeader = "frame,step,time,rho,Z\n";

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
    put(text, static_cast<std::int64_t>(i));
    text += ',';
    put(text, p.x);
    text += ',';
    put(text, p.y);
    text += ',';
    put(text, p.r);
    text += '\n';
  }
  write_file(dir / frame_name(f.index, "particles"), text);

  text = "i,j,fn,ft\n";
  for (const fnet::Contact& c : f.frame.contacts) {
    put(text, c.i);
    text += ',';
    put(text, c.j);
    text += ',';
    put(text, c.fn);
    text += ',';
    put(text, c.ft);
    text += '\n';
  }
  write_file(dir / frame_name(f.index, "contacts"), text);

  text = "grain,wall,side,fn,ft\n";
  for (const WallContact& c : f.wall_contacts) {
    put(text, c.grain);
    text += ',';
    put(text, c.wall_particle);
    text += ',';
    put(text, static_cast<std::int64_t>(c.side));
    text += ',';
    put(text, c.fn);
    text += ',';
    put(text, c.ft);
    text += '\n';
  }
  write_file(dir / frame_name(f.index, "wall_contacts"), text);

  text.clear();
  put(text, static_cast<std::int64_t>(f.index));
  text += ',';
  put(text, f.step);
  text += ',';
  put(text, f.time);
  text += ',';
  put(text, f.rho);
  text += ',';
  put(text, f.z);
  text += '\n';
  write_file(dir / "index.csv", text, /*append=*/true);
}

}  // namespace fnet::sim
