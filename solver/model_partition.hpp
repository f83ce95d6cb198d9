#pragma once
/// \file The partition of a Model for distributed runs (issue 37 item 2): the model's elements
/// weighted by their cost, its rigid bodies kept whole and the contact candidate pairs of the
/// t = 0 search as extra graph edges, handed to partition/mesh_partition.hpp.

#include <string>
#include <vector>

#include "contact/contact_engine.hpp"
#include "partition/mesh_partition.hpp"
#include "solver/model/model.hpp"
#include "solver/motion/rigid_bodies.hpp"
#include "solver/motion/ties.hpp"
#include "solver/output/output_sink.hpp"

namespace xpl {

/// Relative cost of one increment of element e (a C3D8R elastic = 1), measured on this
/// machine (benchmarks/RESULTS.md, "Current numbers", one thread): C3D8 2.2, S4R 1.67
/// (7.7 / 4.6 M element-cycles/s), plastic hexes × 1.12 (plastic / elastic rate 0.89),
/// plastic shells × 1.67 (rate 0.45 all yielding to 0.94 bending: 0.6 taken); 0 for an
/// element of a rigid body (no element kernel runs on it).
Real element_cost(const Model& model, Index e, bool rigid);

/// The model's partition into `parts` with `method`: element costs, rigid bodies (`rigid`)
/// whole, an edge between the element of each slave node and the element of each master
/// face the t = 0 broad phase of `engine` lists for it (null: no contact), and one between
/// the element of each tied slave node and those of its master corners (`ties`).
partition::MeshPartition partition_model(const Model& model, const RigidBodies& rigid,
                                         const Ties& ties, const contact::ContactEngine* engine,
                                         int parts, partition::Method method);

/// partition_model() timed, its report into the .msg (Info) after `note` (when not empty),
/// when parts > 1; nothing else.
void report_partition(const Model& model, const RigidBodies& rigid, const Ties& ties,
                      const contact::ContactEngine* engine, int parts, partition::Method method,
                      const std::string& note, OutputSink& sink);

}  // namespace xpl
