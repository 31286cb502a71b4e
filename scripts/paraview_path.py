"""Makes ParaView's Python package importable under pvbatch.

pvbatch embeds the Python it was built against and looks for the `paraview`
package on that interpreter's path. Where the interpreter found first is
another one (a Python built under /usr/local, a PYTHONHOME of a pyenv or
conda install), the package of Debian's python3-paraview, in
/usr/lib/python3/dist-packages, is not on the path. Importing this module
adds the first folder that holds paraview/simple.py, or stops with a message
that names the folders searched and the package to install.

    import paraview_path  # noqa: F401  (before: from paraview.simple import ...)
"""
import glob
import importlib.util
import os
import sys


def _candidates():
    version = f"python3.{sys.version_info[1]}"
    folders = ["/usr/lib/python3/dist-packages", f"/usr/lib/{version}/dist-packages",
               f"/usr/lib/{version}/site-packages"]
    executable = os.path.realpath(sys.executable) if sys.executable else ""
    if executable:
        prefix = os.path.dirname(os.path.dirname(executable))
        folders += sorted(glob.glob(os.path.join(prefix, "lib*", "python3*", "*-packages")))
    return folders


if importlib.util.find_spec("paraview") is None:
    searched = _candidates()
    found = [f for f in searched if os.path.isfile(os.path.join(f, "paraview", "simple.py"))]
    if not found:
        sys.exit("ParaView's Python package (paraview/simple.py) is on neither the "
                 f"interpreter's path {sys.path} nor in {searched}: install it "
                 "(Debian: apt-get install python3-paraview) and run the script "
                 "with ParaView's pvbatch")
    sys.path.append(found[0])
    print(f"[paraview_path] {sys.version.split()[0]} at {sys.prefix} lacked the paraview "
          f"package; using {found[0]}", file=sys.stderr)
