"""``python -m dfa.cli``: the ``dfa`` command line."""

import sys

from .app import main

sys.exit(main())
