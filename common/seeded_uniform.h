#pragma once
//! \file seeded_uniform.h
//! The mesher's generic choices (directions and frame rotations that must avoid a measure-zero
//! set of bad values) are drawn from a seeded pseudo-random stream: the same seed and the same
//! sample ids give the same choice in every run, on every thread count.

#include <cstdint>

namespace delmesh {

//! A deterministic pseudo-random number in [0, 1) from a seed and up to three integers
//! (splitmix64 finalisers over the seed and the integers).
inline double seeded_uniform(std::uint64_t seed, std::int64_t a, std::int64_t b = 0, std::int64_t c = 0) {
  std::uint64_t z = seed * 0x9E3779B97F4A7C15ULL;
  for (std::int64_t w : {a, b, c}) {
    z += static_cast<std::uint64_t>(w) + 0x9E3779B97F4A7C15ULL;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    z ^= z >> 31;
  }
  return static_cast<double>(z >> 11) * (1.0 / 9007199254740992.0);
}

//! The seed of the attempt-th alternative to the generic choices drawn from `seed` (attempt 0:
//! `seed` itself).  A check all of whose witnesses were rejected is run again with the choices of
//! attempt 1, 2, … (meshing/driver/refinement.h); each attempt's choices are as generic as the first's.
inline std::uint64_t attempt_seed(std::uint64_t seed, int attempt) {
  return attempt == 0 ? seed : seed ^ (0xD1B54A32D192ED03ULL * static_cast<std::uint64_t>(attempt));
}

//! The streams of the generic choices: the last argument of seeded_uniform, one constant per
//! choice, so that choices made from the same seed and the same ids are independent.
namespace generic_stream {
inline constexpr std::int64_t facet_rotation = 17;       //!< in-plane frame of a Voronoi facet
inline constexpr std::int64_t silhouette_direction = 29; //!< Silhouette's direction d′ of a sample
inline constexpr std::int64_t height_direction = 101;    //!< SampleTopology's height direction
inline constexpr std::int64_t flow_segment = 131;        //!< the flow certificate's counting segments
}  // namespace generic_stream

}  // namespace delmesh
