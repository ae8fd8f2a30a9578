#pragma once
//! \file report_html.h
//! The page of `delmesh report`: one self-contained HTML file with an interactive 3-D view of a
//! triangle mesh (three.js, embedded as text and imported through a Blob URL, so the page works
//! from a file:// URL without a network), its triangles coloured by a quality measure with a
//! legend, SVG histograms of the angles and the radius-edge ratios, the checker's report, and the
//! statistics of `delmesh mesh` as tables (the run, the distance certificate, everything else
//! flattened).  The page loads nothing from elsewhere.

#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/enum_names.h"
#include "meshing/core/mesh_checker.h"
#include "meshing/core/mesh_soup.h"

namespace delmesh::app {

//! The measure the triangles are coloured by when the page opens (the page can switch).
enum class ReportColor { min_angle, radius_edge, area, none };
constexpr auto enum_names(ReportColor) {
  return name_table<ReportColor>("ReportColor", {{ReportColor::min_angle, "min-angle"},
                                                 {ReportColor::radius_edge, "radius-edge"},
                                                 {ReportColor::area, "area"},
                                                 {ReportColor::none, "none"}});
}

//! What the page shows.
struct ReportPage {
  std::string mesh_name;  //!< the mesh file as given (shown as text, escaped)
  const TriangleSoup* soup = nullptr;
  MeshReport check;       //!< check_mesh() of the soup
  //! The statistics JSON of `delmesh mesh` (an object), and its file name as given.
  std::optional<nlohmann::ordered_json> statistics;
  std::string statistics_name;
  ReportColor color = ReportColor::min_angle;
  std::string three_js;          //!< the module text (apps/report_three_js.h)
  std::string three_js_version;  //!< e.g. "0.170.0"
  std::string program_version;   //!< e.g. "delmesh 0.1.0"
  std::vector<std::string> notes;  //!< shown above the view (e.g. statistics of another mesh)
};

//! Writes the page to `out`.  The coordinates are embedded centred on the bounding box and
//! divided by half its diagonal, so meshes at any scale (1e-300 to 1e300) show alike; every
//! measure is computed on the original coordinates (apps/report_measures.h), areas as multiples
//! of the mean triangle area.  Text from the files (names, JSON strings) is HTML-escaped, and
//! the embedded JSON cannot end its <script> element.
//! \pre page.soup is set, its indices are in range and its coordinates finite (as after
//! read_polygon_soup and triangulate_polygons), and page.three_js is not empty.
void write_report_page(std::ostream& out, const ReportPage& page);

}  // namespace delmesh::app
