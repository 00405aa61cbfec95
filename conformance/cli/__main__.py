"""`python -m conformance.cli`: how the runner starts each child run."""

import sys

from conformance.cli import main

sys.exit(main())
