"""The svo package as users install it, run by ctest (not by pytest):

    check_install.py pip SOURCE            `pip install SOURCE` into a fresh venv made with
                                           --system-site-packages, then import it there
    check_install.py cmake BUILD PYTHON    `cmake --install BUILD --component python` (into a
                                           DESTDIR) puts the package where PYTHON looks
Exits non-zero with a message on the first failure."""
import os
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path


def fail(message):
    print(f"check_install: {message}", file=sys.stderr)
    sys.exit(1)


def run(args, **kwargs):
    r = subprocess.run(args, capture_output=True, text=True, **kwargs)
    if r.returncode:
        fail(f"{' '.join(map(str, args))} failed ({r.returncode}):\n{r.stdout[-4000:]}\n{r.stderr[-4000:]}")
    return r.stdout


def project_version(source):
    return re.search(r"project\(svo VERSION ([0-9.]+)", (Path(source) / "CMakeLists.txt").read_text()).group(1)


def check_pip(source):
    with tempfile.TemporaryDirectory(prefix="svo-pip-") as tmp:
        venv = Path(tmp) / "venv"
        run([sys.executable, "-m", "venv", "--system-site-packages", str(venv)])
        python = str(venv / "bin" / "python")
        start = time.monotonic()
        run([python, "-m", "pip", "install", "--no-input", str(source)], cwd=tmp)
        print(f"pip install {source}: {time.monotonic() - start:.0f} s")
        # From a folder without the sources: the installed package, not the checkout's.
        version = run([python, "-c", "import svo; print(svo.__version__)"], cwd=tmp).strip()
        if version != project_version(source):
            fail(f"svo.__version__ is {version!r}, CMakeLists.txt says {project_version(source)!r}")
        where = Path(run([python, "-c", "import svo; print(svo.__file__)"], cwd=tmp).strip()).parent
        if venv not in where.parents:
            fail(f"svo imported from {where}, not from the venv {venv}")
        for name in ("__init__.pyi", "py.typed", "_result.py", "_build.py"):
            if not (where / name).is_file():
                fail(f"the installed package lacks {name}")
        # System site packages: Debian's pyopenvdb, and grids as its objects.
        kind = run([python, "-c", "import numpy as np, svo\n"
                    "r = svo.voxelize(np.eye(3), [[0, 1, 2]], resolution=8)\n"
                    "print(type(r.grid).__module__, r.grid.activeVoxelCount())"], cwd=tmp).split()
        if kind[0] != "pyopenvdb" or int(kind[1]) <= 0:
            fail(f"expected a pyopenvdb grid with voxels, got {kind}")
        print(f"svo {version} from {where}: {kind}")


def check_cmake(build, python):
    with tempfile.TemporaryDirectory(prefix="svo-install-") as tmp:
        env = dict(os.environ, DESTDIR=tmp)
        run(["cmake", "--install", str(build), "--component", "python"], env=env)
        installed = sorted(Path(tmp).rglob("svo/__init__.py"))
        if len(installed) != 1:
            fail(f"expected one svo package under DESTDIR, found {installed}")
        folder = "/" + str(installed[0].parent.parent.relative_to(tmp))
        paths = run([python, "-c", "import sys; print('\\n'.join(sys.path))"], cwd=tmp).split("\n")
        if folder not in paths:
            fail(f"cmake --install puts svo in {folder}, which {python} does not search ({paths})")
        print(f"cmake --install: {folder}, on {python}'s sys.path")


if __name__ == "__main__":
    if len(sys.argv) == 3 and sys.argv[1] == "pip":
        check_pip(Path(sys.argv[2]).resolve())
    elif len(sys.argv) == 4 and sys.argv[1] == "cmake":
        check_cmake(Path(sys.argv[2]).resolve(), sys.argv[3])
    else:
        fail(__doc__)
