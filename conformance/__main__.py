"""``python -m conformance``; see conformance/cli.py."""

import sys

from conformance.cli.main import main

sys.exit(main())
