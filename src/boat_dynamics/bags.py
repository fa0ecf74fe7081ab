"""Deprecated: :mod:`boat_dynamics.tools.bags` (moved in 0.2; removed in 0.3).

The README documented ``boat_dynamics.bags.compare_bags`` for test suites; this keeps that
import working, with a DeprecationWarning naming the new place.
"""

import warnings

from boat_dynamics.tools.bags import *  # noqa: F403
from boat_dynamics.tools.bags import __all__  # noqa: F401

warnings.warn("boat_dynamics.bags is deprecated: import boat_dynamics.tools.bags "
              "(removed in 0.3)", DeprecationWarning, stacklevel=2)
