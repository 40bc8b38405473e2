#!/usr/bin/env python3
# Runs under bash too (`bash scripts/check_layers.py`, as the other scripts are
# run): to bash the next line is the no-op `:` and the one after hands over to
# Python; to Python the three lines are a string.
""":"
exec python3 "$0" "$@"
"""
"""The layer check: every #include and every CMake link of svo's own code must
follow the layer diagram of docs/design.md. Exit 1, naming each offending
line, when one does not.

    python3 scripts/check_layers.py [repository root]

A file belongs to the layer of the deepest folder in FOLDERS that holds it. An
include belongs to the layer whose folder holds the included file (svo/...
paths through each layer's include/ folder; other quoted names beside the
including file, in its layer's src/ and shaders/, else anywhere in the tree).
A CMake link belongs to the layer of the target it names (TARGETS), and the
external libraries and headers a layer may not use are in FORBIDDEN.
"""
import pathlib
import re
import sys

# Folder -> layer. The deepest match wins.
FOLDERS = {
    "core": "core",
    "core/validate": "validate",
    "core/reference": "reference",
    "gl/device": "gl_device",
    "gl/voxelize": "gl_voxelize",
    "gl/fields": "gl_fields",
    "gl/view": "gl_view",
    "gl/nanovdb": "gl_nanovdb",
    "vdb_io/convert": "vdb_io",
    "vdb_io/voxelizer": "svo",
    "apps": "apps",
    "python": "python",
    "bench": "bench",
    "tests": "tests",
}

# The layer diagram: what each layer may use besides itself.
LIBRARIES = ["core", "gl_device", "gl_voxelize", "gl_fields", "gl_view", "gl_nanovdb", "vdb_io", "svo", "validate",
             "reference"]
ALLOWED = {
    "core": [],
    "validate": ["core"],
    "reference": ["core"],
    "gl_device": ["core"],
    "gl_voxelize": ["core", "gl_device"],
    "gl_fields": ["core", "gl_device", "gl_voxelize"],
    "gl_view": ["core", "gl_device"],
    "gl_nanovdb": ["core", "gl_device"],
    "vdb_io": ["core"],
    "svo": ["core", "gl_device", "gl_voxelize", "gl_fields", "gl_nanovdb", "vdb_io"],
    "apps": LIBRARIES,
    "python": LIBRARIES,
    "bench": LIBRARIES,
    "tests": LIBRARIES + ["apps"],
}

# CMake target -> layer (svo_gl is the four GL layers together).
TARGETS = {
    "svo_core": ["core"], "svo::core": ["core"],
    "svo_gl_device": ["gl_device"], "svo::gl_device": ["gl_device"],
    "svo_gl_voxelize": ["gl_voxelize"], "svo::gl_voxelize": ["gl_voxelize"],
    "svo_gl_fields": ["gl_fields"], "svo::gl_fields": ["gl_fields"],
    "svo_gl_view": ["gl_view"], "svo::gl_view": ["gl_view"],
    "svo_gl_nanovdb": ["gl_nanovdb"], "svo::gl_nanovdb": ["gl_nanovdb"],
    "svo_gl": ["gl_device", "gl_voxelize", "gl_fields", "gl_view", "gl_nanovdb"],
    "svo::gl": ["gl_device", "gl_voxelize", "gl_fields", "gl_view", "gl_nanovdb"],
    "svo_vdb_io": ["vdb_io"], "svo::vdb_io": ["vdb_io"],
    "svo_svo": ["svo"], "svo::svo": ["svo"],
    "svo_validate": ["validate"], "svo_reference": ["reference"],
}

# What a layer may not touch outside svo: header prefixes and CMake targets.
NO_GL = (r"^(GL|EGL|GLFW|epoxy)/", r"OpenGL::|glfw|EGL|epoxy")
NO_VDB = (r"^(openvdb|nanovdb)/", r"OpenVDB::")
FORBIDDEN = {
    "core": [NO_GL, NO_VDB, (r"^CGAL/|^embree3/|^vtk", r"CGAL::|embree|VTK::")],
    "gl_device": [NO_VDB], "gl_voxelize": [NO_VDB], "gl_fields": [NO_VDB], "gl_view": [NO_VDB], "gl_nanovdb": [NO_VDB],
    "vdb_io": [NO_GL],
    "validate": [NO_GL], "reference": [NO_GL],
}

SOURCE_SUFFIXES = {".h", ".cpp", ".glsl", ".comp", ".vert", ".frag", ".geom"}
INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]')


def layer_of(root, path):
    rel = path.relative_to(root).as_posix()
    best = None
    for folder, layer in FOLDERS.items():
        if rel == folder or rel.startswith(folder + "/"):
            if best is None or len(folder) > len(best[0]):
                best = (folder, layer)
    return best


def index_tree(root):
    """Every source file by its path under an include/ folder and by its name."""
    by_svo_path, by_name = {}, {}
    for f in root.rglob("*"):
        if f.suffix not in SOURCE_SUFFIXES or not f.is_file() or "build" in f.relative_to(root).parts[:1]:
            continue
        parts = f.relative_to(root).parts
        if "include" in parts:
            by_svo_path["/".join(parts[parts.index("include") + 1:])] = f
        by_name.setdefault(f.name, []).append(f)
    return by_svo_path, by_name


def resolve(root, source, name, by_svo_path, by_name, folder):
    if name in by_svo_path:
        return by_svo_path[name]
    here = source.parent / name
    if here.is_file():
        return here
    for sub in ("src", "shaders", "include"):
        candidate = root / folder / sub / name
        if candidate.is_file():
            return candidate
    found = by_name.get(pathlib.PurePath(name).name, [])
    return found[0] if len(found) == 1 else None


def check_includes(root, problems):
    by_svo_path, by_name = index_tree(root)
    for f in sorted(root.rglob("*")):
        if f.suffix not in SOURCE_SUFFIXES or not f.is_file():
            continue
        owner = layer_of(root, f)
        if owner is None or "build" in f.relative_to(root).parts[:1]:
            continue
        folder, layer = owner
        for number, line in enumerate(f.read_text(errors="replace").splitlines(), 1):
            m = INCLUDE.match(line)
            if not m:
                continue
            bracket, name = m.groups()
            where = f"{f.relative_to(root)}:{number}"
            for header_rule, _ in FORBIDDEN.get(layer, []):
                if re.search(header_rule, name):
                    problems.append(f"{where}: {layer} may not include <{name}>")
            target = resolve(root, f, name, by_svo_path, by_name, folder)
            if target is None:
                continue  # a system or generated header
            other = layer_of(root, target)
            if other is None or other[1] == layer:
                continue
            if other[1] not in ALLOWED[layer]:
                problems.append(f"{where}: {layer} includes {name} of {other[1]}")


def cmake_calls(text, command):
    """The argument lists of every `command(...)` call (parentheses balanced)."""
    for m in re.finditer(r"\b" + command + r"\s*\(", text):
        depth, i = 1, m.end()
        while depth and i < len(text):
            depth += {"(": 1, ")": -1}.get(text[i], 0)
            i += 1
        body = re.sub(r"#[^\n]*", "", text[m.end():i - 1])
        yield text.count("\n", 0, m.start()) + 1, body.split()


def check_links(root, problems):
    for cmake in sorted(root.rglob("CMakeLists.txt")):
        owner = layer_of(root, cmake)
        if owner is None or "build" in cmake.relative_to(root).parts[:1]:
            continue
        layer = owner[1]
        text = cmake.read_text()
        links = [(n, args[1:]) for n, args in cmake_calls(text, "target_link_libraries") if args]
        links += [(n, args[args.index("USES") + 1:]) for n, args in cmake_calls(text, "svo_gl_layer")
                  if "USES" in args]
        for number, args in links:
            where = f"{cmake.relative_to(root)}:{number}"
            for arg in args:
                name = re.sub(r"^\$<(BUILD_INTERFACE|LINK_ONLY):(.*)>$", r"\2", arg)
                for _, target_rule in FORBIDDEN.get(layer, []):
                    if re.search(target_rule, name):
                        problems.append(f"{where}: {layer} may not link {name}")
                for other in TARGETS.get(name, []):
                    if other != layer and other not in ALLOWED[layer]:
                        problems.append(f"{where}: {layer} links {name} ({other})")


def main():
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parent.parent)
    problems = []
    check_includes(root, problems)
    check_links(root, problems)
    for p in problems:
        print(f"check_layers: {p}", file=sys.stderr)
    if problems:
        print(f"check_layers: {len(problems)} dependencies against the layer diagram (docs/design.md)",
              file=sys.stderr)
        return 1
    print("check_layers: every include and link follows the layer diagram")
    return 0


if __name__ == "__main__":
    sys.exit(main())
