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

#include "small_vector.hpp"

#include <cmath>

namespace gdc::detail {

/// The Gauss-map angular tolerance as its cosine and sine (computed once per query).
struct AngularTolerance {
    double cosine;
    double sine;
    explicit AngularTolerance(double radians) : cosine(std::cos(radians)), sine(std::sin(radians)) {}
};

/// The feature of `polytope` whose Gauss-map region is nearest `direction` (unit, local frame),
/// within the angular tolerance for faces and edges.
Feature selectFeature(const Polytope& polytope, const Vec3& direction, const AngularTolerance& tolerance,
                      int bruteForceLimit);

/// Most faces one cap may hold (bounds the time a very finely tessellated flat region costs).
constexpr int kMaxCapFaces = 64;

/// The cap of a selected face: that face and every face reachable from it through shared vertices
/// whose normal is also within the angular tolerance of `direction` — the near-coplanar faces
/// (a hull of noisy points, a finely tessellated flat side) that together make up the flat region
/// the body rests on. Writes face indices, the selected face first; at most kMaxCapFaces.
void faceCap(const Polytope& polytope, int face, const Vec3& direction, const AngularTolerance& tolerance,
             SmallVector<int, 8>& faces);

/// The feature's vertices in order (1 for a vertex, 2 for an edge, the CCW loop of a face).
int featureVertices(const Polytope& polytope, const Feature& feature, const int** indices, int* storage);

}  // namespace gdc::detail
