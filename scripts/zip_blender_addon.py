"""Zips the Blender add-on (blender/ctmap_addon) with the built `ctmap` Python module inside it,
for Blender's Preferences > Add-ons > Install. Usage: zip_blender_addon.py ADDON_DIR MODULE.so OUT.zip"""
import os
import sys
import zipfile

addon, module, out = sys.argv[1:4]
tmp = out + ".tmp"
with zipfile.ZipFile(tmp, "w", zipfile.ZIP_DEFLATED) as z:
    for name in sorted(os.listdir(addon)):
        if name.endswith(".py"):
            z.write(os.path.join(addon, name), "ctmap_addon/" + name)
    z.write(module, "ctmap_addon/" + os.path.basename(module))
os.replace(tmp, out)
print(f"wrote {out}")
