"""`python3 -m geomipmap_apps.view ...` runs the same program as the geomipmap-view launcher."""

import sys

from ..hugeheap import restart_with_huge_heap

restart_with_huge_heap(["-m", __package__] + sys.argv[1:])  # as the launcher does

from .cli import main  # noqa: E402

sys.exit(main())
