"""The keywords of svo's calls: declared once (the library's options beside
their structs, Python's own in module.cpp), and the stub, the docstrings and
the reading of **kwargs agree with those declarations."""
import ast
import pathlib

import numpy as np
import pytest

import svo

STUB = pathlib.Path(__file__).resolve().parent.parent / "svo" / "__init__.pyi"
OPTIONS = svo._options()


def stub_functions():
    """Each function the stub declares, by the name _options() uses: "voxelize", "Voxelizer.voxelize"."""
    out = {}
    for node in ast.parse(STUB.read_text()).body:
        if isinstance(node, ast.FunctionDef):
            out[node.name] = node
        elif isinstance(node, ast.ClassDef):
            for item in node.body:
                if isinstance(item, ast.FunctionDef):
                    out[f"{node.name}.{item.name}"] = item
    return out


def call_named(name):
    """svo.voxelize for "voxelize", svo.Voxelizer.octree for "Voxelizer.octree"."""
    obj = svo
    for part in name.split("."):
        obj = getattr(obj, part)
    return obj


# The annotation a default of each type has in the stub.
ANNOTATIONS = {bool: "bool", str: "str", float: "float", int: "int", tuple: "Sequence[str]"}


def annotation_of(default):
    """A default's annotation: a tuple of ints (render's size) is a fixed-size Tuple, other tuples lists of names."""
    if isinstance(default, tuple) and default and all(type(v) is int for v in default):
        return f"Tuple[{', '.join('int' for _ in default)}]"
    return ANNOTATIONS[type(default)]


@pytest.mark.parametrize("name", sorted(OPTIONS))
def test_the_stub_declares_each_calls_keywords_and_defaults(name):
    declared = OPTIONS[name]
    function = stub_functions().get(name)
    assert function is not None, f"the stub lacks {name}"
    args = function.args
    stub = {a.arg: (ast.literal_eval(d), a.annotation) for a, d in zip(args.kwonlyargs, args.kw_defaults)}
    assert sorted(stub) == sorted(declared), f"{name}: the stub's keywords differ from the module's"
    for keyword, entry in declared.items():
        default, annotation = stub[keyword]
        # The same value and type: 3.0, not 3; (), not [].
        assert (type(default), default) == (type(entry["default"]), entry["default"]), f"{name}({keyword}=...)"
        if entry["default"] is not None:
            assert ast.unparse(annotation) == annotation_of(default), f"{name}({keyword}: ...)"
    # Every option is keyword-only: no positional parameter has a default.
    assert not args.defaults, f"{name}: a positional parameter with a default"


def test_resolution_is_a_whole_number_in_the_stub():
    for name, function in stub_functions().items():
        for a in function.args.kwonlyargs:
            if a.arg == "resolution":
                assert ast.unparse(a.annotation) == "Optional[int]", name


@pytest.mark.parametrize("name", sorted(OPTIONS))
def test_docstrings_list_each_keyword_with_its_default_and_doc(name):
    doc = call_named(name).__doc__
    for keyword, entry in OPTIONS[name].items():
        assert f"    {keyword}={entry['default']!r}\n" in doc, f"{name}: {keyword}"
        assert " ".join(entry["doc"].split()) in " ".join(doc.split()), f"{name}: {keyword}'s doc"
    for entry in OPTIONS[name].values():
        assert entry["doc"] and "\n" not in entry["doc"]


def test_library_defaults_are_the_structs():
    assert OPTIONS["Voxelizer.level_set"]["winding_accuracy"]["default"] == 1.5
    assert OPTIONS["Voxelizer.level_set"]["exterior_band"]["default"] == 3.0
    assert OPTIONS["Voxelizer.level_set"]["closest_triangle"]["default"] is False
    assert OPTIONS["Voxelizer.voxelize"]["mode"]["default"] == "conservative"
    assert OPTIONS["Voxelizer.voxelize"]["gpu_memory"]["default"] is None
    assert OPTIONS["Voxelizer.voxelize"]["attributes"]["default"] == ()
    assert OPTIONS["voxelize"] == OPTIONS["Voxelizer.voxelize"]
    # The library's names, which its errors use, beside the keywords that replace them in Python's messages.
    assert OPTIONS["Voxelizer.level_set"]["exterior_band"]["identifier"] == "LevelSetOptions::exteriorBand"
    assert OPTIONS["Voxelizer.voxelize"]["conservative"]["identifier"] == "VoxelizeOptions::dilation"
    assert OPTIONS["Voxelizer.voxelize"]["resolution"]["identifier"] == "GridRequest::resolution"
    assert OPTIONS["Voxelizer.voxelize"]["grid"]["identifier"] is None  # Python's own
    # The view's options, declared beside their structs as svo view's flags are.
    render = OPTIONS["Octree.render"]
    assert render["ao_aperture"]["default"] == 60.0 and render["ao_aperture"]["identifier"] == "AmbientOcclusion::apertureDegrees"
    assert render["gi_cones"]["default"] == 5 and type(render["gi_cones"]["default"]) is int
    assert render["light_volume"]["default"] == 256
    assert render["gi_emission"]["default"] == "isotropic"
    assert render["surface"]["identifier"] == "ViewRequest::surface"
    assert render["lighting"]["identifier"] is None  # Python's own word for svo view's --render


TETRAHEDRON = (np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float),
               np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]))


@pytest.mark.parametrize("call, keyword", [
    (lambda **k: svo.voxelize(*TETRAHEDRON, **k), "voxelize() got an unexpected keyword argument 'resolutoin'"),
    (lambda **k: svo.Voxelizer().level_set(*TETRAHEDRON, **k),
     "level_set() got an unexpected keyword argument 'resolutoin'"),
    (lambda **k: svo.Voxelizer(**k), "Voxelizer() got an unexpected keyword argument 'resolutoin'"),
])
def test_an_unknown_keyword_is_a_type_error_as_pythons(call, keyword):
    with pytest.raises(TypeError, match=keyword.replace("(", r"\(").replace(")", r"\)")):
        call(resolutoin=8)


def test_a_keyword_another_call_takes_is_refused():
    # mode= is voxelize()'s; level sets do not depend on it.
    with pytest.raises(TypeError, match="level_set\\(\\) got an unexpected keyword argument 'mode'"):
        svo.Voxelizer().level_set(*TETRAHEDRON, resolution=8, mode="thin")


@pytest.mark.parametrize("call, kwargs", [
    ("level_set", {"backend": 3}),
    ("voxelize", {"attributes": "normal"}),  # a str is not a list of names
    ("level_set", {"unsigned": "yes"}),
    ("level_set", {"exterior_band": "3"}),
])
def test_a_keyword_of_the_wrong_type_is_a_type_error(call, kwargs):
    with pytest.raises(TypeError, match=f"keyword '{next(iter(kwargs))}' has the wrong type"):
        getattr(svo.Voxelizer(), call)(*TETRAHEDRON, resolution=8, **kwargs)


def test_an_enum_name_is_checked_by_its_table():
    with pytest.raises(ValueError, match="conservative: expected 'auto', 'hardware', 'shader' or 'centroid', "
                                         "got 'always'"):
        svo.voxelize(*TETRAHEDRON, resolution=8, conservative="always")


def stub_classes():
    return {node.name: node for node in ast.parse(STUB.read_text()).body if isinstance(node, ast.ClassDef)}


def test_the_stub_declares_every_public_name():
    tree = ast.parse(STUB.read_text())
    declared = {node.name for node in tree.body if isinstance(node, (ast.FunctionDef, ast.ClassDef))}
    declared |= {node.target.id for node in tree.body if isinstance(node, ast.AnnAssign)}
    missing = [name for name in svo.__all__ if name not in declared and name != "OutOfMemoryError"]
    assert not missing, f"the stub lacks {missing}"


def test_the_stubs_grid_and_result_are_the_modules():
    classes = stub_classes()
    grid = {item.name if isinstance(item, ast.FunctionDef) else item.target.id
            for item in classes["Grid"].body if isinstance(item, (ast.FunctionDef, ast.AnnAssign))}
    public = {name for name in dir(svo.Grid) if not name.startswith("_")}
    assert grid == public
    import dataclasses
    result = {item.target.id for item in classes["Result"].body if isinstance(item, ast.AnnAssign)}
    assert result == {f.name for f in dataclasses.fields(svo.Result)}


def test_the_version_is_the_projects():
    import re
    cmake = (pathlib.Path(__file__).resolve().parents[2] / "CMakeLists.txt").read_text()
    assert svo.__version__ == re.search(r"project\(svo VERSION ([0-9.]+)", cmake).group(1)
