"""What every benchmark program shares: --help, the tmfdem path checked,
a work folder removed when the program ends (also when it fails)."""
import atexit
import os
import shutil
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_BINARY = os.path.join(HERE, "..", "build-release", "tmfdem")


def help_requested(doc):
    """Prints the program's docstring and exits for -h or --help."""
    if any(a in ("-h", "--help") for a in sys.argv[1:]):
        print(doc)
        sys.exit(0)


def tmfdem(path):
    """The path of an executable tmfdem, or exit with a message naming it."""
    path = path or DEFAULT_BINARY
    if not (os.path.isfile(path) and os.access(path, os.X_OK)):
        sys.exit(f"{path}: not an executable tmfdem (build it with "
                 f"'bash scripts/build.sh Release', or name it as the first argument)")
    return os.path.abspath(path)


def work_folder(prefix):
    """A temporary folder for the runs, removed at exit."""
    folder = tempfile.mkdtemp(prefix=prefix)
    atexit.register(shutil.rmtree, folder, ignore_errors=True)
    return folder
