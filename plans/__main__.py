"""``python -m plans``: the command line (:func:`plans.cli.main`)."""

import sys

from .cli import main

sys.exit(main())
