"""quadsimp's filters in pymeshlab 2025.7.

    import pymeshlab, quadsimp_pymeshlab
    quadsimp_pymeshlab.load()
    ms = pymeshlab.MeshSet(); ms.load_new_mesh(path); ms.meshing_quad_mesh_simplification(targetfacenum=5000)
"""
import os

import pymeshlab

FILTERS = (
    "meshing_quad_mesh_simplification",
    "meshing_tri_to_pure_quad",
    "compute_scalar_by_fitmap_per_vertex",
    "get_quad_mesh_quality_measures",
)

_loaded = None


def plugin_path():
    """The plugin to load: $QUADSIMP_PLUGIN, or the copy bundled in this package."""
    path = os.environ.get("QUADSIMP_PLUGIN") or os.path.join(os.path.dirname(__file__), "libfilter_quadsimp.so")
    if not os.path.exists(path):
        raise FileNotFoundError(f"quadsimp MeshLab 2025.07 plugin not found at {path}")
    return path


def load(path=None):
    """Loads the plugin into pymeshlab and adds the four filters as MeshSet methods,
    like pymeshlab's own filters. Loading twice is a no-op. Returns the plugin path."""
    global _loaded
    path = path or plugin_path()
    if _loaded is None:
        pymeshlab.load_plugin(path)
        _loaded = path
    # pymeshlab binds its own filters as methods when it is imported; filters from a
    # plugin loaded later are only reachable through apply_filter until bound the same way.
    for name in FILTERS:
        setattr(pymeshlab.MeshSet, name, pymeshlab.bind_function(name))
    return _loaded
