# Blender 3.4's glTF importer (io_scene_gltf2/blender/imp/gltf2_blender_mesh.py) makes an array of
# dtype np.bool, an alias numpy deprecated in 1.20 and removed in 1.24, the version Debian 12 ships
# with its Blender 3.4.1: every import of a mesh with normals fails with "module 'numpy' has no
# attribute 'bool'". The alias was Python's bool; putting it back is what numpy < 1.24 did.
# Blender 3.5's importer no longer uses it, and numpy 2 has np.bool again: then this does nothing.


def restore_numpy_bool():
    import numpy
    if "bool" not in vars(numpy):  # hasattr would warn (numpy 1.24 warns on the name)
        numpy.bool = bool
