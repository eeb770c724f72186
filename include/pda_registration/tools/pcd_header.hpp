#pragma once
// A strict check of a PCD file's header before PCL reads it: PCL 1.13's reader crashes on some
// malformed files (a text file without a header segfaults pcl::PCDReader::read), so anything
// that is not a consistent PCD header with enough data behind it is refused here with a reason.

#include <istream>
#include <string>

namespace pda_registration {

/// True when `path` starts with a complete, self-consistent PCD header (FIELDS, SIZE, TYPE and
/// COUNT agree; WIDTH x HEIGHT = POINTS; DATA ascii|binary|binary_compressed) and, for binary
/// data, the file holds at least POINTS x point size bytes after it.
bool checkPcdHeader(const std::string& path, std::string* error);
/// The same check on an open (binary) stream positioned at the start of the file.
bool checkPcdHeader(std::istream& file, std::string* error);

}  // namespace pda_registration
