"""``python -m boat_dynamics`` is ``boatsim``."""

import sys

try:
    from boat_dynamics.cli import main
except KeyboardInterrupt:  # Ctrl-C while starting: stop quietly, as the verbs do
    sys.exit(130)

sys.exit(main())
