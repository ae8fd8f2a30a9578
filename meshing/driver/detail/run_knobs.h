#pragma once
//! \file run_knobs.h
//! Knobs of a DelMesh run that are not options: the library's own tests set them to exercise a
//! code path the options would not reach on a small input.  Programs do not use them; the mesh
//! does not depend on them.

#include "meshing/driver/del_mesh.h"

namespace delmesh::detail {

struct RunKnobs {
  //! Every batch of records and facets runs on options.threads threads, however small
  //! (otherwise batches below tolerances::parallel_least_* run on one), so that a test on a
  //! small surface checks that the mesh does not depend on how the batches were split.
  bool parallel_every_batch = false;
};

//! del_mesh(surface, box, options) with `knobs`.  Same preconditions, results and throws.
DelMeshResult del_mesh_with(const Surface& surface, const Box3& box, const DelMeshOptions& options,
                            const RunKnobs& knobs);

}  // namespace delmesh::detail
