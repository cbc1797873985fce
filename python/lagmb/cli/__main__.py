"""python -m lagmb.cli: the lagmb command, as python -m lagmb."""

import sys

from . import main

sys.exit(main())
