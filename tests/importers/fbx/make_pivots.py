# Makes pivots.fbx and pivots.glb beside this script: an FBX whose Models use
# every part of the FBX SDK's transform (rotation offset and pivot, pre- and
# post-rotation, rotation orders, scaling offset and pivot, geometric
# translation, rotation and scaling; RotationActive on and off), written by
# Blender's own FBX encoder (io_scene_fbx.encode_bin), and Blender's reading
# of it exported as glTF: the reference the FBX importer's transforms are
# tested against. Not part of the build: both files are committed.
#
#   blender -b --factory-startup -noaudio --python tests/importers/fbx/make_pivots.py
import os
import sys

import numpy

numpy.bool = bool

import bpy  # noqa: E402
import addon_utils  # noqa: E402

here = os.path.dirname(os.path.abspath(__file__))
addon_utils.enable("io_scene_fbx")
sys.path.append(os.path.join(os.path.dirname(addon_utils.paths()[0]), "addons", "io_scene_fbx"))
for path in addon_utils.paths():
    sys.path.append(os.path.join(path, "io_scene_fbx"))
import encode_bin  # noqa: E402


def child(parent, name):
    elem = encode_bin.FBXElem(name.encode())
    parent.elems.append(elem)
    return elem


def leaf(parent, name, add, value):
    elem = child(parent, name)
    getattr(elem, add)(value)
    return elem


def properties(parent, entries):
    block = child(parent, "Properties70")
    for name, kind, values in entries:
        p = child(block, "P")
        # Name, type, label, flags as the FBX SDK writes them (Blender's reader checks them).
        label = {"double": "Number", "int": "Integer", "Vector3D": "Vector"}.get(kind, "")
        flags = "A" if kind.startswith("Lcl") else ""
        for s in (name, kind, label, flags):
            p.add_string(s.encode())
        for v in values:
            if kind == "int" or kind == "enum" or kind == "bool":
                p.add_int32(v)
            else:
                p.add_float64(v)


def name(n, cls):
    return n.encode() + b"\x00\x01" + cls.encode()


root = encode_bin.FBXElem(b"")
header = child(root, "FBXHeaderExtension")
leaf(header, "FBXHeaderVersion", "add_int32", 1003)
leaf(header, "FBXVersion", "add_int32", 7400)
settings = child(root, "GlobalSettings")
leaf(settings, "Version", "add_int32", 1000)
properties(settings, [("UpAxis", "int", [1]), ("UpAxisSign", "int", [1]), ("FrontAxis", "int", [2]),
                      ("FrontAxisSign", "int", [1]), ("CoordAxis", "int", [0]), ("CoordAxisSign", "int", [1]),
                      ("UnitScaleFactor", "double", [100.0])])
objects = child(root, "Objects")

# A box that is not centred on its origin, so pivots show.
corners = [(x, y, z) for z in (0.0, 1.0) for y in (0.0, 2.0) for x in (0.5, 1.5)]
quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]


def geometry(id, label):
    g = child(objects, "Geometry")
    g.add_int64(id)
    g.add_string(name(label, "Geometry"))
    g.add_string(b"Mesh")
    leaf(g, "Vertices", "add_float64_array", [c for corner in corners for c in corner])
    leaf(g, "PolygonVertexIndex", "add_int32_array", [i if k < 3 else ~i for quad in quads for k, i in enumerate(quad)])


def model(id, label, kind, props):
    m = child(objects, "Model")
    m.add_int64(id)
    m.add_string(name(label, "Model"))
    m.add_string(kind.encode())
    leaf(m, "Version", "add_int32", 232)
    properties(m, props)


geometry(10, "BoxGeometry")
geometry(11, "PlainGeometry")
model(20, "Parent", "Null", [
    ("Lcl Translation", "Lcl Translation", [0.3, -0.2, 0.4]),
    ("RotationActive", "bool", [1]),
    ("RotationOrder", "enum", [4]),  # ZXY
    ("PreRotation", "Vector3D", [10.0, -20.0, 5.0]),
    ("Lcl Rotation", "Lcl Rotation", [30.0, 15.0, -40.0]),
    ("RotationOffset", "Vector3D", [0.1, 0.0, -0.1]),
    ("RotationPivot", "Vector3D", [0.5, 1.0, 0.25]),
    ("ScalingOffset", "Vector3D", [0.0, 0.2, 0.0]),
    ("ScalingPivot", "Vector3D", [-0.3, 0.4, 0.1]),
    ("Lcl Scaling", "Lcl Scaling", [1.5, 0.8, 1.2]),
])
model(21, "Box", "Mesh", [
    ("Lcl Translation", "Lcl Translation", [1.0, 0.5, -0.5]),
    ("RotationActive", "bool", [1]),
    ("RotationOrder", "enum", [2]),  # YZX
    ("Lcl Rotation", "Lcl Rotation", [-25.0, 60.0, 10.0]),
    # A half turn, its own inverse: Blender 3.4 applies a post-rotation as it
    # is where the FBX SDK and three.js apply its inverse, and both agree here.
    ("PostRotation", "Vector3D", [0.0, 180.0, 0.0]),
    ("GeometricTranslation", "Vector3D", [0.2, -0.1, 0.3]),
    ("GeometricRotation", "Vector3D", [0.0, 45.0, 0.0]),
    ("GeometricScaling", "Vector3D", [1.0, 1.0, 2.0]),
])
# Pre-rotation and order written but RotationActive off: both are ignored.
model(22, "Plain", "Mesh", [
    ("Lcl Translation", "Lcl Translation", [-2.0, 0.0, 0.0]),
    ("RotationOrder", "enum", [5]),
    ("PreRotation", "Vector3D", [90.0, 0.0, 0.0]),
    ("Lcl Rotation", "Lcl Rotation", [0.0, 0.0, 20.0]),
])

connections = child(root, "Connections")
for a, b in ((20, 0), (21, 20), (10, 21), (22, 0), (11, 22)):
    c = child(connections, "C")
    c.add_string(b"OO")
    c.add_int64(a)
    c.add_int64(b)

fbx_path = os.path.join(here, "pivots.fbx")
encode_bin.write(fbx_path, root, 7400)

bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.fbx(filepath=fbx_path)
bpy.ops.export_scene.gltf(filepath=os.path.join(here, "pivots.glb"), export_format='GLB', export_animations=False)
