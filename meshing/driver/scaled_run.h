#pragma once
//! \file scaled_run.h
//! A run of del_mesh at unit scale (meshing/inputs/unit_scale.h): its options go in, and its
//! output and statistics come out, multiplied by 2^∓k.

#include "meshing/driver/del_mesh.h"
#include "meshing/inputs/unit_scale.h"

namespace delmesh {

//! The options of a run at unit scale: min_spacing, size_bound and max_distance times 2^-k.
DelMeshOptions unit_scale_options(DelMeshOptions options, int k);

//! A run at unit scale brought back to the input's scale: the output mesh's vertices and the
//! statistics' clip_box, unsettled.regions[].location, min_spacing and topology_phase.min_spacing
//! (value, topology_value, locations), and closed_ball's listed witnesses, witness distances and
//! non-generic locations, times 2^k; the statistics get "unit_scale_exponent": k.
void restore_scale(DelMeshResult& result, int k);

}  // namespace delmesh
