# Makes rigged_face.{fbx,glb} and animated_face.{fbx,glb} beside this script: one small
# scene written by Blender's own FBX and glTF exporters, so that the FBX
# importer is tested against another reader's idea of the same scene (the
# glTF loader's), not against a writer of ours. Not part of the build: the
# two files are committed; run again only to change the scene.
#
#   blender -b --factory-startup -noaudio --python tests/importers/fbx/make_rigged_face.py
#
# (Debian's Blender 3.4 with numpy 1.24 needs the np.bool alias below.)
# The scene: an armature of two bones, turned, scaled and moved as an
# object; a skinned low-polygon "face" (a UV sphere) with two shape keys
# named as ARKit names them, one with a default weight, two materials (one
# with an embedded 4x4 texture), and a static "hat" parented to the armature
# with a transform of its own.
import math
import os

import numpy

numpy.bool = bool

import bpy  # noqa: E402

here = os.path.dirname(os.path.abspath(__file__))
bpy.ops.wm.read_factory_settings(use_empty=True)

# A 4x4 texture, each texel its own colour, so a flipped V shows.
image = bpy.data.images.new("checker", 4, 4)
pixels = []
for y in range(4):
    for x in range(4):
        pixels += [x / 3.0, y / 3.0, 0.5, 1.0]
image.pixels = pixels
image.filepath_raw = os.path.join(bpy.app.tempdir, "checker.png")
image.file_format = 'PNG'
image.save()

skin = bpy.data.materials.new("Skin")
skin.use_nodes = True
bsdf = skin.node_tree.nodes["Principled BSDF"]
texture = skin.node_tree.nodes.new("ShaderNodeTexImage")
texture.image = image
skin.node_tree.links.new(texture.outputs["Color"], bsdf.inputs["Base Color"])
iris = bpy.data.materials.new("Iris")
iris.use_nodes = True
iris.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value = (0.1, 0.2, 0.7, 1.0)

# The armature: Root up the Z axis (Blender's up), Head above it.
bpy.ops.object.armature_add(enter_editmode=True, location=(0, 0, 0))
rig = bpy.context.object
rig.name = "Rig"
bones = rig.data.edit_bones
root = bones[0]
root.name = "Root"
root.head, root.tail = (0, 0, 0), (0, 0, 1)
head = bones.new("Head")
head.head, head.tail = (0, 0, 1), (0, 0.2, 2.4)
head.parent = root
bpy.ops.object.mode_set(mode='OBJECT')
rig.location = (0.3, -0.2, 0.1)
rig.rotation_euler = (math.radians(10), 0, math.radians(25))
rig.scale = (1.5, 1.5, 1.5)

bpy.ops.mesh.primitive_uv_sphere_add(segments=12, ring_count=6, radius=0.8, location=(0, 0, 1.6))
face = bpy.context.object
face.name = "Face"
face.data.materials.append(skin)
face.data.materials.append(iris)
for polygon in face.data.polygons:
    centre = polygon.center
    polygon.material_index = 1 if centre.y < -0.5 and centre.z > 0.1 else 0
# Shape keys: the jaw drops the lower half, the left corner moves out and up.
face.shape_key_add(name="Basis")
jaw = face.shape_key_add(name="jawOpen")
smile = face.shape_key_add(name="mouthSmile_L")
for i, v in enumerate(face.data.vertices):
    if v.co.z < -0.2:
        jaw.data[i].co = v.co + v.co.__class__((0, 0, -0.25))
    if v.co.x > 0.3 and v.co.z < 0.2:
        smile.data[i].co = v.co + v.co.__class__((0.1, 0, 0.12))
jaw.value = 0.25
# Skinned to both bones by height; parented to the rig.
root_group = face.vertex_groups.new(name="Root")
head_group = face.vertex_groups.new(name="Head")
for v in face.data.vertices:
    t = min(max((v.co.z + 0.8) / 1.6, 0.0), 1.0)
    root_group.add([v.index], 1.0 - t, 'REPLACE')
    head_group.add([v.index], t, 'REPLACE')
face.parent = rig
modifier = face.modifiers.new("Armature", 'ARMATURE')
modifier.object = rig

bpy.ops.mesh.primitive_cube_add(size=0.5, location=(0.4, 0.1, 2.6))
hat = bpy.context.object
hat.name = "Hat"
hat.rotation_euler = (0, math.radians(30), math.radians(-15))
hat.scale = (1.0, 2.0, 0.5)
hat.data.materials.append(iris)
hat.parent = rig

bpy.ops.export_scene.fbx(filepath=os.path.join(here, "rigged_face.fbx"), path_mode='COPY', embed_textures=True,
                         add_leaf_bones=False, bake_anim=False)
bpy.ops.export_scene.gltf(filepath=os.path.join(here, "rigged_face.glb"), export_format='GLB', export_animations=False)

# The same scene animated over one second at 24 frames per second (frames 1 to
# 25): the jaw opens and closes, the smile comes in, the Head bone nods.
# animated_face.fbx (baked, every frame keyed) and animated_face.glb.
scene = bpy.context.scene
scene.render.fps = 24
scene.frame_start, scene.frame_end = 1, 25
for frame, jaw_weight, smile_weight in ((1, 0.0, 0.0), (9, 1.0, 0.2), (17, 0.3, 1.0), (25, 0.0, 0.0)):
    jaw.value, smile.value = jaw_weight, smile_weight
    jaw.keyframe_insert("value", frame=frame)
    smile.keyframe_insert("value", frame=frame)
bpy.ops.object.select_all(action='DESELECT')
rig.select_set(True)
bpy.context.view_layer.objects.active = rig
bpy.ops.object.mode_set(mode='POSE')
nod = rig.pose.bones["Head"]
nod.rotation_mode = 'XYZ'
for frame, angle, lift in ((1, 0.0, 0.0), (13, 35.0, 0.15), (25, -10.0, 0.0)):
    nod.rotation_euler = (math.radians(angle), 0.0, math.radians(angle / 3))
    nod.location = (0.0, lift, 0.0)
    nod.keyframe_insert("rotation_euler", frame=frame)
    nod.keyframe_insert("location", frame=frame)
bpy.ops.object.mode_set(mode='OBJECT')
bpy.ops.export_scene.fbx(filepath=os.path.join(here, "animated_face.fbx"), path_mode='COPY', embed_textures=True,
                         add_leaf_bones=False, bake_anim=True, bake_anim_use_all_actions=False,
                         bake_anim_use_nla_strips=False, bake_anim_simplify_factor=0.0)
bpy.ops.export_scene.gltf(filepath=os.path.join(here, "animated_face.glb"), export_format='GLB', export_animations=True,
                          export_force_sampling=True, export_frame_range=True)
