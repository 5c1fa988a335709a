#!/usr/bin/env python3
"""Write the console scripts of pyproject.toml's [project.scripts] into a bin folder.

    python3 python/launchers.py BIN

Each launcher imports the visco2d package from this folder (the checkout's python/) and calls
its entry point, as the launcher of an editable pip install does, without pip, a virtual
environment or network access (`make build` calls this; doc/python.md).
"""
import os
import sys
import tomllib

HERE = os.path.dirname(os.path.abspath(__file__))

LAUNCHER = """#!/usr/bin/env python3
# {name}: written by python/launchers.py (make build) for the visco2d package in {folder}
import sys
sys.path.insert(0, {folder!r})
from {module} import {function}
sys.exit({function}())
"""


def scripts():
    """{command: 'module:function'} of pyproject.toml."""
    with open(os.path.join(HERE, "pyproject.toml"), "rb") as handle:
        return tomllib.load(handle)["project"]["scripts"]


def main(argv):
    if len(argv) != 2:
        print("usage: launchers.py BIN", file=sys.stderr)
        return 2
    folder = argv[1]
    os.makedirs(folder, exist_ok=True)
    for name, target in scripts().items():
        module, function = target.split(":")
        path = os.path.join(folder, name)
        with open(path, "w") as handle:
            handle.write(LAUNCHER.format(name=name, folder=HERE, module=module, function=function))
        os.chmod(path, 0o755)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
