"""`python3 -m geomipmap_apps.fly ...` runs the same program as the geomipmap-fly launcher."""

import sys

from .cli import main

sys.exit(main())
