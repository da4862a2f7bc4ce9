#!/usr/bin/env python3
"""Each folder of host/ is a layer; a layer may include only the layers below it.

The table below is the one statement of that order (CMakeLists.txt builds one library per row,
and each links only libraries of the rows this one names). A file that includes a header of a folder not on its row, or a
folder missing from the table, fails the check: a new dependency upward is a design change to
make here on purpose, not by accident. `shared/` (shaders/shared, the headers C++ and GLSL both
compile) lies below every layer.

Usage: layering_check.py SOURCE_DIR
"""
import pathlib
import re
import sys

# folder: the folders (or single headers, "folder/file.h") its files may include, lowest first.
LAYERS = {
    "util":    [],
    "vulkan":  ["util"],
    "bvh":     ["util"],
    "scene":   ["util", "bvh"],
    "gltf":    ["util", "scene"],
    "output":  ["util"],
    "compare": ["util", "output"],
    "cms":     ["util", "scene"],
    "backend": ["util", "output", "cms"],
    "wavefront": ["util", "vulkan", "scene", "output", "cms", "backend"],
    "cpu":     ["util", "scene", "output", "cms", "backend"],
    "session": ["util", "scene", "gltf", "output", "compare", "cms", "backend"],
    "viewer":  ["util", "vulkan", "scene", "output", "cms", "backend", "wavefront", "session"],
    "app":     ["util", "vulkan", "scene", "gltf", "output", "compare", "cms", "backend", "wavefront", "cpu", "session", "viewer"],
}
BELOW_ALL = {"shared"}
# The shaders' interface headers (shaders/<folder>/*_interface.h: a pass's buffers and push
# constants, which the host binds and pushes) lie below every layer too, like shared/.
SHADERS_DIR = pathlib.Path(__file__).resolve().parents[2] / "shaders"


def shader_interface(header):
    return header.endswith("_interface.h") and (SHADERS_DIR / header).is_file()
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"')


def allowed(layer, header):
    folder = header.split("/", 1)[0]
    if "/" not in header or folder == layer or folder in BELOW_ALL or shader_interface(header):
        return True  # a same-folder or generated header (e.g. "intersect.spv.h")
    rules = LAYERS[layer]
    return folder in rules or header in rules


def main():
    host = pathlib.Path(sys.argv[1]) / "host"
    failures = []
    for path in sorted(host.rglob("*")):
        if path.suffix not in {".h", ".cpp", ".inc", ".in"} or not path.is_file():
            continue
        layer = path.relative_to(host).parts[0]
        if layer not in LAYERS:
            failures.append(f"host/{layer}/: a folder the layer table does not know (add it to {__file__})")
            continue
        for number, line in enumerate(path.read_text().splitlines(), 1):
            match = INCLUDE.match(line)
            if match and not allowed(layer, match.group(1)):
                failures.append(f"{path.relative_to(host.parent)}:{number}: {layer}/ includes {match.group(1)}, "
                                f"which is not below it")
    for failure in sorted(set(failures)):
        print("layering: FAIL:", failure)
    if not failures:
        print(f"layering: every include of host/ goes down the table ({len(LAYERS)} layers)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
