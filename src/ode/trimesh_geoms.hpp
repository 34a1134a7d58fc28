// ODE's trimesh geoms (dTriMeshClass) as gdc::TriangleMesh, and the pairs gdcontact collides with
// them: box–, convex–, capsule– and cylinder–trimesh (round_geoms.hpp's isGdcontactPair). docs/ode.md,
// "Triangle meshes".
//
// Reading the mesh. ODE 0.16 has no public getter of a trimesh data's vertex and index buffers, so
// the mesh is read through the geom: dGeomTriMeshGetTriangleCount and dGeomTriMeshGetTriangle
// (world coordinates), mapped back to the geom's frame with its pose (local = Rᵀ(world − p)).
// Vertices that come out within a weld tolerance of each other (a billionth of the mesh's size, or
// the rounding of the mapping where that is larger) are one vertex, so that triangles sharing an
// edge are neighbours even where the data repeats its vertices (a triangle soup) or the mapping
// rounds a shared vertex differently. Triangles keep ODE's numbers (a degenerate one stays numbered
// and never touches anything: TriangleMesh).
//
// Caching. The mesh is built once per dTriMeshDataID (every geom of one data shares it: the data's
// vertices are in the geom's frame) and kept in a process-wide map under a mutex. ODE frees a data
// through its free handler, which the adapter hooks (free_hook.hpp): the entry then goes. Because
// a data can still change under the same address unseen — destroyed while the hook was not ODE's
// handler and another built at its address, or given new vertices by dGeomTriMeshDataUpdate — every
// use also checks, cheaply, that the triangle count and three sampled triangles (the first, the
// middle and the last, read through the geom and mapped back) still match what was read when the
// mesh was built; the mesh is built again when they do not. A change that keeps the count and those
// three triangles (a vertex moved in place elsewhere with dGeomTriMeshDataUpdate) is not seen: build
// a new data for it. The mesh is also built again when the settings differ (the edges' activity
// depends on Settings::angularTolerance).
#pragma once

#include "thread_cache.hpp"
#include "resolved_pair.hpp"

#include <gdcontact/settings.hpp>
#include <gdcontact/triangle_mesh.hpp>

#include <ode/ode.h>

#include <cstddef>
#include <memory>

namespace gdc::ode::detail {

/// The mesh of the trimesh geom `geom` in the geom's frame, `pose` being the geom's world pose
/// (readPoseInto). Shared: it stays valid while the caller holds it, whatever happens to the cache.
/// nullptr for a data without triangles, and for a data whose mesh could not be built before (its
/// error was thrown, and so reported, once, when that was found). Throws InvalidInput for a geom
/// without data, a non-finite vertex or pose, and the first time a data's mesh cannot be built.
/// Thread-safe; calls ODE's getters outside the lock.
std::shared_ptr<const TriangleMesh> trimeshOf(dGeomID geom, const Pose& pose, const Settings& settings);

/// For the free hook: forgets the mesh of the data at `address` if there is one (ODE is freeing
/// it). Never throws; takes no lock while no mesh is cached.
void forgetTrimeshData(const void* address) noexcept;

/// Number of trimesh datas whose mesh is cached (tests).
std::size_t cachedTrimeshCount();

/// Resolves a pair with a trimesh geom (out.o1, o2, class1, class2 set): kind Mesh with the other
/// geom's polytope in polytope1 (a capsule or a cylinder: nullptr, its kind and size in kind1 and
/// round1) and its pose in pose1, the mesh geom's pose in pose2, `flip` when
/// o1 is the mesh. Kind Ode (ODE's own collider) when the other geom is a convex gdcontact does not
/// know: false then for a plain dCreateConvex geom (as resolvePair). dError for a class pair
/// gdcontact does not collide.
bool resolveMeshPair(const Settings& settings, ThreadCache& cache, ResolvedPair& out);

/// The contacts of a resolved Mesh pair in ODE's convention: at most maxContacts, the deepest,
/// ordered as Settings::contactOrder says, normal from o2 into o1, depth ≥ 0, the triangle's index
/// in the trimesh's side field (side1 when o1 is the mesh, side2 when o2 is, as ODE's own trimesh
/// colliders and dCollide's reversal give it), -1 in the other. The geom's dTriCallback, if any, is
/// asked about each triangle the mid phase finds (a rejected one gives none and takes no place in
/// the reduction: TriangleFilter); its dTriArrayCallback,
/// if any, gets the triangles whose bounds meet the shape's, as ODE's colliders give it theirs.
/// Throws (the caller's guard reports it).
int collideMeshPair(const ResolvedPair& pair, int maxContacts, dContactGeom* contact, int skip,
                    const Settings& settings);

}  // namespace gdc::ode::detail
