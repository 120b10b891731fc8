# SPDX-License-Identifier: Apache-2.0
"""python3 -m torrance_tools.farm ... (scripts/farm): see torrance_tools/farm/cli.py."""

import sys

from torrance_tools.farm.cli import main

sys.exit(main())
