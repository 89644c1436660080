"""`python3 -m geomipmap_apps.view ...` runs the same program as the geomipmap-view launcher."""

import sys

from .cli import main

sys.exit(main())
