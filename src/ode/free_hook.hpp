// ODE's free handler, the only notice of a geom's end ODE 0.16.2 gives (it has no geom-destroy
// callback): the adapter's hook forgets a freed geom's hull (convex_registry), its pair-cache
// entries (pair_cache_table) and a freed trimesh data's mesh (trimesh_geoms), then forwards to
// the handler that was active before it.
#pragma once

namespace gdc::ode::detail {

/// Puts the adapter's free hook in front of ODE's free handler, if it is not there already. Hulls
/// registered while another handler had replaced it lose their trust (convex_registry).
void ensureFreeHook();

/// Whether the adapter's hook is ODE's active free handler: if not, frees go unseen and a geom's
/// address may now hold another geom.
bool freeHookActive();

}  // namespace gdc::ode::detail
