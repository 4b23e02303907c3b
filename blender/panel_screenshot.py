# The picture of the Glint panel in blender/README.md, taken by Blender itself. Blender draws its
# interface only in a window (-b, background mode, draws none), so scripts/blender-panel-screenshot
# runs it in a virtual display (xvfb-run, Mesa llvmpipe):
#   blender --factory-startup SCENE.blend --python panel_screenshot.py -- ADDON.zip OUT.png
# SCENE.blend is opened from the command line so that Blender shows no splash screen. The add-on is
# installed from ADDON.zip (into BLENDER_USER_SCRIPTS, which the script points at a temporary
# folder) and enabled; `glint export carpaint` is imported; the Properties editor shows the car
# paint's Material tab, scrolled to the Glint panel, and is written to OUT.png.

import sys

import bpy

arguments = sys.argv[sys.argv.index("--") + 1:]
ADDON_ZIP, GLB, OUTPUT = arguments


def properties_area():
    return next(a for a in bpy.context.window.screen.areas if a.type == "PROPERTIES")


def prepare():
    bpy.ops.preferences.addon_install(filepath=ADDON_ZIP)
    bpy.ops.preferences.addon_enable(module="glint_gltf")
    bpy.context.preferences.view.show_tooltips = False
    for item in list(bpy.data.objects):
        bpy.data.objects.remove(item)
    bpy.ops.import_scene.gltf(filepath=GLB)
    body = bpy.data.objects["car body"]
    bpy.context.view_layer.objects.active = body
    body.select_set(True)
    area = properties_area()
    area.spaces[0].context = "MATERIAL"
    # The Properties editor alone in the window, so that the panel is drawn at full width.
    with bpy.context.temp_override(area=area):
        bpy.ops.screen.screen_full_area()
    bpy.app.timers.register(scroll, first_interval=1.0)


def scroll():
    # The pointer over the editor's header, not over a field (which it would highlight).
    bpy.context.window.cursor_warp(bpy.context.window.width // 2, bpy.context.window.height - 5)
    area = properties_area()
    region = next(r for r in area.regions if r.type == "WINDOW")
    with bpy.context.temp_override(area=area, region=region):
        for _ in range(200):  # to the end: the Glint panel is the last of the Material tab
            bpy.ops.view2d.scroll_down()
    bpy.app.timers.register(shoot, first_interval=1.0)


def shoot():
    area = properties_area()
    with bpy.context.temp_override(area=area):
        bpy.ops.screen.screenshot_area(filepath=OUTPUT)
    print("panel_screenshot.py: wrote " + OUTPUT)
    bpy.ops.wm.quit_blender()


bpy.app.timers.register(prepare, first_interval=1.0)
