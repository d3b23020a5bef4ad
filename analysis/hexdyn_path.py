"""The package hexdyn for the scripts of analysis/, without PYTHONPATH.

Called first by every script that reads hexdyn's files (`hexdyn_path.ensure()`): when the
interpreter cannot import hexdyn already (an installed package, or PYTHONPATH as the
pipelines and the module file of docs/user/sweeps.md#an-installed-hexdyn set it), the build
tree's package, build/python next to this folder, is put first on sys.path. So
`/usr/bin/python3 analysis/plot_sweep.py ...` works from a checkout right after
`bash pipelines/paper.sh`. Without either, the script stops with one line saying how to get
the package, instead of a traceback.
"""
import importlib.util
import os
import sys

_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
_BUILD_PACKAGE = os.path.join(_ROOT, "build", "python")


def ensure():
    """Makes `import hexdyn` work, or exits with one line naming what is missing."""
    if importlib.util.find_spec("hexdyn") is None:
        if os.path.isfile(os.path.join(_BUILD_PACKAGE, "hexdyn", "__init__.py")):
            sys.path.insert(0, _BUILD_PACKAGE)
        else:
            sys.exit(f"{os.path.basename(sys.argv[0]) or 'python'}: error: the Python package hexdyn "
                     f"is not importable and {_BUILD_PACKAGE} has none: build it "
                     "(bash pipelines/setup.sh) or set PYTHONPATH to an installed one")
