"""`python3 -m geomipmap_apps.bench ...` runs the same program as the geomipmap-bench launcher."""

import sys

from .cli import main

sys.exit(main())
