# SPDX-License-Identifier: MIT
"""`python -m silk_export ...` (and `torchrun ... -m silk_export train ...`): the console script."""

import sys

from .cli import main

sys.exit(main())
