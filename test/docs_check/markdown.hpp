#pragma once
// The little of markdown the reference checks need: tables under a heading, heading anchors and
// relative links.

#include <string>
#include <vector>

namespace pda_registration {
namespace docs_check {

/// Cells of the rows of the first table after the line `heading` (header and separator rows
/// left out). `problem` says why when the heading or the table is missing.
std::vector<std::vector<std::string>> tableAfterHeading(const std::string& markdown,
                                                        const std::string& heading,
                                                        std::string* problem);

/// GitHub's anchor for a heading's text (ASCII letters, digits, '-', '_' and spaces -> '-';
/// other ASCII dropped; non-ASCII kept except common punctuation such as dashes and arrows).
std::string headingAnchor(const std::string& heading_text);

/// Relative links of the markdown file `path` that do not resolve: a missing file or directory,
/// or an #anchor that no heading of the linked (or the same) markdown file produces.
/// Links inside code (fenced blocks, `spans`) and absolute URLs are not checked.
std::vector<std::string> brokenRelativeLinks(const std::string& path);

}  // namespace docs_check
}  // namespace pda_registration
