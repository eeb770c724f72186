#pragma once
// pda_bag_eval's progress on stderr, "[ 12/40] set 3/8 message 4/5": redrawn in place on a
// terminal, one line per finished message otherwise, so logs stay readable.

#include <cstddef>
#include <string>

namespace pda_registration {

class ProgressLine {
 public:
  /// `tool` prefixes notes; `total` alignments over `sets` parameter sets and `messages` maps.
  ProgressLine(std::string tool, size_t total, size_t sets, size_t messages);

  /// Set `set` (1-based) is about to align message `message`: redraws the line on a terminal.
  void starting(size_t set, size_t message);
  /// Message `message` is done with `alignments` more alignments.
  void finished(size_t alignments, size_t message);
  /// Prints a message on its own line, clearing the progress line first.
  void note(const std::string& text);
  /// Ends an open progress line before anything else is printed.
  void end();

 private:
  std::string line(size_t done, size_t set, size_t message) const;

  std::string tool_;
  size_t total_, sets_, messages_, done_ = 0;
  bool terminal_, line_open_ = false;
};

}  // namespace pda_registration
