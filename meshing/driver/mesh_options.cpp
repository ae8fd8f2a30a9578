#include "meshing/driver/mesh_options.h"

#include <cmath>

namespace delmesh {

std::optional<std::string> violated_range(MeshOption option, const DelMeshOptions& options) {
  switch (option) {
    case MeshOption::lambda:
      if (!(options.lambda > 0) || !(options.lambda < alpha_lambda_bound)) return "satisfy 0 < lambda < 1/3";
      break;
    case MeshOption::size_bound:
      if (options.size_bound && !(std::isfinite(*options.size_bound) && *options.size_bound > 0))
        return "be a positive length";
      break;
    case MeshOption::max_distance:
      if (options.max_distance && !(std::isfinite(*options.max_distance) && *options.max_distance > 0))
        return "be a positive length";
      break;
    case MeshOption::max_points:
      if (options.max_points < 1) return "be at least 1";
      break;
    case MeshOption::time_limit:
      static_assert(max_time_limit_seconds == 1e9, "the requirement below states the bound");
      if (!(options.time_limit_seconds >= 0 && options.time_limit_seconds <= max_time_limit_seconds))
        return "be >= 0 and <= 1e9 seconds (0: none)";
      break;
    case MeshOption::threads:
      if (options.threads < 0) return "be >= 0 (0: every hardware thread)";
      break;
    case MeshOption::min_spacing:
      if (!(std::isfinite(options.min_spacing) && options.min_spacing >= 0)) return "be a length >= 0 (0: no floor)";
      break;
    case MeshOption::feature_angle:
      if (options.feature_angle_deg && !(*options.feature_angle_deg > 0 && *options.feature_angle_deg < 180))
        return "lie in (0, 180) degrees";
      break;
  }
  return std::nullopt;
}

std::optional<OptionViolation> DelMeshOptions::validate() const {
  for (MeshOption option : all_mesh_options)
    if (auto requirement = violated_range(option, *this)) return OptionViolation{option, std::move(*requirement)};
  return std::nullopt;
}

std::optional<std::chrono::steady_clock::time_point> deadline_of(const DelMeshOptions& options,
                                                                 std::chrono::steady_clock::time_point start) {
  if (options.time_limit_seconds <= 0) return std::nullopt;
  return start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                     std::chrono::duration<double>(options.time_limit_seconds));
}

}  // namespace delmesh
