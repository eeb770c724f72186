#pragma once
// Checks that docs/ documents exactly what the code declares: the dynamic_reconfigure entries of
// cfg/*.cfg, the start-up parameters the node reads and every <arg> of every launch file.
// Each check returns one readable problem per missing, stale or malformed entry (empty = fine).
//
// Convention (docs/nodelet.md, "Parameters" and "Launch files"):
// - a reference table is the first markdown table after a given heading line;
// - its first cell is the backticked name alone: | `k` | ...;
// - a launch file's table follows the heading "### `launch/<file>`"; its second cell (default) is
//   `value` for default="value", "" for default="", *(required)* without a default, and starts
//   with **computed** for an arg declared with value= (set by the launch file itself).

#include <string>
#include <vector>

#include "docs_check/markdown.hpp"

namespace pda_registration {
namespace docs_check {

/// Names of `<any>.add("name", ...)` entries (gen.add, group.add) of a dynamic_reconfigure .cfg.
std::vector<std::string> dynamicReconfigureEntries(const std::string& cfg_text);

/// Names passed to param("name"...), param<T>("name"...) and getParam("name"...) in C++ source.
std::vector<std::string> parametersReadInSource(const std::string& cpp_text);

struct LaunchArg {
  enum class Kind { kDefault, kRequired, kComputed };
  std::string name;
  Kind kind = Kind::kRequired;
  std::string default_value;  ///< for kDefault
};

/// The args a launch file declares: its own <arg> tags, not those passed on inside <include>.
std::vector<LaunchArg> declaredLaunchArgs(const std::string& launch_xml);

/// Missing and stale names: `declared` (by `source`) against the table after `heading` in
/// `page` (named `page_name` in the messages). `what` names the kind: "parameter", "launch arg".
std::vector<std::string> compareWithTable(const std::vector<std::string>& declared,
                                          const std::string& source, const std::string& what,
                                          const std::string& page, const std::string& page_name,
                                          const std::string& heading);

/// Every arg of `launch_file` ("map_alignment.launch") has a row with the right default kind
/// under "### `launch/<launch_file>`" in `page`, and the table has no other rows.
std::vector<std::string> checkLaunchFile(const std::string& launch_file,
                                         const std::string& launch_xml, const std::string& page,
                                         const std::string& page_name);

/// Launch files documented in `page` ("### `launch/x.launch`" headings) that are not in
/// `existing` (file names).
std::vector<std::string> staleLaunchFileSections(const std::vector<std::string>& existing,
                                                 const std::string& page,
                                                 const std::string& page_name);

}  // namespace docs_check
}  // namespace pda_registration
