"""Builds a small room with a TV in Blender and exports it as a GLB for Penumbra.

This script stands in for modelling by hand: every step is one a user does in Blender's UI
(add a cube, scale it, give the screen an emissive material named `Screen`, place a camera),
followed by File > Export > glTF 2.0 with the settings docs/blender.md lists.

Usage: blender -b --factory-startup -P examples/blender/make_tv_room.py -- OUT.glb
"""

import sys

import bpy


def output_path():
    args = sys.argv[sys.argv.index("--") + 1 :] if "--" in sys.argv else []
    if len(args) != 1:
        sys.exit("usage: blender -b --factory-startup -P make_tv_room.py -- OUT.glb")
    return args[0]


def diffuse_material(name, colour):
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    bsdf = material.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (*colour, 1.0)
    bsdf.inputs["Roughness"].default_value = 1.0
    return material


def emissive_material(name, strength):
    material = diffuse_material(name, (0.0, 0.0, 0.0))
    bsdf = material.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Emission"].default_value = (1.0, 1.0, 1.0, 1.0)
    bsdf.inputs["Emission Strength"].default_value = strength
    return material


def box(name, centre, size, material):
    """A cube scaled to `size` (full extents, Blender's z up) with its centre at `centre`."""
    bpy.ops.mesh.primitive_cube_add(size=1.0, location=centre)
    obj = bpy.context.active_object
    obj.name = name
    obj.scale = size
    obj.data.materials.append(material)
    return obj


def build_room():
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene

    wall = diffuse_material("Wall", (0.8, 0.8, 0.8))
    floor = diffuse_material("Floor", (0.55, 0.45, 0.35))
    frame = diffuse_material("TVFrame", (0.05, 0.05, 0.05))
    crate = diffuse_material("Box", (0.8, 0.2, 0.15))
    screen = emissive_material("Screen", 5.0)

    # The room: 6 m wide (x), 5 m deep (y), 3 m high (z); thin boxes so that each side is solid.
    box("Floor", (0.0, 0.0, -0.05), (6.0, 5.0, 0.1), floor)
    box("BackWall", (0.0, 2.55, 1.5), (6.0, 0.1, 3.0), wall)
    box("LeftWall", (-3.05, 0.0, 1.5), (0.1, 5.0, 3.0), wall)
    box("RightWall", (3.05, 0.0, 1.5), (0.1, 5.0, 3.0), wall)

    # The TV on the back wall: a thin dark frame and, just in front of it, the screen plane
    # facing the room (-y), 16:9 to match the video.
    box("TV", (0.0, 2.42, 1.4), (1.76, 0.06, 1.04), frame)
    bpy.ops.mesh.primitive_plane_add(size=1.0, location=(0.0, 2.385, 1.4), rotation=(1.5708, 0.0, 0.0))
    plane = bpy.context.active_object
    plane.name = "Screen"
    plane.scale = (1.6, 0.9, 1.0)
    plane.data.materials.append(screen)

    # A box on the floor in front of the TV, turned so that its shadow is not axis-aligned.
    crate_obj = box("Crate", (0.5, 1.2, 0.3), (0.6, 0.6, 0.6), crate)
    crate_obj.rotation_euler = (0.0, 0.0, 0.5)

    # The camera in the front of the room, looking at the TV; 16:9 render resolution.
    bpy.ops.object.camera_add(location=(-1.2, -2.3, 1.6), rotation=(1.45, 0.0, -0.35))
    camera = bpy.context.active_object
    camera.name = "Camera"
    camera.data.lens_unit = "FOV"
    camera.data.angle = 1.2
    scene.camera = camera
    scene.render.resolution_x = 640
    scene.render.resolution_y = 360


def export(path):
    bpy.ops.export_scene.gltf(
        filepath=path,
        export_format="GLB",
        export_cameras=True,
        export_lights=False,
        export_yup=True,
        export_apply=True,
        export_texcoords=True,
        export_normals=True,
        export_materials="EXPORT",
        export_animations=False,
    )


build_room()
export(output_path())
