"""``python -m boat_dynamics`` is ``boatsim``."""

import sys

from boat_dynamics.cli import main

sys.exit(main())
