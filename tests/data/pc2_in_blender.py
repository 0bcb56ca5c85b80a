# Run by tests/app/point_cache_test.cpp where Blender is installed:
#   blender -b --factory-startup --python-exit-code 2 -P pc2_in_blender.py -- FILE.obj FILE.pc2
# Imports the OBJ at rest, plays the point cache on it with a Mesh Cache modifier (format PC2, its
# other settings Blender's defaults) and compares every frame Blender evaluates with the cache's
# samples: frame f shows sample f, with Frame Start 1 frame f + 1 does, and without the modifier
# the mesh is sample 0. Exit 0 when the frames match to the bit and the mesh at rest to 1e-6 m
# (the OBJ's 9 digits of a double, rounded to float, may land one float from the sample's own
# rounding: 2.4e-7 m at 2 m), 1 otherwise.
import struct
import sys

import bpy

obj_path, pc2_path = sys.argv[sys.argv.index("--") + 1:]
data = open(pc2_path, "rb").read()
_, _, points, _, _, samples = struct.unpack_from("<12siiffi", data, 0)

bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.wm.obj_import(filepath=obj_path)
cloth = bpy.context.selected_objects[0]
print("imported", len(cloth.data.vertices), "vertices of", points, "points in the cache")
if len(cloth.data.vertices) != points:
    sys.exit(1)
cache = cloth.modifiers.new("cache", "MESH_CACHE")
cache.cache_format = "PC2"
cache.filepath = pc2_path
scene = bpy.context.scene


def largest_difference(frame, sample):
    """The largest |coordinate − sample's| of the mesh Blender evaluates at `frame`."""
    scene.frame_set(frame)
    evaluated = cloth.evaluated_get(bpy.context.evaluated_depsgraph_get())
    mesh = evaluated.to_mesh()
    worst = 0.0
    for k, v in enumerate(mesh.vertices):
        x = struct.unpack_from("<3f", data, 32 + (sample * points + k) * 12)
        worst = max(worst, max(abs(v.co[a] - x[a]) for a in range(3)))
    evaluated.to_mesh_clear()
    return worst


played = max(largest_difference(s, s) for s in range(samples))
cache.frame_start = 1.0
shifted = max(largest_difference(s + 1, s) for s in range(samples))
cache.show_viewport = False
rest = largest_difference(1, 0)
print(f"largest difference: {played} played, {shifted} from Frame Start 1, {rest} at rest")
sys.exit(0 if played == 0 and shifted == 0 and rest < 1e-6 else 1)
