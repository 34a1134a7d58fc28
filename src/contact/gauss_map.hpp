// Stage 2 of the paper: one feature per body from its Gauss map.
//
// On the Gauss map of a polytope a face is a point (its normal), an edge is the arc between its
// two face normals, and a vertex is the spherical region between them. The contact normal lands in
// one region; an angular tolerance widens faces and arcs so that a nearly aligned face is taken as
// a face (precedence face > edge > vertex), which is what makes resting contact produce the whole
// support polygon rather than a flickering vertex.
#pragma once

#include <gdcontact/manifold.hpp>
#include <gdcontact/polytope.hpp>

#include "geometry/small_vector.hpp"
#include "shapes/feature.hpp"

#include <cmath>

namespace gdc::detail {

/// The feature of `polytope` whose Gauss-map region is nearest `direction` (unit, local frame),
/// within the angular tolerance for faces and edges. `support` is the polytope's support vertex
/// in `direction` (the caller has usually just found it).
Feature selectFeature(const Polytope& polytope, const Vec3& direction, int support, const AngularTolerance& tolerance);

/// Whether selectFeature(polytope, direction, support, tolerance) returns `face`, proved without
/// its search (stage 2 of a hull pair, whose enumeration proposes the face: hull_gauge.hpp). The
/// search's candidates include every face around `support`, so `face` is one when `support` is its
/// vertex; it wins when its cosine c_f exceeds the tolerance's and every other face's. Any other
/// face g has n_g·direction ≤ n_g·n_f + |direction − n_f| ≤ largestOtherCosine + |direction − n_f|;
/// c_f above that by more than the dot products' rounding (1e-14 for unit vectors) is strictly the
/// largest, so the search's tie rule never comes in. The cosine is computed as the search does.
inline bool faceIsSelected(const Polytope& polytope, int face, const Vec3& direction, int support,
                           const AngularTolerance& tolerance) {
    const Polytope::Face& f = polytope.faces()[face];
    const Vec3& n = f.normal;
    const double c = n.x() * direction.x() + n.y() * direction.y() + n.z() * direction.z();
    if (!(c > tolerance.cosine)) return false;
    const double margin = c - f.largestOtherCosine - 1e-14;
    if (!(margin > 0) || !(margin * margin > (direction - n).squaredNorm() * (1 + 1e-9))) return false;
    const int* vertices = polytope.faceVertices().data() + f.first;
    for (int i = 0; i < f.count; ++i)
        if (vertices[i] == support) return true;
    return false;
}

/// Most faces one cap may hold (bounds the time a very finely tessellated flat region costs).
constexpr int kMaxCapFaces = 64;

/// The cap of a selected face: that face and every face reachable from it through shared vertices
/// whose normal is also within the angular tolerance of `direction` — the near-coplanar faces
/// (a hull of noisy points, a finely tessellated flat side) that together make up the flat region
/// the body rests on. Writes face indices, the selected face first; at most kMaxCapFaces.
void faceCap(const Polytope& polytope, int face, const Vec3& direction, const AngularTolerance& tolerance,
             SmallVector<int, 8>& faces);

/// Most edges one chain may hold (edgeChain).
constexpr int kMaxChainEdges = 16;

/// The chain of a selected edge: that edge and every edge continuing it end to end, nearly
/// straight (its direction within the angular tolerance of the selected edge's) and with its arc
/// also within the tolerance of `direction` — the nearly collinear edges (a side bent by 1e-6 rad,
/// a finely tessellated rim) that together make up the edge the body touches with, as a face's cap
/// makes up its flat region. Without it rounding picks one of them, in A's frame one and in B's
/// the other (issue 21). Writes edge indices in increasing order; at most kMaxChainEdges.
void edgeChain(const Polytope& polytope, int edge, const Vec3& direction, const AngularTolerance& tolerance,
               SmallVector<int, 8>& edges);

/// The vertices of a face's cap (faceCap), each once, appended in the order the cap's loops meet
/// them, in the polytope's frame.
void capVertices(const Polytope& polytope, const SmallVector<int, 8>& cap, SmallVector<int, 32>& vertices);

}  // namespace gdc::detail
