#include "pda_registration/tools/progress_line.hpp"

#include <unistd.h>

#include <iomanip>
#include <iostream>
#include <sstream>
#include <utility>

#include "pda_registration/tools/command_line.hpp"

namespace pda_registration {

ProgressLine::ProgressLine(std::string tool, size_t total, size_t sets, size_t messages)
    : tool_(std::move(tool)),
      total_(total),
      sets_(sets),
      messages_(messages),
      terminal_(isatty(STDERR_FILENO) != 0) {}

void ProgressLine::starting(size_t set, size_t message) {
  if (!terminal_) return;
  std::cerr << "\r" << line(done_ + set, set, message) << std::flush;
  line_open_ = true;
}

void ProgressLine::finished(size_t alignments, size_t message) {
  done_ += alignments;
  if (!terminal_) std::cerr << line(done_, sets_, message) << "\n";
}

void ProgressLine::note(const std::string& text) {
  std::cerr << (line_open_ ? "\r\033[K" : "") << tool_ << ": " << escapeControlCharacters(text)
            << "\n";
  line_open_ = false;
}

void ProgressLine::end() {
  if (line_open_) std::cerr << "\n";
  line_open_ = false;
}

std::string ProgressLine::line(size_t done, size_t set, size_t message) const {
  std::ostringstream text;
  text << '[' << std::setw(static_cast<int>(std::to_string(total_).size())) << done << '/' << total_
       << "] set " << set << '/' << sets_ << " message " << message << '/' << messages_;
  return text.str();
}

}  // namespace pda_registration
