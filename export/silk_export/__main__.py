"""`python3 -m silk_export ...`: the same commands as the `silk-export` console script."""
import sys

from .cli import main

sys.exit(main())
