"""`make regold`: re-record every golden run after an intended physics change.

Prints, per golden, what changed against the committed bag (the differences being
accepted), then replaces it. Runs on an isolated ROS domain.
"""

from __future__ import annotations

import os
import shutil
import sys
import tempfile
from pathlib import Path

os.environ.setdefault("ROS_DOMAIN_ID", str(60 + os.getpid() % 30))
os.environ["ROS_AUTOMATIC_DISCOVERY_RANGE"] = "LOCALHOST"

sys.path.insert(0, str(Path(__file__).resolve().parent))

from golden_tools import HERE, record_run, specs

from boat_dynamics.tools.bags import compare_bags


def main() -> int:
    """Re-record every golden; print the accepted differences."""
    with tempfile.TemporaryDirectory() as tmp:
        for name in specs():
            new = Path(tmp) / name
            record_run(name, new, Path(tmp) / "work")
            old = HERE / name
            if old.exists():
                result = compare_bags(old, new)
                print(f"== {name}: " + ("unchanged" if result.ok else "accepting changes:"))
                if not result.ok:
                    print(result.report())
                shutil.rmtree(old)
            else:
                print(f"== {name}: new golden")
            shutil.copytree(new, old)
    return 0


if __name__ == "__main__":
    sys.exit(main())
