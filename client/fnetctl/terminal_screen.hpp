// The terminal's alternate screen (xterm's mode 1049), for a display redrawn in place: what is
// drawn there never reaches the scrollback, and leaving it gives back the screen as it was. The
// destructor leaves it, so an exception or a Ctrl-C handled by the caller's loop restores it too.
#pragma once

#include <ostream>
#include <sstream>
#include <string>

namespace fnet::client {

class AlternateScreen {
 public:
  explicit AlternateScreen(std::ostream& out) : out_(out) { out_ << "\x1b[?1049h\x1b[?25l" << std::flush; }
  AlternateScreen(const AlternateScreen&) = delete;
  AlternateScreen& operator=(const AlternateScreen&) = delete;
  ~AlternateScreen() { out_ << "\x1b[?25h\x1b[?1049l" << std::flush; }

  // Redraws from the top left; each line and then the rest of the screen are erased after the
  // text, so nothing of a longer previous frame stays and nothing scrolls.
  void draw(const std::string& text) {
    std::ostringstream s;
    s << "\x1b[H";
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);) s << line << "\x1b[K\n";
    s << "\x1b[J";
    out_ << s.str() << std::flush;
  }

 private:
  std::ostream& out_;
};

}  // namespace fnet::client
