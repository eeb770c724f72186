#include "pda_registration/ros/association_markers.hpp"

#include <algorithm>

namespace pda_registration {
namespace {

geometry_msgs::Point toPoint(const Point& p) {
  geometry_msgs::Point out;
  out.x = p.x();
  out.y = p.y();
  out.z = p.z();
  return out;
}

std_msgs::ColorRGBA weightColour(double weight) {
  std_msgs::ColorRGBA c;
  const float w = static_cast<float>(std::min(std::max(weight, 0.0), 1.0));
  c.r = w;
  c.g = 0.2f;
  c.b = 1.0f - w;
  c.a = w;
  return c;
}

}  // namespace

visualization_msgs::MarkerArray associationMarkers(const Associations& associations,
                                                   const std_msgs::Header& header, size_t max_lines,
                                                   double line_width) {
  visualization_msgs::MarkerArray array;
  visualization_msgs::Marker lines;
  lines.header = header;
  lines.ns = "associations";
  lines.id = 0;
  lines.type = visualization_msgs::Marker::LINE_LIST;
  lines.action = visualization_msgs::Marker::ADD;
  lines.pose.orientation.w = 1.0;
  lines.scale.x = line_width;

  const size_t total = associations.candidates.size();
  const size_t stride =
      (max_lines == 0 || total <= max_lines) ? 1 : (total + max_lines - 1) / max_lines;
  for (size_t i = 0; i < associations.size(); i += stride) {
    const size_t count = associations.offsets[i + 1] - associations.offsets[i];
    if (max_lines > 0 && lines.points.size() / 2 + count > max_lines) break;
    const geometry_msgs::Point from = toPoint(associations.source_points[i]);
    for (size_t c = associations.offsets[i]; c < associations.offsets[i + 1]; ++c) {
      const std_msgs::ColorRGBA colour = weightColour(associations.posterior[c]);
      lines.points.push_back(from);
      lines.points.push_back(toPoint(associations.candidates[c]));
      lines.colors.push_back(colour);
      lines.colors.push_back(colour);
    }
  }
  if (max_lines == 0) lines.action = visualization_msgs::Marker::DELETE;
  array.markers.push_back(lines);
  return array;
}

}  // namespace pda_registration
