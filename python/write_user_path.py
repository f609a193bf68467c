#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Makes `import frictopt` work for this interpreter without PYTHONPATH: writes
frictopt-build.pth (one line: the build's python/ directory) into the interpreter's user
site-packages, which Python adds to sys.path at start-up. Run by scripts/build.sh through the
CMake target python_user_path; remove the file (path printed) to undo."""
import pathlib
import site
import sys

package_dir = pathlib.Path(sys.argv[1]).resolve()
if not site.ENABLE_USER_SITE:
    print(f"python_user_path: user site-packages disabled for {sys.executable}; use PYTHONPATH={package_dir}")
    sys.exit(0)
target = pathlib.Path(site.getusersitepackages()) / "frictopt-build.pth"
if not target.exists() or target.read_text().strip() != str(package_dir):
    target.parent.mkdir(parents=True, exist_ok=True)
    target.write_text(f"{package_dir}\n")
print(f"python_user_path: {target} -> {package_dir}")
