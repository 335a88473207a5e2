"""Where the add-on finds the `ctmap` Python module: next to it (the zip built by CMake holds the
module), on sys.path, or in $CTMAP_PYTHONPATH. `load()` says where it looked when it is missing."""
import importlib
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
_error = None


def searched():
    extra = [p for p in os.environ.get("CTMAP_PYTHONPATH", "").split(os.pathsep) if p]
    return [HERE] + extra + [p for p in sys.path if p not in extra and p != HERE]


def load():
    """The ctmap module, or raises ImportError naming the folders searched."""
    global _error
    for p in [HERE] + [p for p in os.environ.get("CTMAP_PYTHONPATH", "").split(os.pathsep) if p]:
        if p not in sys.path:
            sys.path.insert(0, p)
    try:
        return importlib.import_module("ctmap")
    except ImportError as e:
        _error = e
        raise ImportError("the ctmap Python module was not found (built as build/python/ctmap.*.so for Python "
                          f"{sys.version_info.major}.{sys.version_info.minor}); looked in: " + ", ".join(searched())
                          + f" ({e})") from e
