"""Finds and imports the `pierce` Python module (built from Pierce's C++ core).

Looked for, in order:
  1. the PIERCE_PYTHONPATH environment variable (directories separated by os.pathsep);
  2. the file pierce_path.txt next to this package's add-on directory, written by
     packaging/install-freecad-addon.sh (one directory per line);
  3. the FreeCAD parameter User parameter:BaseApp/Preferences/Mod/Pierce/ModulePath;
  4. a development checkout, when the add-on runs from <repo>/freecad_addon (linked install):
     <repo>/build/python, then <repo>/build-*/python, newest first;
  5. sys.path as it is: where the pierce Debian package installs it (/usr/lib/python3/dist-packages,
     next to the workbench in /usr/share/freecad/Mod/Pierce), so an installed workbench needs none
     of the above.
"""
import glob
import os
import sys

ADDON_DIR = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PATH_FILE = os.path.join(ADDON_DIR, "pierce_path.txt")
PARAM_PATH = "User parameter:BaseApp/Preferences/Mod/Pierce"


class PierceUnavailable(ImportError):
    """The pierce module could not be imported; the message says where it was looked for."""


def _is_module_dir(d):
    return os.path.isfile(os.path.join(d, "pierce", "__init__.py"))


def candidate_dirs():
    dirs = []
    env = os.environ.get("PIERCE_PYTHONPATH", "")
    dirs += [d for d in env.split(os.pathsep) if d]
    if os.path.isfile(PATH_FILE):
        with open(PATH_FILE, encoding="utf-8") as f:
            dirs += [line.strip() for line in f if line.strip() and not line.startswith("#")]
    try:
        import FreeCAD
        p = FreeCAD.ParamGet(PARAM_PATH).GetString("ModulePath", "")
        if p:
            dirs.append(p)
    except Exception:  # outside FreeCAD, or no parameter store: nothing to add
        pass
    repo = os.path.dirname(os.path.realpath(ADDON_DIR))
    dirs.append(os.path.join(repo, "build", "python"))  # packaging/build.sh's build directory
    dirs += sorted(glob.glob(os.path.join(repo, "build-*", "python")), key=os.path.getmtime, reverse=True)
    return dirs


def import_pierce():
    """Returns the pierce module or raises PierceUnavailable with a helpful message."""
    if "pierce" in sys.modules:
        return sys.modules["pierce"]
    tried = []
    for d in candidate_dirs():
        if _is_module_dir(d):
            if d not in sys.path:
                sys.path.insert(0, d)
            break
        tried.append(d)
    try:
        import pierce
    except ImportError as e:
        where = ", ".join(tried) if tried else "no candidate directory"
        raise PierceUnavailable(
            "The Pierce Python module could not be imported (%s). Install the pierce package "
            "(packaging/build-deb.sh builds it), or build Pierce (bash packaging/build.sh) and run "
            "packaging/install-freecad-addon.sh, or set PIERCE_PYTHONPATH to <build>/python. "
            "Looked in: %s, then sys.path" % (e, where)) from e
    return pierce
